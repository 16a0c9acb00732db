//! The triangle set-up: what every triangle writer needs of a triangle, computed once.
//!
//! Role in the pipeline: between projection and the writers. The fill
//! ([`fill`](super::fill)), the attribute planes (`small_plane`, `plane`, `wide_plane`), the
//! tiny-triangle writer, Phong and the shadow map's depth pass all start from a
//! [`TriangleSetup`]: the vertices as given and sorted by row, the twice-area and the
//! orientation, the bounding box and the three edges. A writer that declines a triangle (the
//! tiny writer for a large box, say) hands the same set-up on to the next one.
//!
//! ## Conventions
//! - Screen axes: `x` right, `y` down; sub-pixel units of `2^-S` pixel ([`SubpixelPoint`]).
//! - The sort is stable: three compare-and-swaps of rows (`<`, so equal rows keep the given
//!   order), `a` top, `b` middle, `c` bottom. A writer whose per-vertex values need no order
//!   (the exact planes' values do not depend on it) takes them in the given order with the
//!   vertices as given; the edges are the sorted vertices'.
//! - The twice-area is `(b − a) × (c − a)` of the sorted vertices: negative when the middle
//!   vertex lies left of the long edge `a → c` (the edges walked from `b` are then the left
//!   ones), and when the sorted vertices turn counter-clockwise on screen.
//!   [`TriangleSetup::given_twice_area`] is the same for the vertices in the given order (the
//!   planes' order: vertex 0 is their origin), the sorted one negated when the sort is an odd
//!   permutation.
//!
//! ## Numeric contract
//! Vertices within the raster's range (`|x|, |y| ≤ MAX_COORD = 2^28 − 1`, checked by
//! [`TriangleSetup::new`], asserted by [`TriangleSetup::in_range`]): differences of
//! coordinates fit `i32` (`< 2^29`), so each product of the twice-area is one 32×32→64-bit
//! multiply (`smull` on a Cortex-M3/M4), the twice-area `|2A| < 2^59` is exact in `i64`, and a
//! triangle whose bounding box is below `2^K` units on both axes has `|2A| < 2^(2K)` (a
//! triangle fills at most half its box), exact in its low 32 bits for `K ≤ 15`. Zero area
//! (collinear or repeated vertices) covers nothing.

use super::edge_walker::Edge;
use crate::arith::wide::mul_wide;
use crate::raster::range::{check_range, FillError};
use crate::raster::SubpixelPoint;

/// The screen orientation of `a, b, c`: twice their signed area in sub-pixel units squared,
/// `(b − a) × (c − a)`, the one formula every stage uses (the set-up, the renderer's cull and
/// polygon area, the visibility methods' stored triangles, facts and planes).
///
/// With screen axes (`x` right, `y` down) it is negative when the vertices turn
/// counter-clockwise on screen (a front face, the renderer's culling rule), and, for `a`
/// above `c`, when `b` lies left of the line `a → c`; zero for a triangle that covers no
/// pixel.
///
/// Numeric contract: points within the raster's range (`|x|, |y| ≤ MAX_COORD = 2^28 − 1`,
/// what the projector and the set-up check): differences fit `i32` (`< 2^29`), so each
/// product is one 32×32→64-bit multiply (`arith::wide::mul_wide`: `smull`/`smlal` on a Cortex-M3/M4,
/// inline 16-bit products on the M0), each below `2^58`, and the result `|2A| < 2^59` is exact.
/// Formed as `bx·cy + by·(−cx)` (a multiply and a multiply-accumulate).
#[inline(always)]
pub fn twice_area<const S: u32>(
    a: SubpixelPoint<S>,
    b: SubpixelPoint<S>,
    c: SubpixelPoint<S>,
) -> i64 {
    let (bx, by) = (b.x.wrapping_sub(a.x), b.y.wrapping_sub(a.y));
    let (cx, cy) = (c.x.wrapping_sub(a.x), c.y.wrapping_sub(a.y));
    mul_wide(bx, cy).wrapping_add(mul_wide(by, cx.wrapping_neg()))
}

/// One triangle, set up once for every writer (see the module doc).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriangleSetup<const S: u32> {
    /// The vertices in the order given.
    pub(crate) given: [SubpixelPoint<S>; 3],
    /// The vertices sorted by row: top `a`, middle `b`, bottom `c`.
    pub(crate) sorted: [SubpixelPoint<S>; 3],
    /// The three compare-and-swaps of the sort, in order (true: swapped): their parity is
    /// the sign between the given and the sorted orientation.
    swaps: [bool; 3],
    /// `(b − a) × (c − a)` of the sorted vertices.
    pub(crate) twice_area: i64,
    /// The bounding box's columns `[x_lo, x_hi]` (sub-pixel units).
    pub(crate) x: [i32; 2],
    /// The bounding box's rows `[y_lo, y_hi]` (sub-pixel units): the top and bottom vertices'.
    pub(crate) y: [i32; 2],
}

impl<const S: u32> TriangleSetup<S> {
    /// The set-up of `v`, or [`FillError::CoordinateOutOfRange`] for a vertex outside the
    /// raster's range (before any arithmetic).
    #[inline(always)]
    pub(crate) fn new(v: [SubpixelPoint<S>; 3]) -> Result<Self, FillError> {
        check_range(&v)?;
        Ok(Self::in_range(v))
    }

    /// The set-up of `v`, whose range the caller has checked (the renderer's projector per
    /// vertex, the span writers once per triangle); asserted in checked builds.
    #[inline(always)]
    pub(crate) fn in_range(v: [SubpixelPoint<S>; 3]) -> Self {
        debug_assert!(
            check_range(&v).is_ok(),
            "vertices outside the raster's range"
        );
        let swaps = sort_swaps(v.map(|p| p.y));
        let sorted @ [a, b, c] = sort_by(swaps, v);
        TriangleSetup {
            given: v,
            sorted,
            swaps,
            twice_area: twice_area(a, b, c),
            x: [
                v[0].x.min(v[1].x).min(v[2].x),
                v[0].x.max(v[1].x).max(v[2].x),
            ],
            y: [a.y, c.y],
        }
    }

    /// `values` (one per given vertex) in the order of [`Self::sorted`] (the tests' check of
    /// the sort).
    #[cfg(test)]
    pub(crate) fn sort<T: Copy>(&self, values: [T; 3]) -> [T; 3] {
        sort_by(self.swaps, values)
    }

    /// Twice the signed area of the vertices in the given order, `(v1 − v0) × (v2 − v0)`.
    #[inline(always)]
    pub(crate) fn given_twice_area(&self) -> i64 {
        let [s0, s1, s2] = self.swaps;
        if s0 ^ s1 ^ s2 {
            -self.twice_area
        } else {
            self.twice_area
        }
    }

    /// True when the middle vertex lies left of the long edge (the short edges are the left
    /// ones); meaningful for a triangle with area.
    #[inline(always)]
    pub(crate) fn middle_left(&self) -> bool {
        self.twice_area < 0
    }

    /// True when the bounding box is below `2^bits` units on both axes (`bits < 32`).
    #[inline(always)]
    pub(crate) fn box_below(&self, bits: u32) -> bool {
        // Unsigned: the true difference of `hi ≥ lo` is below 2^32.
        let lim = 1u32 << bits;
        (self.x[1].wrapping_sub(self.x[0]) as u32) < lim
            && (self.y[1].wrapping_sub(self.y[0]) as u32) < lim
    }

    /// The long edge `a → c` and the short edges `a → b` (top) and `b → c` (bottom), low end
    /// first as the walkers take them.
    #[inline(always)]
    pub(crate) fn edges(&self) -> [Edge; 3] {
        let [a, b, c] = self.sorted;
        let edge = |p: SubpixelPoint<S>, q: SubpixelPoint<S>| Edge {
            x0: p.x,
            y0: p.y,
            x1: q.x,
            y1: q.y,
        };
        [edge(a, c), edge(a, b), edge(b, c)]
    }
}

/// The compare-and-swaps that sort rows `y` (stable: strict compares).
#[inline(always)]
fn sort_swaps(y: [i32; 3]) -> [bool; 3] {
    let s0 = y[1] < y[0];
    let (y0, y1) = if s0 { (y[1], y[0]) } else { (y[0], y[1]) };
    let s1 = y[2] < y1;
    let y1 = if s1 { y[2] } else { y1 };
    [s0, s1, y1 < y0]
}

/// `t` reordered by the compare-and-swaps `swaps` (selects, no memory).
#[inline(always)]
fn sort_by<T: Copy>([s0, s1, s2]: [bool; 3], t: [T; 3]) -> [T; 3] {
    let (t0, t1) = if s0 { (t[1], t[0]) } else { (t[0], t[1]) };
    let (t1, t2) = if s1 { (t[2], t1) } else { (t1, t[2]) };
    let (t0, t1) = if s2 { (t1, t0) } else { (t0, t1) };
    [t0, t1, t2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On random triangles (many with equal rows): the rows sorted stably, the values sorted
    /// with them, the twice-area in both orders against its definition, the box.
    #[test]
    fn set_up_matches_its_definition() {
        let mut rng = crate::test_rng::XorShift(0x7E1A_5E70_0000_0019);
        let mut rnd = |m: i32| (rng.next_u64() % (2 * m as u64 + 1)) as i32 - m;
        let cross = |p: [SubpixelPoint<4>; 3]| {
            (p[1].x as i64 - p[0].x as i64) * (p[2].y as i64 - p[0].y as i64)
                - (p[1].y as i64 - p[0].y as i64) * (p[2].x as i64 - p[0].x as i64)
        };
        for i in 0..5000 {
            let m = if i % 2 == 0 {
                3
            } else {
                crate::raster::MAX_COORD
            };
            let v = [0; 3].map(|_| SubpixelPoint::<4>::new(rnd(m), rnd(m)));
            let t = TriangleSetup::new(v).unwrap();
            let idx = t.sort([0usize, 1, 2]);
            // A permutation, sorted by row, equal rows in the given order.
            for k in 0..2 {
                let (p, q) = (idx[k], idx[k + 1]);
                assert!(v[p].y < v[q].y || (v[p].y == v[q].y && p < q), "{v:?}");
            }
            assert_eq!(t.sorted, idx.map(|k| v[k]));
            assert_eq!(t.twice_area, cross(t.sorted), "{v:?}");
            assert_eq!(t.given_twice_area(), cross(v), "{v:?}");
            let xs = v.map(|p| p.x);
            let ys = v.map(|p| p.y);
            assert_eq!(t.x, [*xs.iter().min().unwrap(), *xs.iter().max().unwrap()]);
            assert_eq!(t.y, [*ys.iter().min().unwrap(), *ys.iter().max().unwrap()]);
        }
        let far = [0, 1, 2].map(|k| SubpixelPoint::<4>::new(k, crate::raster::MAX_COORD + k));
        assert_eq!(
            TriangleSetup::new(far).err(),
            Some(FillError::CoordinateOutOfRange { vertex: 1 })
        );
    }
}
