//! The blend table: two palette indices (a translucent surface's and the pixel's under it)
//! to the index of their mix, for blended transparency in an 8-bit frame.
//!
//! Role in the pipeline: beside the colour look-up table ([`Lut`]), read by the span loop of
//! a blended object (`raster::triangle::transparency`). An 8-bit frame holds palette indices,
//! not colours, so a mix of two colours must itself be an index: the table stores, for every
//! source index `s` and destination index `d`, the index of the palette entry nearest
//! `α·palette[s] + (1 − α)·palette[d]`.
//!
//! Size: `256 × 256` bytes, 64 KiB, one table per opacity `α`. It is built once
//! ([`BlendTable::build`], integer arithmetic, `2^16 × 256` distance evaluations: tens of
//! milliseconds on a host, a few seconds on a 125 MHz Cortex-M0+) into caller memory, or
//! built on a host and kept in flash as bytes ([`BlendTable::from_entries`] over an
//! `include_bytes!`): the lookup only reads it.
//!
//! The palette's constraints: a full [`Lut<Rgb888>`] (256 entries; indices the frame never
//! holds may be anything); channels mixed as stored (the 8-bit values are treated as linear,
//! no gamma); the result is the nearest entry in squared RGB distance, the lowest index on
//! ties. The table can only be as good as the palette is dense near the mixes: a translucent
//! material over a background shows its mix only if the palette holds colours between the
//! two (say, a ramp of each material and a few of their mixes); otherwise the nearest entry
//! may be far, which the table does faithfully rather than well.
//!
//! Numeric contract: opacity `α = alpha/256`, `alpha` in `0..=256` (past it
//! [`BlendError::AlphaPastOne`]); channel mix `⌊(alpha·s + (256 − alpha)·d + 128)/256⌋`
//! (`≤ 255`, `u32`); distances `≤ 3·255² < 2^18`.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use super::Lut;

/// Entries of a blend table: every (source, destination) pair of bytes.
pub const BLEND_ENTRIES: usize = 256 * 256;

/// Why a blend table could not be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlendError {
    /// The opacity's numerator is past 256 (`α = alpha/256 ≤ 1`).
    AlphaPastOne {
        /// The numerator given.
        alpha: u16,
    },
}

impl core::fmt::Display for BlendError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BlendError::AlphaPastOne { alpha } => write!(
                f,
                "blend opacity {alpha}/256 is past 1 (the numerator is 0..=256)"
            ),
        }
    }
}

impl core::error::Error for BlendError {}

/// A blend table: `(source, destination) → index`, 64 KiB, borrowed from RAM or flash.
///
/// ```
/// use embedded_graphics_core::pixelcolor::Rgb888;
/// use zscan::output::{BlendTable, Lut, BLEND_ENTRIES};
///
/// let palette = Lut::<Rgb888>::GREY;
/// let mut entries = vec![0u8; BLEND_ENTRIES];
/// let entries: &mut [u8; BLEND_ENTRIES] = entries.as_mut_slice().try_into().unwrap();
/// let half = BlendTable::build(&palette, 128, entries)?;
/// assert_eq!(half.get(200, 100), 150); // grey over grey: the mean
/// # Ok::<(), zscan::output::BlendError>(())
/// ```
#[derive(Clone, Copy)]
pub struct BlendTable<'t> {
    entries: &'t [u8; BLEND_ENTRIES],
}

impl core::fmt::Debug for BlendTable<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("BlendTable { .. }")
    }
}

impl<'t> BlendTable<'t> {
    /// The table whose entry `source · 256 + destination` is the blend of the two (bytes
    /// built by [`BlendTable::build`], kept in flash, say).
    pub const fn from_entries(entries: &'t [u8; BLEND_ENTRIES]) -> Self {
        BlendTable { entries }
    }

    /// Builds into `entries` the table of opacity `alpha/256` over `palette` (the module
    /// doc's constraints) and returns it: each entry the palette index nearest the mix.
    pub fn build(
        palette: &Lut<Rgb888>,
        alpha: u16,
        entries: &'t mut [u8; BLEND_ENTRIES],
    ) -> Result<Self, BlendError> {
        if alpha > 256 {
            return Err(BlendError::AlphaPastOne { alpha });
        }
        let rgb = palette
            .entries()
            .map(|c| [c.r() as u32, c.g() as u32, c.b() as u32]);
        let (a, b) = (alpha as u32, 256 - alpha as u32);
        for (s, row) in entries.chunks_exact_mut(256).enumerate() {
            for (d, out) in row.iter_mut().enumerate() {
                let mix: [u32; 3] =
                    core::array::from_fn(|k| (a * rgb[s][k] + b * rgb[d][k] + 128) >> 8);
                *out = nearest(&rgb, mix);
            }
        }
        Ok(BlendTable { entries })
    }

    /// The index of `source` blended over `destination`.
    #[inline(always)]
    pub fn get(&self, source: u8, destination: u8) -> u8 {
        self.entries[(source as usize) << 8 | destination as usize]
    }

    /// The table's bytes (to write them out and keep them in flash).
    pub fn entries(&self) -> &'t [u8; BLEND_ENTRIES] {
        self.entries
    }
}

/// The index of the palette entry nearest `c` (squared RGB distance), the lowest on ties.
fn nearest(palette: &[[u32; 3]; 256], c: [u32; 3]) -> u8 {
    let mut best = (u32::MAX, 0u8);
    for (i, p) in palette.iter().enumerate() {
        let d: u32 = (0..3).map(|k| p[k].abs_diff(c[k]).pow(2)).sum();
        if d < best.0 {
            best = (d, i as u8);
            if d == 0 {
                break;
            }
        }
    }
    best.1
}
