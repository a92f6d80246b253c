"""What the OPC UA client scripts of tests/opcua.rs share: the server's address from the command
line, the PLC's namespace, its nodes by operand, waiting for a value, and an expected refusal."""

import asyncio
import sys
import time

from asyncua import Client, ua


def url():
    """The server's address, from the port on the command line."""
    return f"opc.tcp://127.0.0.1:{int(sys.argv[1])}/"


async def namespace(client):
    return await client.get_namespace_index("urn:awl:plc")


def node(client, ns, operand):
    """A node by its id: an operand in the command line's notation."""
    return client.get_node(ua.NodeId(operand, ns))


async def browse(client, ns, *path):
    """The node at PLC/... under Objects, by browse names."""
    return await client.nodes.objects.get_child([f"{ns}:{name}" for name in ("PLC",) + path])


def typed(value, variant_type):
    return ua.DataValue(ua.Variant(value, variant_type))


async def until(what, read, wanted, seconds=5.0):
    """Reads until `await read()` gives `wanted` (the program needs a cycle or two)."""
    deadline = time.monotonic() + seconds
    while True:
        value = await read()
        if value == wanted:
            return
        assert time.monotonic() < deadline, f"{what} is {value!r}, not {wanted!r}"
        await asyncio.sleep(0.02)


async def refused(what, action, status):
    """`action` must fail with the status named `status` (`BadTypeMismatch`)."""
    try:
        await action
    except ua.UaStatusCodeError as error:
        name = type(error).__name__
        assert name == status, f"{what}: {name}, not {status}"
        return
    raise AssertionError(f"{what} was not refused with {status}")


def run(main):
    asyncio.run(main())
