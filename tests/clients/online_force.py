"""The online page's force against python-snap7 (tests/serve.rs): a forced input holds against
the client's write, a forced output is what the client reads, and neither the program nor the
client's write changes it, until the force ends."""

import json
import sys
import time
import urllib.request

from served import Area, s7, until, word

s7_port, http_port = int(sys.argv[1]), int(sys.argv[3])
plc = s7(s7_port)


def api(method, path, body=None):
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(
        f"http://127.0.0.1:{http_port}{path}",
        method=method,
        data=data,
        headers={"Content-Type": "application/json"},
    )
    with urllib.request.urlopen(request) as answer:
        return json.load(answer)


def pump():
    """Q 0.0 as a client reads it."""
    return plc.read_area(Area.PA, 0, 0, 1)[0] & 1


# The level sensor IW 0 forced to 100: the client's write reaches the input module, the program
# (it copies IW 0 into DB1.DBW 2) and the clients read the forced PII.
assert api("POST", "/api/force", {"operand": "IW 0", "value": 100})["raw"] == 100
plc.write_area(Area.PE, 0, 0, bytearray((700).to_bytes(2, "big")))
time.sleep(0.2)
assert word(plc.db_read(1, 2, 2)) == 100, "the program read the forced input"
assert word(plc.read_area(Area.PE, 0, 0, 2)) == 100, "a client reads the forced PII"

# The pump Q 0.0 forced on: the program writes 0 in every cycle (the HMI's run is off), and a
# client's write of 0 does not hold either.
api("POST", "/api/force", {"operand": "Q 0.0", "value": 1})
until("the forced pump", pump, 1)
plc.write_area(Area.PA, 0, 0, bytearray([0]))
time.sleep(0.2)
assert pump() == 1, "the force held against the client's write and the program's"
modules = api("GET", "/api/values?operands=PQB%200")["values"][0]["raw"]
assert modules & 1 == 1, "the output module has the forced value"
assert api("GET", "/api/cpu")["forces"] == 2

# Unforced: the module's 700 reaches the program, and the pump is the program's again.
assert api("DELETE", "/api/force?operand=IW%200") == {"operand": "IW 0"}
until("the level from the module", lambda: word(plc.db_read(1, 2, 2)), 700)
assert api("DELETE", "/api/force") == {"operands": ["Q 0.0"]}
until("the program's pump", pump, 0)
assert api("GET", "/api/forces") == {"forces": []}
