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
    0x1008: ("Manufacturer device name", dt.VISIBLE_STRING, "const", "canopen-rs all types", False, None, None),
    0x1009: ("Manufacturer hardware version", dt.VISIBLE_STRING, "const", "HW 1.0", False, None, None),
    0x100A: ("Manufacturer software version", dt.VISIBLE_STRING, "const", "SW 0.1", False, None, None),
    0x100C: ("Guard time", dt.UNSIGNED16, "rw", 0, False, None, None),
    0x100D: ("Life time factor", dt.UNSIGNED8, "rw", 0, False, None, None),
    0x1017: ("Producer heartbeat time", dt.UNSIGNED16, "rw", 1000, False, None, None),
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


def test_every_object_is_present(od):
    expected = set(VARS) | set(COMPOUND)
    assert {obj.index for obj in od.values()} == expected


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
    assert info.vendor_name == "canopen-rs"
    assert info.product_name == "All types"
    assert info.simple_boot_up_slave is True
    assert info.nr_of_RXPDO == 0 and info.nr_of_TXPDO == 0
    assert info.allowed_baudrates == {125000, 250000, 500000, 1000000}


def test_values_encode_like_the_node(od):
    # python canopen encodes with the same layout the node reads (DT-01, DT-05, DT-06).
    assert od[0x2011].encode_raw(266) == bytes([0x0A, 0x01])
    assert od[0x2002].encode_raw(-266) == bytes([0xF6, 0xFE])
    assert od[0x2003].encode_raw(-266) == bytes([0xF6, 0xFE, 0xFF])
    assert od[0x2018].encode_raw(6.25) == bytes([0x00, 0x00, 0xC8, 0x40])
