"""A client writes the high-level switch I 8.0 by its node id: the input module's channel 0
raises OB 40, as an S7 client's write does, which counts the alarm."""

from asyncua import Client, ua
from opcua_common import namespace, node, run, typed, until, url


async def main():
    async with Client(url()) as client:
        ns = await namespace(client)
        await node(client, ns, "DB1.run").write_value(typed(True, ua.VariantType.Boolean))
        await node(client, ns, "I 8.0").write_value(typed(True, ua.VariantType.Boolean))
        alarms = node(client, ns, "DB1.high_alarms")
        await until("the alarms DB1.high_alarms", alarms.read_value, 1)
        assert await node(client, ns, "DB1.run").read_value() is False, "OB 40 reset the run"
    print("OB 40 from an OPC UA input write: ok")


run(main)
