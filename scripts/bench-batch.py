"""Times photosolid batch vs the Dask recipe on N bulk files (BENCHMARKS.md, "Catalogue batches").
Usage: .venv-notebooks/bin/python scripts/bench-batch.py [N]   (from the repository root; PHOTOSOLID_BIN: the CLI)
Prints one JSON line: files/s of both runs and the summed per-file CPU time of parse, hold-out and fit."""
import os, sys, time, subprocess, json, tempfile
sys.path.insert(0, "python/examples")
import dask_batch, pyarrow.parquet as pq, pyarrow.compute as pc
from dask.distributed import Client, LocalCluster
BIN = os.environ.get("PHOTOSOLID_BIN", "target/debug/photosolid"); N = sys.argv[1] if len(sys.argv) > 1 else "8000"; d = tempfile.mkdtemp()
def main():

    t=time.perf_counter(); subprocess.run(["bash","scripts/make-bulk.sh",N,d+"/files"],check=True,stderr=subprocess.DEVNULL); print("make", time.perf_counter()-t)
    files = dask_batch.list_files([d+"/files"])
    t=time.perf_counter(); subprocess.run([BIN,"batch",d+"/files","-o",d+"/cli.parquet"],check=True); tc=time.perf_counter()-t
    t=time.perf_counter(); subprocess.run([BIN,"validate",d+"/files"],stdout=subprocess.DEVNULL); tv=time.perf_counter()-t
    cli = pq.read_table(d+"/cli.parquet")
    s = {k: pc.sum(cli[k]).as_py()/1e3 for k in ["parse_ms","holdout_ms","fit_ms"]}
    with LocalCluster(n_workers=2, threads_per_worker=1, env={"RAYON_NUM_THREADS":"1"}, dashboard_address=":0") as c, Client(c):
        t=time.perf_counter(); n = dask_batch.batch_dataset(files, d+"/dataset", 16); td=time.perf_counter()-t
    print(json.dumps({"files":len(files),"cli_s":tc,"cli_files_per_s":len(files)/tc,"validate_s":tv,"dask_s":td,"dask_files_per_s":n/td,"cpu_s":s,"bytes":int(subprocess.check_output(["du","-sb",d+"/files"]).split()[0]),"load":os.getloadavg()}))
    subprocess.run(["rm", "-rf", d])
    
if __name__ == "__main__":
    main()
