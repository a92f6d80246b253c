#!/usr/bin/env bash
# Measures awl and awlsim side by side on the same machine, pair by pair, and prints the ratio.
# awl runs programs/bench/logic_loop (STEP 5, release build); awlsim (installed with pip into
# a virtual environment under target/) runs the same loop in S7 form, logic_loop_s7.awl, and
# reports its own statement rate. Usage: benches/awlsim/compare.sh [pairs] [awlsim seconds]
set -euo pipefail
cd "$(dirname "$0")/../.."
pairs=${1:-3}
seconds=${2:-8}
awlsim_version=0.77.1
venv=target/awlsim-venv

benches/awlsim/install.sh pip > /dev/null
cargo build --release --quiet

awl_rate() {
    target/release/awl run programs/bench/logic_loop.awl --cycles 2000 2>&1 \
        | sed -n 's/.*rate: \([0-9.]*\) M instr\/s.*/\1/p'
}

awlsim_rate() {
    # The CPU dump ends with "Speed: N k stmt/s" (or "M stmt/s"); the last one counts.
    "$venv/bin/awlsim-test" -m en -M "$seconds" benches/awlsim/logic_loop_s7.awl 2>&1 \
        | tr '\r' '\n' \
        | sed -n 's/.*Speed: *\([0-9.]*\) \([kM]\) stmt\/s.*/\1 \2/p' \
        | tail -n 1 \
        | awk '{ print ($2 == "k") ? $1 / 1000 : $1 }'
}

echo "awlsim $awlsim_version (pip, pure Python) vs awl, logic loop, M operations/s"
printf '%-6s %12s %12s %10s\n' pair awl awlsim ratio
for pair in $(seq "$pairs"); do
    ours=$(awl_rate)
    theirs=$(awlsim_rate)
    ratio=$(awk -v a="$ours" -v b="$theirs" 'BEGIN { printf "%.0f", a / b }')
    printf '%-6s %12s %12s %9sx\n' "$pair" "$ours" "$theirs" "$ratio"
done
