"""What the Modbus client scripts share: the fake CPU's memory as the test fills it, the raw
frames of requests pymodbus will not send, and checks that say what went wrong."""

import socket
import struct
import sys

from pymodbus.client import ModbusTcpClient

# The fake CPU's areas (tests/modbus_protocol.rs): their sizes and first contents.
SIZES = {"inputs": 128, "outputs": 128, "flags": 256, "db1": 20}
FACTORS = {"inputs": (7, 3), "outputs": (11, 1), "flags": (13, 5), "db1": (17, 2)}


def byte(area, n):
    factor, offset = FACTORS[area]
    return (n * factor + offset) % 256


def bit(area, n):
    return bool(byte(area, n // 8) >> (n % 8) & 1)


def word(area, n):
    """Register n: the big-endian word at byte 2n."""
    return byte(area, 2 * n) << 8 | byte(area, 2 * n + 1)


def port():
    return int(sys.argv[1])


def client():
    connection = ModbusTcpClient("127.0.0.1", port=port(), timeout=5, retries=0)
    check(connection.connect(), "the client connects")
    return connection


def check(condition, what):
    if not condition:
        print(f"FAILED: {what}", file=sys.stderr)
        sys.exit(1)


def ok(response, what):
    check(not response.isError(), f"{what}: {response}")
    return response


def exception(response, code, what):
    check(response.isError(), f"{what}: an exception, not {response}")
    check(
        response.exception_code == code,
        f"{what}: exception {code}, not {response.exception_code}",
    )


def frame(pdu, transaction=1, protocol=0, length=None, unit=1):
    """An MBAP header and `pdu`; `length` overrides the header's length field."""
    if length is None:
        length = len(pdu) + 1
    return struct.pack(">HHHB", transaction, protocol, length, unit) + pdu


def raw_socket():
    connection = socket.create_connection(("127.0.0.1", port()), timeout=5)
    return connection


def receive(connection):
    """One response frame's PDU, or None when the server closed the connection."""
    header = b""
    while len(header) < 7:
        chunk = connection.recv(7 - len(header))
        if not chunk:
            return None
        header += chunk
    _, protocol, length, _ = struct.unpack(">HHHB", header)
    check(protocol == 0, f"protocol id 0 in the response, not {protocol}")
    pdu = b""
    while len(pdu) < length - 1:
        chunk = connection.recv(length - 1 - len(pdu))
        check(chunk, "the response arrives whole")
        pdu += chunk
    return pdu


def closed(connection):
    """Whether the server closes the connection (within the socket's timeout)."""
    try:
        return connection.recv(300) == b""
    except ConnectionResetError:
        return True
