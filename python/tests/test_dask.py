"""The Dask recipe (docs/scale.md, python/examples/dask_batch.py) on a LocalCluster of 2 worker processes over a
bulk-size catalogue made from the project's own data (scripts/make-bulk.sh): the Parquet dataset it writes holds
exactly the rows of ``photosolid batch`` on the same files (timings aside).

PHOTOSOLID_BULK_N sets the number of files (default 400; BENCHMARKS.md uses 8000).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pyarrow.parquet as pq
import pytest

ROOT = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
BIN = os.environ.get("PHOTOSOLID_BIN", str(ROOT / "target" / "debug" / "photosolid"))
sys.path.insert(0, str(ROOT / "python" / "examples"))

import dask_batch  # noqa: E402

TIMING = {"parse_ms", "holdout_ms", "fit_ms"}


@pytest.fixture(scope="module")
def bulk(tmp_path_factory):
    n = int(os.environ.get("PHOTOSOLID_BULK_N", "400"))
    d = tmp_path_factory.mktemp("bulk")
    subprocess.run(["bash", str(ROOT / "scripts" / "make-bulk.sh"), str(n), str(d / "files")], check=True,
                   env={**os.environ, "PHOTOSOLID_BIN": BIN})
    return n, d


def test_dask_dataset_equals_the_cli_table(bulk):
    from dask.distributed import Client, LocalCluster

    n, d = bulk
    files = dask_batch.list_files([d / "files"])
    assert len(files) == n
    t0 = time.perf_counter()
    subprocess.run([BIN, "batch", str(d / "files"), "-o", str(d / "cli.parquet")], check=True, capture_output=True)
    t_cli = time.perf_counter() - t0
    cli = pq.read_table(d / "cli.parquet")
    # The client lists the files in the CLI's order.
    assert cli["path"].to_pylist() == files

    with LocalCluster(n_workers=2, threads_per_worker=1, env={"RAYON_NUM_THREADS": "1"},
                      dashboard_address=None) as cluster, Client(cluster):
        t0 = time.perf_counter()
        rows = dask_batch.batch_dataset(files, d / "dataset", npartitions=8)
        t_dask = time.perf_counter() - t0
    assert rows == n
    parts = sorted(p.name for p in (d / "dataset").iterdir())
    # from_sequence makes at most 8 partitions of equal size (ceil(n / 8) paths each): one part file each.
    assert parts == [f"part-{i:05d}.parquet" for i in range(-(-n // -(-n // 8)))]
    ds = pq.read_table(d / "dataset").sort_by("path")
    cli = cli.sort_by("path")
    assert ds.schema.names == cli.schema.names
    for name in cli.column_names:
        if name not in TIMING:
            assert ds[name].to_pylist() == cli[name].to_pylist(), name
    # One file in 100 is truncated by make-bulk.sh: a row with ok False and an error each, not a failed batch.
    not_ok = [r for r in ds.to_pylist() if not r["ok"]]
    assert len(not_ok) == n // 100
    assert all(r["errors"] for r in not_ok)
    print(f"\n{n} files: photosolid batch {n / t_cli:.1f} files/s, Dask 2 workers {n / t_dask:.1f} files/s")


def test_dask_reads_every_input_batch_reads(catalogue, tmp_path):
    """The recipe on a folder of every kind of input (.ies, .ldt, no extension, TM-33, a GLDF container of two
    photometries): the dataset holds exactly the rows of ``photosolid batch`` on that folder, value for value."""
    from dask.distributed import Client, LocalCluster

    subprocess.run([BIN, "batch", str(catalogue), "-o", str(tmp_path / "cli.parquet")], check=True,
                   capture_output=True)
    cli = pq.read_table(tmp_path / "cli.parquet")
    files = dask_batch.list_files([catalogue])
    assert files == cli["path"].to_pylist() and len(files) == 6
    with LocalCluster(n_workers=2, threads_per_worker=1, env={"RAYON_NUM_THREADS": "1"},
                      dashboard_address=None) as cluster, Client(cluster):
        rows = dask_batch.batch_dataset(files, tmp_path / "dataset", npartitions=3)
    assert rows == cli.num_rows
    ds = pq.read_table(tmp_path / "dataset").sort_by("path")
    cli = cli.sort_by("path")
    for name in cli.column_names:
        if name not in TIMING:
            assert ds[name].to_pylist() == cli[name].to_pylist(), name
    assert all(ds["ok"].to_pylist())
