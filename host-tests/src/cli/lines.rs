//! `zscan lines`: a test pattern of lines and circles.
use super::CliError;

/// Arguments of `zscan lines`.
#[derive(clap::Args, Debug)]
pub struct LinesArgs {
    /// Output image (.png, .pgm or .ppm).
    #[arg(short, long, default_value = "out/lines.png")]
    pub output: std::path::PathBuf,
}

/// Runs `zscan lines`.
pub fn run(_args: LinesArgs) -> Result<(), CliError> {
    Err("not yet implemented".into())
}
