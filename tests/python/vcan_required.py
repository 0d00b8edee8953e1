"""The rule every vcan test module of this directory starts with: without the SocketCAN interface the module is
skipped with the reason, except where CANOPEN_REQUIRE_VCAN=1 (CI, inside the with-vcan VM), where a skip would
hide that nothing ran, so it fails instead."""

import os
import pathlib

import pytest


def require_vcan(iface):
    """Skips the calling test module (or fails, see above) unless the interface `iface` exists."""
    if pathlib.Path(f"/sys/class/net/{iface}").exists():
        return
    if os.environ.get("CANOPEN_REQUIRE_VCAN") == "1":
        raise RuntimeError(f"no SocketCAN interface {iface} but CANOPEN_REQUIRE_VCAN=1")
    pytest.skip(f"no SocketCAN interface {iface}: run through scripts/vcan-run.sh (scripts/test-interop.sh)",
                allow_module_level=True)
