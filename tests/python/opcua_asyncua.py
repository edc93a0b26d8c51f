"""Drives plcrun's OPC UA server with Python's asyncua (an independent
client): run by tests/opcua_python.rs as

    python opcua_asyncua.py URL WORKDIR

against `plcrun tests/python/opcua_counter.st --opcua ... --opcua-users`
with user `op` / `pw`. Prints one line per check; exits 0 when all pass.
"""

import asyncio
import socket
import sys
from pathlib import Path

from asyncua import Client, ua
from asyncua.crypto.cert_gen import setup_self_signed_certificate
from cryptography.x509.oid import ExtendedKeyUsageOID

URL, WORK = sys.argv[1], Path(sys.argv[2])
APP_URI = "urn:plcrun:asyncua-test"


async def client(user=None):
    key, cert = WORK / "client-key.pem", WORK / "client-cert.der"
    if not cert.exists():
        await setup_self_signed_certificate(
            key, cert, APP_URI, socket.gethostname(),
            [ExtendedKeyUsageOID.CLIENT_AUTH], {"commonName": "plcrun asyncua test"})
    c = Client(URL, timeout=10)
    c.application_uri = APP_URI
    await c.set_security_string(f"Basic256Sha256,SignAndEncrypt,{cert},{key}")
    if user:
        c.set_user(user[0])
        c.set_password(user[1])
    return c


async def until(node, want, seconds=5.0):
    value = None
    for _ in range(int(seconds / 0.02)):
        value = await node.read_value()
        if value == want:
            return value
        await asyncio.sleep(0.02)
    return value


def expect_status(error, name):
    assert type(error).__name__ == name, f"{type(error).__name__} instead of {name}"


async def main():
    op = await client(("op", "pw"))
    async with op:
        ns = await op.get_namespace_index("urn:plcrun:plc")
        node = lambda path: op.get_node(f"ns={ns};s={path}")
        # A computed output, read.
        assert await node("doubled").read_value() == 0
        print("read doubled = 0")
        # An input written; the program reacts in a later cycle.
        await node("setpoint").write_value(ua.Variant(21, ua.VariantType.Int16))
        assert await until(node("doubled"), 42) == 42, "the program never saw the write"
        print("wrote setpoint = 21, read doubled = 42")
        # A plain Python int (Int64) fits an INT: accepted.
        await node("setpoint").write_value(5)
        assert await until(node("doubled"), 10) == 10
        print("wrote setpoint = 5 as Int64, read doubled = 10")
        # A subscription receives the counter's changes.
        seen = []

        class Handler:
            def datachange_notification(self, n, value, data):
                seen.append(value)

        sub = await op.create_subscription(20, Handler())
        await sub.subscribe_data_change(node("ticks"))
        await asyncio.sleep(1.0)
        await sub.delete()
        assert len(seen) >= 5 and seen == sorted(seen), seen
        print(f"subscription: {len(seen)} changes of ticks, increasing")
        # A CONSTANT is refused.
        try:
            await node("limit").write_value(ua.Variant(3, ua.VariantType.Int16))
            raise AssertionError("a CONSTANT was written")
        except ua.UaStatusCodeError as e:
            expect_status(e, "BadNotWritable")
        print("write to a CONSTANT: BadNotWritable")
        # An unknown NodeId.
        try:
            await op.get_node(f"ns={ns};s=no_such_variable").read_value()
            raise AssertionError("an unknown NodeId was read")
        except ua.UaStatusCodeError as e:
            expect_status(e, "BadNodeIdUnknown")
        print("read of an unknown NodeId: BadNodeIdUnknown")
        # Browse: the program's folder holds its variables.
        objects = op.nodes.objects
        folder = await objects.get_child([f"{ns}:Main"])
        names = {(await c.read_browse_name()).Name for c in await folder.get_children()}
        assert {"setpoint", "doubled", "ticks", "limit"} <= names, names
        print(f"browse Objects/Main: {sorted(names)}")
    anon = await client()
    async with anon:
        ns = await anon.get_namespace_index("urn:plcrun:plc")
        setpoint = anon.get_node(f"ns={ns};s=setpoint")
        assert await setpoint.read_value() == 5
        try:
            await setpoint.write_value(ua.Variant(9, ua.VariantType.Int16))
            raise AssertionError("an anonymous write was accepted")
        except ua.UaStatusCodeError as e:
            expect_status(e, "BadUserAccessDenied")
        print("anonymous write: BadUserAccessDenied")
    print("OK")


asyncio.run(main())
