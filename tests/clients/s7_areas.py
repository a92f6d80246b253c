"""Every area and width read and written, several items in one job, item errors with the
connection still serving: python-snap7 against awl serve's S7comm server."""

import random

from s7_common import connect, item, job, main, refused
from snap7.type import Area, WordLen

WIDTHS = [
    (WordLen.Byte, 1),
    (WordLen.Char, 1),
    (WordLen.Word, 2),
    (WordLen.Int, 2),
    (WordLen.DWord, 4),
    (WordLen.DInt, 4),
    (WordLen.Real, 4),
]
BYTE_AREAS = [(Area.PE, 0, 128), (Area.PA, 0, 128), (Area.MK, 0, 128), (Area.DB, 1, 100)]


def bytes_and_bits(client, rng):
    for area, db, size in BYTE_AREAS:
        start = 0
        for word_len, width in WIDTHS:
            data = bytearray(rng.randrange(256) for _ in range(3 * width))
            client.write_area(area, db, start, data, word_len)
            assert client.read_area(area, db, start, 3, word_len) == data, (area, word_len)
            start += len(data)
        whole = client.read_area(area, db, 0, size)
        assert len(whole) == size
        client.write_area(area, db, 60, bytearray([0b1010_0000]))
        client.write_area(area, db, 60 * 8 + 3, bytearray([1]), WordLen.Bit)
        assert client.read_area(area, db, 60 * 8 + 3, 1, WordLen.Bit) == bytearray([1])
        assert client.read_area(area, db, 60 * 8 + 4, 1, WordLen.Bit) == bytearray([0])
        assert client.read_area(area, db, 60, 1) == bytearray([0b1010_1000]), area
        client.write_area(area, db, 60 * 8 + 7, bytearray([0]), WordLen.Bit)
        assert client.read_area(area, db, 60, 1) == bytearray([0b0010_1000]), area


def timers_and_counters(client):
    for area in (Area.TM, Area.CT):
        data = bytearray([0x01, 0x23, 0x02, 0x50, 0x09, 0x99])
        client.write_area(area, 0, 13, data)
        assert client.read_area(area, 0, 13, 3) == data
        assert client.read_area(area, 0, 14, 1) == data[2:4]
        assert len(client.read_area(area, 0, 0, 16)) == 32
    # The CPU gives no bit of a timer: "data type not supported".
    refused(lambda: client.read_area(Area.TM, 0, 0, 1, WordLen.Bit), "0x06")


def several_items(client):
    client.db_write(1, 70, bytearray(b"\x11\x22\x33"))
    client.write_area(Area.MK, 0, 100, bytearray(b"\x44\x55"))
    client.write_area(Area.PA, 0, 90, bytearray(b"\x66"))
    items = [
        {"area": Area.DB, "db_number": 1, "start": 70, "size": 3},
        {"area": Area.MK, "start": 100, "size": 2},
        {"area": Area.PA, "start": 90, "size": 1},
    ]
    _, values = client.read_multi_vars(items)
    assert values == [bytearray(b"\x11\x22\x33"), bytearray(b"\x44\x55"), bytearray(b"\x66")], values

    # A write job of three items (python-snap7 writes one item a job, so it is built here):
    # three bytes to DB 1 (then a fill byte), a bit of the outputs (a fill byte), a word of the
    # flags.
    parameters = bytes([0x05, 3])
    parameters += item(WordLen.Byte, 3, Area.DB, 1, 80 * 8)
    parameters += item(WordLen.Bit, 1, Area.PA, 0, 91 * 8 + 2)
    parameters += item(WordLen.Word, 1, Area.MK, 0, 110 * 8)
    data = bytes([0, 0x04, 0, 24, 0xA1, 0xA2, 0xA3, 0, 0, 0x03, 0, 1, 1, 0, 0, 0x04, 0, 16, 0xBE, 0xEF])
    client.write_area(Area.PA, 0, 91, bytearray([0]))
    answer = job(client, parameters, data)
    assert answer["raw_parameters"] == bytes([0x05, 3]), answer
    assert answer["raw_data"] == bytes([0xFF, 0xFF, 0xFF]), answer
    assert client.db_read(1, 80, 3) == bytearray(b"\xa1\xa2\xa3")
    assert client.read_area(Area.PA, 0, 91, 1) == bytearray([0b100])
    assert client.read_area(Area.MK, 0, 110, 2) == bytearray(b"\xbe\xef")

    # A read job whose middle item names the absent DB 2: the others are served.
    parameters = bytes([0x04, 3])
    parameters += item(WordLen.Byte, 2, Area.DB, 1, 80 * 8)
    parameters += item(WordLen.Byte, 2, Area.DB, 2, 0)
    parameters += item(WordLen.Word, 1, Area.MK, 0, 110 * 8)
    answer = job(client, parameters)
    assert answer["raw_data"] == bytes([0xFF, 0x04, 0, 16, 0xA1, 0xA2, 0x0A, 0, 0, 0, 0xFF, 0x04, 0, 16, 0xBE, 0xEF]), answer


def item_errors(client):
    refused(lambda: client.db_read(2, 0, 4), "object does not exist", "0x0a")
    refused(lambda: client.db_write(2, 0, bytearray(4)), "object does not exist", "0x0a")
    assert client.db_read(1, 0, 4) == client.read_area(Area.DB, 1, 0, 4)
    refused(lambda: client.db_read(1, 98, 4), "invalid address", "0x05")
    refused(lambda: client.read_area(Area.MK, 0, 127, 2, WordLen.Word), "0x05")
    assert len(client.db_read(1, 96, 4)) == 4


def run(argv):
    port, rack, slot, pdu_request, pdu_expected = map(int, argv)
    client = connect(port, rack, slot, pdu_request)
    assert client.get_pdu_length() == pdu_expected, client.get_pdu_length()
    bytes_and_bits(client, random.Random(rack * 16 + slot))
    timers_and_counters(client)
    several_items(client)
    item_errors(client)
    # A mark the test reads from the CPU's DB 1 afterwards.
    client.db_write(1, 96, bytearray(b"AWL!"))
    client.disconnect()


main(run)
