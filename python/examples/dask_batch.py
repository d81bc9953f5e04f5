"""Batch a catalogue over a Dask cluster: one Parquet dataset (a folder of part files) out.

The recipe of docs/scale.md. Each Dask partition is a shard of paths; a task runs the binding's
``photosolid.batch`` on its shard (the Rust code releases the GIL and runs the shard's files in parallel on the
worker's cores: set ``RAYON_NUM_THREADS`` to the cores per worker) and writes the shard's table to
``OUT/part-NNNNN.parquet``. ``pyarrow.parquet.read_table(OUT)`` (or ``dask.dataframe.read_parquet``) reads the
dataset back as one table, with the columns of ``photosolid batch`` (docs/batch.md).

Usage: python dask_batch.py OUT PATH... [--partitions N] [--workers N] [--scheduler ADDRESS]
(without --scheduler, a LocalCluster of --workers single-threaded worker processes is started).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Iterable, List, Sequence

import dask
import dask.bag as db
import pyarrow.parquet as pq


def list_files(paths: Iterable[str | os.PathLike]) -> List[str]:
    """Every photometry ``photosolid batch`` reads under ``paths``, in its order: the binding's own list (every
    format, extension-less files read by content, one ``FILE#ID`` per photometry of a GLDF container or TM-33
    document), so the dataset holds exactly the rows of ``photosolid batch``; listing happens on the client, once."""
    import photosolid

    return photosolid.list_inputs([os.fspath(p) for p in paths])


def write_shard(paths: Sequence[str], out_dir: str, index: int) -> int:
    """Run the binding's batch on one shard and write it as ``out_dir/part-INDEX.parquet``; returns its rows."""
    import photosolid  # imported on the worker

    table = photosolid.batch(list(paths))
    target = Path(out_dir) / f"part-{index:05d}.parquet"
    tmp = target.with_name(f".{target.name}.tmp")
    pq.write_table(table, tmp, compression="snappy")
    os.replace(tmp, target)  # atomic: a reader sees the whole part or none
    return table.num_rows


def batch_dataset(paths: Sequence[str], out_dir: str | os.PathLike, npartitions: int) -> int:
    """Batch ``paths`` as ``npartitions`` Dask tasks into the Parquet dataset ``out_dir``; returns the rows written.
    Runs on the current Dask client (or the local scheduler when none)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    bag = db.from_sequence(list(paths), npartitions=npartitions)
    tasks = [dask.delayed(write_shard)(part, str(out), i) for i, part in enumerate(bag.to_delayed())]
    return sum(dask.compute(*tasks))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("paths", nargs="+")
    ap.add_argument("--partitions", type=int, default=None, help="default: 4 per worker")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--scheduler", default=None)
    a = ap.parse_args()
    from dask.distributed import Client, LocalCluster

    files = list_files(a.paths)
    if a.scheduler:
        client = Client(a.scheduler)
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, env={"RAYON_NUM_THREADS": "1"})
        client = Client(cluster)
    with client:
        n = batch_dataset(files, a.out, a.partitions or 4 * a.workers)
    print(f"{n} rows written to {a.out}")


if __name__ == "__main__":
    main()
