"""python canopen's LSS master against `examples/node --node-id 255 --store FILE` over vcan (run by scripts/test-lss.sh inside
scripts/vcan-run.sh): fastscan finds the node started without a node-ID, configure_node_id(0x22),
store_configuration, switch to waiting → the node boots as 0x22 and answers SDO; restarted, it boots as
0x22 from its store (FILE.lss.a), over the --node-id argument."""

import os
import pathlib
import subprocess
import threading
import time

import canopen
import pytest
from canopen.lss import LssError

ROOT = pathlib.Path(__file__).resolve().parents[2]
NODE_BIN = os.environ.get("NODE_EXAMPLE_BIN", str(ROOT / "target/debug/examples/node"))
IFACE = os.environ.get("CAN_IFACE", "vcan0")
# The LSS address of the example node (examples/common/io_module.rs CONFIG, serial from --serial).
VENDOR, PRODUCT, REVISION, SERIAL = 0x0, 0x401, 0x0001_0000, 0x8000_0001
NEW_ID = 0x22


class Recorder:
    """Collects frames on one COB-ID."""

    def __init__(self, network, cob_id):
        self.frames = []
        self.event = threading.Event()
        network.subscribe(cob_id, self._on)

    def _on(self, cob_id, data, timestamp):
        self.frames.append(bytes(data))
        self.event.set()

    def wait(self, timeout=3.0):
        assert self.event.wait(timeout), "no frame in time"
        return self.frames


@pytest.fixture
def network():
    net = canopen.Network()
    net.connect(interface="socketcan", channel=IFACE)
    yield net
    net.disconnect()


def start_node(store, log_path):
    log = open(log_path, "a")
    proc = subprocess.Popen(
        [NODE_BIN, "--iface", IFACE, "--store", str(store), "--serial", hex(SERIAL), "--node-id", "255",
         "--heartbeat", "0", "--quiet"],
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    time.sleep(0.5)
    assert proc.poll() is None, pathlib.Path(log_path).read_text()
    return proc


def stop_node(proc):
    proc.terminate()
    proc.wait(timeout=5)


# LSS-01, LSS-03, LSS-05, LSS-06, LSS-09, LSS-10, LSS-13, LSS-14, LSS-15 against python canopen's master.
def test_fastscan_configure_store_and_reboot(network, tmp_path):
    store = tmp_path / "state"
    log = tmp_path / "lss-node.log"
    boot = Recorder(network, 0x700 + NEW_ID)
    lss_answers = Recorder(network, 0x7E4)
    proc = start_node(store, log)
    try:
        # Without a node-ID the node is silent and ignores NMT.
        network.nmt.send_command(0x01)
        time.sleep(0.3)
        assert boot.frames == [] and lss_answers.frames == []
        # LSS waiting: configuration services are not answered.
        with pytest.raises(LssError):
            network.lss.inquire_node_id()

        network.lss.send_switch_state_global(network.lss.WAITING_STATE)
        found, lss_id = network.lss.fast_scan()
        assert found, pathlib.Path(log).read_text()
        assert lss_id == [VENDOR, PRODUCT, REVISION, SERIAL]
        # Fastscan left it in LSS configuration.
        assert network.lss.inquire_node_id() == 0xFF
        assert network.lss.inquire_lss_address(canopen.lss.CS_INQUIRE_SERIAL_NUMBER) == SERIAL

        network.lss.configure_node_id(NEW_ID)
        network.lss.store_configuration()
        assert (tmp_path / "state.lss.a").exists(), pathlib.Path(log).read_text()
        # The new node-ID is pending until the node leaves LSS configuration.
        assert network.lss.inquire_node_id() == 0xFF
        assert boot.frames == []

        network.lss.send_switch_state_global(network.lss.WAITING_STATE)
        assert boot.wait() == [b"\x00"], pathlib.Path(log).read_text()

        node = network.add_node(NEW_ID, canopen.ObjectDictionary())
        assert int.from_bytes(node.sdo.upload(0x1018, 4), "little") == SERIAL
        assert int.from_bytes(node.sdo.upload(0x1018, 2), "little") == PRODUCT
        # Configured now: fastscan no longer finds it.
        assert network.lss.fast_scan() == (False, None)
    finally:
        stop_node(proc)

    # Power cycle: the stored node-ID is used at once.
    boot.frames.clear()
    boot.event.clear()
    proc = start_node(store, log)
    try:
        assert boot.wait() == [b"\x00"], pathlib.Path(log).read_text()
        node = network.nodes[NEW_ID]
        assert int.from_bytes(node.sdo.upload(0x1018, 4), "little") == SERIAL
    finally:
        stop_node(proc)


# LSS-09 (issue 16 item 1): the stored node-ID wins over --node-id (the factory default, CiA 305) at the
# next start.
def test_node_example_stores_lss_config_and_boots_with_it_over_node_id(network, tmp_path):
    store = tmp_path / "state"
    log = tmp_path / "node.log"
    boot = Recorder(network, 0x700 + NEW_ID)

    def start(node_id):
        out = open(log, "a")
        proc = subprocess.Popen(
            [NODE_BIN, "--iface", IFACE, "--store", str(store), "--node-id", str(node_id),
             "--heartbeat", "0", "--quiet"],
            stdout=out,
            stderr=subprocess.STDOUT,
        )
        time.sleep(0.5)
        assert proc.poll() is None, log.read_text()
        return proc

    proc = start(255)
    try:
        network.lss.send_switch_state_global(network.lss.CONFIGURATION_STATE)
        assert network.lss.inquire_node_id() == 0xFF
        network.lss.configure_node_id(NEW_ID)
        network.lss.store_configuration()
        assert (tmp_path / "state.lss.a").exists(), log.read_text()
        network.lss.send_switch_state_global(network.lss.WAITING_STATE)
        assert boot.wait() == [b"\x00"], log.read_text()
    finally:
        stop_node(proc)

    boot.frames.clear()
    boot.event.clear()
    proc = start(5)
    try:
        assert boot.wait() == [b"\x00"], log.read_text()
        node = network.add_node(NEW_ID, canopen.ObjectDictionary())
        assert int.from_bytes(node.sdo.upload(0x1018, 2), "little") == 0x401
    finally:
        stop_node(proc)
    assert "node-ID 34 from the LSS store" in log.read_text()
