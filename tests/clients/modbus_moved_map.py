"""A scenario's [modbus] moves the tables: coils onto the inputs (a plant simulation writing
its sensors), discrete inputs from M 2.1, input registers onto QW 4 and a missing DB 9,
holding registers onto DB 1 (20 bytes)."""

from modbus_common import SIZES, bit, byte, check, client, exception, ok, word

modbus = client()

coils = ok(modbus.read_coils(0, count=12), "read coils").bits[:12]
check(coils == [bit("inputs", n) for n in range(12)], f"coils = input bits: {coils}")
ok(modbus.write_coils(8, [True] * 8), "sensors written into coils 8-15")
check(modbus.read_coils(8, count=8).bits[:8] == [True] * 8, "I 1.0-1.7 read back")

inputs = ok(modbus.read_discrete_inputs(0, count=7), "discrete inputs").bits[:7]
check(inputs == [bit("flags", n) for n in range(17, 24)], f"from M 2.1: {inputs}")

registers = ok(modbus.read_holding_registers(0, count=10), "holding registers").registers
check(registers == [word("db1", n) for n in range(10)], f"DB1 words: {registers}")
ok(modbus.write_register(9, 0xCAFE), "the last word of DB 1")
exception(modbus.read_holding_registers(9, count=2), 2, "past the end of DB 1")
exception(modbus.write_registers(10, [1]), 2, "a write past the end of DB 1")

exception(modbus.read_input_registers(0, count=1), 2, "a data block that does not exist")
modbus.close()
print("modbus moved map: all passed")
