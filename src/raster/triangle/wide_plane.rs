//! The wide plane: the exact interpolant of **any** triangle of the raster's range, for the
//! few whose `2D` reaches `2^31` (large viewports, guard-band fan triangles).
//!
//! Role in the pipeline: the span writers' last plane, set up out of line only for the
//! triangles the general [`AttributePlane`](super::plane::AttributePlane) refuses
//! ([`PlaneError::TooLarge`](super::plane::PlaneError::TooLarge)), so the others run the
//! instructions they ran before. Same values as the other planes; conventions and the rounded
//! value: the `plane` module's doc.
//!
//! Numeric contract: `D < 2^58`, `i128` set-up and span starts, a 64-bit remainder
//! ([`ExactWide`]); see [`WidePlane`].

use super::interpolants::{Dda, Interpolant, SpanStarts};
use super::plane::PlaneError;
use super::setup::TriangleSetup;
use crate::raster::SubpixelPoint;

/// [`Exact`] with a 64-bit remainder: the correctly rounded value of a [`WidePlane`], whose
/// `2D` may reach `2^59`. Same value, remainder and carry rule as [`Exact`].
#[derive(Debug, Clone, Copy)]
pub struct ExactWide {
    value: u32,
    /// Remainder of `2M + D` by `2D`, in `0..two_d`.
    rem: u64,
    /// Quotient added per pixel (mod 2^32).
    pub(super) q: u32,
    /// Remainder added per pixel, in `0..two_d`.
    pub(super) r: u64,
    /// `2D < 2^59`: `rem + r < 2^60` cannot overflow.
    two_d: u64,
}

impl ExactWide {
    /// The remainder of the value's numerator and `2D` (as [`Exact::remainder`]).
    #[cfg(test)]
    pub fn remainder(&self) -> (u64, u64) {
        (self.rem, self.two_d)
    }
}

impl Interpolant for ExactWide {
    #[inline(always)]
    fn value(&self) -> u32 {
        self.value
    }

    #[inline(always)]
    fn step(&mut self) {
        let t = self.rem + self.r;
        let carry = t >= self.two_d;
        self.rem = if carry { t - self.two_d } else { t };
        self.value = self.value.wrapping_add(self.q).wrapping_add(carry as u32);
    }
}

/// The exact affine interpolant of `N` attributes over **any** triangle of the raster's range
/// (`|x|, |y| ≤ 2^28 − 1` sub-pixel units): the same values as [`AttributePlane`], for the
/// triangles whose `2D` reaches `2^31` (its [`PlaneError::TooLarge`]).
///
/// ## Why a third plane, and not a tighter guard band
/// Screen triangles that large are legitimate: a quad filling a 512×512 view is two
/// triangles of `D = 2^26` at `S = 4`, the guard band ([`Frustum`](crate::clip::frustum::Frustum))
/// lets a clipped polygon's fan triangles reach four times the screen, and a 4096×4096 view
/// alone holds triangles of `D = 2^32`. No guard band can keep `D < 2^30` at such sizes, and
/// a screen-space split would put new vertices at rounded positions, changing edges or
/// values. So the planes take larger triangles: [`AttributePlane::new`] keeps its 32-bit
/// stepping (every triangle of the standard scenes), and only when it reports
/// [`PlaneError::TooLarge`] do the span writers call this set-up, out of line, so that the
/// common triangles run exactly the instructions they ran before.
///
/// ## Numeric contract
/// - Differences of vertex coordinates are below `2^29`, so `D < 2^58` (a triangle fills at
///   most half its box) and `2D < 2^59`: [`ExactWide`]'s remainder, step and `2D` are `u64`,
///   `rem + r < 2^60`.
/// - `|A1 − A0|, |A2 − A0| < 2^32`: `|gx|, |gy| < 2·2^32·2^29 = 2^62`, exact in `i64`.
/// - `M(p)` and `gx·F` are formed in `i128` (`|gx·px| < 2^62·2^48`), and every division is an
///   exact floored `i128` division: a span start costs one `i128` division per attribute
///   (evaluated directly, no row carry: these triangles are few and their spans long).
/// - Quotients are kept mod `2^32`, like the values themselves (wrapping, exact at covered
///   pixels as the module doc says).
#[derive(Debug, Clone)]
pub struct WidePlane<const N: usize, const S: u32> {
    origin: SubpixelPoint<S>,
    base: [u32; N],
    gx: [i64; N],
    gy: [i64; N],
    /// `D`, positive, `< 2^58`.
    d: u64,
    /// Per attribute, `(q, r)` of one pixel step right.
    step_x: [(u32, u64); N],
}

impl<const N: usize, const S: u32> WidePlane<N, S> {
    /// Sets up the plane of `values[i]` at vertex `v[i]` (vertices within the raster's range),
    /// as [`Self::of`].
    #[cfg(test)]
    pub fn new(v: [SubpixelPoint<S>; 3], values: [[u32; N]; 3]) -> Result<Self, PlaneError> {
        Self::of(&TriangleSetup::in_range(v), values)
    }

    /// The plane of `values[i]` at the given vertex `i` of set-up `t`;
    /// [`PlaneError::Degenerate`] for a triangle of zero area, never `TooLarge`.
    pub(crate) fn of(t: &TriangleSetup<S>, values: [[u32; N]; 3]) -> Result<Self, PlaneError> {
        let v = t.given;
        let (x0, y0) = (v[0].x as i64, v[0].y as i64);
        let (dx1, dy1) = (v[1].x as i64 - x0, v[1].y as i64 - y0);
        let (dx2, dy2) = (v[2].x as i64 - x0, v[2].y as i64 - y0);
        // The set-up's twice-area, below 2^59.
        let cross = t.given_twice_area();
        if cross == 0 {
            return Err(PlaneError::Degenerate);
        }
        let sign = cross.signum();
        let d = cross.unsigned_abs();
        let mut gx = [0i64; N];
        let mut gy = [0i64; N];
        let mut step_x = [(0u32, 0u64); N];
        for i in 0..N {
            let a1 = values[1][i] as i64 - values[0][i] as i64;
            let a2 = values[2][i] as i64 - values[0][i] as i64;
            gx[i] = sign * (a1 * dy2 - a2 * dy1);
            gy[i] = sign * (a2 * dx1 - a1 * dx2);
            // One pixel right adds 2·gx·F to 2M + D: quotient ⌊gx·F / D⌋, remainder
            // 2·(gx·F mod D).
            let gf = (gx[i] as i128) << S;
            let (q, r) = (gf.div_euclid(d as i128), gf.rem_euclid(d as i128));
            step_x[i] = (q as u32, 2 * r as u64);
        }
        Ok(WidePlane {
            origin: v[0],
            base: values[0],
            gx,
            gy,
            d,
            step_x,
        })
    }

    /// `M(p)` of the module doc at pixel `(x, y)`, exactly.
    #[inline]
    fn m(&self, i: usize, x: i32, y: i32) -> i128 {
        let px = ((x as i64) << S) - self.origin.x as i64;
        let py = ((y as i64) << S) - self.origin.y as i64;
        self.gx[i] as i128 * px as i128 + self.gy[i] as i128 * py as i128
    }

    /// Attribute `i < N` at the covered pixel `(x, y)`, ready to step right exactly: the
    /// value [`AttributePlane::exact`] gives where both apply.
    pub fn exact(&self, i: usize, x: i32, y: i32) -> ExactWide {
        let two_d = 2 * self.d as i128;
        let n = 2 * self.m(i, x, y) + self.d as i128;
        ExactWide {
            value: self.base[i].wrapping_add(n.div_euclid(two_d) as u32),
            rem: n.rem_euclid(two_d) as u64,
            q: self.step_x[i].0,
            r: self.step_x[i].1,
            two_d: two_d as u64,
        }
    }

    /// Attribute `i < N` at the covered pixel `(x, y)` as a 16.16 [`Dda`]: the value
    /// [`AttributePlane::dda`] gives where both apply (attributes below `2^15`).
    pub fn dda(&self, i: usize, x: i32, y: i32) -> Dda {
        let d = self.d as i128;
        let start = ((self.base[i] as i128) << 16) + (self.m(i, x, y) << 16).div_euclid(d);
        let inc = ((self.gx[i] as i128) << (16 + S)).div_euclid(d);
        Dda {
            acc: (start + (1 << 15)) as u32,
            inc: inc as u32,
        }
    }
}

impl<const N: usize, const S: u32> SpanStarts<N> for WidePlane<N, S> {
    type Exact = ExactWide;

    #[inline]
    fn exact_at(&mut self, x: i32, y: i32) -> [ExactWide; N] {
        core::array::from_fn(|i| self.exact(i, x, y))
    }

    #[inline]
    fn dda_at(&self, i: usize, x: i32, y: i32) -> Dda {
        self.dda(i, x, y)
    }
}
