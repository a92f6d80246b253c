//! The crates a plain `cargo build --release` compiles, held to a budget: every crate is time
//! on every cold build (the README's first command), so a new dependency, or a feature of one
//! that pulls in more, is a choice made on purpose, with the README's build time measured again.

use std::process::Command;

/// The crates (name and version) of awl's default build on this host, as of the last
/// measurement in the README ("How long a build takes"), and the 37 of the online page's server
/// (`awl serve --http`: axum with HTTP/1 and WebSocket only, hyper, and the WebSocket's
/// handshake hashing and masking), and the 89 of the OPC UA server (`awl serve --opcua`:
/// async-opcua's server with the core namespace every client browses from, its pure-Rust
/// RSA, AES and SHA-2 for Basic256Sha256, X.509 for the self-signed certificate), and the 4 of
/// `awl dap`'s attach (ureq, HTTP/1 without TLS, to the online API).
const BUDGET: usize = 286;

/// `cargo tree`'s list of the crates the default build compiles for this host: the normal and
/// build dependencies, no dev-dependencies.
fn crates_of_the_build() -> Vec<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let output = Command::new(cargo)
        .args(["tree", "--package", "awl", "--edges", "normal,build"])
        .args(["--prefix", "none"])
        .args(["--offline", "--locked"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let mut crates: Vec<String> = String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| {
            let mut words = line.split_whitespace();
            Some(format!("{} {}", words.next()?, words.next()?))
        })
        .collect();
    crates.sort();
    crates.dedup();
    crates
}

#[test]
fn the_default_build_compiles_no_more_crates_than_its_budget() {
    let crates = crates_of_the_build();
    assert!(crates.len() > 50, "{crates:?}");
    assert!(
        crates.len() <= BUDGET,
        "the default build compiles {} crates, {} over its budget of {BUDGET}. Take only the \
         features awl uses (`default-features = false`), put what only tests need under \
         [dev-dependencies], or, where the crate is worth its time, measure the cold build \
         again and raise the budget and the README's figure together. The crates:\n{}",
        crates.len(),
        crates.len() - BUDGET,
        crates.join("\n")
    );
}

#[test]
fn diagnostics_build_without_backtraces() {
    // awl's reports point at STL source, never at its own stack.
    let crates = crates_of_the_build();
    for unused in ["backtrace ", "backtrace-ext "] {
        assert!(
            !crates.iter().any(|name| name.starts_with(unused)),
            "the default build compiles {unused}"
        );
    }
}
