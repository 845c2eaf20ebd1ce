//! Printing without panicking (issue 42, item 1). `println!` panics when stdout is a pipe whose
//! reader has gone (`alea run study.toml | head -2`: "failed printing to stdout: Broken pipe");
//! every line of the binary goes through [`outln!`] (stdout) and [`errln!`] (stderr) instead.
//!
//! - A closed stdout (EPIPE) is not an error: the rest of the printout is dropped and the
//!   command goes on, so that its files are complete; it ends with its own exit code (0 when
//!   all else succeeded).
//! - Any other error writing stdout (a redirection to a full disk) drops the rest of the
//!   printout too, and the command then fails with that error ([`finish`]: exit code 3) unless
//!   it failed otherwise.
//! - An error writing stderr is ignored: there is nowhere left to say it.

use std::io::{ErrorKind, Write};
use std::sync::Mutex;

/// The state of stdout: `None` while it is written, then why it is not any more (the first
/// error, `ErrorKind::BrokenPipe` for a reader that has gone).
static STDOUT_FAILED: Mutex<Option<std::io::Error>> = Mutex::new(None);

/// Prints one line to stdout unless stdout failed before; a failure is kept for [`finish`].
pub fn line(args: std::fmt::Arguments<'_>) {
    let mut failed = STDOUT_FAILED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if failed.is_some() {
        return;
    }
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(args).and_then(|()| out.write_all(b"\n")) {
        *failed = Some(e);
    }
}

/// Prints one line to stderr, ignoring an error.
pub fn error_line(args: std::fmt::Arguments<'_>) {
    let mut err = std::io::stderr().lock();
    let _ = err.write_fmt(args).and_then(|()| err.write_all(b"\n"));
}

/// Flushes stdout and returns the error that stopped the printout, if any, but a closed pipe
/// (the reader has all it wanted).
///
/// # Errors
/// The first error writing stdout other than [`ErrorKind::BrokenPipe`].
pub fn finish() -> std::io::Result<()> {
    let mut failed = STDOUT_FAILED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if failed.is_none()
        && let Err(e) = std::io::stdout().lock().flush()
    {
        *failed = Some(e);
    }
    match failed.take() {
        Some(e) if e.kind() != ErrorKind::BrokenPipe => Err(e),
        _ => Ok(()),
    }
}

/// `println!` that does not panic: see the module doc.
macro_rules! outln {
    () => {
        $crate::out::line(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::out::line(format_args!($($arg)*))
    };
}

/// `eprintln!` that does not panic: see the module doc.
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::out::error_line(format_args!($($arg)*))
    };
}

pub(crate) use {errln, outln};
