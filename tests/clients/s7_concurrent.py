"""Eight clients at once, each writing and reading back its own bytes for a while; a ninth is
turned away while they are connected."""

import threading
import time

from s7_common import connect, main
from snap7.error import S7Error
from snap7.type import Area

CLIENTS = 8


def worker(port, index, seconds, connected, done, failures, rounds):
    try:
        client = connect(port, 0, 1 + index % 2)
        connected.wait()
        deadline = time.monotonic() + seconds
        count = 0
        while time.monotonic() < deadline:
            value = (index * 31 + count) % 256
            block = bytearray((value + k) % 256 for k in range(10))
            client.db_write(1, index * 10, block)
            flags = bytearray([value, index])
            client.write_area(Area.MK, 0, index * 16, flags)
            assert client.db_read(1, index * 10, 10) == block, (index, count)
            assert client.read_area(Area.MK, 0, index * 16, 2) == flags, (index, count)
            count += 1
        rounds[index] = count
        done.wait()
        client.disconnect()
    except BaseException as error:  # noqa: BLE001 - reported by the main thread
        failures.append((index, repr(error)))
        connected.abort()
        done.abort()


def run(argv):
    port, seconds = int(argv[0]), float(argv[1])
    connected = threading.Barrier(CLIENTS + 1)
    done = threading.Barrier(CLIENTS + 1)
    failures, rounds = [], [0] * CLIENTS
    threads = [
        threading.Thread(target=worker, args=(port, index, seconds, connected, done, failures, rounds))
        for index in range(CLIENTS)
    ]
    for thread in threads:
        thread.start()
    connected.wait(timeout=20)
    try:
        connect(port)
        turned_away = False
    except S7Error:
        turned_away = True
    done.wait(timeout=seconds + 20)
    for thread in threads:
        thread.join()
    assert not failures, failures
    assert turned_away, "a ninth client was served"
    assert all(count > 0 for count in rounds), rounds
    print("rounds", rounds)


main(run)
