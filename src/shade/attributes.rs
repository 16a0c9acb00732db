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

use crate::arith::euclid::{div_floor_i64, Divisor, DivisorU32};
use crate::arith::{HARDWARE_DIVIDE, WIDE_REGISTERS};
use crate::raster::setup::TriangleSetup;
use crate::raster::SubpixelPoint;
use core::num::NonZeroU32;

/// Why an attribute plane could not be set up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlaneError {
    /// The triangle has zero area: it covers no pixel, nothing to interpolate.
    Degenerate,
    /// Twice the area is `2^30` sub-pixel units squared or more.
    TooLarge,
}

/// A value that moves one pixel right at a time: the interface span loops are generic over.
pub trait Interpolant: Copy {
    /// True for [`Constant`]: lets span loops pick a branch-free, vectorisable form at compile time.
    const IS_CONSTANT: bool = false;
    /// The value at the current pixel.
    fn value(&self) -> u32;
    /// Moves one pixel to the right.
    fn step(&mut self);
}

/// The correctly rounded value of an affine attribute, stepped exactly (quotient, remainder).
#[derive(Debug, Clone, Copy)]
pub struct Exact {
    value: u32,
    /// Remainder of `2M + D` by `2D`, in `0..two_d`.
    rem: u32,
    /// Quotient added per pixel (mod 2^32).
    q: u32,
    /// Remainder added per pixel, in `0..two_d`.
    r: u32,
    /// `2D`, the carry threshold (`< 2^31`).
    two_d: u32,
}

impl Exact {
    /// The state from its parts: `value`, its remainder `rem < two_d`, and the per-pixel
    /// quotient `q` and remainder `r < two_d` (`two_d < 2^31`).
    #[inline(always)]
    pub(crate) fn from_parts(value: u32, rem: u32, (q, r): (u32, u32), two_d: u32) -> Self {
        Exact {
            value,
            rem,
            q,
            r,
            two_d,
        }
    }

    /// Moves by a precomputed quotient and remainder (`r < 2D`), carrying once.
    #[inline(always)]
    pub fn advance(&mut self, (q, r): (u32, u32)) {
        let t = self.rem + r;
        let carry = (t >= self.two_d) as u32;
        self.rem = t - carry * self.two_d;
        self.value = self.value.wrapping_add(q).wrapping_add(carry);
    }

    /// The longest run of pixels an [`ExactRun`] started from this plane's values keeps
    /// correctly rounded: `⌊(2^32 − 1) / 2D⌋` (at least 2, since `2D < 2^31`).
    #[cfg(test)]
    pub fn run_limit(&self) -> u32 {
        u32::MAX / self.two_d
    }

    /// The remainder of the value's numerator, `0 ≤ rem < 2D` (the value's exact fraction is
    /// `rem / 2D − 1/2`, its rounding residue).
    #[cfg(test)]
    pub fn remainder(&self) -> (u32, u32) {
        (self.rem, self.two_d)
    }
}

impl Interpolant for Exact {
    #[inline(always)]
    fn value(&self) -> u32 {
        self.value
    }

    #[inline(always)]
    fn step(&mut self) {
        self.advance((self.q, self.r)); // rem, r < 2^31: the sum cannot overflow
    }
}

/// The exact interpolant as one 32.32 fixed-point accumulator: one add per pixel, and still
/// correctly rounded on runs of at most `2^32 / 2D − 1` pixels ([`Exact::run_limit`]).
///
/// Why: the exact value is `⌊V⌋` with `V = T / 2D`, whose fraction is a multiple of `1/2D`.
/// Starting from `V` rounded **up** to 2^-32 and adding the step rounded up to 2^-32, after `k`
/// steps the accumulator exceeds `V` by less than `(k + 1)·2^-32`, which stays below `1/2D` —
/// too little to reach the next integer — while `(k + 1)·2D < 2^32`. Span loops use it when
/// every span of a triangle is that short (all triangles of the standard sphere and bunny) and
/// fall back to [`Exact`] otherwise.
#[derive(Debug, Clone, Copy)]
pub struct ExactRun {
    acc: u64,
    inc: u64,
}

impl ExactRun {
    /// The 32.32 step of `e` and `2D` prepared for the starts (per triangle: neither depends
    /// on the span).
    #[inline]
    pub fn prepare(e: &Exact) -> (u64, Divisor) {
        let two_d = Divisor::new(e.two_d as i64);
        (Self::ceil_frac(e.q, e.r, &two_d), two_d)
    }

    /// `(q << 32) + ⌈r·2^32 / 2D⌉` for `r < 2D` (wrapping in the integer part).
    #[inline(always)]
    fn ceil_frac(q: u32, r: u32, two_d: &Divisor) -> u64 {
        let (f, rem) = two_d.div_floor((r as i64) << 32);
        ((q as u64) << 32).wrapping_add(f as u64 + (rem != 0) as u64)
    }

    /// Starts at the exact state `e` with the step and divisor of [`ExactRun::prepare`].
    #[inline(always)]
    pub fn start(e: &Exact, (inc, two_d): &(u64, Divisor)) -> Self {
        // rem < 2D, so the rounded-up fraction stays below 2^32.
        ExactRun {
            acc: Self::ceil_frac(e.value, e.rem, two_d),
            inc: *inc,
        }
    }
}

impl Interpolant for ExactRun {
    #[inline(always)]
    fn value(&self) -> u32 {
        (self.acc >> 32) as u32
    }

    #[inline(always)]
    fn step(&mut self) {
        self.acc = self.acc.wrapping_add(self.inc);
    }
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

/// An attribute with the same value at every pixel: stepping is free.
#[derive(Debug, Clone, Copy)]
pub struct Constant(pub u32);

impl Interpolant for Constant {
    const IS_CONSTANT: bool = true;

    #[inline(always)]
    fn value(&self) -> u32 {
        self.0
    }

    #[inline(always)]
    fn step(&mut self) {}
}

/// The fast variant: the value in 16.16 fixed point plus a 16.16 increment per pixel. Each
/// span starts from the plane's value (exact to 2^-16); along the span the increment's
/// truncation (< 2^-16 per pixel) accumulates, so after `n` pixels the value may be low by up
/// to `n · 2^-16` plus the final rounding. For attributes below `2^15` (luminance, not depth).
#[derive(Debug, Clone, Copy)]
pub struct Dda {
    acc: u32,
    inc: u32,
}

impl Interpolant for Dda {
    #[inline(always)]
    fn value(&self) -> u32 {
        self.acc >> 16
    }

    #[inline(always)]
    fn step(&mut self) {
        self.acc = self.acc.wrapping_add(self.inc);
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

/// Where the exact span starts of one triangle come from: [`RowStarts`] over an
/// [`AttributePlane`] (`2D < 2^31`), a [`SmallPlane`] (32-bit arithmetic), or a
/// [`WidePlane`] (any triangle of the raster's range). Span loops are generic over it, so all
/// three feed the same span machinery.
pub trait SpanStarts<const N: usize> {
    /// The exact interpolant a span starts from: [`Exact`], or [`ExactWide`] for a
    /// [`WidePlane`].
    type Exact: Interpolant;
    /// The exact values at `(x, y)`, a covered pixel, ready to step right.
    fn exact_at(&mut self, x: i32, y: i32) -> [Self::Exact; N];
    /// Attribute `i < N` at `(x, y)` (a covered pixel) as [`AttributePlane::dda`] gives it.
    fn dda_at(&self, i: usize, x: i32, y: i32) -> Dda;
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

/// `log2` of the largest bounding box (in `2^-S` pixel units, each side) a [`SmallPlane`]
/// accepts: 10 (64 pixels at `S = 4`) for `S ≤ 12`, less above so that `2^S · 2^(2K) ≤ 2^32`.
pub const fn small_bits(s: u32) -> u32 {
    let k = (32 - s) / 2;
    if k < 10 {
        k
    } else {
        10
    }
}

/// The exact affine interpolant of `N` attributes over a *small* triangle, in 32-bit
/// arithmetic only: the same values (and remainders) as [`AttributePlane::exact`] and
/// [`AttributePlane::dda`], without 64-bit products or divisions on 32-bit targets.
///
/// ## Numeric contract
/// With `K = `[`small_bits`]`(S)`, the triangle's bounding box is `W` units wide and `H` high
/// with `W, H ≤ m = 2^K − 1` (checked by [`SmallPlane::new`]). Then every vertex difference is
/// at most `m` in magnitude and `D ≤ W·H` (a triangle fills at most half its box), and with
/// `A1 − A0 = D·Q1 + R1`, `A2 − A0 = D·Q2 + R2` (`0 ≤ R < D`, one 32-bit division of
/// `|A − A0| < 2^32` each):
///
/// - `gx = D·(Q1·dy2 − Q2·dy1) + (R1·dy2 − R2·dy1)` (signs as the module doc), whose second
///   part is below `2·2^(2K)·2^K = 2^(3K+1) ≤ 2^31`: one `i32` floored division splits it, giving
///   `gx = D·g1 + g0` with `0 ≤ g0 < D` and `g1` kept mod `2^32` (it only ever moves values,
///   which wrap mod `2^32`); the same for `gy = D·h1 + h0`.
/// - Span starts are measured from the box's top-left corner `C`, so that the offsets
///   `px = x·F − Cx`, `py = y·F − Cy` of a covered pixel lie in `0..=W` and `0..=H` and every
///   term below is non-negative: no signed division, no floor fix-up. The corner's own value
///   is split once, `M(C) = D·(g1·cx + h1·cy) + E` with `cx, cy ∈ (−2^K, 0]` the corner's offset
///   from `P0` and `|E| < 2^(3K+1)`; one floored division `E = D·c1 + c0` (`0 ≤ c0 < D`) and
///   `B = A0 + g1·cx + h1·cy + c1` (mod `2^32`) give `2M(p) + D = 2D·(B − A0 + g1·px + h1·py)
///   + e'` with
///
///   ```text
///   e' = (2·c0 + D) + 2·g0·px + 2·h0·py  ≤  2·(D − 1)·(1 + W + H) + D  <  m²·(4m + 3)  <  2^32
///   ```
///
///   so the start is one unsigned division `e' = 2D·q + rem`: value `B + g1·px + h1·py + q`,
///   remainder `rem` (bound tight at `K = 10`: `1023²·4095 < 2^32`).
/// - a step right adds `2F·gx` to `2M + D`: quotient `F·g1 + ⌊F·g0 / D⌋`, remainder
///   `2·(F·g0 mod D)`, with `F·g0 < 2^(S+2K) ≤ 2^32`.
/// - the 16.16 [`Dda`] needs `⌊e·2^16 / D⌋` with `e = (e' − D) / 2` and `⌊g0·2^(16+S) / D⌋`,
///   long divisions of a fraction `n / D < 1` eight bits at a time (`n·2^8 < 2^(2K+8) ≤ 2^28`).
///
/// On 64-bit targets the split of `gx` and `gy` is one `i64` division each (the hardware's),
/// which gives the same `g1 mod 2^32, g0`.
#[derive(Debug, Clone)]
pub struct SmallPlane<const N: usize, const S: u32> {
    /// `C`, the bounding box's top-left corner.
    corner: SubpixelPoint<S>,
    /// Per attribute, `B` (mod 2^32): the whole part of the value at the corner.
    base: [u32; N],
    /// `D` (twice the area, positive, `≤ W·H < 2^(2K)`), prepared for divisions.
    d: DivisorU32,
    /// `2D`, prepared for the span starts' divisions.
    two_d: DivisorU32,
    /// Per attribute `(g1 mod 2^32, 2·g0, h1 mod 2^32, 2·h0, 2·c0 + D)`: `gx = D·g1 + g0`,
    /// `gy = D·h1 + h0`, and `e'` at the corner itself (`px = py = 0`).
    split: [(u32, u32, u32, u32, u32); N],
    /// Per attribute, `(q, r)` of one pixel step right.
    step_x: [(u32, u32); N],
    /// Per attribute, the 16.16 [`Dda`] step `⌊gx·2^(16+S) / D⌋` (mod `2^32`): computed once
    /// per triangle (and by the compiler only where a span loop reads it).
    dda_inc: [u32; N],
}

impl<const N: usize, const S: u32> SmallPlane<N, S> {
    /// The plane of `values[i]` at vertex `v[i]` (vertices within the raster's range), as
    /// [`Self::of`].
    #[cfg(test)]
    pub fn new(v: [SubpixelPoint<S>; 3], values: [[u32; N]; 3]) -> Option<Self> {
        Self::of(&TriangleSetup::in_range(v), values)
    }

    /// The plane of `values[i]` at the given vertex `i` of set-up `t`, or `None` when the
    /// bounding box is not below `2^K` units on both axes ([`small_bits`]) or the triangle has
    /// zero area.
    #[inline(always)]
    pub(crate) fn of(t: &TriangleSetup<S>, values: [[u32; N]; 3]) -> Option<Self> {
        if !Self::fits(t) {
            return None;
        }
        let v = t.given;
        let (dx1, dy1) = (v[1].x.wrapping_sub(v[0].x), v[1].y.wrapping_sub(v[0].y));
        let (dx2, dy2) = (v[2].x.wrapping_sub(v[0].x), v[2].y.wrapping_sub(v[0].y));
        // |2A| < 2^(2K): the box is below 2^K on both axes (`fits`), so the set-up's
        // twice-area is its low 32 bits.
        debug_assert!(dx1.unsigned_abs().max(dy1.unsigned_abs()) < 1 << small_bits(S));
        let cross = t.given_twice_area() as i32;
        let negative = cross < 0;
        let d = NonZeroU32::new(cross.unsigned_abs())?;
        // Every set-up division is by D: prepared once (a reciprocal where there is no divider).
        let dd = DivisorU32::new(d);
        // The corner's offset from P0: (cx, cy) in (−2^K, 0].
        let (cx, cy) = (dx1.min(dx2).min(0), dy1.min(dy2).min(0));
        let corner = SubpixelPoint::new(v[0].x.wrapping_add(cx), v[0].y.wrapping_add(cy));
        let mut base = [0; N];
        let mut split = [(0, 0, 0, 0, 0); N];
        let mut step_x = [(0, 0); N];
        let mut dda_inc = [0; N];
        for i in 0..N {
            let a1 = values[1][i] as i64 - values[0][i] as i64;
            let a2 = values[2][i] as i64 - values[0][i] as i64;
            let (g1, g0) = split_gradient(a1, a2, dy2, dy1, negative, &dd);
            let (h1, h0) = split_gradient(a2, a1, dx1, dx2, negative, &dd);
            // |E| = |g0·cx + h0·cy| < D·2^(K+1).
            let e = (g0 as i32)
                .wrapping_mul(cx)
                .wrapping_add((h0 as i32).wrapping_mul(cy));
            let (c1, c0) = div_floor_small(e, &dd);
            base[i] = values[0][i]
                .wrapping_add(g1.wrapping_mul(cx as u32))
                .wrapping_add(h1.wrapping_mul(cy as u32))
                .wrapping_add(c1);
            // F·g0 < 2^(S+2K) ≤ 2^32.
            let fg0 = g0 << S;
            let (fq, fr) = dd.div_rem(fg0);
            step_x[i] = (g1.wrapping_shl(S).wrapping_add(fq), 2 * fr);
            split[i] = (g1, 2 * g0, h1, 2 * h0, 2 * c0 + d.get());
            // ⌊gx·2^(16+S) / D⌋ = 2^(16+S)·g1 + ⌊g0·2^(16+S) / D⌋ (mod 2^32).
            dda_inc[i] = g1
                .wrapping_shl(16 + S)
                .wrapping_add(frac_bits(g0, &dd, 16 + S));
        }
        Some(SmallPlane {
            corner,
            base,
            d: dd,
            // D < 2^(2K) ≤ 2^20: 2D does not overflow.
            two_d: dd.doubled(),
            split,
            step_x,
            dda_inc,
        })
    }

    /// True when the bounding box of set-up `t` is below `2^K` units on both axes
    /// ([`small_bits`]): the triangles [`SmallPlane::of`] accepts, if they have area.
    #[inline(always)]
    pub(crate) fn fits(t: &TriangleSetup<S>) -> bool {
        t.box_below(small_bits(S))
    }

    /// `(px, py) = (x·F − Cx, y·F − Cy)` for pixel `(x, y)`: in `0..=W`, `0..=H` when covered.
    #[inline(always)]
    fn offset(&self, x: i32, y: i32) -> (u32, u32) {
        (
            (x << S).wrapping_sub(self.corner.x) as u32,
            (y << S).wrapping_sub(self.corner.y) as u32,
        )
    }

    /// `(B + g1·px + h1·py mod 2^32, e')` at offset `(px, py)`: `2M + D = 2D·(whole − A0) + e'`.
    #[inline(always)]
    fn numerator(&self, i: usize, px: u32, py: u32) -> (u32, u32) {
        let (g1, g0x2, h1, h0x2, e_corner) = self.split[i];
        let whole = self.base[i]
            .wrapping_add(g1.wrapping_mul(px))
            .wrapping_add(h1.wrapping_mul(py));
        // e' < 2^32 at a covered pixel (see the numeric contract).
        (
            whole,
            e_corner
                .wrapping_add(g0x2.wrapping_mul(px))
                .wrapping_add(h0x2.wrapping_mul(py)),
        )
    }

    /// Attribute `i < N` at the covered pixel `(x, y)`, ready to step right exactly: equal to
    /// [`AttributePlane::exact`] of the same triangle.
    #[inline(always)]
    #[cfg(test)]
    pub fn exact(&self, i: usize, x: i32, y: i32) -> Exact {
        let (px, py) = self.offset(x, y);
        self.exact_from(i, px, py)
    }

    #[inline(always)]
    fn exact_from(&self, i: usize, px: u32, py: u32) -> Exact {
        let (whole, e) = self.numerator(i, px, py);
        let (value, rem) = self.two_d.add_div_rem(whole, e);
        Exact {
            value,
            rem,
            q: self.step_x[i].0,
            r: self.step_x[i].1,
            two_d: self.two_d.get(),
        }
    }

    /// Attribute `i < N` at the covered pixel `(x, y)` as a 16.16 [`Dda`]: equal to
    /// [`AttributePlane::dda`] of the same triangle.
    #[inline]
    pub fn dda(&self, i: usize, x: i32, y: i32) -> Dda {
        let (px, py) = self.offset(x, y);
        let (whole, e2) = self.numerator(i, px, py);
        // M = D·(whole − A0) + e with e = (e' − D) / 2 ≥ 0, so
        // ⌊M·2^16 / D⌋ + A0·2^16 = 2^16·(whole + ⌊e / D⌋) + ⌊(e mod D)·2^16 / D⌋ (mod 2^32).
        let (d, e) = (&self.d, e2.wrapping_sub(self.d.get()) / 2);
        let (q, r) = d.div_rem(e);
        let start = (whole.wrapping_add(q) << 16).wrapping_add(frac_bits(r, d, 16));
        Dda {
            acc: start.wrapping_add(1 << 15),
            inc: self.dda_inc[i],
        }
    }

    /// The longest run an [`ExactRun`] of this plane keeps exact: `⌊(2^32 − 1) / 2D⌋`.
    #[cfg(test)]
    pub fn run_limit(&self) -> u32 {
        self.two_d.max_quotient()
    }
}

impl<const N: usize, const S: u32> SpanStarts<N> for SmallPlane<N, S> {
    type Exact = Exact;

    #[inline(always)]
    fn exact_at(&mut self, x: i32, y: i32) -> [Exact; N] {
        let (px, py) = self.offset(x, y);
        // A loop, not `array::from_fn` (which the compiler leaves out of line).
        let mut out = [Exact {
            value: 0,
            rem: 0,
            q: 0,
            r: 0,
            two_d: 1,
        }; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.exact_from(i, px, py);
        }
        out
    }

    #[inline(always)]
    fn dda_at(&self, i: usize, x: i32, y: i32) -> Dda {
        self.dda(i, x, y)
    }
}

/// [`Exact`] with a 64-bit remainder: the correctly rounded value of a [`WidePlane`], whose
/// `2D` may reach `2^59`. Same value, remainder and carry rule as [`Exact`].
#[derive(Debug, Clone, Copy)]
pub struct ExactWide {
    value: u32,
    /// Remainder of `2M + D` by `2D`, in `0..two_d`.
    rem: u64,
    /// Quotient added per pixel (mod 2^32).
    q: u32,
    /// Remainder added per pixel, in `0..two_d`.
    r: u64,
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

/// `(g1 mod 2^32, g0)` with `±(a1·c1 − a2·c2) = D·g1 + g0`, `0 ≤ g0 < D` (minus when
/// `negative`), for `|a| < 2^32`, `|c| < 2^K`, `D < 2^(2K)` (see [`SmallPlane`]).
#[inline(always)]
fn split_gradient(
    a1: i64,
    a2: i64,
    c1: i32,
    c2: i32,
    negative: bool,
    d: &DivisorU32,
) -> (u32, u32) {
    if WIDE_REGISTERS {
        // One hardware division of the exact i64 gradient (|g| < 2^(33+K)).
        let g = a1 * c1 as i64 - a2 * c2 as i64;
        let g = if negative { -g } else { g };
        let (g1, g0) = div_floor_i64(g, d.get() as i64);
        return (g1 as u32, g0 as u32);
    }
    split_gradient_narrow(a1, a2, c1, c2, negative, d)
}

/// [`split_gradient`] in 32-bit operations (the 32-bit targets' form; same results).
#[inline(always)]
fn split_gradient_narrow(
    a1: i64,
    a2: i64,
    c1: i32,
    c2: i32,
    negative: bool,
    d: &DivisorU32,
) -> (u32, u32) {
    let (q1, r1) = div_floor_by_u32(a1, d);
    let (q2, r2) = div_floor_by_u32(a2, d);
    // |r1·c1 − r2·c2| < 2·D·2^K.
    let gq = q1
        .wrapping_mul(c1 as u32)
        .wrapping_sub(q2.wrapping_mul(c2 as u32));
    let gr = (r1 as i32)
        .wrapping_mul(c1)
        .wrapping_sub((r2 as i32).wrapping_mul(c2));
    let (gq, gr) = if negative {
        (gq.wrapping_neg(), gr.wrapping_neg())
    } else {
        (gq, gr)
    };
    let (u, g0) = div_floor_small(gr, d);
    (gq.wrapping_add(u), g0)
}

/// `(⌊a / d⌋ mod 2^32, a mod d)` for `|a| < 2^32` and `0 < d < 2^31`: one 32-bit division of
/// `|a|`.
#[inline(always)]
fn div_floor_by_u32(a: i64, d: &DivisorU32) -> (u32, u32) {
    let m = a.unsigned_abs() as u32;
    let (q, r) = d.div_rem(m);
    if a >= 0 {
        (q, r)
    } else if r == 0 {
        (q.wrapping_neg(), 0)
    } else {
        ((!q), d.get() - r) // −q − 1
    }
}

/// `(⌊a / d⌋ mod 2^32, a mod d)` for `d ≤ 2^20` and `|a| < 2^11·d` (the small planes' terms:
/// `|a| < 2^(K+1)·D`, `D < 2^(2K)`, `K ≤ 10`): one unsigned division of `a + 2^11·d`, which
/// lies in `0..2^12·d ≤ 2^32`, so no sign fix-up. Without a hardware divider
/// ([`HARDWARE_DIVIDE`]) the division of the magnitude through `d`'s reciprocal and the
/// floor's fix-up instead.
#[inline(always)]
fn div_floor_small(a: i32, d: &DivisorU32) -> (u32, u32) {
    if !HARDWARE_DIVIDE {
        // The reciprocal's cost does not grow with the quotient: the magnitude's division and
        // the floor's fix-up.
        return div_floor_by_u32(a as i64, d);
    }
    let biased = (a as u32).wrapping_add(d.get() << 11);
    let (q, r) = d.div_rem(biased);
    (q.wrapping_sub(1 << 11), r)
}

/// `⌊n·2^bits / d⌋ mod 2^32` for `0 ≤ n < d < 2^24`: long division eight bits at a time
/// (`n·2^8 < 2^32`).
#[inline(always)]
fn frac_bits(mut n: u32, d: &DivisorU32, mut bits: u32) -> u32 {
    let mut q = 0u32;
    while bits > 0 {
        let c = bits.min(8);
        let (digit, rest) = d.div_rem(n << c);
        q = (q << c).wrapping_add(digit);
        n = rest;
        bits -= c;
    }
    q
}

#[cfg(test)]
mod tests {
    use super::*;

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
