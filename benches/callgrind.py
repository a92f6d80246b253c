#!/usr/bin/env python3
"""Host (machine) instructions per STL operation of the benchmark scenarios, counted by callgrind.

Each bench runs twice under `valgrind --tool=callgrind`, for N1 and for N2 cycles; the start-up
(loading, compiling, the first cycle's set-up) is the same in both and cancels out of

    (instructions of run 2 - instructions of run 1) / (STL operations of run 2 - of run 1)

so the figure is what the VM's loop costs per operation. Callgrind counts are deterministic:
a machine busy with other work gives the same figures. Needs valgrind and a release build
(`cargo build --release`).

The serve benches run a bench scenario under `awl serve` (S7 server on a free port, at speed
1000, so the CPU never waits for the clock), without and with the online page (`--http`,
nothing watched): the page's server must leave the loop's cost unchanged (within 1 %). They
run only when named, and are less exact than the others: the network is looked at by the wall
clock, which callgrind slows.

With awlsim installed where benches/awlsim/install.sh installs it (virtual environments in
target/awlsim-venv and target/awlsim-cython-venv), its pure-Python core and its Cython core are
measured the same way on the STEP 7 files: the same operations, counted by awlsim itself, for
far fewer cycles.

Usage: benches/callgrind.py [--quick] [--jobs N] [--no-awlsim] [BENCH ...]
"""

import argparse
import concurrent.futures
import os
import pathlib
import re
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
AWL = ROOT / "target" / "release" / "awl"
AWLSIM_PYTHONS = {
    "pip": ROOT / "target" / "awlsim-venv" / "bin" / "python3",
    "cython": ROOT / "target" / "awlsim-cython-venv" / "bin" / "python3",
}

# Runs a STEP 7 file in awlsim (see benches/awlsim/driver.py).
AWLSIM_DRIVER = ROOT / "benches" / "awlsim" / "driver.py"


class Bench:
    """A scenario of programs/bench/ run with the given interrupt points, for N1 and N2 cycles
    (and fewer with --quick); `awlsim` ("pip" or "cython"): its program run in that awlsim."""

    def __init__(self, name, scenario, points, cycles, quick_cycles, awlsim=None, serve=None):
        self.name = name
        self.scenario = scenario
        self.points = points
        self.cycles = cycles
        self.quick_cycles = quick_cycles
        self.awlsim = awlsim
        # `awl serve` with these servers' options instead of `awl run`.
        self.serve = serve

    def command(self, cycles):
        """The command that runs `cycles` cycles and prints the operation count."""
        if self.awlsim:
            program = ROOT / "programs" / "bench" / f"{self.scenario}.awl"
            python = AWLSIM_PYTHONS[self.awlsim]
            return [str(python), str(AWLSIM_DRIVER), str(program), "--cycles", str(cycles)]
        scenario = ROOT / "programs" / "bench" / f"{self.scenario}.toml"
        command = [str(AWL), "run", "--scenario", str(scenario), "--cycles", str(cycles)]
        if self.serve is not None:
            command[1] = "serve"
            command += ["--speed", "1000", *self.serve]
        if self.points:
            command += ["--interrupt-points", self.points]
        return command


BENCHES = [
    # STEP 5 on the SINUMERIK 840C: block interrupt points, the scenario's default.
    Bench("logic_loop", "logic_loop", None, (50, 250), (5, 25)),
    Bench("logic_loop_operation", "logic_loop", "operation", (50, 250), (5, 25)),
    # STEP 7 on the SPEED7: operation interrupt points, its default.
    Bench("s7_logic_loop", "s7_logic_loop", None, (50, 250), (5, 25)),
    Bench("calls", "calls", None, (1000, 5000), (100, 500)),
    Bench("fb_params", "fb_params", None, (50, 250), (5, 25)),
    Bench("s7_calls", "s7_calls", None, (1000, 5000), (100, 500)),
    # STEP 7 calls with parameters: an FB on instance DBs, an FC.
    Bench("s7_fb_instances", "s7_fb_instances", None, (50, 250), (5, 25)),
    Bench("s7_fc_params", "s7_fc_params", None, (50, 250), (5, 25)),
]

# `awl serve` without and with the online page, nothing watched (the S7 server in both).
SERVE = ["--s7", "127.0.0.1:0"]
SERVE_BENCHES = [
    Bench("serve_s7_logic_loop", "s7_logic_loop", None, (50, 250), (5, 25), serve=SERVE),
    Bench(
        "serve_s7_logic_loop_http",
        "s7_logic_loop",
        None,
        (50, 250),
        (5, 25),
        serve=[*SERVE, "--http", "127.0.0.1:0"],
    ),
    Bench("serve_calls", "calls", None, (1000, 5000), (100, 500), serve=SERVE),
    Bench(
        "serve_calls_http",
        "calls",
        None,
        (1000, 5000),
        (100, 500),
        serve=[*SERVE, "--http", "127.0.0.1:0"],
    ),
]

AWLSIM_BENCHES = [
    Bench("awlsim_s7_logic_loop", "s7_logic_loop", None, (1, 3), (1, 2), awlsim="pip"),
    Bench("awlsim_s7_calls", "s7_calls", None, (20, 100), (10, 30), awlsim="pip"),
    Bench("cython_s7_logic_loop", "s7_logic_loop", None, (2, 10), (1, 3), awlsim="cython"),
    Bench("cython_s7_calls", "s7_calls", None, (100, 500), (20, 100), awlsim="cython"),
    Bench("awlsim_s7_fb_instances", "s7_fb_instances", None, (1, 3), (1, 2), awlsim="pip"),
    Bench("awlsim_s7_fc_params", "s7_fc_params", None, (1, 3), (1, 2), awlsim="pip"),
    Bench(
        "cython_s7_fb_instances", "s7_fb_instances", None, (5, 25), (2, 6), awlsim="cython"
    ),
    Bench("cython_s7_fc_params", "s7_fc_params", None, (5, 25), (2, 6), awlsim="cython"),
]

COLLECTED = re.compile(r"Collected\s*:\s*(\d+)")
# awl's summary line `instructions: N`, the awlsim driver's `operations: N`.
OPERATIONS = re.compile(r"^(?:instructions|operations):\s*(\d+)", re.MULTILINE)


def measure(bench, cycles):
    """(host instructions, STL operations) of one run of `cycles` cycles."""
    command = ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"]
    command += bench.command(cycles)
    # awl's exit status tells whether the scenario's expectations were met, which hold only
    # for the scenario's own number of cycles: the run is judged by its summary alone.
    # awlsim's loader takes its Cython modules only when asked (2: or fail).
    environment = dict(os.environ, AWLSIM_CYTHON="2" if bench.awlsim == "cython" else "0")
    done = subprocess.run(command, capture_output=True, text=True, cwd=ROOT, env=environment)
    host = COLLECTED.search(done.stderr)
    operations = OPERATIONS.search(done.stdout + done.stderr)
    if not host or not operations:
        sys.exit(
            f"{bench.name}, {cycles} cycles: no callgrind total or operation count in the "
            f"output (exit status {done.returncode}):\n{done.stdout}\n{done.stderr}"
        )
    return int(host.group(1)), int(operations.group(1))


def per_operation(bench, quick):
    """The bench's figure and the counts it comes from."""
    first, second = bench.quick_cycles if quick else bench.cycles
    host1, ops1 = measure(bench, first)
    host2, ops2 = measure(bench, second)
    return {
        "cycles": f"{first}/{second}",
        "operations": ops2 - ops1,
        "host": host2 - host1,
        "per_operation": (host2 - host1) / (ops2 - ops1),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick", action="store_true", help="fewer cycles (a tenth of awl's)"
    )
    parser.add_argument(
        "--jobs", type=int, default=2, help="benches measured at once (default 2)"
    )
    parser.add_argument(
        "--no-awlsim",
        action="store_true",
        help="leave awlsim out even where it is installed",
    )
    parser.add_argument(
        "benches",
        nargs="*",
        metavar="BENCH",
        help="the benches to measure (default all): "
        + ", ".join(bench.name for bench in BENCHES + SERVE_BENCHES + AWLSIM_BENCHES),
    )
    options = parser.parse_args()
    known = {bench.name: bench for bench in BENCHES + SERVE_BENCHES + AWLSIM_BENCHES}
    unknown = [name for name in options.benches if name not in known]
    if unknown:
        parser.error(f"unknown bench {', '.join(unknown)}; known: {', '.join(known)}")
    installed = [
        bench
        for bench in AWLSIM_BENCHES
        if AWLSIM_PYTHONS[bench.awlsim].exists() and not options.no_awlsim
    ]
    chosen = [known[name] for name in options.benches] or BENCHES + installed
    missing = [bench for bench in chosen if bench.awlsim and bench not in installed]
    if missing and not options.no_awlsim:
        sys.exit(
            f"{AWLSIM_PYTHONS[missing[0].awlsim]} is missing: benches/awlsim/install.sh "
            "installs awlsim there"
        )
    if not shutil.which("valgrind"):
        sys.exit("valgrind is missing: install it (Debian, Ubuntu: apt install valgrind)")
    if not AWL.exists():
        sys.exit(f"{AWL} is missing: build it first with `cargo build --release`")

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, options.jobs)) as pool:
        results = list(
            pool.map(lambda bench: per_operation(bench, options.quick), chosen)
        )

    header = ("bench", "cycles N1/N2", "STL ops (N2-N1)", "host instr (N2-N1)", "per op")
    rows = [
        (
            bench.name,
            result["cycles"],
            f"{result['operations']:,}",
            f"{result['host']:,}",
            f"{result['per_operation']:.2f}",
        )
        for bench, result in zip(chosen, results)
    ]
    widths = [max(len(row[column]) for row in [header, *rows]) for column in range(5)]
    for row in [header, *rows]:
        print(
            "  ".join(
                cell.ljust(width) if column == 0 else cell.rjust(width)
                for column, (cell, width) in enumerate(zip(row, widths))
            )
        )


if __name__ == "__main__":
    main()
