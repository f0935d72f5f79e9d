//! The `rastray` command line: the terminal editor, headless rendering, scene info, benchmarks.

mod cli;

use std::io::Write;
use std::process::ExitCode;

use rastray::text_escape::Escaped;

fn main() -> ExitCode {
    let args = cli::parse();
    match cli::run(args) {
        Ok(code) => code,
        Err(error) => {
            // Messages quote names, paths and lines from files: their control characters are
            // escaped. stderr may be a terminal that has gone away: nothing to do about a failed
            // write.
            let message = format!("{error:#}");
            let _ = writeln!(std::io::stderr(), "error: {}", Escaped(&message));
            ExitCode::from(2)
        }
    }
}
