//! The `photosolid` command: a thin layer over the library.
//!
//! `run()` matches on the subcommand; the exit code is decided here only:
//! 0 success (also when stdout is closed early, e.g. `| head`), 1 a file failed (validate)
//! or a command failed, 2 usage errors (clap's, and [`cli::UsageError`]).

mod cli;

fn main() {
    let args = cli::parse();
    // Mesa's drivers print "error: XDG_RUNTIME_DIR is invalid or not set" on every
    // GPU run without one: give them a private directory, removed at exit.
    let runtime_dir = cli::runtime_dir::ensure();
    let code = match cli::run(args) {
        Ok(code) => code,
        // A closed stdout (e.g. `| head`) is not a failure: stop quietly, as Unix tools do.
        Err(e) if is_broken_pipe(&e) => 0,
        // A value clap could not check alone (a range outside its key's values): a usage error.
        Err(e) if e.downcast_ref::<cli::UsageError>().is_some() => {
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
