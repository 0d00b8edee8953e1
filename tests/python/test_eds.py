"""The EDS written by `cargo run --example write_eds` loads in python canopen with every object, data type,
access type, PDO mapping, default and limit matching the Rust definition (tests/common/all_types.rs plus
the core's communication profile)."""

import os
import subprocess
import pathlib

import canopen
import pytest
from canopen.objectdictionary import ODArray, ODRecord, ODVariable, datatypes as dt

ROOT = pathlib.Path(__file__).resolve().parents[2]

# index: (name, data type, access, default, pdo mappable, low, high)
VARS = {
    0x1000: ("Device type", dt.UNSIGNED32, "ro", 0x00010191, False, None, None),
    0x1001: ("Error register", dt.UNSIGNED8, "ro", 0, True, None, None),
    0x1008: ("Manufacturer device name", dt.VISIBLE_STRING, "const", "canopener all types", False, None, None),
    0x1009: ("Manufacturer hardware version", dt.VISIBLE_STRING, "const", "HW 1.0", False, None, None),
    0x100A: ("Manufacturer software version", dt.VISIBLE_STRING, "const", "SW 0.1", False, None, None),
    0x100C: ("Guard time", dt.UNSIGNED16, "rw", 0, False, None, None),
    0x100D: ("Life time factor", dt.UNSIGNED8, "rw", 0, False, None, None),
    0x1017: ("Producer heartbeat time", dt.UNSIGNED16, "rw", 1000, False, None, None),
    0x1005: ("COB-ID SYNC message", dt.UNSIGNED32, "rw", 0x80, False, None, None),
    0x1006: ("Communication cycle period", dt.UNSIGNED32, "rw", 0, False, None, None),
    0x1007: ("Synchronous window length", dt.UNSIGNED32, "rw", 0, False, None, None),
    0x1012: ("COB-ID time stamp object", dt.UNSIGNED32, "rw", 0x80000100, False, None, None),
    0x1014: ("COB-ID EMCY", dt.UNSIGNED32, "rw", 0x85, False, None, None),  # $NODEID+0x80, node 5
    0x1015: ("Inhibit time EMCY", dt.UNSIGNED16, "rw", 0, False, None, None),
    0x1019: ("Synchronous counter overflow value", dt.UNSIGNED8, "rw", 0, False, None, None),
    0x1F80: ("NMT startup", dt.UNSIGNED32, "rw", 4, False, None, None),
    # The optional objects of canopen-core's default features (profile::optional).
    0x1002: ("Manufacturer status register", dt.UNSIGNED32, "ro", 0, True, None, None),
    0x1013: ("High resolution time stamp", dt.UNSIGNED32, "rw", 0, True, None, None),
    0x2000: ("Boolean", dt.BOOLEAN, "rw", 1, True, None, None),
    0x2001: ("Integer8", dt.INTEGER8, "rw", -1, True, -100, 100),
    0x2002: ("Integer16", dt.INTEGER16, "rww", 0, True, -1000, 1000),
    0x2003: ("Integer24", dt.INTEGER24, "rwr", -5, True, None, None),
    0x2004: ("Integer32", dt.INTEGER32, "rw", -70000, True, -70000, None),
    0x2005: ("Integer40", dt.INTEGER40, "rw", -1, False, None, None),
    0x2006: ("Integer48", dt.INTEGER48, "rw", 0, False, None, None),
    0x2007: ("Integer56", dt.INTEGER56, "rw", 0, True, None, None),
    0x2008: ("Integer64", dt.INTEGER64, "rw", -9000000000, True, None, None),
    0x2010: ("Unsigned8", dt.UNSIGNED8, "rw", 200, True, None, 200),
    0x2011: ("Unsigned16", dt.UNSIGNED16, "rw", 10, True, 10, 60000),
    0x2012: ("Unsigned24", dt.UNSIGNED24, "rw", 0x123456, False, None, None),
    0x2013: ("Unsigned32", dt.UNSIGNED32, "rw", 0xDEADBEEF, True, None, None),
    0x2014: ("Unsigned40", dt.UNSIGNED40, "rw", 0, False, None, None),
    0x2015: ("Unsigned48", dt.UNSIGNED48, "rw", 0, False, None, None),
    0x2016: ("Unsigned56", dt.UNSIGNED56, "rw", 0, False, None, None),
    0x2017: ("Unsigned64", dt.UNSIGNED64, "rw", 2**64 - 1, True, None, None),
    0x2018: ("Real32", dt.REAL32, "rw", 1.25, True, None, None),  # float limits: checked separately
    0x2019: ("Real64", dt.REAL64, "rw", -0.5, False, None, None),
    0x2020: ("Visible string", dt.VISIBLE_STRING, "rw", "hello", False, None, None),
    0x2021: ("Octet string", dt.OCTET_STRING, "rw", b"AB", False, None, None),
    0x2022: ("Unicode string", dt.UNICODE_STRING, "rw", "hi", False, None, None),
    0x2023: ("Time of day", dt.TIME_OF_DAY, "rw", 0, True, None, None),
    0x2024: ("Time difference", dt.TIME_DIFFERENCE, "rw", 0, False, None, None),
    0x2025: ("Firmware image", dt.DOMAIN, "rw", None, False, None, None),
    0x2030: ("Write only", dt.UNSIGNED32, "wo", 0, True, None, None),
    0x2031: ("Read only", dt.UNSIGNED16, "ro", 0, True, None, None),
    0x2032: ("Constant", dt.UNSIGNED8, "const", 7, False, None, None),
}

# index: (class, name, {sub: (name, data type, access, default, pdo, low, high)})
COMPOUND = {
    0x1016: (ODArray, "Consumer heartbeat time", {
        **{s: (f"Consumer heartbeat time {s}", dt.UNSIGNED32, "rw", 0, False, None, None) for s in range(1, 5)},
    }, 4),
    0x1018: (ODRecord, "Identity object", {
        1: ("Vendor-ID", dt.UNSIGNED32, "ro", 0x2B6, False, None, None),
        2: ("Product code", dt.UNSIGNED32, "ro", 0x1234, False, None, None),
        3: ("Revision number", dt.UNSIGNED32, "ro", 0x00010002, False, None, None),
        4: ("Serial number", dt.UNSIGNED32, "ro", 42, False, None, None),
    }, 4),
    0x1010: (ODArray, "Store parameters", {
        1: ("Save all parameters", dt.UNSIGNED32, "rw", 0, False, None, None),
        2: ("Save communication parameters", dt.UNSIGNED32, "rw", 0, False, None, None),
        3: ("Save application parameters", dt.UNSIGNED32, "rw", 0, False, None, None),
    }, 3),
    0x1011: (ODArray, "Restore default parameters", {
        1: ("Restore all default parameters", dt.UNSIGNED32, "rw", 0, False, None, None),
        2: ("Restore communication default parameters", dt.UNSIGNED32, "rw", 0, False, None, None),
        3: ("Restore application default parameters", dt.UNSIGNED32, "rw", 0, False, None, None),
    }, 3),
    0x1020: (ODArray, "Verify configuration", {
        1: ("Configuration date", dt.UNSIGNED32, "rw", 0, False, None, None),
        2: ("Configuration time", dt.UNSIGNED32, "rw", 0, False, None, None),
    }, 2),
    0x1028: (ODArray, "Emergency consumer object", {
        s: (f"Emergency consumer {s}", dt.UNSIGNED32, "rw", 0x80 + s, False, None, None) for s in range(1, 128)
    }, 127),
    # The MPDO lists of canopen-core's default feature `mpdo` (profile::optional, MPDO-03).
    0x1FA0: (ODArray, "Object scanner list", {
        s: (f"Scanned object {s}", dt.UNSIGNED32, "rw", 0, False, None, None) for s in range(1, 17)
    }, 16),
    0x1FD0: (ODArray, "Object dispatching list", {
        s: (f"Dispatched object {s}", dt.UNSIGNED64, "rw", 0, False, None, None) for s in range(1, 17)
    }, 16),
    0x1029: (ODArray, "Error behaviour", {1: ("Communication error", dt.UNSIGNED8, "rw", 0, False, None, None)}, 1),
    **{0x1400 + k: (ODRecord, "RPDO communication parameter", {
        1: ("COB-ID used by RPDO", dt.UNSIGNED32, "rw", (0x200 + 0x100 * k + 5) | (0 if k == 0 else 0x80000000), False, None, None),
        2: ("Transmission type", dt.UNSIGNED8, "rw", 254, False, None, None),
        3: ("Inhibit time", dt.UNSIGNED16, "rw", 0, False, None, None),
        5: ("Event timer", dt.UNSIGNED16, "rw", 0, False, None, None),
    }, 5) for k in range(4)},
    **{0x1800 + k: (ODRecord, "TPDO communication parameter", {
        1: ("COB-ID used by TPDO", dt.UNSIGNED32, "rw", (0x180 + 0x100 * k + 5) | (0 if k == 0 else 0x80000000), False, None, None),
        2: ("Transmission type", dt.UNSIGNED8, "rw", 254, False, None, None),
        3: ("Inhibit time", dt.UNSIGNED16, "rw", 0, False, None, None),
        5: ("Event timer", dt.UNSIGNED16, "rw", 0, False, None, None),
        6: ("SYNC start value", dt.UNSIGNED8, "rw", 0, False, None, None),
    }, 6) for k in range(4)},
    # The SDO parameter records of a node with two additional servers and one client record (CiA 301
    # §7.5.2.33/§7.5.2.34, SDO-53, SDO-54, SDO-56): 1200h as the default server answers, 1201h+ and 1280h
    # invalid (8000_0000h) at power-on, sub 03h the peer's node-ID (0 until written).
    0x1200: (ODRecord, "SDO server parameter", {
        1: ("COB-ID client to server (rx)", dt.UNSIGNED32, "const", 0x605, False, None, None),  # $NODEID+0x600
        2: ("COB-ID server to client (tx)", dt.UNSIGNED32, "ro", 0x585, False, None, None),
    }, 2),
    **{0x1201 + k: (ODRecord, "SDO server parameter", {
        1: ("COB-ID client to server (rx)", dt.UNSIGNED32, "rw", 0x80000000, False, None, None),
        2: ("COB-ID server to client (tx)", dt.UNSIGNED32, "rw", 0x80000000, False, None, None),
        3: ("Node-ID of the SDO client", dt.UNSIGNED8, "rw", 0, False, None, None),
    }, 3) for k in range(2)},
    0x1280: (ODRecord, "SDO client parameter", {
        1: ("COB-ID client to server (tx)", dt.UNSIGNED32, "rw", 0x80000000, False, None, None),
        2: ("COB-ID server to client (rx)", dt.UNSIGNED32, "rw", 0x80000000, False, None, None),
        3: ("Node-ID of the SDO server", dt.UNSIGNED8, "rw", 0, False, None, None),
    }, 3),
    0x2100: (ODRecord, "PID controller", {
        1: ("Kp", dt.REAL32, "rw", 1.0, True, None, None),
        2: ("Ki", dt.REAL32, "rw", 0, False, 0, 10),  # limits written "0" and "10": python reads them
        3: ("Mode", dt.UNSIGNED8, "rw", 1, False, 1, 3),
        4: ("Label", dt.VISIBLE_STRING, "ro", "", False, None, None),
    }, 4),
    0x6000: (ODArray, "Digital inputs", {
        s: (f"Digital inputs {s}", dt.UNSIGNED8, "ro", 0, True, None, None) for s in range(1, 9)
    }, 8),
    0x6200: (ODArray, "Outputs", {
        s: (f"Outputs {s}", dt.INTEGER16, "rw", 0, True, -10, 10) for s in range(1, 5)
    }, 4),
}


@pytest.fixture(scope="module")
def eds_path(tmp_path_factory):
    eds = os.environ.get("CANOPEN_EDS")
    if not eds:
        eds = str(tmp_path_factory.mktemp("eds") / "all_types.eds")
        subprocess.run(
            ["cargo", "run", "--quiet", "--example", "write_eds", "--", eds], cwd=ROOT, check=True
        )
    return eds


@pytest.fixture(scope="module")
def od(eds_path):
    return canopen.import_od(eds_path, node_id=5)


def check_var(var, expected):
    name, data_type, access, default, pdo, low, high = expected
    assert isinstance(var, ODVariable)
    assert var.name == name
    assert var.data_type == data_type
    assert var.access_type == access
    assert var.pdo_mappable == pdo, f"{name}: PDOMapping"
    if default is not None:
        assert var.default == default, f"{name}: default {var.default!r}"
    assert var.min == low, f"{name}: LowLimit"
    assert var.max == high, f"{name}: HighLimit"


# Objects whose sub 00h is writable (checked in test_rw_count_objects).
RW_COUNT = {0x1003, *range(0x1600, 0x1604), *range(0x1A00, 0x1A04)}


def test_every_object_is_present(od):
    expected = set(VARS) | set(COMPOUND) | RW_COUNT
    assert {obj.index for obj in od.values()} == expected


def test_rw_count_objects(od):
    hist = od[0x1003]
    assert isinstance(hist, ODArray) and hist.name == "Pre-defined error field"
    assert hist[0].access_type == "rw" and hist[0].data_type == dt.UNSIGNED8
    assert sorted(hist.subindices) == list(range(0, 9))
    assert hist[1].access_type == "ro" and hist[1].name == "Standard error field 1"
    for base, first in ((0x1600, [0x20020010]), (0x1A00, [0x20100008, 0x20110010])):
        for k in range(4):
            m = od[base + k]
            assert isinstance(m, ODRecord)
            assert m[0].access_type == "rw"
            assert m[0].default == (len(first) if k == 0 else 0)
            assert sorted(m.subindices) == list(range(0, 9))
            for s in range(1, 9):
                assert m[s].data_type == dt.UNSIGNED32
                assert m[s].default == (first[s - 1] if k == 0 and s <= len(first) else 0)


@pytest.mark.parametrize("index", sorted(VARS))
def test_variables(od, index):
    check_var(od[index], VARS[index])


@pytest.mark.parametrize("index", sorted(COMPOUND))
def test_arrays_and_records(od, index):
    cls, name, subs, highest = COMPOUND[index]
    obj = od[index]
    assert isinstance(obj, cls)
    assert obj.name == name
    sub0 = obj[0]
    assert sub0.data_type == dt.UNSIGNED8
    assert sub0.access_type == "const"
    assert sub0.default == highest
    assert sorted(obj.subindices) == [0, *sorted(subs)]
    for sub, expected in subs.items():
        check_var(obj[sub], expected)


def test_float_limits(od, eds_path):
    # python canopen parses LowLimit/HighLimit with int() only, so non-integral REAL limits are not loaded
    # (var.min stays None); check the raw text the node wrote instead.
    import configparser

    ini = configparser.RawConfigParser()
    ini.optionxform = str
    ini.read(eds_path)
    assert float(ini["2018"]["LowLimit"]) == -1.5
    assert float(ini["2018"]["HighLimit"]) == 2.5
    assert od[0x2018].default == 1.25
    # No empty numeric field anywhere (INTEROP: import_od raises on some).
    textual = {"ParameterName", "Description", "VendorName", "ProductName", "OrderCode", "CreatedBy",
               "ModifiedBy", "FileName", "DefaultValue"}
    for section in ini.sections():
        for key, value in ini[section].items():
            assert value != "" or key in textual, f"[{section}] {key} is empty"


def test_device_info(od):
    info = od.device_information
    assert info.vendor_number == 0x2B6
    assert info.product_number == 0x1234
    assert info.revision_number == 0x00010002
    assert info.vendor_name == "canopener"
    assert info.product_name == "All types"
    assert info.simple_boot_up_slave is True
    assert info.nr_of_RXPDO == 4 and info.nr_of_TXPDO == 4
    assert info.allowed_baudrates == {125000, 250000, 500000, 1000000}


def test_values_encode_like_the_node(od):
    # python canopen encodes with the same layout the node reads (DT-01, DT-05, DT-06).
    assert od[0x2011].encode_raw(266) == bytes([0x0A, 0x01])
    assert od[0x2002].encode_raw(-266) == bytes([0xF6, 0xFE])
    assert od[0x2003].encode_raw(-266) == bytes([0xF6, 0xFE, 0xFF])
    assert od[0x2018].encode_raw(6.25) == bytes([0x00, 0x00, 0xC8, 0x40])
