"""`awl serve --read-only`: reads and subscriptions are served, every write and method call is
refused with BadUserAccessDenied."""

from asyncua import Client, ua
from opcua_common import browse, namespace, node, refused, run, typed, url


async def main():
    async with Client(url()) as client:
        ns = await namespace(client)
        setpoint = await browse(client, ns, "DataBlocks", "DB5", "setpoint")
        assert await setpoint.read_value() == 500
        await refused("a browsed write", setpoint.write_value(typed(1, ua.VariantType.Int16)),
                      "BadUserAccessDenied")
        await refused("a write by operand", node(client, ns, "MW 10").write_value(
            typed(1, ua.VariantType.UInt16)), "BadUserAccessDenied")
        await refused("a wrong type too", setpoint.write_value(typed(1.5, ua.VariantType.Double)),
                      "BadUserAccessDenied")
        plc = await browse(client, ns)
        await refused("a STOP", plc.call_method(f"{ns}:Stop"), "BadUserAccessDenied")
        assert await node(client, ns, "PLC.State").read_value() == "RUN"
    print("OPC UA, read-only: ok")


run(main)
