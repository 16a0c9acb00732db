//! The fill's target: from a seed, a random polygon (0 to 12 vertices, at 0, 4 or 8 sub-pixel
//! bits, mostly within 4 pixels of a 28 × 28-pixel area, one in ten spread over ±2^18 pixels,
//! one in twenty with a vertex past the raster's range), filled under both rules
//! (`FillRule::NonZero` and `FillRule::EvenOdd`) inside a random pixel window, and through a
//! random `ConvexWindow` (3 to 8 points, their convex hull half the time, both orientations);
//! lines of random ends through the same window.
//!
//! Properties: every span lies in its window and covers no pixel twice; the pixels are exactly
//! the exact rational reference's (`reference::exact_fill::covered_by`) under the same rule,
//! intersected with the convex window's (nonzero) for `ConvexWindow`; a clipped line draws
//! exactly the unclipped Bresenham line's pixels the window covers, in order; a vertex past the
//! range is an error, before any span; an accepted window covers one run per row.

use std::collections::BTreeSet;

use embedded_graphics::prelude::Point;
use zscan::output::Window;
use zscan::raster::convex_window::ConvexWindow;
use zscan::raster::line::{Bresenham, Ends};
use zscan::raster::polygon::{fill_polygon_with_rule, FillRule};
use zscan::raster::SubpixelPoint;

use super::values::{chance, int, one_of, size};
use super::{hash, Outcome, Rng};
use crate::reference::exact_fill::{covered_by, RefRule};

/// One case of the target (module doc).
pub(super) fn run(seed: u64) -> Result<Outcome, String> {
    let mut rng = Rng::new(seed);
    match one_of(&mut rng, &[0u32, 4, 4, 8]) {
        0 => run_at::<0>(&mut rng),
        4 => run_at::<4>(&mut rng),
        _ => run_at::<8>(&mut rng),
    }
}

/// The raster's range in sub-pixel units (`|x|, |y| ≤ 2^28 − 1`).
const MAX_COORD: i64 = (1 << 28) - 1;

fn run_at<const S: u32>(rng: &mut Rng) -> Result<Outcome, String> {
    let f = 1i64 << S;
    let spread = chance(rng, 10);
    let point = |rng: &mut Rng| -> (i64, i64) {
        let c = |rng: &mut Rng| {
            if spread {
                int(rng, -(1 << 18), 1 << 18) * f + int(rng, 0, f - 1)
            } else {
                int(rng, -4 * f, 32 * f)
            }
        };
        (c(rng), c(rng))
    };
    let mut polygon: Vec<(i64, i64)> = (0..size(rng, 0, 12)).map(|_| point(rng)).collect();
    let past_range = !polygon.is_empty() && chance(rng, 5);
    if past_range {
        let k = size(rng, 0, polygon.len() - 1);
        let beyond = MAX_COORD + int(rng, 1, 1 << 20);
        polygon[k].0 = if chance(rng, 50) { beyond } else { -beyond };
    }
    let points: Vec<SubpixelPoint<S>> = polygon
        .iter()
        .map(|&(x, y)| {
            SubpixelPoint::new(x.clamp(i32::MIN as i64, i32::MAX as i64) as i32, y as i32)
        })
        .collect();
    let x0 = int(rng, -8, 30) as i32;
    let y0 = int(rng, -8, 30) as i32;
    let window = Window::new(
        x0,
        y0,
        x0 + int(rng, 0, 30) as i32,
        y0 + int(rng, 0, 30) as i32,
    );
    let mut fingerprint = Vec::new();
    for (rule, reference) in [
        (FillRule::NonZero, RefRule::NonZero),
        (FillRule::EvenOdd, RefRule::EvenOdd),
    ] {
        let mut got = BTreeSet::new();
        let mut bad = None;
        let filled = fill_polygon_with_rule::<S, 16>(&points, &window, rule, |s| {
            if s.y < window.y0 || s.y >= window.y1 || s.x0 < window.x0 || s.x1 > window.x1 {
                bad = Some(format!("span {s:?} outside the window {window:?}"));
            }
            for x in s.x0..s.x1 {
                if !got.insert((x as i64, s.y as i64)) {
                    bad = Some(format!("pixel ({x}, {}) twice", s.y));
                }
            }
        });
        if let Some(b) = bad {
            return Err(format!("{rule:?}: {b}; polygon {polygon:?}"));
        }
        match filled {
            Err(e) if past_range => {
                if !got.is_empty() {
                    return Err(format!("{rule:?}: spans before the error {e}"));
                }
                fingerprint.push(hash(e.to_string().bytes().map(u64::from)));
                continue;
            }
            Err(e) => return Err(format!("{rule:?}: {e}; polygon {polygon:?}")),
            Ok(()) if past_range => {
                return Err(format!(
                    "{rule:?}: a vertex past the range was filled: {polygon:?}"
                ))
            }
            Ok(()) => {}
        }
        let mut want = BTreeSet::new();
        for y in window.y0..window.y1 {
            for x in window.x0..window.x1 {
                if covered_by(&polygon, S, x as i64, y as i64, reference) {
                    want.insert((x as i64, y as i64));
                }
            }
        }
        if got != want {
            let diff: Vec<_> = got.symmetric_difference(&want).take(4).collect();
            return Err(format!(
                "{rule:?}: differs from the exact reference at {diff:?}; polygon {polygon:?}, \
                 window {window:?}"
            ));
        }
        fingerprint.push(hash(got.iter().flat_map(|&(x, y)| [x as u64, y as u64])));
    }
    if past_range || spread {
        return Ok(Ok(fingerprint));
    }
    convex_window::<S>(rng, &polygon, &points, &mut fingerprint)?;
    Ok(Ok(fingerprint))
}

/// The convex hull of `points` (Andrew's monotone chain), without collinear points.
fn hull(mut points: Vec<(i64, i64)>) -> Vec<(i64, i64)> {
    points.sort_unstable();
    points.dedup();
    let cross = |o: (i64, i64), a: (i64, i64), b: (i64, i64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut chain: Vec<(i64, i64)> = Vec::new();
    for pass in [
        &points[..],
        &points.iter().rev().copied().collect::<Vec<_>>()[..],
    ] {
        let start = chain.len();
        for &p in pass {
            while chain.len() >= start + 2
                && cross(chain[chain.len() - 2], chain[chain.len() - 1], p) <= 0
            {
                chain.pop();
            }
            chain.push(p);
        }
        chain.pop();
    }
    chain
}

/// `ConvexWindow` over the same polygon and random lines (module doc).
fn convex_window<const S: u32>(
    rng: &mut Rng,
    polygon: &[(i64, i64)],
    points: &[SubpixelPoint<S>],
    fingerprint: &mut Vec<u64>,
) -> Result<(), String> {
    let f = 1i64 << S;
    let mut corners: Vec<(i64, i64)> = (0..size(rng, 3, 8))
        .map(|_| (int(rng, -2 * f, 26 * f), int(rng, -2 * f, 26 * f)))
        .collect();
    if chance(rng, 50) {
        corners = hull(corners);
    }
    if chance(rng, 50) {
        corners.reverse();
    }
    let sub: Vec<SubpixelPoint<S>> = corners
        .iter()
        .map(|&(x, y)| SubpixelPoint::new(x as i32, y as i32))
        .collect();
    let clip = match ConvexWindow::<S, 16>::new(&sub) {
        Ok(c) => c,
        Err(e) => {
            fingerprint.push(hash(e.to_string().bytes().map(u64::from)));
            return Ok(());
        }
    };
    let inside = |x: i64, y: i64| covered_by(&corners, S, x, y, RefRule::NonZero);
    for y in -4..32 {
        let runs = (-4..33)
            .map(|x| inside(x, y))
            .collect::<Vec<bool>>()
            .windows(2)
            .filter(|w| !w[0] && w[1])
            .count()
            + inside(-4, y) as usize;
        if runs > 1 {
            return Err(format!(
                "window {corners:?} accepted with {runs} runs on row {y}"
            ));
        }
    }
    for (rule, reference) in [
        (FillRule::NonZero, RefRule::NonZero),
        (FillRule::EvenOdd, RefRule::EvenOdd),
    ] {
        let mut got = BTreeSet::new();
        let mut twice = false;
        let filled = clip.fill_polygon::<16>(points, rule, |s| {
            for x in s.x0..s.x1 {
                twice |= !got.insert((x as i64, s.y as i64));
            }
        });
        if let Err(e) = filled {
            return Err(format!("ConvexWindow {rule:?}: {e}; polygon {polygon:?}"));
        }
        let mut want = BTreeSet::new();
        for y in -6..34 {
            for x in -6..34 {
                if covered_by(polygon, S, x, y, reference) && inside(x, y) {
                    want.insert((x, y));
                }
            }
        }
        if twice || got != want {
            let diff: Vec<_> = got.symmetric_difference(&want).take(4).collect();
            return Err(format!(
                "ConvexWindow {rule:?}: differs from the reference at {diff:?} (a pixel twice: \
                 {twice}); window {corners:?}, polygon {polygon:?}"
            ));
        }
        fingerprint.push(hash(got.iter().flat_map(|&(x, y)| [x as u64, y as u64])));
    }
    for _ in 0..3 {
        let mut end = || Point::new(int(rng, -12, 40) as i32, int(rng, -12, 40) as i32);
        let (p0, p1) = (end(), end());
        let got: Vec<Point> = match clip.line(p0, p1, Ends::Closed) {
            Ok(l) => l.collect(),
            Err(e) => return Err(format!("ConvexWindow line {p0:?}–{p1:?}: {e}")),
        };
        let want: Vec<Point> = Bresenham::new(p0, p1)
            .filter(|p| inside(p.x as i64, p.y as i64))
            .collect();
        if got != want {
            return Err(format!(
                "ConvexWindow line {p0:?}–{p1:?}: {got:?} against {want:?}; window {corners:?}"
            ));
        }
        fingerprint.push(got.len() as u64);
    }
    Ok(())
}
