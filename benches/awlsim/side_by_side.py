#!/usr/bin/env python3
"""awl and awlsim's Cython core on the same STEP 7 files, wall clock, pair by pair.

For each file of programs/bench/ (s7_logic_loop, s7_calls), alternately: awl runs the scenario
(`awl run --scenario`, its summary's operation rate, start-up included) and awlsim runs the same
file in its core for SECONDS of cycles (its own statement counter over the wall time of those
cycles, without `awlsim-test`'s CPU dump). The ratio of each pair is printed; the machine's
load changes both sides of a pair alike.

awlsim's Cython core is built by benches/awlsim/install.sh into target/awlsim-cython-venv.

Usage: benches/awlsim/side_by_side.py [--pairs N] [--seconds S] [FILE ...]
"""

import argparse
import os
import pathlib
import re
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
AWL = ROOT / "target" / "release" / "awl"
CYTHON_PYTHON = ROOT / "target" / "awlsim-cython-venv" / "bin" / "python3"

# Runs a STEP 7 file in awlsim (see benches/awlsim/driver.py).
AWLSIM_DRIVER = ROOT / "benches" / "awlsim" / "driver.py"

RATE = re.compile(r"rate:\s*([0-9.]+)")


def awl_rate(name):
    scenario = ROOT / "programs" / "bench" / f"{name}.toml"
    done = subprocess.run(
        [str(AWL), "run", "--scenario", str(scenario)], capture_output=True, text=True
    )
    return float(RATE.search(done.stdout + done.stderr).group(1))


def awlsim_rate(name, seconds):
    program = ROOT / "programs" / "bench" / f"{name}.awl"
    environment = dict(os.environ, AWLSIM_CYTHON="2")
    done = subprocess.run(
        [str(CYTHON_PYTHON), str(AWLSIM_DRIVER), str(program), "--seconds", str(seconds)],
        capture_output=True,
        text=True,
        env=environment,
    )
    found = RATE.search(done.stdout)
    if not found:
        sys.exit(f"awlsim on {name}: no rate\n{done.stdout}\n{done.stderr}")
    return float(found.group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=8)
    parser.add_argument("files", nargs="*", default=["s7_logic_loop", "s7_calls"])
    options = parser.parse_args()
    if not CYTHON_PYTHON.exists():
        sys.exit(f"{CYTHON_PYTHON} is missing: benches/awlsim/install.sh builds it")
    if not AWL.exists():
        sys.exit(f"{AWL} is missing: build it first with `cargo build --release`")
    print("awl vs awlsim 0.77.1's Cython core, M operations/s, wall clock")
    print(f"{'file':<15}{'pair':>5}{'awl':>10}{'awlsim':>10}{'ratio':>9}")
    for name in options.files:
        ratios = []
        for pair in range(1, options.pairs + 1):
            ours = awl_rate(name)
            theirs = awlsim_rate(name, options.seconds)
            ratios.append(ours / theirs)
            print(f"{name:<15}{pair:>5}{ours:>10.1f}{theirs:>10.2f}{ours / theirs:>8.1f}x")
        print(f"{name:<15}{'median':>5}{'':>20}{statistics.median(ratios):>8.1f}x")


if __name__ == "__main__":
    main()
