//! Spot lights and distance attenuation against the independent `f64` model
//! (`reference::float_lighting`), and their shadow maps.
//!
//! - The lighting stage: attenuated points and spots at random points and normals, every
//!   intensity within ±1 of `f64` (the largest error is printed), with points inside, across
//!   and outside the cones' ramps.
//! - Every shading mode: Phong pixels within ±1 of the `f64` per-pixel evaluation on a plane
//!   lit by a spot; the renderer's flat and Gouraud (exact and fast) frames of a sphere under
//!   a spot equal the frames drawn from the lighting stage's levels, which are within ±1 of
//!   `f64` at every vertex and polygon centre.
//! - Out-of-range input refused in words: a zero axis, cones out of range, attenuation below
//!   1 or above 256; a spot too wide for a shadow map.
//! - A spot's shadow map: a point behind an occluder inside the cone is shadowed, one beside
//!   it lit; the map's field of view is the narrowest holding the cone.
use zscan::geometry::camera::{Camera, FovAxis, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::{uv_sphere, uv_sphere_sizes};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::Mesh;
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::internals::{draw_triangle_phong, PhongContext, PhongVertex};
use zscan::lighting::{
    light_faces, light_vertices, Attenuation, Cone, Illumination, Light, LightingError, Material,
};
use zscan::output::{DepthBuffer, Framebuffer};
use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
use zscan::raster::SubpixelPoint;
use zscan::render::{PreparedVertex, RenderError, RenderStats, Renderer};
use zscan::scene::{Intensities, Object};
use zscan::shadow::{ShadowError, ShadowMap, Visibility};
use zscan_host::reference::float_lighting::{FloatLight, FloatLighting, FloatMaterial, V3};

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
}

/// The exact value of a fixed-point vector.
fn f(p: Vec3) -> V3 {
    p.bits().map(|b| b as f64 / 65536.0)
}

fn degrees(a: BinaryAngle) -> f64 {
    a.0 as f64 * 360.0 / 4294967296.0
}

fn coefficients(a: Attenuation) -> [f64; 3] {
    [a.constant, a.linear, a.quadratic].map(|c| c as f64 / 65536.0)
}

/// The `f64` twin of a core light (its exact fixed-point values).
fn float_light(l: &Light) -> FloatLight {
    match *l {
        Light::Point {
            position,
            intensity,
        } => FloatLight::Point(f(position), intensity as f64),
        Light::Directional { toward, intensity } => {
            FloatLight::Directional(f(toward), intensity as f64)
        }
        Light::AttenuatedPoint {
            position,
            intensity,
            attenuation,
        } => FloatLight::Attenuated(f(position), intensity as f64, coefficients(attenuation)),
        Light::Spot {
            position,
            axis,
            cone,
            attenuation,
            intensity,
        } => FloatLight::Spot {
            position: f(position),
            axis: f(axis),
            inner: degrees(cone.inner),
            outer: degrees(cone.outer),
            attenuation: coefficients(attenuation),
            intensity: intensity as f64,
        },
    }
}

fn float_material(m: &Material) -> FloatMaterial {
    FloatMaterial {
        ka: m.ka as f64 / 32768.0,
        kd: m.kd as f64 / 32768.0,
        ks: m.ks as f64 / 32768.0,
        n: m.shininess() as i32,
    }
}

fn cone(inner: i32, outer: i32) -> Cone {
    Cone {
        inner: BinaryAngle::from_degrees(inner),
        outer: BinaryAngle::from_degrees(outer),
    }
}

struct Rng(u64);

impl Rng {
    /// Uniform in `[lo, hi)`.
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        lo + (self.0 >> 11) as f64 / (1u64 << 53) as f64 * (hi - lo)
    }
}

#[test]
fn local_lights_match_f64_within_one_level() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut max_err = 0.0f64;
    let (mut in_ramp, mut outside, mut inside) = (0, 0, 0);
    let materials = [
        Material::from_thousandths(200, 700, 500, 12),
        Material::from_thousandths(100, 900, 0, 1),
        Material::from_thousandths(300, 400, 900, 60),
    ];
    for case in 0..400 {
        // Observer frame: the eye at the origin, the scene ahead (z > 0).
        let spot = Light::Spot {
            position: v(
                rng.range(-6.0, 6.0),
                rng.range(-6.0, 6.0),
                rng.range(0.0, 8.0),
            ),
            axis: v(
                rng.range(-0.5, 0.5),
                rng.range(-0.5, 0.5),
                rng.range(0.3, 1.0),
            ),
            cone: [cone(10, 25), cone(0, 40), cone(30, 45), cone(50, 80)][case % 4],
            attenuation: [
                Attenuation::NONE,
                Attenuation::from_thousandths(1000, 50, 10),
                Attenuation::from_thousandths(1500, 0, 3),
                Attenuation::from_thousandths(1000, 200, 0),
            ][case / 4 % 4],
            intensity: 255,
        };
        let point = Light::AttenuatedPoint {
            position: v(
                rng.range(-20.0, 20.0),
                rng.range(-20.0, 20.0),
                rng.range(-5.0, 30.0),
            ),
            intensity: 180,
            attenuation: Attenuation::from_thousandths(1000, 20, 2),
        };
        let lights = [spot, point];
        let ill = Illumination::observer(30, &lights).unwrap();
        let fl = FloatLighting {
            eye: [0.0; 3],
            ambient: 30.0,
            lights: lights.iter().map(float_light).collect(),
        };
        let mat = &materials[case % 3];
        let fm = float_material(mat);
        let Light::Spot { position, axis, .. } = spot else {
            unreachable!()
        };
        for _ in 0..50 {
            // Points around the spot's axis, 2 to 15 units ahead of it.
            let t = rng.range(2.0, 15.0);
            let (q, a) = (f(position), f(axis));
            let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            let s = t * 1.2;
            let p = v(
                q[0] + a[0] / la * t + rng.range(-s, s),
                q[1] + a[1] / la * t + rng.range(-s, s),
                q[2] + a[2] / la * t + rng.range(-s, s),
            );
            // Normals facing the light often enough.
            let n = v(
                rng.range(-1.0, 1.0) - a[0],
                rng.range(-1.0, 1.0) - a[1],
                rng.range(-1.0, 1.0) - a[2],
            );
            let nb = n.bits().map(|c| c as i64);
            let core = ill.intensity(mat, p, nb) as f64;
            let want = fl.intensity(&fm, f(p), f(n));
            let err = (core - want).abs();
            max_err = max_err.max(err);
            assert!(
                err <= 1.0,
                "case {case}: {lights:?} at {:?} normal {:?}: core {core}, f64 {want:.3}",
                f(p),
                f(n)
            );
            // Where the point lies with respect to the cone.
            let d = [0, 1, 2].map(|k| f(p)[k] - q[k]);
            let ld = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let cos_phi = (d[0] * a[0] + d[1] * a[1] + d[2] * a[2]) / (ld * la);
            let Light::Spot { cone, .. } = spot else {
                unreachable!()
            };
            let (ci, co) = (
                degrees(cone.inner).to_radians().cos(),
                degrees(cone.outer).to_radians().cos(),
            );
            if cos_phi >= ci {
                inside += 1;
            } else if cos_phi <= co {
                outside += 1;
            } else {
                in_ramp += 1;
            }
        }
    }
    eprintln!(
        "local lights: max |core − f64| = {max_err:.3} over 20000 points \
         ({inside} inside, {in_ramp} in the ramp, {outside} outside the cones)"
    );
    assert!(
        inside > 1000 && in_ramp > 1000 && outside > 1000,
        "{inside} {in_ramp} {outside}"
    );
}

/// A 112 × 112-pixel square facing the eye at distance 200, pixel `(x, y)` at
/// `(x − 64, 64 − y, 200)`, its normal the same everywhere (tilted), lit by a spot from
/// `(10, −5, 90)` aimed at the square: every Phong pixel within ±1 of `f64`.
#[test]
fn phong_pixels_under_a_spot_match_f64() {
    let spot = Light::Spot {
        position: v(10.0, -5.0, 90.0),
        axis: v(-0.1, 0.05, 1.0),
        cone: cone(12, 22),
        attenuation: Attenuation::from_thousandths(1000, 4, 0),
        intensity: 255,
    };
    let ill = Illumination::observer(20, &[spot]).unwrap();
    let mat = Material::from_thousandths(300, 800, 600, 8);
    let fl = FloatLighting {
        eye: [0.0; 3],
        ambient: 20.0,
        lights: vec![float_light(&spot)],
    };
    let fm = float_material(&mat);
    let normal = v(0.15, -0.1, -1.0);
    let corners = [[8, 8], [120, 8], [120, 120], [8, 120]];
    let (w, h) = (128usize, 128usize);
    let mut px = vec![0u8; w * h];
    let mut zs = vec![0u16; w * h];
    {
        let mut fb = Framebuffer::new(&mut px, w as u16, h as u16).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, w as u16, h as u16).unwrap();
        zb.clear();
        let ctx = PhongContext {
            illumination: &ill,
            material: mat,
            ramp: LuminanceRamp::GREY,
            dither: false,
        };
        for t in [[0usize, 1, 2], [0, 2, 3]] {
            let c = t.map(|k| {
                let [x, y] = corners[k];
                PhongVertex::<4> {
                    screen: SubpixelPoint::from_pixel(x, y),
                    depth: 1 << 30,
                    position: Vec3::from_int(x - 64, 64 - y, 200),
                    normal,
                }
            });
            draw_triangle_phong(&mut fb, &mut zb, c, &ctx).unwrap();
        }
    }
    let mut max_err = 0.0f64;
    let mut levels = std::collections::BTreeSet::new();
    for y in 9..120 {
        for x in 9..120 {
            let got = px[y * w + x] as f64;
            let p = [x as f64 - 64.0, 64.0 - y as f64, 200.0];
            let want = fl.intensity(&fm, p, f(normal));
            let err = (got - want).abs();
            max_err = max_err.max(err);
            levels.insert(px[y * w + x]);
            assert!(err <= 1.0, "pixel ({x}, {y}): core {got}, f64 {want:.3}");
        }
    }
    eprintln!(
        "Phong under a spot: max |core − f64| = {max_err:.3}, {} levels",
        levels.len()
    );
    // The spot's disc and its ramp are on the square: ambient-only pixels and many levels.
    assert!(levels.contains(&6) && levels.len() > 100, "{levels:?}");
}

const W: u16 = 96;
const H: u16 = 72;
const SEG: u16 = 20;
const RINGS: u16 = 12;
const NV: usize = uv_sphere_sizes(SEG, RINGS).0;
const NI: usize = uv_sphere_sizes(SEG, RINGS).1;

fn camera() -> Camera {
    let lens = Lens {
        fov: BinaryAngle::from_degrees(60),
        axis: FovAxis::Vertical,
        near: Coord::from_num(0.5),
        far: Coord::from_num(20),
    };
    Camera::look_at(
        v(0.4, 0.7, 3.0),
        Vec3::ZERO,
        Vec3::from_int(0, 1, 0),
        lens,
        Viewport::new(W, H),
    )
    .unwrap()
}

fn sphere_spot() -> [Light; 2] {
    [
        Light::Spot {
            position: v(1.5, 2.5, 2.0),
            axis: v(-1.5, -2.5, -2.0),
            cone: cone(8, 20),
            attenuation: Attenuation::from_thousandths(1000, 100, 30),
            intensity: 255,
        },
        Light::AttenuatedPoint {
            position: v(-3.0, 0.0, 2.0),
            intensity: 90,
            attenuation: Attenuation::from_thousandths(1000, 0, 50),
        },
    ]
}

#[test]
fn flat_and_gouraud_under_a_spot_match_the_stage_and_f64() {
    let (mut vertices, mut indices) = (vec![Vec3::ZERO; NV], vec![0u16; NI]);
    uv_sphere(SEG, RINGS, Coord::from_num(1), &mut vertices, &mut indices).unwrap();
    let mesh = Mesh::triangles(&vertices, &indices).unwrap();
    let cam = camera();
    let lights = sphere_spot();
    let mat = Material::from_thousandths(150, 800, 500, 16);
    let ill = Illumination::new(&cam, 25, &lights).unwrap();
    let id = Affine3::IDENTITY;
    let (mut levels, mut normals) = (vec![0u8; NV], vec![Vec3::ZERO; NV]);
    light_vertices(&mesh, &id, &cam, &ill, &mat, &mut normals, &mut levels).unwrap();
    let mut faces = vec![0u8; mesh.polygon_count()];
    light_faces(&mesh, &id, &cam, &ill, &mat, &mut faces).unwrap();

    // The stage's levels against f64 (world frame, the camera's eye), at the vertices with
    // the mesh's vertex normals and at the polygon centres with the face normals.
    let fl = FloatLighting {
        eye: [0.4, 0.7, 3.0],
        ambient: 25.0,
        lights: lights.iter().map(float_light).collect(),
    };
    let fm = float_material(&mat);
    let mut max_err = 0.0f64;
    for (i, (p, n)) in vertices.iter().zip(&normals).enumerate() {
        let want = fl.intensity(&fm, f(*p), f(*n));
        let err = (levels[i] as f64 - want).abs();
        max_err = max_err.max(err);
        assert!(err <= 1.0, "vertex {i}: core {}, f64 {want:.3}", levels[i]);
    }
    for (k, poly) in mesh.polygons().enumerate() {
        let c: Vec<V3> = poly.iter().map(|&i| f(vertices[i as usize])).collect();
        let centre = [0, 1, 2].map(|j| c.iter().map(|p| p[j]).sum::<f64>() / c.len() as f64);
        let n = f(mesh.face_normal(poly).unwrap());
        let want = fl.intensity(&fm, centre, n);
        let err = (faces[k] as f64 - want).abs();
        max_err = max_err.max(err);
        assert!(err <= 1.0, "polygon {k}: core {}, f64 {want:.3}", faces[k]);
    }
    eprintln!("flat/Gouraud levels under a spot: max |core − f64| = {max_err:.3}");
    let lit_vertices = levels.iter().filter(|&&l| l > 40).count();
    assert!(
        lit_vertices > 10 && lit_vertices < NV / 2,
        "the spot lights part of the sphere: {lit_vertices} of {NV} vertices"
    );

    // The renderer in each mode equals the frame drawn from the stage's levels.
    let r = Renderer::<4>::new(&cam)
        .unwrap()
        .with_lights(25, &lights)
        .unwrap();
    let frame = |intensities: Intensities<'_>, shade: ShadeMode| {
        let mut o = Object::new(mesh);
        o.intensities = intensities;
        o.shade = shade;
        o.ramp = LuminanceRamp::GREY;
        let n = W as usize * H as usize;
        let (mut px, mut zs) = (vec![255u8; n], vec![0u16; n]);
        let mut fb = Framebuffer::new(&mut px, W, H).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, W, H).unwrap();
        zb.clear();
        let mut stats = RenderStats::default();
        let mut scratch = vec![PreparedVertex::<4>::default(); NV];
        r.draw_object(&o, &mut scratch, &mut fb, &mut zb, &mut stats)
            .unwrap();
        px
    };
    for (shade, given) in [
        (ShadeMode::GouraudExact, Intensities::PerVertex(&levels)),
        (ShadeMode::GouraudFast, Intensities::PerVertex(&levels)),
        (ShadeMode::Flat, Intensities::PerPolygon(&faces)),
    ] {
        let lit = frame(
            Intensities::Lit {
                material: mat,
                normals: &normals,
            },
            shade,
        );
        assert_eq!(lit, frame(given, shade), "{shade:?}");
        assert!(lit.iter().any(|&p| p > 100), "{shade:?}: the spot shows");
    }
}

#[test]
fn out_of_range_lights_are_refused_in_words() {
    let at = Vec3::from_int(0, 0, 5);
    let spot = |axis: Vec3, cone: Cone, attenuation: Attenuation| Light::Spot {
        position: at,
        axis,
        cone,
        attenuation,
        intensity: 200,
    };
    let z = Vec3::from_int(0, 0, 1);
    let ok = Attenuation::NONE;
    let refused = |lights: &[Light]| Illumination::observer(10, lights).err();
    let point = Light::Point {
        position: at,
        intensity: 1,
    };
    assert_eq!(
        refused(&[point, spot(Vec3::ZERO, cone(10, 20), ok)]),
        Some(LightingError::ZeroAxis { light: 1 })
    );
    for bad in [
        cone(20, 20),
        cone(30, 10),
        cone(10, 91),
        cone(0, 200),
        // cos 60° − cos 60.5° < 1/64.
        Cone {
            inner: BinaryAngle::from_degrees(60),
            outer: BinaryAngle::from_degrees_ratio(605, 10),
        },
    ] {
        assert_eq!(
            refused(&[spot(z, bad, ok)]),
            Some(LightingError::ConeOutOfRange { light: 0 }),
            "{bad:?}"
        );
    }
    assert!(refused(&[spot(z, cone(0, 90), ok)]).is_none());
    assert!(refused(&[spot(z, cone(59, 61), ok)]).is_none());
    for bad in [
        Attenuation::from_thousandths(999, 0, 0),
        Attenuation::from_thousandths(0, 100, 100),
        Attenuation::from_thousandths(257_000, 0, 0),
        Attenuation::from_thousandths(1000, 256_001, 0),
        Attenuation::from_thousandths(1000, 0, 300_000),
    ] {
        let attenuated = Light::AttenuatedPoint {
            position: at,
            intensity: 9,
            attenuation: bad,
        };
        assert_eq!(
            refused(&[point, point, attenuated]),
            Some(LightingError::AttenuationOutOfRange { light: 2 }),
            "{bad:?}"
        );
        assert_eq!(
            refused(&[spot(z, cone(10, 20), bad)]),
            Some(LightingError::AttenuationOutOfRange { light: 0 })
        );
    }
    assert!(refused(&[spot(
        z,
        cone(10, 20),
        Attenuation::from_thousandths(256_000, 256_000, 256_000)
    )])
    .is_none());
    // Through the renderer, with the light's index and the limit in the words.
    let e = Renderer::<4>::new(&camera())
        .unwrap()
        .with_lights(10, &[point, spot(z, cone(25, 24), ok)])
        .err()
        .unwrap();
    assert_eq!(
        e,
        RenderError::Lighting(LightingError::ConeOutOfRange { light: 1 })
    );
    let words = e.to_string();
    assert!(words.contains("light 1") && words.contains("90"), "{words}");
}

/// A spot 10 units above the ground (`y = 0`) pointing down, a unit cube at height 4 on its
/// axis: the ground under the cube is shadowed, the ground inside the cone beside the cube's
/// shadow lit.
#[test]
fn a_spot_casts_shadows_through_its_map() {
    use zscan::geometry::generators::unit_cube;
    let light = Light::Spot {
        position: Vec3::from_int(0, 10, 0),
        axis: Vec3::from_int(0, -1, 0),
        cone: cone(20, 40),
        attenuation: Attenuation::NONE,
        intensity: 255,
    };
    let mut samples = vec![0u32; 64 * 64];
    let mut map =
        ShadowMap::for_light(&mut samples, 64, 64, &light, Vec3::ZERO, Coord::from_num(6)).unwrap();
    // The narrowest field of view holding the cone: tan(half)·31/32 ≥ tan 40°.
    let cam = *map.light_camera().unwrap();
    let half = degrees(cam.lens().fov) / 2.0;
    let want = (40f64.to_radians().tan() * 32.0 / 31.0).atan().to_degrees();
    assert!((half - want).abs() < 0.01, "half fov {half} vs {want}");
    let cube = unit_cube();
    let at = Affine3::translation(v(-0.5, 4.0, -0.5));
    map.render(&cube, &at).unwrap();
    let bias = map.texel_depth() * 4;
    let ground = |x: f64, z: f64| map.classify(v(x, 0.0, z), bias);
    // The cube spans [-0.5, 0.5]² at heights 4..5, 5 to 6 units below the spot, which
    // shadows [-1, 1]² on the ground (10/5 = 2); the cone's foot has radius 10·tan 40° ≈ 8.4.
    assert_eq!(ground(0.0, 0.0), Visibility::Shadowed);
    assert_eq!(ground(0.6, -0.6), Visibility::Shadowed);
    assert_eq!(ground(2.0, 0.0), Visibility::Lit);
    assert_eq!(ground(-3.0, 3.0), Visibility::Lit);
}

#[test]
fn a_spot_too_wide_for_a_map_is_refused() {
    let mut samples = vec![0u16; 32 * 32];
    let wide = |outer: i32| Light::Spot {
        position: Vec3::from_int(0, 10, 0),
        axis: Vec3::from_int(0, -1, 0),
        cone: cone(10, outer),
        attenuation: Attenuation::NONE,
        intensity: 255,
    };
    let map = |s: &mut [u16], outer| {
        ShadowMap::for_light(s, 32, 32, &wide(outer), Vec3::ZERO, Coord::from_num(5)).map(|_| ())
    };
    assert_eq!(map(&mut samples, 59), Err(ShadowError::SpotConeTooWide));
    assert_eq!(map(&mut samples, 80), Err(ShadowError::SpotConeTooWide));
    assert_eq!(map(&mut samples, 55), Ok(()));
    let words = ShadowError::SpotConeTooWide.to_string();
    assert!(words.contains("120") && words.contains("60"), "{words}");
    let zero_axis = Light::Spot {
        position: Vec3::from_int(0, 10, 0),
        axis: Vec3::ZERO,
        cone: cone(10, 30),
        attenuation: Attenuation::NONE,
        intensity: 255,
    };
    assert_eq!(
        ShadowMap::for_light(
            &mut samples,
            32,
            32,
            &zero_axis,
            Vec3::ZERO,
            Coord::from_num(5)
        )
        .map(|_| ()),
        Err(ShadowError::BadLight)
    );
}
