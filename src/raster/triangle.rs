//! The triangle fast path: the same coverage as [`polygon`](super::polygon), built for speed.
//!
//! Role in the pipeline: meshes are drawn triangle by triangle; this is the stage between
//! projection and the span writers (bare index fill, depth test, shading).
//!
//! Set-up once per triangle: sort the three vertices by row, find on which side of the long
//! edge (top → bottom) the middle vertex lies from the sign of one cross product, and start one
//! [`EdgeWalker`] on the long edge and one on each short edge, each at its first visible row.
//! Then each row is two walker steps and one span. Both walkers yield `⌈x_e⌉` (TIPE's left-edge
//! rounding), so a row covers `⌈x_left⌉ ≤ x < ⌈x_right⌉`: exactly the polygon fill's rule
//! (left edge in, right edge out, rows `y_low ≤ y < y_high`), tested against it.
//!
//! Numeric contract: as the polygon fill (`|x|, |y| ≤ MAX_COORD`, `S ≤ 16`); the cross product
//! is formed in `i64` (`< 2^60`). Triangles with zero area (collinear or repeated vertices)
//! cover nothing. Either orientation is filled; callers cull back faces before, if they want to.

use super::edge_walker::{Edge, EdgeSide, EdgeWalker, IncrementalWalker};
use super::range::{check_range, FillError};
use super::{Span, SubpixelPoint, Window};

/// The bounding box of `v` in sub-pixel units: `([x_lo, x_hi], [y_lo, y_hi])`.
#[inline(always)]
pub fn bounds<const S: u32>(v: &[SubpixelPoint<S>; 3]) -> ([i32; 2], [i32; 2]) {
    (
        [
            v[0].x.min(v[1].x).min(v[2].x),
            v[0].x.max(v[1].x).max(v[2].x),
        ],
        [
            v[0].y.min(v[1].y).min(v[2].y),
            v[0].y.max(v[1].y).max(v[2].y),
        ],
    )
}

/// Twice the signed area of triangle `a, b, c` in sub-pixel units squared, `(b − a) × (c − a)`.
/// With screen axes (`x` right, `y` down) it is negative when the vertices turn
/// counter-clockwise on screen, and, for `a` above `c`, when `b` lies left of the line `a → c`.
#[inline(always)]
pub fn cross<const S: u32>(a: SubpixelPoint<S>, b: SubpixelPoint<S>, c: SubpixelPoint<S>) -> i64 {
    (b.x as i64 - a.x as i64) * (c.y as i64 - a.y as i64)
        - (b.y as i64 - a.y as i64) * (c.x as i64 - a.x as i64)
}

/// [`cross`] for vertices in the raster range (`|x|, |y| ≤ MAX_COORD`): the differences fit
/// `i32` (`< 2^29`), so each product is one 32×32→64-bit multiply (`smull` on a Cortex-M3/M4)
/// instead of a product of 64-bit operands. Same value.
#[inline(always)]
fn cross_in_range<const S: u32>(
    a: SubpixelPoint<S>,
    b: SubpixelPoint<S>,
    c: SubpixelPoint<S>,
) -> i64 {
    let (dx1, dy1) = (b.x.wrapping_sub(a.x), b.y.wrapping_sub(a.y));
    let (dx2, dy2) = (c.x.wrapping_sub(a.x), c.y.wrapping_sub(a.y));
    dx1 as i64 * dy2 as i64 - dy1 as i64 * dx2 as i64
}

/// Fills a triangle with the default (incremental) walker, emitting its spans inside `window`
/// row by row from the top. Same coverage as [`fill_polygon`](super::polygon::fill_polygon).
#[inline]
pub fn fill_triangle<const S: u32>(
    v: [SubpixelPoint<S>; 3],
    window: &Window,
    emit: impl FnMut(Span),
) -> Result<(), FillError> {
    fill_triangle_with::<IncrementalWalker, S>(v, window, emit)
}

/// Fills a triangle with the edge stepping strategy `W`; vertices outside the range are
/// [`FillError::CoordinateOutOfRange`], before any arithmetic.
pub fn fill_triangle_with<W: EdgeWalker, const S: u32>(
    v: [SubpixelPoint<S>; 3],
    window: &Window,
    emit: impl FnMut(Span),
) -> Result<(), FillError> {
    check_range(&v)?;
    fill_in_range_with::<W, S>(v, window, emit);
    Ok(())
}

/// [`fill_triangle`] for vertices whose range the caller has checked once already (the span
/// writers check before their plane set-up, the renderer's projector per vertex): the same
/// spans, without a second check. Asserted in checked builds.
#[inline]
pub(crate) fn fill_triangle_in_range<const S: u32>(
    v: [SubpixelPoint<S>; 3],
    window: &Window,
    emit: impl FnMut(Span),
) {
    debug_assert!(check_range(&v).is_ok(), "vertices outside the fill's range");
    fill_in_range_with::<IncrementalWalker, S>(v, window, emit)
}

/// The fill itself, for vertices within the range.
///
/// The middle vertex `b` (by row) is left of the long edge `a → c` when
/// `cross(a, b, c) < 0` (screen axes: `x` right, `y` down).
fn fill_in_range_with<W: EdgeWalker, const S: u32>(
    v: [SubpixelPoint<S>; 3],
    window: &Window,
    mut emit: impl FnMut(Span),
) {
    // Sort by row (three compares).
    let [mut a, mut b, mut c] = v;
    if b.y < a.y {
        core::mem::swap(&mut a, &mut b);
    }
    if c.y < b.y {
        core::mem::swap(&mut b, &mut c);
        if b.y < a.y {
            core::mem::swap(&mut a, &mut b);
        }
    }
    let area = cross_in_range(a, b, c); // in range: checked by the callers
    if area == 0 {
        return;
    }
    let long = Edge {
        x0: a.x,
        y0: a.y,
        x1: c.x,
        y1: c.y,
    };
    let top = Edge {
        x0: a.x,
        y0: a.y,
        x1: b.x,
        y1: b.y,
    };
    let bottom = Edge {
        x0: b.x,
        y0: b.y,
        x1: c.x,
        y1: c.y,
    };
    let y_first = long.first_row::<S>().max(window.y0);
    let y_mid = top.end_row::<S>(); // == bottom.first_row()
    let y_end = long.end_row::<S>().min(window.y1);
    if y_first >= y_end || window.x0 >= window.x1 {
        return;
    }
    let long_w = W::start::<S>(&long, EdgeSide::Left, y_first);
    let middle_left = area < 0;
    // One row loop for both halves (the span code is inlined once): the short walker starts
    // on the top edge, or on the bottom edge when the first visible row is past the middle
    // vertex, and is replaced by the bottom edge's walker at row `y_mid`. The walkers are
    // placed once per triangle as the left and the right one, so a row selects nothing.
    let (short_w, mut rows_end) = if y_first < y_mid {
        (
            W::start::<S>(&top, EdgeSide::Left, y_first),
            y_mid.min(y_end),
        )
    } else {
        (W::start::<S>(&bottom, EdgeSide::Left, y_first), y_end)
    };
    let (mut left_w, mut right_w) = if middle_left {
        (short_w, long_w)
    } else {
        (long_w, short_w)
    };
    let mut y = y_first;
    loop {
        while y < rows_end {
            let x0 = left_w.x().max(window.x0);
            let x1 = right_w.x().min(window.x1);
            if x0 < x1 {
                emit(Span { y, x0, x1 });
            }
            left_w.step();
            right_w.step();
            y += 1;
        }
        if y >= y_end {
            return;
        }
        if middle_left {
            left_w = W::start::<S>(&bottom, EdgeSide::Left, y);
        } else {
            right_w = W::start::<S>(&bottom, EdgeSide::Left, y);
        }
        rows_end = y_end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::polygon::fill_polygon;
    use heapless::Vec;

    #[test]
    fn matches_polygon_fill_on_random_triangles() {
        let mut rng = crate::test_rng::XorShift(0x2545_F491_4F6C_DD1Du64);
        let mut rnd = |m: i32| (rng.next_u64() % (2 * m as u64 + 1)) as i32 - m;
        let w = Window::new(-3, -2, 20, 17);
        for i in 0..4000 {
            let m = if i % 2 == 0 { 200 } else { 20 };
            let v = [
                SubpixelPoint::<4>::new(rnd(m) + 130, rnd(m) + 120),
                SubpixelPoint::<4>::new(rnd(m) + 130, rnd(m) + 120),
                SubpixelPoint::<4>::new(rnd(m) + 130, rnd(m) + 120),
            ];
            let mut a: Vec<Span, 64> = Vec::new();
            let mut b: Vec<Span, 64> = Vec::new();
            fill_triangle(v, &w, |s| a.push(s).unwrap()).unwrap();
            fill_polygon::<4, 3>(&v, &w, |s| b.push(s).unwrap()).unwrap();
            assert_eq!(a, b, "{v:?}");
        }
    }
}
