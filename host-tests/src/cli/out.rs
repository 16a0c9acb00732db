//! Standard output and standard error of the `zscan` subcommands: the one way each is written.
//!
//! - **Standard output** (what a subcommand prints for the user: tables, summaries, spans)
//!   goes through [`outln!`](crate::outln) or [`Stdout`]: every write is fallible, and a
//!   failure (a closed pipe, as in `zscan … | head -1`; a full device, as in
//!   `zscan … > /dev/full`) is an [`OutputError`], which the subcommand returns, so that `main`
//!   answers in words (`zscan: cannot write standard output: …`) with a non-zero exit instead
//!   of panicking. `main` also [`flush`]es standard output before it exits, so a failure of
//!   the last buffered bytes is reported as well.
//! - **Standard error** (progress, warnings, the final error message) goes through
//!   [`note!`](crate::note): a failure to write there is ignored, since there is nowhere left
//!   to report it (and it must not panic either).
//!
//! The crate denies `clippy::print_stdout` and `clippy::print_stderr`, so `println!` and
//! `eprintln!` (which panic on such failures) cannot come back.
use std::fmt;
use std::io::{self, Write};

/// Standard output could not be written: a closed pipe, a full device, another I/O error.
#[derive(Debug)]
pub struct OutputError(pub io::Error);

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write standard output: {}", self.0)
    }
}

impl std::error::Error for OutputError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.0)
    }
}

/// Writes `args` and a newline to standard output ([`outln!`](crate::outln)'s body).
pub fn line(args: fmt::Arguments<'_>) -> Result<(), OutputError> {
    let mut out = io::stdout().lock();
    out.write_fmt(args)
        .and_then(|()| out.write_all(b"\n"))
        .map_err(OutputError)
}

/// Flushes standard output (`main` does, last).
pub fn flush() -> Result<(), OutputError> {
    io::stdout().lock().flush().map_err(OutputError)
}

/// Writes `args` and a newline to standard error, ignoring a failure
/// ([`note!`](crate::note)'s body).
pub fn note(args: fmt::Arguments<'_>) {
    let mut err = io::stderr().lock();
    let _ = err.write_fmt(args).and_then(|()| err.write_all(b"\n"));
}

/// Standard output as a buffered [`Write`] for output written piece by piece (`zscan spans`):
/// call [`Stdout::finish`] at the end; the [`OutputError`] of a failed write is
/// [`Stdout::error`].
pub struct Stdout(io::BufWriter<io::StdoutLock<'static>>);

impl Stdout {
    /// Standard output, locked and buffered.
    pub fn new() -> Stdout {
        Stdout(io::BufWriter::new(io::stdout().lock()))
    }

    /// Flushes what is buffered.
    pub fn finish(mut self) -> Result<(), OutputError> {
        self.0.flush().map_err(OutputError)
    }

    /// The error of a failed write to standard output, in words.
    pub fn error(e: io::Error) -> OutputError {
        OutputError(e)
    }
}

impl Default for Stdout {
    fn default() -> Self {
        Stdout::new()
    }
}

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.0.flush()
    }
}

/// `println!` that returns `Result<(), OutputError>` instead of panicking when standard output
/// fails (module [`cli::out`](crate::cli::out)).
#[macro_export]
macro_rules! outln {
    () => {
        $crate::cli::out::line(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::cli::out::line(format_args!($($arg)*))
    };
}

/// `eprintln!` that ignores a failure of standard error instead of panicking (module
/// [`cli::out`](crate::cli::out)).
#[macro_export]
macro_rules! note {
    ($($arg:tt)*) => {
        $crate::cli::out::note(format_args!($($arg)*))
    };
}
