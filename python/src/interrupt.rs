//! Long calls that Ctrl-C interrupts: the work runs on a thread of its own
//! while the calling thread lets Python handle its signals every 0.1 s.

use std::sync::mpsc::{channel, RecvTimeoutError};
use std::time::Duration;

use pyo3::prelude::*;

/// How often the calling thread looks at Python's signals.
const POLL: Duration = Duration::from_millis(100);

/// Run `work` on a thread of its own and return its result; a Ctrl-C (or any
/// exception a signal handler raises) while it runs is raised here at once,
/// within [`POLL`]. The work is not stopped: it finishes in the background
/// and its result is dropped (a job of the library cannot be stopped midway;
/// a batch can, see `batch::interruptible`). So `work` owns what it uses.
pub(crate) fn detached<T: Send + 'static>(py: Python<'_>, work: impl FnOnce() -> T + Send + 'static) -> PyResult<T> {
    let (tx, rx) = channel();
    std::thread::Builder::new()
        .name("photosolid-job".into())
        .spawn(move || {
            // The receiver is gone when the call was interrupted: nothing to tell.
            let _ = tx.send(work());
        })
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    let mut rx = rx;
    loop {
        // The receiver is Send, not Sync: it goes into the GIL-free closure and comes back.
        let (received, back) = py.detach(move || (rx.recv_timeout(POLL), rx));
        rx = back;
        match received {
            Ok(out) => return Ok(out),
            Err(RecvTimeoutError::Timeout) => py.check_signals()?,
            Err(RecvTimeoutError::Disconnected) => {
                return Err(pyo3::exceptions::PyRuntimeError::new_err(
                    "a photosolid worker thread panicked (a bug)",
                ))
            }
        }
    }
}
