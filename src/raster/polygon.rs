//! The exact scanline fill of arbitrary polygons: TIPE 2010's `Remplissage`.
//!
//! Role in the pipeline: the raster stage's general polygon fill (any vertex count, convex or
//! not). Triangles from meshes take the faster [`triangle`](super::triangle) path, which covers
//! exactly the same pixels.
//!
//! ## The fill rule (the contract every later stage relies on)
//! A pixel is the lattice point `(x, y)`. It is covered when it lies inside the polygon; a point
//! exactly on a **left** edge is in, exactly on a **right** edge is out. Each non-horizontal edge
//! covers the rows `y_low ≤ y < y_high` (its top row in, its bottom row out); horizontal edges
//! contribute nothing. With `y` growing downward this is the *top-left rule*:
//!
//! ```text
//!        x=0 1 2 3 4 5 6            triangle (1,0) (5,0) (1,4):
//!   y=0    . # # # # . .            top edge horizontal: row 0 is in (its
//!   y=1    . # # # . . .            edges' first row), column 5 is on the
//!   y=2    . # # . . . .            right edge → out; the left edge x = 1
//!   y=3    . # . . . . .            is in on every row; row 4 (the bottom
//!   y=4    . . . . . . .            vertex's row) is out.
//! ```
//!
//! Two polygons sharing an edge therefore never both cover a pixel, and together leave no gap:
//! meshes are watertight (tested on random tilings).
//!
//! Polygons may be given in either orientation. Self-intersecting polygons are filled by one
//! of two rules, the caller's [`FillRule`]:
//! - **nonzero winding** (the default, [`fill_polygon`]): a pixel is covered when the edges'
//!   winding number around it is not zero; a figure-eight fills both lobes, a pentagram its
//!   centre too;
//! - **even-odd** (the course's algorithm 2.4, ch. 2: a row's intersections sorted, the spans
//!   run from each even-numbered intersection to the next odd one, a vertex where the
//!   boundary passes through counted twice): a pixel is covered when an odd number of edges
//!   lie at or left of it on its row; a pentagram's centre is a hole, two overlapping
//!   squares of one polygon leave their overlap empty.
//!
//! For a simple polygon (no self-intersection) both rules cover the same pixels. Under both,
//! the guarantees above hold unchanged: a point exactly on the edge where a covered run
//! begins is in, on the edge where it ends is out, and two polygons sharing an edge neither
//! overlap nor leave a gap (watertight). The half-open rows of each edge (`y_low ≤ y <
//! y_high`) are what makes the course's "vertex counted twice" exact: at a vertex where the
//! boundary goes on downward (or upward) one edge ends and the next begins on the same row,
//! so the row counts one crossing there; at a vertex where it turns back (a local top or
//! bottom) both edges count or neither does, so the row counts two or none, and the parity
//! is right either way.
//!
//! ## The procedure (TIPE §4.3, with readable names)
//! 1. [`PolygonEdges::build`] is `Construire_TAG_et_TAD`: walking the vertices in order, an
//!    edge along which `y` increases goes to [`left_edges`](PolygonEdges::left_edges) (`TAG`),
//!    one along which it decreases to [`right_edges`](PolygonEdges::right_edges) (`TAD`), stored
//!    low end first; horizontal edges are dropped. Capacity is the const generic `MAX_EDGES`;
//!    a polygon with more non-horizontal edges is an error (before any pixel is written).
//! 2. Each edge is walked with `edge_walker` (`Parcours`), giving per row
//!    the ends `xG` (left edges: first pixel in) and `xD` (right edges: last pixel in).
//! 3. Each row's ends are sorted and turned into maximal spans (`Remplissage`, step 6). TIPE
//!    pairs the k-th `xG` with the k-th `xD`; this implementation sweeps the sorted ends with a
//!    winding counter (`+1` at `xG`, `−1` at `xD + 1`), which gives TIPE's pairs for simple
//!    polygons in TIPE's orientation and stays right for the other orientation and for
//!    self-intersections (`xG` and `xD + 1` are the same rounding, `⌈x_e⌉`). Adjacent spans merge.
//!    The even-odd rule reads the same counter's parity: every event changes the count by
//!    one, so the number of edges at or left of a pixel is odd exactly when the counter is.
//!
//! Unlike the text, rows are produced one at a time (an active edge list) instead of filling
//! `XG[NbLig][NbCol]` tables for the whole screen: memory is `O(MAX_EDGES)`, not `O(rows)`.
//!
//! ## Window
//! Only rows and columns inside the [`Window`] are produced; walkers start directly at the
//! window's first row (one division), so the pixels inside the window are exactly those of the
//! unclipped polygon, and polygons far outside cost only their set-up.
//!
//! ## Numeric contract
//! Vertices are [`SubpixelPoint<S>`] with `|x|, |y| ≤ `[`MAX_COORD`](super::MAX_COORD)` = 2^28 − 1` and
//! `S ≤ `[`MAX_SUBPIXEL_BITS`](super::MAX_SUBPIXEL_BITS); other input is rejected with [`FillError::CoordinateOutOfRange`].
//! See `edge_walker` for why nothing overflows in that range.

use super::range::check_range;
pub use super::range::FillError;
use super::triangle::edge_walker::{Edge, EdgeSide, EdgeWalker, IncrementalWalker};
use super::{Span, SubpixelPoint, Window};
use heapless::Vec;

/// Which pixels of a self-intersecting polygon are inside (see the module doc). Both rules
/// cover the same pixels for a simple polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FillRule {
    /// Covered where the winding number of the boundary around the pixel is not zero (TIPE's
    /// pairing of `xG` and `xD`, extended to any orientation and to self-intersections).
    #[default]
    NonZero,
    /// Covered where an odd number of edges lie at or left of the pixel on its row (the
    /// course's algorithm 2.4: spans from even to odd intersections).
    EvenOdd,
}

impl FillRule {
    /// Whether a pixel with `winding` (the signed count of edges at or left of it) is inside.
    #[inline(always)]
    fn inside(self, winding: i32) -> bool {
        match self {
            FillRule::NonZero => winding != 0,
            FillRule::EvenOdd => winding & 1 != 0,
        }
    }
}

/// TIPE's `TAG` and `TAD`: the left and right edges of a polygon, low end first.
#[derive(Debug, Clone)]
pub struct PolygonEdges<const MAX_EDGES: usize> {
    left: Vec<Edge, MAX_EDGES>,
    right: Vec<Edge, MAX_EDGES>,
}

impl<const MAX_EDGES: usize> PolygonEdges<MAX_EDGES> {
    /// `Construire_TAG_et_TAD`: splits the polygon's non-horizontal edges into left and right
    /// edges (see the module doc). Fewer than 3 vertices give no edges that cover anything.
    pub fn build<const S: u32>(vertices: &[SubpixelPoint<S>]) -> Result<Self, FillError> {
        check_range(vertices)?;
        let mut edges = PolygonEdges {
            left: Vec::new(),
            right: Vec::new(),
        };
        let too_many = FillError::TooManyEdges {
            capacity: MAX_EDGES,
        };
        let n = vertices.len();
        if n < 3 {
            return Ok(edges);
        }
        for i in 0..n {
            let (a, b) = (vertices[i], vertices[(i + 1) % n]);
            if b.y > a.y {
                let e = Edge {
                    x0: a.x,
                    y0: a.y,
                    x1: b.x,
                    y1: b.y,
                };
                edges.left.push(e).map_err(|_| too_many)?;
            } else if b.y < a.y {
                let e = Edge {
                    x0: b.x,
                    y0: b.y,
                    x1: a.x,
                    y1: a.y,
                };
                edges.right.push(e).map_err(|_| too_many)?;
            }
        }
        if edges.left.len() + edges.right.len() > MAX_EDGES {
            return Err(too_many);
        }
        Ok(edges)
    }

    /// `TAG`: the edges along which `y` increases in vertex order, low end first.
    pub fn left_edges(&self) -> &[Edge] {
        &self.left
    }

    /// `TAD`: the edges along which `y` decreases in vertex order, low end first.
    pub fn right_edges(&self) -> &[Edge] {
        &self.right
    }

    /// TIPE's table rows `xG[y]` and `xD[y]` for row `y`, each sorted increasingly, computed
    /// by direct evaluation (for inspection and tests; the fill itself walks incrementally).
    pub fn row_ends<const S: u32>(&self, y: i32) -> (Vec<i32, MAX_EDGES>, Vec<i32, MAX_EDGES>) {
        let ends = |edges: &[Edge], side| {
            let mut v: Vec<i32, MAX_EDGES> = edges
                .iter()
                .filter(|e| e.first_row::<S>() <= y && y < e.end_row::<S>())
                .map(|e| e.end_at::<S>(y, side))
                .collect();
            v.sort_unstable();
            v
        };
        (
            ends(&self.left, EdgeSide::Left),
            ends(&self.right, EdgeSide::Right),
        )
    }

    /// The rows any edge covers: `first..end` (empty when there are no edges).
    pub fn rows<const S: u32>(&self) -> (i32, i32) {
        let all = self.left.iter().chain(self.right.iter());
        let first = all.clone().map(|e| e.first_row::<S>()).min().unwrap_or(0);
        let end = all.map(|e| e.end_row::<S>()).max().unwrap_or(0);
        (first, end)
    }

    /// Emits the covered spans inside `window` under the nonzero winding rule, row by row
    /// from the top, each row left to right, each span maximal. `W` chooses the edge stepping
    /// strategy.
    pub fn fill_with<W: EdgeWalker, const S: u32>(&self, window: &Window, emit: impl FnMut(Span)) {
        self.fill_with_rule::<W, S>(window, FillRule::NonZero, emit);
    }

    /// [`Self::fill_with`] under the given [`FillRule`].
    pub fn fill_with_rule<W: EdgeWalker, const S: u32>(
        &self,
        window: &Window,
        rule: FillRule,
        mut emit: impl FnMut(Span),
    ) {
        let Some(mut pending) = self.pending::<S>(window) else {
            return;
        };
        let first_row = pending
            .last()
            .map_or(window.y0, |(e, _)| e.first_row::<S>().max(window.y0));
        // The active edges stay sorted by their event position from row to row: a row only
        // reorders edges that cross, so the insertion sort below costs O(n + crossings), and
        // it hands over to an O(n log n) sort when a row holds many inversions (many new or
        // crossing edges), so no row costs more than O(n log n) (n = active edges).
        let mut active: Vec<Active<W>, MAX_EDGES> = Vec::new();
        let mut ends: Vec<(i32, i8), MAX_EDGES> = Vec::new();
        let mut y = first_row;
        while y < window.y1 && !(active.is_empty() && pending.is_empty()) {
            // Activate the edges that start on this row (or above the window).
            while let Some((e, side)) = pending.last().copied() {
                if e.first_row::<S>().max(window.y0) != y {
                    break;
                }
                pending.pop();
                let _ = active.push(Active {
                    walker: W::start::<S>(&e, side, y),
                    end_row: e.end_row::<S>(),
                    side,
                });
            }
            // This row's ends as winding events, sorted: +1 at xG, −1 at xD + 1.
            sort_nearly_sorted(&mut active, Active::key);
            ends.clear();
            for a in active.iter() {
                let _ = ends.push((a.key(), a.winding()));
            }
            emit_row(y, &ends, window, rule, &mut emit);
            // Step, retiring edges whose last row this was (keeping the others' order).
            active.retain_mut(|a| {
                if a.end_row <= y + 1 {
                    false
                } else {
                    a.walker.step();
                    true
                }
            });
            y += 1;
            if active.is_empty() {
                // Skip empty rows up to the next edge (a polygon with a gap between parts).
                if let Some((e, _)) = pending.last() {
                    y = y.max(e.first_row::<S>().max(window.y0));
                }
            }
        }
    }

    /// The edges that cover a row of `window`, both sides in one table with their winding
    /// direction, sorted by first row, the first last; `None` when there are none (or the
    /// window is empty).
    fn pending<const S: u32>(&self, window: &Window) -> Option<Vec<(Edge, EdgeSide), MAX_EDGES>> {
        if window.is_empty() {
            return None;
        }
        let mut pending: Vec<(Edge, EdgeSide), MAX_EDGES> = Vec::new();
        for (edges, side) in [(&self.left, EdgeSide::Left), (&self.right, EdgeSide::Right)] {
            for e in edges.iter() {
                let first = e.first_row::<S>().max(window.y0);
                let end = e.end_row::<S>().min(window.y1);
                if first < end {
                    // Capacity holds: `build` checked left + right ≤ MAX_EDGES.
                    let _ = pending.push((*e, side));
                }
            }
        }
        if pending.is_empty() {
            return None;
        }
        pending.sort_unstable_by_key(|(e, _)| core::cmp::Reverse(e.first_row::<S>()));
        Some(pending)
    }
}

/// An edge of the fill's active table: its walker, the row past its last, its side.
struct Active<W> {
    walker: W,
    end_row: i32,
    side: EdgeSide,
}

impl<W: EdgeWalker> Active<W> {
    /// The row's winding event position: `xG` for a left edge, `xD + 1` for a right one.
    #[inline(always)]
    fn key(&self) -> i32 {
        match self.side {
            EdgeSide::Left => self.walker.x(),
            EdgeSide::Right => self.walker.x() + 1,
        }
    }

    /// The winding change at [`Self::key`]: +1 for a left edge, −1 for a right one.
    #[inline(always)]
    fn winding(&self) -> i8 {
        match self.side {
            EdgeSide::Left => 1,
            EdgeSide::Right => -1,
        }
    }
}

/// Sorts `v` by `key`, fast when it is nearly sorted (the active edges of the previous row):
/// insertion sort, O(n + inversions), fastest for the handful of edges a row usually holds;
/// after `4n + 16` moves it hands over to `sort_unstable_by_key` (O(n log n)), so a row never
/// costs more than O(n log n). Equal keys may end in any order (the row's events at one
/// position are applied together).
fn sort_nearly_sorted<T>(v: &mut [T], key: impl Fn(&T) -> i32) {
    let mut budget = 4 * v.len() + 16;
    for i in 1..v.len() {
        let mut j = i;
        while j > 0 && key(&v[j - 1]) > key(&v[j]) {
            if budget == 0 {
                v.sort_unstable_by_key(|t| key(t));
                return;
            }
            budget -= 1;
            v.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// Sweeps sorted winding events and emits the maximal spans that `rule` puts inside, clipped
/// to the window's columns.
fn emit_row(
    y: i32,
    ends: &[(i32, i8)],
    window: &Window,
    rule: FillRule,
    emit: &mut impl FnMut(Span),
) {
    let mut winding = 0i32;
    let mut start = 0i32;
    let mut i = 0;
    while i < ends.len() {
        let x = ends[i].0;
        let was_in = rule.inside(winding);
        // Apply every event at this position before deciding (equal ends cancel or merge).
        while i < ends.len() && ends[i].0 == x {
            winding += ends[i].1 as i32;
            i += 1;
        }
        let is_in = rule.inside(winding);
        if !was_in && is_in {
            start = x;
        } else if was_in && !is_in {
            let (x0, x1) = (start.max(window.x0), x.min(window.x1));
            if x0 < x1 {
                emit(Span { y, x0, x1 });
            }
        }
    }
}

/// Fills a polygon with the default (incremental) edge walker: emits its covered spans inside
/// `window` in row order. `MAX_EDGES` bounds the number of non-horizontal edges.
///
/// Degenerate polygons (fewer than 3 vertices, zero area, all vertices collinear) cover no
/// pixel and are not an error. Errors ([`FillError`]) are returned before any span is emitted.
pub fn fill_polygon<const S: u32, const MAX_EDGES: usize>(
    vertices: &[SubpixelPoint<S>],
    window: &Window,
    emit: impl FnMut(Span),
) -> Result<(), FillError> {
    fill_polygon_with_rule::<S, MAX_EDGES>(vertices, window, FillRule::NonZero, emit)
}

/// [`fill_polygon`] under the given [`FillRule`] (the even-odd rule for polygons whose
/// self-intersections should leave holes). Same errors, same guarantees.
pub fn fill_polygon_with_rule<const S: u32, const MAX_EDGES: usize>(
    vertices: &[SubpixelPoint<S>],
    window: &Window,
    rule: FillRule,
    emit: impl FnMut(Span),
) -> Result<(), FillError> {
    PolygonEdges::<MAX_EDGES>::build(vertices)?
        .fill_with_rule::<IncrementalWalker, S>(window, rule, emit);
    Ok(())
}

/// The rows `⌈y_min⌉ .. ⌈y_max⌉` a polygon's edges can cover (helper for callers sizing bands);
/// exact for any `i32` coordinates, not only the fill's range (`ceil_shift`).
#[cfg(test)]
pub(crate) fn row_range<const S: u32>(vertices: &[SubpixelPoint<S>]) -> (i32, i32) {
    let lo = vertices.iter().map(|p| p.y).min().unwrap_or(0);
    let hi = vertices.iter().map(|p| p.y).max().unwrap_or(0);
    use super::triangle::edge_walker::ceil_shift;
    (ceil_shift(lo, S), ceil_shift(hi, S))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::triangle::edge_walker::{DivisionWalker, MAX_COORD};

    type P = SubpixelPoint<0>;

    fn grid(vertices: &[P], w: i32, h: i32) -> [[u8; 8]; 6] {
        let mut g = [[b'.'; 8]; 6];
        fill_polygon::<0, 16>(vertices, &Window::new(0, 0, w, h), |s| {
            for x in s.x0..s.x1 {
                let c = &mut g[s.y as usize][x as usize];
                *c = if *c == b'.' { b'#' } else { b'2' }; // '2' marks a double write
            }
        })
        .unwrap();
        g
    }

    #[test]
    fn top_left_rule_on_the_doc_triangle() {
        let tri = [P::new(1, 0), P::new(5, 0), P::new(1, 4)];
        let g = grid(&tri, 8, 6);
        let expect = [
            *b".####...",
            *b".###....",
            *b".##.....",
            *b".#......",
            *b"........",
            *b"........",
        ];
        assert_eq!(g, expect);
        // Same pixels in the other orientation.
        let rev = [tri[2], tri[1], tri[0]];
        assert_eq!(grid(&rev, 8, 6), expect);
    }

    #[test]
    fn degenerate_polygons_cover_nothing() {
        let mut n = 0;
        let w = Window::new(-10, -10, 10, 10);
        for poly in [
            &[P::new(0, 0), P::new(3, 3)][..],
            &[P::new(0, 0), P::new(3, 3), P::new(6, 6)][..],
            &[P::new(0, 0), P::new(3, 3), P::new(1, 1), P::new(0, 0)][..],
            &[P::new(2, 2), P::new(2, 2), P::new(2, 2)][..],
            &[][..],
        ] {
            fill_polygon::<0, 8>(poly, &w, |_| n += 1).unwrap();
        }
        assert_eq!(n, 0);
    }

    #[test]
    fn errors_are_reported_before_drawing() {
        let mut n = 0;
        let w = Window::new(0, 0, 10, 10);
        let many = [
            P::new(0, 0),
            P::new(5, 1),
            P::new(0, 2),
            P::new(5, 3),
            P::new(0, 4),
        ];
        assert_eq!(
            fill_polygon::<0, 3>(&many, &w, |_| n += 1),
            Err(FillError::TooManyEdges { capacity: 3 })
        );
        let far = [P::new(0, 0), P::new(MAX_COORD + 1, 0), P::new(0, 5)];
        assert_eq!(
            fill_polygon::<0, 8>(&far, &w, |_| n += 1),
            Err(FillError::CoordinateOutOfRange { vertex: 1 })
        );
        let far = [P::new(0, 0), P::new(i32::MIN, 0), P::new(0, 5)];
        assert!(fill_polygon::<0, 8>(&far, &w, |_| n += 1).is_err());
        assert_eq!(n, 0);
    }

    #[test]
    fn both_walkers_fill_the_same() {
        let star = [
            SubpixelPoint::<4>::new(100, 0),
            SubpixelPoint::<4>::new(130, 170),
            SubpixelPoint::<4>::new(-10, 60),
            SubpixelPoint::<4>::new(210, 60),
            SubpixelPoint::<4>::new(70, 170),
        ];
        let e = PolygonEdges::<8>::build(&star).unwrap();
        let w = Window::new(-2, -2, 30, 30);
        let mut a: Vec<Span, 64> = Vec::new();
        let mut b: Vec<Span, 64> = Vec::new();
        e.fill_with::<DivisionWalker, 4>(&w, |s| a.push(s).unwrap());
        e.fill_with::<IncrementalWalker, 4>(&w, |s| b.push(s).unwrap());
        assert!(!a.is_empty());
        assert_eq!(a, b);
    }

    /// Parity of the edges at or left of pixel `(x, y)` (S = 0), by direct exact evaluation:
    /// an edge counts on rows `y_low ≤ y < y_high` when its crossing `x_e ≤ x`.
    fn odd_crossings(poly: &[P], x: i32, y: i32) -> bool {
        let mut n = 0;
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (lo, hi) = if a.y < b.y { (a, b) } else { (b, a) };
            if lo.y == hi.y || y < lo.y || y >= hi.y {
                continue;
            }
            // x_e = lo.x + (hi.x − lo.x)(y − lo.y)/(hi.y − lo.y) ≤ x, multiplied out (hi.y > lo.y).
            let lhs =
                (lo.x - x) as i64 * (hi.y - lo.y) as i64 + (hi.x - lo.x) as i64 * (y - lo.y) as i64;
            if lhs <= 0 {
                n += 1;
            }
        }
        n % 2 == 1
    }

    /// `n ≤ 8` random vertices in `[−1, 23]²`.
    fn random_polygon(rng: &mut crate::test_rng::XorShift, n: usize) -> Vec<P, 8> {
        let mut coordinate = || (rng.next_u64() % 25) as i32 - 1;
        (0..n).map(|_| P::new(coordinate(), coordinate())).collect()
    }

    fn covered_set(poly: &[P], rule: FillRule, w: &Window) -> Vec<(i32, i32), 1024> {
        let mut v: Vec<(i32, i32), 1024> = Vec::new();
        fill_polygon_with_rule::<0, 16>(poly, w, rule, |s| {
            for x in s.x0..s.x1 {
                v.push((x, s.y)).unwrap();
            }
        })
        .unwrap();
        v.sort_unstable();
        v
    }

    #[test]
    fn even_odd_leaves_the_pentagram_centre_empty() {
        let star = [
            P::new(10, 0),
            P::new(16, 19),
            P::new(0, 7),
            P::new(20, 7),
            P::new(4, 19),
        ];
        let w = Window::new(0, 0, 21, 20);
        let nonzero = covered_set(&star, FillRule::NonZero, &w);
        let even_odd = covered_set(&star, FillRule::EvenOdd, &w);
        assert!(
            nonzero.contains(&(10, 10)),
            "the nonzero rule fills the centre"
        );
        assert!(
            !even_odd.contains(&(10, 10)),
            "the even-odd rule leaves it empty"
        );
        assert!(even_odd.contains(&(10, 3)), "a point of the star is in");
        // Every pixel against the direct parity count, and no span emitted twice.
        let mut expect: Vec<(i32, i32), 1024> = Vec::new();
        for x in 0..21 {
            for y in 0..20 {
                if odd_crossings(&star, x, y) {
                    expect.push((x, y)).unwrap();
                }
            }
        }
        expect.sort_unstable();
        assert_eq!(even_odd, expect);
    }

    #[test]
    fn even_odd_equals_nonzero_on_simple_polygons_and_matches_parity_on_random_ones() {
        let mut rng = crate::test_rng::XorShift(0xE7E7_0DD0_0000_0031);
        let w = Window::new(0, 0, 24, 24);
        for i in 0..3000 {
            let n = 3 + (rng.next_u64() % 6) as usize;
            let poly = random_polygon(&mut rng, n);
            let even_odd = covered_set(&poly, FillRule::EvenOdd, &w);
            for x in w.x0..w.x1 {
                for y in w.y0..w.y1 {
                    assert_eq!(
                        even_odd.binary_search(&(x, y)).is_ok(),
                        odd_crossings(&poly, x, y),
                        "case {i}: pixel ({x}, {y}) of {poly:?}"
                    );
                }
            }
            if n == 3 {
                // A triangle is simple: both rules agree.
                assert_eq!(
                    even_odd,
                    covered_set(&poly, FillRule::NonZero, &w),
                    "case {i}"
                );
            }
        }
    }

    #[test]
    fn even_odd_is_the_parity_of_the_fan_triangles() {
        // Parity adds up: a polygon's even-odd coverage is the exclusive or of its fan
        // triangles' coverages, which holds only if the fan's shared edges give each pixel to
        // exactly one side (watertight, no overlap) under the left-in, right-out rule.
        let mut rng = crate::test_rng::XorShift(0xFA11_0DD0_0000_0031);
        let w = Window::new(0, 0, 24, 24);
        for i in 0..2000 {
            let n = 4 + (rng.next_u64() % 5) as usize;
            let poly = random_polygon(&mut rng, n);
            let mut parity = [[false; 24]; 24];
            for k in 1..n - 1 {
                let tri = [poly[0], poly[k], poly[k + 1]];
                for (x, y) in covered_set(&tri, FillRule::EvenOdd, &w) {
                    parity[y as usize][x as usize] ^= true;
                }
            }
            let mut fan: Vec<(i32, i32), 1024> = Vec::new();
            for (y, row) in parity.iter().enumerate() {
                for (x, &odd) in row.iter().enumerate() {
                    if odd {
                        fan.push((x as i32, y as i32)).unwrap();
                    }
                }
            }
            fan.sort_unstable();
            assert_eq!(
                covered_set(&poly, FillRule::EvenOdd, &w),
                fan,
                "case {i}: {poly:?}"
            );
        }
    }

    /// Issue "hostile inputs" #10: the active-edge sort is a correct sort whatever the input
    /// (nearly sorted, reversed, random, with ties), and its budget bounds the work.
    #[test]
    fn nearly_sorted_sort_sorts_everything() {
        let mut rng = crate::test_rng::XorShift(0x50A7_ED00_0000_0010);
        for i in 0..2000 {
            let n = (rng.next_u64() % 200) as usize;
            let mut v: Vec<(i32, u16), 200> = Vec::new();
            for k in 0..n {
                let x = match i % 4 {
                    0 => k as i32 + (rng.next_u64() % 3) as i32, // nearly sorted
                    1 => -(k as i32),                            // reversed
                    2 => (rng.next_u64() % 8) as i32,            // many ties
                    _ => rng.next_u64() as i32,                  // random
                };
                let _ = v.push((x, k as u16));
            }
            let mut want = v.clone();
            want.sort_unstable();
            sort_nearly_sorted(&mut v, |t| t.0);
            let keys = |v: &[(i32, u16)]| -> Vec<i32, 200> { v.iter().map(|t| t.0).collect() };
            assert_eq!(keys(&v), keys(&want));
            let mut ids: Vec<u16, 200> = v.iter().map(|t| t.1).collect();
            ids.sort_unstable();
            assert!(ids.iter().enumerate().all(|(k, &id)| id == k as u16));
        }
    }
}
