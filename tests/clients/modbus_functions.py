"""Every function code against the default map: discrete inputs = I bits, coils = Q bits,
input registers = IW, holding registers = MW; exceptions 1, 2 and 3."""

import struct

from modbus_common import (
    SIZES, bit, check, client, exception, frame, ok, raw_socket, receive, word,
)

modbus = client()

# 2: discrete inputs are the input bits, I 0.0 = 0, I 1.0 = 8.
inputs = ok(modbus.read_discrete_inputs(3, count=21), "read discrete inputs").bits[:21]
check(inputs == [bit("inputs", n) for n in range(3, 24)], f"discrete inputs 3-23: {inputs}")

# 1: coils are the output bits.
coils = ok(modbus.read_coils(0, count=16), "read coils").bits[:16]
check(coils == [bit("outputs", n) for n in range(16)], f"coils 0-15: {coils}")

# 4: input registers are the input words, IW 0 = 0, IW 2 = 1.
registers = ok(modbus.read_input_registers(1, count=4), "read input registers").registers
check(registers == [word("inputs", n) for n in range(1, 5)], f"input registers: {registers}")

# 3: holding registers are the flag words.
registers = ok(modbus.read_holding_registers(0, count=3), "read holding registers").registers
check(registers == [word("flags", n) for n in range(3)], f"holding registers: {registers}")

# 5 and 15: coils written, read back; the test checks the bytes of Q they landed in.
ok(modbus.write_coil(100, True), "write single coil")
ok(modbus.write_coil(101, False), "write single coil off")
pattern = [n % 3 == 0 for n in range(21)]
ok(modbus.write_coils(203, pattern), "write multiple coils")
coils = ok(modbus.read_coils(203, count=21), "read the coils back").bits[:21]
check(coils == pattern, f"coils 203-223 read back: {coils}")
check(modbus.read_coils(100, count=2).bits[:2] == [True, False], "coils 100 and 101")

# 6 and 16: registers written, read back.
ok(modbus.write_register(7, 0xBEEF), "write single register")
ok(modbus.write_registers(20, [1, 0x1234, 0xFFFF]), "write multiple registers")
registers = ok(modbus.read_holding_registers(20, count=3), "read back").registers
check(registers == [1, 0x1234, 0xFFFF], f"holding registers 20-22: {registers}")

# 23: the write comes before the read.
registers = ok(
    modbus.readwrite_registers(read_address=30, read_count=2, write_address=31, values=[0x4242]),
    "read/write multiple registers",
).registers
check(registers == [word("flags", 30), 0x4242], f"read/write: {registers}")

# 2, illegal data address: past the end of the flags (256 bytes: registers 0-127) and Q.
last = SIZES["flags"] // 2 - 1
ok(modbus.read_holding_registers(last, count=1), "the last flag word")
exception(modbus.read_holding_registers(last, count=2), 2, "a register past the flags")
exception(modbus.write_register(last + 1, 5), 2, "a write past the flags")
exception(modbus.read_coils(SIZES["outputs"] * 8 - 4, count=8), 2, "coils past the outputs")
exception(modbus.read_discrete_inputs(65535, count=2), 2, "past address 65535")

# 1, illegal function: a function the server does not have (22, mask write register).
exception(modbus.mask_write_register(address=1, and_mask=0xF0F0, or_mask=1), 1, "function 22")
modbus.close()

raw = raw_socket()
raw.sendall(frame(bytes([0x41, 0, 0])))
check(receive(raw) == bytes([0xC1, 1]), "function 0x41: exception 1")
# 3, illegal data value: quantities past the protocol's limits, a short byte count.
raw.sendall(frame(struct.pack(">BHH", 3, 0, 126)))
check(receive(raw) == bytes([0x83, 3]), "126 registers: exception 3")
raw.sendall(frame(struct.pack(">BHH", 1, 0, 0)))
check(receive(raw) == bytes([0x81, 3]), "0 coils: exception 3")
raw.sendall(frame(struct.pack(">BHHB", 0x0F, 0, 100, 0)))
check(receive(raw) == bytes([0x8F, 3]), "100 coils in 0 bytes: exception 3")
raw.sendall(frame(struct.pack(">BHHB", 0x10, 0, 0x8000, 0)))
check(receive(raw) == bytes([0x90, 3]), "0x8000 registers: exception 3")
# The connection still serves.
raw.sendall(frame(struct.pack(">BHH", 3, 7, 1), transaction=0x7777))
check(receive(raw) == bytes([3, 2, 0xBE, 0xEF]), "register 7 after the exceptions")
raw.close()
print("modbus functions: all passed")
