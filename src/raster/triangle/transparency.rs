//! Transparency in 8-bit colour: the screen door and the blend, as quantizers of the one span
//! loop.
//!
//! Role in the pipeline: the last step of shading, after luminance → index (`span`,
//! `dither`). The course (seed 000, ch. 3 §2.2.1) notes that the z-buffer handles only
//! transparency *without refraction* ("une mince couche de verre, mais pas de bouteille
//! remplie d'eau"): a surface lets through what lies behind it along the same line of sight,
//! never bent. Both forms here are of that kind, and neither needs a colour channel the 8-bit
//! frame does not have:
//!
//! - **Screen door** ([`Opacity`], `ScreenDoor`): an object of opacity `k` (`0..=16`) covers
//!   pixel `(x, y)` only where the 4×4 Bayer matrix (`BAYER4`) gives `B(x mod 4, y mod 4) <
//!   k`, so exactly `k` of the 16 pixels of every aligned 4×4 block. A pixel outside the mask
//!   is not drawn at all (neither colour nor depth), so what lies behind shows through it;
//!   inside the mask the depth test and stores are the opaque ones. The mask depends on the
//!   pixel alone, never on the drawing order: every visibility method that draws the
//!   z-buffer's picture of opaque objects draws the z-buffer's picture of screen-door ones.
//! - **Blend** (`Blend`, with a [`BlendTable`]): a pixel that
//!   passes the depth test (against the opaque surfaces) becomes `table[source][under]`, the
//!   palette entry nearest the mix of the two colours, and the depth is *not* stored. The
//!   result depends on the order: blended objects are drawn after the opaque ones, far to
//!   near (`render::transparency`).
//!
//! The seam: a `Quantizer` says whether it is plain (`Quantizer::PLAIN`); where it is not,
//! the span loop asks it `Quantizer::covers` before the depth test and, where it
//! blends (`Quantizer::BLENDS`), stores `Quantizer::blend` of the index and the pixel under
//! it instead of the index and the depth. Plain quantizers (the ramp, `Bayer4`) compile to
//! the loop they had. Both wrap a `Bayer4`: an undithered ramp is the Bayer quantizer with
//! every threshold at the middle, which maps as the ramp does (`Bayer4::plain`), so one
//! writer serves dithered and plain objects.
//!
//! Numeric contract: opacity `0..=16` (16 opaque, 0 invisible; [`Opacity::new`] rejects
//! more); the mask row is 4 bits, the phase `x mod 4`; blend indices are bytes and the table
//! holds every pair (`2^16` entries), so no lookup can miss.
//!
//! Conventions: pixel `(x, y)` as [`raster`](crate::raster), the frame's own coordinates (a
//! band's rows keep their frame `y`, so the mask does not move with the bands).

// Without the crate's `transparency` feature the renderer does not draw these quantizers.
#![cfg_attr(not(feature = "transparency"), allow(dead_code))]

use super::dither::{Bayer4, BAYER4};
use super::span::{LuminanceRamp, Quantizer};
use crate::output::BlendTable;

/// A screen-door opacity: the number of pixels of every 4×4 block an object covers
/// (`0..=16`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Opacity(u8);

/// An opacity above 16 (the 4×4 mask's pixels).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OpacityError {
    /// The opacity asked for.
    pub given: u8,
}

impl core::fmt::Display for OpacityError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "opacity {} is past the screen door's 16 levels (0 invisible ..= 16 opaque)",
            self.given
        )
    }
}

impl core::error::Error for OpacityError {}

impl Opacity {
    /// Every pixel covered.
    pub const OPAQUE: Opacity = Opacity(16);
    /// The levels of the mask: 16 pixels of a 4×4 block.
    pub const LEVELS: u8 = 16;

    /// The opacity covering `pixels` of every 16 (`0..=16`).
    pub const fn new(pixels: u8) -> Result<Opacity, OpacityError> {
        if pixels > Self::LEVELS {
            return Err(OpacityError { given: pixels });
        }
        Ok(Opacity(pixels))
    }

    /// Pixels covered of every 16.
    pub const fn pixels(self) -> u8 {
        self.0
    }

    /// The mask of row `y`: bit `i` set when pixel `x ≡ i (mod 4)` of the row is covered.
    #[inline(always)]
    pub(crate) fn row_mask(self, y: i32) -> u8 {
        let row = BAYER4[(y & 3) as usize];
        let mut mask = 0;
        for (i, b) in row.iter().enumerate() {
            mask |= ((*b < self.0) as u8) << i;
        }
        mask
    }
}

/// A screen-door quantizer: the dithered (or plain) ramp of `Bayer4`, and the opacity's mask
/// at the current pixel.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScreenDoor {
    inner: Bayer4,
    /// The row's mask, rotated so that bit 0 is the current pixel's.
    mask: u8,
}

impl ScreenDoor {
    /// The quantizer of `ramp` (dithered or not) and `opacity` at pixel `(x, y)`.
    #[inline(always)]
    pub(crate) fn at(ramp: LuminanceRamp, dither: bool, opacity: Opacity, x: i32, y: i32) -> Self {
        let row = opacity.row_mask(y);
        let phase = (x & 3) as u32;
        // Bits 0..4 from `phase` on, then around: a rotation of the 4-bit row in 8 bits.
        let doubled = (row as u32) | ((row as u32) << 4);
        ScreenDoor {
            inner: bayer(ramp, dither, x, y),
            mask: ((doubled >> phase) & 0xF) as u8,
        }
    }
}

/// The dithered ramp at `(x, y)`, or the plain one as a Bayer quantizer.
#[inline(always)]
fn bayer(ramp: LuminanceRamp, dither: bool, x: i32, y: i32) -> Bayer4 {
    if dither {
        Bayer4::at(ramp, x, y)
    } else {
        Bayer4::plain(ramp)
    }
}

impl Quantizer for ScreenDoor {
    const PLAIN: bool = false;

    #[inline(always)]
    fn index(&self, lum: u32) -> u8 {
        self.inner.index(lum)
    }

    #[inline(always)]
    fn index_byte(&self, lum: u8) -> u8 {
        self.inner.index_byte(lum)
    }

    #[inline(always)]
    fn covers(&self) -> bool {
        self.mask & 1 != 0
    }

    #[inline(always)]
    fn step(&mut self) {
        self.inner.step();
        self.mask = (self.mask >> 1) | ((self.mask & 1) << 3);
    }
}

/// A blending quantizer: the dithered (or plain) ramp of `Bayer4`, each index stored as the
/// table's mix of it and the pixel under it (depth tested, not stored).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Blend<'t> {
    inner: Bayer4,
    table: BlendTable<'t>,
}

impl<'t> Blend<'t> {
    /// The quantizer of `ramp` (dithered or not) blending through `table`, at pixel `(x, y)`.
    #[inline(always)]
    pub(crate) fn at(
        ramp: LuminanceRamp,
        dither: bool,
        table: BlendTable<'t>,
        x: i32,
        y: i32,
    ) -> Self {
        Blend {
            inner: bayer(ramp, dither, x, y),
            table,
        }
    }
}

impl Quantizer for Blend<'_> {
    const PLAIN: bool = false;
    const BLENDS: bool = true;

    #[inline(always)]
    fn index(&self, lum: u32) -> u8 {
        self.inner.index(lum)
    }

    #[inline(always)]
    fn index_byte(&self, lum: u8) -> u8 {
        self.inner.index_byte(lum)
    }

    #[inline(always)]
    fn blend(&self, src: u8, dst: u8) -> u8 {
        self.table.get(src, dst)
    }

    #[inline(always)]
    fn step(&mut self) {
        self.inner.step();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The row masks hold exactly the Bayer cells below the opacity, and a whole 4×4 block
    /// covers `k` pixels: counted cell by cell against the matrix.
    #[test]
    fn masks_cover_k_of_16() {
        for k in 0..=16u8 {
            let o = Opacity::new(k).unwrap();
            let mut n = 0;
            for y in 0..4 {
                for x in 0..4 {
                    let q = ScreenDoor::at(LuminanceRamp::GREY, false, o, x, y);
                    let want = BAYER4[y as usize][x as usize] < k;
                    assert_eq!(q.covers(), want, "k {k} ({x},{y})");
                    n += want as u32;
                }
            }
            assert_eq!(n, k as u32);
        }
        assert_eq!(Opacity::new(17), Err(OpacityError { given: 17 }));
    }

    /// Stepping along a row from any start gives the mask at each pixel, negative
    /// coordinates included.
    #[test]
    fn stepping_follows_the_mask() {
        for k in [1u8, 5, 8, 11, 15] {
            let o = Opacity::new(k).unwrap();
            for y in -5..5 {
                for x0 in -7..7 {
                    let mut q = ScreenDoor::at(LuminanceRamp::GREY, true, o, x0, y);
                    for x in x0..x0 + 13 {
                        let want = BAYER4[(y & 3) as usize][(x & 3) as usize] < k;
                        assert_eq!(q.covers(), want, "k {k} x0 {x0} ({x},{y})");
                        q.step();
                    }
                }
            }
        }
    }

    /// The plain Bayer quantizer maps every luminance as the ramp does, for ramps of every
    /// length and first index.
    #[test]
    fn plain_bayer_is_the_ramp() {
        for levels in [1u16, 2, 7, 32, 200, 255, 256] {
            for first in [0u8, 3, 100, 255] {
                let ramp = LuminanceRamp { first, levels };
                let q = Bayer4::plain(ramp);
                for lum in 0..=300u32 {
                    assert_eq!(q.index(lum), ramp.index(lum), "{ramp:?} {lum}");
                    if lum < 256 {
                        assert_eq!(q.index_byte(lum as u8), ramp.index(lum));
                    }
                }
            }
        }
    }
}
