"""The CPU's state, stop and restarts, order code, CPU info and clock through python-snap7."""

from datetime import datetime, timedelta

from fake_cpu import check_identity
from s7_common import connect, main, refused
from snap7.type import cpu_statuses


def state(client):
    # python-snap7 3.x's get_cpu_state does not ask the CPU; SZL 0x0424's mode byte does.
    return cpu_statuses[client.read_szl(0x0424, 0).Data[7]]


def run(argv):
    port, clock_ms, version = int(argv[0]), int(argv[1]), argv[2]
    client = connect(port, 0, 2, pdu_request=240)
    assert client.get_pdu_length() == 240
    assert state(client) == "S7CpuStatusRun"
    refused(client.plc_hot_start, "operating mode already set")
    client.plc_stop()
    assert state(client) == "S7CpuStatusStop"
    client.plc_hot_start()
    assert state(client) == "S7CpuStatusRun"
    client.plc_stop()
    client.plc_cold_start()
    assert state(client) == "S7CpuStatusRun"
    refused(client.plc_cold_start, "operating mode already set")

    # The CPU info's eight records of 34 bytes: more than a PDU of 240 bytes holds, read in two
    # packets.
    check_identity(client, version)

    expected = datetime(1990, 1, 1) + timedelta(milliseconds=clock_ms)
    assert client.get_plc_datetime() == expected, client.get_plc_datetime()
    refused(lambda: client.set_plc_datetime(datetime(2025, 1, 1)), "0x8104")
    refused(lambda: client.read_szl(0x0132, 1), "information function unavailable")
    # python-snap7's get_cpu_state sends a read job without items: wrong frames.
    refused(client.get_cpu_state, "class=0x85")
    assert state(client) == "S7CpuStatusRun"
    client.disconnect()


main(run)
