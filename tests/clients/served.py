"""What every client script of tests/serve.rs shares: waiting for a value the program writes,
and the clients connected to the ports awl serve printed."""

import sys
import time

import snap7
from pymodbus.client import ModbusTcpClient
from snap7.type import Area, cpu_statuses


def ports():
    """The S7 and Modbus ports, from the command line."""
    return int(sys.argv[1]), int(sys.argv[2])


def s7(port, slot=2):
    client = snap7.client.Client()
    client.connect("127.0.0.1", 0, slot, tcp_port=port)
    return client


def modbus(port):
    client = ModbusTcpClient("127.0.0.1", port=port)
    assert client.connect(), "the Modbus client connects"
    return client


def state(client):
    """The operating mode from SZL 0x0424 (python-snap7 3.x's get_cpu_state asks nothing)."""
    return cpu_statuses[client.read_szl(0x0424, 0).Data[7]]


def word(data, at=0):
    return int.from_bytes(data[at:at + 2], "big", signed=True)


def until(what, read, wanted, seconds=5.0):
    """Reads until `read()` gives `wanted` (the program needs a cycle or two)."""
    deadline = time.monotonic() + seconds
    value = read()
    while value != wanted and time.monotonic() < deadline:
        time.sleep(0.01)
        value = read()
    assert value == wanted, f"{what}: expected {wanted}, got {value}"


def raises(what, call):
    try:
        call()
    except Exception as error:  # the client's own exception types differ by version
        return error
    raise AssertionError(f"{what}: no error")


__all__ = ["Area", "ports", "s7", "modbus", "state", "word", "until", "raises"]
