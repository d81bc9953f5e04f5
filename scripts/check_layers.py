#!/usr/bin/env python3
"""Layers only point down: fail on any path from one top-level module of src/ to a higher one.

The order is read from ARCHITECTURE.md, the fenced block tagged `layers` (one module per
line, lowest first; text after `#` is a comment). It is the one source of truth: this script
holds no list of its own.

Every `src/**/*.rs` file belongs to the top-level module of its path (`src/solid/grid.rs`
-> `solid`; `src/main.rs` -> `cli`, the binary; `src/lib.rs` is the crate root, whose
re-exports are resolved instead of checked). In each file, after comments and string
literals are blanked out, these name another module:
  - `crate::m` paths anywhere: `use` lines, grouped imports (`use crate::{a, b::c}`,
    nested groups) and inline paths in code (`crate::m::f(x)`), `$crate::m` in macros;
  - `super::` chains that climb out of the file's top-level module (`super::super::m` in
    `src/a/b.rs`);
  - root re-exports (`crate::Luminaire`) count as the module lib.rs re-exports them from.
A file in module A may name module B when B is A or B is lower in the order. Code under
`#[cfg(test)]` (an item, an inline `mod tests { .. }`, or a file declared as
`#[cfg(test)] mod x;`) is exempt. Doc comments are comments: their links are not checked.

Usage: python3 scripts/check_layers.py [--root DIR]     (exit 0: clean; 1: violations; 2: usage)
Each violation is one line: `src/FILE:LINE: A -> B (path), B is above A in the layer order`.
"""

import argparse
import os
import re
import sys

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
CFG_TEST = re.compile(r"#\[cfg\((?:all\((?:[^\]]*,\s*)?)?test\b")


def read_order(root):
    """The layer order from ARCHITECTURE.md's ```layers block, lowest first."""
    path = os.path.join(root, "ARCHITECTURE.md")
    try:
        text = open(path, encoding="utf-8").read()
    except OSError as e:
        sys.exit(f"check_layers: cannot read {path}: {e}")
    m = re.search(r"^```layers[ \t]*\n(.*?)^```", text, re.M | re.S)
    if not m:
        sys.exit(f"check_layers: {path} has no ```layers block")
    order = []
    for line in m.group(1).splitlines():
        name = line.split("#", 1)[0].strip()
        if name:
            if not re.fullmatch(IDENT, name) or name in order:
                sys.exit(f"check_layers: bad or repeated layer name {name!r} in {path}")
            order.append(name)
    return order


def blank(text):
    """Comments, string and char literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)

    def keep_newlines(s):
        return "".join(c if c == "\n" else " " for c in s)

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(keep_newlines(text[i:j]))
            i = j
        elif (m := re.compile(r'b?r(#*)"').match(text, i)) and (
            i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")
        ):
            end = '"' + m.group(1)
            j = text.find(end, m.end())
            j = n if j < 0 else j + len(end)
            out.append(keep_newlines(text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(keep_newlines(text[i:j]))
            i = j
        elif c == "'":
            # A char literal ('a', '\n', '\u{1F600}') or a lifetime ('a).
            m = re.compile(r"'(?:\\(?:u\{[0-9a-fA-F]*\}|x..|.)|[^\\'\n])'").match(text, i)
            if m:
                out.append(" " * (m.end() - i))
                i = m.end()
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def item_end(text, start):
    """Index just past the item that begins at `start` (after its attributes)."""
    depth = 0  # () and [] depth
    i, n = start, len(text)
    while i < n:
        c = text[i]
        if c in "([":
            depth += 1
        elif c in ")]":
            depth -= 1
        elif c == ";" and depth == 0:
            return i + 1
        elif c == "{" and depth == 0:
            braces = 0
            while i < n:
                if text[i] == "{":
                    braces += 1
                elif text[i] == "}":
                    braces -= 1
                    if braces == 0:
                        return i + 1
                i += 1
            return n
        i += 1
    return n


def test_spans(text, raw):
    """(start, end) spans of items under #[cfg(test)] in `text` (blanked `raw`), and the
    files of the `mod x;` among them (a `#[path]` attribute's, else `x`)."""
    spans, mods = [], []
    for m in CFG_TEST.finditer(text):
        # Skip this attribute and any that follow it, then the item.
        i = m.start()
        while True:
            i = item_end_attr(text, i)
            k = len(text) - len(text[i:].lstrip())
            if text.startswith("#[", k):
                i = k
                continue
            i = k
            break
        end = item_end(text, i)
        spans.append((m.start(), end))
        mm = re.match(rf"(?:pub(?:\([^)]*\))?\s+)?mod\s+({IDENT})\s*;", text[i:end])
        if mm:
            path_attr = re.search(r'#\[path\s*=\s*"([^"]*)"\]', raw[m.start():i])
            mods.append(path_attr.group(1) if path_attr else mm.group(1))
    return spans, mods


def item_end_attr(text, i):
    """Index just past the attribute `#[...]` at i."""
    depth = 0
    j = i + 1
    while j < len(text):
        if text[j] == "[":
            depth += 1
        elif text[j] == "]":
            depth -= 1
            if depth == 0:
                return j + 1
        j += 1
    return len(text)


def group_heads(text, i):
    """First segments of each entry of the group `{...}` at text[i]; returns (heads, end)."""
    heads = []
    depth = 0
    expect = False
    j = i
    while j < len(text):
        c = text[j]
        if c == "{":
            depth += 1
            if depth == 1:
                expect = True
        elif c == "}":
            depth -= 1
            if depth == 0:
                return heads, j + 1
        elif c == "," and depth == 1:
            expect = True
        elif expect and not c.isspace():
            m = re.compile(IDENT).match(text, j)
            if m:
                heads.append((m.group(0), j))
                j = m.end()
                expect = False
                continue
            expect = False
        j += 1
    return heads, len(text)


PATH = re.compile(r"(?<![A-Za-z0-9_:$])(\$?crate\s*::\s*|photosolid_core\s*::\s*|(?:super\s*::\s*)+)")


def chain(text, j):
    """The path `ident::ident::...` that starts at j (without a trailing `::`)."""
    m = re.compile(rf"{IDENT}(?:\s*::\s*{IDENT})*").match(text, j)
    if not m:
        return ""
    rest = re.compile(r"\s*::\s*\{").match(text, m.end())
    return re.sub(r"\s+", "", m.group(0)) + ("::{..}" if rest else "")


def references(text):
    """(offset, kind, climb, head, path) for every crate:: or super:: path; kind 'crate' or 'super'."""
    refs = []
    for m in PATH.finditer(text):
        word = m.group(1)
        j = m.end()
        if "crate" in word or "photosolid_core" in word:
            kind, climb = "crate", 0
        else:
            kind, climb = "super", word.count("super")
        prefix = "crate::" if kind == "crate" else "super::" * climb
        if j < len(text) and text[j] == "{":
            heads, _ = group_heads(text, j)
            refs.extend((off, kind, climb, h, prefix + "{" + chain(text, off) + "}") for h, off in heads)
        else:
            mm = re.compile(IDENT).match(text, j)
            if mm:
                refs.append((m.start(), kind, climb, mm.group(0), prefix + chain(text, j)))
    return refs


def root_reexports(src):
    """name -> module for the crate root's `pub use m::{...}` re-exports."""
    out = {}
    try:
        text = blank(open(os.path.join(src, "lib.rs"), encoding="utf-8").read())
    except OSError:
        return out
    for m in re.finditer(rf"pub\s+use\s+({IDENT})\s*::\s*(\{{[^}}]*\}}|{IDENT})", text):
        module, names = m.group(1), m.group(2)
        for name in re.findall(IDENT, names):
            # `pub use photosolid_core::{model, ..}`: a layer crate's module of the same name;
            # its other re-exports (`Error`, `Luminaire`) resolve as the root's own do
            if module.startswith("photosolid_"):
                if name[:1].islower():
                    out[name] = name
            else:
                out[name] = module
    return out


def module_path(rel):
    """Module path of a file relative to src/, e.g. solid/grid.rs -> ['solid', 'grid']."""
    parts = rel[:-3].split("/")
    if parts[-1] == "mod":
        parts.pop()
    if parts == ["main"]:
        return ["cli"]
    return parts


def check(root):
    order = read_order(root)
    rank = {m: i for i, m in enumerate(order)}
    src = os.path.join(root, "src")
    reexports = root_reexports(src)
    # The root package's src/ and each layer crate's crates/NAME/src/: a file's module is
    # its path under its own src/ (the layer crates hold modules of the same order).
    roots = [src]
    crates = os.path.join(root, "crates")
    # A crate named photosolid-LAYER is that one layer (crates/photosolid-gpu is `gpu`): cargo
    # already keeps it from naming anything above it (it depends only on lower crates), so its
    # files are not read, only counted as the layer present.
    whole_layers = set()
    if os.path.isdir(crates):
        for c in sorted(os.listdir(crates)):
            if not os.path.isdir(os.path.join(crates, c, "src")):
                continue
            layer = c.removeprefix("photosolid-")
            if layer in rank:
                whole_layers.add(layer)
            else:
                roots.append(os.path.join(crates, c, "src"))
    files, rel_of = [], {}
    for base in roots:
        for dirpath, _, names in os.walk(base):
            for name in names:
                if name.endswith(".rs"):
                    full = os.path.join(dirpath, name)
                    key = os.path.relpath(full, root).replace(os.sep, "/")
                    files.append(key)
                    rel_of[key] = os.path.relpath(full, base).replace(os.sep, "/")
    files.sort()
    raws = {f: open(os.path.join(root, f), encoding="utf-8").read() for f in files}
    texts = {f: blank(raws[f]) for f in files}
    # Files declared `#[cfg(test)] mod x;` are test code as a whole.
    test_files = set()
    spans_of = {}
    for f in files:
        spans, mods = test_spans(texts[f], raws[f])
        spans_of[f] = spans
        d = os.path.dirname(f)
        own = d if os.path.basename(f) in ("mod.rs", "lib.rs", "main.rs") else f[:-3]
        for m in mods:
            if m.endswith(".rs"):
                test_files.add(os.path.normpath(os.path.join(d, m)).replace(os.sep, "/"))
            else:
                test_files.add(f"{own}/{m}.rs".lstrip("/"))
                test_files.add(f"{own}/{m}/mod.rs".lstrip("/"))
    violations = []
    tops = sorted({module_path(rel_of[f])[0] for f in files if rel_of[f] != "lib.rs"})
    for top in tops:
        if top not in rank:
            violations.append(f"src/{top}: module {top} is not in the layer order (ARCHITECTURE.md)")
    for name in order:
        if name not in tops and name not in whole_layers:
            violations.append(f"ARCHITECTURE.md: layer {name} is no module of src/")
    for f in files:
        if rel_of[f] == "lib.rs" or f in test_files:
            continue
        path = module_path(rel_of[f])
        top = path[0]
        if top not in rank:
            continue
        text = texts[f]
        for off, kind, climb, head, shown in references(text):
            if any(a <= off < b for a, b in spans_of[f]):
                continue
            if kind == "crate":
                target = reexports.get(head, head)
            else:
                # Inline `mod x { }` blocks deepen the path; count those enclosing off.
                depth = len(path) + inline_mod_depth(text, off)
                if climb < depth:
                    continue
                target = head
            if target in ("self", "super", "crate") or target == top:
                continue
            where = f"{f}:{text.count(chr(10), 0, off) + 1}"
            if target not in rank:
                violations.append(f"{where}: {top} -> {target} ({shown}): {target} is not in the layer order")
            elif rank[target] > rank[top]:
                violations.append(f"{where}: {top} -> {target} ({shown}): {target} is above {top} in the layer order")
    return order, files, violations


def inline_mod_depth(text, off):
    """How many inline `mod x { ... }` blocks enclose offset off."""
    depth = 0
    for m in re.finditer(rf"\bmod\s+{IDENT}\s*\{{", text[:off]):
        if item_end(text, m.start()) > off:
            depth += 1
    return depth


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    args = ap.parse_args()
    order, files, violations = check(args.root)
    for v in violations:
        print(v)
    if violations:
        print(f"check_layers: {len(violations)} path(s) point up the layer order ({' < '.join(order)})")
        return 1
    print(f"check_layers: {len(files)} files, layers only point down ({' < '.join(order)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
