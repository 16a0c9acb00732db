//! Three-component fixed-point vectors ([`Vec3`]) in [`Coord`] (I16F16).
//!
//! Role in the pipeline: positions and directions in the model, world and observer frames.
//!
//! ## Numeric contract
//! - Components are [`Coord`]: raw `i32` with 16 fractional bits, range ±32 768.
//! - [`add`](Vec3::add), [`sub`](Vec3::sub), [`scale`](Vec3::scale), [`cross`](Vec3::cross) and
//!   [`normalize`](Vec3::normalize) **saturate** each component to the `i32` range; they never wrap.
//! - [`dot`](Vec3::dot) and [`cross_wide`](Vec3::cross_wide) return exact `i64` results in
//!   units of 2^-32 (Q32): each product of two raw components is below 2^62 in magnitude, and
//!   the sum of three (dot) or the difference of two (cross) of them stays below 2^63 because
//!   `|a·b| ≤ 2^31·2^31 = 2^62` with equality only at `i32::MIN²`; callers that may feed
//!   `i32::MIN` components use [`dot`](Vec3::dot), which saturates.
//! - Lengths come from the exact integer square root (`arith::isqrt`): `length` is
//!   `floor(√(x² + y² + z²))` in raw units, as `u32` (up to `√3·2^31`).
//! - `unit_bits` turns any `i64` direction into a unit vector with a chosen number of
//!   fractional bits (`≤ 30`), with about 30 significant bits.

use super::fixed::{saturate_i32, Coord};
use crate::arith::isqrt::isqrt_u64;

/// A 3-vector of [`Coord`] (I16F16) components.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Vec3 {
    /// x component.
    pub x: Coord,
    /// y component.
    pub y: Coord,
    /// z component.
    pub z: Coord,
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Vec3 = Vec3::from_bits(0, 0, 0);

    /// The vector `(x, y, z)`.
    pub const fn new(x: Coord, y: Coord, z: Coord) -> Vec3 {
        Vec3 { x, y, z }
    }

    /// The vector with raw I16F16 components (`1.0 = 65 536`).
    pub const fn from_bits(x: i32, y: i32, z: i32) -> Vec3 {
        Vec3 {
            x: Coord::from_bits(x),
            y: Coord::from_bits(y),
            z: Coord::from_bits(z),
        }
    }

    /// The vector with whole-unit components, saturating outside ±32 767.
    pub const fn from_int(x: i32, y: i32, z: i32) -> Vec3 {
        Vec3::from_bits(
            saturate_i32((x as i64) << 16),
            saturate_i32((y as i64) << 16),
            saturate_i32((z as i64) << 16),
        )
    }

    /// The vector from `f32` components (set-up only, `float-setup` feature), saturating;
    /// NaN gives zero.
    #[cfg(feature = "float-setup")]
    pub fn from_f32(x: f32, y: f32, z: f32) -> Vec3 {
        Vec3::new(
            Coord::saturating_from_num(if x.is_nan() { 0.0 } else { x }),
            Coord::saturating_from_num(if y.is_nan() { 0.0 } else { y }),
            Coord::saturating_from_num(if z.is_nan() { 0.0 } else { z }),
        )
    }

    /// Raw components `[x, y, z]`.
    #[inline(always)]
    pub const fn bits(&self) -> [i32; 3] {
        [self.x.to_bits(), self.y.to_bits(), self.z.to_bits()]
    }

    /// Component-wise sum, saturating.
    #[allow(clippy::should_implement_trait)]
    #[inline]
    pub fn add(self, o: Vec3) -> Vec3 {
        let (a, b) = (self.bits(), o.bits());
        Vec3::from_bits(
            a[0].saturating_add(b[0]),
            a[1].saturating_add(b[1]),
            a[2].saturating_add(b[2]),
        )
    }

    /// Component-wise difference, saturating.
    #[allow(clippy::should_implement_trait)]
    #[inline]
    pub fn sub(self, o: Vec3) -> Vec3 {
        let (a, b) = (self.bits(), o.bits());
        Vec3::from_bits(
            a[0].saturating_sub(b[0]),
            a[1].saturating_sub(b[1]),
            a[2].saturating_sub(b[2]),
        )
    }

    /// The opposite vector, saturating (`-i32::MIN` becomes `i32::MAX`).
    #[allow(clippy::should_implement_trait)]
    pub fn neg(self) -> Vec3 {
        let a = self.bits();
        Vec3::from_bits(
            a[0].saturating_neg(),
            a[1].saturating_neg(),
            a[2].saturating_neg(),
        )
    }

    /// Dot product, exact, in Q32 (units of 2^-32); saturates only for `i32::MIN` components.
    #[inline]
    pub fn dot(self, o: Vec3) -> i64 {
        let (a, b) = (self.bits(), o.bits());
        let p = |i: usize| a[i] as i64 * b[i] as i64;
        p(0).saturating_add(p(1)).saturating_add(p(2))
    }

    /// Dot product in [`Coord`] (rounded to nearest, saturating).
    pub fn dot_coord(self, o: Vec3) -> Coord {
        Coord::from_bits(saturate_i32(super::fixed::shr_round(self.dot(o), 16)))
    }

    /// Cross product, exact, in Q32 raw `i64` components (each `a·b − c·d`, saturating only
    /// for `i32::MIN` inputs).
    #[inline]
    pub fn cross_wide(self, o: Vec3) -> [i64; 3] {
        let (a, b) = (self.bits(), o.bits());
        let m = |i: usize, j: usize| a[i] as i64 * b[j] as i64;
        [
            m(1, 2).saturating_sub(m(2, 1)),
            m(2, 0).saturating_sub(m(0, 2)),
            m(0, 1).saturating_sub(m(1, 0)),
        ]
    }

    /// Cross product in [`Coord`] (rounded to nearest, saturating). Loses precision for short
    /// vectors: prefer [`cross_wide`](Vec3::cross_wide) for normals of small polygons.
    pub fn cross(self, o: Vec3) -> Vec3 {
        let w = self.cross_wide(o);
        let f = |v: i64| saturate_i32(super::fixed::shr_round(v, 16));
        Vec3::from_bits(f(w[0]), f(w[1]), f(w[2]))
    }

    /// `self · k` for a [`Coord`] factor, rounded to nearest, saturating.
    pub fn scale(self, k: Coord) -> Vec3 {
        let a = self.bits();
        let k = k.to_bits() as i64;
        let f = |v: i32| saturate_i32(super::fixed::shr_round(v as i64 * k, 16));
        Vec3::from_bits(f(a[0]), f(a[1]), f(a[2]))
    }

    /// Squared length, exact, in Q32 (`u64`: at most `3·2^62`).
    pub fn length_squared(self) -> u64 {
        let a = self.bits();
        let s = |v: i32| (v as i64).unsigned_abs().pow(2);
        s(a[0]) + s(a[1]) + s(a[2])
    }

    /// Length `floor(√(x² + y² + z²))` in raw I16F16 units (`u32`, up to `√3·2^31`, which may
    /// exceed [`Coord`]'s range — hence not a `Coord`).
    pub fn length_bits(self) -> u32 {
        isqrt_u64(self.length_squared())
    }

    /// Length as a [`Coord`], saturating at [`Coord::MAX`].
    pub fn length(self) -> Coord {
        Coord::from_bits(self.length_bits().min(i32::MAX as u32) as i32)
    }

    /// The unit vector in the direction of `self` (components rounded to 2^-16), or `None`
    /// for the zero vector.
    pub fn normalize(self) -> Option<Vec3> {
        let a = self.bits();
        let u = unit_bits([a[0] as i64, a[1] as i64, a[2] as i64], 16)?;
        Some(Vec3::from_bits(u[0], u[1], u[2]))
    }
}

/// The unit vector along `v` (any `i64` components, any scale) with `frac` fractional bits
/// (`frac ≤ 30`, larger values are treated as 30), or `None` if `v` is zero.
///
/// Method: `v` is shifted until its largest component is in `[2^29, 2^30)` (so the squared
/// length is below `3·2^60`), the length is the exact integer square root, and each component
/// is `round(c·2^frac / len)` with `c·2^frac < 2^60`. Precision: about 2^-29 relative, plus the
/// final rounding to 2^-frac. Components are in `[-2^frac, 2^frac]`.
pub(crate) fn unit_bits(v: [i64; 3], frac: u32) -> Option<[i32; 3]> {
    let frac = frac.min(30);
    let w = to_30_bits(v)?;
    let len2: u64 = w.iter().map(|c| c.unsigned_abs().pow(2)).sum();
    let len = isqrt_u64(len2) as i64;
    if len == 0 {
        return None;
    }
    let f = |c: i64| {
        let n = c << frac; // |c| < 2^30, so |n| < 2^60
        let q = (n.abs() + len / 2) / len;
        let q = q.min(1 << frac) as i32;
        if c < 0 {
            -q
        } else {
            q
        }
    };
    Some([f(w[0]), f(w[1]), f(w[2])])
}

/// `v` scaled by a power of two so that its largest component lies in `[2^29, 2^30)`, or
/// `None` if `v` is zero: small vectors shifted up (exactly), large ones shifted down by
/// magnitude (so both signs round the same way, toward zero). The squared length of the
/// result is below `3·2^60`, within `u64`. Shared by [`unit_bits`] and the lighting's
/// `unit_q15`.
#[inline]
pub(crate) fn to_30_bits(v: [i64; 3]) -> Option<[i64; 3]> {
    let max = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    if max == 0 {
        return None;
    }
    let bits = 64 - max.leading_zeros(); // max < 2^bits
    Some(if bits <= 30 {
        let up = 30 - bits;
        v.map(|c| c << up) // |c| < 2^bits, so |c·2^up| < 2^30
    } else {
        let down = bits - 30;
        v.map(|c| {
            let m = (c.unsigned_abs() >> down) as i64;
            if c < 0 {
                -m
            } else {
                m
            }
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
    }

    #[test]
    fn arithmetic() {
        let a = v(1.5, -2.0, 0.25);
        let b = v(0.5, 4.0, -1.0);
        assert_eq!(a.add(b), v(2.0, 2.0, -0.75));
        assert_eq!(a.sub(b), v(1.0, -6.0, 1.25));
        // dot = 0.75 − 8 − 0.25 = −7.5
        assert_eq!(a.dot(b), (-7.5 * 4_294_967_296.0) as i64);
        assert_eq!(a.dot_coord(b), Coord::from_num(-7.5));
        // cross = (2·1... ) computed by hand: (y1 z2 − z1 y2, z1 x2 − x1 z2, x1 y2 − y1 x2)
        assert_eq!(a.cross(b), v(2.0 - 1.0, 0.125 + 1.5, 6.0 + 1.0));
        assert_eq!(a.scale(Coord::from_num(2)), v(3.0, -4.0, 0.5));
        assert_eq!(v(3.0, 4.0, 0.0).length(), Coord::from_num(5));
        assert_eq!(v(-1.0, 2.0, 3.0).neg(), v(1.0, -2.0, -3.0));
    }

    #[test]
    fn saturation_never_panics() {
        let m = Vec3::from_bits(i32::MAX, i32::MIN, i32::MAX);
        let n = Vec3::from_bits(i32::MIN, i32::MAX, i32::MIN);
        let _ = m.add(m);
        let _ = m.sub(n);
        let _ = m.neg();
        let _ = m.dot(n);
        let _ = m.cross(n);
        let _ = m.cross_wide(m);
        let _ = m.scale(Coord::MAX);
        let _ = m.length();
        let _ = m.normalize();
        assert_eq!(m.add(m).x, Coord::MAX);
        assert_eq!(
            Vec3::from_int(40_000, -40_000, 1),
            Vec3::from_bits(i32::MAX, i32::MIN, 65_536)
        );
    }

    #[test]
    fn normalize_is_unit() {
        assert_eq!(Vec3::ZERO.normalize(), None);
        for (x, y, z) in [
            (1.0, 2.0, 3.0),
            (-0.001, 0.0, 0.002),
            (30000.0, -30000.0, 1.0),
            (0.0, 0.0, -7.0),
        ] {
            let p = v(x, y, z);
            let n = p.normalize().unwrap();
            let (x, y, z) = (
                p.x.to_num::<f64>(),
                p.y.to_num::<f64>(),
                p.z.to_num::<f64>(),
            );
            let l = (x * x + y * y + z * z).sqrt();
            for (c, e) in [(n.x, x / l), (n.y, y / l), (n.z, z / l)] {
                assert!((c.to_num::<f64>() - e).abs() <= 1.0 / 65536.0, "{c} vs {e}");
            }
        }
        assert_eq!(unit_bits([0, 0, i64::MIN], 30), Some([0, 0, -(1 << 30)]));
        assert_eq!(unit_bits([i64::MAX, 0, 0], 40), Some([1 << 30, 0, 0]));
    }
}
