#!/usr/bin/env python3
"""Where the flash of an ARM ELF goes, by crate and (for canopen-core) by module, and how a second ELF
(the baseline) differs. Usage: footprint-breakdown.py NODE_ELF [BASELINE_ELF]

With LTO almost everything is inlined into a few big functions (the executor's `TaskStorage::poll` holds the
whole driver task), so symbol sizes (`nm -S`) say little. This walks the DWARF line table instead
(`objdump --dwarf=decodedline`): every byte of .text is charged to the source file of the line it was
compiled from, inlined or not. Lines from Rust's `core` library (slice copies, Option, cell borrows...) are
charged to the last non-library source seen before them in the same function, i.e. to the code that
inlined them; this is a heuristic, but it keeps `core` from swallowing the callers' cost. Bytes with no line
information are charged by the enclosing symbol's crate. Named read-only data (.rodata symbols) is charged
by symbol name; unnamed constants (string literals, LTO-merged tables) are listed as one group.
"""
import os
import re
import subprocess
import sys
from collections import defaultdict

ROW = re.compile(r"^(\S+)\s+(\d+|-)\s+(0x[0-9a-f]+)")


def classify(path):
    m = re.search(r"canopen-core/src/(.*)\.rs$", path)
    if m:
        mod = m.group(1).replace("/mod", "").replace("/", "::")
        return "canopen-core::" + mod
    if "canopen-od-derive" in path:
        return "canopen-od-derive"
    # Before the registry match: a unit's relative "src/bin/minimal.rs" may have been resolved against a
    # dependency's root.
    if re.search(r"src/bin/(node|minimal|baseline)\.rs$", path):
        return "firmware bin (app, tasks, derived dictionary)"
    if re.search(r"examples/firmware/src/lib\.rs$", path) or path == "src/lib.rs":
        return "firmware glue (lib.rs)"
    m = re.search(r"registry/src/[^/]+/([A-Za-z0-9_\-]+?)-\d+\.\d+\.\d+[^/]*/", path)
    if m:
        return m.group(1)
    if "/build/embassy-stm32-" in path:
        return "embassy-stm32"
    if "compiler-builtins" in path or "compiler_builtins" in path:
        return "compiler_builtins"
    if re.search(r"library/(core|alloc)/", path):
        return "core"
    return "other: " + path


def symbol_crate(name):
    if name.startswith(".L"):
        # LTO-local constants: `.Lswitch.table.<mangled fn>` names its user, `.Lanon.*` nobody.
        m = re.search(r"([a-z][a-z0-9_]*)\.\.", name)
        if not m:
            return "unnamed (literals, tables)"
        name = m.group(1) + "::"
    name = name.lstrip("<&* ")
    m = re.match(r"(?:mut |dyn )?([A-Za-z_][A-Za-z0-9_]*)::", name)
    if not m:
        return "unnamed/" + ("linker" if name.startswith("_") or name.isupper() else "other")
    crate = m.group(1).replace("_", "-")
    if crate == "compiler-builtins":
        return "compiler_builtins"
    if crate in ("node", "minimal", "baseline"):
        return "firmware bin (app, tasks, derived dictionary)"
    if crate == "canopen-firmware":
        return "firmware glue (lib.rs)"
    return crate


def symbols(elf):
    out = subprocess.run(["nm", "-S", "-C", elf], capture_output=True, text=True, check=True).stdout
    syms = []
    for line in out.splitlines():
        parts = line.split(None, 3)
        if len(parts) == 4:
            addr, size, kind, name = parts
            syms.append((int(addr, 16) & ~1, int(size, 16), kind, name))
    return syms


def sections(elf):
    out = subprocess.run(["size", "-A", elf], capture_output=True, text=True, check=True).stdout
    secs = {}
    for line in out.splitlines():
        p = line.split()
        if len(p) == 3 and p[0].startswith("."):
            secs[p[0]] = (int(p[2]), int(p[1]))
    return secs


def breakdown(elf):
    dump = subprocess.run(["objdump", "--dwarf=decodedline", elf], capture_output=True, text=True).stdout
    # objdump prints a file's path relative to its compilation unit's directory when it lies there
    # ("src/time.rs" is in canopen-core and in embassy-stm32). Each unit starts with a bare file name line;
    # its relative paths are resolved against the crate root (seen in absolute paths anywhere in the dump)
    # under which most of them exist.
    units = [[]]  # per unit: [(path, [(addr, is_end)])]
    roots = set()
    for line in dump.splitlines():
        if line.endswith(":") and not line.startswith(" ") and "File name" not in line and not line.startswith("CU:"):
            path = line[:-1]
            if "/" not in path:
                units.append([])
                continue
            m = re.match(r"(.*/(?:canopen-[a-z-]+|examples/firmware|[A-Za-z0-9_\-]+-\d+\.\d+\.\d+[^/]*))/src/", path)
            if path.startswith("/") and m:
                roots.add(m.group(1))
            units[-1].append((path, []))
            continue
        m = ROW.match(line)
        if m and units[-1]:
            units[-1][-1][1].append((int(m.group(3), 16), m.group(2) == "-"))
    rows = []  # (addr, group or None for end of sequence)
    for unit in units:
        rel = {p for p, _ in unit if not p.startswith("/") and not p.startswith("library/")}
        root = max(sorted(roots), key=lambda r: sum(os.path.exists(os.path.join(r, p)) for p in rel), default="")
        for path, addrs in unit:
            if not path.startswith("/") and not path.startswith("library/") and root:
                path = os.path.join(root, path)
            group = classify(path)
            rows.extend((a, None if end else group) for a, end in addrs)
    rows.sort(key=lambda r: r[0])

    syms = symbols(elf)
    text_syms = sorted((a, s, n) for a, s, k, n in syms if k in "tT" and s > 0)
    secs = sections(elf)
    groups = defaultdict(int)

    # Per function: walk its line rows.
    import bisect

    addrs = [r[0] for r in rows]
    covered = 0
    for start, size, name in text_syms:
        end = start + size
        i = bisect.bisect_right(addrs, start) - 1
        last_own = None
        fallback = symbol_crate(name)
        pos = start
        while pos < end:
            group = rows[i][1] if 0 <= i < len(rows) else None
            nxt = rows[i + 1][0] if i + 1 < len(rows) else end
            seg_end = min(max(nxt, pos), end)
            if seg_end <= pos:
                i += 1
                continue
            if group is None:
                charge = fallback
            elif group == "core":
                charge = last_own or fallback
            else:
                charge = group
                last_own = group
            groups[charge] += seg_end - pos
            covered += seg_end - pos
            pos = seg_end
            i += 1

    # Read-only data and the vector table.
    ro_named = 0
    if ".rodata" in secs:
        ro_start, ro_size = secs[".rodata"]
        for a, s, k, n in syms:
            if k in "rR" and ro_start <= a < ro_start + ro_size and s > 0:
                groups["rodata: " + symbol_crate(n)] += s
                ro_named += s
        groups["rodata: unnamed (literals, tables)"] += ro_size - ro_named
    if ".vector_table" in secs:
        groups["vector table"] += secs[".vector_table"][1]
    if ".data" in secs:
        groups[".data (initial values, in flash)"] += secs[".data"][1]
    text_size = secs.get(".text", (0, 0))[1]
    groups["text: padding / no symbol"] += text_size - covered
    return groups


def main():
    node = breakdown(sys.argv[1])
    base = breakdown(sys.argv[2]) if len(sys.argv) > 2 else defaultdict(int)
    keys = sorted(set(node) | set(base), key=lambda k: (-(node.get(k, 0) - base.get(k, 0)), k))
    print(f"  {'group':<52} {'node':>7} {'baseline':>9} {'delta':>7}")
    for k in keys:
        n, b = node.get(k, 0), base.get(k, 0)
        if n or b:
            print(f"  {k:<52} {n:>7} {b:>9} {n - b:>7}")
    tn, tb = sum(node.values()), sum(base.values())
    print(f"  {'total (flash)':<52} {tn:>7} {tb:>9} {tn - tb:>7}")


if __name__ == "__main__":
    main()
