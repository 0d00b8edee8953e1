#!/usr/bin/env python3
"""What one big function of an ARM ELF is made of: its bytes charged to every function inlined into it, at
any depth (a byte counts for each function of its inline chain, so the figures nest: `handle_frame` includes
the `handle_sdo` inlined into it). With LTO the node's frame handling is inlined whole into the driver
task's future (`TaskStorage::poll`, `__canopen_task_inner_function::{{closure}}`), where `nm` shows one
symbol of 7-10 KB; this says which source functions those bytes come from.

Usage: footprint-inlined.py ELF [SYMBOL-SUBSTRING] [N]
       footprint-inlined.py --functions ELF [NAME-SUBSTRING] [N]
  ELF        e.g. examples/firmware/target/thumbv7em-none-eabihf/release/minimal (after scripts/footprint.sh)
  SYMBOL     the function to break down, by a substring of its demangled name; default: the biggest one
  N          how many rows (default 40)
  --functions  the other view, over the whole .text: each source function's own bytes (exclusive: every
             byte goes to the innermost function of its inline chain that is not Rust's `core` library),
             wherever LTO inlined it and adding up its copies; only names containing NAME-SUBSTRING
             (default: canopen)
Needs llvm-objdump, nm and addr2line (binutils reads ARM ELF files). Generic parameters are dropped from
the names, so every instance of a function adds up in one row.
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


def functions(elf, pattern, rows):
    """The --functions view (see the module docs)."""
    listing = run("llvm-objdump", "-d", "--no-show-raw-insn", "-j", ".text", elf)
    addrs = [int(m.group(1), 16) for m in re.finditer(r"^\s*([0-9a-f]+):\s", listing, re.M)]
    # Instruction sizes from consecutive addresses; a gap over 8 bytes is data or padding between symbols.
    sizes = {a: b - a for a, b in zip(addrs, addrs[1:]) if b - a <= 8}
    lines = run("addr2line", "-i", "-f", "-C", "-a", "-e", elf, stdin="".join(f"{a:#x}\n" for a in sizes))
    own = collections.Counter()
    addr, frames = None, []  # frames: innermost first, (function, file:line)

    def charge():
        if addr is not None:
            core = lambda loc: "/rustc/" in loc or "library/core" in loc
            fn = next((f for f, loc in frames if not core(loc)), frames[0][0] if frames else "?")
            own[strip_generics(fn)] += sizes.get(addr, 0)

    it = iter(lines.splitlines())
    for line in it:
        if line.startswith("0x"):
            charge()
            addr, frames = int(line, 16), []
            continue
        frames.append((line, next(it, "")))
    charge()
    chosen = [(fn, n) for fn, n in own.most_common() if pattern in fn]
    print(f"{elf}: {sum(n for _, n in chosen)} bytes of .text in functions matching {pattern!r}, exclusive:")
    for fn, n in chosen[:rows]:
        print(f"  {n:6d}  {fn}")


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--functions":
        rest = sys.argv[2:]
        functions(rest[0], rest[1] if len(rest) > 1 else "canopen", int(rest[2]) if len(rest) > 2 else 40)
        return
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    elf, pattern = sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else ""
    rows = int(sys.argv[3]) if len(sys.argv) > 3 else 40
    symbols = []
    for line in run("nm", "-S", "-t", "d", "-C", elf).splitlines():
        parts = line.split(None, 3)
        if len(parts) == 4 and parts[2] in "tT" and pattern in parts[3]:
            symbols.append((int(parts[1]), int(parts[0]) & ~1, parts[3]))
    if not symbols:
        sys.exit(f"no function symbol matching {pattern!r}")
    size, start, name = max(symbols)
    listing = run("llvm-objdump", "-d", "--no-show-raw-insn", f"--start-address={start}",
                  f"--stop-address={start + size}", elf)
    addrs = [int(m.group(1), 16) for m in re.finditer(r"^\s*([0-9a-f]+):\s", listing, re.M)] + [start + size]
    sizes = {a: b - a for a, b in zip(addrs, addrs[1:])}
    lines = run("addr2line", "-i", "-f", "-C", "-a", "-e", elf, stdin="".join(f"{a:#x}\n" for a in sizes))
    inclusive = collections.Counter()
    chain, addr = set(), None
    it = iter(lines.splitlines())
    for line in it:
        if line.startswith("0x"):
            addr, chain = int(line, 16), set()
            continue
        next(it, None)  # the file:line row of this frame
        fn = strip_generics(line)
        if fn not in chain:
            chain.add(fn)
            inclusive[fn] += sizes.get(addr, 0)
    print(f"{name}: {size} bytes; bytes per function inlined into it (any depth, nested):")
    for fn, n in inclusive.most_common(rows):
        print(f"  {n:6d}  {fn}")


if __name__ == "__main__":
    main()
