//! Shadow maps for point and directional lights (`zscan::shadow`) against a float64
//! ground truth, and the shadow pass over rendered frames.
//!
//! - Acne and leaking on a floor with a unit box standing on it, lit by a point light (and by
//!   a directional one): the truth is the exact ray–box test from each floor sample toward the
//!   light; samples within 1.5 texels *of the map* of the shadow's outline (found through a
//!   float model of the map's projection) are left out. Three biases: too small (acne), the
//!   documented rule (`ShadowMap::plane_bias`: no acne, no leaking), too large (leaking).
//! - Stability: a point light inside the scene's bounding sphere and 0.01 above the box, so
//!   that the box's polygons cross the light's near plane; lights far away or at extreme
//!   coordinates; zero sizes and degenerate inputs → the documented errors, never a panic.
//! - The pass over a rendered frame: back-projected points lie on the floor; floor pixels
//!   shadowed exactly where the truth says, outside the outline's band; band by band gives
//!   the same picture as one pass.
//! - Pictures: `target/shadow-{point,acne,leak}.png` (copied to `docs/images/`).
use std::path::PathBuf;

use embedded_graphics::pixelcolor::Rgb888;
use zscan::geometry::camera::{Camera, FovAxis, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::unit_cube;
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::lighting::{Light, Material};
use zscan::output::{DepthBuffer, DepthValue, Framebuffer, Lut};
use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
use zscan::render::{render_scene, PreparedVertex, Renderer};
use zscan::scene::{Intensities, Object, Scene};
use zscan::shadow::{
    observer_depth_slack, DepthSample, ShadowError, ShadowMap, ShadowPass, Visibility,
};
use zscan_host::image::write_image;

fn c(v: f64) -> Coord {
    Coord::from_num(v)
}

fn v3(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(c(x), c(y), c(z))
}

fn f3(v: Vec3) -> [f64; 3] {
    v.bits().map(|b| b as f64 / 65536.0)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The box: the unit cube moved to `[-½, ½] × [0, 1] × [-½, ½]`.
fn box_place() -> Affine3 {
    Affine3::translation(v3(-0.5, 0.0, -0.5))
}

/// Under the box (and 0.05 around it): left out of every count.
fn under_box(p: [f64; 3]) -> bool {
    p[0].abs() < 0.55 && p[2].abs() < 0.55
}

/// Does `o + t·d` meet the box for some `t ∈ (1e-9, t_max]`? (slabs)
fn hits_box(o: [f64; 3], d: [f64; 3], t_max: f64) -> bool {
    let (lo, hi) = ([-0.5, 0.0, -0.5], [0.5, 1.0, 0.5]);
    let (mut t0, mut t1) = (1e-9f64, t_max);
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k] < lo[k] || o[k] > hi[k] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[k] - o[k]) / d[k], (hi[k] - o[k]) / d[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

/// The light, in f64.
#[derive(Clone, Copy)]
enum Lamp {
    Point([f64; 3]),
    /// Toward the light.
    Directional([f64; 3]),
}

impl Lamp {
    /// Ground truth: the box lies between floor point `p` and the light.
    fn shadowed(&self, p: [f64; 3]) -> bool {
        match *self {
            Lamp::Point(l) => hits_box(p, sub(l, p), 1.0),
            Lamp::Directional(t) => hits_box(p, t, f64::INFINITY),
        }
    }
}

/// A float model of a map's projection, from its documented parameters (light frame, focal
/// lengths and principal point, or `u = (w − 1)/2 + x·w/2r`): texel coordinates of a world
/// point, and the floor point (`y = 0`) seen through given texel coordinates.
struct MapModel {
    rows: [[f64; 3]; 3],
    t: [f64; 3],
    persp: bool,
    /// Texels per unit of `x/z` (perspective) or of `x` (orthographic).
    kx: f64,
    ky: f64,
    i0: f64,
    j0: f64,
}

impl MapModel {
    fn new<D: DepthValue>(map: &ShadowMap<'_, D>, radius: f64) -> MapModel {
        let a = map.light_frame();
        let rows = a
            .linear_bits()
            .map(|r| r.map(|e| e as f64 / (1u64 << 24) as f64));
        let t = f3(a.translation_part());
        let (w, h) = (map.width() as f64, map.height() as f64);
        match map.light_camera() {
            Some(cam) => MapModel {
                rows,
                t,
                persp: true,
                kx: cam.focal_x().to_num::<f64>(),
                ky: cam.focal_y().to_num::<f64>(),
                i0: cam.viewport().principal_x.to_num::<f64>(),
                j0: cam.viewport().principal_y.to_num::<f64>(),
            },
            None => MapModel {
                rows,
                t,
                persp: false,
                kx: w / (2.0 * radius),
                ky: h / (2.0 * radius),
                i0: (w - 1.0) / 2.0,
                j0: (h - 1.0) / 2.0,
            },
        }
    }

    fn texel(&self, p: [f64; 3]) -> (f64, f64) {
        let q: [f64; 3] = std::array::from_fn(|i| dot(self.rows[i], p) + self.t[i]);
        if self.persp {
            (
                self.i0 + self.kx * q[0] / q[2],
                self.j0 - self.ky * q[1] / q[2],
            )
        } else {
            (self.i0 + self.kx * q[0], self.j0 - self.ky * q[1])
        }
    }

    /// Rᵀ·v
    fn back(&self, v: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| (0..3).map(|k| self.rows[k][i] * v[k]).sum())
    }

    fn floor_point(&self, u: f64, v: f64) -> Option<[f64; 3]> {
        let (x, y) = ((u - self.i0) / self.kx, -(v - self.j0) / self.ky);
        let (o_l, d_l) = if self.persp {
            ([0.0; 3], [x, y, 1.0])
        } else {
            ([x, y, 0.0], [0.0, 0.0, 1.0])
        };
        let o = self.back(sub(o_l, self.t));
        let d = self.back(d_l);
        if d[1].abs() < 1e-12 {
            return None;
        }
        let s = -o[1] / d[1];
        Some([o[0] + s * d[0], 0.0, o[2] + s * d[2]])
    }

    /// True when the truth changes within `texels` texels of the map around floor point `p`.
    fn near_outline(&self, lamp: &Lamp, p: [f64; 3], texels: f64) -> bool {
        let truth = lamp.shadowed(p);
        let (u, v) = self.texel(p);
        (0..16).any(|k| {
            let a = k as f64 * std::f64::consts::TAU / 16.0;
            [0.5, 1.0].iter().any(|f| {
                let r = f * texels;
                self.floor_point(u + r * a.cos(), v + r * a.sin())
                    .is_some_and(|q| lamp.shadowed(q) != truth)
            })
        })
    }
}

/// A floor `[-half, half]²` at `y = 0` as `n × n` quads facing up, with its vertex normals.
struct Floor {
    vertices: Vec<Vec3>,
    indices: Vec<u16>,
    normals: Vec<Vec3>,
}

impl Floor {
    fn new(half: f64, n: usize) -> Floor {
        let mut vertices = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let x = -half + 2.0 * half * j as f64 / n as f64;
                let z = -half + 2.0 * half * i as f64 / n as f64;
                vertices.push(v3(x, 0.0, z));
            }
        }
        let mut indices = Vec::new();
        let k = |i: usize, j: usize| (i * (n + 1) + j) as u16;
        for i in 0..n {
            for j in 0..n {
                // Counter-clockwise seen from above (+y).
                indices.extend([k(i, j), k(i + 1, j), k(i + 1, j + 1), k(i, j + 1)]);
            }
        }
        let normals = vec![Vec3::from_int(0, 1, 0); vertices.len()];
        Floor {
            vertices,
            indices,
            normals,
        }
    }

    fn mesh(&self) -> Mesh<'_> {
        Mesh::new(&self.vertices, &self.indices, PolygonSizes::Uniform(4)).unwrap()
    }
}

/// Acne and leaking counts over the floor samples kept.
#[derive(Debug, Default, Clone, Copy)]
struct Counts {
    lit: u32,
    shaded: u32,
    acne: u32,
    leak: u32,
    outside: u32,
    /// Samples left out in the outline's band.
    band: u32,
    /// Farthest leaking sample from the box (world units).
    leak_far: f64,
}

/// The floor samples (step 0.05 inside `[-half + 0.1, half − 0.1]²`, not under the box) with
/// their truth, and whether they lie in the 1.5-texel band of the outline.
fn floor_samples(model: &MapModel, lamp: &Lamp, half: f64) -> Vec<([f64; 3], bool, bool)> {
    let n = ((2.0 * half - 0.2) / 0.05).round() as i32;
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let p = [
                -half + 0.1 + i as f64 * 0.05,
                0.0,
                -half + 0.1 + j as f64 * 0.05,
            ];
            if !under_box(p) {
                out.push((p, lamp.shadowed(p), model.near_outline(lamp, p, 1.5)));
            }
        }
    }
    out
}

fn measure<D: DepthValue>(
    map: &ShadowMap<'_, D>,
    samples: &[([f64; 3], bool, bool)],
    bias: u32,
) -> Counts {
    let mut k = Counts::default();
    for &(p, truth, band) in samples {
        if band {
            k.band += 1;
            continue;
        }
        let vis = map.classify(v3(p[0], p[1], p[2]), bias);
        k.outside += (vis == Visibility::Outside) as u32;
        if truth {
            k.shaded += 1;
            if vis.is_lit() {
                k.leak += 1;
                k.leak_far = k.leak_far.max((p[0].abs() - 0.5).max(p[2].abs() - 0.5));
            }
        } else {
            k.lit += 1;
            if !vis.is_lit() {
                k.acne += 1;
            }
        }
    }
    k
}

fn report(name: &str, bias: u32, rule: u32, k: &Counts) {
    eprintln!(
        "{name}: bias {bias} ({:.3} × rule): acne {}/{} lit ({:.2}%), leaking {}/{} shadowed \
         ({:.2}%), farthest leak {:.2} from the box, outside {}, band {}",
        bias as f64 / rule as f64,
        k.acne,
        k.lit,
        100.0 * k.acne as f64 / k.lit.max(1) as f64,
        k.leak,
        k.shaded,
        100.0 * k.leak as f64 / k.shaded.max(1) as f64,
        k.leak_far,
        k.outside,
        k.band
    );
}

const LIGHT: [f64; 3] = [2.5, 3.5, 1.5];
const CENTRE: [f64; 3] = [0.0, 0.5, 0.0];
const HALF: f64 = 2.5;
const RADIUS: f64 = 3.6; // > √(2.5² + 2.5² + 0.5²) = 3.57: the floor's corners are inside

/// Point light at (3, 5, 2) over a 6 × 6 floor and the unit box, 128 × 128 map: acne with a
/// quarter of the rule's bias, none with the rule, leaking with 16 times the rule.
#[test]
fn point_light_acne_and_leaking() {
    let floor = Floor::new(HALF, 6);
    let mut store = vec![0u16; 128 * 128];
    let l = v3(LIGHT[0], LIGHT[1], LIGHT[2]);
    let centre = v3(CENTRE[0], CENTRE[1], CENTRE[2]);
    let mut map = ShadowMap::point(&mut store, 128, 128, l, centre, c(RADIUS)).unwrap();
    map.render(&floor.mesh(), &Affine3::IDENTITY).unwrap();
    map.render(&unit_cube(), &box_place()).unwrap();
    let cam = map.light_camera().unwrap();
    eprintln!(
        "point map: f = {:.2} texels, near {:.3}, far {:.3}",
        cam.focal_x().to_num::<f64>(),
        cam.lens().near.to_num::<f64>(),
        cam.lens().far.to_num::<f64>()
    );
    let model = MapModel::new(&map, RADIUS);
    let lamp = Lamp::Point(LIGHT);
    let samples = floor_samples(&model, &lamp, HALF);
    let rule = map.plane_bias(Vec3::from_int(0, 1, 0), Vec3::ZERO, Coord::ZERO);
    let sweep = [0, rule / 4, rule / 2, rule, 16 * rule, 64 * rule];
    let counts: Vec<Counts> = sweep.iter().map(|&b| measure(&map, &samples, b)).collect();
    for (b, k) in sweep.iter().zip(&counts) {
        report("point light", *b, rule, k);
    }
    let (small, good, large) = (&counts[1], &counts[3], &counts[5]);
    assert!(good.lit > 5000 && good.shaded > 300, "{good:?}");
    assert_eq!(good.outside, 0, "the framed map covers the whole floor");
    assert_eq!((good.acne, good.leak), (0, 0), "{good:?}");
    assert!(
        small.acne * 100 > small.lit,
        "too little bias: acne expected, {small:?}"
    );
    assert!(
        large.leak * 5 > large.shaded,
        "too much bias: leaking expected, {large:?}"
    );
}

/// The same measurement for a directional light from (1, 1, 0.5) (as `lighting.rs`, whose
/// biases are multiples of `texel_depth`): the plane rule gives no acne and no leaking.
#[test]
fn directional_light_plane_rule() {
    let floor = Floor::new(4.0, 2);
    let mut store = vec![0u32; 128 * 128];
    let toward = [1.0, 1.0, 0.5];
    let t = v3(toward[0], toward[1], toward[2]);
    let centre = v3(CENTRE[0], CENTRE[1], CENTRE[2]);
    let mut map = ShadowMap::new(&mut store, 128, 128, t, centre, c(6.0)).unwrap();
    map.render(&floor.mesh(), &Affine3::IDENTITY).unwrap();
    map.render(&unit_cube(), &box_place()).unwrap();
    let model = MapModel::new(&map, 6.0);
    let lamp = Lamp::Directional(toward);
    let samples = floor_samples(&model, &lamp, 3.6);
    let rule = map.plane_bias(Vec3::from_int(0, 1, 0), Vec3::ZERO, Coord::ZERO);
    let texel = map.texel_depth() as f64;
    eprintln!(
        "directional rule: {rule} = {:.3} texel depths",
        rule as f64 / texel
    );
    let sweep = [rule / 4, rule, 64 * rule];
    let counts: Vec<Counts> = sweep.iter().map(|&b| measure(&map, &samples, b)).collect();
    for (b, k) in sweep.iter().zip(&counts) {
        report("directional light", *b, rule, k);
    }
    let (small, good, large) = (&counts[0], &counts[1], &counts[2]);
    assert_eq!((good.acne, good.leak, good.outside), (0, 0, 0), "{good:?}");
    assert!(small.acne * 100 > small.lit, "{small:?}");
    assert!(large.leak * 5 > large.shaded, "{large:?}");
}

/// A point light inside the bounding sphere, 0.01 above the box's top face: the map's near
/// plane (far/256 ≈ 0.016) lies inside the box, the top face is wholly nearer (dropped) and
/// the side faces cross it (clipped). Nothing panics; floor points whose ray to the light
/// leaves the box through a side are shadowed; points outside the 120° cone are outside.
#[test]
fn point_light_inside_sphere_crossing_near_plane() {
    let floor = Floor::new(HALF, 4);
    let mut store = vec![0u32; 96 * 96];
    let l = [0.0, 1.01, 0.0];
    let centre = v3(CENTRE[0], CENTRE[1], CENTRE[2]);
    let mut map =
        ShadowMap::point(&mut store, 96, 96, v3(l[0], l[1], l[2]), centre, c(RADIUS)).unwrap();
    map.render(&floor.mesh(), &Affine3::IDENTITY).unwrap();
    map.render(&unit_cube(), &box_place()).unwrap();
    let cam = map.light_camera().unwrap();
    let near = cam.lens().near.to_num::<f64>();
    assert!(near > 0.01 && near < 0.03, "near {near}");
    let fov_half = (48.0 / cam.focal_y().to_num::<f64>()).atan().to_degrees();
    assert!(
        (fov_half - 60.0).abs() < 0.01,
        "capped half field of view {fov_half}"
    );
    let lamp = Lamp::Point(l);
    let rule = map.plane_bias(Vec3::from_int(0, 1, 0), Vec3::ZERO, Coord::ZERO);
    let (mut inside, mut outside) = (0, 0);
    for i in -60..=60 {
        for j in -60..=60 {
            let p = [i as f64 * 0.05, 0.0, j as f64 * 0.05];
            let rho = p[0].hypot(p[2]);
            let vis = map.classify(v3(p[0], 0.0, p[2]), rule);
            // Slightly inside the cone (1.01·tan 60° = 1.749), away from the box's edge.
            if rho < 1.65 && !under_box(p) {
                assert!(lamp.shadowed(p), "{p:?}");
                assert_eq!(vis, Visibility::Shadowed, "{p:?}");
                inside += 1;
            }
            // Outside the square map: beyond 1.01·tan 60° along the light frame's axes (world
            // x and z: the light looks straight down with up = world x).
            if p[0].abs().max(p[2].abs()) > 1.85 {
                assert_eq!(vis, Visibility::Outside, "{p:?}");
                outside += 1;
            }
        }
    }
    assert!(inside > 2_000 && outside > 8_000, "{inside} {outside}");
    // A point nearer to the light than the near plane is outside the map (lit).
    assert_eq!(map.classify(v3(0.0, 1.0, 0.0), rule), Visibility::Outside);
    // Behind the light (above it) too.
    assert_eq!(map.classify(v3(0.2, 2.0, 0.1), rule), Visibility::Outside);
}

/// Far, extreme and degenerate inputs: documented errors or documented results, no panic.
#[test]
fn extreme_and_degenerate_inputs() {
    let centre = v3(CENTRE[0], CENTRE[1], CENTRE[2]);
    let r = c(RADIUS);
    let mut s = vec![0u16; 64 * 64];
    let up = Vec3::from_int(0, 1, 0);
    // Sizes.
    assert_eq!(
        ShadowMap::new(&mut s, 0, 8, up, centre, r).err(),
        Some(ShadowError::BadSize)
    );
    assert_eq!(
        ShadowMap::new(&mut s[..10], 8, 8, up, centre, r).err(),
        Some(ShadowError::BadSize)
    );
    assert_eq!(
        ShadowMap::point(&mut s, 3, 8, v3(0.0, 5.0, 0.0), centre, r).err(),
        Some(ShadowError::BadSize)
    );
    assert_eq!(
        ShadowMap::point(&mut [0u16; 0][..], 4, 4, v3(0.0, 5.0, 0.0), centre, r).err(),
        Some(ShadowError::BadSize)
    );
    let mut big = vec![0u16; 1 << 20];
    assert_eq!(
        ShadowMap::new(&mut big, 1024, 1024, up, centre, r).err(),
        Some(ShadowError::BadSize)
    );
    // Light and radius.
    assert_eq!(
        ShadowMap::new(&mut s, 8, 8, Vec3::ZERO, centre, r).err(),
        Some(ShadowError::BadLight)
    );
    assert_eq!(
        ShadowMap::new(&mut s, 8, 8, up, centre, Coord::ZERO).err(),
        Some(ShadowError::BadLight)
    );
    assert_eq!(
        ShadowMap::new(&mut s, 8, 8, up, centre, c(9000.0)).err(),
        Some(ShadowError::OutOfRange)
    );
    assert_eq!(
        ShadowMap::point(&mut s, 8, 8, v3(0.0, 5.0, 0.0), centre, c(-1.0)).err(),
        Some(ShadowError::BadLight)
    );
    // Far point lights: d + r beyond I16F16, or a sphere too small to frame from there.
    assert_eq!(
        ShadowMap::point(&mut s, 64, 64, v3(30000.0, 30000.0, 30000.0), centre, r).err(),
        Some(ShadowError::OutOfRange)
    );
    let extreme = Vec3::from_bits(i32::MAX, i32::MIN, i32::MAX);
    assert_eq!(
        ShadowMap::point(&mut s, 64, 64, extreme, centre, r).err(),
        Some(ShadowError::OutOfRange)
    );
    assert_eq!(
        ShadowMap::point(&mut s, 64, 64, v3(0.0, 20000.0, 0.0), centre, c(0.01)).err(),
        Some(ShadowError::OutOfRange)
    );
    // A light at the centre looks straight down; a 1 × 1 orthographic map works.
    let mut m = ShadowMap::point(&mut s, 8, 8, centre, centre, r).unwrap();
    m.render(&unit_cube(), &box_place()).unwrap();
    let f = m.light_camera().unwrap().forward();
    assert_eq!(f, Vec3::from_int(0, -1, 0));
    let mut one = [0u16; 1];
    let mut m = ShadowMap::new(&mut one, 1, 1, up, centre, r).unwrap();
    m.render(&unit_cube(), &box_place()).unwrap();
    assert_eq!(m.sample(0, 0), Some(m.sample(0, 0).unwrap()));
    assert_eq!(m.sample(1, 0), None);
    // Empty meshes draw nothing; overflowing transforms are errors.
    let mut m = ShadowMap::point(&mut s, 64, 64, v3(0.0, 5.0, 0.0), centre, r).unwrap();
    m.render(&Mesh::empty(), &Affine3::IDENTITY).unwrap();
    assert!((0..64).all(|x| (0..64).all(|y| m.sample(x, y) == Some(u16::MAX))));
    let huge = Affine3::scale(c(60.0))
        .unwrap()
        .then(&Affine3::translation(v3(30000.0, 0.0, 0.0)))
        .unwrap();
    let r1 = m.render(&unit_cube(), &huge);
    assert!(r1.is_ok() || r1 == Err(ShadowError::Transform), "{r1:?}");
    // Points anywhere, including the extremes of I16F16, are classified without panicking.
    for p in [
        extreme,
        extreme.neg(),
        Vec3::from_bits(i32::MIN, i32::MIN, i32::MIN),
        v3(0.0, 5.0, 0.0),
    ] {
        let _ = m.classify(p, 0);
        let _ = m.classify(p, u32::MAX);
    }
    // A far point light (360 units away) frames the scene with a narrow cone: its shadow is
    // where the (almost parallel) rays say.
    let l = [200.0, 300.0, 0.0];
    let mut m = ShadowMap::point(&mut s, 64, 64, v3(l[0], l[1], l[2]), centre, r).unwrap();
    m.render(&Floor::new(HALF, 1).mesh(), &Affine3::IDENTITY)
        .unwrap();
    m.render(&unit_cube(), &box_place()).unwrap();
    let rule = m.plane_bias(up, Vec3::ZERO, Coord::ZERO);
    let lamp = Lamp::Point(l);
    for x in [-0.8, -1.3, 1.5] {
        let p = [x, 0.0, 0.0];
        let vis = m.classify(v3(x, 0.0, 0.0), rule);
        assert_eq!(vis.is_lit(), !lamp.shadowed(p), "x = {x}: {vis:?}");
        assert_ne!(vis, Visibility::Outside);
    }
    // Plane rule: an edge-on plane (through the light) gets no finite bias.
    let edge_on = m.plane_bias(Vec3::from_int(0, 0, 1), v3(l[0], l[1], l[2]), Coord::ZERO);
    assert_eq!(edge_on, u32::MAX);
    assert_eq!(m.plane_bias(Vec3::ZERO, Vec3::ZERO, Coord::ZERO), u32::MAX);
}

// ---------------------------------------------------------------------------------------
// The pass over a rendered frame.

const FW: u16 = 320;
const FH: u16 = 240;
/// Palette: 0 background, 1..=127 floor shades, 128..=254 box shades, 255 marker.
const FLOOR_RAMP: LuminanceRamp = LuminanceRamp {
    first: 1,
    levels: 127,
};
const BOX_RAMP: LuminanceRamp = LuminanceRamp {
    first: 128,
    levels: 127,
};
const AMBIENT: u8 = 60;
const MATERIAL: Material = Material::from_thousandths(1000, 800, 0, 1);

fn observer() -> Camera {
    let lens = Lens {
        fov: BinaryAngle::from_degrees(50),
        axis: FovAxis::Vertical,
        near: c(1.0),
        far: c(30.0),
    };
    Camera::look_at(
        v3(-2.6, 3.0, 4.2),
        v3(-0.3, 0.2, 0.0),
        Vec3::from_int(0, 1, 0),
        lens,
        Viewport::new(FW, FH),
    )
    .unwrap()
}

fn lut() -> Lut<Rgb888> {
    let mut lut = Lut::shaded(
        &[Rgb888::new(236, 214, 170), Rgb888::new(90, 140, 230)],
        127,
        1,
    )
    .unwrap();
    lut.set(0, Rgb888::new(28, 32, 44));
    lut.set(255, Rgb888::new(255, 0, 255));
    lut
}

/// The index a shadowed pixel gets: its material's ambient-only level (the light's diffuse
/// term removed; the material has no specular term).
fn in_shadow(index: u8) -> u8 {
    let level = (MATERIAL.ka as u32 * AMBIENT as u32 + (1 << 14)) >> 15;
    if index == 0 || index == 255 {
        index
    } else if index < 128 {
        FLOOR_RAMP.index(level)
    } else {
        BOX_RAMP.index(level)
    }
}

/// Renders the floor and box seen by [`observer`], lit by the point light, into `frame`
/// (whole picture or band).
fn render_frame<D: DepthValue>(
    floor: &Floor,
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
) {
    let mut floor_obj = Object::new(floor.mesh());
    floor_obj.intensities = Intensities::Lit {
        material: MATERIAL,
        normals: &floor.normals,
    };
    floor_obj.shade = ShadeMode::Phong;
    floor_obj.ramp = FLOOR_RAMP;
    let mut box_obj = Object::new(unit_cube());
    box_obj.transform = box_place();
    box_obj.intensities = Intensities::Lit {
        material: MATERIAL,
        normals: &[],
    };
    box_obj.shade = ShadeMode::Flat;
    box_obj.ramp = BOX_RAMP;
    let lights = [Light::Point {
        position: v3(LIGHT[0], LIGHT[1], LIGHT[2]),
        intensity: 200,
    }];
    let objects = [floor_obj, box_obj];
    let scene = Scene {
        camera: observer(),
        ambient: AMBIENT,
        lights: &lights,
        objects: &objects,
        background: 0,
    };
    let renderer = Renderer::for_scene(&scene).unwrap();
    let mut scratch = vec![PreparedVertex::<4>::default(); floor.vertices.len().max(8)];
    let mut stats = zscan::render::StatsWithoutWritten::default();
    render_scene(&renderer, frame, depth, &mut scratch, &mut stats).unwrap();
}

/// The float ray through pixel `(i, j)` of the observer meets the floor at this point.
fn pixel_floor_point(cam: &Camera, i: f64, j: f64) -> [f64; 3] {
    let (w, v, u) = (f3(cam.right()), f3(cam.up()), f3(cam.forward()));
    let vp = cam.viewport();
    let a = (i - vp.principal_x.to_num::<f64>()) / cam.focal_x().to_num::<f64>();
    let b = (vp.principal_y.to_num::<f64>() - j) / cam.focal_y().to_num::<f64>();
    let d: [f64; 3] = std::array::from_fn(|k| a * w[k] + b * v[k] + u[k]);
    let o = f3(cam.position());
    let s = -o[1] / d[1];
    [o[0] + s * d[0], 0.0, o[2] + s * d[2]]
}

/// Back-projection: for every floor pixel the pass's observer-frame point is within 0.01 of
/// the float ray–floor intersection (u16 and u32 depth buffers).
#[test]
fn back_projection_lands_on_the_floor() {
    fn check<D: DepthSample>(tolerance: f64) {
        let floor = Floor::new(HALF, 6);
        let cam = observer();
        let mut px = vec![0u8; FW as usize * FH as usize];
        let mut dz = vec![D::FAR; FW as usize * FH as usize];
        let mut fb = Framebuffer::new(&mut px, FW, FH).unwrap();
        let mut db = DepthBuffer::new(&mut dz, FW, FH).unwrap();
        render_frame(&floor, &mut fb, &mut db);
        let mut store = vec![0u16; 16 * 16];
        let l = v3(LIGHT[0], LIGHT[1], LIGHT[2]);
        let map = ShadowMap::point(&mut store, 16, 16, l, Vec3::ZERO, c(RADIUS)).unwrap();
        let pass = ShadowPass::new(&map, &cam, 0).unwrap();
        let (w, v, u, o) = (
            f3(cam.right()),
            f3(cam.up()),
            f3(cam.forward()),
            f3(cam.position()),
        );
        let (mut worst, mut n) = (0f64, 0);
        for y in 0..FH as i32 {
            for x in 0..FW as i32 {
                let idx = fb.pixel(x, y).unwrap();
                if !(1..128).contains(&idx) {
                    continue;
                }
                let s = db.get(x, y).unwrap();
                let q = f3(pass.observer_point(x, y, s.to_depth32()).unwrap());
                let p = pixel_floor_point(&cam, x as f64, y as f64);
                let e: [f64; 3] = [dot(sub(p, o), w), dot(sub(p, o), v), dot(sub(p, o), u)];
                let err = (0..3).map(|k| (q[k] - e[k]).abs()).fold(0.0, f64::max);
                worst = worst.max(err);
                n += 1;
            }
        }
        eprintln!(
            "back-projection, {}-bit depth: {n} floor pixels, worst error {worst:.5}",
            D::BITS
        );
        assert!(n > 8_000, "{n}");
        assert!(worst < tolerance, "{worst}");
    }
    check::<u32>(0.005);
    check::<u16>(0.01);
}

/// The pass over a frame (u16 depth buffer, 256 × 256 u16 map, bias from the plane rule with
/// the observer's depth slack): floor pixels are shadowed exactly where the float truth says,
/// outside the outline's 1.5-texel band; band by band (17 rows, the last band shorter) gives
/// the identical picture.
#[test]
fn frame_pass_matches_truth_and_bands() {
    let floor = Floor::new(HALF, 6);
    let cam = observer();
    let mut store = vec![0u16; 256 * 256];
    let l = v3(LIGHT[0], LIGHT[1], LIGHT[2]);
    let centre = v3(CENTRE[0], CENTRE[1], CENTRE[2]);
    let mut map = ShadowMap::point(&mut store, 256, 256, l, centre, c(RADIUS)).unwrap();
    map.render(&floor.mesh(), &Affine3::IDENTITY).unwrap();
    map.render(&unit_cube(), &box_place()).unwrap();
    let slack = observer_depth_slack::<u16>(&cam, c(16.0)).unwrap();
    let bias = map.plane_bias(Vec3::from_int(0, 1, 0), Vec3::ZERO, slack);
    eprintln!(
        "frame pass: slack {:.5} world units, bias {bias}",
        slack.to_num::<f64>()
    );
    let pass = ShadowPass::new(&map, &cam, bias).unwrap();
    let n = FW as usize * FH as usize;
    let mark = |i: u8, lit: bool| if lit { i } else { 255 };

    // One pass.
    let (mut px, mut dz) = (vec![0u8; n], vec![0u16; n]);
    let mut fb = Framebuffer::new(&mut px, FW, FH).unwrap();
    let mut db = DepthBuffer::new(&mut dz, FW, FH).unwrap();
    render_frame(&floor, &mut fb, &mut db);
    let before: Vec<u8> = fb.rows().flat_map(|(_, r)| r.to_vec()).collect();
    let stats = pass.apply(&mut fb, &db, mark).unwrap();
    let after: Vec<u8> = fb.rows().flat_map(|(_, r)| r.to_vec()).collect();
    eprintln!("frame pass: {stats:?}");
    assert_eq!(stats.outside, 0);
    assert_eq!(
        stats.tested as usize,
        before.iter().filter(|&&i| i != 0).count(),
        "every drawn pixel tested, background left alone"
    );

    // Against the truth on the floor.
    let model = MapModel::new(&map, RADIUS);
    let lamp = Lamp::Point(LIGHT);
    let (mut agree, mut band, mut wrong) = (0, 0, Vec::new());
    for y in 0..FH as usize {
        for x in 0..FW as usize {
            let k = y * FW as usize + x;
            if !(1..128).contains(&before[k]) {
                continue;
            }
            let p = pixel_floor_point(&cam, x as f64, y as f64);
            if under_box(p) {
                continue;
            }
            if model.near_outline(&lamp, p, 1.5) {
                band += 1;
                continue;
            }
            if (after[k] == 255) == lamp.shadowed(p) {
                agree += 1;
            } else {
                wrong.push((x, y, p));
            }
        }
    }
    eprintln!(
        "frame pass vs truth: {agree} floor pixels agree, {} disagree, {band} in the band",
        wrong.len()
    );
    assert!(agree > 8_000, "{agree}");
    assert!(wrong.is_empty(), "{:?}", &wrong[..wrong.len().min(10)]);

    // Band by band.
    let rows = 17u16;
    let mut banded = vec![0u8; n];
    let (mut bpx, mut bdz) = (
        vec![0u8; FW as usize * rows as usize],
        vec![0u16; FW as usize * rows as usize],
    );
    let mut total = zscan::shadow::ShadowStats::default();
    let mut top = 0u16;
    while top < FH {
        let h = rows.min(FH - top);
        let m = FW as usize * h as usize;
        let mut fb = Framebuffer::band(&mut bpx[..m], FW, h, top).unwrap();
        let mut db = DepthBuffer::band(&mut bdz[..m], FW, h, top).unwrap();
        render_frame(&floor, &mut fb, &mut db);
        total += pass.apply(&mut fb, &db, mark).unwrap();
        for (y, r) in fb.rows() {
            let s = y as usize * FW as usize;
            banded[s..s + FW as usize].copy_from_slice(r);
        }
        top += h;
    }
    assert_eq!(total, stats);
    assert!(banded == after, "bands differ from one pass");

    // Mismatched buffers are errors.
    let mut small = vec![0u8; 10 * 10];
    let mut sd = vec![0u16; 10 * 10];
    let mut f = Framebuffer::new(&mut small, 10, 10).unwrap();
    let d = DepthBuffer::new(&mut sd, 10, 10).unwrap();
    assert_eq!(
        pass.apply(&mut f, &d, mark),
        Err(ShadowError::FrameMismatch)
    );
    let mut bp = vec![0u8; FW as usize * 4];
    let mut bd = vec![0u16; FW as usize * 4];
    let mut f = Framebuffer::band(&mut bp, FW, 4, FH - 2).unwrap();
    let d = DepthBuffer::band(&mut bd, FW, 4, FH - 2).unwrap();
    assert_eq!(
        pass.apply(&mut f, &d, mark),
        Err(ShadowError::FrameMismatch)
    );
}

/// Pictures of the floor and box lit by the point light with shadows: the rule's bias
/// (largest over the floor and the box faces that face the light), too little bias (acne:
/// zero) and too much (leaking: worth 1.3 world units at the box). Written to
/// `target/shadow-*.png`.
#[test]
fn shadow_pictures() {
    let floor = Floor::new(HALF, 6);
    let cam = observer();
    let mut store = vec![0u16; 256 * 256];
    let l = v3(LIGHT[0], LIGHT[1], LIGHT[2]);
    let centre = v3(CENTRE[0], CENTRE[1], CENTRE[2]);
    let mut map = ShadowMap::point(&mut store, 256, 256, l, centre, c(RADIUS)).unwrap();
    map.render(&floor.mesh(), &Affine3::IDENTITY).unwrap();
    map.render(&unit_cube(), &box_place()).unwrap();
    let slack = observer_depth_slack::<u16>(&cam, c(16.0)).unwrap();
    // Receivers facing the light: the floor, the box's top and its faces x = ½ and z = ½.
    let planes = [
        (Vec3::from_int(0, 1, 0), Vec3::ZERO),
        (Vec3::from_int(0, 1, 0), v3(0.0, 1.0, 0.0)),
        (Vec3::from_int(1, 0, 0), v3(0.5, 0.5, 0.0)),
        (Vec3::from_int(0, 0, 1), v3(0.0, 0.5, 0.5)),
    ];
    let good = planes
        .iter()
        .map(|&(n, p)| map.plane_bias(n, p, slack))
        .max()
        .unwrap();
    // Too much: a bias worth 1.3 world units at the box's distance from the light
    // (`b·z²/K` world units, parent module doc): rays crossing less than that of the box
    // leak.
    let lens = map.light_camera().unwrap().lens();
    let (near, far) = (lens.near.to_num::<f64>(), lens.far.to_num::<f64>());
    let k = 4294967295.0 * far * near / (far - near);
    let z = dot(sub(LIGHT, CENTRE), sub(LIGHT, CENTRE)).sqrt();
    let leaky = (1.3 * k / (z * z)) as u32;
    let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target");
    let n = FW as usize * FH as usize;
    let mut shadowed = Vec::new();
    for (name, bias) in [("point", good), ("acne", 0), ("leak", leaky)] {
        let pass = ShadowPass::new(&map, &cam, bias).unwrap();
        let (mut px, mut dz) = (vec![0u8; n], vec![0u16; n]);
        let mut fb = Framebuffer::new(&mut px, FW, FH).unwrap();
        let mut db = DepthBuffer::new(&mut dz, FW, FH).unwrap();
        render_frame(&floor, &mut fb, &mut db);
        let stats = pass
            .apply(&mut fb, &db, |i, lit| if lit { i } else { in_shadow(i) })
            .unwrap();
        eprintln!("picture {name}: bias {bias}, {stats:?}");
        shadowed.push(stats.shadowed);
        write_image(&out.join(format!("shadow-{name}.png")), &fb, &lut()).unwrap();
    }
    // Acne shadows more pixels than the rule, leaking fewer.
    assert!(shadowed[1] > shadowed[0] + 1000, "{shadowed:?}");
    assert!(shadowed[2] + 300 < shadowed[0], "{shadowed:?}");
}
