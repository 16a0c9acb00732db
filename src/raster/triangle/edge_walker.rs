//! Edge walking: TIPE 2010's `Parcours`, generalised to sub-pixel vertices.
//!
//! Role in the pipeline: inside the raster stage, each non-horizontal polygon edge is walked
//! row by row to find where a span starts or ends. [`polygon`](crate::raster::polygon) and
//! [`fill`](super::fill) both use it.
//!
//! ## What an edge produces
//! An edge runs from its low end `(X0, Y0)` to its high end `(X1, Y1)` with `Y0 < Y1`
//! (screen rows grow downward, so "low" is the top of the edge on screen). Coordinates are in
//! units of `2^-S` pixel; write `F = 2^S`, `DX = X1 - X0`, `DY = Y1 - Y0 > 0`. The edge covers the
//! integer rows `y` with `Y0 ≤ y·F < Y1` (its first row in, its last row out: TIPE's
//! "only the edge of which a vertex is the lowest point"), and crosses row `y` at
//!
//! ```text
//! x_e(y) = (X0 + (y·F − Y0)·DX / DY) / F   = num(y) / den,
//! num(y) = X0·DY + (y·F − Y0)·DX,          den = F·DY.
//! ```
//!
//! A **left** edge (TIPE's `TAG`, its ends `xG`) yields the first pixel at or right of the edge,
//! `xG = ⌈x_e⌉` — a pixel exactly on a left edge is inside. A **right** edge (TIPE's `TAD`, its
//! ends `xD`) yields the last pixel strictly left of the edge, `xD = ⌈x_e⌉ − 1` — a pixel exactly
//! on a right edge is outside. Both are Euclidean divisions with a bias, exactly TIPE's
//! initialisation of the numerator `N`:
//!
//! ```text
//! left:  xG = ⌊(num + den − 1) / den⌋      (TIPE: N ← Δy − 1)
//! right: xD = ⌊(num − 1) / den⌋            (TIPE: N ← −1)
//! ```
//!
//! ## Two stepping strategies, identical results
//! - [`DivisionWalker`] is the text's `Parcours`: every row performs one Euclidean division
//!   `(Q, N) ← div_euclid(N, den)`, then `x ← x + Q`, then `N ← N + F·DX`.
//! - [`IncrementalWalker`] divides once per edge: with `q = ⌊DX/DY⌋` and `r = DX − q·DY`
//!   (`0 ≤ r < DY`), each row is `x ← x + q; k ← k + r; if k ≥ DY { k ← k − DY; x ← x + 1 }`.
//!   The remainder of the text's `N` is `F·k + c` with a constant `c < F` (every step adds a
//!   multiple of `F`), so comparing `k` with `DY` decides the carry exactly: no drift, ever.
//!   (`k` is kept biased by `2^32 − DY` in a `u32`, so the comparison is the carry of the add.)
//!
//! Both implement [`EdgeWalker`] and are tested to agree on every row of random edges.
//!
//! ## Numeric contract
//! Vertex coordinates satisfy `|X|, |Y| ≤ MAX_COORD = 2^28 − 1` and `S ≤ 16`. Then
//! `|DX|, DY < 2^29`, `|num| < 2^59` and `den < 2^45`: the set-up fits `i64`. The incremental
//! state fits 32 bits (`0 ≤ k < DY < 2^29`, biased `k + 2^32 − DY < 2^32`), and so do the ends (`|x| ≤ 2^28`).
//! On 32-bit targets a *narrow* edge (`|DX|, DY < 2^13`, [`Edge::is_narrow`]) divides in `i32`
//! instead: the whole pixels of `X0` are taken out of the numerator, which leaves terms below
//! `2^29` ([`Edge::divide_narrow`]); same quotient and remainder (tested). The
//! [`IncrementalWalker`] starts a narrow edge (`DY ≥ 1` as well) inline with the same terms made
//! non-negative by a multiple of the divisor (sum `< 2^31`), so both of its divisions are
//! unsigned with no sign fix-up; wide edges take an out-of-line start (tested equal). Cores
//! that divide in software (`arith::HARDWARE_DIVIDE` false: Cortex-M0/M0+) take the signed
//! [`Edge::divide_narrow`] instead, whose quotients are 13 to 16 bits shorter than the biased
//! ones, each bit one turn of the division routine's loop (M0 frame_bunny −5.5 %).

use crate::arith::euclid::{div_floor_i32, div_floor_i64};
use crate::arith::{HARDWARE_DIVIDE, WIDE_REGISTERS};
use core::num::NonZeroU32;

/// The largest coordinate magnitude (in sub-pixel units) the raster stage accepts.
pub const MAX_COORD: i32 = (1 << 28) - 1;

/// The largest number of sub-pixel bits supported.
pub const MAX_SUBPIXEL_BITS: u32 = 16;

/// Which end of a span an edge produces (TIPE's left/right edge type).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EdgeSide {
    /// A left edge (`TAG`): yields `xG`, the first covered pixel (edge pixels included).
    Left,
    /// A right edge (`TAD`): yields `xD`, the last covered pixel (edge pixels excluded).
    Right,
}

/// A non-horizontal edge with its low end first (`y0 < y1`), in units of `2^-S` pixel.
///
/// The fields are TIPE's `xbas, ybas, xhaut, yhaut`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Edge {
    /// `xbas`: column of the low end (the end with the smaller row).
    pub x0: i32,
    /// `ybas`: row of the low end.
    pub y0: i32,
    /// `xhaut`: column of the high end.
    pub x1: i32,
    /// `yhaut`: row of the high end (`y1 > y0`).
    pub y1: i32,
}

/// `⌈v / 2^s⌉` for **every** `i32` `v` (`i32::MIN` included) and `s < 32`: the floor
/// `v >> s` (arithmetic shift rounds toward −∞) plus one when a remainder bit is set. No term
/// can overflow: the floor is at least `i32::MIN / 2^s` and one is added only when
/// `v ≠ floor·2^s`, so the result lies between `v / 2^s` and `v / 2^s + 1`.
#[inline(always)]
pub const fn ceil_shift(v: i32, s: u32) -> i32 {
    let mask = ((1u32 << s) - 1) as i32; // s < 32; `1 << 31` − 1 as u32 is fine
    (v >> s) + ((v & mask) != 0) as i32
}

/// `⌈v / 2^s⌉` for `v > i32::MIN` (the raster's coordinates, within `±MAX_COORD`), in the
/// shorter form `−(−v >> s)`; at `i32::MIN` the negation wraps and the result is wrong (no
/// panic). [`ceil_shift`] is exact for every `i32`; in the edges' rows, run for every
/// triangle, its longer form cost the Cortex-M4 `fill_bunny` +3.0 % (1,476,259 against
/// 1,433,633 with this one).
#[inline(always)]
const fn ceil_shift_in_range(v: i32, s: u32) -> i32 {
    (v.wrapping_neg() >> s).wrapping_neg()
}

impl Edge {
    /// The first pixel row the edge covers: `⌈y0 / 2^S⌉` (ends within the module's range).
    #[inline(always)]
    pub const fn first_row<const S: u32>(&self) -> i32 {
        ceil_shift_in_range(self.y0, S)
    }

    /// One past the last pixel row the edge covers: `⌈y1 / 2^S⌉` (ends within the module's
    /// range).
    #[inline(always)]
    pub const fn end_row<const S: u32>(&self) -> i32 {
        ceil_shift_in_range(self.y1, S)
    }

    /// `(num(y) + bias, den)` of the module doc for row `y`, with TIPE's bias for `side`.
    #[inline(always)]
    fn biased_numerator<const S: u32>(&self, y: i32, side: EdgeSide) -> (i64, i64) {
        // The module's bound: ends within ±MAX_COORD, so |num| < 2^60 below.
        debug_assert!(
            [self.x0, self.y0, self.x1, self.y1]
                .iter()
                .all(|c| c.unsigned_abs() <= MAX_COORD as u32),
            "edge ends outside ±MAX_COORD"
        );
        let dx = self.x1 as i64 - self.x0 as i64;
        let dy = self.y1 as i64 - self.y0 as i64;
        let den = dy << S;
        let rows_below = ((y as i64) << S) - self.y0 as i64; // y·F − Y0
        let num = self.x0 as i64 * dy + rows_below * dx;
        let bias = match side {
            EdgeSide::Left => den - 1,
            EdgeSide::Right => -1,
        };
        (num + bias, den)
    }

    /// The span end on row `y` by direct evaluation (one division): `xG` for a left edge,
    /// `xD` for a right edge. Meaningful for rows the edge covers.
    pub fn end_at<const S: u32>(&self, y: i32, side: EdgeSide) -> i32 {
        self.divide::<S>(y, side).0
    }

    /// True when `|DX|, DY < 2^13`: [`Edge::divide_narrow`] applies.
    #[inline(always)]
    pub const fn is_narrow(&self) -> bool {
        const LIM: u32 = 1 << 13;
        let dx = self.x1.wrapping_sub(self.x0);
        let dy = self.y1.wrapping_sub(self.y0);
        dx.wrapping_add(LIM as i32 - 1) as u32 <= 2 * LIM - 2 && (dy as u32) < LIM
    }

    /// `(end, k)` on row `y` (covered by the edge): the end of [`Edge::end_at`] and
    /// `k = ⌊rem / F⌋ < DY` for the remainder `0 ≤ rem < F·DY` of its division (the
    /// [`IncrementalWalker`]'s error term; `rem` itself may exceed `i32`). On 32-bit targets a
    /// narrow edge takes [`Edge::divide_narrow`]; both give the same result.
    #[inline(always)]
    fn divide<const S: u32>(&self, y: i32, side: EdgeSide) -> (i32, i32) {
        if !WIDE_REGISTERS && self.is_narrow() {
            return self.divide_narrow::<S>(y, side);
        }
        let (n, den) = self.biased_numerator::<S>(y, side);
        let (x, rem) = div_floor_i64(n, den);
        (x as i32, (rem >> S) as i32)
    }

    /// The end and `⌊rem / F⌋` of row `y` (as `Edge::divide`) in 32-bit operations, for a
    /// narrow edge ([`Edge::is_narrow`]) and a row it covers. `X0 = F·⌊X0/F⌋ + (X0 mod F)` and
    /// the whole pixels `⌊X0/F⌋` come out of the division unchanged, so it divides
    /// `(X0 mod F)·DY + (y·F − Y0)·DX + bias` by `F·DY`: with `S ≤ 16`, `0 ≤ y·F − Y0 < DY` on a
    /// covered row and `|DX|, DY < 2^13`, the terms are below `2^29`, `2^26` and `2^29`, so the
    /// sum fits `i32`.
    #[inline(always)]
    pub fn divide_narrow<const S: u32>(&self, y: i32, side: EdgeSide) -> (i32, i32) {
        let (dx, dy) = (self.x1 - self.x0, self.y1 - self.y0);
        let den = dy << S;
        let rows_below = (y << S) - self.y0;
        let bias = match side {
            EdgeSide::Left => den - 1,
            EdgeSide::Right => -1,
        };
        let num = (self.x0 & ((1 << S) - 1)) * dy + rows_below * dx + bias;
        let (x, rem) = div_floor_i32(num, den);
        (x + (self.x0 >> S), rem >> S)
    }
}

/// Walks one edge row by row, yielding TIPE's `xG` (left edges) or `xD` (right edges).
pub trait EdgeWalker: Sized {
    /// Starts on row `y` (which the edge must cover) with the end for that row ready in [`x`](Self::x).
    fn start<const S: u32>(edge: &Edge, side: EdgeSide, y: i32) -> Self;
    /// The span end on the current row.
    fn x(&self) -> i32;
    /// Moves to the next row.
    fn step(&mut self);
}

/// TIPE's `Parcours` literally: one Euclidean division per row.
#[derive(Debug, Clone, Copy)]
pub struct DivisionWalker {
    /// TIPE's `x`: the span end accumulated from the quotients.
    x: i32,
    /// TIPE's `N`: the numerator still to divide (after a step, the remainder plus `F·DX`).
    n: i64,
    /// The divisor `F·DY` (TIPE's `Δy` when `S = 0`).
    den: i64,
    /// Added to `N` each row: `F·DX` (TIPE's `Δx` when `S = 0`).
    n_step: i64,
}

impl EdgeWalker for DivisionWalker {
    #[inline]
    fn start<const S: u32>(edge: &Edge, side: EdgeSide, y: i32) -> Self {
        let (n, den) = edge.biased_numerator::<S>(y, side);
        let n_step = (edge.x1 as i64 - edge.x0 as i64) << S;
        let mut w = DivisionWalker {
            x: 0,
            n,
            den,
            n_step,
        };
        w.divide();
        w
    }

    #[inline(always)]
    fn x(&self) -> i32 {
        self.x
    }

    #[inline]
    fn step(&mut self) {
        self.n += self.n_step; // 5.4  N ← N + Δx
        self.divide();
    }
}

impl DivisionWalker {
    /// Steps 5.1–5.2 of `Parcours`: `(Q, N) ← div_euclid(N, Δy); x ← x + Q`.
    #[inline(always)]
    fn divide(&mut self) {
        let (q, n) = div_floor_i64(self.n, self.den);
        self.n = n;
        self.x += q as i32;
    }
}

/// The incremental form of `Parcours`: one division per edge, then per row one add, one
/// add with carry and a conditional subtract. Produces the same ends as [`DivisionWalker`].
///
/// The error term `k` (`0 ≤ k < DY`) is stored biased as `K = k + 2^32 − DY` in a `u32`, so
/// `k + r ≥ DY` is exactly the carry out of `K + r` (`DY < 2^29` keeps `K` in range): the
/// carry adds the extra pixel (`adds` / `adc` on a Cortex-M) and `K − DY` (wrapping) restores
/// the bias.
#[derive(Debug, Clone, Copy)]
pub struct IncrementalWalker {
    /// The span end on the current row.
    x: i32,
    /// The biased error term `k + 2^32 − DY`: TIPE's remainder `N` is `F·k + c`, `0 ≤ k < DY`,
    /// `c` constant.
    k: u32,
    /// Whole pixels added per row: `⌊DX / DY⌋`.
    q: i32,
    /// Error added per row: `DX − q·DY`, in `0..DY`.
    r: u32,
    /// `DY`: when `k` reaches it, the end moves one more pixel.
    dy: u32,
}

impl IncrementalWalker {
    /// The walker from an end, its `k` and the edge's `DX, DY` (any edge, one 32-bit division).
    #[inline(always)]
    fn from_end(x: i32, k: i32, dx: i32, dy: i32) -> Self {
        let (q, r) = div_floor_i32(dx, dy);
        IncrementalWalker {
            x,
            k: (k as u32).wrapping_sub(dy as u32),
            q,
            r: r as u32,
            dy: dy as u32,
        }
    }

    /// [`EdgeWalker::start`] for any edge (the 32-bit target's rare wide edges, out of line).
    #[inline(never)]
    fn start_wide<const S: u32>(edge: &Edge, side: EdgeSide, y: i32) -> Self {
        let (x, k) = edge.divide::<S>(y, side);
        Self::from_end(x, k, edge.x1 - edge.x0, edge.y1 - edge.y0)
    }

    /// [`EdgeWalker::start`] for an edge with `|DX| < 2^13` and `1 ≤ DY < 2^13` (else `None`),
    /// in two unsigned 32-bit divisions with no sign fix-up. As [`Edge::divide_narrow`], but
    /// both dividends are first made non-negative by adding a multiple of the divisor:
    /// `DY·2^16 = F·DY·2^(16−S)` to the end's numerator (whose negative term
    /// `(y·F − Y0)·DX > −DY·2^13`; the sum stays below `2^29 + 2^26 + 2^29 + 2^29 < 2^31`), and
    /// `DY·2^13` to `DX` (`> −2^13`); the quotients come out `2^(16−S)` and `2^13` too large,
    /// the remainders unchanged.
    #[inline(always)]
    fn start_narrow<const S: u32>(edge: &Edge, side: EdgeSide, y: i32) -> Option<Self> {
        const LIM: i32 = 1 << 13;
        let dx = edge.x1.wrapping_sub(edge.x0);
        let dy = edge.y1.wrapping_sub(edge.y0);
        if dx.wrapping_add(LIM - 1) as u32 > (2 * LIM - 2) as u32
            || dy.wrapping_sub(1) as u32 >= (LIM - 1) as u32
        {
            return None;
        }
        let dy_nz = NonZeroU32::new(dy as u32)?;
        let den = NonZeroU32::new((dy as u32) << S)?;
        let rows_below = (y << S) - edge.y0;
        let bias = match side {
            EdgeSide::Left => den.get() as i32 - 1,
            EdgeSide::Right => -1,
        };
        let num = (edge.x0 & ((1 << S) - 1)) * dy + rows_below * dx + bias + (dy << 16);
        let num = num as u32;
        let (qx, rem) = (num / den, num % den);
        let x = qx as i32 + (edge.x0 >> S) - (1 << (16 - S));
        let step = (dx + (dy << 13)) as u32;
        let (q, r) = (step / dy_nz, step % dy_nz);
        Some(IncrementalWalker {
            x,
            k: (rem >> S).wrapping_sub(dy as u32),
            q: q as i32 - LIM,
            r,
            dy: dy as u32,
        })
    }
}

impl EdgeWalker for IncrementalWalker {
    #[inline(always)]
    fn start<const S: u32>(edge: &Edge, side: EdgeSide, y: i32) -> Self {
        if !WIDE_REGISTERS {
            if !HARDWARE_DIVIDE {
                // Software divisions: the signed narrow form, whose quotients are short (the
                // biased one adds 13 to 16 bits to each, one loop turn per bit).
                if edge.is_narrow() && edge.y1 > edge.y0 {
                    let (x, k) = edge.divide_narrow::<S>(y, side);
                    return Self::from_end(x, k, edge.x1 - edge.x0, edge.y1 - edge.y0);
                }
            } else if let Some(w) = Self::start_narrow::<S>(edge, side, y) {
                return w;
            }
            return Self::start_wide::<S>(edge, side, y);
        }
        let (x, k) = edge.divide::<S>(y, side); // 0 ≤ k < DY
        Self::from_end(x, k, edge.x1 - edge.x0, edge.y1 - edge.y0)
    }

    #[inline(always)]
    fn x(&self) -> i32 {
        self.x
    }

    #[inline(always)]
    fn step(&mut self) {
        let (k, carry) = self.k.overflowing_add(self.r);
        self.x += self.q + carry as i32;
        self.k = if carry { k.wrapping_sub(self.dy) } else { k };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ⌈a/b⌉ for b > 0 in i128, straight from the definition.
    fn ceil_div(a: i128, b: i128) -> i128 {
        -((-a).div_euclid(b))
    }

    fn expected<const S: u32>(e: &Edge, y: i32, side: EdgeSide) -> i32 {
        let f = 1i128 << S;
        let (x0, y0, dx, dy) = (
            e.x0 as i128,
            e.y0 as i128,
            (e.x1 - e.x0) as i128,
            (e.y1 - e.y0) as i128,
        );
        let c = ceil_div(x0 * dy + (y as i128 * f - y0) * dx, f * dy);
        (match side {
            EdgeSide::Left => c,
            EdgeSide::Right => c - 1,
        }) as i32
    }

    fn walk<W: EdgeWalker, const S: u32>(e: &Edge, side: EdgeSide) {
        let (y0, y1) = (e.first_row::<S>(), e.end_row::<S>());
        if y0 >= y1 {
            return;
        }
        let mut w = W::start::<S>(e, side, y0);
        for y in y0..y1 {
            assert_eq!(w.x(), expected::<S>(e, y, side), "{e:?} {side:?} row {y}");
            assert_eq!(e.end_at::<S>(y, side), w.x());
            w.step();
        }
    }

    #[test]
    fn tipe_figure_6_left_edge() {
        // TIPE's example: (3,0) → (7,10) as a left edge gives ⌈3 + 0.4·y⌉ for y = 0..9.
        let e = Edge {
            x0: 3,
            y0: 0,
            x1: 7,
            y1: 10,
        };
        let mut w = DivisionWalker::start::<0>(&e, EdgeSide::Left, 0);
        let mut xs = [0; 10];
        for x in xs.iter_mut() {
            *x = w.x();
            w.step();
        }
        assert_eq!(xs, [3, 4, 4, 5, 5, 5, 6, 6, 7, 7]);
    }

    #[test]
    fn walkers_agree_with_definition() {
        let mut rng = crate::test_rng::XorShift(0x9E37_79B9_7F4A_7C15u64);
        let mut rnd = |m: i32| (rng.next_u64() % (2 * m as u64 + 1)) as i32 - m;
        for _ in 0..3000 {
            let (x0, y0, x1) = (rnd(200), rnd(200), rnd(200));
            let y1 = y0 + 1 + rnd(100).abs();
            let e = Edge { x0, y0, x1, y1 };
            for side in [EdgeSide::Left, EdgeSide::Right] {
                walk::<DivisionWalker, 0>(&e, side);
                walk::<IncrementalWalker, 0>(&e, side);
                walk::<DivisionWalker, 4>(&e, side);
                walk::<IncrementalWalker, 4>(&e, side);
                walk::<IncrementalWalker, 2>(&e, side);
            }
        }
    }

    /// The smallest wide edge: `DX = 2^13` (one past the narrow limit), `DY = 5`.
    const WIDE: Edge = Edge {
        x0: 0,
        y0: 0,
        x1: 1 << 13,
        y1: 5,
    };

    /// 20,000 edges of at most `2^13 − 1` units across and down (the narrow limits, reached
    /// in a quarter of them), from the xorshift seed `seed`.
    fn narrow_edges(seed: u64) -> impl Iterator<Item = Edge> {
        let mut rng = crate::test_rng::XorShift(seed);
        let mut rnd = move |m: i32| (rng.next_u64() % (2 * m as u64 + 1)) as i32 - m;
        let lim = (1 << 13) - 1;
        (0..20_000).filter_map(move |i| {
            let (x0, y0) = (rnd(MAX_COORD), rnd(MAX_COORD - lim));
            let dx = [rnd(lim), rnd(40), lim, -lim][i % 4];
            let dy = 1 + [rnd(lim - 1).abs(), rnd(40).abs(), lim - 1, 0][i % 4];
            let x1 = x0.checked_add(dx).filter(|x| x.abs() <= MAX_COORD)?;
            Some(Edge {
                x0,
                y0,
                x1,
                y1: y0 + dy,
            })
        })
    }

    /// Both sides of `e` at its first two, middle and last two rows (at `S` sub-pixel bits).
    fn sampled_rows<const S: u32>(e: &Edge) -> impl Iterator<Item = (EdgeSide, i32)> {
        let (y0, y1) = (e.first_row::<S>(), e.end_row::<S>());
        [EdgeSide::Left, EdgeSide::Right]
            .into_iter()
            .flat_map(move |side| {
                [y0, y0 + 1, (y0 + y1) / 2, y1 - 2, y1 - 1]
                    .into_iter()
                    .filter(move |y| (y0..y1).contains(y))
                    .map(move |y| (side, y))
            })
    }

    /// The 32-bit division of narrow edges equals the i64 one (which the host takes).
    #[test]
    fn narrow_division_equals_wide() {
        fn check<const S: u32>(e: &Edge) {
            for (side, y) in sampled_rows::<S>(e) {
                let (n, den) = e.biased_numerator::<S>(y, side);
                let (x, rem) = div_floor_i64(n, den);
                let want = (x as i32, (rem >> S) as i32);
                assert_eq!(e.divide_narrow::<S>(y, side), want, "{e:?}");
                assert_eq!(e.divide::<S>(y, side), want, "{e:?}");
            }
        }
        for e in narrow_edges(0x1357_9BDF_2468_ACE0) {
            assert!(e.is_narrow());
            check::<0>(&e);
            check::<4>(&e);
            check::<16>(&e);
        }
        assert!(!WIDE.is_narrow());
    }

    /// The 32-bit target's unsigned narrow start equals the general one (which the host takes).
    #[test]
    fn narrow_start_equals_general() {
        fn check<const S: u32>(e: &Edge) {
            for (side, y) in sampled_rows::<S>(e) {
                let (x, k) = e.divide::<S>(y, side);
                let want = IncrementalWalker::from_end(x, k, e.x1 - e.x0, e.y1 - e.y0);
                let got = IncrementalWalker::start_narrow::<S>(e, side, y).expect("narrow");
                let fields = |w: IncrementalWalker| (w.x, w.k, w.q, w.r, w.dy);
                assert_eq!(fields(got), fields(want), "{e:?} {side:?} row {y}");
            }
        }
        for e in narrow_edges(0x0F1E_2D3C_4B5A_6978) {
            check::<0>(&e);
            check::<4>(&e);
            check::<16>(&e);
        }
        assert!(IncrementalWalker::start_narrow::<4>(&WIDE, EdgeSide::Left, 0).is_none());
        let flat = Edge {
            x0: 0,
            y0: 3,
            x1: 5,
            y1: 3,
        };
        assert!(IncrementalWalker::start_narrow::<4>(&flat, EdgeSide::Left, 0).is_none());
    }

    #[test]
    fn extreme_coordinates_do_not_overflow() {
        let m = MAX_COORD;
        for e in [
            Edge {
                x0: -m,
                y0: -m,
                x1: m,
                y1: m,
            },
            Edge {
                x0: m,
                y0: -m,
                x1: -m,
                y1: m,
            },
            Edge {
                x0: m,
                y0: -m,
                x1: m,
                y1: m,
            },
            Edge {
                x0: -m,
                y0: m - 1,
                x1: m,
                y1: m,
            },
        ] {
            for side in [EdgeSide::Left, EdgeSide::Right] {
                for y in [e.first_row::<4>(), 0, e.end_row::<4>() - 1] {
                    if y < e.first_row::<4>() || y >= e.end_row::<4>() {
                        continue;
                    }
                    let mut a = DivisionWalker::start::<4>(&e, side, y);
                    let mut b = IncrementalWalker::start::<4>(&e, side, y);
                    for k in 0..3 {
                        if y + k >= e.end_row::<4>() {
                            break;
                        }
                        assert_eq!(a.x(), expected::<4>(&e, y + k, side));
                        assert_eq!(b.x(), expected::<4>(&e, y + k, side));
                        a.step();
                        b.step();
                    }
                }
            }
        }
    }

    /// Issue "hostile inputs" #8: `ceil_shift` (and so `polygon::row_range`) is exact for every
    /// `i32`, `i32::MIN` included, with no overflow.
    #[test]
    fn ceil_shift_is_exact_for_every_i32() {
        let exact = |v: i32, s: u32| {
            (v as i64).div_euclid(1 << s) + ((v as i64).rem_euclid(1 << s) != 0) as i64
        };
        let mut rng = crate::test_rng::XorShift(0xC311_5A1F_0000_0008);
        for s in [0u32, 1, 4, 16, 31] {
            for v in [
                i32::MIN,
                i32::MIN + 1,
                -17,
                -16,
                -1,
                0,
                1,
                15,
                16,
                i32::MAX - 1,
                i32::MAX,
            ] {
                assert_eq!(ceil_shift(v, s) as i64, exact(v, s), "{v} {s}");
            }
            for _ in 0..2000 {
                let v = rng.next_u64() as i32;
                assert_eq!(ceil_shift(v, s) as i64, exact(v, s), "{v} {s}");
            }
        }
        use crate::raster::{polygon::row_range, SubpixelPoint};
        let p = |x: i32, y: i32| SubpixelPoint::<4>::new(x, y);
        assert_eq!(
            row_range(&[p(0, i32::MIN), p(0, i32::MAX)]),
            (-(1 << 27), 1 << 27)
        );
    }
}
