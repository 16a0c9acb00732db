//! The shade table: texel colour × light level → palette index.
//!
//! Role: what a lit texture's pixel becomes. Row `r` of the table (`levels` rows of 256
//! entries) holds, for every palette colour `c`, the palette entry nearest (squared RGB
//! distance, first of equals) to `c` scaled by the light of that row, `(2r + 1) / (2·levels)`
//! of full (the middle of the row's band of luminances). A pixel of luminance `l` (`0..=255`)
//! and texel `t` takes entry `⌊l · levels / 256⌋ · 256 + t`.
//!
//! Numeric contract: `1 ≤ levels ≤ 256`, the table at least `levels · 256` entries (checked
//! by [`ShadeTable::new`]); the `const fn` builder works in `u32` (a channel times a level
//! below `2^17`, a squared distance below `2^18`).

use super::{TextureError, TextureTable};

/// A shade table in caller memory (module doc), checked once.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShadeTable<'a> {
    entries: &'a [u8],
    levels: u16,
}

impl<'a> ShadeTable<'a> {
    /// The table of `levels` rows (`1..=256`) in `entries` (at least `levels · 256`).
    pub const fn new(entries: &'a [u8], levels: u16) -> Result<Self, TextureError> {
        if levels == 0 || levels > 256 {
            return Err(TextureError::BadLevels { levels });
        }
        let needed = levels as usize * 256;
        if entries.len() < needed {
            return Err(TextureError::WrongLength {
                table: TextureTable::Shades,
                given: entries.len(),
                needed,
            });
        }
        Ok(ShadeTable { entries, levels })
    }

    /// Light levels (rows).
    pub const fn levels(&self) -> u16 {
        self.levels
    }

    /// The row offset of luminance `lum` (`0..=255`).
    #[inline(always)]
    pub(crate) fn row(&self, lum: u32) -> usize {
        ((lum.min(255) * self.levels as u32) >> 8) as usize * 256
    }

    /// The palette index of texel `t` in row offset `row` (from [`Self::row`]).
    #[inline(always)]
    pub(crate) fn shade(&self, row: usize, t: u8) -> u8 {
        self.entries.get(row + t as usize).copied().unwrap_or(t)
    }
}

/// The shade table of `palette` with `N / 256` levels (`N` a multiple of 256 in
/// `256..=65536`, else a compile-time error where it is evaluated in a `static`): for
/// `static SHADES: [u8; 32 * 256] = shade_table(&PALETTE);` in flash.
pub const fn shade_table<const N: usize>(palette: &[[u8; 3]; 256]) -> [u8; N] {
    assert!(
        N % 256 == 0 && N >= 256 && N <= 65536,
        "shade_table: N must be levels × 256"
    );
    let levels = (N / 256) as u32;
    let mut out = [0u8; N];
    let mut r = 0;
    while r < levels {
        let mut c = 0;
        while c < 256 {
            let mut want = [0u32; 3];
            let mut k = 0;
            while k < 3 {
                // Channel × (2r + 1) / (2·levels), rounded.
                want[k] = (palette[c][k] as u32 * (2 * r + 1) + levels) / (2 * levels);
                k += 1;
            }
            let (mut best, mut best_d) = (0usize, u32::MAX);
            let mut p = 0;
            while p < 256 {
                let mut d = 0u32;
                let mut k = 0;
                while k < 3 {
                    let e = palette[p][k] as i32 - want[k] as i32;
                    d += (e * e) as u32;
                    k += 1;
                }
                if d < best_d {
                    best = p;
                    best_d = d;
                }
                p += 1;
            }
            out[r as usize * 256 + c] = best as u8;
            c += 1;
        }
        r += 1;
    }
    out
}
