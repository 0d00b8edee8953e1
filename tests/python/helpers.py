"""What the tests of this directory that run python canopen as the master of one of our nodes share, whatever
the link (SocketCAN in test_interop.py and test_fixed_mapping.py, slcan to QEMU in test_qemu_slcan.py): waiting
for a condition, the abort code of an `SdoAbortedError`, the node's heartbeats, NMT commands that end in a
boot-up, the `fast_heartbeat` fixture and the checks more than one module runs on its node.

A test module imports what it uses; a fixture from here (`fast_heartbeat`) is imported by name into the module
whose tests request it, where pytest finds it.
"""

import threading
import time

import canopen
import pytest


def wait_until(predicate, timeout=3.0):
    """Polls `predicate` every 20 ms until it is true (True) or `timeout` seconds passed (its last value)."""
    end = time.time() + timeout
    while time.time() < end:
        if predicate():
            return True
        time.sleep(0.02)
    return predicate()


def abort_code(excinfo):
    """The SDO abort code of `pytest.raises(SdoAbortedError)`'s `excinfo`."""
    return excinfo.value.code


class Heartbeats:
    """Collects (time, state) of one node's error-control frames while the context is open: the frame's own
    timestamp (the kernel's on SocketCAN, the arrival time on slcan) and the NMT state without the toggle bit."""

    def __init__(self, network, node_id):
        self.network = network
        self.cob_id = 0x700 + node_id
        self.seen = []
        self.lock = threading.Lock()

    def __call__(self, can_id, data, timestamp):
        with self.lock:
            self.seen.append((timestamp, data[0] & 0x7F))

    def __enter__(self):
        self.network.subscribe(self.cob_id, self)
        return self

    def __exit__(self, *exc):
        # INTEROP: pass the callback, or python canopen's own heartbeat tracking is removed too.
        self.network.unsubscribe(self.cob_id, self)

    def wait_for(self, state, timeout=3.0):
        """True once a heartbeat with `state` (00h boot-up, 04h stopped, 05h operational, 7Fh pre-operational)
        was seen, False after `timeout` seconds."""

        def seen():
            with self.lock:
                return any(s == state for _, s in self.seen)

        return wait_until(seen, timeout)


def command_until_boot_up(network, node, state="RESET"):
    """Sends NMT `state` ("RESET" or "RESET COMMUNICATION") to `node` and waits up to 5 s for its boot-up.
    `node.nmt.wait_for_bootup()` would start listening when called, after the boot-up of a fast node already
    went by: this collects from before the command."""
    with Heartbeats(network, node.id) as hb:
        node.nmt.state = state
        assert hb.wait_for(0x00, 5), hb.seen


@pytest.fixture
def fast_heartbeat(node):
    """1017h at 100 ms for the test, 1000 ms (the nodes' default) after it. Needs the module's `node`."""
    node.sdo[0x1017].raw = 100
    yield
    node.sdo[0x1017].raw = 1000


def check_nmt_states_seen_in_heartbeats(node, network):
    """NMT start, stop and enter pre-operational, each seen in the node's heartbeat; stopped, the node's SDO
    server is silent (NMT-18), so python's client times out. Leaves the node pre-operational and its SDO
    client's response time-out as it found it."""
    with Heartbeats(network, node.id) as hb:
        node.nmt.state = "OPERATIONAL"
        assert hb.wait_for(0x05), hb.seen
        node.nmt.state = "STOPPED"
        assert hb.wait_for(0x04), hb.seen
        timeout = node.sdo.RESPONSE_TIMEOUT
        node.sdo.RESPONSE_TIMEOUT = 0.5
        try:
            with pytest.raises(canopen.SdoCommunicationError):
                node.sdo.upload(0x1000, 0)
        finally:
            node.sdo.RESPONSE_TIMEOUT = timeout
        node.nmt.state = "PRE-OPERATIONAL"
        assert hb.wait_for(0x7F), hb.seen


def check_default_io_module_mappings(node):
    """The example node's (examples/common/io_module.rs) default PDO mappings, read through python canopen's PDO
    API: TPDO1/RPDO1 the eight digital inputs/outputs, TPDO2/RPDO2 the four analogue ones."""
    node.tpdo.read()
    node.rpdo.read()
    assert [v.name for v in node.tpdo[1].map] == [f"Digital inputs.Digital inputs {i}" for i in range(1, 9)]
    assert [v.name for v in node.tpdo[2].map] == [f"Analog inputs.Analog inputs {i}" for i in range(1, 5)]
    assert [v.name for v in node.rpdo[1].map] == [f"Digital outputs.Digital outputs {i}" for i in range(1, 9)]
    assert [v.name for v in node.rpdo[2].map] == [f"Analog outputs.Analog outputs {i}" for i in range(1, 5)]
