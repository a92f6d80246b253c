"""Malformed, truncated and oversized packets on both servers, a client that sends half a
packet and one that vanishes; then working clients are served as before."""

import socket
import struct

from served import modbus, ports, s7, word

s7_port, modbus_port = ports()


def send(port, data, read=True):
    with socket.create_connection(("127.0.0.1", port), timeout=5) as sock:
        sock.sendall(data)
        if read:
            try:
                sock.recv(4096)
            except (socket.timeout, ConnectionError):
                pass


garbage = [
    b"\x00" * 7,
    b"GET / HTTP/1.0\r\n\r\n",
    b"\x03\x00\xff\xff" + b"\x00" * 16,       # TPKT claiming 65535 bytes
    b"\x03\x00\x00\x05\x02",                  # TPKT shorter than its header needs
    b"\x03\x00\x00\x16\x11\xe0\x00\x00\x00\x01\x00\xc1\x02\x01\x00\xc2\x02\x01\x02\xc0\x01",  # CR cut short
    bytes(range(256)),
]
for packet in garbage:
    send(s7_port, packet)
send(s7_port, b"\x03\x00", read=False)  # half a header, then gone

modbus_garbage = [
    b"\x00\x01\x00\x00\x00\x06",                              # MBAP without its unit and PDU
    struct.pack(">HHHB", 1, 0, 0xFFFF, 1) + b"\x03",         # length 65535
    struct.pack(">HHHB", 1, 7, 6, 1) + b"\x03\x00\x00\x00\x01",  # protocol id 7
    struct.pack(">HHHB", 1, 0, 2, 1) + b"\x55",              # function 0x55
    bytes(range(256)),
]
for packet in modbus_garbage:
    send(modbus_port, packet)

plc = s7(s7_port)
assert word(plc.db_read(1, 0, 2)) == 500
plc.disconnect()
bus = modbus(modbus_port)
assert not bus.read_holding_registers(0, count=2).isError()
bus.close()
print("malformed packets, then working clients: ok")
