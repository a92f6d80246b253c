"""What the fake CPU of tests/s7comm_protocol.rs reports of itself, checked alike through every
S7 client (python-snap7 3.x; Snap7's C library through python-snap7 1.x)."""

ORDER_CODE = b"6ES7 315-2AG10-0AB0"


def check_identity(client, version):
    """The order code, awl's version as the firmware's, and the CPU info."""
    order_code = client.get_order_code()
    # Snap7's C library keeps the space that fills the order code's field of 20 characters.
    assert order_code.OrderCode.rstrip() == ORDER_CODE, order_code.OrderCode
    assert f"{order_code.V1}.{order_code.V2}.{order_code.V3}" == version

    info = client.get_cpu_info()
    assert info.ASName == b"awl", info.ASName
    assert info.ModuleName == b"awl speed7", info.ModuleName
    assert info.ModuleTypeName == b"awl speed7", info.ModuleTypeName
    assert info.Copyright == b"awl, MIT licence", info.Copyright
    assert info.SerialNumber == b"AWL 0000001", info.SerialNumber
