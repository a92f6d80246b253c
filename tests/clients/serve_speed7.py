"""The tank on speed7 over S7comm and Modbus TCP: read, written, stopped and restarted."""

from served import Area, modbus, ports, raises, s7, state, until, word

s7_port, modbus_port = ports()
plc = s7(s7_port)
assert state(plc) == "S7CpuStatusRun"
assert word(plc.db_read(1, 0, 2)) == 500, "the setpoint as loaded"
assert plc.get_order_code().OrderCode.decode().startswith("6ES7 315-2EH14-0AB0")
assert plc.get_plc_datetime().year == 2024

# The plant simulation's level reaches the program through the input modules.
plc.write_area(Area.PE, 0, 0, bytearray((300).to_bytes(2, "big")))
until("the level in DB1.DBW 2", lambda: word(plc.db_read(1, 2, 2)), 300)
# The HMI's start: the pump fills below the setpoint.
plc.write_area(Area.DB, 1, 12, bytearray([1]))
until("the pump Q 0.0", lambda: plc.read_area(Area.PA, 0, 0, 1)[0] & 1, 1)
plc.write_area(Area.PE, 0, 0, bytearray((600).to_bytes(2, "big")))
until("the pump off above the setpoint", lambda: plc.read_area(Area.PA, 0, 0, 1)[0] & 1, 0)
assert word(plc.db_read(1, 4, 2)) == 1, "one pump start"

# Several variables in one request, and every width.
result, items = plc.read_multi_vars([
    {"area": Area.DB, "db_number": 1, "start": 0, "size": 2},
    {"area": Area.MK, "db_number": 0, "start": 20, "size": 2},
    {"area": Area.PE, "db_number": 0, "start": 0, "size": 2},
])
assert word(items[0]) == 500 and word(items[1]) == 1 and word(items[2]) == 600, items
plc.write_area(Area.MK, 0, 40, bytearray(b"\x12\x34\x56\x78"))
assert plc.read_area(Area.MK, 0, 40, 4) == bytearray(b"\x12\x34\x56\x78")
assert len(plc.read_area(Area.TM, 0, 0, 2)) == 4 and len(plc.read_area(Area.CT, 0, 0, 2)) == 4

# An absent DB is an error for that request; the connection stays up.
raises("DB 5 does not exist", lambda: plc.db_read(5, 0, 2))
assert word(plc.db_read(1, 0, 2)) == 500

# STOP: no more cycles; a hot start keeps the memory, a cold start puts it back as loaded.
plc.db_write(1, 0, bytearray((700).to_bytes(2, "big")))
plc.plc_stop()
until("the CPU state", lambda: state(plc), "S7CpuStatusStop")
cycles = plc.db_read(1, 6, 4)
assert plc.db_read(1, 6, 4) == cycles, "no cycle in STOP"
plc.plc_hot_start()
until("the CPU state", lambda: state(plc), "S7CpuStatusRun")
until("OB 100 ran again", lambda: word(plc.read_area(Area.MK, 0, 20, 2)), 2)
assert word(plc.db_read(1, 0, 2)) == 700, "a hot start keeps the data"
plc.plc_stop()
until("the CPU state", lambda: state(plc), "S7CpuStatusStop")
plc.plc_cold_start()
until("the CPU state", lambda: state(plc), "S7CpuStatusRun")
assert word(plc.db_read(1, 0, 2)) == 500, "a cold start puts the DB back as loaded"
until("the flags cleared, then OB 100", lambda: word(plc.read_area(Area.MK, 0, 20, 2)), 1)

# Modbus: discrete inputs are the input bits, coils the output bits, input registers the
# input words, holding registers the flag words.
bus = modbus(modbus_port)
# The cold start cleared the PII; the modules still deliver 600 at the next cycle start.
until("input register 0", lambda: bus.read_input_registers(0, count=1).registers, [600])
assert bus.read_discrete_inputs(8, count=8).bits[:8] == [(600 >> bit) & 1 == 1 for bit in range(8)]
assert bus.read_holding_registers(10, count=1).registers == [1], "MW 20 = 1"
bus.write_register(25, 4321)
assert word(plc.read_area(Area.MK, 0, 50, 2)) == 4321, "holding register 25 is MW 50"
bus.write_coil(7, True)
assert plc.read_area(Area.PA, 0, 0, 1)[0] & 0x80, "coil 7 is Q 0.7"
assert bus.read_holding_registers(4096, count=1).isError(), "past the 8192 flag bytes"
bus.close()
plc.disconnect()
print("speed7 over S7comm and Modbus: ok")
