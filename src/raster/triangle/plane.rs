//! Exact incremental interpolation of per-vertex integer attributes over a triangle.
//!
//! Role in the pipeline: between the triangle fill and the span writers. Depth, Gouraud
//! luminance and any other per-vertex quantity go through this one mechanism: an
//! [`AttributePlane<N>`] holds `N` attributes; at the start of each span it gives, per
//! attribute, an [`Interpolant`] that steps one pixel right with integer adds only. Span loops
//! are generic over [`Interpolant`], so a flat attribute ([`Constant`]) costs nothing per pixel
//! and the exact ([`Exact`]) and fast ([`Dda`]) variants share one loop.
//!
//! Three set-ups give the same values: [`AttributePlane`] (`2D < 2^30`; `i64` products, span
//! starts carried row to row by [`RowStarts`] on 32-bit targets), [`SmallPlane`] (a
//! bounding box below `2^K` sub-pixel units, `K = 10` at `S = 4`: every product, division and
//! remainder fits 32 bits, so a span start is two multiply-adds and one 32-bit division per
//! attribute and the set-up has no 64-bit division) and [`WidePlane`] (any triangle of the
//! raster's range, `i128` set-up and starts, a 64-bit remainder: [`ExactWide`]), taken out of
//! line only for the triangles [`AttributePlane`] refuses (its doc says why this, and not a
//! tighter guard band). Span loops take any of them through [`SpanStarts`].
//!
//! ## What is computed
//! With vertices `P0, P1, P2` (sub-pixel units, `F = 2^S`) and values `A0, A1, A2`, the affine
//! interpolant at pixel `(x, y)` (the point `p = (x·F, y·F)`) is `A(p) = A0 + M(p) / D` with
//!
//! ```text
//! D    = (P1 − P0) × (P2 − P0)                   (twice the signed area; made positive)
//! M(p) = gx·(p.x − X0) + gy·(p.y − Y0)
//! gx   = (A1−A0)·(Y2−Y0) − (A2−A0)·(Y1−Y0)
//! gy   = (A2−A0)·(X1−X0) − (A1−A0)·(X2−X0)
//! ```
//!
//! and every pixel receives the **correctly rounded** value `A0 + ⌊(2M + D) / 2D⌋`
//! (round half up). The cursor keeps that quotient and its remainder `0 ≤ rem < 2D`: a step adds
//! a precomputed quotient and remainder and carries once, so there is no drift on any span
//! length (the exact variant of course exercise 18).
//!
//! ## Numeric contract
//! - Attribute values are `u32` (depth uses the full range). Values are added with wrapping
//!   arithmetic: at a covered pixel the true value is a convex combination of the vertex values,
//!   so it lies in `0..2^32` and the wrapped result equals it exactly.
//! - [`AttributePlane`] and [`SmallPlane`]: `0 < D < 2^30` (at `S = 4`, triangles up to 2 M
//!   square pixels): the remainder and `2D` fit `u32` with room for one addition. Larger
//!   triangles are [`PlaneError::TooLarge`] there and go to [`WidePlane`] (`D < 2^58`, the
//!   whole raster range: a quad filling a 512×512 view already has `D = 2^26`, the guard band
//!   lets fan triangles reach 16 times that, a 4096×4096 view `2^32`).
//! - `|A1 − A0|, |A2 − A0| ≤ 2^32` and coordinate differences `< 2^29` give `|gx|, |gy| < 2^62`.
//!   `M` at a covered pixel is bounded by `D·2^32 < 2^62`; it is evaluated with wrapping
//!   products, exact because the true result is in range.
//! - [`SmallPlane`]: `D < 2^(2K)` and the decomposition of its doc keep every intermediate
//!   below `2^31` (`i32`) or `2^32` (`u32`); quotients that only move values are kept mod
//!   `2^32`, like the values themselves.

#[cfg(test)]
use super::interpolants::Interpolant;
use super::interpolants::{Dda, Exact, SpanStarts};
use super::setup::TriangleSetup;
use crate::arith::euclid::Divisor;
use crate::arith::WIDE_REGISTERS;
use crate::raster::SubpixelPoint;

/// Why an attribute plane could not be set up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlaneError {
    /// The triangle has zero area: it covers no pixel, nothing to interpolate.
    Degenerate,
    /// Twice the area is `2^30` sub-pixel units squared or more.
    TooLarge,
}

/// Exact values at the successive span starts of one triangle, carried from row to row.
///
/// Consecutive spans of a triangle start on consecutive rows, and their starts move by the
/// left edge's slope: `q` or `q + 1` pixels. The move `(dx, +1)` is divided once per distinct
/// `dx` (two are cached) and then applied with one add and one carry per attribute, so a row
/// costs no division. Any other start (first span, a jump) is evaluated directly.
#[derive(Debug)]
pub struct RowStarts<'p, const N: usize, const S: u32> {
    plane: &'p AttributePlane<N, S>,
    /// The previous span start (`y = i32::MIN` before the first).
    x: i32,
    y: i32,
    values: [Exact; N],
    /// Two cached moves: `dx` and the per-attribute `(q, r)` of `(dx, +1)`.
    dx: [i32; 2],
    moves: [[(u32, u32); N]; 2],
}

impl<'p, const N: usize, const S: u32> RowStarts<'p, N, S> {
    /// Starts with no previous span.
    pub fn new(plane: &'p AttributePlane<N, S>) -> Self {
        let none = Exact {
            value: 0,
            rem: 0,
            q: 0,
            r: 0,
            two_d: 1,
        };
        RowStarts {
            plane,
            x: 0,
            y: i32::MIN,
            values: [none; N],
            dx: [i32::MIN; 2],
            moves: [[(0, 0); N]; 2],
        }
    }

    /// The exact values at `(x, y)` (a covered pixel), ready to step right.
    ///
    /// Where a 64-bit division is one instruction (64-bit targets) the values are evaluated
    /// directly, which counts fewer instructions than the carried form; on 32-bit targets,
    /// where it is a library call of about a hundred instructions, they are carried from the
    /// previous row. Both give the same values (tested).
    #[inline]
    pub fn at(&mut self, x: i32, y: i32) -> [Exact; N] {
        if WIDE_REGISTERS {
            self.direct(x, y)
        } else {
            self.carried(x, y)
        }
    }

    /// The values at `(x, y)` by direct evaluation (a loop, not `array::from_fn`, which the
    /// compiler left out of line here).
    #[inline(always)]
    fn direct(&mut self, x: i32, y: i32) -> [Exact; N] {
        for i in 0..N {
            self.values[i] = self.plane.exact(i, x, y);
        }
        self.values
    }

    /// [`RowStarts::at`] by carrying the previous row's values (the 32-bit targets' form).
    #[inline]
    pub fn carried(&mut self, x: i32, y: i32) -> [Exact; N] {
        let dx = x.wrapping_sub(self.x);
        if self.y.wrapping_add(1) == y && dx.unsigned_abs() <= 1 << 15 {
            let slot = if self.dx[0] == dx {
                0
            } else if self.dx[1] == dx {
                1
            } else {
                // Replace the older entry: slot 1 moves to 0, the new move goes to 1.
                self.dx[0] = self.dx[1];
                self.moves[0] = self.moves[1];
                self.dx[1] = dx;
                self.moves[1] = self.plane.row_move(dx);
                1
            };
            for (e, m) in self.values.iter_mut().zip(self.moves[slot]) {
                e.advance(m);
            }
        } else {
            self.direct(x, y);
        }
        self.x = x;
        self.y = y;
        self.values
    }
}

/// The exact affine interpolant of `N` attributes over one triangle.
#[derive(Debug, Clone)]
pub struct AttributePlane<const N: usize, const S: u32> {
    origin: SubpixelPoint<S>,
    base: [u32; N],
    gx: [i64; N],
    gy: [i64; N],
    d: i64,
    /// `d` prepared for repeated division (a reciprocal on 32-bit targets).
    div: Divisor,
    /// Per attribute, `(q, r)` of one pixel step right.
    step_x: [(u32, u32); N],
    /// Per attribute, `gx = D·g1 + g0` and `gy = D·h1 + h0` (`0 ≤ g0, h0 < D`): lets a move
    /// by `(dx, 1)` be divided with products below 2^51 ([`AttributePlane::row_move`]).
    split: [(i64, i64, i64, i64); N],
}

impl<const N: usize, const S: u32> AttributePlane<N, S> {
    /// Sets up the plane of `values[i]` at vertex `v[i]` (vertices within the raster's range).
    #[cfg(test)]
    pub fn new(v: [SubpixelPoint<S>; 3], values: [[u32; N]; 3]) -> Result<Self, PlaneError> {
        Self::of(&TriangleSetup::in_range(v), values)
    }

    /// The plane of `values[i]` at the given vertex `i` of set-up `t`.
    #[inline(always)]
    pub(crate) fn of(t: &TriangleSetup<S>, values: [[u32; N]; 3]) -> Result<Self, PlaneError> {
        let v = t.given;
        // The raster's range (the set-up's), on which the products below rely (|dx|, |dy| < 2^29).
        let (x0, y0) = (v[0].x as i64, v[0].y as i64);
        let (dx1, dy1) = (v[1].x as i64 - x0, v[1].y as i64 - y0);
        let (dx2, dy2) = (v[2].x as i64 - x0, v[2].y as i64 - y0);
        let mut d = t.given_twice_area();
        if d == 0 {
            return Err(PlaneError::Degenerate);
        }
        let sign = d.signum();
        d = d.abs();
        if d >= 1 << 30 {
            return Err(PlaneError::TooLarge);
        }
        let mut gx = [0i64; N];
        let mut gy = [0i64; N];
        let mut step_x = [(0u32, 0u32); N];
        let mut split = [(0i64, 0i64, 0i64, 0i64); N];
        let f = 1i64 << S;
        let div = Divisor::new(d);
        for i in 0..N {
            let a1 = values[1][i] as i64 - values[0][i] as i64;
            let a2 = values[2][i] as i64 - values[0][i] as i64;
            gx[i] = sign * (a1 * dy2 - a2 * dy1);
            gy[i] = sign * (a2 * dx1 - a1 * dx2);
            // One pixel right adds 2·gx·F to 2M + D: quotient ⌊gx·F / D⌋ (mod 2^32), remainder
            // 2·(gx·F mod D). Split gx = D·g1 + g0 so no product exceeds 2^46.
            let (g1, g0) = div.div_floor(gx[i]);
            let (q0, r0) = div.div_floor(g0 << S);
            step_x[i] = ((g1.wrapping_mul(f) + q0) as u32, (2 * r0) as u32);
            let (h1, h0) = div.div_floor(gy[i]);
            split[i] = (g1, g0, h1, h0);
        }
        Ok(AttributePlane {
            origin: v[0],
            base: values[0],
            gx,
            gy,
            d,
            div,
            step_x,
            split,
        })
    }

    /// `M(p)` of the module doc at pixel `(x, y)` (wrapping products, exact in range).
    #[inline(always)]
    fn m(&self, i: usize, x: i32, y: i32) -> i64 {
        let px = ((x as i64) << S) - self.origin.x as i64;
        let py = ((y as i64) << S) - self.origin.y as i64;
        self.gx[i]
            .wrapping_mul(px)
            .wrapping_add(self.gy[i].wrapping_mul(py))
    }

    /// Attribute `i < N` at pixel `(x, y)`, which must be covered by the triangle (see the
    /// module's numeric contract), ready to step right exactly.
    #[inline]
    pub fn exact(&self, i: usize, x: i32, y: i32) -> Exact {
        let two_d = 2 * self.d;
        // ⌊(2M + D) / 2D⌋ = ⌊⌊(2M + D) / D⌋ / 2⌋, remainder r' + D·(q' mod 2): one division by
        // the prepared D.
        let (q1, r1) = self.div.div_floor(2 * self.m(i, x, y) + self.d);
        let (q, rem) = (q1 >> 1, r1 + (q1 & 1) * self.d);
        Exact {
            value: self.base[i].wrapping_add(q as u32),
            rem: rem as u32,
            q: self.step_x[i].0,
            r: self.step_x[i].1,
            two_d: two_d as u32,
        }
    }

    /// Attribute `i < N` at pixel `(x, y)` as a fast 16.16 [`Dda`]. Only for attributes whose
    /// vertex values are below `2^15`.
    #[inline]
    pub fn dda(&self, i: usize, x: i32, y: i32) -> Dda {
        let start = ((self.base[i] as i64) << 16) + self.div.div_floor(self.m(i, x, y) << 16).0;
        let inc = self.div.div_floor(self.gx[i] << (16 + S)).0;
        Dda {
            acc: (start + (1 << 15)) as u32,
            inc: inc as u32,
        }
    }

    /// `(q, r)` per attribute of the move from pixel `(x, y)` to `(x + dx, y + 1)`, for
    /// `|dx| ≤ 2^15`: `2F·(gx·dx + gy)` divided by `2D`, via the split of `gx` and `gy`.
    #[inline]
    pub fn row_move(&self, dx: i32) -> [(u32, u32); N] {
        let dx = dx as i64;
        let mut out = [(0, 0); N];
        for (i, o) in out.iter_mut().enumerate() {
            let (g1, g0, h1, h0) = self.split[i];
            // F·(g0·dx + h0): |g0·dx| < 2^45, so below 2^47 · 2^S.
            let (q, r) = self.div.div_floor((g0 * dx + h0) << S);
            let whole = (g1.wrapping_mul(dx).wrapping_add(h1)).wrapping_shl(S);
            *o = (whole.wrapping_add(q) as u32, (2 * r) as u32);
        }
        out
    }

    /// All values at pixel `(x, y)`, exactly rounded.
    #[cfg(test)]
    pub fn values_at(&self, x: i32, y: i32) -> [u32; N] {
        core::array::from_fn(|i| self.exact(i, x, y).value())
    }

    /// The longest run an [`ExactRun`] of this plane keeps exact: `⌊(2^32 − 1) / 2D⌋`.
    pub fn run_limit(&self) -> u32 {
        u32::MAX / (2 * self.d) as u32
    }
}

impl<const N: usize, const S: u32> SpanStarts<N> for RowStarts<'_, N, S> {
    type Exact = Exact;

    #[inline(always)]
    fn exact_at(&mut self, x: i32, y: i32) -> [Exact; N] {
        self.at(x, y)
    }

    #[inline(always)]
    fn dda_at(&self, i: usize, x: i32, y: i32) -> Dda {
        self.plane.dda(i, x, y)
    }
}

#[cfg(test)]
mod tests {
    use super::super::interpolants::ExactRun;
    use super::super::small_plane::{
        small_bits, split_gradient, split_gradient_narrow, SmallPlane,
    };
    use super::super::wide_plane::WidePlane;
    use super::*;
    use crate::arith::euclid::DivisorU32;
    use core::num::NonZeroU32;

    /// Correctly rounded interpolant, straight from barycentric coordinates in i128.
    fn exact(v: [SubpixelPoint<4>; 3], a: [u32; 3], x: i32, y: i32) -> u32 {
        let p = |q: SubpixelPoint<4>| (q.x as i128, q.y as i128);
        let ((x0, y0), (x1, y1), (x2, y2)) = (p(v[0]), p(v[1]), p(v[2]));
        let (px, py) = ((x as i128) << 4, (y as i128) << 4);
        let d = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
        let w1 = (px - x0) * (y2 - y0) - (py - y0) * (x2 - x0);
        let w2 = (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0);
        let w0 = d - w1 - w2;
        let num = w0 * a[0] as i128 + w1 * a[1] as i128 + w2 * a[2] as i128;
        let (num, d) = if d < 0 { (-num, -d) } else { (num, d) };
        (2 * num + d).div_euclid(2 * d) as u32
    }

    #[test]
    fn every_pixel_is_correctly_rounded() {
        let mut rng = crate::test_rng::XorShift(0xDEAD_BEEF_1234_5678u64);
        let mut rnd = |m: u64| rng.next_u64() % m;
        let window = crate::raster::Window::new(0, 0, 64, 64);
        let mut checked = 0;
        for _ in 0..400 {
            let v = [0; 3].map(|_| SubpixelPoint::<4>::new(rnd(1024) as i32, rnd(1024) as i32));
            let a = [0; 3].map(|_| [rnd(1 << 32) as u32, rnd(256) as u32]);
            let Ok(plane) = AttributePlane::<2, 4>::new(v, a) else {
                continue;
            };
            crate::raster::triangle::fill_triangle(v, &window, |s| {
                let mut c = [plane.exact(0, s.x0, s.y), plane.exact(1, s.x0, s.y)];
                for x in s.x0..s.x1 {
                    for (i, got) in c.iter_mut().enumerate() {
                        let want = exact(v, [a[0][i], a[1][i], a[2][i]], x, s.y);
                        assert_eq!(got.value(), want, "attr {i} at ({x},{}) of {v:?}", s.y);
                        got.step();
                    }
                    checked += 1;
                }
            })
            .unwrap();
        }
        assert!(checked > 100_000, "{checked}");
    }

    #[test]
    fn row_starts_equal_direct_evaluation() {
        let mut rng = crate::test_rng::XorShift(0x1234_5678_9ABC_DEF0u64);
        let mut rnd = |m: u64| rng.next_u64() % m;
        let window = crate::raster::Window::new(-5, -5, 80, 80);
        let mut rows = 0;
        for _ in 0..300 {
            let v = [0; 3]
                .map(|_| SubpixelPoint::<4>::new(rnd(1400) as i32 - 100, rnd(1400) as i32 - 100));
            let a = [0; 3].map(|_| [rnd(1 << 32) as u32, rnd(256) as u32]);
            let Ok(plane) = AttributePlane::<2, 4>::new(v, a) else {
                continue;
            };
            let mut starts = RowStarts::new(&plane);
            crate::raster::triangle::fill_triangle(v, &window, |s| {
                let got = starts.carried(s.x0, s.y);
                for (i, g) in got.iter().enumerate() {
                    let want = plane.exact(i, s.x0, s.y);
                    assert_eq!((g.value(), g.remainder()), (want.value(), want.remainder()));
                }
                rows += 1;
            })
            .unwrap();
        }
        assert!(rows > 2000, "{rows}");
    }

    #[test]
    fn exact_runs_stay_exact_up_to_their_limit() {
        let mut rng = crate::test_rng::XorShift(0x0F0F_1234_5555_AAAAu64);
        let mut rnd = |m: u64| rng.next_u64() % m;
        let mut pixels = 0u64;
        for i in 0..3000 {
            // Small and large triangles: limits from a few pixels to thousands.
            let m = [64u64, 1024, 16384][i % 3];
            let v = [0; 3].map(|_| SubpixelPoint::<4>::new(rnd(m) as i32, rnd(m) as i32));
            let a = [0; 3].map(|_| [rnd(1 << 32) as u32]);
            let Ok(plane) = AttributePlane::<1, 4>::new(v, a) else {
                continue;
            };
            let (x, y) = (rnd(m >> 4) as i32, rnd(m >> 4) as i32);
            let mut exact = plane.exact(0, x, y);
            let limit = exact.run_limit().min(5000);
            let mut run = ExactRun::start(&exact, &ExactRun::prepare(&exact));
            for _ in 0..limit {
                assert_eq!(run.value(), exact.value(), "{v:?} {a:?} limit {limit}");
                run.step();
                exact.step();
                pixels += 1;
            }
        }
        assert!(pixels > 100_000, "{pixels}");
    }

    /// The 32-bit plane gives the general plane's exact values, remainders, steps and DDAs at
    /// every covered pixel, for boxes up to its limit and attribute differences up to 2^32.
    fn small_plane_matches<const S: u32>(seed: u64, count: usize) -> (u64, u64) {
        let mut rng = crate::test_rng::XorShift(seed);
        let mut rnd = |m: u64| rng.next_u64() % m;
        let lim = 1u64 << small_bits(S);
        let window = crate::raster::Window::new(-100, -100, 200, 200);
        let (mut pixels, mut planes) = (0u64, 0);
        for i in 0..count {
            // Boxes from a few sub-pixel units to the limit (and a little over: rejected).
            let m = [24, 200.min(lim), lim, lim + 1, lim + 60][i % 5];
            let o = (rnd(2000) as i32 - 1000, rnd(2000) as i32 - 1000);
            let v =
                [0; 3].map(|_| SubpixelPoint::<S>::new(o.0 + rnd(m) as i32, o.1 + rnd(m) as i32));
            let a = [0; 3].map(|_| match i % 3 {
                0 => [rnd(1 << 32) as u32, rnd(256) as u32],
                1 => [u32::MAX - rnd(3) as u32, rnd(2) as u32 * 255],
                _ => [rnd(1 << 20) as u32 + (3 << 30), rnd(1 << 15) as u32],
            });
            let general = AttributePlane::<2, S>::new(v, a);
            let Some(small) = SmallPlane::<2, S>::new(v, a) else {
                let xs = v.map(|p| p.x);
                let ys = v.map(|p| p.y);
                let w = xs.iter().max().unwrap() - xs.iter().min().unwrap();
                let h = ys.iter().max().unwrap() - ys.iter().min().unwrap();
                assert!(
                    w as u64 >= lim || h as u64 >= lim || general.is_err(),
                    "{v:?}"
                );
                continue;
            };
            let general = general.unwrap();
            assert_eq!(small.run_limit(), general.run_limit());
            planes += 1;
            crate::raster::triangle::fill_triangle(v, &window, |s| {
                for x in s.x0..s.x1 {
                    for i in 0..2 {
                        let (mut g, mut e) = (general.exact(i, x, s.y), small.exact(i, x, s.y));
                        for _ in 0..2 {
                            assert_eq!(
                                (e.value(), e.remainder()),
                                (g.value(), g.remainder()),
                                "attr {i} at ({x},{}) of {v:?} {a:?}",
                                s.y
                            );
                            g.step();
                            e.step();
                        }
                    }
                    let (g, e) = (general.dda(1, x, s.y), small.dda(1, x, s.y));
                    assert_eq!((e.acc, e.inc), (g.acc, g.inc), "dda at ({x},{}) {v:?}", s.y);
                    pixels += 1;
                }
            })
            .unwrap();
        }
        (planes, pixels)
    }

    /// The corner form's numerator `e'` at its extremes: right triangles filling half of the
    /// largest box (`2^K − 1` units a side, `D = W·H`) in each of its four corners, values with
    /// the largest and random differences. At every covered pixel `e'` (recomputed in `u64`)
    /// stays below `2^32` and the values and remainders equal the general plane's.
    #[test]
    fn corner_numerator_bound_at_the_largest_box() {
        let m = (1i32 << small_bits(4)) - 1;
        let mut rng = crate::test_rng::XorShift(0x0DDB_1A5E_5BAD_5EEDu64);
        let mut rnd = || rng.next_u64() as u32;
        let p = SubpixelPoint::<4>::new;
        let window = crate::raster::Window::new(-100, -100, 200, 200);
        let (mut largest, mut pixels) = (0u64, 0u64);
        for (k, v) in [
            [p(0, 0), p(m, 0), p(0, m)],
            [p(m, 0), p(m, m), p(0, 0)],
            [p(m, m), p(0, m), p(m, 0)],
            [p(0, m), p(0, 0), p(m, m)],
        ]
        .into_iter()
        .enumerate()
        {
            for j in 0..24 {
                let a = match j {
                    0 => [[0, 0], [u32::MAX, 255], [u32::MAX, 255]],
                    1 => [[u32::MAX, 255], [0, 0], [0, 0]],
                    2 => [[0, 0], [u32::MAX, 255], [0, 0]],
                    _ => [0; 3].map(|_| [rnd(), rnd() % 256]),
                };
                let plane = SmallPlane::<2, 4>::new(v, a).expect("largest small box");
                let general = AttributePlane::<2, 4>::new(v, a).unwrap();
                crate::raster::triangle::fill_triangle(v, &window, |s| {
                    for x in s.x0..s.x1 {
                        let (px, py) = plane.offset(x, s.y);
                        for i in 0..2 {
                            let (_, g0x2, _, h0x2, e_corner) = plane.split[i];
                            let e =
                                e_corner as u64 + g0x2 as u64 * px as u64 + h0x2 as u64 * py as u64;
                            assert!(e < 1 << 32, "e' = {e} at ({x},{}) of {v:?} {a:?}", s.y);
                            largest = largest.max(e);
                            let (got, want) = (plane.exact(i, x, s.y), general.exact(i, x, s.y));
                            assert_eq!(
                                (got.value(), got.remainder()),
                                (want.value(), want.remainder()),
                                "triangle {k} values {j} attr {i} at ({x},{})",
                                s.y
                            );
                        }
                        pixels += 1;
                    }
                })
                .unwrap();
            }
        }
        // The extremes reach within 3 % of the bound (measured: 4,208,277,249 of 2^32).
        assert!(largest > 4_150_000_000, "{largest}");
        assert!(pixels > 100_000, "{pixels}");
    }

    #[test]
    fn small_plane_equals_general_plane() {
        let (planes, pixels) = small_plane_matches::<4>(0x5DEE_CE66_D1CE_4E5B, 6000);
        assert!(planes > 2000 && pixels > 200_000, "{planes} {pixels}");
        let (planes, pixels) = small_plane_matches::<0>(0x0123_4567_89AB_CDEF, 2000);
        assert!(planes > 500 && pixels > 100_000, "{planes} {pixels}");
        // S = 14: K = 9, boxes below 2^9 units (1/32 pixel): few pixels, exact planes.
        let (planes, _) = small_plane_matches::<14>(0xFEDC_BA98_7654_3210, 2000);
        assert!(planes > 500, "{planes}");
    }

    /// The 32-bit split of a gradient equals the i64 one (the host takes the i64 form).
    #[test]
    fn narrow_gradient_split_equals_wide() {
        let mut rng = crate::test_rng::XorShift(0x2545_F491_4F6C_DD1Du64);
        let mut rnd = |m: u64| rng.next_u64() % m;
        for i in 0..200_000 {
            let k = 1 + (i % 10) as u32;
            let d = 1 + rnd((1 << (2 * k)) - 1) as u32;
            let a = |r: u64| r as i64 - (1 << 32) + 1;
            let (a1, a2) = (a(rnd((1 << 33) - 1)), a(rnd((1 << 33) - 1)));
            let c = |r: u64| r as i32 - (1 << k) + 1;
            let (c1, c2) = (c(rnd((2 << k) - 1)), c(rnd((2 << k) - 1)));
            let negative = i % 2 == 0;
            let g =
                (a1 as i128 * c1 as i128 - a2 as i128 * c2 as i128) * if negative { -1 } else { 1 };
            let want = (
                g.div_euclid(d as i128) as u32,
                g.rem_euclid(d as i128) as u32,
            );
            let d = DivisorU32::new(NonZeroU32::new(d).unwrap());
            assert_eq!(split_gradient(a1, a2, c1, c2, negative, &d), want);
            assert_eq!(split_gradient_narrow(a1, a2, c1, c2, negative, &d), want);
        }
    }

    /// The wide plane on triangles up to the raster's whole range: every value of sampled
    /// spans (stepped exactly across the span, up to 2^14 pixels) is the correctly rounded
    /// interpolant of [`exact`], for depths over the full 32-bit range; and where the general
    /// plane also applies, values, remainders, steps and 16.16 starts are the general plane's.
    #[test]
    fn wide_plane_is_exact_up_to_the_raster_range() {
        let mut rng = crate::test_rng::XorShift(0x9E37_79B9_7F4A_7C15u64);
        let mut rnd = |m: u64| rng.next_u64() % m;
        let (mut wide, mut both, mut pixels) = (0, 0, 0u64);
        for i in 0..600 {
            // Boxes from 2^10 to 2^29 sub-pixel units: past the general plane's limit and within.
            let bits = 10 + (i % 20) as u32;
            let lim = ((1u64 << bits) - 1).min((1 << 28) - 1);
            let c = |r: u64| r as i32 - lim as i32 / 2 * (bits < 29) as i32;
            let pick = |r: &mut dyn FnMut(u64) -> u64| {
                if bits >= 29 {
                    (r(2 * lim + 1) as i64 - lim as i64) as i32
                } else {
                    c(r(lim + 1))
                }
            };
            let v = [0; 3].map(|_| SubpixelPoint::<4>::new(pick(&mut rnd), pick(&mut rnd)));
            let a = [0; 3].map(|_| [rnd(1 << 32) as u32, rnd(511) as u32]);
            let Ok(plane) = WidePlane::<2, 4>::new(v, a) else {
                continue;
            };
            let general = AttributePlane::<2, 4>::new(v, a);
            wide += general.is_err() as u32;
            // 8 rows around a random height of the triangle, each span cut to 2^14 pixels.
            let ys = v.map(|p| p.y >> 4);
            let (y_lo, y_hi) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
            let y = y_lo + (rnd((y_hi - y_lo) as u64 + 1) as i32);
            let window = crate::raster::Window::new(-(1 << 24), y - 4, 1 << 24, y + 4);
            crate::raster::triangle::fill_triangle(v, &window, |s| {
                let mut c = [plane.exact(0, s.x0, s.y), plane.exact(1, s.x0, s.y)];
                if let Ok(g) = &general {
                    for (k, w) in c.iter().enumerate() {
                        let e = g.exact(k, s.x0, s.y);
                        let (rem, two_d) = e.remainder();
                        let narrow = (e.value(), (rem as u64, two_d as u64));
                        assert_eq!((w.value(), w.remainder()), narrow);
                        assert_eq!((w.q, w.r), (e.q, e.r as u64));
                    }
                    let (wd, gd) = (plane.dda(1, s.x0, s.y), g.dda(1, s.x0, s.y));
                    assert_eq!((wd.acc, wd.inc), (gd.acc, gd.inc));
                    both += 1;
                }
                for x in s.x0..s.x1.min(s.x0 + (1 << 14)) {
                    for (k, got) in c.iter_mut().enumerate() {
                        let want = exact(v, [a[0][k], a[1][k], a[2][k]], x, s.y);
                        assert_eq!(got.value(), want, "attr {k} at ({x},{}) of {v:?}", s.y);
                        got.step();
                    }
                    pixels += 1;
                }
            })
            .unwrap();
        }
        assert!(
            wide > 300 && both > 100 && pixels > 1_000_000,
            "{wide} {both} {pixels}"
        );
    }

    #[test]
    fn rejects_degenerate_and_huge() {
        let p = SubpixelPoint::<4>::new;
        assert_eq!(
            AttributePlane::<1, 4>::new([p(0, 0), p(5, 5), p(10, 10)], [[0]; 3]).err(),
            Some(PlaneError::Degenerate)
        );
        assert_eq!(
            AttributePlane::<1, 4>::new([p(0, 0), p(1 << 16, 0), p(0, 1 << 15)], [[0]; 3]).err(),
            Some(PlaneError::TooLarge)
        );
    }
}
