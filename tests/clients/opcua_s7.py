"""A STEP 7 program's data by name: browse to DB5/setpoint, read and write members of every
kind, subscribe to a changing value (stamped with the simulated time), the PLC's methods, and
the refusals of an unknown node and a wrong type."""

import asyncio

from asyncua import Client, ua
from opcua_common import browse, namespace, node, refused, run, typed, until, url


class Changes:
    def __init__(self):
        self.values = []
        self.stamps = []

    def datachange_notification(self, node, value, data):
        self.values.append(value)
        self.stamps.append(data.monitored_item.Value.SourceTimestamp)


async def members(client, ns):
    setpoint = await browse(client, ns, "DataBlocks", "DB5", "setpoint")
    assert setpoint.nodeid == ua.NodeId("DB5.setpoint", ns), setpoint.nodeid
    assert await setpoint.read_value() == 500
    assert await setpoint.read_data_type_as_variant_type() == ua.VariantType.Int16
    await setpoint.write_value(typed(640, ua.VariantType.Int16))
    assert await setpoint.read_value() == 640
    assert await node(client, ns, "DB5.DBW 0").read_value() == 640, "the same word unbrowsed"
    level = node(client, ns, "DB5.level")
    assert await level.read_value() == 12.5
    await level.write_value(typed(3.25, ua.VariantType.Float))
    assert await level.read_value() == 3.25
    speed = await browse(client, ns, "DataBlocks", "DB5", "motor", "speed")
    assert await speed.read_value() == 1200
    assert await node(client, ns, "DB5.delay").read_value() == 1500, "a TIME in milliseconds"
    table = await browse(client, ns, "DataBlocks", "DB5", "table")
    assert await table.read_value() == [0, 0, 0]
    await table.write_value(ua.DataValue(ua.Variant([7, 8, 9], ua.VariantType.Int16)))
    assert await node(client, ns, "DB5.table[2]").read_value() == 8
    name = node(client, ns, "DB5.name")
    assert await name.read_value() == "tank"
    await name.write_value(typed("pump", ua.VariantType.String))
    assert await name.read_value() == "pump"
    await refused("a name too long", name.write_value(typed("x" * 9, ua.VariantType.String)),
                  "BadOutOfRange")
    await refused("an unknown operand", node(client, ns, "XY 1").read_value(), "BadNodeIdUnknown")
    await refused("a data block the program lacks", node(client, ns, "DB9.DBW 0").read_value(),
                  "BadNodeIdUnknown")
    await refused("an INT written as a Double",
                  setpoint.write_value(typed(1.5, ua.VariantType.Double)), "BadTypeMismatch")


async def subscription(client, ns):
    changes = Changes()
    subscribed = await client.create_subscription(20, changes)
    await subscribed.subscribe_data_change(node(client, ns, "DB5.cycles"), sampling_interval=10)
    for _ in range(200):
        if len(changes.values) >= 4:
            break
        await asyncio.sleep(0.02)
    assert len(changes.values) >= 4, changes.values
    assert changes.values == sorted(changes.values), changes.values
    assert all(stamp is not None for stamp in changes.stamps)
    assert changes.stamps == sorted(changes.stamps), "the simulated time goes on"
    pump = Changes()
    watched = await client.create_subscription(20, pump)
    await watched.subscribe_data_change(node(client, ns, "Q 0.0"))
    assert await node(client, ns, "Q 0.0").read_value() is False
    await node(client, ns, "I 0.0").write_value(typed(True, ua.VariantType.Boolean))
    for _ in range(200):
        if True in pump.values:
            break
        await asyncio.sleep(0.02)
    assert True in pump.values, f"the pump's change arrives: {pump.values}"
    await subscribed.delete()
    await watched.delete()


async def methods(client, ns):
    plc = await browse(client, ns)
    state = node(client, ns, "PLC.State")
    setpoint = node(client, ns, "DB5.setpoint")
    assert await state.read_value() == "RUN"
    assert await node(client, ns, "PLC.Cycle").read_value() > 0
    await plc.call_method(f"{ns}:Stop")
    assert await state.read_value() == "STOP"
    await plc.call_method(f"{ns}:WarmRestart")
    await until("the state", state.read_value, "RUN")
    assert await setpoint.read_value() == 640, "a warm restart keeps the data"
    await refused("a start in RUN", plc.call_method(f"{ns}:WarmRestart"), "BadInvalidState")
    await plc.call_method(f"{ns}:Stop")
    await plc.call_method(f"{ns}:ColdRestart")
    await until("the state", state.read_value, "RUN")
    assert await setpoint.read_value() == 500, "a cold restart loads the data again"


async def main():
    async with Client(url()) as client:
        ns = await namespace(client)
        await members(client, ns)
        await subscription(client, ns)
        await methods(client, ns)
    print("OPC UA, STEP 7: ok")


run(main)
