//! Ordered dithering between adjacent shade levels (4×4 Bayer matrix).
//!
//! Role in the pipeline: the last step of shading, luminance → palette index. A
//! [`LuminanceRamp`] with `levels < 256` maps luminance `0..=255` to `⌊lum·levels/256⌋`, which
//! shows bands on smooth surfaces. [`Bayer4`] adds a position-dependent threshold before the
//! truncation, so a luminance a fraction `f` of the way between two levels picks the upper one
//! on about `f·16` of every 16 pixels of a 4×4 block; the mean over a block follows the
//! luminance to 1/16 of a level.
//!
//! ## Numeric contract
//! The level numerator is `lum·levels + t − 128` (saturating at 0) with `lum ≤ 255`,
//! `levels ≤ 256` and the threshold `t = 16·B(x mod 4, y mod 4) + 8 ∈ [8, 248]`: below `2^17`,
//! `u32`. The index is `first + min(⌊(lum·levels + t − 128)/256⌋, levels − 1)` (the brightest
//! level is never passed). The `− 128` keeps the plain ramp's convention: a luminance at the
//! centre of level `k`'s interval (`lum·levels/256 = k + 1/2`) gives `k` at every pixel, and in
//! between the block mean moves linearly from `k` to `k + 1`, so the mean index is
//! `lum·levels/256 − 1/2` to within 1/32 of a level, as the undithered ramp's is on average.
//!
//! Cost: a table read, an add, a subtraction and a compare per pixel more than the plain ramp,
//! and a 2-bit counter step. Measured by `zscan chart` (whole lit frames of the standard
//! sphere, per covered pixel; docs/chart.svg): host exact Gouraud 152.0 → 166.0 instructions
//! (+14), fast 155.1 → 164.0 (+9), Phong 1357.5 → 1374.5 (+17); Cortex-M4 exact Gouraud
//! 212.7 → 220.5 (+8), fast 228.2 → 226.8 (−1.4, measured when [`draw_triangle_dithered`] had
//! its own span loop; it now runs the undithered writer's with a [`Bayer4`] quantizer), Phong
//! 2490 → 2515 (+25). On the bunny, where per-vertex work dominates, the differences are within
//! ±1 %.
//!
//! Conventions: pixel `(x, y)` as [`raster`](crate::raster); the matrix is the classical
//! recursive Bayer matrix, indexed `[y mod 4][x mod 4]`.

use super::span::{LuminanceRamp, Quantizer};

/// The 4×4 Bayer matrix: `0..16`, each value once.
pub const BAYER4: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// A ramp with a 4×4 ordered dither, positioned at one pixel of a span.
#[derive(Debug, Clone, Copy)]
pub struct Bayer4 {
    ramp: LuminanceRamp,
    /// Thresholds of the row, `16·B + 8`.
    row: [u8; 4],
    /// `x mod 4` of the current pixel.
    phase: u8,
}

impl Bayer4 {
    /// The dithered `ramp` at pixel `(x, y)`.
    #[inline]
    pub fn at(ramp: LuminanceRamp, x: i32, y: i32) -> Self {
        let r = BAYER4[(y & 3) as usize];
        Bayer4 {
            ramp,
            row: r.map(|b| b * 16 + 8),
            phase: (x & 3) as u8,
        }
    }
}

impl Bayer4 {
    /// `ramp` as a Bayer quantizer with every threshold at the middle (`t = 128`): the
    /// numerator is `lum·levels`, so the index is the plain ramp's at every pixel (its level
    /// `⌊lum·levels/256⌋ ≤ levels − 1` for `lum ≤ 255`). The transparency quantizers wrap it,
    /// so that one writer serves dithered and plain objects.
    #[inline]
    #[cfg_attr(not(feature = "transparency"), allow(dead_code))]
    pub(crate) fn plain(ramp: LuminanceRamp) -> Self {
        Bayer4 {
            ramp,
            row: [128; 4],
            phase: 0,
        }
    }
}

impl Quantizer for Bayer4 {
    #[inline(always)]
    fn index(&self, lum: u32) -> u8 {
        let levels = self.ramp.levels as u32;
        let t = self.row[(self.phase & 3) as usize] as u32;
        let level =
            ((lum.min(255) * levels + t).saturating_sub(128) >> 8).min(levels.saturating_sub(1));
        self.ramp.first.wrapping_add(level as u8)
    }

    #[inline(always)]
    fn index_byte(&self, lum: u8) -> u8 {
        let levels = self.ramp.levels as u32;
        let t = self.row[(self.phase & 3) as usize] as u32;
        let level =
            ((lum as u32 * levels + t).saturating_sub(128) >> 8).min(levels.saturating_sub(1));
        self.ramp.first.wrapping_add(level as u8)
    }

    #[inline(always)]
    fn step(&mut self) {
        self.phase = self.phase.wrapping_add(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_mean_follows_luminance() {
        let ramp = LuminanceRamp {
            first: 10,
            levels: 16,
        };
        for lum in 0..=255u32 {
            let mut sum = 0u32;
            for y in 0..4 {
                let mut q = Bayer4::at(ramp, 0, y);
                for _ in 0..4 {
                    let i = q.index(lum);
                    assert!((10..26).contains(&i));
                    sum += (i - 10) as u32;
                    q.step();
                }
            }
            // Mean level over the block vs lum·16/256 − 1/2 (the level's centre convention),
            // within 1/32 of a level, away from the saturated ends.
            let want = lum as f64 * 16.0 / 256.0 - 0.5;
            let got = sum as f64 / 16.0;
            if (0.0..=15.0).contains(&want) {
                assert!(
                    (got - want).abs() <= 1.0 / 32.0 + 1e-9,
                    "lum {lum}: {got} vs {want}"
                );
            }
        }
    }
}
