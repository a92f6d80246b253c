"""Snap7's C library, the client most HMIs and SCADA drivers are built on, through python-snap7
1.x (whose wheel bundles it) against awl serve: the CPU's identity, communication capabilities,
protection, list of lists and state; data blocks and areas read and written; STOP and warm
restart. With `read-only`, the protection of a read-only CPU and its refusals."""

import ctypes
import sys

import snap7
from fake_cpu import ORDER_CODE, check_identity
from snap7.types import Areas, S7SZLList

# The ids of the lists awl answers (src/serve/s7comm/szl.rs).
LISTS = [0x0000, 0x0011, 0x001C, 0x0111, 0x0131, 0x0132, 0x0232, 0x0424]
# An S7-300 CPU 315-2 PN/DP's MPI and communication bus data rates, in bit/s.
MPI_RATE, BUS_RATE = 12_000_000, 187_500


class CpInfo(ctypes.Structure):
    """Snap7's TS7CpInfo: four 32-bit integers. python-snap7 1.x declares them 16 bits wide, so
    its get_cp_info() shows the PDU length right and the rest shifted; the library is asked
    directly here to see all four."""

    _fields_ = [
        ("MaxPduLength", ctypes.c_int),
        ("MaxConnections", ctypes.c_int),
        ("MaxMpiRate", ctypes.c_int),
        ("MaxBusRate", ctypes.c_int),
    ]


def library(client, function, *args):
    """Calls Snap7's client function on `client`; it must succeed."""
    code = getattr(client._lib, function)(client._s7_client, *args)
    assert code == 0, f"{function}: {snap7.common.error_text(code)}"


def cp_info(client):
    info = CpInfo()
    library(client, "Cli_GetCpInfo", ctypes.byref(info))
    return info.MaxPduLength, info.MaxConnections, info.MaxMpiRate, info.MaxBusRate


def lists(client):
    """The ids of SZL 0x0000, as Snap7's Cli_ReadSZLList gives them. (python-snap7 1.x's
    read_szl_list() returns as many bytes of that list as it has ids: the first half.)"""
    found = S7SZLList()
    count = ctypes.c_int(len(found.List))
    library(client, "Cli_ReadSZLList", ctypes.byref(found), ctypes.byref(count))
    return list(found.List[: count.value])


def protection(client):
    found = client.get_protection()
    return found.sch_schal, found.sch_par, found.sch_rel, found.bart_sch, found.anl_sch


def connect(port):
    client = snap7.client.Client()
    client.connect("127.0.0.1", 0, 2, port)
    assert client.get_connected()
    # Snap7 asks for a PDU of 480 bytes; awl grants it.
    assert client.get_pdu_length() == 480
    return client


def writable(client, version, connections):
    assert client.get_cpu_state() == "S7CpuStatusRun"

    check_identity(client, version)

    # The longest PDU awl negotiates, the connections it serves at once, an S7-300's rates.
    assert cp_info(client) == (960, connections, MPI_RATE, BUS_RATE), cp_info(client)
    assert client.get_cp_info().MaxPduLength == 960

    # Protection level 1 from the mode selector at RUN-P, no password, no startup switch.
    assert protection(client) == (1, 0, 1, 2, 0), protection(client)

    assert lists(client) == LISTS, [hex(id) for id in lists(client)]
    assert len(client.read_szl_list()) == len(LISTS)
    # One module identification record by its index: the order code's.
    one = client.read_szl(0x0111, 1)
    assert (one.Header.LengthDR, one.Header.NDR) == (28, 1)
    assert bytes(one.Data[2:22]) == ORDER_CODE.ljust(20)
    # The protection of the CPU's communication section, as SZL 0x0232 gives it.
    section = client.read_szl(0x0132, 4)
    assert (section.Header.LengthDR, section.Header.NDR) == (40, 1)
    assert bytes(section.Data[:12]) == bytes([0, 4, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0])

    client.db_write(1, 10, bytearray(b"\x12\x34"))
    assert client.db_read(1, 10, 2) == bytearray(b"\x12\x34")
    client.write_area(Areas.MK, 0, 20, bytearray([0xAB, 0xCD]))
    assert client.read_area(Areas.MK, 0, 20, 2) == bytearray([0xAB, 0xCD])
    client.write_area(Areas.DB, 1, 40, bytearray(b"snap7"))
    assert client.read_area(Areas.DB, 1, 40, 5) == bytearray(b"snap7")
    # Two timers of a word each.
    assert len(client.read_area(Areas.TM, 0, 0, 2)) == 4

    assert client.plc_stop() == 0
    assert client.get_cpu_state() == "S7CpuStatusStop"
    assert client.plc_hot_start() == 0
    assert client.get_cpu_state() == "S7CpuStatusRun"
    # A start while the CPU runs is refused, as a real CPU refuses it.
    assert client.plc_hot_start() != 0


def read_only(client):
    # Write protection (level 2) set in the parameters, as a password sets it.
    assert protection(client) == (1, 2, 2, 2, 0), protection(client)
    assert len(client.db_read(1, 0, 4)) == 4
    try:
        client.db_write(1, 0, bytearray(2))
    except RuntimeError as error:
        # Snap7 names the item's return code 0x03 (access denied) no further.
        assert b"function refused by cpu" in str(error).encode().lower(), error
    else:
        raise AssertionError("a write to a read-only CPU was not refused")
    assert client.plc_stop() != 0
    assert client.get_cpu_state() == "S7CpuStatusRun"


def main(argv):
    client = connect(int(argv[0]))
    if argv[1] == "read-only":
        read_only(client)
    else:
        writable(client, argv[1], int(argv[2]))
    client.disconnect()
    print("ok")


main(sys.argv[1:])
