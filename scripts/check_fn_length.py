#!/usr/bin/env python3
"""Functions a reader can hold: no function in src/ longer than 80 lines, with a ratchet.

A function's length is counted from the line of its `fn` keyword to the line of its
closing brace, after comments and string literals are blanked (`check_layers.blank`).
Code under `#[cfg(test)]` is exempt (tests are read one at a time).

`scripts/fn_length_allowed.txt` lists the functions that were longer when the rule came
(one `src/FILE::NAME LINES` per line, `#` comments): each may stay at or below its recorded
length until it is split, and is then taken off the list. The check fails on
  - a function over the limit that is not listed, or one that grew past its recorded length;
  - a listed function that no longer exists or is now within the limit (take it off: the
    list only shrinks).
Usage: python3 scripts/check_fn_length.py [--root DIR] [--list]
  --list: print every function over the limit with its length (to write the allow list).
Exit 0: clean; 1: violations.
"""

import argparse
import importlib.util
import os
import re
import sys

LIMIT = 80
HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("check_layers", os.path.join(HERE, "check_layers.py"))
layers = importlib.util.module_from_spec(spec)
spec.loader.exec_module(layers)

FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def long_functions(root):
    """{`src/FILE::NAME`: lines} of every function over LIMIT outside #[cfg(test)] code.
    Two functions of one name in one file are told apart by a `#2`, `#3` suffix."""
    found = {}
    # the root package's src/ and every layer crate's crates/NAME/src/
    srcs = [os.path.join(root, "src")]
    crates = os.path.join(root, "crates")
    if os.path.isdir(crates):
        srcs += [os.path.join(crates, c, "src") for c in sorted(os.listdir(crates))]
    files_ = []
    for src in srcs:
        for dirpath, _, files in os.walk(src):
            files_ += [os.path.join(dirpath, f) for f in sorted(files) if f.endswith(".rs")]
    parsed = {}
    test_files = set()
    for path in files_:
        raw = open(path, encoding="utf-8").read()
        text = layers.blank(raw)
        spans, mods = layers.test_spans(text, raw)
        parsed[path] = (text, spans)
        # `#[cfg(test)] mod x;` makes x.rs (or x/mod.rs, or its #[path]) test code
        base = os.path.dirname(path)
        if os.path.basename(path) not in ("mod.rs", "lib.rs", "main.rs"):
            base = os.path.join(base, os.path.basename(path)[:-3])
        for m in mods:
            test_files.add(os.path.normpath(os.path.join(base, m if m.endswith(".rs") else m + ".rs")))
            test_files.add(os.path.normpath(os.path.join(base, m, "mod.rs")))
    for path in files_:
        if os.path.normpath(path) in test_files:
            continue
        if True:
            rel = os.path.relpath(path, root).replace(os.sep, "/")
            text, spans = parsed[path]
            seen = {}
            for m in FN.finditer(text):
                if any(a <= m.start() < b for a, b in spans):
                    continue
                end = layers.item_end(text, m.start())
                if end > len(text) or text[end - 1] != "}":
                    continue  # a declaration without a body (trait item)
                lines = text.count("\n", m.start(), end - 1) + 1
                name = m.group(1)
                seen[name] = seen.get(name, 0) + 1
                key = f"{rel}::{name}" + (f"#{seen[name]}" if seen[name] > 1 else "")
                if lines > LIMIT:
                    found[key] = lines
    return found


def read_allowed(root):
    allowed = {}
    path = os.path.join(HERE if root is None else os.path.join(root, "scripts"), "fn_length_allowed.txt")
    if not os.path.exists(path):
        return allowed
    for n, line in enumerate(open(path, encoding="utf-8"), 1):
        line = line.split("#", 1)[0].strip() if not line.lstrip().startswith("src/") else line.strip()
        if not line:
            continue
        parts = line.split()
        if len(parts) != 2 or not parts[1].isdigit():
            sys.exit(f"check_fn_length: {path}:{n}: expected `src/FILE::NAME LINES`, found {line!r}")
        allowed[parts[0]] = int(parts[1])
    return allowed


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default=os.path.dirname(HERE))
    ap.add_argument("--list", action="store_true")
    a = ap.parse_args()
    found = long_functions(a.root)
    if a.list:
        for k, v in sorted(found.items(), key=lambda kv: -kv[1]):
            print(f"{k} {v}")
        return 0
    allowed = read_allowed(a.root)
    bad = []
    for k, v in sorted(found.items()):
        if k not in allowed:
            bad.append(f"{k}: {v} lines (limit {LIMIT}): split it at its seams")
        elif v > allowed[k]:
            bad.append(f"{k}: {v} lines, grew past its recorded {allowed[k]} (limit {LIMIT}): split it")
    for k, v in sorted(allowed.items()):
        if k not in found:
            bad.append(f"{k}: listed in scripts/fn_length_allowed.txt but now within {LIMIT} lines or gone: take it off")
    for line in bad:
        print(line)
    print(
        f"check_fn_length: {len(found)} functions over {LIMIT} lines in src/ "
        f"({len(allowed)} on the shrinking allow list), {len(bad)} violations"
    )
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
