//! The triangle fill: the same coverage as [`polygon`](crate::raster::polygon), built for
//! speed.
//!
//! Role in the pipeline: meshes are drawn triangle by triangle; this is the stage between
//! projection and the span writers (bare index fill, depth test, shading).
//!
//! Set-up once per triangle (`setup`'s `TriangleSetup`: the vertices sorted by row, and on
//! which side of the long edge (top → bottom) the middle vertex lies from the sign of the
//! twice-area), then one [`EdgeWalker`] started on the long edge and one on each short edge,
//! each at its first visible row.
//! Then each row is two walker steps and one span. Both walkers yield `⌈x_e⌉` (TIPE's left-edge
//! rounding), so a row covers `⌈x_left⌉ ≤ x < ⌈x_right⌉`: exactly the polygon fill's rule
//! (left edge in, right edge out, rows `y_low ≤ y < y_high`), tested against it.
//!
//! Numeric contract: as the polygon fill (`|x|, |y| ≤ MAX_COORD`, `S ≤ 16`); the twice-area
//! is the set-up's (`i64`, `< 2^59`). Triangles with zero area (collinear or repeated vertices)
//! cover nothing. Either orientation is filled; callers cull back faces before, if they want to.

use super::edge_walker::{EdgeSide, EdgeWalker, IncrementalWalker};
use super::setup::TriangleSetup;
use crate::raster::range::FillError;
use crate::raster::{Span, SubpixelPoint, Window};

/// Fills a triangle with the default (incremental) walker, emitting its spans inside `window`
/// row by row from the top. Same coverage as [`fill_polygon`](crate::raster::polygon::fill_polygon).
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
    fill_setup_with::<W, S>(&TriangleSetup::new(v)?, window, emit);
    Ok(())
}

/// [`fill_triangle`] of a triangle already set up (its range checked once, by the set-up's
/// caller): the writers' form.
#[inline]
pub(crate) fn fill_setup<const S: u32>(
    t: &TriangleSetup<S>,
    window: &Window,
    emit: impl FnMut(Span),
) {
    fill_setup_with::<IncrementalWalker, S>(t, window, emit)
}

/// The rows a triangle draws inside `window` and its walkers there: `y_first..y_end`, the
/// left and right walkers started at `y_first`, and the row `rows_end` where the short walker
/// changes from the top edge to the bottom one (`y_end` when it starts on the bottom edge).
/// `None` when no row or no column of the window is drawn.
struct Rows<W> {
    y_first: i32,
    rows_end: i32,
    y_end: i32,
    left: W,
    right: W,
}

/// Places the walkers of set-up `t` at its first row inside `window` (see [`Rows`]).
#[inline(always)]
fn start_rows<W: EdgeWalker, const S: u32>(
    t: &TriangleSetup<S>,
    window: &Window,
) -> Option<Rows<W>> {
    if t.twice_area == 0 {
        return None;
    }
    let [long, top, bottom] = t.edges();
    let y_first = long.first_row::<S>().max(window.y0);
    let y_mid = top.end_row::<S>(); // == bottom.first_row()
    let y_end = long.end_row::<S>().min(window.y1);
    if y_first >= y_end || window.x0 >= window.x1 {
        return None;
    }
    let long_w = W::start::<S>(&long, EdgeSide::Left, y_first);
    // The short walker starts on the top edge, or on the bottom edge when the first visible
    // row is past the middle vertex. The walkers are placed once per triangle as the left
    // and the right one, so a row selects nothing.
    let (short_w, rows_end) = if y_first < y_mid {
        (
            W::start::<S>(&top, EdgeSide::Left, y_first),
            y_mid.min(y_end),
        )
    } else {
        (W::start::<S>(&bottom, EdgeSide::Left, y_first), y_end)
    };
    let (left, right) = if t.middle_left() {
        (short_w, long_w)
    } else {
        (long_w, short_w)
    };
    Some(Rows {
        y_first,
        rows_end,
        y_end,
        left,
        right,
    })
}

/// The fill itself, for a set-up triangle: one row loop for both halves (the span code is
/// inlined once), the short walker replaced by the bottom edge's at row `rows_end`. Inlined
/// into each writer, so that its span code reaches the writer's values in registers (out of
/// line, the span writers' per-span state went through memory: Cortex-M4 `frame_cube_backface`
/// +7.6 %).
#[inline(always)]
fn fill_setup_with<W: EdgeWalker, const S: u32>(
    t: &TriangleSetup<S>,
    window: &Window,
    mut emit: impl FnMut(Span),
) {
    let Some(Rows {
        y_first,
        mut rows_end,
        y_end,
        left: mut left_w,
        right: mut right_w,
    }) = start_rows::<W, S>(t, window)
    else {
        return;
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
        // `y == rows_end` here (the rows run one by one from `y_first < rows_end`): the
        // bottom walker starts at `rows_end`, a value fixed for the rows above, so the row
        // loop carries nothing for it (started at `y`, LLVM stepped its numerator along
        // every row: 4 instructions a row on the Cortex-M4).
        let bottom = t.edges()[2];
        if t.middle_left() {
            left_w = W::start::<S>(&bottom, EdgeSide::Left, rows_end);
        } else {
            right_w = W::start::<S>(&bottom, EdgeSide::Left, rows_end);
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
