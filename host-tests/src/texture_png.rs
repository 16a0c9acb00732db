//! A texture read from a PNG file: the palette indices the core's
//! [`Texture`](zscan::texture::Texture) holds, for `zscan render`'s `texture` key.
//!
//! Role: host set-up, before the frame. Conventions:
//! - texel `(i, j)` (column `i`, the `u` direction; row `j`, the `v` direction) is the image's
//!   pixel in column `i` and row `j` as the file stores it, **top row first** (so row 0 lies at
//!   `v = 0`, SCENES.md's convention);
//! - an **indexed** PNG (colour type 3, bit depths 1, 2, 4 or 8) gives its indices as they
//!   are: the scene's palette colours them, the PNG's own palette is not read;
//! - a **grey, grey + alpha, RGB or RGBA** PNG (any bit depth, widened or cut to 8 bits) is
//!   mapped to the scene's palette by nearest colour: the entry `k` with the least squared RGB
//!   distance `Σ (c − p_k)²` (grey `g` counts as `(g, g, g)`), the lowest index among equals;
//!   alpha is ignored.
//!
//! Numeric contract: sides `1..=`[`MAX_TEXTURE_SIDE`] (the core's limit), checked from the
//! header before the pixels are decoded; any error names the file.

use std::collections::HashMap;
use std::path::Path;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use zscan::output::Lut;
pub use zscan::texture::MAX_TEXTURE_SIDE;

/// A texture's palette indices, row by row, and its sides.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextureImage {
    /// `texels[row · width + column]`.
    pub texels: Vec<u8>,
    /// Columns.
    pub width: u16,
    /// Rows.
    pub height: u16,
}

/// The palette index nearest `rgb` in `palette` (module doc: least squared distance, lowest
/// index among equals).
pub fn nearest(palette: &[Rgb888; 256], rgb: [u8; 3]) -> u8 {
    let d = |p: &Rgb888| {
        [p.r(), p.g(), p.b()]
            .iter()
            .zip(rgb)
            .map(|(&a, b)| (a as i32 - b as i32).pow(2))
            .sum::<i32>()
    };
    let mut best = 0;
    for (k, p) in palette.iter().enumerate() {
        if d(p) < d(&palette[best]) {
            best = k;
        }
    }
    best as u8
}

/// Reads `path` as a texture over the palette `lut` (module doc).
pub fn read_texture(path: &Path, lut: &Lut<Rgb888>) -> Result<TextureImage, String> {
    let name = path.display();
    let file = std::fs::File::open(path).map_err(|e| format!("{name}: cannot read: {e}"))?;
    let mut dec = png::Decoder::new(std::io::BufReader::new(file));
    let header = dec
        .read_header_info()
        .map_err(|e| format!("{name}: not a PNG image: {e}"))?;
    let (w, h, indexed) = (
        header.width,
        header.height,
        header.color_type == png::ColorType::Indexed,
    );
    let max = MAX_TEXTURE_SIDE as u32;
    if !(1..=max).contains(&w) || !(1..=max).contains(&h) {
        return Err(format!(
            "{name}: {w} × {h} texels: a texture's sides are 1..={max} texels"
        ));
    }
    // Indices as they are (packed below 8 bits); other images to 8-bit samples.
    dec.set_transformations(if indexed {
        png::Transformations::IDENTITY
    } else {
        png::Transformations::EXPAND | png::Transformations::STRIP_16
    });
    let mut reader = dec
        .read_info()
        .map_err(|e| format!("{name}: not a PNG image: {e}"))?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("{name}: bad PNG data: {e}"))?;
    let (n, line) = (w as usize * h as usize, info.line_size);
    let rows = buf.chunks(line).take(h as usize);
    let texels: Vec<u8> = match info.color_type {
        png::ColorType::Indexed => {
            let bits = info.bit_depth as usize;
            let per = 8 / bits;
            let mask = ((1u16 << bits) - 1) as u8;
            rows.flat_map(|row| {
                (0..w as usize).map(move |i| {
                    let byte = row.get(i / per).copied().unwrap_or(0);
                    let shift = 8 - bits * (i % per + 1);
                    byte >> shift & mask
                })
            })
            .collect()
        }
        colour => {
            let channels = colour.samples();
            let palette = lut.entries();
            let mut memo: HashMap<[u8; 3], u8> = HashMap::new();
            let mut out = Vec::with_capacity(n);
            for row in rows {
                for p in row.chunks_exact(channels).take(w as usize) {
                    let rgb = if channels < 3 {
                        [p[0]; 3]
                    } else {
                        [p[0], p[1], p[2]]
                    };
                    out.push(*memo.entry(rgb).or_insert_with(|| nearest(palette, rgb)));
                }
            }
            out
        }
    };
    if texels.len() != n {
        return Err(format!(
            "{name}: {} texels decoded, {w} × {h} = {n} expected",
            texels.len()
        ));
    }
    Ok(TextureImage {
        texels,
        width: w as u16,
        height: h as u16,
    })
}
