#!/usr/bin/env python3
"""Flash per source function of an ARM ELF, exclusive: every byte of .text is charged to the innermost
function of its inline chain that is not Rust's `core` library (so a slice copy counts for the function
that wrote it), whatever symbol it was inlined into. With LTO the node is a few big symbols (`nm` sees the
driver task as one `TaskStorage::poll` of 6-11 KB); this says which source functions are big on their own,
wherever their copies ended up, and adds up the copies of a function inlined at several places.

Usage: footprint-functions.py ELF [SUBSTRING] [N]
  ELF        e.g. examples/firmware/target/thumbv7em-none-eabihf/release/minimal (after scripts/footprint.sh)
  SUBSTRING  only functions whose name contains it (default: canopen)
  N          how many rows (default 40)
Needs llvm-objdump and addr2line (binutils reads ARM ELF files). Generic parameters are dropped from the
names, so every instance of a function adds up in one row. Compare with footprint-inlined.py (inclusive
bytes inside one symbol) and footprint-breakdown.py (bytes per crate and module).
"""
import collections
import re
import subprocess
import sys


def run(*cmd, stdin=None):
    return subprocess.run(cmd, input=stdin, capture_output=True, text=True, check=True).stdout


def strip_generics(name):
    while True:
        shorter = re.sub(r"<[^<>]*>", "", name)
        if shorter == name:
            return name
        name = shorter


def is_core(location):
    return "/rustc/" in location or "library/core" in location


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    elf = sys.argv[1]
    pattern = sys.argv[2] if len(sys.argv) > 2 else "canopen"
    rows = int(sys.argv[3]) if len(sys.argv) > 3 else 40
    listing = run("llvm-objdump", "-d", "--no-show-raw-insn", "-j", ".text", elf)
    addrs = [int(m.group(1), 16) for m in re.finditer(r"^\s*([0-9a-f]+):\s", listing, re.M)]
    # Instruction sizes from consecutive addresses; a gap over 8 bytes is data or padding between symbols.
    sizes = {a: b - a for a, b in zip(addrs, addrs[1:]) if b - a <= 8}
    lines = run("addr2line", "-i", "-f", "-C", "-a", "-e", elf, stdin="".join(f"{a:#x}\n" for a in sizes))
    exclusive = collections.Counter()

    def charge(addr, frames):
        # frames: innermost first, (function, file:line)
        own = next((fn for fn, loc in frames if not is_core(loc)), frames[0][0] if frames else "?")
        exclusive[strip_generics(own)] += sizes.get(addr, 0)

    addr, frames = None, []
    it = iter(lines.splitlines())
    for line in it:
        if line.startswith("0x"):
            if addr is not None:
                charge(addr, frames)
            addr, frames = int(line, 16), []
            continue
        frames.append((line, next(it, "")))
    if addr is not None:
        charge(addr, frames)
    chosen = [(fn, n) for fn, n in exclusive.most_common() if pattern in fn]
    print(f"{elf}: {sum(n for _, n in chosen)} bytes of .text in functions matching {pattern!r}, exclusive:")
    for fn, n in chosen[:rows]:
        print(f"  {n:6d}  {fn}")


if __name__ == "__main__":
    main()
