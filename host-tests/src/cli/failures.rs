//! `zscan failures`: draws where the hidden-surface methods fail
//! ([`crate::failures`]) as PNGs, the wrong pixels marked, and prints their counts.
//!
//! `zscan failures [--out-dir docs/images] [--scale 2]` writes `<name>.png` for each case
//! (the method's frame dimmed, wrong pixels in [`WRONG_COLOUR`](crate::failures::WRONG_COLOUR),
//! scaled up) and prints one Markdown table row per case: picture, what is drawn, wrong
//! pixels. `tests/visibility.rs` asserts the same counts and that the docs state them.

use std::path::PathBuf;

use super::CliError;
use crate::failures::failures;

/// Arguments of `zscan failures`.
#[derive(clap::Args, Debug)]
pub struct FailuresArgs {
    /// Directory the pictures go to.
    #[arg(long, default_value = "docs/images")]
    pub out_dir: PathBuf,
    /// Whole factor each picture is scaled up by (nearest pixel), 1 to 4.
    #[arg(long, default_value_t = 2)]
    pub scale: u8,
}

/// Runs `zscan failures`.
pub fn run(args: FailuresArgs) -> Result<(), CliError> {
    if !(1..=4).contains(&args.scale) {
        return Err(format!("--scale: {} is outside 1..=4", args.scale).into());
    }
    let scale = args.scale as usize;
    let cases = failures().map_err(|e| crate::cli::render::render_error_words(&e))?;
    std::fs::create_dir_all(&args.out_dir)
        .map_err(|e| format!("{}: {e}", args.out_dir.display()))?;
    crate::outln!("| picture | method and scene | wrong pixels |")?;
    crate::outln!("|---|---|---:|")?;
    for case in &cases {
        let path = args.out_dir.join(format!("{}.png", case.name));
        let (w, h) = (
            case.size.0 as u32 * scale as u32,
            case.size.1 as u32 * scale as u32,
        );
        let file = std::fs::File::create(&path)
            .map_err(|e| format!("{}: cannot create: {e}", path.display()))?;
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut wr = enc
            .write_header()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        wr.write_image_data(&case.marked(scale))
            .map_err(|e| format!("{}: {e}", path.display()))?;
        wr.finish()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        crate::outln!(
            "| `{}.png` | {} | {} |",
            case.name,
            case.caption,
            case.wrong()
        )?;
    }
    Ok(())
}
