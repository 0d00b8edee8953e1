#!/usr/bin/env python3
"""Unit tests of scripts/conformance.py's parsing (run by .ci/run: python3 scripts/test_conformance.py)."""

import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import conformance as c  # noqa: E402

PREFIXES = {"SDO", "PDO", "NMT", "STORE", "HB", "COB", "DT", "LSS", "OD"}

RUST = r'''
//! Module docs cite SDO-01: not a test.

// A section header citing NMT-01, then a blank line: not attributed.

/// Doc comment: SDO-02.
// Plain comment: PDO-38/39.
#[test]
fn first() {
    let s = "a brace { in a string, and SDO-03 in it";
    let c = '{';
    let r = r#"}" NMT-02 "#;
    /* nested /* block */ comment with } */
    assert_eq!(s.len(), 1); // STORE-08..10
}

fn helper() {
    // HB-01 in a helper: not a test.
}

#[test]
#[ignore = "slow"]
fn second_sdo_12_24<'a>(_x: &'a str) where 'a: 'a {
    helper();
}

/// Does not cite, and neither does its body.
#[test]
fn third() {}

pub fn not_a_test_sdo_49() {}

mod tests {
    use super::*;

    /// COB-05 – COB-07, then a range with the prefix repeated: DT-01..DT-03.
    #[test]
    fn inner() {
        let _ = || { OD-07 };
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4, ..ProptestConfig::default() })]

    /// LSS-14.
    #[test]
    fn prop(x in 0u8..4, y in prop::collection::vec(any::<u8>(), 0..3)) {
        prop_assert!(x < 4 || y.is_empty());
    }
}

/// An item with a doctest:
///
/// ```
/// assert_eq!(1, 1); // SDO-04
/// ```
///
/// ```ignore
/// SDO-05 in a block rustdoc does not run
/// ```
///
/// Prose citing SDO-06 is not a test.
pub struct Documented;
'''

PYTHON = '''
"""Module docstring citing SDO-01: not a test."""
import pytest


def helper():
    """SDO-02 in a helper."""


# SDO-03 above the test.
@pytest.mark.parametrize("x", [1])
def test_one(x):
    """Docstring: NMT-05."""
    assert x  # HB-02


class TestGroup:
    def test_method(self):
        pass  # PDO-01

    def not_test(self):
        pass  # PDO-02
'''


class CitedIds(unittest.TestCase):
    def test_forms(self):
        got = c.cited_ids("SDO-01, PDO-38/39 and STORE-08..10, HB-01–03, COB-14..COB-16; X-01 SDO-5x", PREFIXES)
        self.assertEqual(
            got,
            {"SDO-01", "PDO-38", "PDO-39", "STORE-08", "STORE-09", "STORE-10", "HB-01", "HB-02", "HB-03",
             "COB-14", "COB-15", "COB-16"},
        )

    def test_unknown_prefix_and_embedded(self):
        self.assertEqual(c.cited_ids("ENC-01 X-SDO-03 MYSDO-01 SDO-01a", PREFIXES), set())

    def test_name_ids(self):
        self.assertEqual(c.name_ids("crc_check_value_sdo_49", PREFIXES), {"SDO-49"})
        self.assertEqual(c.name_ids("expedited_command_bytes_sdo_12_24", PREFIXES), {"SDO-12", "SDO-24"})
        self.assertEqual(c.name_ids("sdo_1_segment", PREFIXES), set())
        self.assertEqual(c.name_ids("nmt_reset", PREFIXES), set())


class RustParsing(unittest.TestCase):
    def setUp(self):
        self.tests = {t.name: c.cited_ids(t.text, PREFIXES) | c.name_ids(t.name, PREFIXES)
                      for t in c.rust_tests("x.rs", RUST) + c.rust_doctests("x.rs", RUST)}

    def test_only_test_functions(self):
        self.assertEqual(set(self.tests), {"first", "second_sdo_12_24", "third", "inner", "prop", "Documented (doctest)"})

    def test_preceding_comments_and_body(self):
        self.assertEqual(
            self.tests["first"],
            {"SDO-02", "PDO-38", "PDO-39", "SDO-03", "NMT-02", "STORE-08", "STORE-09", "STORE-10"},
        )

    def test_name_and_attributes(self):
        self.assertEqual(self.tests["second_sdo_12_24"], {"SDO-12", "SDO-24"})
        self.assertEqual(self.tests["third"], set())

    def test_nested_module_and_macro(self):
        self.assertEqual(self.tests["inner"], {"COB-05", "COB-06", "COB-07", "DT-01", "DT-02", "DT-03", "OD-07"})
        self.assertEqual(self.tests["prop"], {"LSS-14"})

    def test_doctest_code_only(self):
        self.assertEqual(self.tests["Documented (doctest)"], {"SDO-04"})

    def test_mask_keeps_length_and_lines(self):
        mask = c.rust_code_mask(RUST)
        self.assertEqual(len(mask), len(RUST))
        self.assertEqual(mask.count("\n"), RUST.count("\n"))
        self.assertEqual(mask.count("{"), mask.count("}"))


class IgnoredAndDoctestScope(unittest.TestCase):
    SRC = (
        '#[test]\n#[ignore = "needs SocketCAN (vcan0)"]\nfn on_vcan() { SDO-01 }\n'
        '#[ignore = "fails, see issue 9"]\n#[test]\nfn broken() { SDO-02 }\n'
        "#[test]\n#[ignore]\nfn bare() {}\n#[test]\nfn plain() {}\n"
    )

    def test_ignored_reasons(self):
        tests = {t.name: t for t in c.rust_tests("x.rs", self.SRC)}
        self.assertEqual({n: t.ignored for n, t in tests.items()},
                         {"on_vcan": "needs SocketCAN (vcan0)", "broken": "fails, see issue 9", "bare": "", "plain": None})
        self.assertEqual({n for n, t in tests.items() if t.counts}, {"on_vcan", "plain"})

    def test_doctest_scope(self):
        for rel, runs in [("canopen-core/src/od/mod.rs", True), ("src/lib.rs", True), ("tests/lss.rs", False),
                          ("examples/node.rs", False), ("canopen-socketcan/src/bin/x.rs", False),
                          ("canopen-core/tests/a.rs", False), ("x/src/main.rs", False)]:
            self.assertEqual(c.runs_doctests(rel), runs, rel)


class Scope(unittest.TestCase):
    def test_repository_files(self):
        files = c.source_files(c.ROOT)
        self.assertIn("tests/lss.rs", files)
        self.assertIn("tests/python/test_lss.py", files)
        self.assertNotIn("scripts/test_conformance.py", files)
        self.assertFalse([f for f in files if f.startswith(("fuzz/", "examples/firmware/", "ci/")) or "/target/" in f])


class PythonParsing(unittest.TestCase):
    def test_functions_and_methods(self):
        tests = {t.name: c.cited_ids(t.text, PREFIXES) for t in c.python_tests("t.py", PYTHON)}
        self.assertEqual(tests, {"test_one": {"SDO-03", "NMT-05", "HB-02"}, "test_method": {"PDO-01"}})


class Requirements(unittest.TestCase):
    def test_parse_and_reject(self):
        text = "# comment\nid\tlevel\tclause\tstatement\nSDO-01\tM\tCiA 301 §7.3.3\tServer on 600h.\n"
        (r,) = c.parse_requirements(text)
        self.assertEqual((r.id, r.level, r.group, r.standard), ("SDO-01", "M", "SDO", "CiA 301"))
        for bad in ("SDO-01\tX\tc\ts\n", "SDO-01\tM\tc\n", "SDO-01\tM\tc\ts\nSDO-01\tM\tc\ts\n"):
            with self.assertRaises(ValueError):
                c.parse_requirements("id\tlevel\tclause\tstatement\n" + bad)


class EndToEnd(unittest.TestCase):
    def test_generate_counts_reasons_and_check(self):
        with tempfile.TemporaryDirectory() as root:
            os.makedirs(os.path.join(root, "docs"))
            os.makedirs(os.path.join(root, "tests", "python"))
            os.makedirs(os.path.join(root, "target", "debug"))
            with open(os.path.join(root, "docs", "requirements.tsv"), "w") as f:
                f.write("id\tlevel\tclause\tstatement\n")
                f.write("SDO-01\tM\tCiA 301 §7.3.3\tServer on 600h.\n")
                f.write("SDO-02\tM\tCiA 301 §7.2.4\tEight bytes.\n")
                f.write("SDO-03\tM\tCiA 301 §7.2.4\tCommand byte.\n")
                f.write("PDO-01\tO\tCiA 301 §7.2.2\tPDOs.\n")
                f.write("LSS-01\tC\tCiA 305 «x»\tLSS.\n")
            with open(os.path.join(root, "tests", "a.rs"), "w") as f:
                f.write("/// SDO-01\n#[test]\nfn a() {}\n")
            os.makedirs(os.path.join(root, "fuzz", "src"))
            with open(os.path.join(root, "Cargo.toml"), "w") as f:
                f.write('[workspace]\nmembers = ["core"]\nexclude = ["fuzz"]\n')
            with open(os.path.join(root, "fuzz", "src", "lib.rs"), "w") as f:
                f.write("#[test]\nfn f() { SDO-03 }\n")  # an excluded workspace: never scanned
            with open(os.path.join(root, "target", "debug", "b.rs"), "w") as f:
                f.write("#[test]\nfn b() { SDO-02 }\n")  # build output: never scanned
            with open(os.path.join(root, "tests", "python", "test_c.py"), "w") as f:
                f.write("def test_c():\n    pass  # LSS-01\n")
            with open(os.path.join(root, "README.md"), "w") as f:
                f.write("### M items that are not done\n\n| ID | What | Why |\n|---|---|---|\n"
                        "| SDO-02 (partly), PDO-01 | Eight bytes missing | Hardware |\n\n## Next\n| SDO-03 | x | y |\n")
            doc = c.generate(root)
        self.assertIn("| M (mandatory) | 1 / 3 | 0 / 0 | 0 / 0 | 1 / 3 |", doc)
        self.assertIn("| C (conditional) | 0 / 0 | 1 / 1 | 0 / 0 | 1 / 1 |", doc)
        self.assertIn("| SDO-02 | CiA 301 §7.2.4 | Eight bytes. | Eight bytes missing. Hardware |", doc)
        self.assertIn("| SDO-03 | CiA 301 §7.2.4 | Command byte. | No test cites it yet. |", doc)
        self.assertIn("| SDO-01 | M | CiA 301 §7.3.3 | Server on 600h. | `tests/a.rs::a` |", doc)
        self.assertIn("`tests/python/test_c.py::test_c`", doc)
        self.assertIn("- O (1): PDO-01", doc)


if __name__ == "__main__":
    unittest.main()
