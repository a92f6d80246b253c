"""Runs a STEP 7 file in awlsim's core, started by the awlsim Python of target/: for a number of
cycles, printing the operations awlsim counted (`--cycles N`), or for a number of seconds after
a first cycle, printing its statement rate in M/s (`--seconds S`). awlsim's loader takes its
Cython modules when AWLSIM_CYTHON asks for them. No cycle time limit, no CPU dump.

Usage: python3 driver.py FILE (--cycles N | --seconds S)
"""

import sys
import time

from awlsim_loader.common import *
from awlsim_loader.core import *
from awlsim_loader.awlcompiler import *


def operations(sim):
    # The statement counter: name-mangled in Python, plain in the Cython core.
    count = getattr(sim.cpu, "_S7CPU__insnCount", None)
    return getattr(sim.cpu, "__insnCount") if count is None else count


def main():
    path, how, amount = sys.argv[1], sys.argv[2], float(sys.argv[3])
    Logging.setLoglevel(Logging.LOG_ERROR)
    sim = AwlSim()
    sim.cpu.getConf().setConfiguredMnemonics(S7CPUConfig.MNEMONICS_EN)
    sim.cpu.getConf().setCycleTimeLimitUs(0x7FFFFFFF)
    parser = AwlParser()
    parser.parseSource(AwlSource.fromFile(path, path))
    sim.load(parser.getParseTree())
    sim.startup()
    if how == "--cycles":
        for _ in range(int(amount)):
            sim.runCycle()
        print("operations:", operations(sim))
        return
    sim.runCycle()
    before = operations(sim)
    start = time.perf_counter()
    while time.perf_counter() - start < amount:
        sim.runCycle()
    elapsed = time.perf_counter() - start
    print("rate:", (operations(sim) - before) / elapsed / 1e6)


main()
