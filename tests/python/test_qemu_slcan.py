"""python canopen 2.4.1 + python-can 4.6.1 as the master of the Cortex-M4 firmware (`examples/qemu-m4`) running
in QEMU's mps2-an386, over python-can's `slcan` interface: the firmware's UART0 is a TCP port of QEMU
(`socket://127.0.0.1:PORT`), the firmware plays the serial CAN adapter with the node on its bus.

Run by scripts/test-qemu.sh, which builds the image and the EDS, starts QEMU and passes QEMU_SLCAN (the
python-can channel) and QEMU_EDS; without them every test is skipped with the reason. One node on a serial
link: SDO expedited, segmented and block (with CRC) both ways, NMT and heartbeat, PDO mapping and SYNC, EMCY,
store/restore (RAM-backed, across NMT resets), and the serial link's own bad input.
"""

import os
import time

import pytest

SLCAN = os.environ.get("QEMU_SLCAN")
EDS = os.environ.get("QEMU_EDS")
NODE_ID = 5

if not SLCAN or not EDS:
    pytest.skip("QEMU_SLCAN/QEMU_EDS not set: run scripts/test-qemu.sh", allow_module_level=True)

import canopen  # noqa: E402
from canopen.sdo.exceptions import SdoAbortedError  # noqa: E402
from helpers import (  # noqa: E402
    Heartbeats,
    abort_code,
    check_nmt_states_seen_in_heartbeats,
    command_until_boot_up,
    fast_heartbeat,  # noqa: F401 (a fixture of the tests below)
    wait_until,
)


@pytest.fixture(scope="module")
def network():
    net = canopen.Network()
    # bitrate: python-can sends "C", "S5", "O" at connect; sleep_after_open: a TCP port needs no settling.
    net.connect(interface="slcan", channel=SLCAN, bitrate=250000, sleep_after_open=0)
    yield net
    net.disconnect()


@pytest.fixture(scope="module")
def node(network):
    n = network.add_node(NODE_ID, EDS)
    n.sdo.RESPONSE_TIMEOUT = 2.0
    # The firmware booted before we opened the channel (its boot-up went nowhere): its heartbeat says it is up.
    assert n.nmt.wait_for_heartbeat(5) == "PRE-OPERATIONAL"
    return n


@pytest.fixture
def operational(node):
    node.nmt.state = "OPERATIONAL"
    time.sleep(0.05)
    yield
    node.nmt.state = "PRE-OPERATIONAL"


# ---- identity and SDO, all three ways ----------------------------------------------------------------------

def test_identity_expedited_and_segmented_uploads(node):
    assert node.sdo.upload(0x1000, 0) == (0x00030191).to_bytes(4, "little")  # expedited
    assert node.sdo[0x1008].raw == "canopener QEMU AN386"  # 20 bytes: segmented
    assert node.sdo[0x1009].raw == "QEMU mps2-an386"
    assert node.sdo[0x1018][2].raw == 0x386


def test_expedited_download_limits_and_abort(node):
    node.sdo[0x2001].raw = -1000
    assert node.sdo[0x2001].raw == -1000
    with pytest.raises(SdoAbortedError) as e:
        node.sdo.download(0x2001, 0, (1001).to_bytes(2, "little"))
    assert abort_code(e) == 0x06090031  # value too high
    with pytest.raises(SdoAbortedError) as e:
        node.sdo.upload(0x2FFF, 0)
    assert abort_code(e) == 0x06020000  # object does not exist
    node.sdo[0x2001].raw = 0


@pytest.mark.parametrize("size", [0, 5, 7, 8, 200, 256])
def test_segmented_download_and_upload_byte_exact(node, size):
    data = bytes((i * 37 + size) & 0xFF for i in range(size))
    with node.sdo.open(0x2105, 0, "wb", size=size, block_transfer=False) as f:
        f.write(data)
    with node.sdo.open(0x2105, 0, "rb", block_transfer=False) as f:
        assert f.read() == data


@pytest.mark.parametrize("size", [1, 7, 8, 127, 256])
def test_block_download_and_upload_with_crc_byte_exact(node, size):
    """SDO-49: block transfers with the CRC, computed by python canopen and by the Cortex-M4 node."""
    data = bytes((i * 91 + 3 * size) & 0xFF for i in range(size))
    with node.sdo.open(0x2105, 0, "wb", size=size, block_transfer=True) as f:
        f.write(data)
    # request_crc_support: the client asks for the CRC (cc = 1); the node answers sc = cc (INTEROP).
    with node.sdo.open(0x2105, 0, "rb", block_transfer=True, request_crc_support=True) as f:
        assert f.read() == data
    with node.sdo.open(0x2105, 0, "rb", block_transfer=True, request_crc_support=False) as f:
        assert f.read() == data


def test_block_download_larger_than_the_object_is_refused(node):
    with pytest.raises(SdoAbortedError) as e:
        with node.sdo.open(0x2105, 0, "wb", size=257, block_transfer=True) as f:
            f.write(bytes(257))
    assert abort_code(e) in (0x06070012, 0x06070010)  # length too high / does not match


# ---- NMT and heartbeat ------------------------------------------------------------------------------------

def test_nmt_states_seen_in_heartbeats(node, network, fast_heartbeat):
    check_nmt_states_seen_in_heartbeats(node, network)


def test_heartbeat_period_follows_1017h(node, network):
    """HB-03: sent every 1017h ms, timed by the firmware's embassy-time driver in QEMU."""
    node.sdo[0x1017].raw = 200
    try:
        with Heartbeats(network, NODE_ID) as hb:
            assert wait_until(lambda: len(hb.seen) >= 7, 5), hb.seen
            stamps = [t for t, _ in hb.seen]
        gaps = sorted(b - a for a, b in zip(stamps, stamps[1:]))
        assert 0.15 <= gaps[len(gaps) // 2] <= 0.30, gaps
    finally:
        node.sdo[0x1017].raw = 1000


def test_reset_node_boots_up_and_restores_defaults(node, network):
    node.sdo[0x2001].raw = 77
    command_until_boot_up(network, node, "RESET")
    assert node.sdo[0x2001].raw == 0
    assert node.nmt.wait_for_heartbeat(3) == "PRE-OPERATIONAL"


# ---- PDO mapping and SYNC ----------------------------------------------------------------------------------

def test_default_mappings_through_the_pdo_api(node):
    node.tpdo.read()
    node.rpdo.read()
    assert [v.index for v in node.tpdo[1].map] == [0x6000]
    assert [(v.index, v.subindex) for v in node.tpdo[3].map] == [(0x6000, 1), (0x2101, 0), (0x2001, 0)]
    assert [v.index for v in node.rpdo[1].map] == [0x6200]
    assert node.tpdo[1].cob_id == 0x180 + NODE_ID and node.tpdo[1].trans_type == 254


def test_rpdo_output_loops_back_to_the_event_driven_tpdo(node, operational):
    """RPDO 1 writes 6200h:01; the firmware's loopback copies it to 6000h:01 and TPDO 1 (event-driven) sends it."""
    node.rpdo.read()
    node.tpdo.read()
    for value in (0x5A, 0x00, 0x01):
        got = []
        node.tpdo[1].add_callback(lambda m: got.append(m[0].raw))
        node.rpdo[1][0].raw = value
        node.rpdo[1].transmit()
        assert wait_until(lambda: value in got), (value, got)
        node.tpdo[1].callbacks.clear()
    assert node.sdo[0x6000][1].raw == 0x01


def test_pdo_remapped_and_sync_driven(node, network, operational):
    node.nmt.state = "PRE-OPERATIONAL"
    node.tpdo.read()
    tpdo = node.tpdo[2]
    tpdo.clear()
    assert tpdo.add_variable(0x6000, 1) is not None
    assert tpdo.add_variable(0x2101) is not None
    tpdo.trans_type = 2  # every second SYNC
    tpdo.event_timer = 0
    tpdo.enabled = True
    tpdo.save()
    assert int.from_bytes(node.sdo.upload(0x1A01, 0), "little") == 2
    assert int.from_bytes(node.sdo.upload(0x1A01, 1), "little") == 0x60000108
    assert int.from_bytes(node.sdo.upload(0x1A01, 2), "little") == 0x21010010
    with pytest.raises(SdoAbortedError) as e:  # 2001h is RPDO-mappable only
        node.sdo.download(0x1A01, 3, (0x20010010).to_bytes(4, "little"))
    assert abort_code(e) in (0x06040041, 0x06010000, 0x08000022)
    node.sdo[0x6200][1].raw = 0x33  # the loopback puts it on 6000h:01 within 10 ms
    node.nmt.state = "OPERATIONAL"
    time.sleep(0.1)
    frames = []
    node.tpdo[2].add_callback(lambda m: frames.append(m[0].raw))
    for _ in range(6):
        network.sync.transmit()
        time.sleep(0.05)
    assert wait_until(lambda: len(frames) >= 3, 2), frames
    time.sleep(0.3)
    assert frames == [0x33, 0x33, 0x33], frames
    node.tpdo[2].callbacks.clear()
    # Back to the defaults for the tests after this one.
    node.sdo[0x6200][1].raw = 0
    node.nmt.state = "RESET COMMUNICATION"
    assert node.nmt.wait_for_heartbeat(3) == "PRE-OPERATIONAL"


# ---- EMCY -----------------------------------------------------------------------------------------------

def test_short_rpdo_raises_emcy_8210h_and_fills_1003h(node, network, operational):
    """PDO-39: an RPDO shorter than its mapping is not applied and raises EMCY 8210h."""
    mark = len(node.emcy.log)  # INTEROP: read the log from a mark
    network.send_message(0x200 + NODE_ID, b"")  # RPDO 1 maps 8 bits: 0 bytes is a length error
    assert wait_until(lambda: any(e.code == 0x8210 for e in node.emcy.log[mark:])), node.emcy.log[mark:]
    assert node.sdo.upload(0x1003, 0)[0] >= 1
    assert int.from_bytes(node.sdo.upload(0x1003, 1), "little") & 0xFFFF == 0x8210
    node.sdo.download(0x1003, 0, b"\x00")  # clear the history
    assert node.sdo.upload(0x1003, 0)[0] == 0


# ---- store/restore in RAM ---------------------------------------------------------------------------------

def test_store_survives_reset_node_and_restore_defaults_brings_them_back(node, network):
    node.sdo[0x2001].raw = 321
    node.sdo[0x1017].raw = 500
    node.sdo.download(0x1010, 1, b"save")
    node.sdo[0x2001].raw = 5  # after the save: not stored
    command_until_boot_up(network, node, "RESET")
    assert node.sdo[0x2001].raw == 321
    assert node.sdo[0x1017].raw == 500
    node.sdo.download(0x1011, 1, b"load")
    assert node.sdo[0x2001].raw == 321  # nothing changes before the reset
    command_until_boot_up(network, node, "RESET")
    assert node.sdo[0x2001].raw == 0
    assert node.sdo[0x1017].raw == 1000


def test_save_with_a_wrong_signature_is_refused(node):
    with pytest.raises(SdoAbortedError) as e:
        node.sdo.download(0x1010, 1, b"SAVE")
    assert abort_code(e) == 0x08000020


# ---- the serial link itself -------------------------------------------------------------------------------

def test_bad_serial_input_is_skipped_and_counted(node, network):
    """Issue 44 item 5: garbage, an over-long line and a frame whose CR was lost are skipped and counted
    (2104h); the node keeps answering. Written straight to the serial port under python-can."""
    before = node.sdo[0x2104].raw
    port = network.bus.serialPortOrig
    port.write(b"hello world\r")  # garbage: one line
    port.write(b"t" + b"7" * 60 + b"\r")  # over-long: one line
    port.write(b"t00020105t00020105\r")  # a lost CR merges two NMT frames: one line, and neither acts
    port.write(b"T1FFFFFFF0\r")  # a 29-bit frame: not CANopen, ignored and counted
    assert wait_until(lambda: node.sdo[0x2104].raw >= before + 4, 3), node.sdo[0x2104].raw
    assert node.sdo[0x2104].raw == before + 4
    assert node.nmt.wait_for_heartbeat(3) == "PRE-OPERATIONAL"  # the merged "start node" did nothing


def test_stack_high_water_mark_is_reported(node, network):
    """2103h: the stack's high-water mark (painted at boot): sub 01h since boot, sub 02h since the node runs,
    sub 03h in the steady state (from one second after start), after the SDO, PDO and EMCY traffic of the
    tests before this one. scripts/test-qemu.sh prints the three."""
    node.nmt.state = "OPERATIONAL"
    for _ in range(5):
        network.sync.transmit()  # a burst of 4 TPDOs, the deepest the transmit path goes
    node.nmt.state = "PRE-OPERATIONAL"
    time.sleep(1.1)  # refreshed every second
    boot, running, steady = (node.sdo[0x2103][i].raw for i in (1, 2, 3))
    assert 0 < steady <= running <= boot < 128 * 1024, (boot, running, steady)
    print(f"\nstack high-water mark: {boot} bytes since boot, {running} bytes since the node runs, "
          f"{steady} bytes in the steady state")
