"""--read-only: every read is served, every write and mode change refused, the CPU runs on."""

from served import Area, modbus, ports, raises, s7, state, word

s7_port, modbus_port = ports()
plc = s7(s7_port)
assert word(plc.db_read(1, 0, 2)) == 500
raises("a DB write", lambda: plc.db_write(1, 0, bytearray(b"\x00\x01")))
raises("an input write", lambda: plc.write_area(Area.PE, 0, 0, bytearray(b"\x00\x01")))
raises("a STOP", plc.plc_stop)
assert state(plc) == "S7CpuStatusRun"
assert word(plc.db_read(1, 0, 2)) == 500
bus = modbus(modbus_port)
assert bus.write_register(0, 1).isError()
assert bus.write_coil(0, True).isError()
assert not bus.read_holding_registers(0, count=1).isError()
bus.close()
plc.disconnect()
print("read-only: ok")
