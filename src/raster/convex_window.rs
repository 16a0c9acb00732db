//! Windowing against a convex polygon: the course's exercise 9 (ch. 2), made exact.
//!
//! Role in the pipeline: a 2D scissor for the raster stage's polygon fill and lines, beside
//! the rectangle [`Window`]. A [`ConvexWindow`] is any convex polygon (a rotated rectangle, a
//! hexagonal gauge face, a round display's inscribed polygon); [`ConvexWindow::fill_polygon`]
//! and [`ConvexWindow::line`] draw only what lies inside it.
//!
//! ## What "inside" means, exactly
//! A pixel is inside the window when the window polygon, filled by the fill's own rule
//! ([`polygon`](super::polygon): left edges in, right edges out, each edge's rows half-open),
//! covers it. A clipped polygon then covers **exactly the pixels that the unclipped polygon
//! covers and the window covers**, and a clipped line draws exactly the pixels of the unclipped
//! Bresenham line that the window covers, in the same order — as the rectangle scissor does.
//! Two windows that share an edge (a tiling of the screen) therefore split every drawing
//! between them with no pixel drawn twice and none lost.
//!
//! The course's Sutherland–Hodgman procedure cuts the polygon by each window edge in turn and
//! computes the new vertices where the edges cross. Those crossings are rational points, which
//! sub-pixel coordinates cannot hold, so a clipped polygon's rounded vertices would move its
//! edges and its pixels. This module keeps the course's idea (a convex window is the
//! intersection of the half-planes of its edges, and on each row that intersection is one run)
//! and applies it where it is exact: on each row, the window's run `[xg, xd + 1)` is computed
//! from its two edges (one Euclidean division each, TIPE's `xG` and `xD`), and the polygon's
//! spans, or the line's pixels, are cut to it.
//!
//! ## Numeric contract
//! Window vertices are [`SubpixelPoint<S>`] within the fill's range (`|x|, |y| ≤`
//! [`MAX_COORD`](super::MAX_COORD), `S ≤` [`MAX_SUBPIXEL_BITS`](super::MAX_SUBPIXEL_BITS)); the
//! convexity test multiplies two differences of such coordinates (`< 2^29` each) in `i64`.
//! Polygons and lines keep their own ranges ([`FillError`], [`LineError`]).
//!
//! ## Conventions
//! The window may be given in either orientation; collinear vertices and repeated vertices are
//! allowed. A polygon that turns both ways, doubles back on itself, winds around more than once
//! (a pentagram turns one way only), or has no area is refused with [`ConvexWindowError`].
//! Cost: `O(window edges)` per row of the drawing (a window has a handful of edges).

use super::line::{Bresenham, Ends, LineError};
use super::polygon::{fill_polygon_with_rule, FillRule, PolygonEdges};
use super::range::{check_range, FillError};
use super::triangle::edge_walker::EdgeSide;
use super::{Span, SubpixelPoint, Window};
use embedded_graphics_core::geometry::Point;

/// Why a convex window could not be made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConvexWindowError {
    /// A vertex out of the fill's range, or more edges than the window's capacity.
    Fill(FillError),
    /// The polygon is not convex at this vertex (it turns the other way, or doubles back), or
    /// winds around more than once.
    NotConvex {
        /// Index of the vertex where the polygon stops being convex.
        vertex: usize,
    },
    /// Fewer than three vertices that are not collinear: the window covers no pixel.
    NoArea,
}

impl core::fmt::Display for ConvexWindowError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ConvexWindowError::Fill(e) => write!(f, "convex window: {e}"),
            ConvexWindowError::NotConvex { vertex } => write!(
                f,
                "the window polygon is not convex at vertex {vertex} (it turns the other way, \
                 doubles back or winds around more than once)"
            ),
            ConvexWindowError::NoArea => {
                write!(
                    f,
                    "the window polygon has no area (fewer than 3 non-collinear vertices)"
                )
            }
        }
    }
}

impl core::error::Error for ConvexWindowError {}

impl From<FillError> for ConvexWindowError {
    fn from(e: FillError) -> Self {
        ConvexWindowError::Fill(e)
    }
}

/// A convex polygon used as a drawing window (see the module doc). `MAX_EDGES` bounds its
/// number of non-horizontal edges.
#[derive(Debug, Clone)]
pub struct ConvexWindow<const S: u32, const MAX_EDGES: usize> {
    edges: PolygonEdges<MAX_EDGES>,
    /// The pixels of the window's bounding box: no covered pixel lies outside it.
    bounds: Window,
}

impl<const S: u32, const MAX_EDGES: usize> ConvexWindow<S, MAX_EDGES> {
    /// The window bounded by `vertices` (either orientation). Errors name the vertex that
    /// breaks convexity or the range.
    pub fn new(vertices: &[SubpixelPoint<S>]) -> Result<Self, ConvexWindowError> {
        check_range(vertices)?;
        check_convex(vertices)?;
        let edges = PolygonEdges::<MAX_EDGES>::build(vertices)?;
        let (y0, y1) = edges.rows::<S>();
        // Columns: from the floor of the smallest x to one past the floor of the largest.
        let x_lo = vertices.iter().map(|p| p.x).min().unwrap_or(0) >> S;
        let x_hi = vertices.iter().map(|p| p.x).max().unwrap_or(0) >> S;
        Ok(ConvexWindow {
            edges,
            bounds: Window::new(x_lo, y0, x_hi + 1, y1),
        })
    }

    /// The rectangle of pixels that holds every pixel of the window.
    pub fn bounds(&self) -> Window {
        self.bounds
    }

    /// The window's run of row `y`: the pixels `x0 ≤ x < x1` it covers (empty, `x0 == x1`,
    /// when the row misses it).
    pub fn row(&self, y: i32) -> Span {
        // A convex polygon crosses a row it covers exactly twice; both crossings are event
        // positions ⌈x_e⌉ of the fill (xG for a left edge, xD + 1 for a right one), so the
        // run is the half-open interval between them, whatever the orientation.
        let mut lo = i32::MAX;
        let mut hi = i32::MIN;
        let left = self.edges.left_edges().iter().map(|e| (e, 0));
        let right = self.edges.right_edges().iter().map(|e| (e, 1));
        for (e, plus) in left.chain(right) {
            if e.first_row::<S>() <= y && y < e.end_row::<S>() {
                let side = if plus == 0 {
                    EdgeSide::Left
                } else {
                    EdgeSide::Right
                };
                let key = e.end_at::<S>(y, side) + plus;
                lo = lo.min(key);
                hi = hi.max(key);
            }
        }
        if lo >= hi {
            Span { y, x0: 0, x1: 0 }
        } else {
            Span { y, x0: lo, x1: hi }
        }
    }

    /// Fills `vertices` (any polygon, under `rule`) inside the window: emits, row by row from
    /// the top and left to right, exactly the pixels that both the polygon and the window
    /// cover. Errors are the fill's, returned before any span.
    pub fn fill_polygon<const POLYGON_EDGES: usize>(
        &self,
        vertices: &[SubpixelPoint<S>],
        rule: FillRule,
        mut emit: impl FnMut(Span),
    ) -> Result<(), FillError> {
        let mut run = Span {
            y: i32::MIN,
            x0: 0,
            x1: 0,
        };
        fill_polygon_with_rule::<S, POLYGON_EDGES>(vertices, &self.bounds, rule, |s| {
            if run.y != s.y {
                run = self.row(s.y);
            }
            let (x0, x1) = (s.x0.max(run.x0), s.x1.min(run.x1));
            if x0 < x1 {
                emit(Span { y: s.y, x0, x1 });
            }
        })
    }

    /// The pixels of the Bresenham line from `p0` to `p1` (whole pixels, `ends` as in
    /// [`Bresenham::with_ends`]) that the window covers, in the line's order. Errors when an
    /// end point is out of the line's range.
    pub fn line(
        &self,
        p0: Point,
        p1: Point,
        ends: Ends,
    ) -> Result<impl Iterator<Item = Point> + '_, LineError> {
        let pixels = Bresenham::clipped(p0, p1, ends, &self.bounds)?;
        let mut run = Span {
            y: i32::MIN,
            x0: 0,
            x1: 0,
        };
        Ok(pixels.filter(move |p| {
            if run.y != p.y {
                run = self.row(p.y);
            }
            run.x0 <= p.x && p.x < run.x1
        }))
    }
}

/// Checks that `v` bounds a convex region with area: every turn has the same sign (zero turns
/// allowed where the polygon goes straight on), no edge doubles back, and the boundary goes
/// down and up once only (so it winds around once: a pentagram turns one way throughout but
/// changes vertical direction four times).
fn check_convex<const S: u32>(v: &[SubpixelPoint<S>]) -> Result<(), ConvexWindowError> {
    let n = v.len();
    let step = |i: usize| -> (i64, i64) {
        let (a, b) = (v[i], v[(i + 1) % n]);
        (b.x as i64 - a.x as i64, b.y as i64 - a.y as i64)
    };
    // Each edge is compared with the previous non-zero edge, cyclically: start from the last.
    let Some(mut previous) = (0..n).rev().map(step).find(|&e| e != (0, 0)) else {
        return Err(ConvexWindowError::NoArea);
    };
    let Some(mut last_dy) = (0..n).rev().map(|i| step(i).1.signum()).find(|&s| s != 0) else {
        return Err(ConvexWindowError::NoArea);
    };
    // All vertices on one line (or one point): no area, whatever the order.
    let rel = |i: usize| (v[i].x as i64 - v[0].x as i64, v[i].y as i64 - v[0].y as i64);
    let direction = (1..n).map(rel).find(|&d| d != (0, 0)).unwrap_or((0, 0));
    if (1..n).all(|i| rel(i).0 * direction.1 == rel(i).1 * direction.0) {
        return Err(ConvexWindowError::NoArea);
    }
    let mut turn_sign = 0i64;
    let mut vertical_changes = 0;
    for i in 0..n {
        let e = step(i);
        if e == (0, 0) {
            continue;
        }
        // |coordinate differences| < 2^29: each product < 2^58, their sum < 2^59.
        let cross = previous.0 * e.1 - previous.1 * e.0;
        let dot = previous.0 * e.0 + previous.1 * e.1;
        if cross == 0 && dot < 0 {
            return Err(ConvexWindowError::NotConvex { vertex: i });
        }
        if cross != 0 {
            if turn_sign != 0 && cross.signum() != turn_sign {
                return Err(ConvexWindowError::NotConvex { vertex: i });
            }
            turn_sign = cross.signum();
        }
        if e.1 != 0 {
            if e.1.signum() != last_dy {
                vertical_changes += 1;
                if vertical_changes > 2 {
                    return Err(ConvexWindowError::NotConvex { vertex: i });
                }
            }
            last_dy = e.1.signum();
        }
        previous = e;
    }
    if turn_sign == 0 {
        return Err(ConvexWindowError::NoArea);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    type P = SubpixelPoint<0>;

    #[test]
    fn convexity_is_checked() {
        let square = [P::new(0, 0), P::new(8, 0), P::new(8, 8), P::new(0, 8)];
        assert!(ConvexWindow::<0, 8>::new(&square).is_ok());
        let mut reversed = square;
        reversed.reverse();
        assert!(ConvexWindow::<0, 8>::new(&reversed).is_ok());
        // Collinear and repeated vertices are fine.
        let with_extra = [
            P::new(0, 0),
            P::new(4, 0),
            P::new(8, 0),
            P::new(8, 8),
            P::new(8, 8),
            P::new(0, 8),
        ];
        assert!(ConvexWindow::<0, 8>::new(&with_extra).is_ok());
        let dent = [
            P::new(0, 0),
            P::new(8, 0),
            P::new(4, 3),
            P::new(8, 8),
            P::new(0, 8),
        ];
        assert!(matches!(
            ConvexWindow::<0, 8>::new(&dent),
            Err(ConvexWindowError::NotConvex { .. })
        ));
        let star = [
            P::new(10, 0),
            P::new(16, 19),
            P::new(0, 7),
            P::new(20, 7),
            P::new(4, 19),
        ];
        assert!(matches!(
            ConvexWindow::<0, 8>::new(&star),
            Err(ConvexWindowError::NotConvex { .. })
        ));
        let back = [P::new(0, 0), P::new(8, 0), P::new(4, 0), P::new(4, 6)];
        assert!(matches!(
            ConvexWindow::<0, 8>::new(&back),
            Err(ConvexWindowError::NotConvex { .. })
        ));
        let flat = [P::new(0, 0), P::new(4, 4), P::new(8, 8)];
        assert_eq!(
            ConvexWindow::<0, 8>::new(&flat).unwrap_err(),
            ConvexWindowError::NoArea
        );
        assert_eq!(
            ConvexWindow::<0, 8>::new(&[]).unwrap_err(),
            ConvexWindowError::NoArea
        );
        let far = [P::new(0, 0), P::new(i32::MAX, 0), P::new(0, 5)];
        assert!(matches!(
            ConvexWindow::<0, 8>::new(&far),
            Err(ConvexWindowError::Fill(_))
        ));
    }
}
