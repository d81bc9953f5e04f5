//! The `photosolid` command: a thin layer over the library.
//!
//! `run()` matches on the subcommand; the exit code is decided here only:
//! 0 success, 1 a file failed (validate) or a command failed, 2 usage errors (clap).

mod cli;

use clap::Parser;

fn main() {
    let args = cli::Cli::parse();
    let code = match cli::run(args) {
        Ok(code) => code,
        Err(e) => {
            // Broken pipe (e.g. `| head`) is not a failure.
            if let Some(io) = e.downcast_ref::<std::io::Error>() {
                if io.kind() == std::io::ErrorKind::BrokenPipe {
                    std::process::exit(0);
                }
            }
            eprintln!("photosolid: error: {e:#}");
            1
        }
    };
    std::process::exit(code);
}
