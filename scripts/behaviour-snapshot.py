#!/usr/bin/env python3
"""Snapshot what the commands say, to show that a refactor changes no behaviour.

    python3 scripts/behaviour-snapshot.py BIN OUT [--tradeoff]
    python3 scripts/behaviour-snapshot.py --diff OUT_BEFORE OUT_AFTER

Runs BIN (a `photosolid` binary) on every corpus file that `../shared/corpus/MANIFEST.tsv`
lists (`info --json`, `validate --json`, `compare --json`; with `--tradeoff` also
`tradeoff --json`, minutes more) and on the shipped scenes (`road --json`, `plan --json`,
`scene --json`), and writes each JSON document to OUT with the keys that come from
timings removed (`ns_per_*`, `pareto`, anything named after seconds or a time) and lists of
candidates sorted by their representation, keys sorted. An exit code and stderr are kept
for a command that fails, so a changed error shows too. `--diff` compares two snapshots
file by file and exits 1 on any difference.
"""
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus"
TIMING_WORDS = ("ns_per", "seconds", "time", "pareto", "elapsed", "_ms", "throughput")


def scrub(v):
    """The document without timing keys; candidate lists in a fixed order."""
    if isinstance(v, dict):
        return {k: scrub(x) for k, x in v.items() if not any(w in k for w in TIMING_WORDS)}
    if isinstance(v, list):
        items = [scrub(x) for x in v]
        if items and all(isinstance(x, dict) and "representation" in x for x in items):
            items.sort(key=lambda x: str(x["representation"]))
        return items
    return v


def run(bin_, args):
    r = subprocess.run([bin_, *args], capture_output=True, text=True, cwd=ROOT)
    try:
        doc = json.loads(r.stdout) if r.stdout.strip() else None
    except json.JSONDecodeError:
        doc = {"stdout": r.stdout}
    return {"exit": r.returncode, "json": scrub(doc), "stderr": r.stderr if r.returncode else ""}


def snapshot(bin_, out, tradeoff):
    out.mkdir(parents=True, exist_ok=True)
    files = []
    manifest = CORPUS / "MANIFEST.tsv"
    if manifest.is_file():
        for line in manifest.read_text().splitlines()[1:]:
            files.append(CORPUS / line.split("\t")[0])
    else:
        print(f"behaviour-snapshot: no corpus at {CORPUS}: the shipped data only", file=sys.stderr)
    files += sorted((ROOT / "data").glob("*.ldt")) + sorted((ROOT / "data").glob("*.ies"))
    jobs = []
    for f in files:
        name = str(f.relative_to(CORPUS if f.is_relative_to(CORPUS) else ROOT)).replace("/", "__")
        jobs += [(f"info__{name}", ["info", str(f), "--json"]),
                 (f"validate__{name}", ["validate", str(f), "--json"]),
                 (f"compare__{name}", ["compare", str(f), "--json"])]
        if tradeoff:
            jobs.append((f"tradeoff__{name}", ["tradeoff", str(f), "--json"]))
    for scene in sorted((ROOT / "data").glob("*.toml")):
        for cmd in ("road", "plan", "scene"):
            jobs.append((f"{cmd}__{scene.name}", [cmd, str(scene), "--json"]))
    for k, (name, args) in enumerate(jobs):
        (out / f"{name}.json").write_text(json.dumps(run(bin_, args), indent=1, sort_keys=True) + "\n")
        if k % 50 == 0:
            print(f"{k}/{len(jobs)} {name}", file=sys.stderr)
    print(f"behaviour-snapshot: {len(jobs)} documents in {out}", file=sys.stderr)


def diff(a, b):
    names = sorted({p.name for p in a.glob("*.json")} | {p.name for p in b.glob("*.json")})
    differing = [n for n in names if not (a / n).is_file() or not (b / n).is_file()
                 or (a / n).read_text() != (b / n).read_text()]
    for n in differing:
        print(f"differs: {n}")
    print(f"behaviour-snapshot: {len(names) - len(differing)}/{len(names)} documents identical")
    return 1 if differing else 0


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--diff":
        sys.exit(diff(Path(sys.argv[2]), Path(sys.argv[3])))
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    snapshot(sys.argv[1], Path(sys.argv[2]), "--tradeoff" in sys.argv[3:])
