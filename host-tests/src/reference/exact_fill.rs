//! An exact rational reference for the polygon fill rule, independent of the production fill.
//!
//! The production fill (`zscan::raster::polygon`) walks edges row by row with Euclidean
//! divisions and sweeps the sorted span ends. This module uses a different algorithm: for every
//! candidate pixel it evaluates the **winding number** of the polygon around the pixel's lattice
//! point directly, with exact `i128` arithmetic and no division at all.
//!
//! ## The rule, stated once
//! Vertices are in units of `2^-S` pixel (`F = 2^S`); pixel `(x, y)` is the point `(x·F, y·F)`.
//! For an edge from `a` to `b` with `a.y ≠ b.y` (horizontal edges count for nothing), write its
//! low end `(X0, Y0)` and high end `(X1, Y1)` (`Y0 < Y1`). The edge
//! - *covers* row `y` iff `Y0 ≤ y·F < Y1` (first row in, last row out);
//! - crosses that row at `x_e = X0 + (y·F − Y0)·(X1 − X0)/(Y1 − Y0)`;
//! - *counts* for pixel `(x, y)` iff it covers the row and `x_e ≤ x·F`, which after
//!   multiplying by `Y1 − Y0 > 0` is the exact integer test
//!   `X0·(Y1 − Y0) + (y·F − Y0)·(X1 − X0) ≤ x·F·(Y1 − Y0)`;
//! - contributes `+1` when `y` increases from `a` to `b`, `−1` otherwise.
//!
//! The pixel is covered iff the sum (the winding number of the polygon around the pixel,
//! measured with a ray going left) is not zero: the nonzero rule. With `x_e ≤ x` a pixel exactly
//! on an edge where the winding starts (the polygon's left boundary) is in, and one exactly on
//! an edge where it returns to zero (the right boundary) is out.
//!
//! The even-odd rule ([`RefRule::EvenOdd`]) counts the same edges without their sign: the
//! pixel is covered iff an odd number of edges count for it (the parity of the count is the
//! parity of the winding number).
//!
//! Cost: `O(pixels · edges)`; meant for tests on small polygons, or on a small window of a
//! large one ([`covered_pixels_in`]).

use std::collections::BTreeSet;

/// A polygon vertex in units of `2^-S` pixel, as `(x, y)` with `y` growing downward.
pub type Vertex = (i64, i64);

/// A half-open run of covered pixels `x0 ≤ x < x1` on row `y`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RefSpan {
    /// Row.
    pub y: i64,
    /// First covered pixel.
    pub x0: i64,
    /// One past the last covered pixel.
    pub x1: i64,
}

/// The winding number of the polygon around pixel `(x, y)` under the rule of the module doc.
pub fn winding(vertices: &[Vertex], s: u32, x: i64, y: i64) -> i64 {
    let f = 1i128 << s;
    let (px, py) = (x as i128 * f, y as i128 * f);
    let n = vertices.len();
    let mut w = 0i64;
    for i in 0..n {
        let (a, b) = (vertices[i], vertices[(i + 1) % n]);
        if a.1 == b.1 {
            continue;
        }
        let (lo, hi, dir) = if a.1 < b.1 { (a, b, 1) } else { (b, a, -1) };
        let (x0, y0, x1, y1) = (lo.0 as i128, lo.1 as i128, hi.0 as i128, hi.1 as i128);
        if !(y0 <= py && py < y1) {
            continue;
        }
        let dy = y1 - y0;
        // x_e·dy ≤ px·dy  ⇔  x_e ≤ px
        if x0 * dy + (py - y0) * (x1 - x0) <= px * dy {
            w += dir;
        }
    }
    w
}

/// The one item of `items` whose triangle (`corners`) covers pixel `(x, y)`, `Ok(None)` when
/// none does, or an error naming the pixel when two do (front faces of a closed mesh tile
/// the screen, so two covering front triangles mean a broken reference scene).
pub fn sole_cover<T>(
    items: &[T],
    corners: impl Fn(&T) -> &[Vertex],
    s: u32,
    (x, y): (i64, i64),
) -> Result<Option<&T>, String> {
    let mut covering = items.iter().filter(|t| covered(corners(t), s, x, y));
    let first = covering.next();
    match covering.next() {
        Some(_) => Err(format!("two front triangles at ({x},{y})")),
        None => Ok(first),
    }
}

/// True when pixel `(x, y)` is covered (winding number not zero).
pub fn covered(vertices: &[Vertex], s: u32, x: i64, y: i64) -> bool {
    covered_by(vertices, s, x, y, RefRule::NonZero)
}

/// Which count decides coverage (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RefRule {
    /// The winding number is not zero.
    NonZero,
    /// The number of counting edges is odd.
    EvenOdd,
}

/// True when pixel `(x, y)` is covered under `rule`.
pub fn covered_by(vertices: &[Vertex], s: u32, x: i64, y: i64, rule: RefRule) -> bool {
    if vertices.len() < 3 {
        return false;
    }
    let w = winding(vertices, s, x, y);
    match rule {
        RefRule::NonZero => w != 0,
        RefRule::EvenOdd => w.rem_euclid(2) == 1,
    }
}

/// `⌊v / 2^s⌋`.
fn floor_px(v: i64, s: u32) -> i64 {
    v >> s
}

/// The pixel rectangle `(x0, y0, x1, y1)` (half-open) that can hold covered pixels: every
/// covered pixel lies inside the polygon's bounding box.
pub fn pixel_bounds(vertices: &[Vertex], s: u32) -> (i64, i64, i64, i64) {
    if vertices.is_empty() {
        return (0, 0, 0, 0);
    }
    let min_x = vertices.iter().map(|v| v.0).min().unwrap_or(0);
    let max_x = vertices.iter().map(|v| v.0).max().unwrap_or(0);
    let min_y = vertices.iter().map(|v| v.1).min().unwrap_or(0);
    let max_y = vertices.iter().map(|v| v.1).max().unwrap_or(0);
    (
        floor_px(min_x, s),
        floor_px(min_y, s),
        floor_px(max_x, s) + 1,
        floor_px(max_y, s) + 1,
    )
}

/// The covered pixels inside the half-open pixel rectangle `x0 ≤ x < x1`, `y0 ≤ y < y1`
/// (intersected with the polygon's bounding box), by testing each one.
pub fn covered_pixels_in(
    vertices: &[Vertex],
    s: u32,
    rect: (i64, i64, i64, i64),
) -> BTreeSet<(i64, i64)> {
    covered_pixels_in_by(vertices, s, rect, RefRule::NonZero)
}

/// [`covered_pixels_in`] under `rule`.
pub fn covered_pixels_in_by(
    vertices: &[Vertex],
    s: u32,
    (x0, y0, x1, y1): (i64, i64, i64, i64),
    rule: RefRule,
) -> BTreeSet<(i64, i64)> {
    let (bx0, by0, bx1, by1) = pixel_bounds(vertices, s);
    let mut set = BTreeSet::new();
    for y in y0.max(by0)..y1.min(by1) {
        for x in x0.max(bx0)..x1.min(bx1) {
            if covered_by(vertices, s, x, y, rule) {
                set.insert((x, y));
            }
        }
    }
    set
}

/// All covered pixels of the polygon, as `(x, y)`.
pub fn covered_pixels(vertices: &[Vertex], s: u32) -> BTreeSet<(i64, i64)> {
    covered_pixels_in(vertices, s, pixel_bounds(vertices, s))
}

/// Groups a pixel set into maximal half-open runs, sorted by row then column.
pub fn spans_of(pixels: &BTreeSet<(i64, i64)>) -> Vec<RefSpan> {
    let mut rows: Vec<(i64, i64)> = pixels.iter().map(|&(x, y)| (y, x)).collect();
    rows.sort_unstable();
    let mut out: Vec<RefSpan> = Vec::new();
    for (y, x) in rows {
        match out.last_mut() {
            Some(s) if s.y == y && s.x1 == x => s.x1 = x + 1,
            _ => out.push(RefSpan {
                y,
                x0: x,
                x1: x + 1,
            }),
        }
    }
    out
}

/// All covered pixels of the polygon as maximal half-open runs, sorted by row then column.
pub fn covered_spans(vertices: &[Vertex], s: u32) -> Vec<RefSpan> {
    covered_spans_by(vertices, s, RefRule::NonZero)
}

/// [`covered_spans`] under `rule`.
pub fn covered_spans_by(vertices: &[Vertex], s: u32, rule: RefRule) -> Vec<RefSpan> {
    let bounds = pixel_bounds(vertices, s);
    spans_of(&covered_pixels_in_by(vertices, s, bounds, rule))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn top_left_rule_on_a_square() {
        // Square with corners (0,0) and (3,3): pixels 0..3 × 0..3 (left/top in, right/bottom out).
        let sq = [(0, 0), (3, 0), (3, 3), (0, 3)];
        let px = covered_pixels(&sq, 0);
        let expect: BTreeSet<_> = (0..3).flat_map(|y| (0..3).map(move |x| (x, y))).collect();
        assert_eq!(px, expect);
        // Other orientation, same pixels.
        let rev: Vec<_> = sq.iter().rev().copied().collect();
        assert_eq!(covered_pixels(&rev, 0), expect);
        // In sub-pixel units (S = 2), the same square.
        let sq4: Vec<_> = sq.iter().map(|&(x, y)| (x * 4, y * 4)).collect();
        assert_eq!(covered_pixels(&sq4, 2), expect);
    }

    #[test]
    fn even_odd_rule_leaves_a_pentagram_centre_empty() {
        let star = [(10, 0), (16, 19), (0, 7), (20, 7), (4, 19)];
        assert!(!covered_by(&star, 0, 10, 10, RefRule::EvenOdd));
        assert!(covered_by(&star, 0, 10, 3, RefRule::EvenOdd));
        assert!(covered_by(&star, 0, 10, 10, RefRule::NonZero));
    }

    #[test]
    fn nonzero_rule_fills_a_pentagram_centre() {
        let star = [(10, 0), (16, 19), (0, 7), (20, 7), (4, 19)];
        assert_eq!(winding(&star, 0, 10, 10).abs(), 2);
        assert!(covered(&star, 0, 10, 10));
        assert!(!covered(&star, 0, 0, 0));
    }

    #[test]
    fn degenerate_covers_nothing() {
        assert!(covered_pixels(&[(0, 0), (5, 5)], 0).is_empty());
        assert!(covered_pixels(&[(0, 0), (5, 5), (10, 10)], 0).is_empty());
        assert!(covered_pixels(&[], 0).is_empty());
    }
}
