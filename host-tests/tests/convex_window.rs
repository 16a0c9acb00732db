//! Windowing against a convex polygon (`zscan::raster::convex_window`) against the independent
//! exact reference (`zscan_host::reference::exact_fill`): a clipped polygon covers exactly the
//! pixels that both it and the window cover, a clipped line draws exactly the unclipped
//! Bresenham line's pixels that the window covers, and windows that are not convex are refused.

use std::collections::BTreeSet;

use embedded_graphics::prelude::Point;
use zscan::raster::convex_window::{ConvexWindow, ConvexWindowError};
use zscan::raster::line::{Bresenham, Ends};
use zscan::raster::polygon::FillRule;
use zscan::raster::SubpixelPoint;
use zscan_host::reference::exact_fill::{covered_by, RefRule};

const S: u32 = 4;

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next() % ((hi - lo + 1) as u64)) as i64
    }
}

/// The convex hull of `points` (Andrew's monotone chain, integer cross products), without
/// collinear points, counter-clockwise in a y-up frame.
fn hull(mut points: Vec<(i64, i64)>) -> Vec<(i64, i64)> {
    points.sort_unstable();
    points.dedup();
    let cross = |o: (i64, i64), a: (i64, i64), b: (i64, i64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut lower: Vec<(i64, i64)> = Vec::new();
    for &p in &points {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<(i64, i64)> = Vec::new();
    for &p in points.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

fn points(v: &[(i64, i64)]) -> Vec<SubpixelPoint<S>> {
    v.iter()
        .map(|&(x, y)| SubpixelPoint::new(x as i32, y as i32))
        .collect()
}

#[test]
fn clipped_polygons_and_lines_match_the_reference() {
    let mut rng = Rng(0xC04E_0000_0009);
    let f = 1i64 << S;
    let mut windows = 0;
    let mut pixels_checked = 0usize;
    for case in 0..400 {
        let window_points: Vec<(i64, i64)> = (0..rng.range(3, 9))
            .map(|_| (rng.range(-2 * f, 20 * f), rng.range(-2 * f, 20 * f)))
            .collect();
        let mut window = hull(window_points);
        if window.len() < 3 {
            continue;
        }
        if case % 2 == 1 {
            window.reverse(); // both orientations
        }
        let clip = ConvexWindow::<S, 16>::new(&points(&window))
            .unwrap_or_else(|e| panic!("case {case}: hull {window:?} refused: {e}"));
        windows += 1;
        let polygon: Vec<(i64, i64)> = (0..rng.range(3, 8))
            .map(|_| (rng.range(-4 * f, 24 * f), rng.range(-4 * f, 24 * f)))
            .collect();
        for (rule, ref_rule) in [
            (FillRule::NonZero, RefRule::NonZero),
            (FillRule::EvenOdd, RefRule::EvenOdd),
        ] {
            let mut got = BTreeSet::new();
            clip.fill_polygon::<16>(&points(&polygon), rule, |s| {
                for x in s.x0..s.x1 {
                    assert!(
                        got.insert((x as i64, s.y as i64)),
                        "case {case}: pixel twice"
                    );
                }
            })
            .unwrap();
            let mut want = BTreeSet::new();
            for y in -6..26 {
                for x in -6..26 {
                    if covered_by(&polygon, S, x, y, ref_rule)
                        && covered_by(&window, S, x, y, RefRule::NonZero)
                    {
                        want.insert((x, y));
                    }
                }
            }
            pixels_checked += want.len();
            assert_eq!(
                got, want,
                "case {case}: window {window:?}, polygon {polygon:?}, {rule:?}"
            );
        }
        // Lines: the unclipped Bresenham pixels that the window covers, in order.
        for _ in 0..4 {
            let (p0, p1) = (
                Point::new(rng.range(-8, 28) as i32, rng.range(-8, 28) as i32),
                Point::new(rng.range(-8, 28) as i32, rng.range(-8, 28) as i32),
            );
            let got: Vec<Point> = clip.line(p0, p1, Ends::Closed).unwrap().collect();
            let want: Vec<Point> = Bresenham::new(p0, p1)
                .filter(|p| covered_by(&window, S, p.x as i64, p.y as i64, RefRule::NonZero))
                .collect();
            assert_eq!(
                got, want,
                "case {case}: window {window:?}, line {p0:?} -> {p1:?}"
            );
        }
    }
    assert!(
        windows > 300 && pixels_checked > 10_000,
        "{windows} windows, {pixels_checked} pixels"
    );
}

#[test]
fn windows_that_are_not_convex_are_refused() {
    let mut rng = Rng(0x0BAD_C04E);
    let f = 1i64 << S;
    let (mut refused, mut accepted) = (0, 0);
    for _ in 0..3000 {
        let v: Vec<(i64, i64)> = (0..rng.range(3, 7))
            .map(|_| (rng.range(0, 12 * f), rng.range(0, 12 * f)))
            .collect();
        match ConvexWindow::<S, 16>::new(&points(&v)) {
            Ok(_) => {
                accepted += 1;
                // An accepted window has every vertex of its hull among its own and covers
                // one run per row.
                let h: BTreeSet<_> = hull(v.clone()).into_iter().collect();
                assert!(h.iter().all(|p| v.contains(p)), "{v:?}");
                for y in -1..14 {
                    let row: Vec<bool> = (-1..14)
                        .map(|x| covered_by(&v, S, x, y, RefRule::NonZero))
                        .collect();
                    let runs = row.windows(2).filter(|w| !w[0] && w[1]).count();
                    assert!(runs <= 1, "{v:?}: row {y} has {runs} runs");
                }
            }
            Err(ConvexWindowError::NotConvex { .. } | ConvexWindowError::NoArea) => refused += 1,
            Err(e) => panic!("{v:?}: {e}"),
        }
    }
    assert!(
        refused > 500 && accepted > 500,
        "refused {refused}, accepted {accepted}"
    );
    // A pentagram turns one way throughout but winds twice.
    let star = [(10, 0), (16, 19), (0, 7), (20, 7), (4, 19)].map(|(x, y)| (x * f, y * f));
    let e = ConvexWindow::<S, 16>::new(&points(&star)).unwrap_err();
    assert!(e.to_string().contains("not convex"), "{e}");
}

/// Two windows that share an edge split a drawing: no pixel twice, none lost.
#[test]
fn windows_sharing_an_edge_tile() {
    let f = 1i64 << S;
    let a = [(0, 0), (20 * f, 0), (3 * f + 5, 20 * f)];
    let b = [(20 * f, 0), (20 * f, 20 * f), (3 * f + 5, 20 * f)];
    let whole = [(0, 0), (20 * f, 0), (20 * f, 20 * f), (3 * f + 5, 20 * f)];
    let polygon = points(&[(-f, 3 * f), (25 * f, 7), (15 * f + 3, 30 * f)]);
    let fill = |w: &[(i64, i64)]| {
        let mut set = BTreeSet::new();
        ConvexWindow::<S, 8>::new(&points(w))
            .unwrap()
            .fill_polygon::<8>(&polygon, FillRule::NonZero, |s| {
                for x in s.x0..s.x1 {
                    set.insert((x, s.y));
                }
            })
            .unwrap();
        set
    };
    let (pa, pb, pw) = (fill(&a), fill(&b), fill(&whole));
    assert!(pa.is_disjoint(&pb));
    assert_eq!(pa.union(&pb).copied().collect::<BTreeSet<_>>(), pw);
    assert!(pa.len() > 20 && pb.len() > 20);
}
