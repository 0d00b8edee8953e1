#!/usr/bin/env python3
"""Tests of scripts/ratchet.py (the CI ratchet of issue 13 item 4). Run: python3 scripts/test_ratchet.py"""
import os
import subprocess
import sys
import tempfile
import unittest

RATCHET = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ratchet.py")


def run(baseline, figures):
    with tempfile.NamedTemporaryFile("w", suffix=".baseline", delete=False) as f:
        f.write(baseline)
    try:
        p = subprocess.run(
            [sys.executable, RATCHET, f.name, "bytes"], input=figures, capture_output=True, text=True, check=False
        )
        with open(f.name, encoding="utf-8") as g:
            after = g.read()
        return p.returncode, p.stdout, after, f.name
    finally:
        os.unlink(f.name)


class Ratchet(unittest.TestCase):
    def test_equal_and_within_two_percent_pass(self):
        code, out, _, _ = run("# comment\nnode.flash 1000\nnode.ram 500 # trailing\n", "node.flash 1020\nnode.ram 500\n")
        self.assertEqual(code, 0, out)
        self.assertIn("+2.0%", out)
        self.assertNotIn("baseline update", out)

    def test_growth_over_two_percent_fails(self):
        code, out, _, _ = run("node.flash 1000\n", "node.flash 1021\n")
        self.assertEqual(code, 1, out)
        self.assertIn("FAIL: grew more than 2%", out)

    def test_lower_figure_passes_and_prints_the_one_line_update(self):
        code, out, _, _ = run("node.flash 1000\nnode.ram 500\n", "node.flash 900\nnode.ram 500\n")
        self.assertEqual(code, 0, out)
        update = [l.strip() for l in out.splitlines() if l.strip().startswith("sed -i")]
        self.assertEqual(len(update), 1, out)
        self.assertIn("s/^node\\.flash .*/node.flash 900/", update[0])

    def test_the_printed_update_edits_only_its_line(self):
        # `node+store.flash`: a name with a character that is special to sed's extended syntax (GNU sed
        # reads `\+` as "one or more", so a Python-escaped `node\+store` matched nothing).
        with tempfile.NamedTemporaryFile("w", suffix=".baseline", delete=False) as f:
            f.write("# keep\nnode.flash 1000\nnode+store.flash 2000\nnode.ram 500\n")
        try:
            p = subprocess.run(
                [sys.executable, RATCHET, f.name, "bytes"],
                input="node.flash 900\nnode+store.flash 1900\nnode.ram 500\n",
                capture_output=True, text=True, check=False, cwd="/",
            )
            cmds = [l.strip() for l in p.stdout.splitlines() if l.strip().startswith("sed -i")]
            self.assertEqual(len(cmds), 2, p.stdout)
            for cmd in cmds:
                subprocess.run(cmd, shell=True, check=True, cwd="/")
            with open(f.name, encoding="utf-8") as g:
                self.assertEqual(g.read(), "# keep\nnode.flash 900\nnode+store.flash 1900\nnode.ram 500\n")
        finally:
            os.unlink(f.name)

    def test_figure_without_baseline_line_fails(self):
        code, out, _, _ = run("node.flash 1000\n", "node.flash 1000\nminimal.flash 800\n")
        self.assertEqual(code, 1, out)
        self.assertIn("no baseline line", out)

    def test_fractional_figures_keep_one_decimal(self):
        code, out, _, _ = run("sync_4_tpdos 345.2\n", "sync_4_tpdos 345.3\n")
        self.assertEqual(code, 0, out)
        self.assertIn("345.3", out)


if __name__ == "__main__":
    unittest.main()
