//! The `photosolid` command: a thin layer over the library.
//!
//! `run()` matches on the subcommand; the exit code is decided here only:
//! 0 success (also when stdout is closed early, e.g. `| head`), 1 a file failed (validate)
//! or a command failed, 2 usage errors (clap's, [`cli::UsageError`], and the options a library job
//! could not use: `Error::Option`, `RoadError::Option`).

mod cli;

fn main() {
    let args = cli::parse();
    // Mesa's drivers print "error: XDG_RUNTIME_DIR is invalid or not set" on every
    // GPU run without one: give them a private directory, removed at exit.
    let runtime_dir = cli::runtime_dir::ensure();
    // The GPU is plugged in here, at start-up: the library's layers ask for the installed device.
    #[cfg(feature = "gpu")]
    photosolid::gpu::install();
    let code = match cli::run(args) {
        Ok(code) => code,
        // A closed stdout (e.g. `| head`) is not a failure: stop quietly, as Unix tools do.
        Err(e) if is_broken_pipe(&e) => 0,
        // A value clap could not check alone (a range outside its key's values): a usage error.
        Err(e) if is_usage_error(&e) => {
            eprintln!("photosolid: error: {}", error_message(&e));
            2
        }
        Err(e) => {
            eprintln!("photosolid: error: {}", error_message(&e));
            1
        }
    };
    drop(runtime_dir);
    std::process::exit(code);
}

/// Whether `e` is a usage error: the CLI's own, or an option a library job
/// could not use as given (a range outside its key's values, `--align` without `--vs`).
fn is_usage_error(e: &anyhow::Error) -> bool {
    use photosolid::jobs::JobError;
    use photosolid::scene::road::RoadError;
    e.downcast_ref::<cli::UsageError>().is_some()
        || matches!(
            e.downcast_ref::<photosolid::Error>(),
            Some(photosolid::Error::Option { .. })
        )
        || matches!(e.downcast_ref::<RoadError>(), Some(RoadError::Option { .. }))
        || matches!(
            e.downcast_ref::<JobError>(),
            Some(JobError::Road(RoadError::Option { .. }) | JobError::Library(photosolid::Error::Option { .. }))
        )
}

/// The error and its causes joined by ": ", each cause once: a cause whose
/// text the message already holds (an I/O error that a path error also
/// displays) is not repeated.
fn error_message(e: &anyhow::Error) -> String {
    let mut msg = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if msg.contains(&text) {
            continue;
        }
        if !msg.is_empty() {
            msg.push_str(": ");
        }
        msg.push_str(&text);
    }
    msg
}

/// Whether `e` comes from writing to a closed pipe, at any depth of its chain
/// (a plain write, a JSON serialiser's write, a library I/O error).
fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .map(std::io::Error::kind)
            .or_else(|| {
                c.downcast_ref::<serde_json::Error>()
                    .and_then(serde_json::Error::io_error_kind)
            })
            == Some(std::io::ErrorKind::BrokenPipe)
    })
}
