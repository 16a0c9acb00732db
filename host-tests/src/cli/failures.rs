//! `zscan failures`: draws where the hidden-surface methods fail
//! ([`crate::failures`]) as PNGs, the wrong pixels marked, and prints their counts.
//!
//! `zscan failures [--out-dir docs/images] [--scale 2]` writes `<name>.png` for each case
//! (the method's frame dimmed, wrong pixels in [`WRONG_COLOUR`](crate::failures::WRONG_COLOUR),
//! scaled up) and prints one Markdown table row per case: picture, what is drawn, wrong
//! pixels. `tests/visibility.rs` asserts the same counts and that the docs state them.
//!
//! `zscan failures --textures [--out-dir docs/images] [--scale 1]` draws instead the textured
//! scenes of SCENES.md ([`crate::texture_failures`]): `tex_<scene>.png` in the exact mode and
//! `tex_<scene>_<mode>.png` for the fast modes, the pixels whose texel is not the exact mode's
//! in red ([`differing_colour`](crate::texture_failures::differing_colour)), one table row each with
//! that count; then every scene and mode against the exact mode and the `f64` definition.

use std::path::{Path, PathBuf};

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
    /// The texture modes on SCENES.md's textured scenes instead of the hidden-surface methods.
    #[arg(long)]
    pub textures: bool,
}

/// Runs `zscan failures`.
pub fn run(args: FailuresArgs) -> Result<(), CliError> {
    if !(1..=4).contains(&args.scale) {
        return Err(format!("--scale: {} is outside 1..=4", args.scale).into());
    }
    let scale = args.scale as usize;
    if args.textures {
        return textures(&args.out_dir, scale);
    }
    let cases = failures().map_err(|e| crate::cli::render::visibility_error_words(&e))?;
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
        write_rgb(&path, (w, h), &case.marked(scale))?;
        crate::outln!(
            "| `{}.png` | {} | {} |",
            case.name,
            case.caption,
            case.wrong()
        )?;
    }
    Ok(())
}

/// Writes an 8-bit RGB PNG of `w × h` pixels.
fn write_rgb(path: &Path, (w, h): (u32, u32), rgb: &[u8]) -> Result<(), CliError> {
    let file = std::fs::File::create(path)
        .map_err(|e| format!("{}: cannot create: {e}", path.display()))?;
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut wr = enc
        .write_header()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    wr.write_image_data(rgb)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    wr.finish()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(())
}

/// `zscan failures --textures`: the pictures and their counts, then the accuracy table.
fn textures(out_dir: &Path, scale: usize) -> Result<(), CliError> {
    use crate::texture_failures::{accuracy_table, mode_name, texture_failures};
    let pictures = texture_failures()?;
    std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    crate::outln!("| picture | scene and mode | texels differing from the exact mode |")?;
    crate::outln!("|---|---|---:|")?;
    let size = |n: u16| n as u32 * scale as u32;
    for p in &pictures {
        let path = out_dir.join(format!("{}.png", p.name));
        let (w, h) = (
            size(super::bench::cases::WIDTH),
            size(super::bench::cases::HEIGHT),
        );
        write_rgb(&path, (w, h), &p.marked(scale))?;
        crate::outln!("| `{}.png` | {} | {} |", p.name, p.caption, p.count())?;
    }
    crate::outln!()?;
    crate::outln!(
        "| scene | mode | covered | texels ≠ exact mode | levels ≠ exact mode | \
         texels ≠ f64 | mean / max level error vs f64 | covered by one only |"
    )?;
    crate::outln!("|---|---|---:|---:|---:|---:|---:|---:|")?;
    for (scene, mode, a) in accuracy_table()? {
        crate::outln!(
            "| {} | {} | {} | {} | {} | {} of {} ({:.2} %) | {:.2} / {:.1} | {} |",
            scene.name(),
            mode_name(mode),
            a.covered,
            a.texels_vs_exact,
            a.pixels_vs_exact,
            a.texels_vs_reference,
            a.compared,
            100.0 * a.texels_vs_reference as f64 / a.compared.max(1) as f64,
            a.mean_error,
            a.max_error,
            a.coverage_vs_reference
        )?;
    }
    Ok(())
}
