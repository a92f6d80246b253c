"""A CPU held by a debugger's breakpoint as an S7 client sees it. Usage: dap_hold.py PORT; prints
SZL 0x0424's mode byte (0x0A: HOLD, 0x08: RUN) and the output word QW 0."""

from s7_common import connect, main


def run(argv):
    client = connect(int(argv[0]))
    mode = client.read_szl(0x0424, 0).Data[7]
    outputs = int.from_bytes(client.ab_read(0, 2), "big")
    print(mode, outputs)
    client.disconnect()


main(run)
