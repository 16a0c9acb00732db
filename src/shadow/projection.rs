//! The shadow map's projection: light frame → texel position and normalised depth, either
//! orthographic (directional light) or perspective (point light).
//!
//! Role in the pipeline: shared by both passes of the shadow map. Pass 1 projects the
//! (clipped) occluder vertices with [`Projection::project`] and interpolates the depth across
//! each triangle; pass 2 projects the tested point with the same function, so both passes
//! agree to the last unit wherever they meet.
//!
//! ## Conventions
//! Light-frame coordinates are those of a [`Camera`](crate::geometry::camera::Camera) at the
//! light (orthographic: at the bounding sphere's centre) looking along the light's travel:
//! `x` right, `y` up, `z` away from the light (the observer-frame convention). Texel positions
//! are sub-pixel points with [`SUBPIXEL_BITS`] fractional bits, `y` growing down; texel
//! `(i, j)` is the lattice point `(i, j)`, the principal point `((w − 1)/2, (h − 1)/2)`.
//!
//! ## Numeric contract
//! - [`Orthographic`]: `u = i0 + x·w/2r`, `v = j0 − y·h/2r` texels, each an `i64` product of
//!   the raw coordinate (`|x| < 2^31`) and a multiplier below `2^31` (`< 2^62`), rounded by one
//!   shift: within `1/2 + 2^-26·|offset|` sub-pixel unit of the exact value. Depth
//!   `D = (z + r)·(2^32 − 1)/2r`, `z + r` clamped to `0..=2r` (`≤ 2^30` raw since
//!   `r ≤ 8192`) times a multiplier below `2^32` (`< 2^62` in `u64`), rounded: within one unit
//!   of the exact value, monotonic and affine in `z` up to that rounding.
//! - Perspective: [`Projector`]`<4>` (module `project`): positions within
//!   0.51 sub-pixel unit, depth within 6 units of `A − K/z`; points with `z < near` are not
//!   projected.

use crate::arith::scale::Scale;
use crate::geometry::vector::Vec3;
use crate::project::{ProjectError, Projector};

/// Fractional bits of the map's sub-pixel texel positions (as the renderer's default).
pub const SUBPIXEL_BITS: u32 = 4;

/// The orthographic map of a directional light over a bounding sphere of radius `r`
/// (light frame centred on the sphere).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Orthographic {
    /// Principal point, sub-pixel units.
    i0: i64,
    j0: i64,
    /// Raw I16F16 → sub-pixel units (`16·w/2r`, `16·h/2r`).
    kx: Scale,
    ky: Scale,
    /// Raw I16F16 → depth units (`(2^32 − 1)/2r`).
    kd: Scale,
    /// `r`, raw (`1 ≤ r ≤ 2^29`).
    r: i64,
}

impl Orthographic {
    /// The projection of a `w × h` map over radius `r` (raw I16F16, `1 ≤ r ≤ 2^29`); `None`
    /// outside those ranges or for a zero size.
    pub fn new(w: u16, h: u16, r: i32) -> Option<Orthographic> {
        if w == 0 || h == 0 || !(1..=1 << 29).contains(&r) {
            return None;
        }
        let two_r = 2 * r as u128;
        let half = |n: u16| ((n as i64 - 1) << SUBPIXEL_BITS) / 2; // (n − 1)/2 texels, exact
        Some(Orthographic {
            i0: half(w),
            j0: half(h),
            kx: Scale::new((w as u128) << SUBPIXEL_BITS, two_r, 31)?,
            ky: Scale::new((h as u128) << SUBPIXEL_BITS, two_r, 31)?,
            kd: Scale::new(u32::MAX as u128, two_r, 32)?,
            r: r as i64,
        })
    }

    /// The radius, raw I16F16.
    pub fn radius_bits(&self) -> i32 {
        self.r as i32
    }

    /// Sub-pixel texel position and depth of light-frame point `p` (see the module doc).
    #[inline]
    pub fn project(&self, p: Vec3) -> (i64, i64, u32) {
        let [x, y, z] = p.bits();
        let sx = self.i0 + self.kx.signed(x as i64);
        let sy = self.j0 - self.ky.signed(y as i64);
        let zr = (z as i64 + self.r).clamp(0, 2 * self.r) as u64;
        let d = self.kd.unsigned(zr).min(u32::MAX as u64) as u32;
        (sx, sy, d)
    }
}

/// How a shadow map projects the light frame onto its texels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Projection {
    /// Parallel to the light (directional light).
    Orthographic(Orthographic),
    /// From the light's position (point light): the renderer's projector for the light's
    /// camera.
    Perspective(Projector<SUBPIXEL_BITS>),
}

impl Projection {
    /// Sub-pixel texel position (`x`, `y`, [`SUBPIXEL_BITS`] fractional bits) and 32-bit
    /// depth of light-frame point `p`, or `None` when the perspective projection refuses it
    /// (behind the light, nearer than the near plane, or beyond the raster's range): such a
    /// point is outside the map.
    #[inline]
    pub fn project(&self, p: Vec3) -> Option<(i64, i64, u32)> {
        match self {
            Projection::Orthographic(o) => Some(o.project(p)),
            Projection::Perspective(pr) => match pr.project_point(p) {
                Ok((s, d)) => Some((s.x as i64, s.y as i64, d)),
                Err(ProjectError::BehindNearPlane | ProjectError::OutOfRange) => None,
                Err(ProjectError::SubpixelBitsTooLarge | ProjectError::Orthographic(_)) => None,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::geometry::fixed::Coord;

    #[test]
    fn orthographic_against_f64() {
        let (w, h, r) = (128u16, 96u16, 6.0f64);
        let o = Orthographic::new(w, h, Coord::from_num(r).to_bits()).unwrap();
        let mut s: u32 = 99;
        for _ in 0..20_000 {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            let c = |k: u32| ((s.rotate_left(k) % 1_000_000) as f64 / 1_000_000.0 - 0.5) * 4.0 * r;
            let p = Vec3::new(
                Coord::from_num(c(0)),
                Coord::from_num(c(9)),
                Coord::from_num(c(19)),
            );
            let [x, y, z] = p.bits().map(|b| b as f64 / 65536.0);
            let (sx, sy, d) = o.project(p);
            let ex = 16.0 * ((w as f64 - 1.0) / 2.0 + x * w as f64 / (2.0 * r));
            let ey = 16.0 * ((h as f64 - 1.0) / 2.0 - y * h as f64 / (2.0 * r));
            let ed = ((z + r) * 4294967295.0 / (2.0 * r)).clamp(0.0, 4294967295.0);
            assert!((sx as f64 - ex).abs() <= 0.51, "{p:?}");
            assert!((sy as f64 - ey).abs() <= 0.51, "{p:?}");
            assert!((d as f64 - ed).abs() <= 1.0, "{p:?}: {d} vs {ed}");
        }
        assert!(Orthographic::new(0, 4, 65536).is_none());
        assert!(Orthographic::new(4, 4, 0).is_none());
        assert!(Orthographic::new(4, 4, (1 << 29) + 1).is_none());
        assert!(Orthographic::new(1 << 14, 1 << 14, 1).is_some());
    }
}
