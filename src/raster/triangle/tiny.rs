//! The tiny-triangle writer: set-up, edges and span starts of a small triangle in one place.
//!
//! Role in the pipeline: a fast path of the span writers
//! ([`draw_triangle_on`](super::draw::draw_triangle_on)), between the projected
//! triangle and the per-pixel loop ([`depth_span`]). It draws exactly what the general
//! path (the [`fill_triangle`](crate::raster::triangle::fill_triangle) walkers feeding a
//! [`SmallPlane`](super::interpolants::SmallPlane)) draws: the same pixels, depths and
//! luminances, and the same covered and written counts (tested on random triangles against
//! it). What differs is the amount of state: one set-up computes everything the rows need,
//! and each span is a call with a fresh register budget. Measured on the Cortex-M4 (QEMU,
//! instructions): SCENES.md's bunny frame 2.57 M → 2.09 M, the sphere 1.33 M → 1.19 M,
//! 16-row bands of the bunny 3.47 M → 3.02 M. It is used where that measured faster
//! ([`TINY_WRITER`](crate::arith::TINY_WRITER)): the 32-bit cores, with and without a divider.
//!
//! ## When it applies
//! Exact Gouraud luminance, or flat luminance over a depth plane that is not constant (flat
//! colour at constant depth has its own block loop), and a triangle whose bounding box is
//! below `2^K` sub-pixel units on both axes (`K =` [`small_bits`]`(S)`: 64 pixels at
//! `S = 4`) whose columns lie inside the drawable window
//! (its rows are clipped to the window's, so a band draws the triangles across its edges
//! here too). `S + K ≤ 19` (every `S ≤ 9`). Other triangles return `None` from
//! [`TinyTriangle::new`] and take the general path.
//!
//! The luminance reaches the palette through the span's [`Quantizer`], as on the general
//! path: through a 256-level ramp the writers interpolate the palette index itself (the
//! level plus the ramp's first entry) and store it; any other ramp, plain or dithered, maps
//! the level (`0..=255`) at each pixel ([`draw_triangle_on`](super::draw::draw_triangle_on)
//! sends flat triangles here only through a 256-level ramp).
//!
//! ## Without a hardware divider
//! On the Cortex-M0 (a division is a library loop, about 45 instructions plus 12 per quotient
//! bit) the same writer divides as little as the general path: every set-up division by `D`
//! or `2D`, and the two span starts, go through the area's reciprocal
//! ([`DivisorU32`], one division per triangle; the hardware's division elsewhere, the same
//! instructions as before), and the edges are walked from row to row ([`EdgeWalk`]: one
//! division per edge, at its first drawn row, then adds and carries;
//! [`TINY_WALKS_EDGES`](crate::arith::TINY_WALKS_EDGES)). Flat triangles keep the general
//! path there ([`TINY_FLAT`](crate::arith::TINY_FLAT)). Measured on the Cortex-M0 (QEMU,
//! instructions): SCENES.md's bunny frame 7.05 M → 6.61 M, the sphere 2.83 M → 2.82 M, 16-row
//! bands of the bunny 8.65 M → 8.07 M.
//! Tried there and dropped: the span starts walked down the left edge with the crossing
//! (the row's quotient-and-remainder step plus one pixel step per carry, a division only at
//! the first covered row of a left edge): the spans lose their two divisions (bunny span
//! calls 1.53 M → 0.93 M) but the walk's state spills the row loop: bunny 6.71 M → 7.06 M
//! inlined, 7.17 M with the row loop out of line, sphere 2.89 M → 2.94 M (measured with flat
//! triangles still in this writer).
//!
//! ## Where its instructions go, and what did not pay
//! Cortex-M4 profile of SCENES.md's bunny frame (`scripts/m4-profile.sh frame_bunny`,
//! 2.20 M instructions; 1,382 triangles drawn, 5,067 spans, 12,204 pixels): the triangle's
//! set-up and dispatch about 600 instructions a drawn triangle (a straight run of about 420
//! of them builds this writer's state, register-starved), a span about 80 before its
//! first pixel (call, slices, starts), a pixel about 20 (two carries and the depth test). Measured
//! alternatives, all drawing the same pictures:
//! - spans noted in batches of 16 by an out-of-line row walk, then drawn in one loop without
//!   a call per span: bunny +11.8 %, sphere +3.5 % (the inlined span body spills);
//! - each attribute as `whole + ⌊num / 2D⌋` with both parts stepped by adds (one division a
//!   pixel in place of the carry): bunny and sphere −1.3 % instructions, but more cycles
//!   (bunny 3.63 M → 3.77 M, sphere 1.93 M → 2.38 M, at the divider's 12-cycle worst case);
//! - [`Exact`]'s remainder kept biased by `−2D`, the carry read from the sign: bunny +0.4 %,
//!   cube +1.2 %, sphere −0.2 %.
//!
//! ## Conventions
//! Coordinates are local: sub-pixel units from the pixel-aligned corner `(ox, oy)·F` of the
//! bounding box (`F = 2^S`), so every vertex coordinate lies in `0..2^K + F`. The fill rule is
//! the triangle fill's (TIPE 2010): rows `⌈y_top⌉ ≤ y < ⌈y_bottom⌉`, columns
//! `⌈x_left⌉ ≤ x < ⌈x_right⌉` (left edges in, right edges out), each edge crossing
//! `⌈x_e(y)⌉ = ⌊(x_e·DY + F·DY − 1) / (F·DY)⌋` by one unsigned division per row
//! (TIPE's `Parcours` with its bias; the numerator `x_e·DY` is non-negative in local units), or
//! walked from the first drawn row's quotient and remainder ([`EdgeWalk`]).
//!
//! ## Numeric contract
//! - Depth (`u32` vertex values, the full range): the [`SmallPlane`](super::interpolants::SmallPlane)
//!   decomposition `gx = D·g1 + g0`, `gy = D·h1 + h0` (`0 ≤ g0, h0 < D`), whole parts kept
//!   mod `2^32`, and a span start `e' = (2·c0 + D) + 2·g0·px + 2·h0·py < 2^32` divided once by
//!   `2D`; see that type for the bounds. The split is built here from `A_i − A_min = D·Q_i + R_i`
//!   (three unsigned divisions) and the symmetric gradient `gx = Σ (A_i − A_min)·e_i`, whose
//!   remainder part `Σ R_i·e_i` has one zero term (the vertex of least depth) and so stays
//!   below `2·D·2^K ≤ 2^31`.
//! - Luminance (`0..=510`: a level of `0..=255` plus the ramp's first index): `T = 2M + D +
//!   2D·(L0 − L_min) = 2D·(L(p) − L_min) + D` lies in `D..2D·510 + D < 2^30` at a covered
//!   pixel, so the value `L_min + ⌊T / 2D⌋` and its remainder come from one 32-bit division;
//!   `T` is evaluated mod `2^32` with wrapping products, exact because the true value is in
//!   range. Its per-pixel step `2F·gx` is below `2^30` in magnitude (`|gx| < 2^(K+10)`,
//!   `S + K ≤ 19`).
//! - Both attributes round half up, `A0 + ⌊(2M + D) / 2D⌋`, as [`Exact`] everywhere.

use super::interpolants::Exact;
use super::slices::SpanTarget;
use super::small_plane::{div_floor_by_u32, small_bits};
use super::span::{depth_span, in_range, Quantizer, WrittenCount};
use crate::arith::euclid::{div_floor_i32, DivisorU32};
use crate::arith::{HARDWARE_DIVIDE, TINY_WALKS_EDGES};
use crate::raster::triangle::setup::TriangleSetup;
use crate::raster::{SubpixelPoint, Window};
use core::num::NonZeroU32;

/// The crossings of one edge with the rows, by division: on each row the crossing is
/// `n / den`, then `n += step`.
#[derive(Debug, Clone, Copy)]
struct RowCrossings {
    /// `x_e·DY + F·DY − 1` on the current row (local units).
    n: u32,
    /// `F·DX`, added per row.
    step: u32,
    /// `F·DY` (1 for an edge that covers no row: it is never divided by then).
    den: NonZeroU32,
}

impl RowCrossings {
    /// The walk of this edge from its current row: one division.
    #[inline(always)]
    fn walk(&self) -> EdgeWalk {
        EdgeWalk {
            x: self.n / self.den,
            // n mod den < den < 2^20 (S + K ≤ 19): an `i32`.
            k: (self.n % self.den) as i32,
            step: self.step as i32,
            den: self.den.get() as i32,
        }
    }
}

/// An edge's crossing stepped from row to row without a division (TIPE's `Parcours` with the
/// quotient found by subtraction): the numerator `n = den·x + k` with `0 ≤ k < den`; a row adds
/// `F·DX` to `k`, then whole `den`s move between `k` and `x`, one a turn (each turn moves the
/// crossing one pixel). A row takes `|F·DX| / den + 1` turns at most, so over an edge's drawn
/// rows the turns number at most its width in pixels plus its rows; the walk is never moved
/// past an edge's last drawn row (an edge one sub-pixel high may be `2^K` units wide).
///
/// Numeric contract: `den = F·DY < 2^20` and `|F·DX| < 2^20` (`S + K ≤ 19`), so `k + F·DX` is
/// an `i32`; `x` wraps like [`RowCrossings::n`] (the crossings of drawn rows are
/// non-negative).
#[derive(Debug, Clone, Copy)]
struct EdgeWalk {
    /// `⌊n / den⌋`, the crossing `⌈x_e⌉` on the current row.
    x: u32,
    /// `n mod den`.
    k: i32,
    /// `F·DX`.
    step: i32,
    /// `F·DY`.
    den: i32,
}

impl EdgeWalk {
    /// Moves to the next row.
    #[inline(always)]
    fn next_row(&mut self) {
        self.k += self.step;
        while self.k >= self.den {
            self.k -= self.den;
            self.x = self.x.wrapping_add(1);
        }
        while self.k < 0 {
            self.k += self.den;
            self.x = self.x.wrapping_sub(1);
        }
    }
}

/// A triangle set up for the tiny-triangle writer (see the module doc).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TinyTriangle<const S: u32> {
    /// The pixel of the local origin.
    ox: i32,
    /// The row of the local origin.
    oy: i32,
    /// Local rows: the first drawn, the end of the top half, the end of the bottom half (the
    /// vertices' rows `⌈y / F⌉` clipped to the window's).
    rows: [i32; 3],
    /// The edge from the top to the bottom vertex.
    long: RowCrossings,
    /// The top and bottom short edges, each started at its first drawn row.
    short: [RowCrossings; 2],
    /// True when the short edges are the left ones.
    middle_left: bool,
    /// `2D`, twice the positive doubled area, prepared for the span starts' divisions.
    two_d: DivisorU32,
    /// Depth at local pixel `(x, y)`: whole part `z[0] + z[1]·x + z[2]·y` and numerator
    /// `e' = z[3] + z[4]·x + z[5]·y` (all mod `2^32`), the [`SmallPlane`] terms
    /// `(B, g1, h1, 2·c0 + D, 2·g0, 2·h0)` re-based from the corner `C` to the local origin
    /// and scaled by `F`. `e'` is below `2^32` at a covered pixel, so its wrapped value is
    /// the true one.
    ///
    /// [`SmallPlane`]: super::interpolants::SmallPlane
    z: [u32; 6],
    /// Depth step per pixel right, quotient and remainder by `2D`.
    z_step: (u32, u32),
    /// Luminance `T` at the local origin, its per-pixel and per-row increments, and `L_min`.
    l: [u32; 4],
    /// Luminance step per pixel right, quotient and remainder by `2D`.
    l_step: (u32, u32),
}

/// `(⌊n / d⌋ mod 2^32, n mod d)` for `0 < d < 2^31`: the signed hardware division where
/// there is one, else `|n|` through `d`'s reciprocal and the floor's fix-up.
#[inline(always)]
fn div_floor(n: i32, d: &DivisorU32) -> (u32, u32) {
    if !HARDWARE_DIVIDE {
        return div_floor_by_u32(n as i64, d);
    }
    let (q, r) = div_floor_i32(n, d.get() as i32);
    (q as u32, r as u32)
}

impl<const S: u32> TinyTriangle<S> {
    /// The tiny writer's form of set-up `t` with `values[i] = [depth, luminance]` at the given
    /// vertex `i` (luminance `0..=510`), or `None` when the writer does not apply (see the
    /// module doc). A triangle of zero area draws nothing.
    #[inline(always)]
    pub(crate) fn new(
        t: &TriangleSetup<S>,
        values: [[u32; 2]; 3],
        window: &Window,
    ) -> Option<Self> {
        if S + small_bits(S) > 19 || !t.box_below(small_bits(S)) {
            return None;
        }
        let ([x_lo, x_hi], [y_lo, _]) = (t.x, t.y);
        if (x_lo >> S) < window.x0 || (x_hi >> S) >= window.x1 {
            return None;
        }
        let (ox, oy) = (x_lo >> S, y_lo >> S);
        // Local sub-pixel coordinates from the pixel-aligned origin (0..2^K + F). The planes
        // take the vertices in the given order, with their values (the exact values do not
        // depend on the order, and the values need no sort); the edges the sorted ones.
        let local = |q: SubpixelPoint<S>| (q.x - (ox << S), q.y - (oy << S));
        let p = t.given.map(local);
        // |2A| < 2^(2K) (the box is below 2^K): the set-up's twice-area is its low 32 bits.
        let cross = t.given_twice_area() as i32;
        let d = cross.unsigned_abs();
        // Per vertex, the factors of the gradients: gx = Σ A_i·ey_i, gy = Σ A_i·ex_i, signed by
        // the orientation, so that the gradients are those of `2M` over the positive `2D`.
        let (ey, ex) = if cross < 0 {
            (
                [p[2].1 - p[1].1, p[0].1 - p[2].1, p[1].1 - p[0].1],
                [p[1].0 - p[2].0, p[2].0 - p[0].0, p[0].0 - p[1].0],
            )
        } else {
            (
                [p[1].1 - p[2].1, p[2].1 - p[0].1, p[0].1 - p[1].1],
                [p[2].0 - p[1].0, p[0].0 - p[2].0, p[1].0 - p[0].0],
            )
        };
        if d == 0 {
            return Some(TinyTriangle::EMPTY);
        }
        let corner = (x_lo - (ox << S), y_lo - (oy << S));
        // Every set-up division is by D or 2D: prepared once (a reciprocal where there is no
        // divider). D < 2^(2K) ≤ 2^20: 2D does not overflow.
        let d = DivisorU32::new(NonZeroU32::new(d)?);
        let two_d = d.doubled();
        let (z, z_step) = depth_terms::<S>(p[0], values.map(|a| a[0]), &d, (ey, ex), corner);
        let (l, l_step) = luminance_terms::<S>(p[0], values.map(|a| a[1] as i32), &two_d, (ey, ex));
        // Wrapping: only a box about 2^31 rows from the window (possible at S = 0), which draws
        // nothing either way, makes them wrap.
        let (top, bottom) = (window.y0.wrapping_sub(oy), window.y1.wrapping_sub(oy));
        let (rows, long, short) = edges::<S>(t.sorted.map(local), top, bottom);
        Some(TinyTriangle {
            ox,
            oy,
            rows,
            long,
            short,
            middle_left: t.middle_left(),
            two_d,
            z,
            z_step,
            l,
            l_step,
        })
    }

    /// Nothing to draw (zero area).
    const EMPTY: Self = TinyTriangle {
        ox: 0,
        oy: 0,
        rows: [0; 3],
        long: RowCrossings {
            n: 0,
            step: 0,
            den: NonZeroU32::MIN,
        },
        short: [RowCrossings {
            n: 0,
            step: 0,
            den: NonZeroU32::MIN,
        }; 2],
        middle_left: false,
        two_d: DivisorU32::ONE,
        z: [0; 6],
        z_step: (0, 0),
        l: [0; 4],
        l_step: (0, 0),
    };

    /// Draws the triangle into `targets` (depth test, exact depth and luminance, mapped to
    /// indices by `quantizer_at(x, y)` at each span's first pixel, as the general path's span
    /// kinds do); returns the pixels covered and written (0 written when `count` does not
    /// count).
    #[inline(always)]
    pub(crate) fn draw<T: SpanTarget, C: WrittenCount, Q: Quantizer>(
        &self,
        targets: &mut T,
        count: C,
        quantizer_at: &impl Fn(i32, i32) -> Q,
    ) -> (u32, u32) {
        if TINY_WALKS_EDGES {
            self.draw_walked(targets, count, quantizer_at)
        } else {
            self.draw_divided(targets, count, quantizer_at)
        }
    }

    /// [`Self::draw`] with one division per edge and row.
    #[inline(always)]
    fn draw_divided<T: SpanTarget, C: WrittenCount, Q: Quantizer>(
        &self,
        targets: &mut T,
        count: C,
        quantizer_at: &impl Fn(i32, i32) -> Q,
    ) -> (u32, u32) {
        let (mut covered, mut written) = (0u32, 0u32);
        let mut long = self.long;
        let mut y = self.rows[0];
        for (half, short) in self.short.iter().enumerate() {
            let mut short = *short;
            let end = self.rows[half + 1];
            while y < end {
                let xl = long.n / long.den;
                let xs = short.n / short.den;
                let (x0, x1) = if self.middle_left { (xs, xl) } else { (xl, xs) };
                if x0 < x1 {
                    covered += x1 - x0;
                    written += self.span(targets, x0, x1, y, count, quantizer_at);
                }
                long.n = long.n.wrapping_add(long.step);
                short.n = short.n.wrapping_add(short.step);
                y += 1;
            }
        }
        (covered, written)
    }

    /// [`Self::draw`] with one division per edge, at its first drawn row: each later row's
    /// crossing is the previous one moved by the carries of the remainder ([`EdgeWalk`]).
    #[inline(always)]
    fn draw_walked<T: SpanTarget, C: WrittenCount, Q: Quantizer>(
        &self,
        targets: &mut T,
        count: C,
        quantizer_at: &impl Fn(i32, i32) -> Q,
    ) -> (u32, u32) {
        let (mut covered, mut written) = (0u32, 0u32);
        let mut long: Option<EdgeWalk> = None;
        let mut y = self.rows[0];
        for (half, short) in self.short.iter().enumerate() {
            let end = self.rows[half + 1];
            if y >= end {
                continue;
            }
            // The long edge is started on its first drawn row, and moved on from the top half's
            // last row to the bottom half's first.
            let mut l = match long {
                None => self.long.walk(),
                Some(mut l) => {
                    l.next_row();
                    l
                }
            };
            let mut s = short.walk();
            loop {
                let (x0, x1) = if self.middle_left {
                    (s.x, l.x)
                } else {
                    (l.x, s.x)
                };
                if x0 < x1 {
                    covered += x1 - x0;
                    written += self.span(targets, x0, x1, y, count, quantizer_at);
                }
                y += 1;
                // Never moved past its half's last row: an edge one sub-pixel high may cross a
                // row 2^K units wide.
                if y >= end {
                    break;
                }
                l.next_row();
                s.next_row();
            }
            long = Some(l);
        }
        (covered, written)
    }

    /// One span: local pixels `x0..x1` of local row `y`. Out of line: inlined into the row
    /// loop, whose edges keep six values live, its starts and pixel loop spill more (measured
    /// inlined: Cortex-M4 bunny frame +3.8 %, sphere +5.4 %).
    #[inline(never)]
    fn span<T: SpanTarget, C: WrittenCount, Q: Quantizer>(
        &self,
        targets: &mut T,
        x0: u32,
        x1: u32,
        y: i32,
        count: C,
        quantizer_at: &impl Fn(i32, i32) -> Q,
    ) -> u32 {
        let two_d = self.two_d;
        let (px, py) = (x0 as i32 + self.ox, y + self.oy);
        let Some((cs, zs)) = targets.span_at(px, py, (x1 - x0) as usize) else {
            return 0;
        };
        let [b, bx, by, e0, ex, ey] = self.z;
        let whole = b
            .wrapping_add(bx.wrapping_mul(x0))
            .wrapping_add(by.wrapping_mul(y as u32));
        let e = e0
            .wrapping_add(ex.wrapping_mul(x0))
            .wrapping_add(ey.wrapping_mul(y as u32));
        let (value, rem) = two_d.add_div_rem(whole, e);
        let z = Exact::from_parts(value, rem, self.z_step, two_d.get());
        let [t0, gx, gy, l_min] = self.l;
        let t = t0
            .wrapping_add(gx.wrapping_mul(x0))
            .wrapping_add(gy.wrapping_mul(y as u32));
        let (value, rem) = two_d.add_div_rem(l_min, t);
        let lum = Exact::from_parts(value, rem, self.l_step, two_d.get());
        depth_span(cs, zs, z, in_range(lum, quantizer_at(px, py)), count)
    }
}

/// The depth terms of [`TinyTriangle`] (its fields `z` and `z_step`) for depths `z` at the
/// local vertices (in any order), whose first is `p0`; `(ey, ex)` the gradient factors and `corner`
/// the bounding box's local corner `C` (module doc, numeric contract).
#[inline(always)]
fn depth_terms<const S: u32>(
    p0: (i32, i32),
    z: [u32; 3],
    dd: &DivisorU32,
    (ey, ex): ([i32; 3], [i32; 3]),
    (cxl, cyl): (i32, i32),
) -> ([u32; 6], (u32, u32)) {
    // A_i − A_min = D·Q_i + R_i; gx = Σ (A_i − A_min)·ey_i, gy = Σ (A_i − A_min)·ex_i.
    let d = dd.get();
    let z_min = z[0].min(z[1]).min(z[2]);
    let (mut gq, mut gr, mut hq, mut hr) = (0u32, 0i32, 0u32, 0i32);
    for i in 0..3 {
        let a = z[i] - z_min;
        let (q, r) = dd.div_rem(a);
        gq = gq.wrapping_add(q.wrapping_mul(ey[i] as u32));
        hq = hq.wrapping_add(q.wrapping_mul(ex[i] as u32));
        // One of the three R is 0 (the vertex of least depth): |Σ R·e| < 2·D·2^K.
        gr = gr.wrapping_add((r as i32).wrapping_mul(ey[i]));
        hr = hr.wrapping_add((r as i32).wrapping_mul(ex[i]));
    }
    let (g1, g0) = div_floor(gr, dd);
    let (h1, h0) = div_floor(hr, dd);
    let (g1, h1) = (gq.wrapping_add(g1), hq.wrapping_add(h1));
    // Corner C = (min x, min y) of the vertices (local); offsets from vertex 0.
    let (cx, cy) = (cxl - p0.0, cyl - p0.1);
    let e = (g0 as i32)
        .wrapping_mul(cx)
        .wrapping_add((h0 as i32).wrapping_mul(cy));
    let (c1, c0) = div_floor(e, dd);
    let base = z[0]
        .wrapping_add(g1.wrapping_mul(cx as u32))
        .wrapping_add(h1.wrapping_mul(cy as u32))
        .wrapping_add(c1);
    let fg0 = g0 << S;
    let (fq, fr) = dd.div_rem(fg0);
    let z_step = (g1.wrapping_shl(S).wrapping_add(fq), 2 * fr);
    // Offsets from the corner are `x·F − cx`, `y·F − cy`: fold `cx`, `cy` in.
    let (cx, cy) = (cxl as u32, cyl as u32);
    let (g0x2, h0x2, e_corner) = (2 * g0, 2 * h0, 2 * c0 + d);
    let z = [
        base.wrapping_sub(g1.wrapping_mul(cx))
            .wrapping_sub(h1.wrapping_mul(cy)),
        g1 << S,
        h1 << S,
        e_corner
            .wrapping_sub(g0x2.wrapping_mul(cx))
            .wrapping_sub(h0x2.wrapping_mul(cy)),
        g0x2 << S,
        h0x2 << S,
    ];
    (z, z_step)
}

/// The luminance terms of [`TinyTriangle`] (its fields `l` and `l_step`) for luminances `l`
/// at the local vertices (in any order), whose first is `p0`: `T = 2M + D + 2D·(L0 − L_min)` in
/// `0..2^30` (module doc).
#[inline(always)]
fn luminance_terms<const S: u32>(
    p0: (i32, i32),
    l: [i32; 3],
    two_dd: &DivisorU32,
    (ey, ex): ([i32; 3], [i32; 3]),
) -> ([u32; 4], (u32, u32)) {
    let two_d = two_dd.get();
    let d = two_d / 2;
    let l_min = l[0].min(l[1]).min(l[2]);
    let (lx, ly) = (
        l[0] * ey[0] + l[1] * ey[1] + l[2] * ey[2],
        l[0] * ex[0] + l[1] * ex[1] + l[2] * ex[2],
    );
    let t0 = (d + two_d * (l[0] - l_min) as u32)
        .wrapping_sub((2 * lx).wrapping_mul(p0.0) as u32)
        .wrapping_sub((2 * ly).wrapping_mul(p0.1) as u32);
    let l_step = div_floor((2 * lx) << S, two_dd);
    let l = [
        t0,
        ((2 * lx) << S) as u32,
        ((2 * ly) << S) as u32,
        l_min as u32,
    ];
    (l, l_step)
}

/// The rows and edges of [`TinyTriangle`] for the sorted local vertices `p`, the window's
/// rows being `top..bottom` (local): from the first visible row to the middle vertex's row,
/// then to the bottom vertex's; the long edge and the short ones, each started at its first
/// drawn row.
#[inline(always)]
fn edges<const S: u32>(
    p: [(i32, i32); 3],
    top: i32,
    bottom: i32,
) -> ([i32; 3], RowCrossings, [RowCrossings; 2]) {
    let [a, b, c] = p;
    let ceil_row = |t: i32| (t + (1 << S) - 1) >> S;
    let first = ceil_row(a.1).max(top);
    let middle = ceil_row(b.1);
    let rows = [first, middle.min(bottom), ceil_row(c.1).min(bottom)];
    let edge = |p: (i32, i32), q: (i32, i32), y: i32| {
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let den = (dy << S) as u32;
        // Wrapping: an edge started past its last row (never divided) may leave `i32`.
        let n = (p.0 * dy).wrapping_add((y << S).wrapping_sub(p.1).wrapping_mul(dx)) as u32;
        RowCrossings {
            n: n.wrapping_add(den).wrapping_sub(1),
            step: (dx << S) as u32,
            den: NonZeroU32::new(den).unwrap_or(NonZeroU32::MIN),
        }
    };
    let short = [edge(a, b, first), edge(b, c, middle.max(first))];
    (rows, edge(a, c, first), short)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::{DepthBuffer, Framebuffer};
    use crate::raster::triangle::span::Direct;
    use crate::raster::triangle::{draw_tiny_or_planar, LuminanceRamp, RasterTarget};
    use crate::raster::MAX_COORD;

    const TW: usize = 80;
    const TH: usize = 80;

    /// Triangle `v` with `values` (luminance with the ramp's offset, `0..=510`) drawn over the
    /// depth contents `init` by the tiny-triangle writer and by the general exact path. `None`
    /// when the tiny writer does not apply; otherwise both must agree on every pixel, every
    /// depth sample and the counts, which are returned.
    fn tiny_vs_general<const S: u32>(
        v: [SubpixelPoint<S>; 3],
        values: [[u32; 2]; 3],
        init: &[u16; TW * TH],
    ) -> Option<(u32, u32)> {
        tiny_vs_general_in((0, TH as u16), v, values, init)
    }

    /// [`tiny_vs_general`] into the band of rows `top..top + height`.
    fn tiny_vs_general_in<const S: u32>(
        rows: (u16, u16),
        v: [SubpixelPoint<S>; 3],
        values: [[u32; 2]; 3],
        init: &[u16; TW * TH],
    ) -> Option<(u32, u32)> {
        tiny_vs_general_mapped(rows, v, values, init, |_, _| Direct)
    }

    /// [`tiny_vs_general_in`] with luminances (`0..=255`) mapped by `quantizer_at` in both
    /// writers.
    fn tiny_vs_general_mapped<const S: u32, Q: Quantizer>(
        (top, height): (u16, u16),
        v: [SubpixelPoint<S>; 3],
        values: [[u32; 2]; 3],
        init: &[u16; TW * TH],
        quantizer_at: impl Fn(i32, i32) -> Q + Copy,
    ) -> Option<(u32, u32)> {
        // 0: the general path; 1: the tiny writer dividing on each row; 2: walking its edges.
        let draw = |writer: u8| {
            let mut px = [7u8; TW * TH];
            let mut zs = *init;
            let n = TW * height as usize;
            let mut fb = Framebuffer::band(&mut px[..n], TW as u16, height, top).unwrap();
            let mut zb = DepthBuffer::band(&mut zs[..n], TW as u16, height, top).unwrap();
            let mut target = RasterTarget::new(&mut fb, &mut zb);
            let t = TriangleSetup::in_range(v);
            let counts = match writer {
                0 => draw_tiny_or_planar(&mut target, t, values, quantizer_at, false),
                _ => TinyTriangle::<S>::new(&t, values, &target.window).map(|tiny| {
                    let (targets, count) = (&mut target.targets, target.count);
                    if writer == 1 {
                        tiny.draw_divided(targets, count, &quantizer_at)
                    } else {
                        tiny.draw_walked(targets, count, &quantizer_at)
                    }
                }),
            };
            (counts, px, zs)
        };
        let (general, px, zs) = draw(0);
        let (divided, divided_px, divided_zs) = draw(1);
        let (walked, walked_px, walked_zs) = draw(2);
        assert_eq!(divided, walked, "counts {v:?} {values:?}");
        let tiny = divided?;
        for (tiny_px, tiny_zs) in [(divided_px, divided_zs), (walked_px, walked_zs)] {
            assert!(tiny_px == px, "pixels {v:?} {values:?}");
            assert!(tiny_zs == zs, "depths {v:?} {values:?}");
        }
        assert_eq!(Some(tiny), general, "counts {v:?} {values:?}");
        Some(tiny)
    }

    /// Random triangles of every size up to and past the tiny writer's box limit, placed in,
    /// across and outside the frame's edges, with depths over the whole 32-bit range (and at
    /// its ends) drawn over random stored depths: where the writer applies it draws exactly
    /// what the general path draws, and it applies exactly to boxes below `2^K` inside the
    /// window.
    fn tiny_matches_general_on_random_triangles<const S: u32>(seed: u64, n: usize) -> u32 {
        let mut rng = crate::test_rng::XorShift(seed);
        let mut init = [0u16; TW * TH];
        let lim = 1i32 << small_bits(S);
        let mut drawn = 0;
        for i in 0..n {
            let mut rnd = |m: u64| rng.next_u64() % m;
            // Box sizes: one pixel, a few, up to the limit, and just past it.
            let m = [1 << S, 4 << S, lim / 4, lim - 1, lim + 40][i % 5] as i64;
            let (cx, cy) = (
                rnd((TW as u64 + 8) << S) as i64 - (4 << S),
                rnd((TH as u64 + 8) << S) as i64 - (4 << S),
            );
            let mut v = [SubpixelPoint::<S>::new(0, 0); 3];
            for p in v.iter_mut() {
                let x = cx + rnd(m as u64 + 1) as i64 - m / 2;
                let y = cy + rnd(m as u64 + 1) as i64 - m / 2;
                *p = SubpixelPoint::new(x as i32, y as i32);
            }
            let z0 = rnd(1 << 32) as u32;
            let mut values = [[0u32; 2]; 3];
            for a in values.iter_mut() {
                a[0] = match rnd(8) {
                    0 => 0,
                    1 => u32::MAX,
                    2..=4 => z0.wrapping_add(rnd(1 << 22) as u32),
                    _ => rnd(1 << 32) as u32,
                };
                a[1] = rnd(511) as u32;
            }
            for s in init.iter_mut() {
                *s = match rnd(3) {
                    0 => u16::MAX,
                    1 => (z0 >> 16) as u16,
                    _ => rnd(1 << 16) as u16,
                };
            }
            let (xs, ys) = (v.map(|p| p.x), v.map(|p| p.y));
            let (x_lo, x_hi) = (*xs.iter().min().unwrap(), *xs.iter().max().unwrap());
            let (y_lo, y_hi) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
            let applies =
                x_hi - x_lo < lim && y_hi - y_lo < lim && x_lo >> S >= 0 && (x_hi >> S) < TW as i32;
            // One in three into a 16-row band (rows 30..46), the others into the whole frame.
            let rows = if i % 3 == 0 { (30, 16) } else { (0, TH as u16) };
            // Luminances offset to indices (a 256-level ramp) in half of the triangles; in the
            // others levels of 0..=255 through a 32-level ramp, plain or dithered.
            let ramp = LuminanceRamp {
                first: 100,
                levels: 32,
            };
            let counts = match i % 4 {
                0 | 2 => tiny_vs_general_in(rows, v, values, &init),
                1 => {
                    let values = values.map(|[z, l]| [z, l / 2]);
                    tiny_vs_general_mapped(rows, v, values, &init, |_, _| ramp)
                }
                _ => {
                    let values = values.map(|[z, l]| [z, l / 2]);
                    let dither = |x, y| super::super::dither::Bayer4::at(ramp, x, y);
                    tiny_vs_general_mapped(rows, v, values, &init, dither)
                }
            };
            assert_eq!(counts.is_some(), applies, "{v:?}");
            drawn += counts.map_or(0, |(covered, _)| (covered > 0) as u32);
        }
        drawn
    }

    #[test]
    fn tiny_writer_draws_what_the_general_path_draws() {
        // Enough of the triangles are drawn for the comparison to mean something.
        let drawn = tiny_matches_general_on_random_triangles::<4>(0x9E37_79B9_7F4A_7C15, 20_000);
        assert!(drawn > 4000, "{drawn}");
        // At S = 0 the larger boxes (up to 1023 pixels) rarely fit the 80-pixel frame.
        let drawn = tiny_matches_general_on_random_triangles::<0>(0xD1B5_4A32_D192_ED03, 3000);
        assert!(drawn > 300, "{drawn}");
        let drawn = tiny_matches_general_on_random_triangles::<8>(0x8CB9_2BA7_2F3D_8DD7, 3000);
        assert!(drawn > 600, "{drawn}");
    }

    /// The tiny writer's limits: the largest box it takes and the first it leaves to the
    /// general path, boxes touching the window's last row and column and boxes one pixel out,
    /// zero area, vertex values at the ends of their ranges, coordinates whose differences
    /// wrap, and sub-pixel precisions too fine for its 32-bit luminance step.
    #[test]
    fn tiny_writer_limits() {
        let init = [u16::MAX; TW * TH];
        let q = |x: i32, y: i32| SubpixelPoint::<4>::new(x, y);
        let ends = [[0, 0], [u32::MAX, 510], [1 << 31, 255]];
        // Box 1023 × 1023 units (63.9 px): taken; 1024: not.
        let big = [q(8, 8), q(8 + 1023, 8 + 500), q(8 + 300, 8 + 1023)];
        let (covered, written) = tiny_vs_general(big, ends, &init).unwrap();
        assert!(covered > 1000 && written == covered, "{covered} {written}");
        let wide = [q(8, 8), q(8 + 1024, 8 + 500), q(8 + 300, 8 + 100)];
        assert!(tiny_vs_general(wide, ends, &init).is_none());
        let tall = [q(8, 8), q(8 + 100, 8 + 1024), q(8 + 300, 8 + 100)];
        assert!(tiny_vs_general(tall, ends, &init).is_none());
        // The last column and row of the window (pixel 79, 59) are in; one more is out.
        let (xe, ye) = ((TW as i32) << 4, (TH as i32) << 4);
        let corner = [q(xe - 100, ye - 90), q(xe - 1, ye - 40), q(xe - 60, ye - 1)];
        assert!(tiny_vs_general(corner, ends, &init).unwrap().0 > 0);
        let past = [q(xe - 100, ye - 90), q(xe, ye - 40), q(xe - 60, ye - 1)];
        assert!(tiny_vs_general(past, ends, &init).is_none());
        let left = [q(-1, 20), q(50, 40), q(20, 60)];
        assert!(tiny_vs_general(left, ends, &init).is_none());
        // Rows are clipped, not refused: boxes across the window's top or bottom, or across
        // both edges of a band, or wholly outside its rows, draw what the general path draws.
        let below = [
            q(xe - 100, ye - 90),
            q(xe - 1, ye - 40),
            q(xe - 60, ye + 200),
        ];
        assert!(tiny_vs_general(below, ends, &init).unwrap().0 > 0);
        let above = [q(10, -200), q(50, 40), q(20, 60)];
        assert!(tiny_vs_general(above, ends, &init).unwrap().0 > 0);
        let tall = [q(100, 100), q(700, 400), q(300, 1000)];
        let (covered, _) = tiny_vs_general_in((30, 4), tall, ends, &init).unwrap();
        assert!(covered > 40, "{covered}");
        assert_eq!(
            tiny_vs_general_in((30, 4), corner, ends, &init),
            Some((0, 0))
        );
        // Zero area (collinear, repeated vertices): nothing drawn.
        for flat in [
            [q(16, 16), q(48, 48), q(80, 80)],
            [q(16, 16), q(16, 16), q(90, 40)],
            [q(16, 16), q(16, 16), q(16, 16)],
        ] {
            assert_eq!(tiny_vs_general(flat, ends, &init), Some((0, 0)));
        }
        // The widest box of the raster's range (2^29 units) is not a small box.
        let huge = [q(-MAX_COORD, 16), q(MAX_COORD, 16), q(0, 40)];
        let window = Window::new(0, 0, TW as i32, TH as i32);
        let t = TriangleSetup::in_range(huge);
        assert!(TinyTriangle::<4>::new(&t, ends, &window).is_none());
        // S + K > 19: never taken.
        let v12 = [
            SubpixelPoint::<12>::new(0, 0),
            SubpixelPoint::<12>::new(3000, 0),
            SubpixelPoint::<12>::new(0, 3000),
        ];
        let t = TriangleSetup::in_range(v12);
        assert!(TinyTriangle::<12>::new(&t, ends, &window).is_none());
    }
}
