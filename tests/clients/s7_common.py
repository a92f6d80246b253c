"""What the S7comm client scripts share: connecting to awl serve and checking refusals."""

import struct
import sys

import snap7
from snap7.error import S7Error

HOST = "127.0.0.1"


def connect(port, rack=0, slot=1, pdu_request=480):
    client = snap7.client.Client()
    client.pdu_length = pdu_request
    client.connect(HOST, rack, slot, port)
    return client


def refused(action, *fragments):
    """Runs `action`, which must raise an S7 error naming every fragment (case-insensitive)."""
    try:
        action()
    except S7Error as error:
        text = str(error).lower()
        for fragment in fragments:
            assert fragment.lower() in text, f"{fragment!r} not in {text!r}"
        return text
    raise AssertionError(f"{action} was not refused")


def item(word_len, count, area, db, start_bits):
    """One S7ANY item specification of a read or write job."""
    return struct.pack(">BBBBHHB", 0x12, 0x0A, 0x10, word_len, count, db, area) + struct.pack(">I", start_bits)[1:]


def job(client, parameters, data=b""):
    """Sends a job PDU built by hand and returns the parsed answer."""
    header = struct.pack(">BBHHHH", 0x32, 0x01, 0, client.protocol._next_sequence(), len(parameters), len(data))
    return client._send_receive(header + parameters + data)


def main(run):
    """Runs `run(argv)`; a failed check prints its traceback and exits with 1."""
    run(sys.argv[1:])
    print("ok")
