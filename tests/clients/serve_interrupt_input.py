"""A client writes the high-level switch I 8.0: the input module's channel 0 raises OB 40,
which counts the alarm and stops the pump."""

from served import Area, ports, s7, until, word

s7_port, _ = ports()
plc = s7(s7_port)
plc.write_area(Area.PE, 0, 0, bytearray((100).to_bytes(2, "big")))
plc.write_area(Area.DB, 1, 12, bytearray([1]))
until("the pump Q 0.0", lambda: plc.read_area(Area.PA, 0, 0, 1)[0] & 1, 1)
plc.write_area(Area.PE, 0, 8, bytearray([1]))
until("the alarms DB1.DBW 10", lambda: word(plc.db_read(1, 10, 2)), 1)
assert plc.db_read(1, 12, 1)[0] & 1 == 0, "OB 40 reset the HMI's run"
until("the pump Q 0.0", lambda: plc.read_area(Area.PA, 0, 0, 1)[0] & 1, 0)
plc.disconnect()
print("OB 40 from a client's input write: ok")
