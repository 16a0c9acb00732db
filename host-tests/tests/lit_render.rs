//! Lit objects through the main renderer (`Intensities::Lit`, every `ShadeMode`).
//!
//! - The renderer's lighting equals the lighting stage's own entry points: a lit Gouraud
//!   object gives the same frame as the levels of `light_vertices` handed over per vertex, a
//!   lit flat object the same as the levels of `light_faces` per polygon.
//! - Lit objects crossing the frustum are clipped, not skipped: in every mode (flat,
//!   Gouraud, Phong, dithered or not) a sphere through the near plane and the screen edges
//!   covers exactly the pixels the unlit renderer covers, and none of them is left empty.
//! - Phong keeps a highlight that Gouraud misses, through the renderer.
//! - Bands give the same pixels as one pass for every lit mode.
//! - Statistics without the written-pixel count draw the same pixels with the same counts,
//!   `pixels_written` 0, in every mode (front faces only, and with hidden back faces drawn).
//! - Bad input: short normal tables, too many lights, a zero light direction → errors.
use zscan::geometry::camera::{Camera, FovAxis, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::{uv_sphere, uv_sphere_sizes};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::Mesh;
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::internals::NEAR;
use zscan::lighting::{light_faces, light_vertices, Illumination, Light, LightingError, Material};
use zscan::output::{DepthBuffer, Framebuffer};
use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
use zscan::render::{
    render_in_bands, BandScratch, IntensityTable, PolygonRows, PreparedVertex, RenderError,
    RenderStats, Renderer, StatsSink, StatsWithoutWritten,
};
use zscan::scene::{Intensities, Object, Scene};

const W: u16 = 96;
const H: u16 = 72;
const SEG: u16 = 16;
const RINGS: u16 = 10;
const NV: usize = uv_sphere_sizes(SEG, RINGS).0;
const NI: usize = uv_sphere_sizes(SEG, RINGS).1;

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
}

fn camera(eye: Vec3) -> Camera {
    camera_at(eye, Vec3::ZERO)
}

fn camera_at(eye: Vec3, target: Vec3) -> Camera {
    let lens = Lens {
        fov: BinaryAngle::from_degrees(60),
        axis: FovAxis::Vertical,
        near: Coord::from_num(0.5),
        far: Coord::from_num(20),
    };
    Camera::look_at(
        eye,
        target,
        Vec3::from_int(0, 1, 0),
        lens,
        Viewport::new(W, H),
    )
    .unwrap()
}

fn lights() -> [Light; 2] {
    [
        Light::Point {
            position: Vec3::from_int(3, 4, 5),
            intensity: 200,
        },
        Light::Directional {
            toward: Vec3::from_int(-1, 0, 1),
            intensity: 60,
        },
    ]
}

const MATERIAL: Material = Material::from_thousandths(200, 600, 700, 30);
const RAMP: LuminanceRamp = LuminanceRamp {
    first: 0,
    levels: 64,
};

struct Sphere {
    vertices: Vec<Vec3>,
    indices: Vec<u16>,
    normals: Vec<Vec3>,
}

impl Sphere {
    fn new(radius: Coord) -> Sphere {
        let (mut vertices, mut indices) = (vec![Vec3::ZERO; NV], vec![0u16; NI]);
        uv_sphere(SEG, RINGS, radius, &mut vertices, &mut indices).unwrap();
        let mut s = Sphere {
            vertices,
            indices,
            normals: vec![Vec3::ZERO; NV],
        };
        let mut normals = vec![Vec3::ZERO; NV];
        s.mesh().vertex_normals(&mut normals).unwrap();
        s.normals = normals;
        s
    }

    fn mesh(&self) -> Mesh<'_> {
        Mesh::triangles(&self.vertices, &self.indices).unwrap()
    }

    fn object<'a>(
        &'a self,
        intensities: Intensities<'a>,
        shade: ShadeMode,
        dither: bool,
    ) -> Object<'a> {
        let mut o = Object::new(self.mesh());
        o.intensities = intensities;
        o.shade = shade;
        o.ramp = RAMP;
        o.dither = dither;
        o
    }

    fn lit(&self, shade: ShadeMode, dither: bool) -> Object<'_> {
        self.object(
            Intensities::Lit {
                material: MATERIAL,
                normals: &self.normals,
            },
            shade,
            dither,
        )
    }
}

/// One frame of `object` (background 255), its pixels and stats.
fn frame(r: &Renderer<4>, object: &Object<'_>) -> (Vec<u8>, RenderStats) {
    let mut stats = RenderStats::default();
    (frame_into(r, object, &mut stats), stats)
}

/// The pixels `draw` leaves in a `W × H` frame of background 255, given that frame, its
/// cleared depth buffer and vertex scratch for the sphere.
fn drawn(
    draw: impl FnOnce(&mut Framebuffer<'_>, &mut DepthBuffer<'_, u16>, &mut [PreparedVertex<4>]),
) -> Vec<u8> {
    let n = W as usize * H as usize;
    let (mut px, mut zs) = (vec![255u8; n], vec![0u16; n]);
    let mut fb = Framebuffer::new(&mut px, W, H).unwrap();
    let mut zb = DepthBuffer::new(&mut zs, W, H).unwrap();
    zb.clear();
    draw(
        &mut fb,
        &mut zb,
        &mut vec![PreparedVertex::<4>::default(); NV],
    );
    px
}

/// One frame of `object` (background 255) counted into `stats`; its pixels.
fn frame_into(r: &Renderer<4>, object: &Object<'_>, stats: &mut impl StatsSink) -> Vec<u8> {
    drawn(|fb, zb, scratch| {
        r.draw_object(object, scratch, fb, zb, stats).unwrap();
    })
}

/// [`frame_into`] through the band path: `polygon_rows`, then `rasterize_rows` over the whole
/// frame as one band.
fn frame_rows(r: &Renderer<4>, object: &Object<'_>, stats: &mut impl StatsSink) -> Vec<u8> {
    drawn(|fb, zb, scratch| {
        let mut table = vec![PolygonRows::default(); object.mesh.polygon_count()];
        r.prepare(object, scratch).unwrap();
        r.polygon_rows(object, scratch, &mut table, stats).unwrap();
        r.rasterize_rows(object, scratch, &table, fb, zb, stats)
            .unwrap();
    })
}

fn renderer(cam: &Camera) -> Renderer<4> {
    Renderer::new(cam)
        .unwrap()
        .with_lights(40, &lights())
        .unwrap()
}

const MODES: [ShadeMode; 4] = [
    ShadeMode::Flat,
    ShadeMode::GouraudFast,
    ShadeMode::GouraudExact,
    ShadeMode::Phong,
];

#[test]
fn renderer_lighting_equals_the_lighting_stage() {
    let sphere = Sphere::new(Coord::from_num(1));
    let cam = camera(v(0.7, 0.6, 2.6));
    let r = renderer(&cam);
    let ill = Illumination::new(&cam, 40, &lights()).unwrap();
    let mesh = sphere.mesh();
    let (mut levels, mut normals) = (vec![0u8; NV], vec![Vec3::ZERO; NV]);
    let id = Affine3::IDENTITY;
    light_vertices(&mesh, &id, &cam, &ill, &MATERIAL, &mut normals, &mut levels).unwrap();
    let mut faces = vec![0u8; mesh.polygon_count()];
    light_faces(&mesh, &id, &cam, &ill, &MATERIAL, &mut faces).unwrap();
    for (shade, given) in [
        (ShadeMode::GouraudExact, Intensities::PerVertex(&levels)),
        (ShadeMode::GouraudFast, Intensities::PerVertex(&levels)),
        (ShadeMode::Flat, Intensities::PerPolygon(&faces)),
    ] {
        let (lit, s1) = frame(&r, &sphere.lit(shade, false));
        let (reference, s2) = frame(&r, &sphere.object(given, shade, false));
        assert_eq!(s1, s2, "{shade:?}");
        assert!(s1.pixels_written > 1500, "{shade:?}: {s1:?}");
        let differing = lit.iter().zip(&reference).filter(|(a, b)| a != b).count();
        assert_eq!(differing, 0, "{shade:?}");
        // Lit, not uniform: many levels on screen.
        let mut seen = lit.clone();
        seen.sort();
        seen.dedup();
        assert!(seen.len() > 15, "{shade:?}: {} levels", seen.len());
    }
}

#[test]
fn stats_without_written_draw_the_same_pixels() {
    let sphere = Sphere::new(Coord::from_num(2));
    let mut hidden_seen = false;
    for cam in [camera(v(0.0, 0.0, 6.0)), crossing_camera()] {
        let r = renderer(&cam);
        for shade in MODES {
            for dither in [false, true] {
                for cull in [true, false] {
                    let mut lit = sphere.lit(shade, dither);
                    lit.cull_back_faces = cull;
                    let given = sphere.object(Intensities::Uniform(200), shade, dither);
                    for o in [lit, given] {
                        let mut o = o;
                        o.cull_back_faces = cull;
                        let (counted, s) = frame(&r, &o);
                        let mut without = StatsWithoutWritten::default();
                        let px = frame_into(&r, &o, &mut without);
                        let what = format!("{shade:?} dither {dither} cull {cull}");
                        assert_eq!(px, counted, "{what}");
                        assert!(s.pixels_written > 0, "{what}");
                        // Without culling the back half is covered and hidden: written < covered.
                        assert_eq!(s.pixels_written < s.pixels_covered, !cull, "{what} {s:?}");
                        hidden_seen |= s.pixels_written < s.pixels_covered;
                        let expected = RenderStats {
                            pixels_written: 0,
                            ..s
                        };
                        assert_eq!(without.0, expected, "{what}");
                        // The band path (polygon table, then the rows of a full-frame band):
                        // the same counts, but a clipped polygon whose clipped projection
                        // misses the picture's rows is not clipped again to be drawn.
                        let table_clips = |t: RenderStats| {
                            assert!(t.clipped <= s.clipped, "{what}: {t:?}");
                            RenderStats {
                                clipped: s.clipped,
                                ..t
                            }
                        };
                        let mut rows_stats = StatsWithoutWritten::default();
                        assert_eq!(frame_rows(&r, &o, &mut rows_stats), counted, "{what}");
                        assert_eq!(table_clips(rows_stats.0), expected, "{what}");
                        let mut rows_counted = RenderStats::default();
                        assert_eq!(frame_rows(&r, &o, &mut rows_counted), counted, "{what}");
                        assert_eq!(table_clips(rows_counted), s, "{what}");
                    }
                }
            }
        }
    }
    assert!(hidden_seen);
}

fn crossing_camera() -> Camera {
    camera_at(v(0.4, 0.3, 2.25), v(1.6, 0.6, 0.0))
}

#[test]
fn lit_objects_crossing_the_frustum_are_clipped_in_every_mode() {
    // A sphere of radius 2 seen from just outside it, looking past its side: the near plane
    // (0.5) and the screen edges cut it.
    let sphere = Sphere::new(Coord::from_num(2));
    let cam = crossing_camera();
    let r = renderer(&cam);
    let (unlit, s0) = frame(
        &r,
        &sphere.object(Intensities::Uniform(128), ShadeMode::GouraudExact, false),
    );
    assert!(s0.clipped > 0, "{s0:?}");
    // Some vertices of front faces lie before the near plane (outcode bit NEAR).
    let mut prepared = vec![PreparedVertex::<4>::default(); NV];
    r.prepare(&sphere.lit(ShadeMode::Flat, false), &mut prepared)
        .unwrap();
    let near_cut = prepared
        .iter()
        .filter(|p| p.outcode & (1 << NEAR) != 0 && p.view.bits()[2] > 0)
        .count();
    assert!(near_cut > 0);
    let covered: Vec<bool> = unlit.iter().map(|&p| p != 255).collect();
    let n = covered.iter().filter(|&&c| c).count();
    assert!(n > 1000, "{n} pixels {s0:?}");
    for shade in MODES {
        for dither in [false, true] {
            let (px, s) = frame(&r, &sphere.lit(shade, dither));
            assert_eq!(s.clipped, s0.clipped, "{shade:?} {dither}");
            assert_eq!(s.pixels_covered, s0.pixels_covered, "{shade:?} {dither}");
            // Levels stay below the ramp's 64 entries, so 255 marks an unwritten pixel.
            let mism = px
                .iter()
                .zip(&covered)
                .filter(|(&p, &c)| (p != 255) != c)
                .count();
            assert_eq!(mism, 0, "{shade:?} dither {dither}");
        }
    }
}

#[test]
fn phong_keeps_the_highlight_gouraud_misses() {
    // A coarse sphere (a highlight smaller than its faces) lit from the eye's direction:
    // the highlight centre falls inside a face, away from the vertices.
    let (mut vertices, mut indices) = (vec![Vec3::ZERO; 2 + 5 * 8], vec![0u16; 6 * 8 * 5]);
    let mesh = uv_sphere(8, 6, Coord::from_num(1), &mut vertices, &mut indices).unwrap();
    let mut normals = vec![Vec3::ZERO; 2 + 5 * 8];
    mesh.vertex_normals(&mut normals).unwrap();
    let cam = camera(v(0.35, 0.45, 4.0));
    let light = [Light::Point {
        position: v(0.35, 0.45, 4.0),
        intensity: 255,
    }];
    let r = Renderer::<4>::new(&cam)
        .unwrap()
        .with_lights(0, &light)
        .unwrap();
    let shiny = Material::from_thousandths(0, 300, 700, 60);
    let mut brightest = Vec::new();
    for shade in [ShadeMode::GouraudExact, ShadeMode::Phong] {
        let mut o = Object::new(mesh);
        o.intensities = Intensities::Lit {
            material: shiny,
            normals: &normals,
        };
        o.shade = shade;
        o.ramp = LuminanceRamp {
            first: 0,
            levels: 250,
        };
        let (px, _) = frame(&r, &o);
        let max = px.iter().filter(|&&p| p != 255).max().copied().unwrap();
        brightest.push(max);
    }
    // Phong nears full intensity (k_d + k_s = 1 at the highlight, index 249); Gouraud's vertex
    // levels all lie off the highlight.
    assert!(brightest[1] >= 215, "{brightest:?}");
    assert!(brightest[0] + 30 < brightest[1], "{brightest:?}");
}

#[test]
fn lit_bands_equal_one_pass() {
    let sphere = Sphere::new(Coord::from_num(2));
    let cam = crossing_camera();
    let light = lights();
    for shade in MODES {
        for dither in [false, true] {
            let objects = [sphere.lit(shade, dither)];
            let scene = Scene {
                camera: cam,
                objects: &objects,
                background: 255,
                ambient: 40,
                lights: &light,
            };
            let r = Renderer::for_scene(&scene).unwrap();
            let (one, _) = frame(r.renderer(), &objects[0]);
            for (rows, table) in [(1u16, false), (5, false), (72, false), (1, true), (5, true)] {
                let n = W as usize * rows as usize;
                let (mut band, mut depth) = (vec![0u8; n], vec![0u16; n]);
                let mut scratch = vec![PreparedVertex::<4>::default(); NV];
                let mut polygons = vec![PolygonRows::default(); if table { NI / 3 } else { 0 }];
                let mut picture = vec![0u8; W as usize * H as usize];
                render_in_bands(
                    &r,
                    (&mut band, &mut depth),
                    (W, H, rows),
                    BandScratch {
                        vertices: &mut scratch,
                        polygons: &mut polygons,
                    },
                    &mut RenderStats::default(),
                    |f, _| {
                        for (y, row) in f.rows() {
                            let at = y as usize * W as usize;
                            picture[at..at + row.len()].copy_from_slice(row);
                        }
                        Ok::<(), RenderError>(())
                    },
                )
                .unwrap();
                assert!(
                    picture == one,
                    "{shade:?} dither {dither}, bands of {rows}, table {table}"
                );
            }
        }
    }
}

#[test]
fn phong_with_given_levels_is_exact_gouraud() {
    let sphere = Sphere::new(Coord::from_num(1));
    let cam = camera(v(0.7, 0.6, 2.6));
    let r = renderer(&cam);
    let levels: Vec<u8> = (0..NV).map(|i| (i * 37 % 64) as u8 * 4).collect();
    let (a, _) = frame(
        &r,
        &sphere.object(Intensities::PerVertex(&levels), ShadeMode::Phong, false),
    );
    let (b, _) = frame(
        &r,
        &sphere.object(
            Intensities::PerVertex(&levels),
            ShadeMode::GouraudExact,
            false,
        ),
    );
    assert!(a == b);
    assert!(a.iter().filter(|&&p| p != 255).count() > 1500);
}

#[test]
fn bad_lighting_input_is_an_error() {
    let sphere = Sphere::new(Coord::from_num(1));
    let cam = camera(v(0.7, 0.6, 2.6));
    let r = renderer(&cam);
    let n = W as usize * H as usize;
    let (mut px, mut zs) = (vec![0u8; n], vec![0u16; n]);
    let mut fb = Framebuffer::new(&mut px, W, H).unwrap();
    let mut zb = DepthBuffer::new(&mut zs, W, H).unwrap();
    let mut scratch = vec![PreparedVertex::<4>::default(); NV];
    let mut stats = RenderStats::default();
    for shade in [
        ShadeMode::GouraudExact,
        ShadeMode::GouraudFast,
        ShadeMode::Phong,
    ] {
        let mut o = sphere.lit(shade, false);
        o.intensities = Intensities::Lit {
            material: MATERIAL,
            normals: &sphere.normals[..NV - 1],
        };
        let e = r.draw_object(&o, &mut scratch, &mut fb, &mut zb, &mut stats);
        let short = RenderError::IntensitiesTooShort {
            table: IntensityTable::Normals,
            given: NV - 1,
            needed: NV,
        };
        assert_eq!(e, Err(short), "{shade:?}");
    }
    // Flat shading reads no vertex normals: an empty table is fine.
    let mut o = sphere.lit(ShadeMode::Flat, false);
    o.intensities = Intensities::Lit {
        material: MATERIAL,
        normals: &[],
    };
    assert_eq!(
        r.draw_object(&o, &mut scratch, &mut fb, &mut zb, &mut stats),
        Ok(())
    );
    let five = [lights()[0]; 5];
    assert_eq!(
        Renderer::<4>::new(&cam)
            .unwrap()
            .with_lights(0, &five)
            .err(),
        Some(RenderError::Lighting(LightingError::TooManyLights))
    );
    let zero = [Light::Directional {
        toward: Vec3::ZERO,
        intensity: 9,
    }];
    assert_eq!(
        Renderer::<4>::new(&cam)
            .unwrap()
            .with_lights(0, &zero)
            .err(),
        Some(RenderError::Lighting(LightingError::ZeroDirection))
    );
}
