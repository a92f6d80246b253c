#!/usr/bin/env bash
# Builds the playground: target/web/awl-playground.html, one file with the page, its script,
# its worker's script, its styles and awl compiled to WebAssembly (gzipped, as base64; the page
# inflates it with the browser's DecompressionStream), to open from file:// with no server or
# network.
# Installs what it needs: the wasm32 target (rustup) and the wasm-bindgen CLI of the version
# web/Cargo.toml pins.
set -euo pipefail
cd "$(dirname "$0")/.."

bindgen_version=$(sed -n 's/^wasm-bindgen = "=\(.*\)"/\1/p' web/Cargo.toml)
if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
fi
if [ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $bindgen_version" ]; then
    cargo install wasm-bindgen-cli --version "$bindgen_version" --no-default-features
fi

# A target directory of its own: `cargo test` (which runs this script) holds the main one.
build=target/web-build
CARGO_TARGET_DIR=$build cargo build --quiet -p awl-playground \
    --target wasm32-unknown-unknown --profile web
# The names and producers sections only serve debuggers and profilers: a sixth of the module.
wasm-bindgen --target no-modules --no-typescript --out-dir "$build/bindgen" \
    --remove-name-section --remove-producers-section \
    "$build/wasm32-unknown-unknown/web/awl_playground.wasm"

out=target/web/awl-playground.html
mkdir -p target/web
while IFS= read -r line; do
    case "$line" in
        "{{STYLE}}") cat web/common.css web/page.css ;;
        "{{GLUE}}") cat "$build/bindgen/awl_playground.js" ;;
        "{{WORKER}}") cat web/worker.js ;;
        "{{SCRIPT}}") cat web/common.js web/page.js ;;
        *"{{WASM}}"*)
            printf '%s' "${line%%\{\{WASM\}\}*}"
            gzip -9 --no-name --stdout "$build/bindgen/awl_playground_bg.wasm" | base64 -w0
            printf '%s\n' "${line##*\{\{WASM\}\}}"
            ;;
        *) printf '%s\n' "$line" ;;
    esac
done < web/page.html > "$out.partial"
mv "$out.partial" "$out"
echo "$out: $(( $(stat -c %s "$out") / 1024 )) KiB"
