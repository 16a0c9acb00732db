//! `zscan spans`: covered spans of polygons read as text.
use super::CliError;

/// Arguments of `zscan spans`.
#[derive(clap::Args, Debug)]
pub struct SpansArgs {
    /// Fractional bits of vertex coordinates.
    #[arg(long, default_value_t = 4)]
    pub subpixel_bits: u32,
    /// Input file; standard input when absent.
    pub file: Option<std::path::PathBuf>,
}

/// Runs `zscan spans`.
pub fn run(_args: SpansArgs) -> Result<(), CliError> {
    Err("not yet implemented".into())
}
