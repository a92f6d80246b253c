"""Frames a server must not trust: each closes its connection or is answered with an
exception, and a client after them is served as ever."""

import random
import socket
import struct

from modbus_common import check, client, closed, frame, ok, raw_socket, receive, word

read_one = struct.pack(">BHH", 3, 0, 1)

for what, data in [
    ("a wrong protocol id", frame(read_one, protocol=7)),
    ("a length of 0", frame(b"", length=0)),
    ("a huge length", frame(read_one, length=0xFFFF)),
    ("a length past the longest PDU", frame(read_one, length=255)),
]:
    raw = raw_socket()
    raw.sendall(data)
    check(closed(raw), f"{what}: the connection closes")
    raw.close()

# A truncated frame, then the client vanishes.
raw = raw_socket()
raw.sendall(frame(read_one)[:9])
raw.close()

# A frame whose header promises more than comes, then the client vanishes mid-frame.
raw = raw_socket()
raw.sendall(frame(read_one, length=200))
raw.close()

# A request sent a byte at a time is served.
raw = raw_socket()
for single in frame(read_one):
    raw.sendall(bytes([single]))
check(receive(raw) == bytes([3, 2]) + word("flags", 0).to_bytes(2, "big"), "byte by byte")
# Two requests in one write are both answered, in order.
raw.sendall(frame(read_one, transaction=1) + frame(struct.pack(">BHH", 3, 1, 1), transaction=2))
check(receive(raw) == bytes([3, 2]) + word("flags", 0).to_bytes(2, "big"), "the first")
check(receive(raw) == bytes([3, 2]) + word("flags", 1).to_bytes(2, "big"), "the second")
# A PDU of the wrong length for its function: exception 3, the connection stays.
raw.sendall(frame(read_one + b"\x00"))
check(receive(raw) == bytes([0x83, 3]), "a byte too many: exception 3")
raw.sendall(frame(bytes([0x85, 0])))
check(receive(raw) == bytes([0x85, 1]), "a function code with its high bit: exception 1")
raw.close()

# Random bytes: answered or closed, never a hang (the socket's timeout would fail the test).
generator = random.Random(5)
for _ in range(40):
    raw = raw_socket()
    noise = bytes(generator.randrange(256) for _ in range(generator.randrange(1, 300)))
    try:
        raw.sendall(noise)
        raw.shutdown(socket.SHUT_WR)
        while not closed(raw):
            pass
    except TimeoutError:
        check(False, f"the server neither answers nor closes after {noise.hex()}")
    except OSError:
        pass  # the server closed first: the send or the shutdown found it so
    raw.close()

modbus = client()
registers = ok(modbus.read_holding_registers(0, count=2), "a client after them").registers
check(registers == [word("flags", 0), word("flags", 1)], f"served as ever: {registers}")
modbus.close()
print("modbus malformed frames: all passed")
