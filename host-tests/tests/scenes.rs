//! The standard scenes (docs/SCENES.md), the f64 reference renderer and
//! `zscan export-scenes`.
//!
//! The facts asserted here are computed independently of the code under test: the coverage
//! counts and fit scales are SCENES.md's, the projections and rotations are re-derived by hand
//! formulas, and the exact coverage is compared with a brute-force edge-function test in exact
//! integer arithmetic.
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::OnceLock;
use zscan_host::cli::export::{export_scenes, scene_source, to_i16f16};
use zscan_host::reference::float_render::{
    cover_polygon, render, write_grey_png, FloatFrame, Interpolation,
};
use zscan_host::scenes::{standard_scenes, Camera, Scene};

/// The four standard scenes, built once for all tests.
fn scenes() -> &'static [Scene] {
    static S: OnceLock<Vec<Scene>> = OnceLock::new();
    S.get_or_init(|| standard_scenes().expect("standard scenes build"))
}

fn scene(name: &str) -> &'static Scene {
    scenes().iter().find(|s| s.name == name).unwrap()
}

/// The reference frames of the four scenes, rendered once.
fn frames() -> &'static HashMap<String, FloatFrame> {
    static F: OnceLock<HashMap<String, FloatFrame>> = OnceLock::new();
    F.get_or_init(|| {
        scenes()
            .iter()
            .map(|s| (s.name.clone(), render(s).expect("renders")))
            .collect()
    })
}

/// SCENES.md: 30° half-angle, 240 rows → focal length 120·√3 pixels.
fn focal() -> f64 {
    120.0 * 3f64.sqrt()
}

#[test]
fn scene_sizes_are_those_of_scenes_md() {
    let want = [
        ("quad", 4, 2),
        ("cube", 8, 12),
        ("sphere", 482, 960),
        ("bunny", 1839, 3674),
    ];
    for (name, nv, nt) in want {
        let s = scene(name);
        assert_eq!(
            (s.vertices.len(), s.triangles.len(), s.intensities.len()),
            (nv, nt, nt),
            "{name}"
        );
        s.validate().unwrap();
    }
}

#[test]
fn fit_scales_match_the_table_and_the_definition() {
    // SCENES.md's "scale after fitting" column (given to 8 significant digits).
    for (name, table, fraction) in [
        ("cube", 1.4054597, 0.60),
        ("sphere", 1.1241460, 0.70),
        ("bunny", 0.20195037, 0.70),
    ] {
        let s = scene(name);
        assert!(
            (s.scale - table).abs() < 6e-8 * table,
            "{name}: {} vs {table}",
            s.scale
        );
        // The definition: the y extent of the vertices' projections is F × 240 pixels.
        let ys: Vec<f64> = s
            .vertices
            .iter()
            .map(|v| 119.5 - focal() * v[1] / (3.0 - v[2]))
            .collect();
        let extent = ys.iter().cloned().fold(f64::MIN, f64::max)
            - ys.iter().cloned().fold(f64::MAX, f64::min);
        assert!((extent - fraction * 240.0).abs() < 1e-9, "{name}: {extent}");
    }
    assert_eq!(scene("quad").scale, 1.0);
}

#[test]
fn placements_follow_the_definitions() {
    // Cube: corner (+,+,+) rotated 30° about Y, then 20° about X, times the table scale.
    let (s30, c30) = 30f64.to_radians().sin_cos();
    let (s20, c20) = 20f64.to_radians().sin_cos();
    let (x, y, z) = (0.5, 0.5, 0.5);
    let (x1, z1) = (x * c30 + z * s30, -x * s30 + z * c30);
    let (y2, z2) = (y * c20 - z1 * s20, y * s20 + z1 * c20);
    let k = 1.4054597;
    let want = [x1 * k, y2 * k, z2 * k];
    let cube = scene("cube");
    let got = cube
        .vertices
        .iter()
        .min_by(|a, b| dist2(**a, want).total_cmp(&dist2(**b, want)))
        .unwrap();
    assert!(dist2(*got, want) < 1e-12, "{got:?} vs {want:?}");

    // Sphere: poles and the first vertex of ring 1 (θ = π/16, azimuth 0 along +x).
    let sp = scene("sphere");
    let r = sp.scale;
    assert!(dist2(sp.vertices[0], [0.0, r, 0.0]) < 1e-24);
    assert!(dist2(sp.vertices[481], [0.0, -r, 0.0]) < 1e-24);
    let t = std::f64::consts::PI / 16.0;
    assert!(dist2(sp.vertices[1], [r * t.sin(), r * t.cos(), 0.0]) < 1e-24);
    // Ring k segment j is at height cos(πk/16) and radius sin(πk/16).
    for k in 1..16 {
        for j in 0..32 {
            let v = sp.vertices[1 + (k - 1) * 32 + j];
            let th = std::f64::consts::PI * k as f64 / 16.0;
            assert!((v[1] - r * th.cos()).abs() < 1e-12);
            assert!(((v[0] * v[0] + v[2] * v[2]).sqrt() - r * th.sin()).abs() < 1e-12);
        }
    }
    // Band quads are split along (ring k, j)–(ring k+1, j+1): that diagonal is an edge.
    let has_edge = |a: usize, b: usize| {
        sp.triangles.iter().any(|t| {
            (0..3).any(|i| (t[i], t[(i + 1) % 3]) == (a, b) || (t[i], t[(i + 1) % 3]) == (b, a))
        })
    };
    for k in 1..15 {
        for j in 0..32 {
            let at = |k: usize, j: usize| 1 + (k - 1) * 32 + j % 32;
            assert!(has_edge(at(k, j), at(k + 1, j + 1)));
            assert!(!has_edge(at(k, j + 1), at(k + 1, j)));
        }
    }

    // Bunny: bounding box centred.
    let b = scene("bunny");
    for a in 0..3 {
        let lo = b.vertices.iter().map(|v| v[a]).fold(f64::MAX, f64::min);
        let hi = b.vertices.iter().map(|v| v[a]).fold(f64::MIN, f64::max);
        assert!((lo + hi).abs() < 1e-12, "axis {a}: {lo} {hi}");
    }
}

fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[test]
fn front_faces_wind_counter_clockwise_from_outside() {
    for name in ["quad", "cube", "sphere", "bunny"] {
        let s = scene(name);
        let mut volume = 0.0;
        for t in &s.triangles {
            let [a, b, c] = t.map(|i| s.vertices[i]);
            let n = cross(
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            );
            volume += dot(a, cross(b, c)) / 6.0;
            let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
            match name {
                // Convex and centred: every face normal points away from the origin.
                "cube" | "sphere" => assert!(dot(n, centroid) > 0.0, "{name} {t:?}"),
                // Facing the camera.
                "quad" => assert!(n[2] > 0.0),
                _ => {}
            }
        }
        if name != "quad" {
            assert!(volume > 0.0, "{name}: signed volume {volume}");
        }
    }
}

#[test]
fn intensities_follow_the_lighting_formula() {
    let level = |n: [f64; 3]| {
        let len = dot(n, n).sqrt();
        let ndl = dot(n, [1.0, 1.0, 1.0]) / (len * 3f64.sqrt());
        ((0.1 + 0.9 * ndl.max(0.0)).min(1.0) * 255.0).round() as u8
    };
    // Facing +z: N·L = 1/√3, I = 0.1 + 0.9/√3 = 0.6196 → 158.
    assert_eq!(scene("quad").intensities, vec![[158; 3]; 2]);
    // Cube: one level per face (both triangles of a face, all corners), from the face normal.
    let cube = scene("cube");
    for (t, tri) in cube.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|i| cube.vertices[i]);
        let n = cross(
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        assert_eq!(cube.intensities[t], [level(n); 3]);
    }
    // Smooth scenes: one level per vertex, from the normalised sum of the adjacent triangles'
    // cross products; on the sphere that normal is within 3° of the radial direction, and the
    // north pole's is exactly +y (level 158).
    for name in ["sphere", "bunny"] {
        let s = scene(name);
        let mut normals = vec![[0.0; 3]; s.vertices.len()];
        for tri in &s.triangles {
            let [a, b, c] = tri.map(|i| s.vertices[i]);
            let n = cross(
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            );
            for &i in tri {
                normals[i] = [0, 1, 2].map(|k| normals[i][k] + n[k]);
            }
        }
        for (t, tri) in s.triangles.iter().enumerate() {
            assert_eq!(
                s.intensities[t],
                tri.map(|i| level(normals[i])),
                "{name} {t}"
            );
        }
        if name == "sphere" {
            assert_eq!(level(normals[0]), 158);
            for (n, v) in normals.iter().zip(&s.vertices) {
                let cos = dot(*n, *v) / (dot(*n, *n) * dot(*v, *v)).sqrt();
                assert!(cos > 3f64.to_radians().cos(), "{cos}");
            }
        }
    }
    // The lit side of the sphere reaches full white, the far side stays at the 0.1 floor (26).
    let sp = scene("sphere").intensities.concat();
    assert_eq!(sp.iter().max(), Some(&255));
    assert_eq!(sp.iter().min(), Some(&26));
}

#[test]
fn coverage_counts_are_those_of_scenes_md() {
    // SCENES.md, "Coverage with exact arithmetic ... and the top-left rule".
    let want = [
        ("quad", 76_800),
        ("cube", 16_014),
        ("sphere", 22_000),
        ("bunny", 11_462),
    ];
    for (name, pixels) in want {
        let f = &frames()[name];
        assert_eq!(f.stats.covered_pixels, pixels, "{name}: {:?}", f.stats);
        assert_eq!(f.pixels.iter().filter(|p| p.is_some()).count(), pixels);
    }
}

#[test]
fn triangles_drawn_match_the_exact_renderers_in_scenes_md() {
    // Front-facing triangles: tgx and embedded-3dgfx report 2 (quad), 6, 248 and 1,379.
    for (name, drawn) in [("quad", 2), ("cube", 6), ("sphere", 248), ("bunny", 1379)] {
        let st = frames()[name].stats;
        assert_eq!(st.triangles_drawn, drawn, "{name}");
        assert_eq!(
            st.triangles_drawn + st.triangles_culled,
            scene(name).triangles.len()
        );
        assert_eq!(st.triangles_clipped + st.triangles_clipped_away, 0);
    }
    // Convex objects: front faces tile the silhouette, no pixel is written twice.
    for name in ["quad", "cube", "sphere"] {
        let st = frames()[name].stats;
        assert_eq!(st.fragments_written, st.covered_pixels, "{name}");
    }
    assert!(frames()["bunny"].stats.fragments_written > 11_462);
}

#[test]
fn quad_depth_and_luminance_are_constant() {
    let f = &frames()["quad"];
    for p in f.pixels.iter() {
        let p = p.expect("the quad covers every pixel");
        assert!((p.depth - 3.0).abs() < 1e-12, "{}", p.depth);
        assert!((p.luminance_perspective - 158.0).abs() < 1e-9);
        assert!((p.luminance_affine - 158.0).abs() < 1e-9);
    }
}

#[test]
fn depth_is_the_plane_through_the_pixel() {
    // Every visible cube pixel: the back-projected point lies on its triangle's plane.
    let s = scene("cube");
    let f = &frames()["cube"];
    for y in 0..240 {
        for x in 0..320 {
            let Some(p) = f.at(x, y) else { continue };
            let d = p.depth;
            let world = [
                (x as f64 - 159.5) / focal() * d,
                -(y as f64 - 119.5) / focal() * d,
                3.0 - d,
            ];
            let [a, b, c] = s.triangles[p.triangle].map(|i| s.vertices[i]);
            let n = cross(
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            );
            let off = dot(n, [world[0] - a[0], world[1] - a[1], world[2] - a[2]]);
            assert!(off.abs() < 1e-9, "({x}, {y}): {off}");
            assert!(d > 1.5 && d < 4.5);
        }
    }
    // Every visible bunny depth lies between the mesh's nearest and farthest vertex depths.
    let b = scene("bunny");
    let zmin = b.vertices.iter().map(|v| v[2]).fold(f64::MAX, f64::min);
    let zmax = b.vertices.iter().map(|v| v[2]).fold(f64::MIN, f64::max);
    for p in frames()["bunny"].pixels.iter().flatten() {
        assert!(p.depth >= 3.0 - zmax - 1e-12 && p.depth <= 3.0 - zmin + 1e-12);
    }
}

#[test]
fn a_floor_is_clipped_at_the_near_and_far_planes() {
    // The plane y = −1 from z = −100 to z = +100 (behind the eye). Its pixels are those whose ray
    // meets the floor at depth t = f / (y − 119.5) ≤ 10: rows y ≥ 119.5 + f/10 = 140.28, so rows
    // 141..=239, every column (|x| ≤ 160·10/f < 100 at that depth).
    let cam = Camera::standard();
    let (a, b, c, d) = (
        [-100.0, -1.0, 100.0],
        [100.0, -1.0, 100.0],
        [100.0, -1.0, -100.0],
        [-100.0, -1.0, -100.0],
    );
    // Intensity linear in z: 255 at z = +100, 0 at z = −100.
    let scene = Scene::from_triangles(
        "floor",
        cam,
        &[[a, b, c], [a, c, d]],
        &[[255, 255, 0], [255, 0, 0]],
    )
    .unwrap();
    let f = render(&scene).unwrap();
    assert_eq!(f.stats.covered_pixels, 320 * 99);
    assert_eq!(f.stats.triangles_clipped, 2);
    assert!(f.at(10, 140).is_none() && f.at(10, 141).is_some());
    for y in [141, 170, 239] {
        let t = focal() / (y as f64 - 119.5);
        let p = f.at(77, y).unwrap();
        assert!((p.depth - t).abs() < 1e-12);
        // Perspective-correct luminance is the linear function of the visible point's z.
        let z = 3.0 - t;
        let want = 127.5 + 1.275 * z;
        assert!((p.luminance_perspective - want).abs() < 1e-9, "{y}");
    }
    // A triangle entirely behind the eye is clipped away; a back face is culled.
    let behind = Scene::from_triangles(
        "behind",
        cam,
        &[
            [[0.0, 0.0, 4.0], [0.0, 1.0, 4.0], [1.0, 0.0, 4.0]],
            [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
        ],
        &[[1; 3], [2; 3]],
    )
    .unwrap();
    let st = render(&behind).unwrap().stats;
    assert_eq!(
        (
            st.triangles_clipped_away,
            st.triangles_culled,
            st.covered_pixels
        ),
        (1, 1, 0)
    );
}

use zscan_host::test_rng::XorShift as Rng;

/// Brute force with exact integers (coordinates in 1/16 pixel): the edge-function test with
/// the top-left tie rule (a pixel on an edge is in when the edge is a left or a top edge).
fn brute_force_covered(tri: [(i64, i64); 3], x: i64, y: i64) -> bool {
    let (px, py) = (16 * x, 16 * y);
    let [mut a, b, mut c] = tri;
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if area == 0 {
        return false;
    }
    if area < 0 {
        std::mem::swap(&mut a, &mut c);
    }
    // Now (b − a) × (c − a) > 0 in y-down coordinates: visually clockwise.
    [(a, b), (b, c), (c, a)].iter().all(|&(p, q)| {
        let e = (q.0 - p.0) * (py - p.1) - (q.1 - p.1) * (px - p.0);
        let left = q.1 < p.1;
        let top = q.1 == p.1 && q.0 > p.0;
        e > 0 || (e == 0 && (left || top))
    })
}

#[test]
fn exact_coverage_matches_brute_force_and_the_core_fill() {
    use zscan::raster::polygon::fill_polygon;
    use zscan::raster::{ScreenPoint, Window};
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    let (w, h) = (24u32, 20u32);
    let mut on_edge = 0;
    for _ in 0..3000 {
        // Coarse grids make pixels on edges and vertices common.
        let unit = [1, 4, 8, 16][rng.range(0, 3) as usize];
        let tri: [(i64, i64); 3] = std::array::from_fn(|_| {
            (
                rng.range(-4, 28 * 16 / unit) * unit,
                rng.range(-4, 24 * 16 / unit) * unit,
            )
        });
        let poly: Vec<(f64, f64)> = tri
            .iter()
            .map(|&(x, y)| (x as f64 / 16.0, y as f64 / 16.0))
            .collect();
        let mut reference = vec![false; (w * h) as usize];
        cover_polygon(&poly, w, h, |x, y| {
            let cell = &mut reference[(y * w + x) as usize];
            assert!(!*cell, "pixel reported twice");
            *cell = true;
        });
        let mut core = vec![false; (w * h) as usize];
        let pts: Vec<ScreenPoint> = tri
            .iter()
            .map(|&(x, y)| ScreenPoint::new(x as i32, y as i32))
            .collect();
        fill_polygon::<4, 8>(&pts, &Window::of_size(w as u16, h as u16), |s| {
            for x in s.x0..s.x1 {
                core[(s.y as u32 * w + x as u32) as usize] = true;
            }
        })
        .unwrap();
        for y in 0..h {
            for x in 0..w {
                let want = brute_force_covered(tri, x as i64, y as i64);
                let i = (y * w + x) as usize;
                assert_eq!(reference[i], want, "{tri:?} pixel ({x}, {y})");
                assert_eq!(core[i], want, "core fill, {tri:?} pixel ({x}, {y})");
                let on = [(0, 1), (1, 2), (2, 0)].iter().any(|&(p, q)| {
                    let (p, q) = (tri[p], tri[q]);
                    (q.0 - p.0) * (16 * y as i64 - p.1) == (q.1 - p.1) * (16 * x as i64 - p.0)
                });
                on_edge += on as usize;
            }
        }
    }
    assert!(on_edge > 1000, "the test should exercise ties: {on_edge}");
}

#[test]
fn adjacent_triangles_tile_without_gaps_or_overlaps() {
    // Random fans around an interior point with f64 (off-grid) coordinates: the union covers
    // each pixel of the fan's polygon exactly once.
    let mut rng = Rng::new(0x1234_5678_9abc_def1);
    for _ in 0..200 {
        let centre = (
            rng.range(0, 1 << 20) as f64 / 65536.0,
            rng.range(0, 1 << 20) as f64 / 65536.0,
        );
        let n = rng.range(3, 9) as usize;
        let ring: Vec<(f64, f64)> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU
                    * (k as f64 + 0.3 * (rng.range(0, 100) as f64 / 100.0))
                    / n as f64;
                let r = 2.0 + 14.0 * rng.range(0, 1000) as f64 / 1000.0;
                (centre.0 + r * a.cos(), centre.1 + r * a.sin())
            })
            .collect();
        let mut count = vec![0u8; 32 * 32];
        for k in 0..n {
            cover_polygon(&[centre, ring[k], ring[(k + 1) % n]], 32, 32, |x, y| {
                count[(y * 32 + x) as usize] += 1;
            });
        }
        let mut whole = vec![0u8; 32 * 32];
        cover_polygon(&ring, 32, 32, |x, y| whole[(y * 32 + x) as usize] += 1);
        assert_eq!(count, whole);
        assert!(count.iter().all(|&c| c <= 1));
    }
}

#[test]
fn pictures_of_the_scenes() {
    // Writes target/zscan-out/float-<scene>.png (perspective-correct luminance) and
    // float-<scene>-affine.png; prints the mean difference between the two interpolations.
    let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/zscan-out");
    for s in scenes() {
        let f = &frames()[&s.name];
        let persp = f.luminance_image(Interpolation::PerspectiveCorrect);
        let affine = f.luminance_image(Interpolation::ScreenAffine);
        write_grey_png(&out.join(format!("float-{}.png", s.name)), 320, 240, &persp).unwrap();
        write_grey_png(
            &out.join(format!("float-{}-affine.png", s.name)),
            320,
            240,
            &affine,
        )
        .unwrap();
        let covered: Vec<_> = f.pixels.iter().flatten().collect();
        let mean = covered
            .iter()
            .map(|p| (p.luminance_perspective - p.luminance_affine).abs())
            .sum::<f64>()
            / covered.len() as f64;
        println!("{}: mean |perspective − affine| = {mean:.4} levels", s.name);
        // Luminance stays within the corner levels of its triangle.
        for p in covered {
            let l = s.intensities[p.triangle];
            let (lo, hi) = (
                *l.iter().min().unwrap() as f64,
                *l.iter().max().unwrap() as f64,
            );
            for v in [p.luminance_perspective, p.luminance_affine] {
                assert!(
                    v >= lo - 1e-6 && v <= hi + 1e-6,
                    "{}: {v} not in [{lo}, {hi}]",
                    s.name
                );
            }
        }
    }
    // The picture's orientation: the sphere is lit from the upper right front, so its brightest
    // pixels are up and to the right of centre.
    let f = &frames()["sphere"];
    let (mut bx, mut by, mut best) = (0, 0, 0.0);
    for y in 0..240 {
        for x in 0..320 {
            if let Some(p) = f.at(x, y) {
                if p.luminance_perspective > best {
                    (bx, by, best) = (x, y, p.luminance_perspective);
                }
            }
        }
    }
    assert!(
        bx > 160 && by < 120,
        "brightest sphere pixel at ({bx}, {by})"
    );
}

/// Parses `pub static NAME: [[T; 3]; N] = [ [a, b, c], ... ];` out of an exported file.
fn parse_array(text: &str, name: &str) -> Vec<[i64; 3]> {
    let head = format!("pub static {name}: [[");
    let start = text.find(&head).unwrap_or_else(|| panic!("{name} missing"));
    let rest = &text[start + head.len()..];
    let semi = rest.find("; 3]; ").unwrap();
    let ty = &rest[..semi];
    assert!(["i32", "u16", "u8"].contains(&ty), "{ty}");
    let rest = &rest[semi + 6..];
    let close = rest.find("] = [").unwrap();
    let n: usize = rest[..close].parse().unwrap();
    let body = &rest[close + 5..rest.find("];").unwrap()];
    let rows: Vec<[i64; 3]> = body
        .split(']')
        .map(|r| {
            r.trim()
                .trim_start_matches(',')
                .trim()
                .trim_start_matches('[')
        })
        .filter(|r| !r.is_empty())
        .map(|r| {
            let v: Vec<i64> = r.split(',').map(|x| x.trim().parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    assert_eq!(rows.len(), n, "{name}: declared {n}, found {}", rows.len());
    rows
}

#[test]
fn exported_sources_parse_back_to_the_scenes() {
    let counts = [
        ("quad", 4, 2),
        ("cube", 8, 12),
        ("sphere", 482, 960),
        ("bunny", 1839, 3674),
    ];
    for (name, nv, nt) in counts {
        let s = scene(name);
        let text = scene_source(s).unwrap();
        assert!(text.starts_with("// Standard scene"), "header comment");
        assert!(text.contains("zscan export-scenes"));
        let v = parse_array(&text, "VERTICES");
        let t = parse_array(&text, "TRIANGLES");
        let i = parse_array(&text, "INTENSITIES");
        assert_eq!((v.len(), t.len(), i.len()), (nv, nt, nt), "{name}");
        for (got, want) in v.iter().zip(&s.vertices) {
            for k in 0..3 {
                // I16F16: within half a unit of 2^-16 of the f64 position.
                assert!((got[k] as f64 / 65536.0 - want[k]).abs() <= 0.5 / 65536.0);
            }
        }
        for (got, want) in t.iter().zip(&s.triangles) {
            assert_eq!(*got, want.map(|x| x as i64));
        }
        for (got, want) in i.iter().zip(&s.intensities) {
            assert_eq!(*got, want.map(|x| x as i64));
        }
    }
    assert_eq!(to_i16f16(1.0), Ok(65536));
    assert_eq!(to_i16f16(-0.5 / 65536.0), Ok(-1));
    assert!(to_i16f16(40000.0).is_err());
}

#[test]
fn export_scenes_writes_four_files() {
    let dir = std::env::temp_dir().join(format!("zscan-export-test-{}", std::process::id()));
    let paths = export_scenes(&dir).unwrap();
    let names: Vec<String> = paths
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["quad.rs", "cube.rs", "sphere.rs", "bunny.rs"]);
    let sphere = std::fs::read_to_string(dir.join("sphere.rs")).unwrap();
    assert_eq!(sphere, scene_source(scene("sphere")).unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
    // A path that cannot be a directory is an error, not a panic.
    let file = std::env::temp_dir().join(format!("zscan-export-file-{}", std::process::id()));
    std::fs::write(&file, b"x").unwrap();
    assert!(export_scenes(&file.join("sub")).is_err());
    std::fs::remove_file(&file).unwrap();
}

#[test]
fn no_silhouette_pixel_of_the_standard_scenes_is_near_a_tie() {
    // Why the f64 counts equal the exact ones: on the silhouette (edges of exactly one
    // front-facing triangle), no lattice point lies within 1e-6 pixel of an edge crossing on its
    // row and no silhouette vertex within 1e-6 pixel of a row, while projecting in f64 moves a
    // vertex by ~1e-13 pixel. Interior edges are shared, so a tie there only decides which of the
    // two triangles owns the pixel, never whether it is covered. The quad has six exact interior
    // ties: its diagonal is x − 159.5 = −(49/37)(y − 119.5) on screen, which meets the lattice
    // where y − 119.5 is an odd multiple of 18.5 (x − 159.5 then an odd multiple of −24.5).
    let f = focal();
    for s in scenes() {
        let proj = |v: [f64; 3]| {
            (
                159.5 + f * v[0] / (3.0 - v[2]),
                119.5 - f * v[1] / (3.0 - v[2]),
            )
        };
        let mut uses: HashMap<(usize, usize), usize> = HashMap::new();
        let front: Vec<&[usize; 3]> = s
            .triangles
            .iter()
            .filter(|tri| {
                let [a, b, c] = tri.map(|i| s.vertices[i]);
                let n = cross(
                    [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                    [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
                );
                dot(n, [-a[0], -a[1], 3.0 - a[2]]) > 0.0
            })
            .collect();
        for tri in &front {
            for k in 0..3 {
                let (i, j) = (tri[k], tri[(k + 1) % 3]);
                *uses.entry((i.min(j), i.max(j))).or_default() += 1;
            }
        }
        let mut margin = f64::MAX;
        let mut interior_ties = Vec::new();
        for (&(i, j), &n) in &uses {
            let (mut u, mut v) = (proj(s.vertices[i]), proj(s.vertices[j]));
            if n == 1 {
                margin = margin
                    .min((u.1 - u.1.round()).abs())
                    .min((v.1 - v.1.round()).abs());
            }
            if u.1 > v.1 {
                std::mem::swap(&mut u, &mut v);
            }
            let first = u.1.ceil().max(0.0) as i32;
            let end = v.1.ceil().min(240.0) as i32;
            for y in first..end {
                let xe = u.0 + (y as f64 - u.1) * (v.0 - u.0) / (v.1 - u.1);
                if !(-0.5..319.5).contains(&xe) {
                    continue;
                }
                let d = (xe - xe.round()).abs();
                if n == 1 {
                    margin = margin.min(d);
                } else if d < 1e-9 {
                    interior_ties.push((xe.round() as i32, y));
                }
            }
        }
        interior_ties.sort();
        println!(
            "{}: nearest silhouette tie {margin:.3e} pixel; interior ties {interior_ties:?}",
            s.name
        );
        assert!(margin > 1e-6, "{}: {margin}", s.name);
        if s.name == "quad" {
            assert_eq!(
                interior_ties,
                [
                    (37, 212),
                    (86, 175),
                    (135, 138),
                    (184, 101),
                    (233, 64),
                    (282, 27)
                ]
            );
            // With the exact decimal geometry the diagonal is the left edge of triangle 0 (the
            // lower right one), which owns these pixels; in f64 (2.45 and 1.85 are already
            // rounded) they go to triangle 1. Same intensity, same count: nothing observable
            // but the triangle id.
            let fq = &frames()["quad"];
            let owners: Vec<usize> = interior_ties
                .iter()
                .map(|&(x, y)| fq.at(x as u32, y as u32).unwrap().triangle)
                .collect();
            println!("quad: owners of the diagonal ties in the f64 render: {owners:?}");
        }
    }
}
