"""Several clients each monitor many items at a 10 ms sampling interval for a few seconds; each
client's changing value must keep arriving. Arguments: the port, the clients, the items per
client, the seconds. Prints the notifications received."""

import asyncio
import sys

from asyncua import Client
from opcua_common import namespace, node, run, url


class Count:
    def __init__(self):
        self.cycles = 0
        self.all = 0

    def datachange_notification(self, node, value, data):
        self.all += 1
        if node.nodeid.Identifier == "DB5.cycles":
            self.cycles += 1


async def one_client(items, seconds):
    async with Client(url()) as client:
        ns = await namespace(client)
        count = Count()
        subscription = await client.create_subscription(50, count)
        nodes = [node(client, ns, "DB5.cycles")]
        nodes += [node(client, ns, f"MB {byte}") for byte in range(items - 1)]
        await subscription.subscribe_data_change(nodes, sampling_interval=10)
        await asyncio.sleep(seconds)
        await subscription.delete()
        return count


async def main():
    clients, items, seconds = int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
    counts = await asyncio.gather(*(one_client(items, seconds) for _ in range(clients)))
    for count in counts:
        assert count.cycles >= seconds * 5, f"the changing value arrived {count.cycles} times"
    total = sum(count.all for count in counts)
    print(f"{clients} clients x {items} items over {seconds} s: {total} notifications")


run(main)
