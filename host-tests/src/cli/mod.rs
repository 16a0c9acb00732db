//! Subcommands of the `zscan` tool, one module each. Every `run` returns a descriptive error
//! string on bad input instead of panicking.

pub mod bench;
pub mod chart;
pub mod export;
pub mod lines;
pub mod render;
pub mod spans;

/// The error type of the subcommands: a message for the user.
pub type CliError = Box<dyn std::error::Error + Send + Sync>;
