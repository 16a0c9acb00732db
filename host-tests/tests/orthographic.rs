//! The orthographic camera (course ch. 1 §3.2) against an independent `f64` ray caster: for
//! each pixel, the ray from the pixel's lattice point on the screen plane along the view
//! direction, the nearest front-facing triangle of the mesh (Möller–Trumbore in world
//! space; the objects cull back faces) between the near and far planes.
//!
//! Bounds (as `render_accuracy.rs` argues them for the perspective camera):
//! - **Coverage.** The projector places a vertex within `0.5 + |offset|·2^-30` units of
//!   2^-4 pixel (`project.rs`), and the camera basis and coordinates are rounded to 2^-16
//!   world units (below 0.005 pixel at these scales), so a pixel whose coverage differs lies
//!   within `δ = 1/16` pixel of a projected edge of the mesh.
//! - **Depth.** The core's depth is linear in `z`, `(2^32 − 1)·(z − near)/(far − near)`,
//!   correctly rounded at the vertices and interpolated exactly; elsewhere it is off by at most
//!   the visible plane's change over `δ` plus the vertices' `z` error (2^-15 world units) and
//!   one unit of rounding. Every pixel away from the edges is compared with that bound.
//! - Where the near or far plane cuts a face, the clipped edge is placed from vertices whose
//!   `z` is rounded to 2^-16: pixels whose ray meets a face within a few 2^-16 units (plus the
//!   face's slope over `δ`) of either plane are, like edge pixels, not compared.
use zscan::geometry::camera::OrthoView;
use zscan::prelude::*;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn f(v: Vec3) -> V {
    v.bits().map(|c| c as f64 / 65536.0)
}

/// Ray `o + t·d` against triangle `abc`: `t` on the triangle, and `t` on its plane.
fn hit(o: V, d: V, a: V, b: V, c: V) -> Option<(f64, f64)> {
    let (e1, e2) = (sub(b, a), sub(c, a));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-14 {
        return None;
    }
    let s = sub(o, a);
    let u = dot(s, p) / det;
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    let t = dot(e2, q) / det;
    let inside = (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0;
    inside.then_some((t, t))
}

/// `t` of ray `o + t·d` on the plane of `abc`.
fn plane_t(o: V, d: V, a: V, b: V, c: V) -> f64 {
    let n = cross(sub(b, a), sub(c, a));
    dot(n, sub(a, o)) / dot(n, d)
}

fn seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dy * dy;
    let t = if l2 == 0.0 {
        0.0
    } else {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / l2).clamp(0.0, 1.0)
    };
    ((p.0 - a.0 - t * dx).powi(2) + (p.1 - a.1 - t * dy).powi(2)).sqrt()
}

/// Renders `mesh` with an orthographic camera and checks every pixel against the ray caster;
/// returns (pixels compared for depth, coverage differences, all near an edge).
fn check(mesh: Mesh<'_>, eye: [i32; 3], view: OrthoView, w: u16, h: u16) -> (usize, usize) {
    let up = Vec3::from_int(0, 1, 0);
    let camera = Camera::look_at_orthographic(
        Vec3::from_int(eye[0], eye[1], eye[2]),
        Vec3::ZERO,
        up,
        view,
        Viewport::new(w, h),
    )
    .unwrap();
    let objects = [Object::new(mesh)];
    let scene = Scene {
        camera,
        objects: &objects,
        background: 0,
        ambient: 0,
        lights: &[],
    };
    let renderer = Renderer::for_scene(&scene).unwrap();
    let n = w as usize * h as usize;
    let (mut pixels, mut depths) = (vec![0u8; n], vec![0u32; n]);
    let mut frame = Framebuffer::new(&mut pixels, w, h).unwrap();
    let mut depth = DepthBuffer::new(&mut depths, w, h).unwrap();
    let mut scratch = vec![PreparedVertex::default(); mesh.vertices().len()];
    let mut stats = RenderStats::default();
    render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats).unwrap();

    // The reference camera: the core's basis (I16F16), eye, exact scales.
    let (wv, vv, uv, o) = (
        f(camera.right()),
        f(camera.up()),
        f(camera.forward()),
        f(camera.position()),
    );
    let extent = view.extent.to_num::<f64>();
    let s = match view.axis {
        FovAxis::Vertical => h as f64 / extent,
        FovAxis::Horizontal => w as f64 / extent,
        FovAxis::Diagonal => unreachable!(),
    };
    let (i0, j0) = ((w as f64 - 1.0) / 2.0, (h as f64 - 1.0) / 2.0);
    let (near, far) = (view.near.to_num::<f64>(), view.far.to_num::<f64>());
    let full = 4294967295.0;
    let dscale = full / (far - near);
    let screen = |p: V| {
        let q = sub(p, o);
        (i0 + s * dot(q, wv), j0 - s * dot(q, vv))
    };
    let verts: Vec<V> = mesh.vertices().iter().map(|&v| f(v)).collect();
    let mut tris = Vec::new();
    let mut edges = Vec::new();
    for poly in mesh.polygons() {
        for k in 1..poly.len() - 1 {
            tris.push([poly[0], poly[k], poly[k + 1]].map(|i| verts[i as usize]));
        }
        for k in 0..poly.len() {
            let (a, b) = (
                verts[poly[k] as usize],
                verts[poly[(k + 1) % poly.len()] as usize],
            );
            edges.push((screen(a), screen(b)));
        }
    }
    let delta = 1.0 / 16.0;
    let (mut compared, mut differ) = (0, 0);
    for j in 0..h as i32 {
        for i in 0..w as i32 {
            let (x, y) = ((i as f64 - i0) / s, -(j as f64 - j0) / s);
            let origin = |x: f64, y: f64| [0, 1, 2].map(|k| o[k] + x * wv[k] + y * vv[k]);
            let mut best: Option<(f64, [V; 3])> = None;
            for t in &tris {
                // The object culls back faces (outward normal along the view direction).
                if dot(cross(sub(t[1], t[0]), sub(t[2], t[0])), uv) >= 0.0 {
                    continue;
                }
                if let Some((tt, _)) = hit(origin(x, y), uv, t[0], t[1], t[2]) {
                    if tt >= near && tt <= far && best.is_none_or(|b| tt < b.0) {
                        best = Some((tt, *t));
                    }
                }
            }
            // Within the rounding of the near or far plane's cut of the visible face: the
            // clipped polygon's new edge (the plane's change over δ plus the z error).
            let at_plane = |t: f64| {
                let b = 4.0 / 65536.0 + 2.0 * delta / s;
                (t - near).abs() <= b || (t - far).abs() <= b
            };
            let mut all = Vec::new();
            for tri in &tris {
                if let Some((tt, _)) = hit(origin(x, y), uv, tri[0], tri[1], tri[2]) {
                    all.push(tt);
                }
            }
            let cut = all.iter().any(|&t| at_plane(t));
            let near_edge = cut
                || edges
                    .iter()
                    .any(|&(a, b)| seg_dist((i as f64, j as f64), a, b) <= delta + 0.01);
            let got = depth.get(i, j).unwrap();
            let covered = got != u32::MAX;
            if covered != best.is_some() {
                assert!(
                    near_edge,
                    "pixel ({i}, {j}): core covered {covered}, reference {:?}",
                    best.map(|b| b.0)
                );
                differ += 1;
                continue;
            }
            let (Some((t, tri)), false) = (best, near_edge) else {
                continue;
            };
            // The plane's change over δ in x and y.
            let d = delta / s;
            let slope = [(d, 0.0), (-d, 0.0), (0.0, d), (0.0, -d)]
                .iter()
                .map(|&(dx, dy)| {
                    (plane_t(origin(x + dx, y + dy), uv, tri[0], tri[1], tri[2]) - t).abs()
                })
                .fold(0.0, f64::max);
            let want = (t - near) * dscale;
            let allow = (slope + 2.0 / 65536.0) * dscale + 1.0;
            assert!(
                (got as f64 - want).abs() <= allow,
                "pixel ({i}, {j}): depth {got}, reference {want:.1} (allowed ±{allow:.1})"
            );
            compared += 1;
        }
    }
    (compared, differ)
}

#[test]
fn cube_and_sphere_match_the_reference() {
    let view = |e: &str| {
        OrthoView::new(
            Coord::from_num(e.parse::<f64>().unwrap()),
            Coord::lit("0.5"),
            Coord::lit("10"),
        )
    };
    let (c, d) = check(unit_cube(), [3, 2, 4], view("3"), 160, 120);
    assert!(c > 2000, "{c} {d}");
    let (mut vs, mut is) = (vec![Vec3::ZERO; 600], vec![0u16; 4000]);
    let sphere = uv_sphere(16, 10, Coord::lit("1.2"), &mut vs, &mut is).unwrap();
    let (c, d) = check(
        sphere,
        [-2, 3, 5],
        view("3.5").with_axis(FovAxis::Horizontal),
        150,
        100,
    );
    assert!(c > 3000, "{c} {d}");
    // A view cut by the near and the far plane (the cube spans z = 3.71 to 5.39).
    let tight = OrthoView::new(Coord::lit("2"), Coord::lit("4.1"), Coord::lit("4.6"));
    let (c, _) = check(unit_cube(), [3, 2, 4], tight, 96, 96);
    assert!(c > 1000, "{c}");
}

/// The orthographic camera's scene picture does not depend on the eye's distance (only the
/// depth does): the same view from twice as far covers the same pixels.
#[test]
fn parallel_projection_ignores_distance() {
    let render = |eye: [i32; 3]| {
        let view = OrthoView::new(Coord::lit("3"), Coord::lit("0.5"), Coord::lit("30"));
        let camera = Camera::look_at_orthographic(
            Vec3::from_int(eye[0], eye[1], eye[2]),
            Vec3::ZERO,
            Vec3::from_int(0, 1, 0),
            view,
            Viewport::new(64, 48),
        )
        .unwrap();
        let objects = [Object::new(unit_cube())];
        let scene = Scene {
            camera,
            objects: &objects,
            background: 0,
            ambient: 0,
            lights: &[],
        };
        let renderer = Renderer::for_scene(&scene).unwrap();
        let (mut pixels, mut depths) = (vec![0u8; 64 * 48], vec![0u16; 64 * 48]);
        let mut frame = Framebuffer::new(&mut pixels, 64, 48).unwrap();
        let mut depth = DepthBuffer::new(&mut depths, 64, 48).unwrap();
        let mut scratch = [PreparedVertex::default(); 8];
        render_scene(
            &renderer,
            &mut frame,
            &mut depth,
            &mut scratch,
            &mut RenderStats::default(),
        )
        .unwrap();
        pixels
    };
    let (a, b) = (render([2, 2, 2]), render([8, 8, 8]));
    assert!(a.iter().filter(|&&p| p != 0).count() > 300);
    assert_eq!(a, b);
}

/// The stages whose arithmetic is the perspective's own refuse an orthographic camera in
/// words, naming themselves: the shadow pass (its back-projection inverts `A − K/z`), its
/// depth slack, a perspective shadow map built from the camera, and the planner.
#[test]
fn perspective_only_stages_refuse_it_by_name() {
    use zscan::render::ProjectError;
    use zscan::render::RenderError;
    use zscan::shadow::{observer_depth_slack, ShadowError, ShadowMap, ShadowPass};
    use zscan::visibility::{plan, MeshFacts, PlanError};
    let view = OrthoView::new(Coord::lit("3"), Coord::lit("0.5"), Coord::lit("10"));
    let camera = Camera::look_at_orthographic(
        Vec3::from_int(0, 0, 4),
        Vec3::ZERO,
        Vec3::from_int(0, 1, 0),
        view,
        Viewport::new(32, 24),
    )
    .unwrap();
    let named = |e: ProjectError, stage: &str| {
        assert!(matches!(e, ProjectError::Orthographic(_)), "{e:?}");
        let words = e.to_string();
        assert!(
            words.contains(stage) && words.contains("orthographic"),
            "{words}"
        );
    };
    let mut samples = vec![0u16; 16 * 16];
    let map = ShadowMap::new(
        &mut samples,
        16,
        16,
        Vec3::from_int(0, 1, 0),
        Vec3::ZERO,
        Coord::lit("2"),
    )
    .unwrap();
    match ShadowPass::new(&map, &camera, 0) {
        Err(ShadowError::Projection(e)) => named(e, "shadow pass"),
        other => panic!("{:?}", other.err()),
    }
    match observer_depth_slack::<u16>(&camera, Coord::lit("5")) {
        Err(ShadowError::Projection(e)) => named(e, "depth slack"),
        other => panic!("{other:?}"),
    }
    let mut more = vec![0u16; 32 * 24];
    match ShadowMap::from_camera(&mut more, &camera) {
        Err(ShadowError::Projection(e)) => named(e, "perspective shadow map"),
        other => panic!("{:?}", other.err()),
    }
    let cube = unit_cube();
    let objects = [Object::new(cube)];
    let scene = Scene {
        camera,
        objects: &objects,
        background: 0,
        ambient: 0,
        lights: &[],
    };
    let mut words = vec![0u32; MeshFacts::words_needed(&cube)];
    let facts = [MeshFacts::of(&cube, &mut words).unwrap()];
    let mut order = [0u16; 1];
    match plan::<4>(&scene, &facts, 1 << 20, &mut order) {
        Err(PlanError::Camera(RenderError::Projection(e))) => named(e, "the planner"),
        other => panic!("{other:?}"),
    }
}
