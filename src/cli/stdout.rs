//! Lines on standard output, written as a well-behaved filter writes them: when the reader has
//! gone (`rastray info … | head -1`), the command ends quietly, killed by SIGPIPE as `cat` and
//! `ls` are; when the output cannot take the bytes (`> /dev/full`), it ends with an `error:` line
//! and exit code 2. Never a panic.

use std::fmt::Arguments;
use std::io::{ErrorKind, Write};

use rastray::text_escape::Escaped;

/// Writes `text` and a newline to standard output, or ends the process as described above.
pub fn line(text: Arguments) {
    bytes(format!("{text}\n").as_bytes());
}

/// Writes `bytes` to standard output and flushes them, or ends the process as described above.
pub fn bytes(bytes: &[u8]) {
    let result = {
        let mut out = std::io::stdout().lock();
        out.write_all(bytes).and_then(|()| out.flush())
    };
    if let Err(error) = result {
        end_on_write_error(&error);
    }
}

/// Ends the process after standard output failed with `error`.
fn end_on_write_error(error: &std::io::Error) -> ! {
    if error.kind() == ErrorKind::BrokenPipe {
        // Rust ignores SIGPIPE; restore its default action and raise it, so the shell sees the
        // same ending as for any other filter whose reader left.
        let _ = signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGPIPE);
        std::process::exit(141);
    }
    let message = format!("cannot write to standard output: {error}");
    let _ = writeln!(std::io::stderr(), "error: {}", Escaped(&message));
    std::process::exit(2);
}

/// `println!` for the command line's reports: see the module's doc.
macro_rules! outln {
    () => {
        $crate::cli::stdout::line(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::cli::stdout::line(format_args!($($arg)*))
    };
}
pub(crate) use outln;
