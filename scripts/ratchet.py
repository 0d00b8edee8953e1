#!/usr/bin/env python3
"""The CI ratchet of issue 13 item 4: compares measured figures with a committed baseline file.

Usage: <figures on stdin, one "name value" a line> | ratchet.py BASELINE_FILE UNIT

The baseline file is plain text, one "name value" a line ('#' starts a comment). Prints a table of every
figure (baseline, now, change, verdict) and exits 1 when a figure is more than 2 % above its baseline or has
no baseline line. A figure below its baseline passes and gets the one-line update of the baseline file
printed (a `sed` command), so lowering a baseline is a one-line commit with the new figure.
"""
import os
import re
import sys

TOLERANCE = 0.02


def read_baseline(path):
    base = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                name, value = line.split()
                base[name] = float(value)
    return base


def sed_escape(name):
    """`name` as a literal in a sed basic regular expression: `re.escape` would write `\\+` for `+`, which
    GNU sed reads as "one or more"; in a basic expression only these characters are special."""
    return re.sub(r"([.\[\]*^$\\/])", r"\\\1", name)


def fmt(v, decimals):
    return f"{v:,.{decimals}f}"


def main():
    path, unit = sys.argv[1], sys.argv[2]
    base = read_baseline(path)
    now = {}
    for line in sys.stdin:
        if line.strip():
            name, value = line.split()
            now[name] = float(value)
    # Whole numbers (bytes) print as such, fractional ones (instructions per frame) with one decimal.
    decimals = 0 if all(v == int(v) for v in list(base.values()) + list(now.values())) else 1
    rel = os.path.relpath(path)
    print(f"ratchet against {rel} (fails above baseline + {TOLERANCE:.0%}), {unit}:")
    print(f"  {'figure':<24} {'baseline':>10} {'now':>10} {'change':>8}  verdict")
    failed, updates = False, []
    for name in sorted(now):
        v = now[name]
        if name not in base:
            print(f"  {name:<24} {'-':>10} {fmt(v, decimals):>10} {'':>8}  FAIL: no baseline line")
            updates.append(f"echo '{name} {fmt(v, decimals).replace(',', '')}' >> {rel}")
            failed = True
            continue
        b = base[name]
        change = (v - b) / b if b else 0.0
        if v > b * (1 + TOLERANCE):
            verdict = f"FAIL: grew more than {TOLERANCE:.0%}"
            failed = True
        elif v < b:
            verdict = "ok, lower: update the baseline"
            new = fmt(v, decimals).replace(",", "")
            updates.append(f"sed -i 's/^{sed_escape(name)} .*/{name} {new}/' {rel}")
        else:
            verdict = "ok"
        print(f"  {name:<24} {fmt(b, decimals):>10} {fmt(v, decimals):>10} {change:>+8.1%}  {verdict}")
    if updates:
        print("baseline update (one line each; commit it with the change that lowered the figure):")
        for u in updates:
            print(f"  {u}")
    if failed:
        print(f"FAIL: a figure grew more than {TOLERANCE:.0%} over {rel}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
