"""The tank on an S5-115U over S7comm and Modbus TCP: DB 1's data word n at byte 2 × n, the
flags F as S7's M, read, written, stopped and restarted."""

from served import Area, modbus, ports, raises, s7, state, until, word

s7_port, modbus_port = ports()
plc = s7(s7_port, slot=1)
assert state(plc) == "S7CpuStatusRun"
assert word(plc.db_read(1, 0, 2)) == 500, "DW 0, the setpoint as loaded"
assert plc.get_order_code().OrderCode.decode().startswith("AWL S5-115U-944")

plc.write_area(Area.PE, 0, 0, bytearray((300).to_bytes(2, "big")))
until("DW 1, the level", lambda: word(plc.db_read(1, 2, 2)), 300)
until("FW 10, the level", lambda: word(plc.read_area(Area.MK, 0, 10, 2)), 300)
# D 4.0, the HMI's start: bit 0 of data word 4, in its right byte (DR 4), byte 9.
plc.db_write(1, 9, bytearray([1]))
until("the pump Q 0.0", lambda: plc.read_area(Area.PA, 0, 0, 1)[0] & 1, 1)
until("DW 2, one pump start", lambda: word(plc.db_read(1, 4, 2)), 1)

raises("DB 7 does not exist", lambda: plc.db_read(7, 0, 2))
raises("DB 1 has 5 data words", lambda: plc.db_read(1, 8, 4))
assert word(plc.db_read(1, 0, 2)) == 500

plc.plc_stop()
until("the CPU state", lambda: state(plc), "S7CpuStatusStop")
plc.plc_hot_start()
until("the CPU state", lambda: state(plc), "S7CpuStatusRun")
until("the startup OB ran again", lambda: word(plc.read_area(Area.MK, 0, 20, 2)), 2)
plc.plc_stop()
until("the CPU state", lambda: state(plc), "S7CpuStatusStop")
plc.plc_cold_start()
until("the CPU state", lambda: state(plc), "S7CpuStatusRun")
until("the flags cleared, then the startup OB", lambda: word(plc.read_area(Area.MK, 0, 20, 2)), 1)
assert plc.db_read(1, 8, 2) == bytearray(2), "D 4.0 back as loaded"

bus = modbus(modbus_port)
# The cold start cleared the PII; the modules still deliver 300 at the next cycle start.
until("input register 0", lambda: bus.read_input_registers(0, count=1).registers, [300])
assert bus.read_holding_registers(5, count=1).registers == [300], "FW 10"
bus.write_register(15, 77)
assert word(plc.read_area(Area.MK, 0, 30, 2)) == 77, "holding register 15 is FW 30"
assert bus.read_holding_registers(128, count=1).isError(), "past the 256 flag bytes"
bus.close()
plc.disconnect()
print("S5-115U over S7comm and Modbus: ok")
