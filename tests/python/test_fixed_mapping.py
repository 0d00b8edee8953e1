"""python canopen as the master of the example node built with a fixed PDO mapping (canopen-core without its
`pdo-dynamic-mapping` feature, PDO-30: "const if mapping fixed"), over a real SocketCAN interface. Runs only
where `vcan0` exists, as test_interop.py.

The node binary is NODE_BIN_FIXED (default target/debug/examples/node-fixed-mapping, which
scripts/test-interop.sh builds with every default feature of the `canopen` facade but `pdo-dynamic-mapping`).
It writes its EDS with `--eds` first; the master loads that EDS.
"""

import os
import pathlib
import subprocess
import tempfile
import time

import pytest
from vcan_required import require_vcan

ROOT = pathlib.Path(__file__).resolve().parents[2]
IFACE = os.environ.get("CANOPEN_IFACE", "vcan0")
NODE_ID = 6

require_vcan(IFACE)

import canopen  # noqa: E402
from canopen.sdo.exceptions import SdoAbortedError  # noqa: E402
from helpers import abort_code, check_default_io_module_mappings, wait_until  # noqa: E402

NODE_BIN = os.environ.get("NODE_BIN_FIXED", str(ROOT / "target/debug/examples/node-fixed-mapping"))
MAPPINGS = (0x1600, 0x1601, 0x1A00, 0x1A01)


@pytest.fixture(scope="module")
def eds_path():
    path = os.path.join(tempfile.mkdtemp(), "io_module_fixed.eds")
    subprocess.run([NODE_BIN, "--eds", path, "--node-id", str(NODE_ID)], check=True)
    return path


@pytest.fixture(scope="module")
def node(eds_path):
    log = open(os.path.join(tempfile.mkdtemp(), "node.log"), "w")
    proc = subprocess.Popen([NODE_BIN, "--iface", IFACE, "--node-id", str(NODE_ID), "--quiet", "--sdo-timeout", "5000"],
                            stdout=log, stderr=subprocess.STDOUT)
    time.sleep(0.5)
    assert proc.poll() is None, f"node exited early, see {log.name}"
    network = canopen.Network()
    network.connect(interface="socketcan", channel=IFACE)
    remote = network.add_node(NODE_ID, eds_path)
    remote.sdo.RESPONSE_TIMEOUT = 3.0  # the VM is slow; a lost response still fails in 3 s
    yield remote
    network.disconnect()
    proc.terminate()
    proc.wait(timeout=5)
    log.close()


def test_the_eds_says_the_mapping_records_are_const(node):
    """PDO-30: python canopen reads AccessType=const for every sub-index of the mapping records."""
    for index in MAPPINGS:
        record = node.object_dictionary[index]
        assert [var.access_type for var in record.values()] == ["const"] * len(record), f"{index:04X}h"


def test_the_pdo_api_reads_the_configured_mapping(node):
    check_default_io_module_mappings(node)


def test_remapping_is_refused_and_the_mapping_stays(node):
    """PDO-35's procedure on a fixed mapping: the PDO can be made not valid and valid again (its
    communication record stays rw), but the count and the entries answer 0601 0002h (write of a read-only
    object), so the configured mapping is what the PDO keeps."""
    cob = int.from_bytes(node.sdo.upload(0x1800, 1), "little")
    node.sdo.download(0x1800, 1, (cob | 0x8000_0000).to_bytes(4, "little"))  # step 1: not valid
    for sub, data in ((0, b"\x00"), (1, (0x6401_0110).to_bytes(4, "little"))):
        with pytest.raises(SdoAbortedError) as e:
            node.sdo.download(0x1A00, sub, data)
        assert abort_code(e) == 0x06010002, f"1A00h:{sub:02X}"
    node.sdo.download(0x1800, 1, cob.to_bytes(4, "little"))  # valid again
    assert node.sdo.upload(0x1A00, 0) == b"\x08"
    assert int.from_bytes(node.sdo.upload(0x1A00, 1), "little") == 0x6000_0108


def test_the_fixed_tpdo_and_rpdo_work(node):
    node.tpdo.read()
    node.rpdo.read()
    node.nmt.state = "OPERATIONAL"
    try:
        # The walking bit in 6000h moves once a second: TPDO1 follows each change.
        assert node.tpdo[1].wait_for_reception(3) is not None
        bits = [node.tpdo[1][f"Digital inputs.Digital inputs {i}"].raw for i in range(1, 9)]
        assert sorted(bits) == [0] * 7 + [1], bits
        for i in range(1, 9):
            node.rpdo[1][f"Digital outputs.Digital outputs {i}"].raw = 0x20 + i
        node.rpdo[1].transmit()
        wait_until(lambda: node.sdo[0x6200][8].raw == 0x28)
        assert [node.sdo[0x6200][i].raw for i in range(1, 9)] == [0x20 + i for i in range(1, 9)]
    finally:
        node.nmt.state = "PRE-OPERATIONAL"
