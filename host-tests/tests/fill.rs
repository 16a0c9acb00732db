//! The exact scanline fill (TIPE 2010) against the text's worked example and against the
//! independent winding-number reference (`zscan_host::reference::exact_fill`).
//!
//! Everything expected here is computed without the code under test: typed in from the text
//! (checked by hand in comments), or given by the reference, which tests each pixel's winding
//! number with exact `i128` cross-multiplication instead of walking edges.

use std::collections::{BTreeMap, BTreeSet};
use zscan::internals::{DivisionWalker, IncrementalWalker};
use zscan::raster::polygon::{fill_polygon, FillError, PolygonEdges};
use zscan::raster::triangle::{fill_triangle, fill_triangle_with};
use zscan::raster::MAX_COORD;
use zscan::raster::{Span, SubpixelPoint, Window};
use zscan_host::reference::exact_fill as reference;

/// Capacity used for random polygons (they have at most ~40 edges).
const CAP: usize = 64;

type V = (i64, i64);
type Pixels = BTreeSet<(i64, i64)>;

// ---------------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------------

use zscan_host::test_rng::XorShift as Rng;

fn pts<const S: u32>(v: &[V]) -> Vec<SubpixelPoint<S>> {
    v.iter()
        .map(|&(x, y)| SubpixelPoint::new(x as i32, y as i32))
        .collect()
}

fn wtuple(w: &Window) -> (i64, i64, i64, i64) {
    (w.x0 as i64, w.y0 as i64, w.x1 as i64, w.y1 as i64)
}

/// Checks the span stream contract (row order, left to right, maximal, non-empty, inside the
/// window) and adds every pixel to `counts`.
fn collect_spans(spans: &[Span], w: &Window, counts: &mut BTreeMap<(i64, i64), u32>, ctx: &str) {
    for (i, s) in spans.iter().enumerate() {
        assert!(s.x0 < s.x1, "{ctx}: empty span {s:?}");
        assert!(
            w.contains(s.x0, s.y) && w.contains(s.x1 - 1, s.y),
            "{ctx}: span {s:?} outside {w:?}"
        );
        if i > 0 {
            let p = spans[i - 1];
            assert!(
                p.y < s.y || (p.y == s.y && p.x1 < s.x0),
                "{ctx}: spans out of order or not maximal: {p:?} then {s:?}"
            );
        }
        for x in s.x0..s.x1 {
            *counts.entry((x as i64, s.y as i64)).or_insert(0) += 1;
        }
    }
}

fn polygon_spans<const S: u32, W: zscan::internals::EdgeWalker>(v: &[V], w: &Window) -> Vec<Span> {
    let e = PolygonEdges::<CAP>::build(&pts::<S>(v)).expect("build");
    let mut out = Vec::new();
    e.fill_with::<W, S>(w, |s| out.push(s));
    out
}

/// The production coverage of a polygon (default entry point), every pixel written once.
fn fill_pixels<const S: u32>(v: &[V], w: &Window) -> Pixels {
    let mut spans = Vec::new();
    fill_polygon::<S, CAP>(&pts::<S>(v), w, |s| spans.push(s)).expect("fill");
    let mut counts = BTreeMap::new();
    collect_spans(&spans, w, &mut counts, &format!("S={S} {v:?}"));
    assert!(counts.values().all(|&c| c == 1), "double write S={S} {v:?}");
    counts.into_keys().collect()
}

fn describe_diff(a: &Pixels, b: &Pixels) -> String {
    let only_a: Vec<_> = a.difference(b).take(8).collect();
    let only_b: Vec<_> = b.difference(a).take(8).collect();
    format!("only in fill: {only_a:?}; only in reference: {only_b:?}")
}

/// The window of a polygon's pixel bounding box, grown by `m` pixels on every side.
fn bbox_window<const S: u32>(v: &[V], m: i64) -> Window {
    let (x0, y0, x1, y1) = reference::pixel_bounds(v, S);
    Window::new(
        (x0 - m) as i32,
        (y0 - m) as i32,
        (x1 + m) as i32,
        (y1 + m) as i32,
    )
}

/// Full comparison of one polygon in one window: fill vs reference, both walkers, and, for
/// triangles, the triangle fast path (both walkers) vs the polygon path.
fn check<const S: u32>(v: &[V], w: &Window) {
    let got = fill_pixels::<S>(v, w);
    let want = reference::covered_pixels_in(v, S, wtuple(w));
    assert!(
        got == want,
        "S={S} window {w:?} polygon {v:?}: {}",
        describe_diff(&got, &want)
    );
    let a = polygon_spans::<S, DivisionWalker>(v, w);
    let b = polygon_spans::<S, IncrementalWalker>(v, w);
    assert_eq!(a, b, "walkers differ: S={S} {v:?} {w:?}");
    if v.len() == 3 {
        let t = [pts::<S>(v)[0], pts::<S>(v)[1], pts::<S>(v)[2]];
        let mut c = Vec::new();
        let mut d = Vec::new();
        fill_triangle(t, w, |s| c.push(s)).expect("triangle");
        fill_triangle_with::<DivisionWalker, S>(t, w, |s| d.push(s)).expect("triangle");
        assert_eq!(c, b, "triangle path vs polygon path: S={S} {v:?} {w:?}");
        assert_eq!(d, b, "triangle division walker: S={S} {v:?} {w:?}");
    }
}

/// Checks the polygon unclipped (its bounding box plus a margin) and in a few random windows,
/// and that the clipped coverage is the unclipped one intersected with the window.
fn check_with_windows<const S: u32>(v: &[V], rng: &mut Rng) {
    let big = bbox_window::<S>(v, 2);
    check::<S>(v, &big);
    let all = fill_pixels::<S>(v, &big);
    for _ in 0..2 {
        let (x0, y0) = (
            rng.range(big.x0 as i64 - 3, big.x1 as i64 + 1),
            rng.range(big.y0 as i64 - 3, big.y1 as i64 + 1),
        );
        let w = Window::new(
            x0 as i32,
            y0 as i32,
            (x0 + rng.range(0, 20)) as i32,
            (y0 + rng.range(0, 20)) as i32,
        );
        check::<S>(v, &w);
        let clipped = fill_pixels::<S>(v, &w);
        let expect: Pixels = all
            .iter()
            .copied()
            .filter(|&(x, y)| w.contains(x as i32, y as i32))
            .collect();
        assert_eq!(
            clipped, expect,
            "clipped != unclipped ∩ window: S={S} {v:?} {w:?}"
        );
    }
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 {
        a.abs()
    } else {
        gcd(b, a % b)
    }
}

fn cross(a: V, b: V, c: V) -> i128 {
    (b.0 - a.0) as i128 * (c.1 - a.1) as i128 - (b.1 - a.1) as i128 * (c.0 - a.0) as i128
}

// ---------------------------------------------------------------------------------------------
// Polygon generators (coordinates in units of 2^-S pixel; `r` is a radius in such units)
// ---------------------------------------------------------------------------------------------

fn random_points(rng: &mut Rng, n: usize, c: V, r: i64) -> Vec<V> {
    (0..n)
        .map(|_| (c.0 + rng.range(-r, r), c.1 + rng.range(-r, r)))
        .collect()
}

/// Convex hull (monotone chain), strictly convex.
fn convex(rng: &mut Rng, c: V, r: i64) -> Vec<V> {
    let n = rng.range(3, 14) as usize;
    let mut p = random_points(rng, n, c, r);
    p.sort_unstable();
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<V> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Vec<V> = if pass == 0 {
            p.clone()
        } else {
            p.iter().rev().copied().collect()
        };
        for q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    if rng.chance(50) {
        hull.reverse();
    }
    hull
}

/// Star-shaped around `c` (simple, usually not convex): sorted random angles, random radii.
fn star(rng: &mut Rng, c: V, r: i64) -> Vec<V> {
    let n = rng.range(3, 16) as usize;
    let mut ang: Vec<f64> = (0..n).map(|_| rng.unit() * std::f64::consts::TAU).collect();
    ang.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut v: Vec<V> = ang
        .iter()
        .map(|&a| {
            let rr = r as f64 * (0.15 + 0.85 * rng.unit());
            (
                c.0 + (rr * a.cos()).round() as i64,
                c.1 + (rr * a.sin()).round() as i64,
            )
        })
        .collect();
    if rng.chance(50) {
        v.reverse();
    }
    v
}

/// A star polygon with some edges made horizontal (and some vertical).
fn with_horizontals(rng: &mut Rng, c: V, r: i64) -> Vec<V> {
    let mut v = star(rng, c, r);
    let n = v.len();
    for i in 0..n {
        if rng.chance(40) {
            v[(i + 1) % n].1 = v[i].1;
        } else if rng.chance(15) {
            v[(i + 1) % n].0 = v[i].0;
        }
    }
    v
}

/// Inserts repeated vertices, points exactly on edges (collinear) and zero-area spikes.
fn with_collinear(rng: &mut Rng, base: Vec<V>) -> Vec<V> {
    let mut out = Vec::new();
    let n = base.len();
    for i in 0..n {
        let (a, b) = (base[i], base[(i + 1) % n]);
        out.push(a);
        if rng.chance(25) {
            out.push(a); // repeated vertex
        }
        let g = gcd(b.0 - a.0, b.1 - a.1);
        if g > 1 && rng.chance(50) {
            // A lattice point strictly inside the edge: collinear with both ends.
            let k = rng.range(1, g - 1);
            out.push((a.0 + (b.0 - a.0) / g * k, a.1 + (b.1 - a.1) / g * k));
        }
        if rng.chance(10) {
            // A spike out and back along the same line: zero area.
            let t = rng.range(1, 3);
            out.push((a.0 + (a.0 - b.0) * t / 3, a.1 + (a.1 - b.1) * t / 3));
            out.push(a);
        }
    }
    out
}

/// A thin sliver: a triangle or quadrilateral whose vertices are nearly collinear.
fn sliver(rng: &mut Rng, c: V, r: i64) -> Vec<V> {
    let a = (c.0 + rng.range(-r, r), c.1 + rng.range(-r, r));
    let b = (c.0 + rng.range(-r, r), c.1 + rng.range(-r, r));
    let g = gcd(b.0 - a.0, b.1 - a.1).max(1);
    let k = rng.range(0, g);
    let on = (a.0 + (b.0 - a.0) / g * k, a.1 + (b.1 - a.1) / g * k);
    let m = (on.0 + rng.range(-2, 2), on.1 + rng.range(-2, 2));
    if rng.chance(50) {
        vec![a, m, b]
    } else {
        let m2 = (on.0 + rng.range(-2, 2), on.1 + rng.range(-2, 2));
        vec![a, m, b, m2]
    }
}

/// Random vertices in random order: usually self-intersecting (nonzero winding rule).
fn tangle(rng: &mut Rng, c: V, r: i64) -> Vec<V> {
    let n = rng.range(4, 10) as usize;
    random_points(rng, n, c, r)
}

/// One random polygon of the given kind, around `c` with radius `r` (units).
fn polygon_of_kind(kind: usize, rng: &mut Rng, c: V, r: i64) -> Vec<V> {
    match kind {
        0 => convex(rng, c, r),
        1 => star(rng, c, r),
        2 => with_horizontals(rng, c, r),
        3 => {
            let base = if rng.chance(50) {
                convex(rng, c, r)
            } else {
                with_horizontals(rng, c, r)
            };
            with_collinear(rng, base)
        }
        4 => sliver(rng, c, r),
        _ => tangle(rng, c, r),
    }
}

// ---------------------------------------------------------------------------------------------
// The TIPE annex (figure 8)
// ---------------------------------------------------------------------------------------------

/// The polygon of the annex, rebuilt from its TAG/TAD tables: following the cycle, each edge
/// along which y increases is one of TAG (A0 A2 A5 A6 A7 A10 A11), each along which it
/// decreases one of TAD with its ends swapped (A1 A3 A4 A8 A9 A12 A13 A14 A15), and the five
/// remaining edges are horizontal: (15,2)-(13,2), (7,2)-(5,2), (5,10)-(8,10), (13,12)-(16,12),
/// (20,8)-(17,8). 21 vertices = 16 non-horizontal + 5 horizontal edges.
const ANNEX: [V; 21] = [
    (17, 0),
    (15, 2),
    (13, 2),
    (11, 0),
    (9, 4),
    (7, 2),
    (5, 2),
    (1, 0),
    (5, 4),
    (1, 8),
    (1, 12),
    (5, 10),
    (8, 10),
    (10, 6),
    (13, 12),
    (16, 12),
    (18, 14),
    (20, 13),
    (20, 8),
    (17, 8),
    (21, 4),
];

/// TAG of the annex, typed in from the text: (xbas, ybas, xhaut, yhaut).
const TAG: [(i32, i32, i32, i32); 7] = [
    (17, 0, 15, 2),   // A0
    (11, 0, 9, 4),    // A2
    (1, 0, 5, 4),     // A5
    (5, 4, 1, 8),     // A6
    (1, 8, 1, 12),    // A7
    (10, 6, 13, 12),  // A10
    (16, 12, 18, 14), // A11
];

/// TAD of the annex, typed in from the text.
const TAD: [(i32, i32, i32, i32); 9] = [
    (11, 0, 13, 2),   // A1
    (7, 2, 9, 4),     // A3
    (1, 0, 5, 2),     // A4
    (5, 10, 1, 12),   // A8
    (10, 6, 8, 10),   // A9
    (20, 13, 18, 14), // A12
    (20, 8, 20, 13),  // A13
    (21, 4, 17, 8),   // A14
    (17, 0, 21, 4),   // A15
];

/// The xG table of the annex, rows y = 0..13, each row sorted (typed in from the text).
const XG: [&[i32]; 14] = [
    &[1, 11, 17],
    &[2, 11, 16],
    &[3, 10],
    &[4, 10],
    &[5],
    &[4],
    &[3, 10],
    &[2, 11],
    &[1, 11],
    &[1, 12],
    &[1, 12],
    &[1, 13],
    &[16],
    &[17],
];

/// The xD table of the annex, rows y = 0..13. Rows 0..6 are typed in from the text. The copy
/// of the text is truncated for rows ≥ 7 in one column; those rows are derived by hand with
/// xD = ⌈x_e⌉ − 1 on the right edges covering the row (exactly TIPE's `N ← −1` initialisation):
/// - A9 (10,6)→(8,10): x_e = 10 − (y−6)/2: y=7: 9.5 → 9; y=8: 9 → 8; y=9: 8.5 → 8.
/// - A14 (21,4)→(17,8): x_e = 21 − (y−4): y=7: 18 → 17.
/// - A13 (20,8)→(20,13): x_e = 20 → 19 on rows 8..12.
/// - A8 (5,10)→(1,12): x_e = 5 − 2(y−10): y=10: 5 → 4; y=11: 3 → 2.
/// - A12 (20,13)→(18,14): y=13: 20 → 19.
///
/// which agrees with the entries that are legible: (9, 17), (8, 19), (8, 19), (4, 19), (2, 19),
/// (19), (19).
const XD: [&[i32]; 14] = [
    &[0, 10, 16],
    &[2, 11, 17],
    &[6, 18],
    &[7, 19],
    &[20],
    &[19],
    &[9, 18],
    &[9, 17],
    &[8, 19],
    &[8, 19],
    &[4, 19],
    &[2, 19],
    &[19],
    &[19],
];

#[test]
fn tipe_annex_tables() {
    let e = PolygonEdges::<32>::build(&pts::<0>(&ANNEX)).unwrap();
    let as_set = |edges: &[zscan::internals::Edge]| -> BTreeSet<(i32, i32, i32, i32)> {
        edges.iter().map(|e| (e.x0, e.y0, e.x1, e.y1)).collect()
    };
    assert_eq!(e.left_edges().len(), 7);
    assert_eq!(e.right_edges().len(), 9);
    assert_eq!(as_set(e.left_edges()), TAG.iter().copied().collect());
    assert_eq!(as_set(e.right_edges()), TAD.iter().copied().collect());
    for y in -2..16 {
        let (xg, xd) = e.row_ends::<0>(y);
        let (want_g, want_d): (&[i32], &[i32]) = if (0..14).contains(&y) {
            (XG[y as usize], XD[y as usize])
        } else {
            (&[], &[])
        };
        assert_eq!(&xg[..], want_g, "xG row {y}");
        assert_eq!(&xd[..], want_d, "xD row {y}");
    }
    // The other orientation swaps the roles: TAG and TAD exchange.
    let rev: Vec<V> = ANNEX.iter().rev().copied().collect();
    let r = PolygonEdges::<32>::build(&pts::<0>(&rev)).unwrap();
    assert_eq!(as_set(r.left_edges()), TAD.iter().copied().collect());
    assert_eq!(as_set(r.right_edges()), TAG.iter().copied().collect());
}

#[test]
fn tipe_annex_pixels() {
    // Step 6 of `Remplissage`: row y covers xG[y,k] ..= xD[y,k] for each k (pairs from the
    // tables above). Row 0 pairs (1,0) (11,10) (17,16) are all empty: the vertices S11, S14,
    // S18 of the text are not drawn. Row 6 pairs (3,9) (10,18) touch: 3..=18, the text's
    // "(3, 19)". Row 4 is the text's "(5, 21)", row 10 starts with "(1, 5)", row 2 is
    // "(3, 7, 10, 19)", row 13 is "(17, 20)".
    let mut want = Pixels::new();
    for y in 0..14 {
        for (g, d) in XG[y].iter().zip(XD[y].iter()) {
            for x in *g..=*d {
                want.insert((x as i64, y as i64));
            }
        }
    }
    let row = |set: &Pixels, y: i64| -> Vec<i64> {
        set.iter().filter(|p| p.1 == y).map(|p| p.0).collect()
    };
    assert!(row(&want, 0).is_empty());
    assert_eq!(row(&want, 6), (3..=18).collect::<Vec<_>>());
    assert_eq!(row(&want, 4), (5..=20).collect::<Vec<_>>());
    assert_eq!(row(&want, 13), (17..=19).collect::<Vec<_>>());
    assert_eq!(row(&want, 2), (3..=6).chain(10..=18).collect::<Vec<_>>());
    assert_eq!(row(&want, 10)[..4], [1, 2, 3, 4]);
    assert_eq!(row(&want, 10)[4], 12);

    // The reference agrees with the text.
    assert_eq!(reference::covered_pixels(&ANNEX, 0), want);
    // And the fill (both walkers, both orientations, S = 0 and the same polygon at S = 4).
    let w = Window::new(-5, -5, 30, 30);
    assert_eq!(fill_pixels::<0>(&ANNEX, &w), want);
    check::<0>(&ANNEX, &w);
    let rev: Vec<V> = ANNEX.iter().rev().copied().collect();
    assert_eq!(fill_pixels::<0>(&rev, &w), want);
    let sub: Vec<V> = ANNEX.iter().map(|&(x, y)| (x * 16, y * 16)).collect();
    assert_eq!(fill_pixels::<4>(&sub, &w), want);
}

// ---------------------------------------------------------------------------------------------
// Random polygons vs the reference
// ---------------------------------------------------------------------------------------------

fn random_polygons<const S: u32>(seed: u64, per_kind: usize) {
    let f = 1i64 << S;
    let mut rng = Rng::new(seed);
    for kind in 0..6 {
        for i in 0..per_kind {
            // Small (a few pixels: sub-pixel placement matters) and medium polygons.
            let r = if i % 3 == 0 {
                rng.range(f / 2 + 1, 4 * f)
            } else {
                rng.range(4 * f, 18 * f)
            };
            let c = (rng.range(-30 * f, 30 * f), rng.range(-30 * f, 30 * f));
            let v = polygon_of_kind(kind, &mut rng, c, r);
            check_with_windows::<S>(&v, &mut rng);
        }
    }
}

#[test]
fn random_polygons_integer_vertices() {
    random_polygons::<0>(0x1234_5678_9ABC_DEF1, 250);
}

#[test]
fn random_polygons_subpixel_4() {
    random_polygons::<4>(0x0F0F_1234_AAAA_5555, 250);
}

#[test]
fn random_polygons_subpixel_2_and_8() {
    random_polygons::<2>(0x7777_1111_2222_3333, 150);
    random_polygons::<8>(0xDEAD_BEEF_0BAD_F00D, 150);
}

#[test]
fn random_triangles_all_paths() {
    fn run<const S: u32>(seed: u64, n: usize) {
        let f = 1i64 << S;
        let mut rng = Rng::new(seed);
        for i in 0..n {
            let r = if i % 2 == 0 { 3 * f } else { 15 * f };
            let c = (rng.range(-5 * f, 5 * f), rng.range(-5 * f, 5 * f));
            let v = if i % 5 == 0 {
                sliver(&mut rng, c, r)[..3].to_vec()
            } else {
                random_points(&mut rng, 3, c, r)
            };
            check_with_windows::<S>(&v, &mut rng);
        }
    }
    run::<0>(11, 1500);
    run::<4>(12, 1500);
    run::<2>(13, 600);
    run::<8>(14, 600);
}

#[test]
fn named_self_intersecting_polygons() {
    let w = Window::new(-2, -2, 30, 30);
    // Pentagram: its centre has winding ±2 and is filled (nonzero), unlike even-odd.
    let star: [V; 5] = [(10, 0), (16, 19), (0, 7), (20, 7), (4, 19)];
    let got = fill_pixels::<0>(&star, &w);
    assert!(got.contains(&(10, 10)));
    check::<0>(&star, &w);
    // Figure eight (bow tie): both lobes, opposite windings.
    let bow: [V; 4] = [(0, 0), (10, 10), (10, 0), (0, 10)];
    let got = fill_pixels::<0>(&bow, &w);
    assert!(got.contains(&(1, 5)) && got.contains(&(9, 5)));
    assert!(!got.contains(&(5, 1)));
    check::<0>(&bow, &w);
    // A square traversed twice: winding 2 everywhere inside, same pixels as once.
    let twice: [V; 8] = [
        (0, 0),
        (8, 0),
        (8, 8),
        (0, 8),
        (0, 0),
        (8, 0),
        (8, 8),
        (0, 8),
    ];
    let once = fill_pixels::<0>(&twice[..4], &w);
    assert_eq!(fill_pixels::<0>(&twice, &w), once);
    assert_eq!(once.len(), 64);
    check::<0>(&twice, &w);
}

// ---------------------------------------------------------------------------------------------
// Watertightness: meshes tiling a region
// ---------------------------------------------------------------------------------------------

type Tri = [V; 3];

/// Counts, per pixel, how often the triangles of a mesh write it (triangle path), checks the
/// polygon path writes the same, and compares with the reference coverage of the outline:
/// every covered pixel exactly once, nothing else.
fn check_mesh<const S: u32>(tris: &[Tri], outline: &[V], w: &Window, ctx: &str) {
    let mut counts = BTreeMap::new();
    let mut counts_poly = BTreeMap::new();
    for t in tris {
        let p = pts::<S>(t);
        let mut spans = Vec::new();
        fill_triangle([p[0], p[1], p[2]], w, |s| spans.push(s)).unwrap();
        collect_spans(&spans, w, &mut counts, ctx);
        let mut spans = Vec::new();
        fill_polygon::<S, 3>(&p, w, |s| spans.push(s)).unwrap();
        collect_spans(&spans, w, &mut counts_poly, ctx);
    }
    assert_eq!(counts, counts_poly, "{ctx}: triangle vs polygon path");
    let doubles: Vec<_> = counts.iter().filter(|(_, &c)| c > 1).take(5).collect();
    assert!(
        doubles.is_empty(),
        "{ctx}: pixels written twice {doubles:?} in {w:?}"
    );
    let want = reference::covered_pixels_in(outline, S, wtuple(w));
    let got: Pixels = counts.keys().copied().collect();
    assert!(
        got == want,
        "{ctx}: window {w:?}: {}\n outline {outline:?}",
        describe_diff(&got, &want)
    );
}

fn check_mesh_windows<const S: u32>(tris: &[Tri], outline: &[V], rng: &mut Rng, ctx: &str) {
    let big = bbox_window::<S>(outline, 1);
    check_mesh::<S>(tris, outline, &big, ctx);
    // A window cutting through the mesh.
    let (x0, y0) = (
        rng.range(big.x0 as i64, big.x1 as i64),
        rng.range(big.y0 as i64, big.y1 as i64),
    );
    let w = Window::new(
        x0 as i32,
        y0 as i32,
        (x0 + rng.range(1, 25)) as i32,
        (y0 + rng.range(1, 25)) as i32,
    );
    check_mesh::<S>(tris, outline, &w, ctx);
}

/// A fan around an interior point `c` of a star-shaped outline; `None` when rounding broke
/// the angular order (the caller draws again).
fn fan(rng: &mut Rng, f: i64) -> Option<(Vec<Tri>, Vec<V>)> {
    let n = rng.range(4, 18) as usize;
    let c = (rng.range(-8 * f, 8 * f), rng.range(-8 * f, 8 * f));
    let r = rng.range(2 * f, 16 * f) as f64;
    let step = std::f64::consts::TAU / n as f64;
    let phase = rng.unit() * step;
    let outline: Vec<V> = (0..n)
        .map(|i| {
            // Gaps between consecutive angles stay below 1.8·step ≤ 0.9π (n ≥ 4).
            let a = phase + (i as f64 + 0.8 * rng.unit()) * step;
            let rr = r * (0.3 + 0.7 * rng.unit());
            (
                c.0 + (rr * a.cos()).round() as i64,
                c.1 + (rr * a.sin()).round() as i64,
            )
        })
        .collect();
    let tris: Vec<Tri> = (0..n)
        .map(|i| [c, outline[i], outline[(i + 1) % n]])
        .collect();
    // Every triangle strictly positive (same orientation), so the fan wraps exactly once.
    if tris.iter().any(|t| cross(t[0], t[1], t[2]) <= 0) {
        return None;
    }
    Some((tris, outline))
}

/// A grid of `nx × ny` cells with jittered vertices, each cell split along a random diagonal.
fn grid(rng: &mut Rng, f: i64) -> (Vec<Tri>, Vec<V>) {
    let (nx, ny) = (rng.range(1, 6) as usize, rng.range(1, 6) as usize);
    let sp = rng.range(2 * f, 7 * f);
    // |jitter| < sp/8 keeps every triangle positively oriented.
    let j = ((sp - 1) / 8).max(0);
    let o = (rng.range(-10 * f, 10 * f), rng.range(-10 * f, 10 * f));
    let mut p = vec![vec![(0i64, 0i64); ny + 1]; nx + 1];
    for (i, col) in p.iter_mut().enumerate() {
        for (k, q) in col.iter_mut().enumerate() {
            *q = (
                o.0 + i as i64 * sp + rng.range(-j, j),
                o.1 + k as i64 * sp + rng.range(-j, j),
            );
        }
    }
    let mut tris = Vec::new();
    for i in 0..nx {
        for k in 0..ny {
            let (a, b, c, d) = (p[i][k], p[i + 1][k], p[i + 1][k + 1], p[i][k + 1]);
            if rng.chance(50) {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            } else {
                tris.push([a, b, d]);
                tris.push([b, c, d]);
            }
        }
    }
    // Counter-clockwise in the grid's index space: bottom row, right column, top row back,
    // left column back.
    let mut outline: Vec<V> = Vec::new();
    outline.extend(p.iter().take(nx).map(|col| col[0]));
    outline.extend(p[nx].iter().take(ny).copied());
    outline.extend(p.iter().skip(1).rev().map(|col| col[ny]));
    outline.extend(p[0].iter().skip(1).rev().copied());
    (tris, outline)
}

/// A triangle strip between a top and a bottom polyline (optionally transposed into a
/// vertical strip); `None` when a triangle came out flat or flipped.
fn strip(rng: &mut Rng, f: i64) -> Option<(Vec<Tri>, Vec<V>)> {
    let n = rng.range(1, 10) as usize;
    let (mut xt, mut xb) = (rng.range(-4 * f, 4 * f), rng.range(-4 * f, 4 * f));
    let mut top = Vec::new();
    let mut bot = Vec::new();
    for _ in 0..=n {
        top.push((xt, rng.range(0, 6 * f)));
        bot.push((xb, rng.range(9 * f, 16 * f)));
        xt += rng.range(f, 6 * f);
        xb += rng.range(f, 6 * f);
    }
    let mut tris = Vec::new();
    for i in 0..n {
        tris.push([top[i], bot[i], top[i + 1]]);
        tris.push([top[i + 1], bot[i], bot[i + 1]]);
    }
    let mut outline: Vec<V> = top.clone();
    outline.extend(bot.iter().rev());
    let sign = cross(tris[0][0], tris[0][1], tris[0][2]).signum();
    if sign == 0
        || tris
            .iter()
            .any(|t| cross(t[0], t[1], t[2]).signum() != sign)
    {
        return None;
    }
    if rng.chance(50) {
        let tr = |p: &V| (p.1, p.0);
        tris = tris
            .iter()
            .map(|t| [tr(&t[0]), tr(&t[1]), tr(&t[2])])
            .collect();
        outline = outline.iter().map(tr).collect();
    }
    Some((tris, outline))
}

fn watertight<const S: u32>(seed: u64, n: usize) {
    let f = 1i64 << S;
    let mut rng = Rng::new(seed);
    let (mut fans, mut strips) = (0, 0);
    for i in 0..n {
        if let Some((t, o)) = fan(&mut rng, f) {
            fans += 1;
            check_mesh_windows::<S>(&t, &o, &mut rng, &format!("S={S} fan {i}"));
        }
        let (t, o) = grid(&mut rng, f);
        check_mesh_windows::<S>(&t, &o, &mut rng, &format!("S={S} grid {i}"));
        if let Some((t, o)) = strip(&mut rng, f) {
            strips += 1;
            check_mesh_windows::<S>(&t, &o, &mut rng, &format!("S={S} strip {i}"));
        }
    }
    // The generators must not silently skip most meshes.
    assert!(fans > n / 2, "only {fans} fans of {n}");
    assert!(strips > n / 4, "only {strips} strips of {n}");
}

/// Meshes with coordinates up to ±MAX_COORD, watched through small windows: a fan of huge
/// triangles (windows on its spokes, the edges shared by two triangles) and small meshes moved
/// into the corners of the range.
fn huge_meshes<const S: u32>(seed: u64, n: usize) {
    let m = MAX_COORD as i64;
    let f = 1i64 << S;
    let mut rng = Rng::new(seed);
    let mut fans = 0;
    for i in 0..n {
        // Points along the boundary of the square [−m, m]², its corners included, in order.
        let mut pos: Vec<i64> = (0..4).map(|k| 2 * m * k).collect();
        for _ in 0..rng.range(0, 8) {
            pos.push(rng.range(0, 8 * m - 1));
        }
        pos.sort_unstable();
        pos.dedup();
        let outline: Vec<V> = pos
            .iter()
            .map(|&p| {
                let (side, d) = (p / (2 * m), p % (2 * m));
                let mut q = match side {
                    0 => (-m + d, -m),
                    1 => (m, -m + d),
                    2 => (m - d, m),
                    _ => (-m, m - d),
                };
                // Some points pulled inwards (the fan stays valid if every triangle does).
                if rng.chance(30) {
                    q = (q.0 - q.0.signum() * rng.range(0, m / 3), q.1);
                }
                q
            })
            .collect();
        let c = (rng.range(-m / 2, m / 2), rng.range(-m / 2, m / 2));
        let k = outline.len();
        let tris: Vec<Tri> = (0..k)
            .map(|j| [c, outline[j], outline[(j + 1) % k]])
            .collect();
        if tris.iter().any(|t| cross(t[0], t[1], t[2]) <= 0) {
            continue;
        }
        fans += 1;
        for _ in 0..4 {
            let t = &tris[rng.range(0, k as i64 - 1) as usize];
            let (a, b) = if rng.chance(70) {
                (t[0], t[1])
            } else {
                (t[1], t[2])
            };
            let u = rng.unit();
            let px = ((a.0 as f64 + u * (b.0 - a.0) as f64) / f as f64).floor() as i64;
            let py = ((a.1 as f64 + u * (b.1 - a.1) as f64) / f as f64).floor() as i64;
            let w = Window::new(
                (px - 10) as i32,
                (py - 10) as i32,
                (px + 10) as i32,
                (py + 10) as i32,
            );
            check_mesh::<S>(&tris, &outline, &w, &format!("S={S} huge fan {i}"));
        }
        // A small grid moved into a corner of the range.
        let (t, o) = grid(&mut rng, f);
        let (x0, y0, x1, y1) = (
            o.iter().map(|p| p.0).min().unwrap(),
            o.iter().map(|p| p.1).min().unwrap(),
            o.iter().map(|p| p.0).max().unwrap(),
            o.iter().map(|p| p.1).max().unwrap(),
        );
        let d = match i % 4 {
            0 => (m - x1, m - y1),
            1 => (-m - x0, m - y1),
            2 => (m - x1, -m - y0),
            _ => (-m - x0, -m - y0),
        };
        let mv = |p: &V| (p.0 + d.0, p.1 + d.1);
        let t: Vec<Tri> = t
            .iter()
            .map(|t| [mv(&t[0]), mv(&t[1]), mv(&t[2])])
            .collect();
        let o: Vec<V> = o.iter().map(mv).collect();
        check_mesh_windows::<S>(&t, &o, &mut rng, &format!("S={S} corner grid {i}"));
    }
    assert!(fans > n / 2, "only {fans} huge fans of {n}");
}

#[test]
fn meshes_at_extreme_coordinates_are_watertight() {
    huge_meshes::<0>(0xB16_0000, 60);
    huge_meshes::<4>(0xB16_0004, 60);
    huge_meshes::<16>(0xB16_0016, 60);
}

#[test]
fn meshes_are_watertight_integer() {
    watertight::<0>(0xA5A5_5A5A_1234_4321, 250);
}

#[test]
fn meshes_are_watertight_subpixel() {
    watertight::<4>(0x5EED_0000_0000_0004, 250);
    watertight::<2>(0x5EED_0000_0000_0002, 120);
    watertight::<8>(0x5EED_0000_0000_0008, 120);
}

// ---------------------------------------------------------------------------------------------
// Windows: extreme coordinates, far away windows
// ---------------------------------------------------------------------------------------------

/// Polygons with vertices anywhere in ±MAX_COORD (many exactly at the limits), looked at
/// through small windows placed on their edges: the fill in the window equals the reference in
/// the window and the fill in a larger window cut down to it.
fn extreme<const S: u32>(seed: u64, n: usize) {
    let m = MAX_COORD as i64;
    let mut rng = Rng::new(seed);
    let pick = |rng: &mut Rng| -> i64 {
        match rng.range(0, 4) {
            0 => m,
            1 => -m,
            2 => rng.range(m - 40, m),
            3 => rng.range(-m, -m + 40),
            _ => rng.range(-m, m),
        }
    };
    for _ in 0..n {
        let k = rng.range(3, 7) as usize;
        let v: Vec<V> = (0..k).map(|_| (pick(&mut rng), pick(&mut rng))).collect();
        for j in 0..4 {
            let (px, py) = if j < 3 {
                // A pixel on (or next to) a random edge.
                let i = rng.range(0, k as i64 - 1) as usize;
                let (a, b) = (v[i], v[(i + 1) % k]);
                let t = rng.unit();
                let f = (1u64 << S) as f64;
                (
                    ((a.0 as f64 + t * (b.0 - a.0) as f64) / f).floor() as i64,
                    ((a.1 as f64 + t * (b.1 - a.1) as f64) / f).floor() as i64,
                )
            } else {
                // Anywhere: deep inside, or far outside the polygon.
                let r = m >> S;
                (rng.range(-r, r), rng.range(-r, r))
            };
            let w = Window::new(
                (px - 12) as i32,
                (py - 12) as i32,
                (px + 12) as i32,
                (py + 12) as i32,
            );
            let got = fill_pixels::<S>(&v, &w);
            let want = reference::covered_pixels_in(&v, S, wtuple(&w));
            assert!(
                got == want,
                "S={S} {v:?} {w:?}: {}",
                describe_diff(&got, &want)
            );
            let a = polygon_spans::<S, DivisionWalker>(&v, &w);
            let b = polygon_spans::<S, IncrementalWalker>(&v, &w);
            assert_eq!(a, b, "walkers S={S} {v:?} {w:?}");
            let big = Window::new(w.x0 - 7, w.y0 - 3, w.x1 + 5, w.y1 + 9);
            let cut: Pixels = fill_pixels::<S>(&v, &big)
                .into_iter()
                .filter(|&(x, y)| w.contains(x as i32, y as i32))
                .collect();
            assert_eq!(got, cut, "clipped != unclipped ∩ window: S={S} {v:?} {w:?}");
            if k == 3 {
                let p = pts::<S>(&v);
                let mut c = Vec::new();
                fill_triangle([p[0], p[1], p[2]], &w, |s| c.push(s)).unwrap();
                assert_eq!(c, b, "triangle path S={S} {v:?} {w:?}");
            }
        }
    }
}

#[test]
fn extreme_coordinates_in_small_windows() {
    extreme::<0>(101, 150);
    extreme::<4>(102, 150);
    extreme::<16>(103, 150);
}

#[test]
fn windows_far_from_the_polygon_and_huge_windows() {
    let mut rng = Rng::new(77);
    for _ in 0..200 {
        let v = star(&mut rng, (0, 0), 200);
        let far = [
            Window::new(1000, 1000, 1100, 1100),
            Window::new(-1_000_000, -1_000_000, -999_000, -999_000),
            Window::new(i32::MIN, i32::MIN, i32::MIN + 10, i32::MIN + 10),
            Window::new(i32::MAX - 10, i32::MAX - 10, i32::MAX, i32::MAX),
            Window::new(-50, 20, -10, 5), // empty (y1 < y0)
            Window::new(5, -50, 5, 50),   // empty (x1 = x0)
        ];
        for w in far {
            let mut n = 0;
            fill_polygon::<4, CAP>(&pts::<4>(&v), &w, |_| n += 1).unwrap();
            assert_eq!(n, 0, "{v:?} {w:?}");
        }
        // The whole i32 plane as window: same as the bounding box.
        let huge = Window::new(i32::MIN, i32::MIN, i32::MAX, i32::MAX);
        let bb = bbox_window::<4>(&v, 0);
        assert_eq!(fill_pixels::<4>(&v, &huge), fill_pixels::<4>(&v, &bb));
        check::<4>(&v, &huge);
    }
    // A polygon far outside a screen-sized window, at the coordinate limits.
    let m = MAX_COORD as i64;
    let v: [V; 3] = [(m, m), (m - 1000, m), (m, m - 1000)];
    let mut n = 0;
    fill_polygon::<0, 8>(&pts::<0>(&v), &Window::of_size(320, 240), |_| n += 1).unwrap();
    fill_triangle(
        [pts::<0>(&v)[0], pts::<0>(&v)[1], pts::<0>(&v)[2]],
        &Window::of_size(320, 240),
        |_| n += 1,
    )
    .unwrap();
    assert_eq!(n, 0);
}

// ---------------------------------------------------------------------------------------------
// Degenerate input and errors
// ---------------------------------------------------------------------------------------------

#[test]
fn degenerate_polygons_cover_nothing() {
    let w = Window::new(-50, -50, 50, 50);
    let cases: Vec<Vec<V>> = vec![
        vec![],
        vec![(3, 3)],
        vec![(0, 0), (10, 10)],
        vec![(0, 0), (10, 10), (0, 0)],
        vec![(5, 5), (5, 5), (5, 5)],
        vec![(0, 0), (4, 2), (8, 4)],                 // collinear
        vec![(0, 0), (8, 4), (4, 2), (-4, -2)],       // collinear, back and forth
        vec![(0, 0), (10, 0), (20, 0)],               // horizontal
        vec![(3, -5), (3, 5), (3, 9)],                // vertical
        vec![(0, 0), (6, 6), (6, 6), (0, 0), (6, 6)], // repeated
    ];
    fn run<const S: u32>(v: &[V], w: &Window) {
        let mut n = 0;
        fill_polygon::<S, 8>(&pts::<S>(v), w, |_| n += 1).unwrap();
        let e = PolygonEdges::<8>::build(&pts::<S>(v)).unwrap();
        e.fill_with::<DivisionWalker, S>(w, |_| n += 1);
        if v.len() == 3 {
            let p = pts::<S>(v);
            fill_triangle([p[0], p[1], p[2]], w, |_| n += 1).unwrap();
            fill_triangle_with::<DivisionWalker, S>([p[0], p[1], p[2]], w, |_| n += 1).unwrap();
        }
        assert_eq!(n, 0, "S={S} {v:?}");
        assert!(
            reference::covered_pixels(v, S).is_empty(),
            "reference {v:?}"
        );
    }
    for v in &cases {
        run::<0>(v, &w);
        run::<4>(v, &w);
    }
    // A sub-pixel triangle that contains no lattice point covers nothing, Ok.
    let tiny = [(1, 1), (14, 2), (3, 15)]; // inside (0,1)² at S = 4
    run::<4>(&tiny, &w);
}

#[test]
fn errors_are_reported_and_nothing_is_drawn() {
    let w = Window::new(-20, -20, 20, 20);
    let mut n = 0;
    // A zigzag with 6 non-horizontal edges, capacity 5.
    let zig: [V; 6] = [(0, 0), (9, 1), (0, 2), (9, 3), (0, 4), (-5, 10)];
    assert_eq!(
        fill_polygon::<0, 5>(&pts::<0>(&zig), &w, |_| n += 1),
        Err(FillError::TooManyEdges { capacity: 5 })
    );
    assert!(PolygonEdges::<5>::build(&pts::<0>(&zig)).is_err());
    // Exactly at capacity is fine, and horizontal edges do not count.
    fill_polygon::<0, 6>(&pts::<0>(&zig), &w, |_| ()).unwrap();
    let square: [V; 4] = [(0, 0), (5, 0), (5, 5), (0, 5)];
    fill_polygon::<0, 2>(&pts::<0>(&square), &w, |_| ()).unwrap();
    assert_eq!(
        fill_polygon::<0, 1>(&pts::<0>(&square), &w, |_| n += 1),
        Err(FillError::TooManyEdges { capacity: 1 })
    );
    // Out of range coordinates, on either axis, either sign.
    let m = MAX_COORD as i64;
    for (i, bad) in [
        (m + 1, 0),
        (0, m + 1),
        (-m - 1, 0),
        (0, -m - 1),
        (i32::MIN as i64, 0),
    ]
    .into_iter()
    .enumerate()
    {
        let idx = i % 3;
        let mut v: Vec<V> = vec![(0, 0), (10, 0), (0, 10)];
        v[idx] = bad;
        let e = FillError::CoordinateOutOfRange { vertex: idx };
        assert_eq!(fill_polygon::<4, 8>(&pts::<4>(&v), &w, |_| n += 1), Err(e));
        let p = pts::<4>(&v);
        assert_eq!(fill_triangle([p[0], p[1], p[2]], &w, |_| n += 1), Err(e));
        // The message names the problem.
        assert!(e.to_string().contains(&format!("vertex {idx}")));
    }
    // Exactly at the limit is accepted.
    let edge: [V; 3] = [(m, m), (-m, m), (m, -m)];
    fill_polygon::<4, 8>(&pts::<4>(&edge), &w, |_| ()).unwrap();
    // Too many sub-pixel bits.
    let v = [SubpixelPoint::<17>::new(0, 0); 3];
    assert!(matches!(
        fill_polygon::<17, 8>(&v, &w, |_| n += 1),
        Err(FillError::CoordinateOutOfRange { .. })
    ));
    assert!(fill_triangle(v, &w, |_| n += 1).is_err());
    assert_eq!(n, 0, "spans were emitted despite an error");
    assert!(FillError::TooManyEdges { capacity: 5 }
        .to_string()
        .contains("more than 5"));
}
