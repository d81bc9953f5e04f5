//! Batches: the listing and the table of `photosolid batch`, interruptible.

use std::path::PathBuf;
use std::sync::atomic::Ordering;

use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::errors::py_err;
use crate::read_options;

/// The batch table of every input under `paths` (.ies, .ldt, TM-33 .xml,
/// .gldf, files read by content) (as `photosolid
/// batch PATHS -o OUT.parquet`, with `compact` as `--compact`) as Parquet
/// bytes; `photosolid.batch` reads them into a `pyarrow.Table`.
#[pyfunction]
#[pyo3(signature = (paths, compact = false, *, repair = false, handedness = "ccw", lamp_sets = "first", front = None, progress = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn batch_parquet<'py>(
    py: Python<'py>,
    paths: Vec<PathBuf>,
    compact: bool,
    repair: bool,
    handedness: &str,
    lamp_sets: &str,
    front: Option<f64>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyBytes>> {
    let read = read_options(repair, handedness, lamp_sets, front)?;
    let files = py.detach(|| photosolid::batch::collect(&paths)).map_err(py_err)?;
    let options = photosolid::batch::BatchOptions {
        compact,
        read,
        ..Default::default()
    };
    let done = std::sync::atomic::AtomicUsize::new(0);
    let stop = std::sync::atomic::AtomicBool::new(false);
    let report = |n: usize| -> PyResult<()> {
        match &progress {
            Some(callback) => callback.call1((n, files.len())).map(drop),
            None => Ok(()),
        }
    };
    let rows = interruptible(
        py,
        || photosolid::batch::run_until(&files, &options, &|d, _, _| done.store(d, Ordering::Relaxed), &stop),
        &stop,
        || report(done.load(Ordering::Relaxed)),
    )?;
    let Some(rows) = rows else {
        return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err("batch stopped"));
    };
    report(files.len())?;
    let bytes = py
        .detach(|| photosolid::batch::table::parquet_bytes(&rows))
        .map_err(py_err)?;
    Ok(PyBytes::new(py, &bytes))
}

/// Run `work` on a thread of its own while this one, every 0.1 s, lets
/// Python handle its signals (a Ctrl-C raises `KeyboardInterrupt` here) and
/// calls `tick` (progress). On an exception `stop` is set, so `work` stops
/// starting new items, and the exception is raised once `work` returns
/// (within the items already started: a file of a batch, not the batch).
pub(crate) fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send,
    stop: &std::sync::atomic::AtomicBool,
    mut tick: impl FnMut() -> PyResult<()>,
) -> PyResult<T> {
    std::thread::scope(|s| {
        let handle = s.spawn(work);
        let mut failure: Option<PyErr> = None;
        while !handle.is_finished() {
            py.detach(|| {
                for _ in 0..20 {
                    if handle.is_finished() {
                        break;
                    }
                    std::thread::sleep(std::time::Duration::from_millis(5));
                }
            });
            if failure.is_none() {
                if let Err(e) = py.check_signals().and_then(|()| tick()) {
                    stop.store(true, Ordering::Relaxed);
                    failure = Some(e);
                }
            }
        }
        let out = py
            .detach(|| handle.join())
            .map_err(|_| pyo3::exceptions::PyRuntimeError::new_err("a photosolid worker thread panicked (a bug)"))?;
        match failure {
            Some(e) => Err(e),
            None => Ok(out),
        }
    })
}

/// Every photometry `photosolid batch PATHS` reads, in its order: files named
/// explicitly whatever their extension, and below each directory the .ies,
/// .ldt, TM-33 .xml and .gldf files and the extension-less files read by
/// content; a GLDF container or a TM-33 document with several photometries as
/// one `FILE#ID` path each. The one list of `batch` (the library's
/// `batch::collect`), for recipes that shard it.
#[pyfunction]
pub(crate) fn list_inputs(py: Python<'_>, paths: Vec<PathBuf>) -> PyResult<Vec<String>> {
    let files = py.detach(|| photosolid::batch::collect(&paths)).map_err(py_err)?;
    Ok(files.iter().map(|p| p.display().to_string()).collect())
}
