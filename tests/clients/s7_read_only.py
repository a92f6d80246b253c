"""A read-only CPU: writes and control commands refused, reads served."""

from s7_common import connect, main, refused
from snap7.type import Area, WordLen


def run(argv):
    client = connect(int(argv[0]))
    assert len(client.db_read(1, 0, 10)) == 10
    refused(lambda: client.db_write(1, 0, bytearray(2)), "accessing the object not allowed", "0x03")
    refused(lambda: client.write_area(Area.MK, 0, 8 * 3, bytearray([1]), WordLen.Bit), "0x03")
    refused(client.plc_stop, "protection level")
    refused(client.plc_hot_start, "protection level")
    assert len(client.read_area(Area.TM, 0, 0, 16)) == 32
    client.disconnect()


main(run)
