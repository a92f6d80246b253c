"""Basic256Sha256 SignAndEncrypt with the client's own self-signed certificate, as the user of
`--opcua-users`; an anonymous client and a wrong password are refused. Arguments: the port, a
folder for the client's certificate."""

import socket
import sys
from pathlib import Path

from asyncua import Client, ua
from asyncua.crypto.cert_gen import setup_self_signed_certificate
from asyncua.crypto.security_policies import SecurityPolicyBasic256Sha256
from cryptography.x509.oid import ExtendedKeyUsageOID
from opcua_common import browse, namespace, run, typed, url

APPLICATION = "urn:awl:tests:client"


async def secured(folder, user=None, password=None):
    key, cert = folder / "client-key.pem", folder / "client-cert.der"
    await setup_self_signed_certificate(key, cert, APPLICATION, socket.gethostname(),
                                        [ExtendedKeyUsageOID.CLIENT_AUTH],
                                        {"commonName": "awl tests"})
    client = Client(url())
    client.application_uri = APPLICATION
    await client.set_security(SecurityPolicyBasic256Sha256, str(cert), str(key),
                              mode=ua.MessageSecurityMode.SignAndEncrypt)
    if user:
        client.set_user(user)
        client.set_password(password)
    return client


async def refused(folder, user, password):
    client = await secured(folder, user, password)
    try:
        await client.connect()
    except Exception:
        return
    await client.disconnect()
    raise AssertionError(f"the session of {user or 'an anonymous client'} was not refused")


async def main():
    folder = Path(sys.argv[2])
    client = await secured(folder, "operator", "secret")
    async with client:
        assert client.security_policy.Mode == ua.MessageSecurityMode.SignAndEncrypt
        ns = await namespace(client)
        setpoint = await browse(client, ns, "DataBlocks", "DB5", "setpoint")
        await setpoint.write_value(typed(321, ua.VariantType.Int16))
        assert await setpoint.read_value() == 321
    await refused(folder, None, None)
    await refused(folder, "operator", "wrong")
    print("OPC UA, Basic256Sha256 with a user: ok")


run(main)
