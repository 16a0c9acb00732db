//! 3D lines, points and wireframes (`render::lines`) against independent references:
//! - the pixels of the exact segment between the core's sub-pixel end points, and the depth
//!   of that segment at each pixel correctly rounded, evaluated here by definition in `i128`
//!   (no walking);
//! - the `f64` camera of the host (`scenes::Camera`): the segment clipped to `[near, far]` in
//!   `f64` and projected, every drawn pixel within half a pixel (plus the projector's 1/32 and
//!   the coordinates' rounding) of it along the minor axis, every pixel of its `f64` definition
//!   away from a rounding tie drawn, the depth within the end points' error;
//! - lines crossing the near plane, behind the eye, out to `±2^30` raw units; the errors.
use zscan::internals::Projector;
use zscan::prelude::*;
use zscan::raster::depth_line::Walk;
use zscan::render::{LineStyle, RenderError, Wireframe, MAX_POINT_SIZE};
use zscan_host::core_render::{core_camera, to_core};
use zscan_host::scenes::{self, Camera as HostCamera};

const W: usize = 320;
const H: usize = 240;
const D32: f64 = 4294967295.0;

fn host() -> HostCamera {
    HostCamera::standard()
}

fn camera() -> Camera {
    core_camera(&host()).unwrap()
}

fn c(v: f64) -> Coord {
    Coord::from_num(v)
}

/// The host's `f64` depth of a view point at distance `z`: `(2^32 − 1)·far·(z − near) /
/// (z·(far − near))`.
fn d64(z: f64) -> f64 {
    let h = host();
    D32 * h.far * (z - h.near) / (z * (h.far - h.near))
}

/// Draws `segments` of the vertices `points` (world, I16F16 through `transform`) with depth
/// `u32` cleared far and offset 0; returns frame and depth.
fn draw(
    points: &[Vec3],
    segments: &[[u16; 2]],
    transform: Affine3,
    walk: Walk,
) -> (Vec<u8>, Vec<u32>, u32) {
    let mesh = Mesh::triangles(points, &[]).unwrap();
    let mut object = Object::new(mesh);
    object.transform = transform;
    let renderer = Renderer::<4>::new(&camera()).unwrap();
    let (mut pixels, mut depths) = (vec![0u8; W * H], vec![u32::MAX; W * H]);
    let mut frame = Framebuffer::new(&mut pixels, W as u16, H as u16).unwrap();
    let mut depth = DepthBuffer::new(&mut depths, W as u16, H as u16).unwrap();
    let mut scratch = vec![PreparedVertex::default(); points.len()];
    let mut style = LineStyle::new(1);
    style.depth_offset = 0;
    style.walk = walk;
    let n = renderer
        .draw_lines(
            &object,
            segments,
            &mut scratch,
            &style,
            &mut frame,
            &mut depth,
        )
        .unwrap();
    (pixels, depths, n)
}

/// The pixels of the exact segment between sub-pixel ends (units of 1/16 pixel) inside the
/// screen, each with its correctly rounded depth: the definition of `raster::line` and
/// `raster::depth_line`, evaluated per pixel centre.
fn by_definition(p0: (i64, i64), p1: (i64, i64), d0: u32, d1: u32) -> Vec<((i64, i64), u32)> {
    let u = 16i128;
    let (dx, dy) = ((p1.0 - p0.0) as i128, (p1.1 - p0.1) as i128);
    let xm = dx.abs() >= dy.abs();
    let (m0, m1, v0, v1) = if xm {
        (p0.0 as i128, p1.0 as i128, p0.1 as i128, p1.1 as i128)
    } else {
        (p0.1 as i128, p1.1 as i128, p0.0 as i128, p1.0 as i128)
    };
    let n = (m1 - m0).abs();
    let mut out = Vec::new();
    let (lo, hi) = (m0.min(m1), m0.max(m1));
    let mut m = (lo + u - 1).div_euclid(u);
    while m * u <= hi {
        let delta = (m * u - m0).abs();
        let (num, den) = if n == 0 {
            (v0, u)
        } else {
            (v0 * n + delta * (v1 - v0), n * u)
        };
        // Nearest, ties toward the smaller: the largest k with k − 1/2 < num/den.
        let mut k = num.div_euclid(den);
        while 2 * (k + 1) * den - den < 2 * num {
            k += 1;
        }
        while 2 * k * den - den >= 2 * num {
            k -= 1;
        }
        let d = if n == 0 {
            d0.min(d1) as i128
        } else {
            let num = 2 * d0 as i128 * n + 2 * delta * (d1 as i128 - d0 as i128) + n;
            num.div_euclid(2 * n)
        };
        let p = if xm {
            (m as i64, k as i64)
        } else {
            (k as i64, m as i64)
        };
        if (0..W as i64).contains(&p.0) && (0..H as i64).contains(&p.1) {
            out.push((p, d as u32));
        }
        m += 1;
    }
    out
}

fn drawn(pixels: &[u8], depths: &[u32]) -> Vec<((i64, i64), u32)> {
    let mut v = Vec::new();
    for y in 0..H {
        for x in 0..W {
            if pixels[y * W + x] != 0 {
                v.push(((x as i64, y as i64), depths[y * W + x]));
            }
        }
    }
    v
}

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn f(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The `f64` segment of world points `a`–`b` (exact coordinates `f64` of the I16F16 values),
/// clipped to `near ≤ z ≤ far` and projected, with the `f64` depths of its ends; `None` when
/// nothing is left.
fn float_segment(a: [f64; 3], b: [f64; 3]) -> Option<[((f64, f64), f64); 2]> {
    let h = host();
    let (mut va, mut vb) = (h.to_view(a), h.to_view(b));
    for (plane, sign) in [(h.near, 1.0), (h.far, -1.0)] {
        let (da, db) = (sign * (va[2] - plane), sign * (vb[2] - plane));
        if da < 0.0 && db < 0.0 {
            return None;
        }
        let cut = |p: [f64; 3], q: [f64; 3], dp: f64, dq: f64| {
            let t = dp / (dp - dq);
            [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), plane]
        };
        if da < 0.0 {
            va = cut(vb, va, db, da);
        } else if db < 0.0 {
            vb = cut(va, vb, da, db);
        }
    }
    Some([
        (h.project_view(va), d64(va[2])),
        (h.project_view(vb), d64(vb[2])),
    ])
}

/// Checks the drawn pixels against the `f64` segment: each within `0.5 + eps` pixel of it
/// along the minor axis and at a major coordinate within its extent (± eps), with a depth
/// within `depth_tol` of the `f64` depth there; each pixel of the `f64` segment's own
/// definition that is farther than `eps` from a rounding tie or an end drawn. Returns how
/// many pixels were compared.
fn against_float(
    got: &[((i64, i64), u32)],
    seg: Option<[((f64, f64), f64); 2]>,
    eps: f64,
    depth_tol: f64,
    what: &str,
) -> usize {
    let Some([(p0, d0), (p1, d1)]) = seg else {
        assert!(
            got.is_empty(),
            "{what}: drew {} pixels of nothing",
            got.len()
        );
        return 0;
    };
    let (adx, ady) = ((p1.0 - p0.0).abs(), (p1.1 - p0.1).abs());
    // Near a diagonal the core's major axis (on its rounded ends) may be the other one.
    let ambiguous = (adx - ady).abs() < 0.2;
    let xm = adx >= ady;
    let frame_of = |xm: bool| {
        let pick = |p: (f64, f64)| if xm { p } else { (p.1, p.0) };
        let ((m0, v0), (m1, v1)) = (pick(p0), pick(p1));
        move |m: f64| {
            let s = if m1 == m0 { 0.0 } else { (m - m0) / (m1 - m0) };
            (
                v0 + s * (v1 - v0),
                d0 + s * (d1 - d0),
                m0.min(m1),
                m0.max(m1),
            )
        }
    };
    for &((x, y), d) in got {
        let fits = |xm: bool| -> Result<(), String> {
            let (m, k) = if xm { (x, y) } else { (y, x) };
            let (v, dref, lo, hi) = frame_of(xm)(m as f64);
            let m = m as f64;
            if m < lo - eps || m > hi + eps {
                return Err(format!("outside the segment's extent {lo}..{hi}"));
            }
            if (k as f64 - v).abs() > 0.5 + eps {
                return Err(format!("{} from the segment", (k as f64 - v).abs()));
            }
            if (d as f64 - dref).abs() > depth_tol {
                return Err(format!("depth {d}, f64 {dref}"));
            }
            Ok(())
        };
        let verdict = fits(xm);
        if let Err(e) = verdict {
            assert!(
                ambiguous && fits(!xm).is_ok(),
                "{what}: pixel ({x}, {y}): {e}"
            );
        }
    }
    if ambiguous {
        return got.len();
    }
    let at = frame_of(xm);
    let (_, _, m0, m1) = at(0.0);
    let set: std::collections::HashSet<(i64, i64)> = got.iter().map(|g| g.0).collect();
    let (lo, hi) = (m0.min(m1), m0.max(m1));
    let mut m = (lo + eps).ceil();
    while m <= hi - eps {
        let (v, _, _, _) = at(m);
        let frac = v - v.floor();
        let clear_of_tie = (frac - 0.5).abs() > eps;
        let k = (v - 0.5).ceil();
        let p = if xm {
            (m as i64, k as i64)
        } else {
            (k as i64, m as i64)
        };
        let inside = (0..W as i64).contains(&p.0) && (0..H as i64).contains(&p.1);
        if clear_of_tie && inside {
            assert!(set.contains(&p), "{what}: f64 pixel {p:?} not drawn");
        }
        m += 1.0;
    }
    got.len()
}

/// The world point of I16F16 `v` as `f64`.
fn f(v: Vec3) -> [f64; 3] {
    v.bits().map(|c| c as f64 / 65536.0)
}

/// Lines wholly inside the view: pixels and depths equal the definition on the core's own
/// projected end points, and lie on the `f64` segment.
#[test]
fn lines_inside_the_view_match_the_definition_and_the_float_camera() {
    let cam = camera();
    let projector = Projector::<4>::new(&cam).unwrap();
    let mut rng = Rng(0x5EED_1133_7000_0001);
    let mut compared = 0;
    for i in 0..400 {
        let mut p = || {
            Vec3::new(
                c(rng.f(-1.5, 1.5)),
                c(rng.f(-1.1, 1.1)),
                c(rng.f(-4.0, 1.5)),
            )
        };
        let (a, b) = (p(), p());
        let walk = if i % 2 == 0 {
            Walk::OneEnded
        } else {
            Walk::TwoEnded
        };
        let (pixels, depths, n) = draw(&[a, b], &[[0, 1]], Affine3::default(), walk);
        let got = drawn(&pixels, &depths);
        assert_eq!(n as usize, got.len());
        let view = |v: Vec3| cam.view_transform().transform_point(v);
        let ends = [a, b].map(|v| projector.project_point(view(v)));
        if let [Ok((s0, d0)), Ok((s1, d1))] = ends {
            let all_inside = |s: zscan::raster::SubpixelPoint<4>| {
                (0..W as i32 * 16).contains(&s.x) && (0..H as i32 * 16).contains(&s.y)
            };
            if all_inside(s0) && all_inside(s1) {
                let mut want = by_definition(
                    (s0.x as i64, s0.y as i64),
                    (s1.x as i64, s1.y as i64),
                    d0,
                    d1,
                );
                want.sort();
                let mut g = got.clone();
                g.sort();
                assert_eq!(g, want, "{a:?} {b:?}");
            }
        }
        // Depth: the end points' f64 depth error (z rounded to 2^-16 through the view
        // transform: |dD/dz|·2^-14 at the nearer end) plus 1/32 pixel of the slope.
        let seg = float_segment(f(a), f(b));
        let tol = seg.map_or(0.0, |[(p0, e0), (p1, e1)]| {
            let len = (p1.0 - p0.0).abs().max((p1.1 - p0.1).abs()).max(1.0);
            let zmin = 1.5;
            D32 * 0.5 * 10.0 / 9.5 / (zmin * zmin) * 2f64.powi(-14)
                + (e1 - e0).abs() / len / 16.0
                + 16.0
        });
        compared += against_float(&got, seg, 0.07, tol, &format!("{a:?} {b:?}"));
    }
    assert!(compared > 20000, "{compared}");
}

/// Lines crossing the near plane (one end behind the eye), and lines wholly behind it.
#[test]
fn lines_crossing_the_near_plane_and_behind_the_eye() {
    let mut rng = Rng(0x0BE1_11D0_0000_0002);
    let mut crossing = 0;
    for i in 0..300 {
        // The eye is at z = 3 looking toward −z: z > 3 is behind it.
        let a = Vec3::new(
            c(rng.f(-1.0, 1.0)),
            c(rng.f(-0.8, 0.8)),
            c(rng.f(-3.0, 2.0)),
        );
        let b = Vec3::new(c(rng.f(-6.0, 6.0)), c(rng.f(-6.0, 6.0)), c(rng.f(3.2, 9.0)));
        let (a, b) = if i % 3 == 0 {
            // Wholly behind: nothing drawn.
            let a = Vec3::new(a.x, a.y, c(rng.f(3.0, 8.0)));
            (a, b)
        } else {
            (a, b)
        };
        let (pixels, depths, _) = draw(&[b, a], &[[0, 1]], Affine3::default(), Walk::OneEnded);
        let got = drawn(&pixels, &depths);
        let seg = float_segment(f(b), f(a));
        if i % 3 == 0 {
            assert!(got.is_empty() && seg.is_none(), "behind: {a:?} {b:?}");
            continue;
        }
        let tol = seg.map_or(0.0, |[(p0, e0), (p1, e1)]| {
            let len = (p1.0 - p0.0).abs().max((p1.1 - p0.1).abs()).max(1.0);
            D32 * 0.5 * 10.0 / 9.5 / 0.25 * 2f64.powi(-14) + (e1 - e0).abs() / len / 8.0 + 64.0
        });
        crossing += against_float(&got, seg, 0.1, tol, &format!("near {a:?} {b:?}"));
    }
    assert!(crossing > 5000, "{crossing}");
}

/// Segments whose far ends reach `±2^30` raw units (16384 world units, through a scale of
/// 16 on mesh coordinates of 1024): clipped by the guard band and the far plane, still on
/// the `f64` segment.
#[test]
fn lines_out_to_two_to_the_thirty() {
    let big = 1024.0;
    let scale = Affine3::builder().scale(c(16.0)).build().unwrap();
    let mut compared = 0;
    for (x, y, z) in [
        (big, big, -big),
        (-big, big, -big),
        (big, -big, big),
        (-big, 0.0, -big),
        (0.0, -big, -big),
        (big, 0.5, 0.0),
    ] {
        let near_end = Vec3::new(c(0.01), c(-0.02), c(0.0));
        let far_end = Vec3::new(c(x), c(y), c(z));
        let (pixels, depths, _) = draw(&[near_end, far_end], &[[0, 1]], scale, Walk::OneEnded);
        let got = drawn(&pixels, &depths);
        let w = |v: Vec3| f(v).map(|c| c * 16.0);
        let seg = float_segment(w(near_end), w(far_end));
        assert!(far_end.bits()[0].unsigned_abs() * 16 <= 1 << 30);
        compared += against_float(&got, seg, 0.1, 1e6, &format!("far {x} {y} {z}"));
    }
    assert!(compared > 100, "{compared}");
}

fn cube_and_bunny() -> Vec<zscan_host::core_render::CoreMesh> {
    ["cube", "sphere", "bunny"]
        .iter()
        .map(|n| to_core(&scenes::standard_scene(n).unwrap()).unwrap())
        .collect()
}

/// Draws `core`'s object as a wireframe in `mode` (16-bit depth, cleared), returning frame
/// and depth.
fn wire(
    core: &zscan_host::core_render::CoreMesh,
    mode: Wireframe,
    walk: Walk,
) -> Result<(Vec<u8>, Vec<u16>, u32), RenderError> {
    let mesh = core.mesh().unwrap();
    let object = Object::new(mesh);
    let mut edges = vec![[0u16; 2]; mesh.indices().len()];
    let k = mesh.edges(&mut edges).unwrap();
    let renderer = Renderer::<4>::new(&core.camera)?;
    let (mut pixels, mut depths) = (vec![0u8; W * H], vec![u16::MAX; W * H]);
    let mut frame = Framebuffer::new(&mut pixels, W as u16, H as u16).unwrap();
    let mut depth = DepthBuffer::new(&mut depths, W as u16, H as u16).unwrap();
    let mut scratch = vec![PreparedVertex::default(); core.vertices.len()];
    let mut style = LineStyle::new(255);
    style.walk = walk;
    let n = renderer.draw_wireframe(
        &object,
        &edges[..k],
        mode,
        &mut scratch,
        &style,
        &mut frame,
        &mut depth,
    )?;
    Ok((pixels, depths, n))
}

/// Both walks give the same frame and depth buffer, in every mode.
#[test]
fn two_ended_walk_equals_one_ended() {
    for core in cube_and_bunny() {
        for mode in [Wireframe::All, Wireframe::Front, Wireframe::Hidden] {
            let one = wire(&core, mode, Walk::OneEnded).unwrap();
            let two = wire(&core, mode, Walk::TwoEnded).unwrap();
            assert!(one.2 > 100);
            assert!(one == two, "{mode:?}");
        }
    }
}

/// Edges of the surfaces show on them: for the convex cube and sphere, the hidden-line
/// picture (faces into depth, then every edge) is the front edges' picture (Roberts), pixel
/// for pixel; for every mesh, every front edge's pixel drawn in front mode is drawn in hidden
/// mode, up to the few pixels a nearer front surface covers.
#[test]
fn hidden_lines_show_the_front_edges() {
    for (i, core) in cube_and_bunny().iter().enumerate() {
        let front = wire(core, Wireframe::Front, Walk::OneEnded).unwrap().0;
        let hidden = wire(core, Wireframe::Hidden, Walk::OneEnded).unwrap().0;
        let all = wire(core, Wireframe::All, Walk::OneEnded).unwrap().0;
        let count = |p: &[u8]| p.iter().filter(|&&v| v != 0).count();
        let only_front = (0..W * H)
            .filter(|&k| front[k] != 0 && hidden[k] == 0)
            .count();
        let only_hidden = (0..W * H)
            .filter(|&k| front[k] == 0 && hidden[k] != 0)
            .count();
        eprintln!(
            "mesh {i}: all {} front {} hidden {} front-not-hidden {only_front} hidden-not-front {only_hidden}",
            count(&all),
            count(&front),
            count(&hidden)
        );
        assert!(count(&hidden) < count(&all));
        if i < 2 {
            assert_eq!((only_front, only_hidden), (0, 0), "convex mesh {i}");
        }
    }
}

/// Points: each vertex inside the view at the pixel nearest its `f64` projection (within
/// the projector's 1/32 pixel of a tie), squares of the given side, hidden behind a nearer
/// surface.
#[test]
fn points_land_on_the_nearest_pixel() {
    let mut rng = Rng(0x9017_5000_0000_0003);
    let points: Vec<Vec3> = (0..200)
        .map(|_| {
            Vec3::new(
                c(rng.f(-1.5, 1.5)),
                c(rng.f(-1.1, 1.1)),
                c(rng.f(-4.0, 1.5)),
            )
        })
        .collect();
    let renderer = Renderer::<4>::new(&camera()).unwrap();
    let object = Object::new(Mesh::triangles(&points, &[]).unwrap());
    let mut scratch = vec![PreparedVertex::default(); points.len()];
    for size in [1u8, 3, 4] {
        let (mut pixels, mut depths) = (vec![0u8; W * H], vec![u32::MAX; W * H]);
        let mut frame = Framebuffer::new(&mut pixels, W as u16, H as u16).unwrap();
        let mut depth = DepthBuffer::new(&mut depths, W as u16, H as u16).unwrap();
        let style = LineStyle::new(7);
        renderer
            .draw_points(&object, &mut scratch, size, &style, &mut frame, &mut depth)
            .unwrap();
        let (lo, hi) = ((size as i64 - 1) / 2, size as i64 / 2);
        for p in &points {
            let Some((x, y)) = host().project(f(*p)) else {
                continue;
            };
            let tie = |v: f64| ((v - v.floor()) - 0.5).abs() < 0.04;
            if tie(x) || tie(y) {
                continue;
            }
            let (px, py) = ((x - 0.5).ceil() as i64, (y - 0.5).ceil() as i64);
            for dy in -lo..=hi {
                for dx in -lo..=hi {
                    let (qx, qy) = (px + dx, py + dy);
                    if (0..W as i64).contains(&qx) && (0..H as i64).contains(&qy) {
                        assert_eq!(pixels[qy as usize * W + qx as usize], 7, "{p:?} {size}");
                    }
                }
            }
        }
        let drawn = pixels.iter().filter(|&&v| v != 0).count();
        assert!(drawn <= points.len() * (size as usize).pow(2));
    }
}

/// Bad input is refused in words, nothing drawn.
#[test]
fn bad_input_is_refused() {
    let points = [Vec3::ZERO, Vec3::from_int(1, 0, 0)];
    let renderer = Renderer::<4>::new(&camera()).unwrap();
    let object = Object::new(Mesh::triangles(&points, &[]).unwrap());
    let mut scratch = [PreparedVertex::default(); 2];
    let (mut pixels, mut depths) = (vec![0u8; W * H], vec![u16::MAX; W * H]);
    let mut frame = Framebuffer::new(&mut pixels, W as u16, H as u16).unwrap();
    let mut depth = DepthBuffer::new(&mut depths, W as u16, H as u16).unwrap();
    let style = LineStyle::new(1);
    let e = renderer
        .draw_lines(
            &object,
            &[[0, 1], [1, 2]],
            &mut scratch,
            &style,
            &mut frame,
            &mut depth,
        )
        .unwrap_err();
    assert_eq!(
        e,
        RenderError::SegmentOutOfRange {
            segment: 1,
            vertex: 2,
            vertices: 2
        }
    );
    assert!(e.to_string().contains("segment 1 names vertex 2"), "{e}");
    for size in [0, MAX_POINT_SIZE + 1] {
        let e = renderer
            .draw_points(&object, &mut scratch, size, &style, &mut frame, &mut depth)
            .unwrap_err();
        assert!(e.to_string().contains("the side must be 1 to 16"), "{e}");
    }
    let mut short = [PreparedVertex::default(); 1];
    assert!(matches!(
        renderer.draw_lines(
            &object,
            &[[0, 1]],
            &mut short,
            &style,
            &mut frame,
            &mut depth
        ),
        Err(RenderError::ScratchTooSmall {
            given: 1,
            needed: 2
        })
    ));
    assert!(pixels.iter().all(|&p| p == 0));
    let mut small = vec![0u8; 10 * 10];
    let mut frame = Framebuffer::new(&mut small, 10, 10).unwrap();
    assert!(matches!(
        renderer.draw_lines(
            &object,
            &[[0, 1]],
            &mut scratch,
            &style,
            &mut frame,
            &mut depth
        ),
        Err(RenderError::TargetSmallerThanViewport { .. })
    ));
    let cube = unit_cube();
    let mut edges = [[0u16; 2]; 10];
    let e = cube.edges(&mut edges).unwrap_err();
    assert!(format!("{e:?}").contains("Edges"), "{e:?}");
    let mut edges = vec![[0u16; 2]; cube.indices().len()];
    let k = cube.edges(&mut edges).unwrap();
    // A cube of quads has 12 edges, of triangles 18: each once.
    assert!(k == 12 || k == 18, "{k}");
    let mut sorted = edges[..k].to_vec();
    sorted.dedup();
    assert_eq!(sorted.len(), k);
}
