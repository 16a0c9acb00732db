//! Lines and circles of `zscan::raster` against the definitions in
//! `zscan_host::reference::bresenham`, the clipping property, and the `zscan lines` pattern.

use embedded_graphics::prelude::Point;
use std::collections::BTreeSet;
use zscan::output::Framebuffer;
use zscan::raster::circle::{draw_circle, MidpointCircle, MAX_RADIUS};
use zscan::raster::line::{draw_line, draw_polyline, Bresenham, Ends, LineError, MAX_COORD};
use zscan::raster::Window;
use zscan_host::cli::lines::{draw, pattern, Primitive};
use zscan_host::reference::bresenham as reference;

use zscan_host::test_rng::XorShift as Rng;

fn pt(p: (i64, i64)) -> Point {
    Point::new(p.0 as i32, p.1 as i32)
}

fn collect(it: Bresenham) -> Vec<(i64, i64)> {
    it.map(|p| (p.x as i64, p.y as i64)).collect()
}

fn win(w: &Window) -> (i64, i64, i64, i64) {
    (w.x0 as i64, w.y0 as i64, w.x1 as i64, w.y1 as i64)
}

#[test]
fn every_short_line_matches_the_definition_both_ways() {
    let r = 7;
    for y0 in -r..=r {
        for x0 in -r..=r {
            for y1 in -r..=r {
                for x1 in -r..=r {
                    let (p0, p1) = ((x0, y0), (x1, y1));
                    let closed = collect(Bresenham::new(pt(p0), pt(p1)));
                    assert_eq!(
                        closed,
                        reference::line_pixels(p0, p1, true),
                        "{p0:?}→{p1:?}"
                    );
                    let half = collect(Bresenham::half_open(pt(p0), pt(p1)));
                    assert_eq!(half, reference::line_pixels(p0, p1, false), "{p0:?}→{p1:?}");
                    // Symmetry: p1 → p0 gives the same pixels in reverse order.
                    let mut back = collect(Bresenham::new(pt(p1), pt(p0)));
                    back.reverse();
                    assert_eq!(back, closed, "{p0:?}↔{p1:?}");
                    // Exactly one pixel per major coordinate, 8-connected steps.
                    let n = (x1 - x0).abs().max((y1 - y0).abs());
                    assert_eq!(closed.len() as i64, n + 1);
                    for w in closed.windows(2) {
                        assert!((w[1].0 - w[0].0).abs() <= 1 && (w[1].1 - w[0].1).abs() <= 1);
                    }
                }
            }
        }
    }
}

#[test]
fn random_long_lines_match_the_definition() {
    let mut rng = Rng::new(0x5eed1);
    for i in 0..400 {
        // Long lines (up to 20 000 pixels) placed anywhere in ±2^30.
        let span = if i % 4 == 0 { 20_000 } else { 3_000 };
        let base = (
            rng.range(-(1 << 30) + span, (1 << 30) - span),
            rng.range(-(1 << 30) + span, (1 << 30) - span),
        );
        let p0 = (
            base.0 + rng.range(-span, span),
            base.1 + rng.range(-span, span),
        );
        let p1 = (
            base.0 + rng.range(-span, span),
            base.1 + rng.range(-span, span),
        );
        let got = collect(Bresenham::new(pt(p0), pt(p1)));
        assert_eq!(got, reference::line_pixels(p0, p1, true), "{p0:?}→{p1:?}");
        assert_eq!(Bresenham::new(pt(p0), pt(p1)).size_hint().0, got.len());
    }
}

#[test]
fn very_long_lines_sampled_against_the_definition() {
    // Lines of up to 2^31 pixels: check the count and the first pixels from each end (the
    // reversed line's first pixels are the last ones, by symmetry); the clipping tests below
    // check pixels deep inside such lines.
    let mut rng = Rng::new(77);
    let m = MAX_COORD as i64;
    for _ in 0..300 {
        let p0 = (rng.range(-m, m), rng.range(-m, m));
        let p1 = (rng.range(-m, m), rng.range(-m, m));
        if p0 == p1 {
            continue;
        }
        let it = Bresenham::new(pt(p0), pt(p1));
        let n = (p1.0 - p0.0).abs().max((p1.1 - p0.1).abs());
        assert_eq!(it.remaining(), n as u64 + 1);
        let head: Vec<(i64, i64)> = it.take(50).map(|p| (p.x as i64, p.y as i64)).collect();
        // line_pixels of a 2^31-pixel line would be too big: only for short ones.
        if n < 1 << 16 {
            let want: Vec<_> = reference::line_pixels(p0, p1, true);
            assert_eq!(head[..], want[..head.len()]);
        } else {
            let x_major = reference::x_major(p0, p1);
            let step = |a: i64, b: i64| if b > a { 1 } else { -1 };
            for (t, &p) in head.iter().enumerate() {
                let major = if x_major {
                    p0.0 + step(p0.0, p1.0) * t as i64
                } else {
                    p0.1 + step(p0.1, p1.1) * t as i64
                };
                assert_eq!(p, reference::pixel_at(p0, p1, major));
            }
        }
        let last = Bresenham::new(pt(p1), pt(p0)).next().unwrap();
        assert_eq!((last.x as i64, last.y as i64), p1);
        let tail: Vec<(i64, i64)> = Bresenham::new(pt(p1), pt(p0))
            .take(50)
            .map(|p| (p.x as i64, p.y as i64))
            .collect();
        let x_major = reference::x_major(p0, p1);
        for (t, &p) in tail.iter().enumerate() {
            let major = if x_major {
                p1.0 + if p0.0 > p1.0 { t as i64 } else { -(t as i64) }
            } else {
                p1.1 + if p0.1 > p1.1 { t as i64 } else { -(t as i64) }
            };
            assert_eq!(
                p,
                reference::pixel_at(p0, p1, major),
                "tail of {p0:?}→{p1:?}"
            );
        }
    }
}

const WINDOWS: [Window; 7] = [
    Window::new(0, 0, 5, 4),
    Window::new(2, 1, 3, 7),
    Window::new(0, 0, 1, 1),
    Window::new(-3, -2, 8, 9),
    Window::new(-6, -6, 11, 11), // holds every end point: always a trivial accept
    Window::new(4, 4, 4, 9),     // empty
    Window::new(6, -10, 20, 2),
];

#[test]
fn clipping_is_exactly_filtering_on_small_windows() {
    for w in &WINDOWS {
        for y0 in -6..=10 {
            for x0 in -6..=10 {
                for y1 in -6..=10 {
                    for x1 in -6..=10 {
                        let (p0, p1) = (Point::new(x0, y0), Point::new(x1, y1));
                        for ends in [Ends::Closed, Ends::HalfOpen] {
                            let want: Vec<Point> = Bresenham::with_ends(p0, p1, ends)
                                .filter(|p| w.contains(p.x, p.y))
                                .collect();
                            let it = Bresenham::clipped(p0, p1, ends, w).unwrap();
                            assert_eq!(it.remaining(), want.len() as u64);
                            let got: Vec<Point> = it.collect();
                            assert_eq!(got, want, "{p0:?}→{p1:?} {ends:?} in {w:?}");
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn clipping_large_coordinates_matches_the_definition() {
    let mut rng = Rng::new(0xC11B);
    let m = MAX_COORD as i64;
    let mut visible = 0;
    for i in 0..3000 {
        // End points near ±2^20, ±2^24 or anywhere up to ±2^30 (the extremes included).
        let lim = [1 << 20, 1 << 24, m][i % 3];
        let end = |rng: &mut Rng| match rng.next_u64() % 8 {
            0 => (lim, rng.range(-lim, lim)),
            1 => (rng.range(-lim, lim), -lim),
            _ => (rng.range(-lim, lim), rng.range(-lim, lim)),
        };
        let (p0, p1) = (end(&mut rng), end(&mut rng));
        if p0 == p1 {
            continue;
        }
        // A small window, placed on the line two times out of three, anywhere otherwise.
        let (w, h) = (rng.range(1, 40), rng.range(1, 40));
        let (ax, ay) = if i % 3 == 2 {
            (rng.range(-m, m - 40), rng.range(-m, m - 40))
        } else {
            let x_major = reference::x_major(p0, p1);
            let (a, b) = if x_major { (p0.0, p1.0) } else { (p0.1, p1.1) };
            let major = rng.range(a.min(b), a.max(b));
            let (x, y) = reference::pixel_at(p0, p1, major);
            (x - rng.range(0, w - 1), y - rng.range(0, h - 1))
        };
        let window = Window::new(ax as i32, ay as i32, (ax + w) as i32, (ay + h) as i32);
        for ends in [Ends::Closed, Ends::HalfOpen] {
            let it = Bresenham::clipped(pt(p0), pt(p1), ends, &window).unwrap();
            // O(window): never more pixels left than the window's longer side.
            assert!(it.remaining() <= w.max(h) as u64);
            let got = collect(it);
            let want = reference::clipped_line_pixels(p0, p1, ends == Ends::Closed, win(&window));
            assert_eq!(got, want, "{p0:?}→{p1:?} {ends:?} in {window:?}");
            visible += got.len();
        }
    }
    assert!(
        visible > 10_000,
        "the windows should mostly hit the lines ({visible})"
    );
}

#[test]
fn clipping_medium_lines_matches_filtered_iteration() {
    // Lines up to 2^12 long crossing windows, at coordinates beyond 2^20: the clipped iterator
    // against the unclipped one filtered.
    let mut rng = Rng::new(99);
    for _ in 0..2000 {
        let c = (
            rng.range(-(1 << 29), 1 << 29),
            rng.range(-(1 << 29), 1 << 29),
        );
        let r = 1 << 11;
        let p0 = (c.0 + rng.range(-r, r), c.1 + rng.range(-r, r));
        let p1 = (c.0 + rng.range(-r, r), c.1 + rng.range(-r, r));
        let (wx, wy) = (c.0 + rng.range(-300, 300), c.1 + rng.range(-300, 300));
        let window = Window::new(
            wx as i32,
            wy as i32,
            (wx + rng.range(0, 500)) as i32,
            (wy + rng.range(0, 500)) as i32,
        );
        let want: Vec<Point> = Bresenham::new(pt(p0), pt(p1))
            .filter(|p| window.contains(p.x, p.y))
            .collect();
        let got: Vec<Point> = Bresenham::clipped(pt(p0), pt(p1), Ends::Closed, &window)
            .unwrap()
            .collect();
        assert_eq!(got, want);
    }
}

#[test]
fn out_of_range_end_points_are_rejected_without_drawing() {
    let w = Window::new(0, 0, 10, 10);
    let bad = Point::new(MAX_COORD + 1, 3);
    assert_eq!(
        Bresenham::clipped(Point::new(1, 1), bad, Ends::Closed, &w),
        Err(LineError::CoordinateOutOfRange { point: bad })
    );
    let mut buf = vec![0u8; 100];
    let mut fb = Framebuffer::new(&mut buf, 10, 10).unwrap();
    assert!(draw_line(&mut fb, Point::new(i32::MIN, i32::MIN), Point::new(5, 5), 1).is_err());
    assert!(buf.iter().all(|&p| p == 0));
    // The extremes of the range are fine.
    let mut fb = Framebuffer::new(&mut buf, 10, 10).unwrap();
    draw_line(
        &mut fb,
        Point::new(-MAX_COORD, -MAX_COORD),
        Point::new(MAX_COORD, MAX_COORD),
        1,
    )
    .unwrap();
    for i in 0..10 {
        assert_eq!(fb.pixel(i, i), Some(1));
    }
    assert_eq!(buf.iter().filter(|&&p| p == 1).count(), 10);
}

#[test]
fn polyline_draws_each_joint_once() {
    // With counting through the iterators: half-open segments + last point = the union with
    // every joint once.
    let pts = [
        Point::new(1, 1),
        Point::new(8, 3),
        Point::new(4, 9),
        Point::new(1, 1),
    ];
    let mut count = 0;
    for s in pts.windows(2) {
        count += Bresenham::half_open(s[0], s[1]).count();
    }
    count += 1;
    let mut buf = vec![0u8; 12 * 12];
    let mut fb = Framebuffer::new(&mut buf, 12, 12).unwrap();
    draw_polyline(&mut fb, &pts, 5).unwrap();
    let set: BTreeSet<(i64, i64)> = pts
        .windows(2)
        .flat_map(|s| {
            reference::line_pixels(
                (s[0].x as i64, s[0].y as i64),
                (s[1].x as i64, s[1].y as i64),
                true,
            )
        })
        .collect();
    // The closed loop revisits (1,1): the half-open walk yields it twice (first and last).
    assert_eq!(count, set.len() + 1);
    for y in 0..12 {
        for x in 0..12 {
            let want = if set.contains(&(x as i64, y as i64)) {
                5
            } else {
                0
            };
            assert_eq!(fb.pixel(x, y), Some(want));
        }
    }
}

#[test]
fn circles_match_the_midpoint_definition() {
    for r in 0..=300u32 {
        let c = (3, -7);
        let got: Vec<(i64, i64)> = MidpointCircle::new(pt(c), r)
            .map(|p| (p.x as i64, p.y as i64))
            .collect();
        let set: BTreeSet<_> = got.iter().copied().collect();
        assert_eq!(set.len(), got.len(), "r {r}: a pixel was yielded twice");
        assert_eq!(set, reference::circle_pixels(c, r as i64), "r {r}");
    }
    // Large radii and centres near the i32 limits: compare counts and a sample of membership.
    for (c, r) in [
        ((0i64, 0i64), 100_000u32),
        ((i32::MAX as i64 - 5, 0), 50_000),
    ] {
        let got: BTreeSet<(i64, i64)> = MidpointCircle::new(pt(c), r)
            .map(|p| (p.x as i64, p.y as i64))
            .collect();
        let want: BTreeSet<(i64, i64)> = reference::circle_pixels(c, r as i64)
            .into_iter()
            .filter(|&(x, y)| i32::try_from(x).is_ok() && i32::try_from(y).is_ok())
            .collect();
        assert_eq!(got, want, "centre {c:?} r {r}");
    }
}

#[test]
fn clipped_circles_are_the_circle_filtered_to_the_frame() {
    let mut rng = Rng::new(4242);
    for i in 0..600 {
        let (w, h) = (rng.range(1, 40) as u16, rng.range(1, 30) as u16);
        let top = rng.range(0, 20) as u16;
        let r = if i % 5 == 0 {
            rng.range(0, MAX_RADIUS as i64) as u32
        } else {
            rng.range(0, 60) as u32
        };
        // Centres placed so that the outline often crosses the band.
        let side = rng.range(0, 3);
        let (cx, cy) = match side {
            0 => (rng.range(-20, 60), rng.range(-20, 60)),
            1 => (rng.range(-20, 60) - r as i64, rng.range(-20, 60)),
            _ => (rng.range(-20, 60), rng.range(-20, 60) + r as i64),
        };
        let mut buf = vec![0u8; w as usize * h as usize];
        let mut fb = Framebuffer::band(&mut buf, w, h, top).unwrap();
        draw_circle(&mut fb, pt((cx, cy)), r, 9).unwrap();
        let window = fb.window();
        // Expected: the definition, evaluated only over the rows of the band.
        let mut want = BTreeSet::new();
        for (x, y) in circle_pixels_in(cx, cy, r as i64, &window) {
            want.insert((x, y));
        }
        let mut got = BTreeSet::new();
        for (y, row) in fb.rows() {
            for (x, &v) in row.iter().enumerate() {
                if v == 9 {
                    got.insert((x as i64, y as i64));
                }
            }
        }
        assert_eq!(got, want, "c ({cx}, {cy}) r {r} band {w}×{h}@{top}");
    }
}

/// The circle's pixels inside `w` by the definition, cheap for huge radii: for every pixel of
/// the window, is it one of the eight reflections of an octant pixel?
fn circle_pixels_in(cx: i64, cy: i64, r: i64, w: &Window) -> Vec<(i64, i64)> {
    let mut out = Vec::new();
    for y in w.y0 as i64..w.y1 as i64 {
        for x in w.x0 as i64..w.x1 as i64 {
            let (dx, dy) = ((x - cx).abs(), (y - cy).abs());
            let on = if r == 0 {
                dx == 0 && dy == 0
            } else {
                // Octant coordinates: (small, large); on the outline iff large = y(small) and
                // small ≤ large.
                let (s, l) = (dx.min(dy), dx.max(dy));
                reference::circle_row(s, r) == Some(l) && s <= l
            };
            if on {
                out.push((x, y));
            }
        }
    }
    out
}

#[test]
fn pattern_draws_exactly_the_reference_pixels() {
    let (w, h) = (320u16, 240u16);
    let prims = pattern(w, h);
    let mut buf = vec![0u8; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut buf, w, h).unwrap();
    draw(&mut fb, &prims).unwrap();
    // Paint the reference, primitive by primitive, in the same order.
    let window = Window::of_size(w, h);
    let mut want = vec![0u8; w as usize * h as usize];
    let (mut lines, mut circles, mut far_lines) = (0, 0, 0);
    for p in &prims {
        let pixels: Vec<(i64, i64)> = match *p {
            Primitive::Line { p0, p1, .. } => {
                lines += 1;
                let (a, b) = ((p0.x as i64, p0.y as i64), (p1.x as i64, p1.y as i64));
                if !window.contains(p0.x, p0.y) && !window.contains(p1.x, p1.y) {
                    far_lines += 1;
                }
                reference::clipped_line_pixels(a, b, true, win(&window))
            }
            Primitive::Circle { centre, radius, .. } => {
                circles += 1;
                circle_pixels_in(centre.x as i64, centre.y as i64, radius as i64, &window)
            }
        };
        let index = match *p {
            Primitive::Line { index, .. } | Primitive::Circle { index, .. } => index,
        };
        for (x, y) in pixels {
            want[y as usize * w as usize + x as usize] = index;
        }
    }
    assert!(lines >= 48 + 4 && circles >= 8 && far_lines >= 4);
    assert_eq!(buf, want);
    // Something of every kind shows: the lit pixels are a good part of the frame.
    let lit = buf.iter().filter(|&&p| p != 0).count();
    assert!(lit > 3000, "{lit}");
}

#[test]
fn draw_line_into_bands_writes_exactly_the_clipped_pixels() {
    let mut rng = Rng::new(2024);
    for i in 0..1500 {
        let (w, h, top) = (
            rng.range(1, 48) as u16,
            rng.range(1, 24) as u16,
            rng.range(0, 40) as u16,
        );
        let lim = if i % 2 == 0 { 80 } else { MAX_COORD as i64 };
        let p0 = (rng.range(-lim, lim), rng.range(-lim, lim));
        // Often through the band: aim p1 through a pixel of it, far beyond.
        let p1 = if i % 3 == 0 {
            (rng.range(-lim, lim), rng.range(-lim, lim))
        } else {
            let (tx, ty) = (
                rng.range(0, w as i64 - 1),
                top as i64 + rng.range(0, h as i64 - 1),
            );
            let k = rng.range(1, 3);
            (
                (tx + k * (tx - p0.0)).clamp(-(MAX_COORD as i64), MAX_COORD as i64),
                (ty + k * (ty - p0.1)).clamp(-(MAX_COORD as i64), MAX_COORD as i64),
            )
        };
        let mut buf = vec![0u8; w as usize * h as usize];
        let mut fb = Framebuffer::band(&mut buf, w, h, top).unwrap();
        draw_line(&mut fb, pt(p0), pt(p1), 3).unwrap();
        let window = fb.window();
        let want: BTreeSet<(i64, i64)> = reference::clipped_line_pixels(p0, p1, true, win(&window))
            .into_iter()
            .collect();
        let mut got = BTreeSet::new();
        for (y, row) in fb.rows() {
            for (x, &v) in row.iter().enumerate() {
                if v == 3 {
                    got.insert((x as i64, y as i64));
                }
            }
        }
        assert_eq!(got, want, "{p0:?}→{p1:?} band {w}×{h}@{top}");
    }
}
