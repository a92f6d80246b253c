"""Eight clients at once, each writing and reading back its own holding registers."""

import threading

from modbus_common import client, ok

failures = []


def converse(number):
    try:
        modbus = client()
        for round in range(25):
            values = [(number * 1000 + round * 10 + n) & 0xFFFF for n in range(4)]
            ok(modbus.write_registers(number * 4, values), f"client {number} writes")
            read = ok(modbus.read_holding_registers(number * 4, count=4), "reads").registers
            if read != values:
                failures.append(f"client {number} round {round}: {read} != {values}")
        modbus.close()
    except SystemExit:
        failures.append(f"client {number} failed")


threads = [threading.Thread(target=converse, args=(number,)) for number in range(8)]
for thread in threads:
    thread.start()
for thread in threads:
    thread.join()
if failures:
    raise SystemExit("FAILED: " + "; ".join(failures))
print("modbus clients: all passed")
