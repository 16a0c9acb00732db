//! 3×4 affine transforms ([`Affine3`]): a linear part (rotation × scale) and a translation.
//!
//! Role in the pipeline: model → world → observer. The per-vertex work of a frame is one
//! [`Affine3::transform_point`] with the composed model-view transform.
//!
//! ## Conventions
//! Column vectors: `p' = M·p + t`. [`Affine3::mul`]`(a, b)` is the matrix product `a·b`, which
//! applies `b` first; [`Affine3::then`] reads in application order. Rotations follow the
//! right-hand rule: a positive angle turns counter-clockwise when looking down the axis toward
//! the origin (SCENES.md's convention).
//!
//! ## Numeric contract
//! - The linear part is [`Linear`] (I8F24, raw `i32`, resolution 2^-24 ≈ 6·10^-8: unit
//!   vectors and rotations to about 7 decimal digits). Every constructor keeps `|entry| ≤ 64`
//!   (raw `≤ 2^30`); larger entries are [`MatrixError::OutOfRange`].
//! - The translation is a [`Vec3`] (I16F16).
//! - [`transform_point`](Affine3::transform_point): three products `|m·p| ≤ 2^30·2^31 = 2^61`
//!   plus the translation `t·2^24 ≤ 2^55` stay below `2^63` in `i64`; the Q40 sum is rounded to
//!   Q16 and **saturated** to the `i32` range (points that leave ±32 768 units clamp there).
//!   [`point_bounds`](Affine3::point_bounds) bounds the result for all points within a box,
//!   once per object; where that bound fits `i32`,
//!   [`transform_point_wrapping`](Affine3::transform_point_wrapping) (no saturation) is equal.
//! - [`mul`](Affine3::mul): entries are sums of three `Q24·Q24` products (`≤ 3·2^60`); results
//!   outside the ranges above are [`MatrixError::OutOfRange`], never wrapped.

use super::fixed::{saturate_i32, shr_round, Coord, Linear, LINEAR_FRAC};
use super::trig::{sin_cos_bits, BinaryAngle};
use super::vector::{unit_bits, Vec3};
use crate::arith::wide::mul_wide;
use crate::arith::NARROW_MULTIPLY;

/// Largest raw linear entry (`64.0` in I8F24).
pub const MAX_LINEAR_BITS: i32 = 1 << 30;

/// What went wrong building or combining a transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatrixError {
    /// A linear entry would exceed ±64 or a translation would leave the I16F16 range.
    OutOfRange,
    /// A rotation axis was the zero vector.
    ZeroAxis,
    /// [`Affine3::inverse_rigid`] was given a linear part that is not a rotation (within 2^-12).
    NotRigid,
}

/// A 3×4 affine transform: `p' = M·p + t` (see the module doc for formats and ranges).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Affine3 {
    /// Rows of the linear part, raw I8F24, `|entry| ≤ 2^30`.
    m: [[i32; 3]; 3],
    /// Translation, raw I16F16.
    t: [i32; 3],
    /// `t·2^24 + 2^23`: the translation in Q40 with the rounding bias folded in, so that
    /// [`transform_point`](Affine3::transform_point) rounds with a plain shift (derived from `t`).
    t_wide: [i64; 3],
}

const ONE: i32 = 1 << LINEAR_FRAC;

impl Default for Affine3 {
    fn default() -> Self {
        Affine3::IDENTITY
    }
}

impl Affine3 {
    /// The transform from raw parts (callers have checked the ranges).
    const fn raw(m: [[i32; 3]; 3], t: [i32; 3]) -> Affine3 {
        const BIAS: i64 = 1 << (LINEAR_FRAC - 1);
        Affine3 {
            m,
            t,
            t_wide: [
                ((t[0] as i64) << LINEAR_FRAC) + BIAS,
                ((t[1] as i64) << LINEAR_FRAC) + BIAS,
                ((t[2] as i64) << LINEAR_FRAC) + BIAS,
            ],
        }
    }

    /// The identity transform.
    pub const IDENTITY: Affine3 = Affine3::raw([[ONE, 0, 0], [0, ONE, 0], [0, 0, ONE]], [0, 0, 0]);

    /// The transform with linear rows `rows` (raw I8F24) and translation `t`; entries beyond
    /// ±64 are [`MatrixError::OutOfRange`].
    pub fn from_bits(rows: [[i32; 3]; 3], t: Vec3) -> Result<Affine3, MatrixError> {
        if rows
            .iter()
            .flatten()
            .any(|&e| e.unsigned_abs() > MAX_LINEAR_BITS as u32)
        {
            return Err(MatrixError::OutOfRange);
        }
        Ok(Affine3::raw(rows, t.bits()))
    }

    /// The transform with linear rows `rows` and translation `t` (checked like [`from_bits`](Affine3::from_bits)).
    pub fn from_parts(rows: [[Linear; 3]; 3], t: Vec3) -> Result<Affine3, MatrixError> {
        Affine3::from_bits(rows.map(|r| r.map(Linear::to_bits)), t)
    }

    /// Raw I8F24 rows of the linear part.
    pub const fn linear_bits(&self) -> [[i32; 3]; 3] {
        self.m
    }

    /// Entry `(row, col)` of the linear part (indices taken modulo 3).
    pub fn entry(&self, row: usize, col: usize) -> Linear {
        Linear::from_bits(self.m[row % 3][col % 3])
    }

    /// The translation.
    pub const fn translation_part(&self) -> Vec3 {
        Vec3::from_bits(self.t[0], self.t[1], self.t[2])
    }

    /// The translation by `t`.
    pub const fn translation(t: Vec3) -> Affine3 {
        Affine3::raw(Affine3::IDENTITY.m, t.bits())
    }

    /// Scaling by `(sx, sy, sz)` about the origin; factors beyond ±64 are an error.
    pub fn scale3(sx: Coord, sy: Coord, sz: Coord) -> Result<Affine3, MatrixError> {
        let f = |s: Coord| (s.to_bits() as i64) << (LINEAR_FRAC - 16);
        let (x, y, z) = (f(sx), f(sy), f(sz));
        if [x, y, z]
            .iter()
            .any(|v| v.unsigned_abs() > MAX_LINEAR_BITS as u64)
        {
            return Err(MatrixError::OutOfRange);
        }
        Ok(Affine3::raw(
            [[x as i32, 0, 0], [0, y as i32, 0], [0, 0, z as i32]],
            [0; 3],
        ))
    }

    /// Uniform scaling by `s` about the origin; `|s| > 64` is an error.
    pub fn scale(s: Coord) -> Result<Affine3, MatrixError> {
        Affine3::scale3(s, s, s)
    }

    fn trig24(a: BinaryAngle) -> (i32, i32) {
        let (s, c) = sin_cos_bits(a);
        let r = |v: i32| shr_round(v as i64, 30 - LINEAR_FRAC) as i32;
        (r(s), r(c))
    }

    /// Rotation by `a` about the x axis: `y' = c·y − s·z`, `z' = s·y + c·z`.
    pub fn rotation_x(a: BinaryAngle) -> Affine3 {
        let (s, c) = Affine3::trig24(a);
        Affine3::raw([[ONE, 0, 0], [0, c, -s], [0, s, c]], [0; 3])
    }

    /// Rotation by `a` about the y axis: `z' = c·z − s·x`, `x' = s·z + c·x`.
    pub fn rotation_y(a: BinaryAngle) -> Affine3 {
        let (s, c) = Affine3::trig24(a);
        Affine3::raw([[c, 0, s], [0, ONE, 0], [-s, 0, c]], [0; 3])
    }

    /// Rotation by `a` about the z axis: `x' = c·x − s·y`, `y' = s·x + c·y`.
    pub fn rotation_z(a: BinaryAngle) -> Affine3 {
        let (s, c) = Affine3::trig24(a);
        Affine3::raw([[c, -s, 0], [s, c, 0], [0, 0, ONE]], [0; 3])
    }

    /// Rotation by `a` about the axis through the origin along `axis` (any length; it is
    /// normalised here, in 30-bit precision): Rodrigues' `R = c·I + s·[k]× + (1 − c)·k·kᵀ`.
    pub fn rotation_axis(axis: Vec3, a: BinaryAngle) -> Result<Affine3, MatrixError> {
        let b = axis.bits();
        let k =
            unit_bits([b[0] as i64, b[1] as i64, b[2] as i64], 30).ok_or(MatrixError::ZeroAxis)?;
        let (s, c) = sin_cos_bits(a);
        let (s, c) = (s as i64, c as i64); // Q30
        let k = k.map(|v| v as i64); // Q30
        let omc = (1i64 << 30) - c; // Q30, in [0, 2^31]
        let mut m = [[0i32; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                // (1 − c)·k_i·k_j: (k_i·k_j >> 30) ≤ 2^30, times omc ≤ 2^31 → ≤ 2^61.
                let mut v = (omc * ((k[i] * k[j]) >> 30)) >> 30;
                if i == j {
                    v += c;
                }
                // s·[k]×: row i, col j = −s·ε_ijl·k_l
                let cross = match (i, j) {
                    (0, 1) => -k[2],
                    (0, 2) => k[1],
                    (1, 0) => k[2],
                    (1, 2) => -k[0],
                    (2, 0) => -k[1],
                    (2, 1) => k[0],
                    _ => 0,
                };
                v += (s * cross) >> 30;
                *e = shr_round(v, 30 - LINEAR_FRAC) as i32; // |v| ≤ 2^30·(1 + small) → fits
            }
        }
        Ok(Affine3::raw(m, [0; 3]))
    }

    /// The product `self · rhs` (applies `rhs` first), or [`MatrixError::OutOfRange`].
    pub fn mul(&self, rhs: &Affine3) -> Result<Affine3, MatrixError> {
        let mut m = [[0i32; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                let mut acc = 0i64;
                for k in 0..3 {
                    acc += self.m[i][k] as i64 * rhs.m[k][j] as i64; // ≤ 2^60 each
                }
                let v = shr_round(acc, LINEAR_FRAC);
                if v.unsigned_abs() > MAX_LINEAR_BITS as u64 {
                    return Err(MatrixError::OutOfRange);
                }
                *e = v as i32;
            }
        }
        let mut t = [0i32; 3];
        for (i, ti) in t.iter_mut().enumerate() {
            let mut acc = (self.t[i] as i64) << LINEAR_FRAC; // ≤ 2^55
            for k in 0..3 {
                acc += self.m[i][k] as i64 * rhs.t[k] as i64; // ≤ 2^61
            }
            let v = shr_round(acc, LINEAR_FRAC);
            *ti = i32::try_from(v).map_err(|_| MatrixError::OutOfRange)?;
        }
        Ok(Affine3::raw(m, t))
    }

    /// `next ∘ self`: the transform that applies `self`, then `next`.
    pub fn then(&self, next: &Affine3) -> Result<Affine3, MatrixError> {
        next.mul(self)
    }

    /// `M·p + t`, rounded to nearest, saturating to the I16F16 range (see the module doc).
    #[inline]
    pub fn transform_point(&self, p: Vec3) -> Vec3 {
        let [x, y, z] = self.rounded_rows(p).map(saturate_i32);
        Vec3::from_bits(x, y, z)
    }

    /// `M·p + t` per row, rounded to nearest raw I16F16 units, before any range check.
    #[inline(always)]
    fn rounded_rows(&self, p: Vec3) -> [i64; 3] {
        let p = p.bits();
        let row = |i: usize| {
            let r = &self.m[i];
            // Q40 sum with the rounding bias already in t_wide: a plain shift rounds to nearest.
            let acc =
                self.t_wide[i] + mul_wide(r[0], p[0]) + mul_wide(r[1], p[1]) + mul_wide(r[2], p[2]);
            acc >> LINEAR_FRAC
        };
        // Where the products are inline sequences (NARROW_MULTIPLY) the compiler left
        // `array::from_fn` out of line: three calls there (Cortex-M0 vertex_bunny −7.4 %), the
        // array elsewhere (three calls measured +1.2 % on the Cortex-M4's).
        if NARROW_MULTIPLY {
            [row(0), row(1), row(2)]
        } else {
            core::array::from_fn(row)
        }
    }

    /// [`transform_point`](Affine3::transform_point) without the saturation: the low word of
    /// the rounded Q16 sum. Equal to `transform_point(p)` whenever that result does not
    /// saturate, which [`point_bounds`](Affine3::point_bounds) proves for a whole set of points
    /// at once; otherwise the coordinate wraps (never panics). The vertex stage uses it for
    /// objects whose bound fits, saving the per-coordinate range check.
    #[inline]
    pub fn transform_point_wrapping(&self, p: Vec3) -> Vec3 {
        let [x, y, z] = self.rounded_rows(p).map(|v| v as i32);
        Vec3::from_bits(x, y, z)
    }

    /// For points whose raw coordinates all satisfy `|c| ≤ max_coord`, a bound per row on the
    /// magnitude of the raw (I16F16) result of
    /// [`transform_point`](Affine3::transform_point) before saturation:
    /// `|t_i| + ⌈Σ_j |m_ij|·max_coord / 2^24⌉ + 1` (the `+ 1` covers the rounding shift).
    /// When a row's bound is at most `i32::MAX` that coordinate never saturates, so
    /// [`transform_point_wrapping`](Affine3::transform_point_wrapping) gives the same value,
    /// and it is never `i32::MIN`. `Σ_j |m_ij| ≤ 3·2^30` and `max_coord < 2^32`, so the
    /// product stays below `3·2^62` in `u64`.
    pub fn point_bounds(&self, max_coord: u32) -> [u64; 3] {
        core::array::from_fn(|i| {
            let sum: u64 = self.m[i].iter().map(|&e| e.unsigned_abs() as u64).sum();
            let lin = (sum * max_coord as u64).div_ceil(1 << LINEAR_FRAC); // < 2^40
            self.t[i].unsigned_abs() as u64 + lin + 1
        })
    }

    /// `M·v` (no translation), rounded to nearest, saturating.
    pub fn transform_vector(&self, v: Vec3) -> Vec3 {
        Affine3::raw(self.m, [0; 3]).transform_point(v)
    }

    /// The inverse of a rigid transform (rotation + translation): `p = Rᵀ·(p' − t)`.
    /// [`MatrixError::NotRigid`] unless `R·Rᵀ = I` within 2^-12 per entry;
    /// [`MatrixError::OutOfRange`] if the new translation leaves the I16F16 range.
    pub fn inverse_rigid(&self) -> Result<Affine3, MatrixError> {
        for i in 0..3 {
            for j in 0..3 {
                let mut acc = 0i64;
                for k in 0..3 {
                    acc += self.m[i][k] as i64 * self.m[j][k] as i64; // Q48
                }
                let expect = if i == j { 1i64 << 48 } else { 0 };
                if (acc - expect).abs() > 1 << 36 {
                    return Err(MatrixError::NotRigid);
                }
            }
        }
        let mut m = [[0i32; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e = self.m[j][i];
            }
        }
        let mut t = [0i32; 3];
        for (i, ti) in t.iter_mut().enumerate() {
            let acc: i64 =
                -(m[i].iter().zip(self.t).map(|(&a, b)| a as i64 * b as i64)).sum::<i64>();
            *ti =
                i32::try_from(shr_round(acc, LINEAR_FRAC)).map_err(|_| MatrixError::OutOfRange)?;
        }
        Ok(Affine3::raw(m, t))
    }
}

impl Affine3 {
    /// A [`Affine3Builder`] starting from the identity: chain steps in the order they apply
    /// and check the result once with [`build`](Affine3Builder::build).
    ///
    /// ```
    /// use zscan::geometry::{fixed::Coord, matrix::Affine3, trig::BinaryAngle, vector::Vec3};
    ///
    /// let m = Affine3::builder()
    ///     .rotate_y(BinaryAngle::from_degrees(90))
    ///     .scale(Coord::from_num(2))
    ///     .translate(Vec3::from_int(0, 1, 0))
    ///     .build()?;
    /// // (1, 0, 0) turns to (0, 0, -1), doubles to (0, 0, -2), moves up to (0, 1, -2).
    /// assert_eq!(m.transform_point(Vec3::from_int(1, 0, 0)), Vec3::from_int(0, 1, -2));
    /// # Ok::<(), zscan::geometry::matrix::MatrixError>(())
    /// ```
    pub const fn builder() -> Affine3Builder {
        Affine3Builder {
            state: Ok(Affine3::IDENTITY),
        }
    }
}

/// Composes transforms in application order without a `Result` per step
/// ([`Affine3::builder`]).
///
/// Each step applies after the ones before it (`builder().rotate_y(a).translate(t)` rotates,
/// then translates), exactly as chaining [`Affine3::then`] would. A step that fails (a
/// factor beyond ±64, a zero rotation axis, a product out of range) puts the builder in a
/// failed state that later steps keep: [`build`](Affine3Builder::build) reports the first
/// error, once.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[must_use = "a builder does nothing until `build` is called"]
pub struct Affine3Builder {
    state: Result<Affine3, MatrixError>,
}

impl Affine3Builder {
    /// Applies `next` after the steps so far (the first error sticks).
    pub fn then(self, next: &Affine3) -> Affine3Builder {
        self.then_result(Ok(*next))
    }

    fn then_result(self, next: Result<Affine3, MatrixError>) -> Affine3Builder {
        Affine3Builder {
            state: self.state.and_then(|m| m.then(&next?)),
        }
    }

    /// Then a rotation by `a` about the x axis ([`Affine3::rotation_x`]).
    pub fn rotate_x(self, a: BinaryAngle) -> Affine3Builder {
        self.then(&Affine3::rotation_x(a))
    }

    /// Then a rotation by `a` about the y axis ([`Affine3::rotation_y`]).
    pub fn rotate_y(self, a: BinaryAngle) -> Affine3Builder {
        self.then(&Affine3::rotation_y(a))
    }

    /// Then a rotation by `a` about the z axis ([`Affine3::rotation_z`]).
    pub fn rotate_z(self, a: BinaryAngle) -> Affine3Builder {
        self.then(&Affine3::rotation_z(a))
    }

    /// Then a rotation by `a` about `axis` through the origin ([`Affine3::rotation_axis`];
    /// a zero axis fails the builder).
    pub fn rotate_axis(self, axis: Vec3, a: BinaryAngle) -> Affine3Builder {
        self.then_result(Affine3::rotation_axis(axis, a))
    }

    /// Then a uniform scaling by `s` about the origin ([`Affine3::scale`]; `|s| > 64` fails
    /// the builder).
    pub fn scale(self, s: Coord) -> Affine3Builder {
        self.then_result(Affine3::scale(s))
    }

    /// Then a scaling by `(sx, sy, sz)` about the origin ([`Affine3::scale3`]).
    pub fn scale3(self, sx: Coord, sy: Coord, sz: Coord) -> Affine3Builder {
        self.then_result(Affine3::scale3(sx, sy, sz))
    }

    /// Then a translation by `t` ([`Affine3::translation`]).
    pub fn translate(self, t: Vec3) -> Affine3Builder {
        self.then(&Affine3::translation(t))
    }

    /// True once a step has failed ([`build`](Affine3Builder::build) will return its error).
    pub const fn has_failed(&self) -> bool {
        self.state.is_err()
    }

    /// The composed transform, or the first step's error.
    pub const fn build(self) -> Result<Affine3, MatrixError> {
        self.state
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builder_equals_chained_then() {
        let a = BinaryAngle::from_degrees(37);
        let s = Coord::from_num(1.5);
        let t = Vec3::from_int(3, -2, 7);
        let built = Affine3::builder()
            .rotate_x(a)
            .rotate_y(a + a)
            .rotate_z(-a)
            .scale(s)
            .rotate_axis(Vec3::from_int(1, 2, 3), a)
            .scale3(s, Coord::ONE, s)
            .translate(t)
            .build()
            .unwrap();
        let chained = Affine3::rotation_x(a)
            .then(&Affine3::rotation_y(a + a))
            .and_then(|m| m.then(&Affine3::rotation_z(-a)))
            .and_then(|m| m.then(&Affine3::scale(s)?))
            .and_then(|m| m.then(&Affine3::rotation_axis(Vec3::from_int(1, 2, 3), a)?))
            .and_then(|m| m.then(&Affine3::scale3(s, Coord::ONE, s)?))
            .and_then(|m| m.then(&Affine3::translation(t)))
            .unwrap();
        assert_eq!(built, chained);
        assert_eq!(Affine3::builder().build(), Ok(Affine3::IDENTITY));
    }

    #[test]
    fn builder_reports_the_first_error_once() {
        let big = Coord::from_num(100);
        let b = Affine3::builder().scale(big);
        assert!(b.has_failed());
        // Later steps, even failing ones of another kind, keep the first error.
        let b = b
            .rotate_axis(Vec3::ZERO, BinaryAngle::from_degrees(10))
            .translate(Vec3::from_int(1, 0, 0));
        assert_eq!(b.build(), Err(MatrixError::OutOfRange));
        let b = Affine3::builder().rotate_axis(Vec3::ZERO, BinaryAngle::from_degrees(10));
        assert_eq!(b.scale(big).build(), Err(MatrixError::ZeroAxis));
        // A product out of range fails too: 8 × 8 × 8 exceeds ±64.
        let eight = Coord::from_num(8);
        let b = Affine3::builder().scale(eight).scale(eight);
        assert!(!b.has_failed());
        assert_eq!(b.scale(eight).build(), Err(MatrixError::OutOfRange));
    }

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
    }

    fn close(a: Vec3, b: Vec3, tol: i32) -> bool {
        let (a, b) = (a.bits(), b.bits());
        (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
    }

    #[test]
    fn rotations_follow_the_right_hand_rule() {
        let q = BinaryAngle::QUARTER_TURN;
        assert_eq!(
            Affine3::rotation_z(q).transform_point(v(1.0, 0.0, 0.0)),
            v(0.0, 1.0, 0.0)
        );
        assert_eq!(
            Affine3::rotation_x(q).transform_point(v(0.0, 1.0, 0.0)),
            v(0.0, 0.0, 1.0)
        );
        assert_eq!(
            Affine3::rotation_y(q).transform_point(v(0.0, 0.0, 1.0)),
            v(1.0, 0.0, 0.0)
        );
    }

    #[test]
    fn axis_rotation_matches_principal_axes() {
        for deg in [0, 17, 90, 123, 200, 359] {
            let a = BinaryAngle::from_degrees(deg);
            for (axis, r) in [
                (v(1.0, 0.0, 0.0), Affine3::rotation_x(a)),
                (v(0.0, 2.0, 0.0), Affine3::rotation_y(a)),
                (v(0.0, 0.0, -0.5), Affine3::rotation_z(-a)),
            ] {
                let g = Affine3::rotation_axis(axis, a).unwrap();
                for i in 0..3 {
                    for j in 0..3 {
                        assert!((g.m[i][j] - r.m[i][j]).abs() <= 2, "{deg} {i}{j}");
                    }
                }
            }
        }
        assert_eq!(
            Affine3::rotation_axis(Vec3::ZERO, BinaryAngle(1)),
            Err(MatrixError::ZeroAxis)
        );
    }

    #[test]
    fn composition_and_rigid_inverse() {
        let r = Affine3::rotation_axis(v(1.0, 2.0, -3.0), BinaryAngle::from_degrees(40)).unwrap();
        let t = Affine3::translation(v(3.0, -1.5, 7.25));
        let m = t.mul(&r).unwrap();
        assert_eq!(m, r.then(&t).unwrap());
        let inv = m.inverse_rigid().unwrap();
        let p = v(0.3, -5.0, 2.0);
        let back = inv.transform_point(m.transform_point(p));
        assert!(close(back, p, 2), "{back:?}");
        assert!(close(inv.mul(&m).unwrap().transform_point(p), p, 2));
        let s = Affine3::scale(Coord::from_num(2)).unwrap();
        assert_eq!(s.inverse_rigid(), Err(MatrixError::NotRigid));
        assert_eq!(s.transform_point(p), v(0.6, -10.0, 4.0));
    }

    #[test]
    fn wrapping_transform_equals_saturating_within_the_bound() {
        let mut rng = crate::test_rng::XorShift(0x9E37_79B9_7F4A_7C15u64);
        let mut rnd = || rng.next_u64();
        let mc = crate::geometry::mesh::MAX_MESH_COORD_BITS as u32;
        let r = |k: u64, b: u32| (k % (2 * b as u64 + 1)) as i64 - b as i64;
        for n in 0..400 {
            // Random matrices from tiny to extreme (±2^30 entries, full-range translation).
            let es = [6, 14, 22, 30][n % 4];
            let ts = [10, 20, 31][n % 3];
            let rows = core::array::from_fn(|_| {
                core::array::from_fn(|_| r(rnd(), (1u32 << es).min(MAX_LINEAR_BITS as u32)) as i32)
            });
            let t = Vec3::from_bits(
                r(rnd(), (1u32 << ts) - 1) as i32,
                r(rnd(), (1u32 << ts) - 1) as i32,
                r(rnd(), (1u32 << ts) - 1) as i32,
            );
            let m = Affine3::from_bits(rows, t).unwrap();
            for max in [mc, 1 << 16, 1000] {
                let b = m.point_bounds(max);
                let check = |p: [i64; 3]| {
                    let p = Vec3::from_bits(p[0] as i32, p[1] as i32, p[2] as i32);
                    let (s, w) = (
                        m.transform_point(p).bits(),
                        m.transform_point_wrapping(p).bits(),
                    );
                    for i in 0..3 {
                        // The exact (unsaturated) result is within the bound…
                        let r = &m.m[i];
                        let pb = p.bits();
                        let exact = (m.t_wide[i]
                            + (0..3).map(|j| r[j] as i64 * pb[j] as i64).sum::<i64>())
                            >> LINEAR_FRAC;
                        assert!(exact.unsigned_abs() <= b[i], "{exact} > {}", b[i]);
                        // …and where the bound fits, the wrapping transform is the saturating one.
                        if b[i] <= i32::MAX as u64 {
                            assert_eq!(s[i], w[i]);
                            assert_ne!(w[i], i32::MIN);
                        }
                    }
                };
                for _ in 0..20 {
                    check([r(rnd(), max), r(rnd(), max), r(rnd(), max)]);
                }
                // The corners, where |M·p| is largest.
                for k in 0..27 {
                    let c = |d: i64| (d - 1) * max as i64;
                    check([c(k % 3), c(k / 3 % 3), c(k / 9)]);
                }
            }
        }
        // A bound beyond i32 where the saturating transform does clamp.
        let s = Affine3::scale(Coord::from_num(64)).unwrap();
        assert!(s.point_bounds(mc)[0] > i32::MAX as u64);
        assert!(s.point_bounds(1 << 16)[0] <= i32::MAX as u64);
    }

    #[test]
    fn extremes_are_errors_or_saturate() {
        assert_eq!(
            Affine3::scale(Coord::from_num(65)),
            Err(MatrixError::OutOfRange)
        );
        let s = Affine3::scale(Coord::from_num(64)).unwrap();
        assert_eq!(s.mul(&s), Err(MatrixError::OutOfRange));
        let big = Vec3::from_bits(i32::MAX, i32::MIN, i32::MAX);
        let p = s.transform_point(big);
        assert_eq!(p, Vec3::from_bits(i32::MAX, i32::MIN, i32::MAX));
        let t = Affine3::translation(big);
        assert_eq!(t.mul(&t), Err(MatrixError::OutOfRange));
        assert!(Affine3::from_bits([[i32::MAX, 0, 0], [0; 3], [0; 3]], Vec3::ZERO).is_err());
    }
}
