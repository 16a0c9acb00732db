//! The hidden-surface methods (`zscan::visibility`) against the 32-bit z-buffer: identical
//! pictures where a method claims to be exact, the wrong pixels counted where it is not.

use zscan::geometry::camera::{Camera, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::trig::Angle;
use zscan::geometry::vector::Vec3;
use zscan::render::{RenderError, Renderer};
use zscan::scene::{Intensities, Object, Scene};
use zscan::shade::span_writer::ShadeMode;
use zscan::visibility::Visibility;
use zscan_host::core_render::{render_visible, to_core};
use zscan_host::scenes::standard_scene;
use zscan_host::test_rng::XorShift;

/// Pixels that differ between two pictures.
fn differing(a: &[u8], b: &[u8]) -> usize {
    a.iter().zip(b).filter(|(x, y)| x != y).count()
}

/// `(method's picture, z-buffer's picture)` of `scene` at `w × h`.
fn both(
    scene: &Scene<'_>,
    (w, h): (u16, u16),
    method: Visibility,
    splits: Option<usize>,
    band_rows: u16,
) -> Result<(Vec<u8>, Vec<u8>), RenderError> {
    let renderer = Renderer::for_scene(scene)?;
    let (m, _) = render_visible(&renderer, (w, h), method, splits, band_rows)?;
    let (z, _) = render_visible(&renderer, (w, h), Visibility::ZBuffer, None, h)?;
    Ok((m, z))
}

/// Wrong pixels of `method` on the standard scene `name` (Gouraud, as SCENES.md draws it).
fn standard_wrong(name: &str, method: Visibility, band_rows: u16) -> usize {
    standard_wrong_with(name, method, Some(64), band_rows)
}

fn standard_scene_core(name: &str) -> zscan_host::core_render::CoreMesh {
    to_core(&standard_scene(name).unwrap()).unwrap()
}

/// [`standard_wrong`] with the painter's split policy `splits`.
fn standard_wrong_with(
    name: &str,
    method: Visibility,
    splits: Option<usize>,
    band_rows: u16,
) -> usize {
    let core = standard_scene_core(name);
    let objects = [core.object(ShadeMode::GouraudExact).unwrap()];
    let scene = Scene {
        camera: core.camera,
        ambient: 0,
        lights: &[],
        objects: &objects,
        background: 0,
    };
    let vp = *core.camera.viewport();
    let (m, z) = both(&scene, (vp.width, vp.height), method, splits, band_rows).unwrap();
    assert!(
        z.iter().any(|&p| p != 0),
        "{name}: the z-buffer drew nothing"
    );
    differing(&m, &z)
}

#[test]
fn exact_methods_draw_the_z_buffer_pictures_of_the_standard_scenes() {
    for name in ["quad", "cube", "sphere"] {
        assert_eq!(
            standard_wrong(name, Visibility::Painter, 1),
            0,
            "{name}: painter"
        );
    }
    for name in ["quad", "cube", "sphere", "bunny"] {
        for rows in [1, 7, 16] {
            assert_eq!(
                standard_wrong(name, Visibility::ScanLine, rows),
                0,
                "{name}: scan-line {rows}"
            );
        }
    }
}

#[test]
fn back_faces_alone_are_exact_on_convex_meshes_and_wrong_on_the_bunny() {
    for name in ["quad", "cube", "sphere"] {
        assert_eq!(standard_wrong(name, Visibility::BackFace, 1), 0, "{name}");
    }
    let wrong = standard_wrong("bunny", Visibility::BackFace, 1);
    println!("back faces alone, bunny: {wrong} wrong pixels");
    assert!(
        wrong > 0,
        "the bunny is not convex: some front faces overlap"
    );
}

/// The bunny's front faces defeat the painter's tests 1-5 in places (conservative tests on
/// triangles that share edges in folds), its test 6 cannot order the pieces, and the frame is
/// refused; drawn in the tests' order anyway (no test 6) it happens to be right.
#[test]
fn painter_refuses_the_bunny_with_test_6_and_draws_it_right_without() {
    let core = standard_scene_core("bunny");
    let objects = [core.object(ShadeMode::GouraudExact).unwrap()];
    let scene = Scene {
        camera: core.camera,
        ambient: 0,
        lights: &[],
        objects: &objects,
        background: 0,
    };
    let vp = *core.camera.viewport();
    let r = both(
        &scene,
        (vp.width, vp.height),
        Visibility::Painter,
        Some(100_000),
        1,
    );
    assert_eq!(r.err(), Some(RenderError::PainterCycle));
    assert_eq!(
        standard_wrong_with("bunny", Visibility::Painter, None, 1),
        0
    );
}

fn camera(w: u16, h: u16) -> Camera {
    let lens = Lens::new(Angle::from_degrees(60), Coord::lit("0.5"), Coord::lit("50"));
    let up = Vec3::from_int(0, 1, 0);
    Camera::look_at(
        Vec3::from_int(0, 0, 6),
        Vec3::ZERO,
        up,
        lens,
        Viewport::new(w, h),
    )
    .unwrap()
}

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    let c = |a: f64| Coord::from_num(a);
    Vec3::new(c(x), c(y), c(z))
}

/// Objects of one triangle soup each (no culling: both sides show), levels per polygon.
fn soup_objects<'a>(vertices: &'a [Vec3], indices: &'a [u16], levels: &'a [u8]) -> Object<'a> {
    let mesh = Mesh::new(vertices, indices, PolygonSizes::Uniform(3)).unwrap();
    let mut o = Object::new(mesh);
    o.cull_back_faces = false;
    o.intensities = Intensities::PerPolygon(levels);
    o.shade = ShadeMode::Flat;
    o
}

/// Three long triangles each over the next and under the one before (the survey's cycle).
fn cycle_of_three() -> (Vec<Vec3>, Vec<u16>, Vec<u8>) {
    let mut vs = Vec::new();
    for k in 0..3 {
        let a = k as f64 * std::f64::consts::TAU / 3.0;
        let (c, s) = (a.cos(), a.sin());
        // A long strip from the centre outward, tilted in depth so that it passes over the
        // next strip near the centre and under it far out.
        let p = |r: f64, w: f64, z: f64| v(r * c - w * s, r * s + w * c, z);
        vs.extend([p(-0.3, -0.35, 0.6), p(-0.3, 0.35, 0.6), p(2.2, 0.0, -0.6)]);
    }
    (vs, (0..9).collect(), vec![80, 160, 240])
}

#[test]
fn painter_needs_test_6_on_a_cycle_of_three() {
    let (vs, is, ls) = cycle_of_three();
    let objects = [soup_objects(&vs, &is, &ls)];
    let scene = Scene {
        camera: camera(160, 120),
        ambient: 0,
        lights: &[],
        objects: &objects,
        background: 0,
    };
    let (never, z) = both(&scene, (160, 120), Visibility::Painter, None, 1).unwrap();
    let wrong_never = differing(&never, &z);
    println!("cycle of three: painter without test 6 {wrong_never} wrong pixels");
    assert!(wrong_never > 0, "the cycle must defeat tests 1-5");
    // With test 6 the pieces of this cycle are not ordered by the tests (which judge a piece by
    // its whole triangle): the frame is refused, never drawn wrong. A budget of no split is
    // reported as such.
    let r = both(&scene, (160, 120), Visibility::Painter, Some(16), 1);
    assert_eq!(r.err(), Some(RenderError::PainterCycle));
    let r = both(&scene, (160, 120), Visibility::Painter, Some(0), 1);
    assert_eq!(
        r.err(),
        Some(RenderError::SplitBudgetExhausted { budget: 0 })
    );
    let (scan, _) = both(&scene, (160, 120), Visibility::ScanLine, None, 1).unwrap();
    assert_eq!(differing(&scan, &z), 0);
}

#[test]
fn painter_splits_interpenetrating_triangles() {
    let vs = vec![
        v(-2.0, -1.0, -1.0),
        v(2.0, -1.0, 1.0),
        v(0.0, 1.5, 0.0),
        v(-2.0, -1.0, 1.0),
        v(2.0, -1.0, -1.0),
        v(0.0, 1.2, 0.2),
    ];
    let (is, ls) = ((0..6).collect::<Vec<u16>>(), vec![100, 200]);
    let objects = [soup_objects(&vs, &is, &ls)];
    let scene = Scene {
        camera: camera(160, 120),
        ambient: 0,
        lights: &[],
        objects: &objects,
        background: 0,
    };
    let (never, z) = both(&scene, (160, 120), Visibility::Painter, None, 1).unwrap();
    let (split, _) = both(&scene, (160, 120), Visibility::Painter, Some(16), 1).unwrap();
    let (scan, _) = both(&scene, (160, 120), Visibility::ScanLine, None, 1).unwrap();
    let (wrong_never, wrong_split) = (differing(&never, &z), differing(&split, &z));
    println!("interpenetration: painter without test 6 {wrong_never} wrong pixels, with it {wrong_split}");
    assert!(wrong_never > 0);
    assert_eq!(wrong_split, 0);
    assert_eq!(differing(&scan, &z), 0);
}

/// Random soups of triangles in several objects: the painter (with splits) and the scan-line
/// give the z-buffer's picture on every one.
#[test]
fn random_scenes_agree_with_the_z_buffer() {
    let mut rng = XorShift::new(0x5eed_0017);
    let (mut painter_wrong, mut drawn, mut refused) = (0, 0, 0);
    for case in 0..200 {
        let objects_n = 1 + rng.below(4) as usize;
        let mut tables = Vec::new();
        for _ in 0..objects_n {
            let tris = 1 + rng.below(6) as usize;
            let mut vs = Vec::new();
            let (cx, cy, cz) = (
                rng.uniform(-1.5, 1.5),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-2.0, 2.0),
            );
            for _ in 0..3 * tris {
                vs.push(v(
                    cx + rng.uniform(-1.2, 1.2),
                    cy + rng.uniform(-1.2, 1.2),
                    cz + rng.uniform(-1.2, 1.2),
                ));
            }
            let ls: Vec<u8> = (0..tris).map(|_| 16 + rng.below(240) as u8).collect();
            tables.push((vs, (0..3 * tris as u16).collect::<Vec<u16>>(), ls));
        }
        let objects: Vec<Object<'_>> = tables
            .iter()
            .map(|(v, i, l)| soup_objects(v, i, l))
            .collect();
        let scene = Scene {
            camera: camera(96, 72),
            ambient: 0,
            lights: &[],
            objects: &objects,
            background: 0,
        };
        let (s, z) = both(
            &scene,
            (96, 72),
            Visibility::ScanLine,
            None,
            1 + (case % 9) as u16,
        )
        .unwrap();
        assert_eq!(differing(&s, &z), 0, "case {case}: scan-line");
        match both(&scene, (96, 72), Visibility::Painter, Some(4096), 1) {
            Ok((p, _)) => {
                painter_wrong += differing(&p, &z);
                drawn += 1;
            }
            Err(RenderError::PainterCycle | RenderError::PieceCutTooOften { .. }) => refused += 1,
            Err(e) => panic!("case {case}: {e}"),
        }
    }
    println!(
        "random scenes: painter drew {drawn} ({painter_wrong} wrong pixels), refused {refused}"
    );
    assert_eq!(painter_wrong, 0);
    // Dense soups of large interpenetrating triangles: the painter refuses most (measured
    // 57 drawn, 143 refused); what it draws is exact.
    assert!(drawn > 0, "the painter should order some random scenes");
}

#[test]
fn convexity_is_exact_on_the_standard_and_generated_meshes() {
    // The standard cube and sphere are convex as drawn in SCENES.md, but their vertices were
    // turned and rounded to I16F16: some lie a rounding step in front of a neighbouring face's
    // plane, and the exact test says so.
    for (name, convex) in [
        ("quad", true),
        ("cube", false),
        ("sphere", false),
        ("bunny", false),
    ] {
        let core = standard_scene_core(name);
        assert_eq!(core.mesh().unwrap().is_convex(), convex, "{name}");
    }
    assert!(zscan::geometry::generators::unit_cube().is_convex());
    let (nv, ni) = zscan::geometry::generators::torus_sizes(12, 8);
    let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
    let torus =
        zscan::geometry::generators::torus(12, 8, Coord::ONE, Coord::lit("0.4"), &mut vs, &mut is)
            .unwrap();
    assert!(!torus.is_convex());
    // One corner (the cube spans 0..1) pushed in along the diagonal makes it non-convex (a
    // dent), by a little or a lot; pulled out, the triangulated cube is still convex where the
    // faces' diagonals meet the corner (a ridge), so only the dents are asserted.
    let cube = zscan::geometry::generators::unit_cube();
    for d in ["0.2", "0.01"] {
        let mut moved = cube.vertices().to_vec();
        let t = Coord::lit(d);
        moved[0] = Vec3::new(moved[0].x + t, moved[0].y + t, moved[0].z + t);
        let idx: Vec<u16> = cube.polygons().flatten().copied().collect();
        let tris: Vec<u16> = idx
            .chunks(4)
            .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
            .collect();
        let m = Mesh::new(&moved, &tris, PolygonSizes::Uniform(3)).unwrap();
        assert!(!m.is_convex(), "cube with a corner moved by {d}");
    }
}

/// The planner picks back faces alone for the quad (exactly convex) and the z-buffer for the
/// others (their rounded vertices are not exactly convex); either way the picture is the
/// z-buffer's.
#[test]
fn the_plan_of_the_standard_scenes_draws_the_z_buffer_picture() {
    for (name, expected) in [
        ("quad", Visibility::BackFace),
        ("cube", Visibility::ZBuffer),
        ("sphere", Visibility::ZBuffer),
        ("bunny", Visibility::ZBuffer),
    ] {
        let core = standard_scene_core(name);
        let objects = [core.object(ShadeMode::GouraudExact).unwrap()];
        let scene = Scene {
            camera: core.camera,
            ambient: 0,
            lights: &[],
            objects: &objects,
            background: 0,
        };
        let plan = zscan::visibility::plan(&scene, &[objects[0].mesh.is_convex()]);
        assert_eq!(plan.visibility, expected, "{name}: {}", plan.reason);
        let vp = *core.camera.viewport();
        let (m, z) = both(&scene, (vp.width, vp.height), plan.visibility, None, 1).unwrap();
        assert_eq!(differing(&m, &z), 0, "{name}");
    }
}

/// Random ellipsoids (convex) and tori (not), turned and placed at random: the plan's
/// picture is the z-buffer's on every one.
#[test]
fn the_plan_of_random_single_meshes_draws_the_z_buffer_picture() {
    use zscan::geometry::generators::{torus, torus_sizes, uv_sphere, uv_sphere_sizes};
    use zscan::geometry::matrix::Affine3;
    let mut rng = XorShift::new(0x91a7);
    let mut back_faces = 0;
    for case in 0..120 {
        let (seg, rings) = (3 + rng.below(20) as u16, 2 + rng.below(12) as u16);
        let (nv, ni) = if case % 3 == 0 {
            torus_sizes(seg, rings + 1)
        } else {
            uv_sphere_sizes(seg, rings)
        };
        let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
        let mesh = if case % 3 == 0 {
            torus(
                seg,
                rings + 1,
                Coord::ONE,
                Coord::lit("0.35"),
                &mut vs,
                &mut is,
            )
            .unwrap()
        } else {
            uv_sphere(seg, rings, Coord::ONE, &mut vs, &mut is).unwrap()
        };
        let c = |lo: f64, hi: f64, r: &mut XorShift| Coord::from_num(r.uniform(lo, hi));
        let transform = Affine3::builder()
            .scale3(
                c(0.3, 1.6, &mut rng),
                c(0.3, 1.6, &mut rng),
                c(0.3, 1.6, &mut rng),
            )
            .rotate_x(Angle::from_degrees(rng.below(360) as i32))
            .rotate_y(Angle::from_degrees(rng.below(360) as i32))
            .translate(Vec3::new(
                c(-1.5, 1.5, &mut rng),
                c(-1.0, 1.0, &mut rng),
                c(-2.0, 1.0, &mut rng),
            ))
            .build()
            .unwrap();
        let levels: Vec<u8> = (0..nv).map(|_| rng.below(256) as u8).collect();
        let mut o = Object::new(mesh);
        o.transform = transform;
        o.intensities = Intensities::PerVertex(&levels);
        let objects = [o];
        let scene = Scene {
            camera: camera(96, 72),
            ambient: 0,
            lights: &[],
            objects: &objects,
            background: 0,
        };
        let plan = zscan::visibility::plan(&scene, &[mesh.is_convex()]);
        back_faces += (plan.visibility == Visibility::BackFace) as u32;
        let (m, z) = both(&scene, (96, 72), plan.visibility, None, 1).unwrap();
        assert_eq!(differing(&m, &z), 0, "case {case}: {:?}", plan);
        if case % 3 == 0 {
            assert_eq!(
                plan.visibility,
                Visibility::ZBuffer,
                "a torus is not convex"
            );
        }
    }
    // Measured: 16 of the 80 spheres have exactly convex rounded vertices.
    println!("random single meshes: {back_faces} of 120 drawn by back faces alone");
    assert!(back_faces > 5);
}
