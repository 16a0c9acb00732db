//! Geometry, clipping and projection checked against independent `f64` computations.

use zscan::geometry::camera::{frame_sphere, Camera, FovAxis, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::{hollow_prism, torus, unit_cube, uv_sphere, uv_sphere_sizes};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::trig::{sin_cos_bits, BinaryAngle};
use zscan::geometry::vector::Vec3;
use zscan::internals::Projector;
use zscan::internals::{ClipVertex, ClipVolume, Frustum};
use zscan::render::ProjectError;
use zscan_host::obj::load_obj;

type F3 = [f64; 3];

fn v(p: F3) -> Vec3 {
    Vec3::new(
        Coord::from_num(p[0]),
        Coord::from_num(p[1]),
        Coord::from_num(p[2]),
    )
}

fn f(p: Vec3) -> F3 {
    [p.x.to_num(), p.y.to_num(), p.z.to_num()]
}

fn dot(a: F3, b: F3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: F3, b: F3) -> F3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: F3, b: F3) -> F3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: F3) -> F3 {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

use zscan_host::test_rng::XorShift as Rng;

fn scenes_lens() -> Lens {
    Lens {
        fov: BinaryAngle::from_degrees(60),
        axis: FovAxis::Vertical,
        near: Coord::from_num(0.5),
        far: Coord::from_num(10),
    }
}

fn scenes_camera() -> Camera {
    Camera::look_at(
        v([0.0, 0.0, 3.0]),
        Vec3::ZERO,
        v([0.0, 1.0, 0.0]),
        scenes_lens(),
        Viewport::new(320, 240),
    )
    .unwrap()
}

#[test]
fn trig_error_bound_random_angles() {
    let mut r = Rng::new(0x1234_5678_9ABC_DEF1);
    let mut worst = 0.0f64;
    for _ in 0..1_000_000 {
        let a = r.next_u64() as u32;
        let (s, c) = sin_cos_bits(BinaryAngle(a));
        let t = a as f64 / 4_294_967_296.0 * std::f64::consts::TAU;
        let k = (1u64 << 30) as f64;
        worst = worst
            .max((s as f64 - t.sin() * k).abs())
            .max((c as f64 - t.cos() * k).abs());
    }
    assert!(worst <= 0.51, "worst {worst} units of 2^-30");
}

fn f64_rot(axis: usize, deg: f64) -> [F3; 3] {
    let (s, c) = deg.to_radians().sin_cos();
    match axis {
        0 => [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]],
        1 => [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
        _ => [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
    }
}

fn apply(m: &[F3; 3], p: F3) -> F3 {
    [dot(m[0], p), dot(m[1], p), dot(m[2], p)]
}

#[test]
fn matrix_composition_and_rigid_inverse_vs_f64() {
    // SCENES.md's cube placement: v' = Rx(20°)·Ry(30°)·v, then a translation.
    let m = Affine3::translation(v([0.25, -1.0, 2.5]))
        .mul(
            &Affine3::rotation_x(BinaryAngle::from_degrees(20))
                .mul(&Affine3::rotation_y(BinaryAngle::from_degrees(30)))
                .unwrap(),
        )
        .unwrap();
    let inv = m.inverse_rigid().unwrap();
    let (rx, ry) = (f64_rot(0, 20.0), f64_rot(1, 30.0));
    let mut r = Rng::new(99);
    for _ in 0..10_000 {
        let p = [
            r.uniform(-50.0, 50.0),
            r.uniform(-50.0, 50.0),
            r.uniform(-50.0, 50.0),
        ];
        let q = apply(&rx, apply(&ry, p));
        let q = [q[0] + 0.25, q[1] - 1.0, q[2] + 2.5];
        let got = f(m.transform_point(v(p)));
        for i in 0..3 {
            assert!((got[i] - q[i]).abs() < 5e-5, "{got:?} vs {q:?}");
        }
        let back = f(inv.transform_point(v(q)));
        for i in 0..3 {
            assert!((back[i] - p[i]).abs() < 5e-5, "{back:?} vs {p:?}");
        }
    }
    // An arbitrary axis against Rodrigues in f64.
    let axis = norm([1.0, -2.0, 0.5]);
    let g = Affine3::rotation_axis(v([1.0, -2.0, 0.5]), BinaryAngle::from_degrees(77)).unwrap();
    let (s, c) = 77f64.to_radians().sin_cos();
    for p in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.3, 0.4, -2.0]] {
        let k = axis;
        let kxp = cross(k, p);
        let kd = dot(k, p);
        let e: F3 = std::array::from_fn(|i| p[i] * c + kxp[i] * s + k[i] * kd * (1.0 - c));
        let got = f(g.transform_point(v(p)));
        for i in 0..3 {
            assert!((got[i] - e[i]).abs() < 3e-5);
        }
    }
}

#[test]
fn camera_basis_is_orthonormal_and_matches_course() {
    let mut r = Rng::new(7);
    for _ in 0..2000 {
        let pos = [
            r.uniform(-100.0, 100.0),
            r.uniform(-100.0, 100.0),
            r.uniform(-100.0, 100.0),
        ];
        let dir = [
            r.uniform(-1.0, 1.0),
            r.uniform(-1.0, 1.0),
            r.uniform(-1.0, 1.0),
        ];
        let up = [
            r.uniform(-1.0, 1.0),
            r.uniform(-1.0, 1.0),
            r.uniform(-1.0, 1.0),
        ];
        let cam = match Camera::new(
            v(pos),
            v(dir),
            v(up),
            scenes_lens(),
            Viewport::new(320, 240),
        ) {
            Ok(c) => c,
            Err(_) => continue, // degenerate draws (parallel up) are errors, not panics
        };
        let l = cam.view_transform();
        let rows: [F3; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| l.entry(i, j).to_num::<f64>()));
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((dot(rows[i], rows[j]) - e).abs() < 1e-6);
            }
        }
        // f64 course construction: U = dir/|dir|, V ∝ V' − (U·V')U, W = U × V.
        let u = norm(f(v(dir)));
        let vp = norm(f(v(up)));
        let vv = norm(sub(vp, u.map(|c| c * dot(u, vp))));
        if dot(vp, u).abs() > 0.999 {
            continue;
        }
        let w = cross(u, vv);
        for i in 0..3 {
            assert!((rows[0][i] - w[i]).abs() < 1e-5);
            assert!((rows[1][i] - vv[i]).abs() < 1e-5);
            assert!((rows[2][i] - u[i]).abs() < 1e-5);
        }
    }
    // Course exercise 3: P = (2, 2, 4), U = (−1, −1, −2), V' = (0, 0, 1). The point P + U lies
    // on the optical axis at depth |U| = √6; the cube's corners match the f64 change of frame.
    let (p, u, up) = ([2.0, 2.0, 4.0], [-1.0, -1.0, -2.0], [0.0, 0.0, 1.0]);
    let cam = Camera::new(v(p), v(u), v(up), scenes_lens(), Viewport::new(512, 512)).unwrap();
    let o = f(cam.to_observer(v([1.0, 1.0, 2.0])));
    assert!(o[0].abs() < 1e-4 && o[1].abs() < 1e-4 && (o[2] - 6f64.sqrt()).abs() < 1e-4);
    let uu = norm(u);
    let vv = norm(sub(up, uu.map(|c| c * dot(uu, up))));
    let ww = cross(uu, vv);
    for i in 0..8 {
        let c = [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64];
        let d = sub(c, p);
        let e = [dot(d, ww), dot(d, vv), dot(d, uu)];
        let g = f(cam.to_observer(v(c)));
        for k in 0..3 {
            assert!((g[k] - e[k]).abs() < 1e-4, "corner {i}: {g:?} vs {e:?}");
        }
    }
}

#[test]
fn projection_of_known_points_vs_f64() {
    let cam = scenes_camera();
    let proj: Projector<4> = Projector::new(&cam).unwrap();
    let fl = 120.0 / 30f64.to_radians().tan();
    let (near, far) = (0.5, 10.0);
    for p in [
        [0.5, 0.5, 0.0],
        [0.0, 0.0, 0.0],
        [-1.0, 0.7, 1.2],
        [0.5, -0.5, -0.5],
        [3.0, 2.0, -5.0],
    ] {
        let o = cam.to_observer(v(p));
        let (s, d) = proj.project_point(o).unwrap();
        // The f64 reference from the exact point, for x and y (sub-pixel) ...
        let z = 3.0 - p[2];
        let ex = (159.5 + fl * p[0] / z) * 16.0;
        let ey = (119.5 - fl * p[1] / z) * 16.0;
        assert!((s.x as f64 - ex).abs() <= 0.6, "{p:?}: {} vs {ex}", s.x);
        assert!((s.y as f64 - ey).abs() <= 0.6, "{p:?}: {} vs {ey}", s.y);
        // ... and for depth from the I16F16 observer z actually projected (a 2^-17 error in z
        // moves the 32-bit depth by thousands of units, far more than the projector's own error).
        let z = f(o)[2];
        let ed = 4_294_967_295.0 * far * (z - near) / (z * (far - near));
        assert!((d as f64 - ed).abs() <= 64.0, "{p:?}: depth {d} vs {ed}");
    }
    // (0.5, 0.5, 0): 159.5 + 207.846·0.5/3 = 194.141 px, 119.5 − 34.641 = 84.859 px.
    let (s, _) = proj
        .project_point(cam.to_observer(v([0.5, 0.5, 0.0])))
        .unwrap();
    assert_eq!((s.x, s.y), (3106, 1358));
    // Behind the near plane.
    assert_eq!(
        proj.project_point(cam.to_observer(v([0.0, 0.0, 2.75]))),
        Err(ProjectError::BehindNearPlane)
    );
}

#[test]
fn non_square_pixels_and_diagonal_fov() {
    let mut vp = Viewport::new(320, 240);
    vp.pixel_width = 4;
    vp.pixel_height = 3;
    let lens = Lens {
        axis: FovAxis::Diagonal,
        ..scenes_lens()
    };
    let cam = Camera::new(
        Vec3::ZERO,
        v([0.0, 0.0, -1.0]),
        v([0.0, 1.0, 0.0]),
        lens,
        vp,
    )
    .unwrap();
    let r = ((320.0f64 * 4.0).powi(2) + (240.0f64 * 3.0).powi(2)).sqrt() / 2.0;
    let d = r / 30f64.to_radians().tan();
    assert!((cam.focal_x().to_num::<f64>() - d / 4.0).abs() < 1e-3);
    assert!((cam.focal_y().to_num::<f64>() - d / 3.0).abs() < 1e-3);
}

#[test]
fn frame_sphere_vs_f64() {
    for (rad, deg) in [(1.0, 60), (0.25, 30), (5.0, 90), (2.0, 10)] {
        let (eye, d) = frame_sphere(
            v([1.0, 2.0, 3.0]),
            Coord::from_num(rad),
            v([0.0, 0.0, -2.0]),
            BinaryAngle::from_degrees(deg),
        )
        .unwrap();
        let e = rad / (deg as f64 / 2.0).to_radians().sin();
        assert!((d.to_num::<f64>() - e).abs() < 1e-3, "{d} vs {e}");
        let ef = f(eye);
        assert!((ef[2] - (3.0 + e)).abs() < 1e-3 && (ef[0] - 1.0).abs() < 1e-4);
    }
    // The camera version: the sphere's silhouette touches the top and bottom edges (240 < 320).
    let (cam, d) = Camera::framing_sphere(
        Vec3::ZERO,
        Coord::ONE,
        v([0.0, 0.0, -1.0]),
        v([0.0, 1.0, 0.0]),
        scenes_lens(),
        Viewport::new(320, 240),
    )
    .unwrap();
    // tan α = 120 / f, sin α = 120/√(120² + f²) ⇒ D = √(120² + f²)/120.
    let fl = cam.focal_y().to_num::<f64>();
    let e = (120f64.powi(2) + fl * fl).sqrt() / 120.0;
    assert!((d.to_num::<f64>() - e).abs() < 1e-3, "{d} vs {e}");
    assert!((d.to_num::<f64>() - 2.0).abs() < 1e-3); // 1/sin 30°
}

#[test]
fn generators_counts_positions_and_normals() {
    let (nv, ni) = uv_sphere_sizes(32, 16);
    let mut vs = vec![Vec3::ZERO; nv];
    let mut is = vec![0u16; ni];
    let m = uv_sphere(32, 16, Coord::ONE, &mut vs, &mut is).unwrap();
    assert_eq!((m.vertices().len(), m.polygon_count()), (482, 960));
    // Positions against f64 (SCENES.md's formula).
    for k in 1..16 {
        for j in 0..32 {
            let (t, p) = (
                std::f64::consts::PI * k as f64 / 16.0,
                std::f64::consts::TAU * j as f64 / 32.0,
            );
            let e = [t.sin() * p.cos(), t.cos(), -t.sin() * p.sin()];
            let g = f(m.vertices()[1 + (k - 1) * 32 + j]);
            for i in 0..3 {
                assert!((g[i] - e[i]).abs() <= 1.0 / 65536.0);
            }
        }
    }
    // Vertex normals against f64 area-weighted sums: within 2^-14 of each other.
    let mut vn = vec![Vec3::ZERO; nv];
    m.vertex_normals(&mut vn).unwrap();
    let fv: Vec<F3> = m.vertices().iter().map(|&p| f(p)).collect();
    let mut acc = vec![[0.0; 3]; nv];
    for p in m.polygons() {
        let n = cross(
            sub(fv[p[1] as usize], fv[p[0] as usize]),
            sub(fv[p[2] as usize], fv[p[0] as usize]),
        );
        for &i in p {
            for c in 0..3 {
                acc[i as usize][c] += n[c];
            }
        }
    }
    for i in 0..nv {
        let e = norm(acc[i]);
        let g = f(vn[i]);
        for c in 0..3 {
            assert!((g[c] - e[c]).abs() < 1.0 / 16384.0, "vertex {i}");
        }
        // Outward: nearly radial on a sphere.
        assert!(dot(g, norm(fv[i])) > 0.99);
    }
    // Course exercise 4 and the torus: counts and enclosed volume (divergence theorem).
    let volume = |m: &Mesh| -> f64 {
        let mut s = 0.0;
        for p in m.polygons() {
            let a = f(m.vertices()[p[0] as usize]);
            for w in p[1..].windows(2) {
                s += dot(
                    a,
                    cross(
                        f(m.vertices()[w[0] as usize]),
                        f(m.vertices()[w[1] as usize]),
                    ),
                );
            }
        }
        s / 6.0
    };
    let mut hv = [Vec3::ZERO; 24];
    let mut hi = [0u16; 96];
    let h = hollow_prism(
        6,
        Coord::ONE,
        Coord::from_num(0.8),
        Coord::ONE,
        &mut hv,
        &mut hi,
    )
    .unwrap();
    assert_eq!((h.vertices().len(), h.polygon_count()), (24, 24));
    let hex = |r: f64| 1.5 * 3f64.sqrt() * r * r;
    let e = (hex(1.0) - hex(0.8)) * 2.0;
    assert!((volume(&h) - e).abs() < 1e-3, "{} vs {e}", volume(&h));
    let mut tv = vec![Vec3::ZERO; 48 * 24];
    let mut ti = vec![0u16; 4 * 48 * 24];
    let t = torus(
        48,
        24,
        Coord::from_num(2),
        Coord::from_num(0.5),
        &mut tv,
        &mut ti,
    )
    .unwrap();
    let e = 2.0 * std::f64::consts::PI.powi(2) * 2.0 * 0.25;
    assert!((volume(&t) - e).abs() / e < 0.02, "{} vs {e}", volume(&t));
    assert!((volume(&unit_cube()) - 1.0).abs() < 1e-9);
}

#[test]
fn culling_matches_f64_on_the_sphere() {
    let (nv, ni) = uv_sphere_sizes(32, 16);
    let mut vs = vec![Vec3::ZERO; nv];
    let mut is = vec![0u16; ni];
    let m = uv_sphere(32, 16, Coord::from_num(1.124146), &mut vs, &mut is).unwrap();
    let eye = v([0.0, 0.0, 3.0]);
    let mut front = 0;
    for p in m.polygons() {
        let q: Vec<F3> = p.iter().map(|&i| f(m.vertices()[i as usize])).collect();
        let n = cross(sub(q[1], q[0]), sub(q[2], q[0]));
        let e = dot(sub(f(eye), q[0]), n) > 0.0;
        assert_eq!(m.is_front_facing(p, eye), e);
        front += e as usize;
    }
    assert!(front > 200 && front < 480, "{front}");
}

#[test]
fn clipping_random_polygons() {
    let cam = scenes_camera();
    let fr = Frustum::new::<4>(&cam, Frustum::DEFAULT_GUARD).unwrap();
    let proj: Projector<4> = Projector::new(&cam).unwrap();
    let mut r = Rng::new(4242);
    let (mut clipped, mut empty) = (0, 0);
    for _ in 0..20_000 {
        let n = 3 + (r.next_u64() % 4) as usize;
        let poly: Vec<ClipVertex<1>> = (0..n)
            .map(|_| {
                let p = [
                    r.uniform(-30.0, 30.0),
                    r.uniform(-30.0, 30.0),
                    r.uniform(-5.0, 15.0),
                ];
                ClipVertex::new(v(p), [(r.next_u64() % 256) as i32])
            })
            .collect();
        // Random polygons are often self-intersecting: a plane can add more than one vertex.
        let out = fr.clip::<1, 24>(&poly).unwrap();
        if out.is_empty() {
            empty += 1;
            continue;
        }
        clipped += 1;
        let near = Coord::from_num(0.5);
        for c in &out {
            assert!(c.pos.z >= near, "{c:?}");
            assert!((0..=255).contains(&c.attrs[0]));
            let s = proj.project(c).unwrap();
            assert!(
                s.point.x.abs() < 16 * 1400 && s.point.y.abs() < 16 * 1400,
                "{s:?}"
            );
        }
    }
    assert!(clipped > 1000 && empty > 1000, "{clipped} {empty}");
}

#[test]
fn extreme_inputs_never_panic() {
    let cam = scenes_camera();
    let fr = Frustum::new::<4>(&cam, 4).unwrap();
    let proj: Projector<4> = Projector::new(&cam).unwrap();
    let proj16: Projector<16> = Projector::new(&cam).unwrap();
    let mut r = Rng::new(1);
    let pick = |r: &mut Rng| -> i32 {
        match r.next_u64() % 4 {
            0 => [i32::MIN, i32::MAX, 0, 1, -1][(r.next_u64() % 5) as usize],
            1 => (r.next_u64() as i32) >> (r.next_u64() % 31),
            _ => r.next_u64() as i32,
        }
    };
    for _ in 0..200_000 {
        let p = Vec3::from_bits(pick(&mut r), pick(&mut r), pick(&mut r));
        let q = Vec3::from_bits(pick(&mut r), pick(&mut r), pick(&mut r));
        let _ = cam.view_transform().transform_point(p);
        let _ = proj.project_point(p);
        let _ = proj16.project_point(p);
        let _ = p.normalize();
        let _ = p.cross(q);
        let _ = fr.clip::<0, 10>(&[
            ClipVertex::new(p, []),
            ClipVertex::new(q, []),
            ClipVertex::new(p.add(q), []),
        ]);
        let _ = Camera::new(
            p,
            q,
            p,
            scenes_lens(),
            Viewport::new(pick(&mut r) as u16, 240),
        );
        let _ = frame_sphere(p, q.x, q, BinaryAngle(pick(&mut r) as u32));
        let _ = Affine3::rotation_axis(p, BinaryAngle(q.x.to_bits() as u32)).map(|m| m.mul(&m));
    }
    // Random cameras: projector and frustum construction, and the projection of clipped
    // polygons, never panic.
    for _ in 0..20_000 {
        let p = Vec3::from_bits(pick(&mut r), pick(&mut r), pick(&mut r));
        let q = Vec3::from_bits(pick(&mut r), pick(&mut r), pick(&mut r));
        let lens = Lens {
            fov: BinaryAngle(pick(&mut r) as u32),
            axis: [FovAxis::Vertical, FovAxis::Horizontal, FovAxis::Diagonal]
                [(r.next_u64() % 3) as usize],
            near: Coord::from_bits(pick(&mut r)),
            far: Coord::from_bits(pick(&mut r)),
        };
        let mut vp = Viewport::new(r.next_u64() as u16, r.next_u64() as u16);
        vp.pixel_width = r.next_u64() as u16;
        vp.pixel_height = r.next_u64() as u16;
        vp.principal_x = Coord::from_bits(pick(&mut r));
        if let Ok(cam) = Camera::new(p, q, v([0.0, 1.0, 0.0]), lens, vp) {
            let pr = Projector::<4>::new(&cam);
            let pr16 = Projector::<16>::new(&cam);
            let frustums = [
                Frustum::new::<4>(&cam, 4),
                Frustum::new::<16>(&cam, u16::MAX),
            ];
            for fr in frustums.into_iter().flatten() {
                let tri = [0, 1, 2].map(|_| {
                    ClipVertex::new(
                        Vec3::from_bits(pick(&mut r), pick(&mut r), pick(&mut r)),
                        [pick(&mut r)],
                    )
                });
                if let Ok(out) = fr.clip::<1, 9>(&tri) {
                    for c in &out {
                        if let Ok(pr) = &pr {
                            let _ = pr.project(c);
                        }
                        if let Ok(pr) = &pr16 {
                            let _ = pr.project(c);
                        }
                    }
                }
            }
        }
        let _ = Camera::framing_sphere(p, q.x, q, p, lens, vp);
    }
    // Random meshes in range: normals, culling, vertex normals.
    for _ in 0..2_000 {
        let n = 3 + (r.next_u64() % 20) as usize;
        let lim = 1 << 26;
        let vs: Vec<Vec3> = (0..n)
            .map(|_| Vec3::from_bits(pick(&mut r) % lim, pick(&mut r) % lim, pick(&mut r) % lim))
            .collect();
        let is: Vec<u16> = (0..3 * n)
            .map(|_| (r.next_u64() % n as u64) as u16)
            .collect();
        let m = Mesh::triangles(&vs, &is).unwrap();
        let mut vn = vec![Vec3::ZERO; n];
        m.vertex_normals(&mut vn).unwrap();
        let mut fnrm = vec![Vec3::ZERO; n];
        m.face_normals(&mut fnrm).unwrap();
        let eye = Vec3::from_bits(pick(&mut r), pick(&mut r), pick(&mut r));
        for p in m.polygons() {
            let _ = m.is_front_facing(p, eye);
        }
    }
    // Points clipped at the guard band project; wild points are errors, never wrong values.
    let wild = Vec3::from_bits(i32::MAX, i32::MIN, 1 << 15);
    assert_eq!(proj16.project_point(wild), Err(ProjectError::OutOfRange));
}

#[test]
fn bunny_obj() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/meshes/bunny.obj");
    let m = load_obj(path).unwrap();
    assert_eq!(m.vertices.len(), 1839);
    assert_eq!(m.polygons.len(), 3674);
    assert_eq!(m.triangle_count(), 3674);
    assert!(m.signed_volume() > 0.0);
    // Into the core, centred and scaled to about ±1 (SCENES.md's fit is 0.2 on the raw data).
    let (lo, hi) = m.bounds();
    let c: F3 = std::array::from_fn(|i| (lo[i] + hi[i]) / 2.0);
    let (vs, is, ss) = m
        .to_zscan(|p| std::array::from_fn(|i| (p[i] - c[i]) * 0.2))
        .unwrap();
    let mesh = Mesh::new(&vs, &is, PolygonSizes::PerPolygon(&ss)).unwrap();
    let mut vn = vec![Vec3::ZERO; vs.len()];
    mesh.vertex_normals(&mut vn).unwrap();
    // Against f64 normals from the f64 vertices: within 0.5° except where the sum nearly cancels.
    let fv: Vec<F3> = m
        .vertices
        .iter()
        .map(|p| std::array::from_fn(|i| (p[i] - c[i]) * 0.2))
        .collect();
    let mut acc = vec![[0.0; 3]; fv.len()];
    for p in &m.polygons {
        let n = cross(sub(fv[p[1]], fv[p[0]]), sub(fv[p[2]], fv[p[0]]));
        for &i in p {
            for k in 0..3 {
                acc[i][k] += n[k];
            }
        }
    }
    let mut bad = 0;
    for i in 0..fv.len() {
        if dot(acc[i], acc[i]) == 0.0 {
            continue;
        }
        if dot(norm(acc[i]), f(vn[i])) < 0.5f64.to_radians().cos() {
            bad += 1;
        }
    }
    assert!(bad <= 5, "{bad} vertex normals off by more than 0.5°");
}

/// The course's exercise 1 (ch. 1): for unit vectors `V1`, `V2` at angle `θ`, the dot product
/// is `cos θ` and the cross product is a vector of length `sin θ` perpendicular to both, in
/// the direction that makes `(V1, V2, V1 × V2)` right-handed. The answer, from the component
/// formulas: rotate the frame so that `V1 = (1, 0, 0)` and `V2 = (cos θ, sin θ, 0)` (both
/// products are unchanged by rotation); then `V1 · V2 = cos θ` and `V1 × V2 = (0, 0, sin θ)`.
/// Checked on the fixed-point vectors: `Vec3::dot` and `Vec3::cross_wide` are exact on the
/// I16F16 components, so the only error is the components' rounding (2^-17 each).
#[test]
fn course_exercise_1_dot_and_cross_of_unit_vectors() {
    let mut checked = 0;
    for a in (0..360).step_by(15) {
        for b in (0..180).step_by(20) {
            for t in (0..360).step_by(25) {
                // V1 on the unit sphere at azimuth a and polar angle b; V2 at angle t from V1,
                // turned about an axis perpendicular to V1.
                let (a, b, t) = (
                    (a as f64).to_radians(),
                    (b as f64).to_radians(),
                    (t as f64).to_radians(),
                );
                let v1 = [b.sin() * a.cos(), b.cos(), b.sin() * a.sin()];
                let axis = if b.sin().abs() > 0.5 {
                    [0.0, 1.0, 0.0]
                } else {
                    [1.0, 0.0, 0.0]
                };
                let p = cross(v1, axis);
                let p = p.map(|x| x / dot(p, p).sqrt());
                let q = cross(v1, p);
                let v2: F3 = std::array::from_fn(|k| t.cos() * v1[k] + t.sin() * q[k]);
                let (u1, u2) = (v(v1), v(v2));
                let dot_q32 = u1.dot(u2) as f64 / 2f64.powi(32);
                assert!(
                    (dot_q32 - t.cos()).abs() < 4e-5,
                    "dot {dot_q32} vs cos {}",
                    t.cos()
                );
                let c = u1.cross_wide(u2).map(|x| x as f64 / 2f64.powi(32));
                let length = dot(c, c).sqrt();
                assert!(
                    (length - t.sin().abs()).abs() < 4e-5,
                    "|cross| {length} vs |sin| {}",
                    t.sin()
                );
                assert!(
                    dot(c, f(u1)).abs() < 4e-5 && dot(c, f(u2)).abs() < 4e-5,
                    "not perpendicular"
                );
                // The direction: with V2 = cos θ·V1 + sin θ·q (q ⟂ V1), V1 × V2 = sin θ·(V1 × q).
                let want = cross(v1, q).map(|x| x * t.sin());
                assert!(
                    (0..3).all(|k| (c[k] - want[k]).abs() < 4e-5),
                    "{c:?} vs {want:?}"
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 24 * 9 * 15);
}
