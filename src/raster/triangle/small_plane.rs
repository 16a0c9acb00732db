//! The small plane: the exact interpolant of a triangle whose bounding box is below `2^K`
//! sub-pixel units on both axes (`K = small_bits(S)`: 64 pixels at `S = 4`), in 32-bit
//! arithmetic only.
//!
//! Role in the pipeline: the first plane the span writers try (after the tiny writer), the
//! one every triangle of the standard sphere and bunny takes: the same values and remainders
//! as the general [`AttributePlane`](super::plane::AttributePlane), with no 64-bit product or
//! division on 32-bit cores. Conventions and the rounded value: the `plane` module's doc.
//!
//! Numeric contract: `D < 2^(2K)`; the decomposition in [`SmallPlane`]'s doc keeps every
//! intermediate below `2^31` (`i32`) or `2^32` (`u32`); quotients that only move values are
//! kept mod `2^32`, like the values themselves.

use super::interpolants::{Dda, Exact, SpanStarts};
use super::setup::TriangleSetup;
use crate::arith::euclid::{div_floor_i64, DivisorU32};
use crate::arith::{HARDWARE_DIVIDE, WIDE_REGISTERS};
use crate::raster::SubpixelPoint;
use core::num::NonZeroU32;

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
    pub(super) split: [(u32, u32, u32, u32, u32); N],
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
    pub(super) fn offset(&self, x: i32, y: i32) -> (u32, u32) {
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

/// `(g1 mod 2^32, g0)` with `±(a1·c1 − a2·c2) = D·g1 + g0`, `0 ≤ g0 < D` (minus when
/// `negative`), for `|a| < 2^32`, `|c| < 2^K`, `D < 2^(2K)` (see [`SmallPlane`]).
#[inline(always)]
pub(super) fn split_gradient(
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
pub(super) fn split_gradient_narrow(
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
pub(super) fn div_floor_by_u32(a: i64, d: &DivisorU32) -> (u32, u32) {
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
