"""The bindings release the GIL around their Rust work: another Python thread keeps running while a
binding call computes.

Method: a worker thread runs one long `Luminaire.sample` call (single-threaded Rust: one Catmull-Rom evaluation per
point, sized to last about a second) while the main thread spins a counter and records the time of every
iteration. Two measures, each with its reason:

- the longest pause of the main loop while the call runs. If the call held the GIL, the main thread could not
  execute a single bytecode until it returned: one pause as long as the Rust work itself (nearly the whole call,
  the Python-side array conversion being a small part of it). Released, the pauses are the interpreter's switch
  interval (`sys.getswitchinterval()`, 5 ms) plus the OS scheduler's noise on a busy machine (tens of ms). The
  threshold, half the call's duration (≥ 250 ms as the call lasts ≥ 0.5 s), sits between the two by an order of
  magnitude either way.
- the counter's progress during the call against its rate alone (measured just before): with the GIL held it
  advances only while the worker runs Python-side code (copying the inputs: 160 MB for 10 M points, tens of ms
  at memory bandwidth, against a call of a second or more: under 5 %); released, at its solo rate, or a third to
  a half of it where the worker, the main thread and other jobs share the cores (33 % measured on the 2-core
  machine while two other builds ran).
  Threshold: 10 % of the solo rate.

The last tests send SIGINT to a batch and to other long calls running in a subprocess: each raises
KeyboardInterrupt instead of running to its end.
"""

from __future__ import annotations

import os
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import photosolid

ROOT = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
DATA = ROOT / "data"
TARGET_S = 1.0   # how long the Rust call should take
MIN_S = 0.5      # below this the measurement says too little: the test fails rather than pass vacuously


def _angles(n: int, seed: int = 3):
    rng = np.random.default_rng(seed)
    return rng.uniform(0.0, 360.0, n), rng.uniform(0.0, 180.0, n)


def _counter_rate(seconds: float = 0.3) -> float:
    """Iterations per second of the main loop below, with nothing else running."""
    n, t0 = 0, time.perf_counter()
    while (t := time.perf_counter()) - t0 < seconds:
        n += 1
    return n / (t - t0)


def test_the_gil_is_released_while_rust_samples():
    lum = photosolid.load(DATA / "roadway.ldt")
    # Size the call: time a small one, scale to TARGET_S (capped at 20 M points: 320 MB of input).
    c, g = _angles(50_000)
    t0 = time.perf_counter()
    lum.sample("catmull-rom", c, g)
    per_point = (time.perf_counter() - t0) / c.size
    n = int(min(20_000_000, max(50_000, TARGET_S / per_point)))
    c, g = _angles(n)

    rate = _counter_rate()
    span = {}
    done = threading.Event()

    def work():
        span["start"] = time.perf_counter()
        lum.sample("catmull-rom", c, g)
        span["end"] = time.perf_counter()
        done.set()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
    worker.join()
    start, end = span["start"], span["end"]
    elapsed = end - start
    assert elapsed >= MIN_S, f"the call took {elapsed:.3f} s for {n} points: too short to measure"

    during = np.array([t for t in ticks if start <= t <= end])
    edges = np.concatenate([[start], during, [end]])
    longest_pause = np.diff(edges).max()
    assert longest_pause < 0.5 * elapsed, (
        f"the main thread stood still for {longest_pause:.3f} s of a {elapsed:.3f} s call: the GIL was held"
    )
    progress = during.size / (rate * elapsed)
    assert progress > 0.1, (
        f"the counter advanced {during.size} times during the {elapsed:.3f} s call, {progress:.1%} of its solo rate "
        f"({rate:.3g}/s): the GIL was held"
    )
    print(f"call {elapsed:.3f} s ({n} points); longest main-thread pause {longest_pause * 1e3:.1f} ms; "
          f"counter at {progress:.0%} of its solo rate")


def test_ctrl_c_stops_a_batch_and_progress_is_reported(tmp_path):
    """SIGINT during ``photosolid.batch`` raises KeyboardInterrupt in the middle of the batch: the progress callback
    (called about ten times a second) last saw fewer files done than the total, and the interpreter exits with the
    interrupt; the latency from the signal to the exit is printed. Without a signal the callback ends at
    (total, total)."""
    import signal
    import sys
    import time

    root = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
    binary = os.environ.get("PHOTOSOLID_BIN", str(root / "target" / "debug" / "photosolid"))
    files = tmp_path / "files"
    subprocess.run(["bash", str(root / "scripts" / "make-bulk.sh"), "300", str(files)], check=True,
                   env={**os.environ, "PHOTOSOLID_BIN": binary})
    import photosolid

    seen = []
    some = sorted(p for p in files.rglob("*") if p.is_file())[:20]
    photosolid.batch(some, progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1][0] == seen[-1][1]
    script = (
        "import sys, photosolid\n"
        "def p(done, total):\n"
        "    print(f'{done} {total}', flush=True)\n"
        f"photosolid.batch([{str(files)!r}], compact=True, progress=p)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    first = proc.stdout.readline()  # the first progress report: the batch is running
    assert first.split()[1] == "300", first
    time.sleep(0.5)
    t0 = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    latency = time.perf_counter() - t0
    lines = [first] + out.splitlines()
    done, total = map(int, lines[-1].split())
    assert "KeyboardInterrupt" in err, err[-2000:]
    assert proc.returncode != 0
    assert done < total, lines[-3:]
    print(f"\nCtrl-C: batch of {total} files (compact) stopped after {done}; {latency:.2f} s from SIGINT to exit")


CALLS = {
    "tradeoff": "photosolid.tradeoff(lum, repeats=200)",
    "compare": "lum.compare(recons='measured,catmull-rom,sh:16,lobes:4', against='withheld', folds=12)",
    "sample_dirs": "lum.sample_dirs('measured', np.tile([[0.3, 0.2, -1.0]], (8_000_000, 1)))",
}


@pytest.mark.parametrize("call", sorted(CALLS))
def test_ctrl_c_interrupts_a_long_call(call):
    """SIGINT one second into a long call (a tradeoff, a compare, sampling millions of directions) raises
    KeyboardInterrupt in the calling thread: the call does not return. The latency from the signal to the
    process's exit is printed."""
    import signal
    import sys
    import time

    root = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
    script = (
        "import numpy as np, photosolid\n"
        f"lum = photosolid.load({str(root / 'data' / 'roadway.ldt')!r})\n"
        "print('go', flush=True)\n"
        f"{CALLS[call]}\n"
        "print('returned', flush=True)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    assert proc.stdout.readline().strip() == "go"
    time.sleep(1.0)
    t0 = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=300)
    latency = time.perf_counter() - t0
    assert "returned" not in out, f"{call} finished within a second: not a long call"
    assert "KeyboardInterrupt" in err, err[-2000:]
    print(f"\nCtrl-C: {call} interrupted; {latency:.2f} s from SIGINT to exit")
