"""A STEP 5 program (the S5-115U tank): its data block's data words browsed and written, a flag
word by operand, and a STOP and warm restart."""

from asyncua import Client, ua
from opcua_common import browse, namespace, node, run, typed, until, url


async def main():
    async with Client(url()) as client:
        ns = await namespace(client)
        setpoint = await browse(client, ns, "DataBlocks", "DB1", "DW 0")
        assert setpoint.nodeid == ua.NodeId("DB 1 DW 0", ns), setpoint.nodeid
        assert await setpoint.read_value() == 500
        assert await setpoint.read_data_type_as_variant_type() == ua.VariantType.UInt16
        await setpoint.write_value(typed(300, ua.VariantType.UInt16))
        assert await node(client, ns, "DB 1 DW 0").read_value() == 300
        await node(client, ns, "IW 0").write_value(typed(120, ua.VariantType.UInt16))
        level = node(client, ns, "FW 10")
        await until("the level FW 10", level.read_value, 120)
        flags = await browse(client, ns, "Flags")
        names = [(await child.read_browse_name()).Name for child in await flags.get_children()]
        assert "FY 0" in names and "MB 0" not in names, sorted(names)[:3]
        plc = await browse(client, ns)
        state = node(client, ns, "PLC.State")
        await plc.call_method(f"{ns}:Stop")
        assert await state.read_value() == "STOP"
        await plc.call_method(f"{ns}:WarmRestart")
        await until("the state", state.read_value, "RUN")
    print("OPC UA, STEP 5: ok")


run(main)
