#!/usr/bin/env python3
"""Generate docs/CONFORMANCE.md from docs/requirements.tsv and the requirement IDs the tests cite.

    python3 scripts/conformance.py            # rewrite docs/CONFORMANCE.md
    python3 scripts/conformance.py --check    # exit 1 if docs/CONFORMANCE.md is not what this would write
    python3 scripts/conformance.py --stdout   # print the document instead of writing it

A requirement counts as met when at least one test cites its ID. A test is a Rust function carrying a
`#[test]`-like attribute (`#[test]`, `#[tokio::test]`, inside `proptest! {}` too) or a Python `test*`
function in a `test_*.py` file. It cites an ID when the ID appears

- in its name, as `<prefix>_<nn>` (`crc_check_value_sdo_49` cites SDO-49; `..._sdo_12_24` cites SDO-12
  and SDO-24),
- in the comments, doc comments and attributes directly above it (stopping at a blank line), or
- anywhere in its body (comments, strings, code); for Python also in its docstring and decorators.

Python tests are the `test*` functions (and `Test*` class methods) of `test_*.py` files in a `tests`
folder; rustdoc examples of library sources count as tests too (listed as `Item (doctest)`).

`SDO-12..15` and `SDO-12–15` cite the whole range, `PDO-38/39` both IDs. An ID anywhere else (module docs,
helpers, non-test code) is not a citation. Python 3 standard library only.
"""

from __future__ import annotations

import argparse
import ast
import difflib
import os
import re
import sys
from dataclasses import dataclass, field

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REQUIREMENTS = "docs/requirements.tsv"
OUTPUT = "docs/CONFORMANCE.md"
README = "README.md"
SKIP_DIRS = {"target", "node_modules", "__pycache__"}
LEVELS = ("M", "C", "O")
LEVEL_NAMES = {"M": "mandatory", "C": "conditional", "O": "optional"}


@dataclass
class Requirement:
    id: str
    level: str
    clause: str
    statement: str

    @property
    def group(self) -> str:
        return self.id.rsplit("-", 1)[0]

    @property
    def standard(self) -> str:
        return {"LSS": "CiA 305", "PRG": "CiA 302-3"}.get(self.group, "CiA 301")


@dataclass
class TestFn:
    """One test function and the text that may cite requirement IDs."""

    path: str  # relative to the repository root, with '/'
    name: str
    text: str  # preceding comments/attributes, signature and body
    ids: set = field(default_factory=set)
    ignored: str | None = None  # the reason of `#[ignore = "..."]` ("" without one); None if not ignored

    @property
    def label(self) -> str:
        return f"{self.path}::{self.name}"

    @property
    def counts(self) -> bool:
        """An ignored test proves something only where CI runs it: the SocketCAN tests, inside the VM."""
        return self.ignored is None or bool(re.search(r"vcan|socketcan", self.ignored, re.I))


# ---------------------------------------------------------------------------------------------------------
# Requirements


def parse_requirements(text: str) -> list[Requirement]:
    """Parse the TSV: '#' lines are comments, the first other line is the header."""
    reqs, seen, header = [], set(), None
    for n, line in enumerate(text.splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        cols = line.split("\t")
        if header is None:
            header = cols
            if header != ["id", "level", "clause", "statement"]:
                raise ValueError(f"{REQUIREMENTS}:{n}: unexpected header {header}")
            continue
        if len(cols) != 4 or not all(c.strip() for c in cols):
            raise ValueError(f"{REQUIREMENTS}:{n}: expected 4 non-empty tab-separated columns")
        rid, level, clause, statement = (c.strip() for c in cols)
        if not re.fullmatch(r"[A-Z]+-\d+", rid) or level not in LEVELS or rid in seen:
            raise ValueError(f"{REQUIREMENTS}:{n}: bad or duplicate id/level {rid!r} {level!r}")
        seen.add(rid)
        reqs.append(Requirement(rid, level, clause, statement))
    return reqs


# ---------------------------------------------------------------------------------------------------------
# Citations


def cited_ids(text: str, prefixes: set[str]) -> set[str]:
    """IDs written as PREFIX-NN, PREFIX-NN..MM / PREFIX-NN–MM (ranges) or PREFIX-NN/MM[/KK] (lists)."""
    ids = set()
    pat = re.compile(r"(?<![\w-])([A-Z]+)-(\d+)((?:\s*(?:\.\.|–)\s*(?:\1-)?\d+)|(?:/\d+)+)?(?![\w-])")
    for m in pat.finditer(text):
        prefix, first, rest = m.group(1), int(m.group(2)), m.group(3) or ""
        if prefix not in prefixes:
            continue
        width = len(m.group(2))
        nums = [first]
        if rest.startswith("/"):
            nums += [int(x) for x in rest[1:].split("/")]
        elif rest:
            last = int(re.search(r"\d+$", rest).group())
            if first <= last <= first + 64:
                nums = list(range(first, last + 1))
        ids.update(f"{prefix}-{n:0{width}d}" for n in nums)
    return ids


def name_ids(name: str, prefixes: set[str]) -> set[str]:
    """IDs in a function name: `_sdo_49`, `sdo_12_24` (two-digit numbers following a known prefix)."""
    ids, parts, i = set(), name.split("_"), 0
    while i < len(parts):
        prefix = parts[i].upper()
        j = i + 1
        if prefix in prefixes:
            while j < len(parts) and re.fullmatch(r"\d\d", parts[j]):
                ids.add(f"{prefix}-{parts[j]}")
                j += 1
        i = j if j > i + 1 else i + 1
    return ids


# ---------------------------------------------------------------------------------------------------------
# Rust


def rust_code_mask(src: str) -> str:
    """`src` with comments, string and char literals blanked (newlines kept), so that braces, brackets and
    keywords can be found in code only. Handles nested block comments, raw strings and lifetimes."""
    out = list(src)
    i, n = 0, len(src)

    def blank(a: int, b: int) -> None:
        for k in range(a, min(b, n)):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            blank(i, j)
            i = j
        elif src.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif src.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            blank(i, j)
            i = j
        elif (m := re.compile(r"b?r(#*)\"").match(src, i)) and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == "_")):
            end = src.find('"' + m.group(1), m.end())
            j = n if end < 0 else end + 1 + len(m.group(1))
            blank(i, j)
            i = j
        elif c == '"':
            j = i + 1
            while j < n and src[j] != '"':
                j += 2 if src[j] == "\\" else 1
            blank(i, j + 1)
            i = j + 1
        elif c == "'":
            # A char literal ('x', '\n', '\u{..}', '{') or a lifetime ('a, 'static).
            m = re.compile(r"'(?:\\(?:u\{[0-9a-fA-F_]*\}|x[0-9a-fA-F]{2}|.)|[^\\'\n])'").match(src, i)
            if m:
                blank(i, m.end())
                i = m.end()
            else:
                i += 1
        else:
            i += 1
    return "".join(out)


QUALIFIER = re.compile(r"(?:\bpub(?:\s*\([^)]*\))?|\basync|\bunsafe|\bconst|\bextern)\s*$")
TEST_ATTR = re.compile(r"#\s*\[\s*(?:[\w:]+::)?(?:test|rstest|test_case)\b")


def rust_tests(path: str, src: str) -> list[TestFn]:
    mask = rust_code_mask(src)
    tests = []
    for m in re.finditer(r"\bfn\s+([A-Za-z_]\w*)", mask):
        # Walk back over qualifiers and attributes (`pub`, `async`, `#[...]`) to the start of the item.
        start = m.start()
        attrs = []
        while True:
            k = start
            while k > 0 and mask[k - 1].isspace():
                k -= 1
            q = QUALIFIER.search(mask, max(0, k - 40), k)
            if q:
                start = q.start()
                continue
            if k > 0 and mask[k - 1] == "]":
                depth, j = 0, k - 1
                while j >= 0:
                    if mask[j] == "]":
                        depth += 1
                    elif mask[j] == "[":
                        depth -= 1
                        if depth == 0:
                            break
                    j -= 1
                if j > 0 and mask[j - 1] == "#":
                    attrs.append(mask[j - 1 : k])
                    start = j - 1
                    continue
            break
        if not any(TEST_ATTR.match(a) for a in attrs):
            continue
        ignored = None
        for a in attrs:
            if re.match(r"#\s*\[\s*ignore\b", a):
                pos = mask.find(a, start)
                raw = src[pos : pos + len(a)]
                reason = re.search(r'"((?:[^"\\]|\\.)*)"', raw)
                ignored = reason.group(1) if reason else ""
        # The comments directly above: from the line after the previous code, the trailing run of
        # non-blank lines.
        k = start
        while k > 0 and mask[k - 1].isspace():
            k -= 1
        first_line = src.find("\n", k) + 1 if k > 0 else 0
        above = src[first_line:start].split("\n")[:-1]  # the last part is the indentation of `start`
        run = []
        for line in reversed(above):
            if not line.strip():
                break
            run.append(line)
        preceding = "\n".join(reversed(run))
        # The body: the first '{' outside parentheses/brackets after the name, to its matching '}'.
        depth, j, body_end = 0, m.end(), None
        while j < len(mask):
            ch = mask[j]
            if ch in "([":
                depth += 1
            elif ch in ")]":
                depth -= 1
            elif ch == ";" and depth == 0:
                break
            elif ch == "{" and depth == 0:
                braces = 0
                while j < len(mask):
                    if mask[j] == "{":
                        braces += 1
                    elif mask[j] == "}":
                        braces -= 1
                        if braces == 0:
                            body_end = j + 1
                            break
                    j += 1
                break
            j += 1
        if body_end is None:
            continue
        tests.append(TestFn(path, m.group(1), preceding + "\n" + src[start:body_end], ignored=ignored))
    return tests


DOC_LINE = re.compile(r"^\s*//([/!])(?!/) ?(.*)$")
ITEM = re.compile(r"\b(?:fn|struct|enum|trait|const|static|type|mod|union)\s+([A-Za-z_]\w*)|\bimpl\b[^{]*?(\w+)\s*(?:<[^{]*)?\{")
RUNNABLE_TOKENS = {"", "rust", "should_panic", "compile_fail", "test_harness"}


def rust_doctests(path: str, src: str) -> list[TestFn]:
    """The code blocks of doc comments that rustdoc runs as tests (not `ignore`, `no_run`, `text`, ...).
    Only the code block is the test: the prose around it is documentation, not a citation."""
    lines = src.split("\n")
    tests, i = [], 0
    while i < len(lines):
        m = DOC_LINE.match(lines[i])
        if not m:
            i += 1
            continue
        kind, start, doc = m.group(1), i, []
        while i < len(lines) and (dm := DOC_LINE.match(lines[i])) and dm.group(1) == kind:
            doc.append(dm.group(2))
            i += 1
        if kind == "!":
            name = "(module docs)"
        else:
            k = i
            while k < len(lines) and (not lines[k].strip() or lines[k].strip().startswith("#[")):
                k += 1
            im = ITEM.search("\n".join(lines[k : k + 3])) if k < len(lines) else None
            name = (im.group(1) or im.group(2)) if im else f"line {start + 1}"
        blocks, fence, info, body = [], None, "", []
        for line in doc:
            stripped = line.strip()
            if fence is None:
                fm = re.match(r"(```+|~~~+)\s*(.*)$", stripped)
                if fm:
                    fence, info, body = fm.group(1), fm.group(2), []
            elif stripped.startswith(fence):
                tokens = {t for t in re.split(r"[\s,]+", info.strip()) if not t.startswith("edition")}
                if tokens <= RUNNABLE_TOKENS:
                    blocks.append("\n".join(body))
                fence = None
            else:
                body.append(line)
        for b in blocks:
            tests.append(TestFn(path, f"{name} (doctest)", b))
    return tests


# ---------------------------------------------------------------------------------------------------------
# Python


def python_tests(path: str, src: str) -> list[TestFn]:
    lines = src.splitlines()
    tests = []

    def add(node: ast.AST) -> None:
        first = min([node.lineno] + [d.lineno for d in node.decorator_list])
        k = first - 1
        while k > 0 and lines[k - 1].strip().startswith("#"):
            k -= 1
        text = "\n".join(lines[k : node.end_lineno])
        tests.append(TestFn(path, node.name, text))

    tree = ast.parse(src)
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name.startswith("test"):
            add(node)
        elif isinstance(node, ast.ClassDef) and node.name.startswith("Test"):
            for item in node.body:
                if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)) and item.name.startswith("test"):
                    add(item)
    return tests


# ---------------------------------------------------------------------------------------------------------
# Repository scan


def excluded_members(root: str) -> set[str]:
    """The `exclude = [...]` paths of the root Cargo.toml: separate workspaces CI does not test."""
    path = os.path.join(root, "Cargo.toml")
    if not os.path.exists(path):
        return set()
    with open(path, encoding="utf-8") as f:
        m = re.search(r"^exclude\s*=\s*\[([^\]]*)\]", f.read(), re.M)
    return set(re.findall(r'"([^"]+)"', m.group(1))) if m else set()


def source_files(root: str) -> list[str]:
    found, skip = [], excluded_members(root)
    for dirpath, dirnames, filenames in os.walk(root):
        rel_dir = os.path.relpath(dirpath, root).replace(os.sep, "/")
        dirnames[:] = sorted(
            d
            for d in dirnames
            if d not in SKIP_DIRS and not d.startswith(".") and os.path.normpath(f"{rel_dir}/{d}") not in skip
        )
        for f in sorted(filenames):
            # Python tests live in a `tests` folder (tests/python/); the generator's own tests are not ones.
            python_test = f.startswith("test_") and f.endswith(".py") and "tests" in rel_dir.split("/")
            if f.endswith(".rs") or python_test:
                found.append(os.path.relpath(os.path.join(dirpath, f), root).replace(os.sep, "/"))
    return sorted(found)


def runs_doctests(rel: str) -> bool:
    """rustdoc runs the doc examples of library sources only: `src/` of the root package or of a member,
    not integration tests, examples, benches, binaries or build scripts."""
    parts = rel.split("/")
    if "src" not in parts[:2] or "bin" in parts or parts[-1] in ("main.rs", "build.rs"):
        return False
    return parts[0] not in ("tests", "examples", "benches")


def collect_tests(root: str, prefixes: set[str]) -> list[TestFn]:
    tests = []
    for rel in source_files(root):
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            src = f.read()
        if rel.endswith(".rs"):
            found = rust_tests(rel, src) + (rust_doctests(rel, src) if runs_doctests(rel) else [])
        else:
            found = python_tests(rel, src)
        for t in found:
            t.ids = cited_ids(t.text, prefixes) | name_ids(t.name, prefixes)
        tests.extend(found)
    return tests


def not_done_reasons(readme: str, prefixes: set[str]) -> dict[str, str]:
    """ID -> reason, from the README table under the heading that contains "not done"."""
    reasons, in_section = {}, False
    for line in readme.splitlines():
        if line.startswith("#"):
            in_section = "not done" in line.lower()
            continue
        if not in_section or not line.startswith("|") or set(line) <= set("|- "):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 3 or cells[0] == "ID":
            continue
        for rid in cited_ids(cells[0], prefixes):
            reasons[rid] = f"{cells[1]}. {cells[2]}" if cells[2] else cells[1]
    return reasons


# ---------------------------------------------------------------------------------------------------------
# Document

INTRO = """\
# Conformance to CiA 301, CiA 305 and CiA 302-3

Generated by `python3 scripts/conformance.py` from [`requirements.tsv`](requirements.tsv) and the tests'
citations; do not edit it by hand. CI runs `python3 scripts/conformance.py --check`, which fails when this
file is not current.

A requirement is **met** when at least one test cites its ID: in the test function's name (`..._sdo_49`),
in the comments or doc comment directly above it, or in its body. Tests are the Rust `#[test]` functions
of the workspace (integration tests, `mod tests` in the sources, proptests), the code blocks of doc
comments that rustdoc runs (listed as `(doctest)`), and the python `test_*` functions in `tests/python/`
(run by CI against the node over vcan). An `#[ignore]`d test counts only when its reason says it needs
SocketCAN/vcan, because CI runs exactly those inside its VM. An ID written anywhere else (module docs,
item docs, helpers) counts for nothing. `SDO-12..15` cites a range, `PDO-38/39` both IDs.
"""

SOURCES = """\
## Where the requirements come from

- **CiA 301 (CAN-01 … DEV-10)**: the project's checklist of CiA 301 v4.2.0 device requirements. The clause
  is the CiA 301 section, table or annex; the numbers are those of the (Chinese) translation of CiA 301
  v4.2.0 the checklist was written from, which follows the original numbering. A few items rest only on
  secondary sources (a drive vendor's CANopen manual "PD4-E", the ZLG "CANopen 轻松入门" tutorial, the
  "CANopen Memento" cheat sheet); their clause names that source and heading. The statements are our own
  one-line summaries, not the standard's text. Levels: M = every device, C = once the feature named in
  the item is implemented, O = optional.
- **CiA 305 LSS (LSS-01 … LSS-16)**: the checklist has no LSS items (its sources contain no LSS
  protocol), so these IDs are ours, one per service the slave implements. CiA 305 itself was not at hand:
  the clause names the service as CiA 305 calls it, and the statements and levels were taken from what
  `canopen-core/src/lss/` relies on, cross-checked against public restatements of CiA 305: python
  `canopen` `lss.py` (the master we interoperate with), CANopenNode `CO_LSS.h`/`CO_LSSslave.c`, lely-core
  `lss.c`, and device manuals that restate the protocol (TR-Electronic, Gefran RK-5-C, maxon EPOS4, Festo
  CPX-FB14). Levels there are our reading: switch state, configure node-ID, store, inquire are M; bit
  timing is C (a device whose bit rate can change); identify, fastscan and the master side are O.
- **CiA 302-3 program download (PRG-01 … PRG-06)**: our IDs, one per object behaviour of
  `canopen-core/src/program.rs` (feature `program-download`). CiA 302-3 itself was not at hand: the
  statements rest on public restatements (a TR-Electronic CM-36 manual for 1F57h, CANopenNode-based
  bootloaders' download sequences for 1F50h/1F51h/1F56h); the module docs list what was chosen where they
  are silent. All are O: a device without a bootloader path has none of them.
"""


def render(reqs: list[Requirement], tests: list[TestFn], reasons: dict[str, str]) -> str:
    by_id: dict[str, list[str]] = {r.id: [] for r in reqs}
    for t in tests:
        if not t.counts:
            continue
        for rid in sorted(t.ids):
            if rid in by_id and t.label not in by_id[rid]:
                by_id[rid].append(t.label)
    met = {rid for rid, ts in by_id.items() if ts}

    out = [INTRO]
    out.append(
        "| Level | CiA 301 met / total | CiA 305 (LSS) met / total | CiA 302-3 (PRG) met / total | All met / total |"
    )
    out.append("|---|---|---|---|---|")
    for lvl in LEVELS + ("all",):
        cells = []
        for std in ("CiA 301", "CiA 305", "CiA 302-3", None):
            sel = [r for r in reqs if (lvl == "all" or r.level == lvl) and (std is None or r.standard == std)]
            cells.append(f"{sum(r.id in met for r in sel)} / {len(sel)}")
        name = f"{lvl} ({LEVEL_NAMES[lvl]})" if lvl in LEVEL_NAMES else "**all**"
        out.append(f"| {name} | " + " | ".join(cells) + " |")
    doctests = sum(t.name.endswith("(doctest)") for t in tests)
    citing = sum(bool(t.ids) and t.counts for t in tests)
    out.append(f"\n{len(tests) - doctests} test functions and {doctests} doctests found; {citing} of them cite an ID.\n")
    out.append(SOURCES)

    unmet_m = [r for r in reqs if r.level == "M" and r.id not in met]
    out.append("## Mandatory requirements without a test\n")
    if unmet_m:
        out.append("The reason is the README's \"not done\" table where it has the item.\n")
        out.append("| ID | Clause | Requirement | Reason |")
        out.append("|---|---|---|---|")
        for r in unmet_m:
            reason = reasons.get(r.id, "No test cites it yet.")
            out.append(f"| {r.id} | {esc(r.clause)} | {esc(r.statement)} | {esc(reason)} |")
    else:
        out.append("None: every M item is cited by at least one test.")
    out.append("")

    out.append("## Met requirements\n")
    groups: list[str] = []
    for r in reqs:
        if r.group not in groups:
            groups.append(r.group)
    for g in groups:
        sel = [r for r in reqs if r.group == g and r.id in met]
        total = sum(r.group == g for r in reqs)
        out.append(f"### {g} ({len(sel)} of {total})\n")
        if not sel:
            out.append("No item of this group is cited by a test.\n")
            continue
        out.append("| ID | Level | Clause | Requirement | Tests |")
        out.append("|---|---|---|---|---|")
        for r in sel:
            names = ", ".join(f"`{t}`" for t in by_id[r.id])
            out.append(f"| {r.id} | {r.level} | {esc(r.clause)} | {esc(r.statement)} | {names} |")
        out.append("")

    ignored = [t for t in tests if not t.counts]
    if ignored:
        out.append("## Ignored tests, not counted\n")
        out.append("CI does not run these, so their citations do not count.\n")
        for t in ignored:
            out.append(f"- `{t.label}`: {esc(t.ignored) or 'no reason given'}")
        out.append("")

    out.append("## Conditional and optional requirements without a test\n")
    out.append("Not implemented, not applicable to this device, or implemented but not cited by a test yet.\n")
    for lvl in ("C", "O"):
        ids = [r.id for r in reqs if r.level == lvl and r.id not in met]
        out.append(f"- {lvl} ({len(ids)}): " + (", ".join(ids) if ids else "none"))
    return "\n".join(out) + "\n"


def esc(s: str) -> str:
    return s.replace("|", "\\|")


def generate(root: str = ROOT) -> str:
    with open(os.path.join(root, REQUIREMENTS), encoding="utf-8") as f:
        reqs = parse_requirements(f.read())
    prefixes = {r.group for r in reqs}
    tests = collect_tests(root, prefixes)
    known = {r.id for r in reqs}
    for t in tests:
        for rid in sorted(t.ids - known):
            print(f"warning: {t.label} cites {rid}, which is not in {REQUIREMENTS}", file=sys.stderr)
    readme_path = os.path.join(root, README)
    readme = ""
    if os.path.exists(readme_path):
        with open(readme_path, encoding="utf-8") as f:
            readme = f.read()
    return render(reqs, tests, not_done_reasons(readme, prefixes))


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help=f"fail if {OUTPUT} is not current")
    ap.add_argument("--stdout", action="store_true", help="print instead of writing")
    args = ap.parse_args(argv)
    doc = generate()
    path = os.path.join(ROOT, OUTPUT)
    if args.stdout:
        sys.stdout.write(doc)
        return 0
    if args.check:
        current = ""
        if os.path.exists(path):
            with open(path, encoding="utf-8") as f:
                current = f.read()
        if current == doc:
            print(f"{OUTPUT} is current")
            return 0
        diff = difflib.unified_diff(current.splitlines(), doc.splitlines(), OUTPUT, "generated", lineterm="")
        print("\n".join(list(diff)[:60]))
        print(f"{OUTPUT} is out of date: run python3 scripts/conformance.py and commit the result", file=sys.stderr)
        return 1
    with open(path, "w", encoding="utf-8") as f:
        f.write(doc)
    print(f"wrote {OUTPUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
