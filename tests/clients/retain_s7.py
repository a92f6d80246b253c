"""Retentive memory through awl serve's restarts: DB 1's setpoint (DB1.DBW 4) written, read,
and put back by a cold restart. Usage: retain_s7.py PORT write VALUE | read | cold; prints the
setpoint."""

from s7_common import connect, main
from snap7.type import cpu_statuses


def state(client):
    return cpu_statuses[client.read_szl(0x0424, 0).Data[7]]


def setpoint(client):
    return int.from_bytes(client.db_read(1, 4, 2), "big", signed=True)


def run(argv):
    client = connect(int(argv[0]))
    if argv[1] == "write":
        value = int(argv[2])
        client.db_write(1, 4, bytearray(value.to_bytes(2, "big", signed=True)))
        assert setpoint(client) == value
    elif argv[1] == "cold":
        client.plc_stop()
        assert state(client) == "S7CpuStatusStop"
        client.plc_cold_start()
        assert state(client) == "S7CpuStatusRun"
    print(setpoint(client))
    client.disconnect()


main(run)
