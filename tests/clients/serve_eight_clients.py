"""Eight S7 clients at once for a few seconds, each writing its own flag words and reading
them back, all reading the cycle count, which never goes back; a Modbus client beside them."""

import threading
import time

from served import Area, modbus, ports, s7

s7_port, modbus_port = ports()
SECONDS = 3.0
failures = []
counts = [0] * 8


def client(number):
    plc = s7(s7_port)
    last_cycles = 0
    at = 100 + 4 * number
    value = number
    deadline = time.monotonic() + SECONDS
    while time.monotonic() < deadline:
        value = (value * 7 + 13) & 0xFFFF_FFFF
        plc.write_area(Area.MK, 0, at, bytearray(value.to_bytes(4, "big")))
        got = int.from_bytes(plc.read_area(Area.MK, 0, at, 4), "big")
        if got != value:
            failures.append(f"client {number}: MD {at} = {got}, wrote {value}")
        cycles = int.from_bytes(plc.db_read(1, 6, 4), "big")
        if cycles < last_cycles:
            failures.append(f"client {number}: cycles went back from {last_cycles} to {cycles}")
        last_cycles = cycles
        counts[number] += 1
    plc.disconnect()


def modbus_client():
    bus = modbus(modbus_port)
    deadline = time.monotonic() + SECONDS
    register = 0
    while time.monotonic() < deadline:
        register = (register + 1) & 0xFFFF
        bus.write_register(200, register)
        got = bus.read_holding_registers(200, count=1).registers[0]
        if got != register:
            failures.append(f"modbus: holding register 200 = {got}, wrote {register}")
    bus.close()


def guarded(work, *args):
    """A thread's exception is a failure of the test, not a message on the side."""
    try:
        work(*args)
    except Exception as error:
        failures.append(f"{work.__name__}{args}: {error!r}")


threads = [threading.Thread(target=guarded, args=(client, n)) for n in range(8)]
threads.append(threading.Thread(target=guarded, args=(modbus_client,)))
for thread in threads:
    thread.start()
for thread in threads:
    thread.join()
assert not failures, failures[:5]
assert all(count > 10 for count in counts), counts
print(f"eight clients: {sum(counts)} rounds, every value right")
