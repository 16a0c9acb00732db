//! Back-face culling, in one place: on the projected polygon's signed area (exact integers) when
//! every vertex projected, in the observer frame (exact `i128`) otherwise.
//!
//! Numeric contract: projected coordinates are within `±MAX_COORD = ±(2^28 − 1)` (the
//! projector rejects others), so screen differences fit `i32` and each product is exact in
//! `i64`; observer-frame coordinates are I16F16 (`|c| < 2^31` raw), edge vectors below `2^32`,
//! cross products below `2^65`, the final dot below `2^102`: exact in `i128`.

use crate::arith::wide::mul_wide;
use crate::geometry::vector::Vec3;
use crate::raster::SubpixelPoint;

/// Twice the signed area of a projected polygon (fan sum). Projected coordinates are within
/// `±MAX_COORD = ±(2^28 − 1)` (the projector rejects others), so coordinate differences fit
/// `i32` (`< 2^29`) and each product `i32 × i32` is exact in `i64` (one `smull` on a
/// Cortex-M), each triangle's term below `2^59`. The sum wraps modulo `2^64`, so it is exact
/// whenever the true value fits `i64`: always for simple polygons, whose twice-area is at most
/// twice their bounding box's, `2·(2^29)² = 2^59`. Front faces (counter-clockwise seen from outside, with `y` up) are clockwise on a
/// `y`-down screen: negative area.
#[inline(always)]
pub(super) fn screen_area<const S: u32>(n: usize, p: impl Fn(usize) -> SubpixelPoint<S>) -> i64 {
    let o = p(0);
    let mut sum = 0i64;
    for k in 1..n - 1 {
        let (b, c) = (p(k), p(k + 1));
        let (bx, by) = (b.x.wrapping_sub(o.x), b.y.wrapping_sub(o.y));
        let (cx, cy) = (c.x.wrapping_sub(o.x), c.y.wrapping_sub(o.y));
        sum = sum.wrapping_add(bx as i64 * cy as i64 - by as i64 * cx as i64);
    }
    sum
}

/// True when a projected triangle is a front face, [`screen_area`]`(3, …) < 0`, computed as
/// `bx·cy + by·(−cx)` (one multiply and one multiply-accumulate). Projected coordinates are
/// within `±MAX_COORD`, so the differences and their negations are below `2^29` in magnitude
/// and each product below `2^58`: the sum is exact in `i64`, equal to `screen_area`'s.
#[inline(always)]
pub(super) fn front_triangle<const S: u32>(
    a: SubpixelPoint<S>,
    b: SubpixelPoint<S>,
    c: SubpixelPoint<S>,
) -> bool {
    let (bx, by) = (b.x.wrapping_sub(a.x), b.y.wrapping_sub(a.y));
    let (cx, cy) = (c.x.wrapping_sub(a.x), c.y.wrapping_sub(a.y));
    mul_wide(bx, cy).wrapping_add(mul_wide(by, cx.wrapping_neg())) < 0
}

/// Back-face test in the observer frame (eye at the origin): the face is front-facing when
/// `(0 − P0)·N > 0` with `N` the outward normal. The observer frame is left-handed (x right,
/// y up, z forward), so the winding cross product there is `−N`: front ⇔ `P0·Σ cross > 0`.
pub(super) fn faces_eye_observer(n: usize, p: impl Fn(usize) -> Vec3) -> bool {
    let w = |v: Vec3| v.bits().map(|c| c as i128);
    let o = w(p(0));
    let mut nrm = [0i128; 3];
    for k in 1..n - 1 {
        let (a, b) = (w(p(k)), w(p(k + 1)));
        let e1 = [a[0] - o[0], a[1] - o[1], a[2] - o[2]];
        let e2 = [b[0] - o[0], b[1] - o[1], b[2] - o[2]];
        nrm[0] += e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] += e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] += e1[0] * e2[1] - e1[1] * e2[0];
    }
    // |o| < 2^31, |nrm| < 2^66·n: the dot stays below 2^102.
    o[0] * nrm[0] + o[1] * nrm[1] + o[2] * nrm[2] > 0
}
