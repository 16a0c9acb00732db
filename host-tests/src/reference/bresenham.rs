//! Lines and circles by definition, for checking `zscan::raster::{line, circle}`.
//!
//! Nothing here steps an error term: every pixel is computed on its own from the exact
//! rational (lines) or from the midpoint criterion evaluated directly (circles), in `i128`,
//! so these functions share no arithmetic with the incremental code they check.
//!
//! Line definition (the documented contract of `zscan::raster::line`): the major axis is `x`
//! when `|dx| ≥ |dy|`, else `y`; there is one pixel per major coordinate between the ends,
//! and its minor coordinate is the exact value on the segment rounded to the nearest integer,
//! ties toward the smaller coordinate.
//!
//! Circle definition: the octant pixels are `(x, y(x))` for `x ≥ 0` with `x ≤ y(x)`, where
//! `y(x)` is the largest `y` with `4x² + (2y − 1)² < 4r²`, reflected eight ways.

use std::collections::BTreeSet;

/// `⌈p / q⌉` for `q > 0`.
fn ceil_div(p: i128, q: i128) -> i128 {
    -((-p).div_euclid(q))
}

/// True when the line `p0`–`p1` has `x` as its major axis (`|dx| ≥ |dy|`).
pub fn x_major(p0: (i64, i64), p1: (i64, i64)) -> bool {
    (p1.0 - p0.0).abs() >= (p1.1 - p0.1).abs()
}

/// The minor coordinate of the line `p0`–`p1` at major coordinate `major` (any value, also
/// beyond the ends: the line is extended), by the definition: nearest integer to the exact
/// rational, ties toward the smaller value. `p0 ≠ p1`.
pub fn minor_at(p0: (i64, i64), p1: (i64, i64), major: i64) -> i64 {
    let (m0, n0, m1, n1) = if x_major(p0, p1) {
        (p0.0, p0.1, p1.0, p1.1)
    } else {
        (p0.1, p0.0, p1.1, p1.0)
    };
    let (dm, dn) = (m1 as i128 - m0 as i128, n1 as i128 - n0 as i128);
    assert!(dm != 0, "minor_at needs two distinct end points");
    // Exact minor value: v = n0 + (major − m0)·dn / dm = num / den with den > 0.
    let (mut num, mut den) = (n0 as i128 * dm + (major as i128 - m0 as i128) * dn, dm);
    if den < 0 {
        num = -num;
        den = -den;
    }
    // Round half down: ⌈v − ½⌉ = ⌈(2·num − den) / (2·den)⌉.
    ceil_div(2 * num - den, 2 * den) as i64
}

/// The pixel of the line at major coordinate `major`, as `(x, y)`.
pub fn pixel_at(p0: (i64, i64), p1: (i64, i64), major: i64) -> (i64, i64) {
    let minor = minor_at(p0, p1, major);
    if x_major(p0, p1) {
        (major, minor)
    } else {
        (minor, major)
    }
}

/// The pixels of the line from `p0` to `p1` in order, both ends included when `closed`,
/// the last one left out otherwise.
pub fn line_pixels(p0: (i64, i64), p1: (i64, i64), closed: bool) -> Vec<(i64, i64)> {
    if p0 == p1 {
        return if closed { vec![p0] } else { vec![] };
    }
    let (m0, m1) = if x_major(p0, p1) {
        (p0.0, p1.0)
    } else {
        (p0.1, p1.1)
    };
    let step = if m1 > m0 { 1 } else { -1 };
    let n = (m1 - m0).abs();
    let count = if closed { n + 1 } else { n };
    (0..count)
        .map(|t| pixel_at(p0, p1, m0 + step * t))
        .collect()
}

/// The pixels of the line inside the half-open window `x0 ≤ x < x1`, `y0 ≤ y < y1`, in
/// order, computed only over the major coordinates the window spans (cost O(window)).
pub fn clipped_line_pixels(
    p0: (i64, i64),
    p1: (i64, i64),
    closed: bool,
    window: (i64, i64, i64, i64),
) -> Vec<(i64, i64)> {
    let (wx0, wy0, wx1, wy1) = window;
    if p0 == p1 {
        let inside = p0.0 >= wx0 && p0.0 < wx1 && p0.1 >= wy0 && p0.1 < wy1;
        return if closed && inside { vec![p0] } else { vec![] };
    }
    let (m0, m1, lo, hi) = if x_major(p0, p1) {
        (p0.0, p1.0, wx0, wx1 - 1)
    } else {
        (p0.1, p1.1, wy0, wy1 - 1)
    };
    let step = if m1 > m0 { 1 } else { -1 };
    let last = if closed { m1 } else { m1 - step };
    // Major coordinates of the line (in travel order) that the window spans.
    let (a, b) = (m0.min(last), m0.max(last));
    if !closed && m0 == m1 {
        return vec![];
    }
    let (from, to) = (a.max(lo), b.min(hi));
    if from > to {
        return vec![];
    }
    let majors: Vec<i64> = if step > 0 {
        (from..=to).collect()
    } else {
        (from..=to).rev().collect()
    };
    majors
        .into_iter()
        .map(|m| pixel_at(p0, p1, m))
        .filter(|&(x, y)| x >= wx0 && x < wx1 && y >= wy0 && y < wy1)
        .collect()
}

/// `y(x)` of the circle definition: the largest `y ≥ 0` with `4x² + (2y − 1)² < 4r²`, or
/// `None` when there is none. Found by a float estimate corrected with exact `i128` tests.
pub fn circle_row(x: i64, r: i64) -> Option<i64> {
    let (x, r) = (x as i128, r as i128);
    let ok = |y: i128| 4 * x * x + (2 * y - 1) * (2 * y - 1) < 4 * r * r;
    if !ok(0) && !ok(1) {
        return None;
    }
    let mut y = (((r * r - x * x).max(0)) as f64).sqrt() as i128 + 2;
    while y > 0 && !ok(y) {
        y -= 1;
    }
    while ok(y + 1) {
        y += 1;
    }
    Some(y as i64)
}

/// The set of pixels of the circle outline of radius `r` around `centre`, by definition.
pub fn circle_pixels(centre: (i64, i64), r: i64) -> BTreeSet<(i64, i64)> {
    let mut set = BTreeSet::new();
    if r == 0 {
        set.insert(centre);
        return set;
    }
    let mut x = 0;
    while let Some(y) = circle_row(x, r) {
        if x > y {
            break;
        }
        for (a, b) in [(x, y), (y, x)] {
            for (sa, sb) in [(1, 1), (1, -1), (-1, 1), (-1, -1)] {
                set.insert((centre.0 + sa * a, centre.1 + sb * b));
            }
        }
        x += 1;
    }
    set
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_lines() {
        assert_eq!(
            line_pixels((0, 0), (4, 1), true),
            vec![(0, 0), (1, 0), (2, 0), (3, 1), (4, 1)]
        );
        assert_eq!(
            line_pixels((0, 0), (1, 2), true),
            vec![(0, 0), (0, 1), (1, 2)]
        );
        assert_eq!(
            line_pixels((0, 0), (-3, 0), false),
            vec![(0, 0), (-1, 0), (-2, 0)]
        );
        // (0,0)→(−4,−1): y = −t/4 at x = −2 is −0.5 → tie toward −1.
        assert_eq!(line_pixels((0, 0), (-4, -1), true)[2], (-2, -1));
    }

    #[test]
    fn hand_computed_circle() {
        // r = 2: 12 pixels (see the core's test for the derivation).
        assert_eq!(circle_pixels((0, 0), 2).len(), 12);
        assert_eq!(circle_row(0, 5), Some(5));
        assert_eq!(circle_row(3, 5), Some(4)); // 36 + 49 < 100, 36 + 81 ≥ 100
    }
}
