//! Compact bands (`render_in_compact_bands`): the full frame's pixels, depths and counts on the
//! standard scenes, on lit and multi-object scenes, at several band heights and both depth
//! widths; the errors when a vertex needs clipping, when memory is short (naming the part and
//! both sizes) and for Phong objects; the memory formula against the buffers' sizes.

use std::sync::OnceLock;

use zscan::geometry::camera::{Camera, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::{torus, torus_sizes, uv_sphere, uv_sphere_sizes};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::lighting::{Light, Material};
use zscan::output::{DepthBuffer, DepthValue, Framebuffer};
use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
use zscan::render::{
    render_in_compact_bands, BandPart, CompactBandScratch, CompactSizes, CompactVertex, PolygonTop,
    PreparedVertex, RenderError, RenderStats, Renderer, SceneRenderer,
};
use zscan::scene::{Intensities, Object, Scene};
use zscan_host::core_render::{render_compact_picture, to_core, CoreFrame, CoreMesh};
use zscan_host::scenes::standard_scenes;

fn standard() -> &'static [(String, CoreMesh)] {
    static M: OnceLock<Vec<(String, CoreMesh)>> = OnceLock::new();
    M.get_or_init(|| {
        let scenes = standard_scenes().expect("standard scenes build");
        let core = |s: &zscan_host::scenes::Scene| to_core(s).expect("standard scene converts");
        scenes.iter().map(|s| (s.name.clone(), core(s))).collect()
    })
}

/// The compact frame equals the one-pass frame of the same depth width (pixels, depths) and
/// its counts: polygons in and culled once per frame, nothing rejected or clipped, the same
/// pixels covered and written; a triangle counts in every band it draws in.
fn assert_same<D: DepthValue + PartialEq>(
    name: &str,
    rows: u16,
    c: &CoreFrame<D>,
    one: &CoreFrame<D>,
) {
    assert!(
        c.pixels == one.pixels,
        "{name} bands of {rows}: pixels differ"
    );
    assert!(
        c.depth == one.depth,
        "{name} bands of {rows}: depths differ"
    );
    let (s, o) = (c.stats, one.stats);
    assert_eq!(
        (s.polygons_in, s.culled, s.rejected, s.clipped),
        (o.polygons_in, o.culled, o.rejected, o.clipped),
        "{name} bands of {rows}"
    );
    assert_eq!(
        (s.pixels_covered, s.pixels_written),
        (o.pixels_covered, o.pixels_written),
        "{name} bands of {rows}"
    );
    assert!(s.triangles_drawn >= o.triangles_drawn, "{name} {rows}");
    if rows >= 240 {
        assert_eq!(s, o, "{name}: one band counts as one pass");
    }
}

/// Every standard scene whose vertices all lie inside the guard band draws the full frame's
/// pixels, depths and counts at every band height, with 16- and 32-bit depth; a scene whose
/// full frame clips is refused with the vertex named (the quad reaches past the guard band).
#[test]
fn standard_scenes_equal_the_full_frame() {
    let mut drawn = Vec::new();
    for (name, mesh) in standard() {
        for shade in [ShadeMode::GouraudExact, ShadeMode::Flat] {
            let one16: CoreFrame<u16> = mesh.render(shade, None).unwrap();
            let one32: CoreFrame<u32> = mesh.render(shade, None).unwrap();
            if one32.stats.clipped > 0 {
                let e = mesh.render_compact::<u16>(shade, 16).unwrap_err();
                assert!(
                    e.contains("vertex") && e.contains("clipping"),
                    "{name}: {e}"
                );
                continue;
            }
            for rows in [1u16, 5, 12, 16, 37, 240, 1000] {
                assert_same(
                    name,
                    rows,
                    &mesh.render_compact(shade, rows).unwrap(),
                    &one16,
                );
                assert_same(
                    name,
                    rows,
                    &mesh.render_compact(shade, rows).unwrap(),
                    &one32,
                );
            }
            drawn.push(name.clone());
        }
    }
    // The bunny, sphere and cube are inside the guard band (both shadings).
    for name in ["bunny", "sphere", "cube"] {
        assert_eq!(drawn.iter().filter(|n| *n == name).count(), 2, "{drawn:?}");
    }
}

const W: u16 = 160;
const H: u16 = 120;
const SPHERE: (usize, usize) = uv_sphere_sizes(20, 12);
const TORUS: (usize, usize) = torus_sizes(24, 12);

fn camera(eye: Vec3) -> Camera {
    let lens = Lens::new(
        BinaryAngle::from_degrees(50),
        Coord::lit("0.5"),
        Coord::lit("30"),
    );
    let up = Vec3::from_int(0, 1, 0);
    Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(W, H)).unwrap()
}

/// Meshes for the multi-object scenes: a sphere and a torus.
struct Meshes {
    sphere: (Vec<Vec3>, Vec<u16>, Vec<Vec3>),
    torus: (Vec<Vec3>, Vec<u16>, Vec<Vec3>),
}

impl Meshes {
    fn new() -> Meshes {
        let (mut sv, mut si) = (vec![Vec3::ZERO; SPHERE.0], vec![0; SPHERE.1]);
        let mut sn = vec![Vec3::ZERO; SPHERE.0];
        uv_sphere(20, 12, Coord::lit("0.8"), &mut sv, &mut si)
            .unwrap()
            .vertex_normals(&mut sn)
            .unwrap();
        let (mut tv, mut ti) = (vec![Vec3::ZERO; TORUS.0], vec![0; TORUS.1]);
        let mut tn = vec![Vec3::ZERO; TORUS.0];
        torus(
            24,
            12,
            Coord::lit("1"),
            Coord::lit("0.35"),
            &mut tv,
            &mut ti,
        )
        .unwrap()
        .vertex_normals(&mut tn)
        .unwrap();
        Meshes {
            sphere: (sv, si, sn),
            torus: (tv, ti, tn),
        }
    }
}

fn lit(
    (v, i, n): &(Vec<Vec3>, Vec<u16>, Vec<Vec3>),
    shade: ShadeMode,
    at: Vec3,
    turn: i32,
) -> Object<'_> {
    let mesh = zscan::geometry::mesh::Mesh::triangles(v, i).unwrap();
    let mut o = Object::new(mesh);
    o.transform = Affine3::builder()
        .rotate_x(BinaryAngle::from_degrees(turn))
        .rotate_y(BinaryAngle::from_degrees(2 * turn))
        .translate(at)
        .build()
        .unwrap();
    o.intensities = Intensities::Lit {
        material: Material::from_thousandths(150, 600, 400, 20),
        normals: n,
    };
    o.shade = shade;
    o.ramp = LuminanceRamp {
        first: 0,
        levels: 64,
    };
    o
}

/// The one-pass frame of `scene` (32-bit depth) and its counts.
fn one_pass(r: &SceneRenderer<'_, 4>) -> (Vec<u8>, Vec<u32>, RenderStats) {
    let n = W as usize * H as usize;
    let (mut px, mut zs) = (vec![0u8; n], vec![0u32; n]);
    let mut scratch = vec![PreparedVertex::<4>::default(); SPHERE.0.max(TORUS.0)];
    let mut stats = RenderStats::default();
    let mut frame = Framebuffer::new(&mut px, W, H).unwrap();
    let mut depth = DepthBuffer::new(&mut zs, W, H).unwrap();
    zscan::render::render_scene(r, &mut frame, &mut depth, &mut scratch, &mut stats).unwrap();
    (px, zs, stats)
}

/// Interpenetrating lit objects (flat, exact and fast Gouraud, dithered or not: the Gouraud
/// ones keep a level byte per vertex), seen from several eyes: compact bands draw the
/// one-pass frame.
#[test]
fn lit_objects_equal_the_full_frame() {
    let m = Meshes::new();
    let light = [Light::Point {
        position: Vec3::from_int(-3, 4, 5),
        intensity: 230,
    }];
    let shades = [
        ShadeMode::Flat,
        ShadeMode::GouraudExact,
        ShadeMode::GouraudFast,
    ];
    let mut cases = 0;
    for (k, eye) in [(0, 1, 5), (3, 2, 4), (-2, -3, 4), (0, 5, 1)]
        .into_iter()
        .enumerate()
    {
        let cam = camera(Vec3::from_int(eye.0, eye.1, eye.2));
        for (s, &shade) in shades.iter().enumerate() {
            let mut a = lit(&m.sphere, shade, Vec3::from_int(0, 0, 0), 10 * k as i32);
            let b = lit(&m.torus, shades[(s + 1) % 3], Vec3::ZERO, 25 + 7 * k as i32);
            a.dither = k % 2 == 1;
            let objects = [a, b];
            let scene = Scene {
                camera: cam,
                objects: &objects,
                background: 255,
                ambient: 40,
                lights: &light,
            };
            let r = Renderer::for_scene(&scene).unwrap();
            let (px, zs, st) = one_pass(&r);
            assert!(st.pixels_covered > 1000, "{eye:?}: something is drawn");
            let sizes = CompactSizes::of(&scene);
            let lit_vertices = [shade, shades[(s + 1) % 3]]
                .iter()
                .zip([SPHERE.0, TORUS.0])
                .filter(|(sh, _)| **sh != ShadeMode::Flat)
                .map(|(_, n)| n)
                .sum::<usize>();
            assert_eq!(sizes.levels, lit_vertices);
            for rows in [1u16, 9, 40] {
                let (cp, cz, cs) = render_compact_picture::<u32, 4>(&r, (W, H), rows).unwrap();
                assert!(cp == px && cz == zs, "{eye:?} {shade:?} bands of {rows}");
                assert_eq!(
                    (cs.pixels_covered, cs.pixels_written, cs.culled),
                    (st.pixels_covered, st.pixels_written, st.culled)
                );
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 36);
}

/// A vertex behind the near plane (the eye inside the torus's hole, looking along it) needs
/// the clipper: the frame is refused, naming the object and the vertex, before any band is
/// drawn; so is a Phong object.
#[test]
fn clipping_and_phong_are_refused() {
    let m = Meshes::new();
    let cam = camera(Vec3::from_int(3, 0, 0));
    let far = lit(
        &m.sphere,
        ShadeMode::GouraudExact,
        Vec3::from_int(-2, 0, 0),
        0,
    );
    let near = lit(&m.torus, ShadeMode::Flat, Vec3::from_int(3, 0, 0), 0);
    let objects = [far, near];
    let scene = Scene {
        camera: cam,
        objects: &objects,
        background: 0,
        ambient: 40,
        lights: &[],
    };
    let r = Renderer::for_scene(&scene).unwrap();
    let (_, _, st) = one_pass(&r);
    assert!(st.clipped > 0, "the one-pass frame clips");
    let mut bands = 0;
    let e = render_with(&r, [W as usize * 8, W as usize * 8], &mut bands).unwrap_err();
    match e {
        RenderError::NotCompact { object, vertex } => {
            assert_eq!(object, 1);
            assert!(vertex < TORUS.0);
            // The named vertex is one the full vertex stage finds outside the frustum.
            let mut full = vec![PreparedVertex::<4>::default(); TORUS.0];
            r.renderer().prepare(&objects[1], &mut full).unwrap();
            assert_ne!(full[vertex].outcode, 0);
            assert!(full[..vertex].iter().all(|p| p.outcode == 0));
        }
        e => panic!("expected NotCompact, got {e}"),
    }
    assert_eq!(bands, 0, "no band drawn");
    let phong = [lit(&m.sphere, ShadeMode::Phong, Vec3::ZERO, 0)];
    let scene = Scene {
        camera: camera(Vec3::from_int(0, 0, 5)),
        objects: &phong,
        ..scene
    };
    let r = Renderer::for_scene(&scene).unwrap();
    let e = render_with(&r, [W as usize * 8; 2], &mut bands).unwrap_err();
    assert_eq!(e, RenderError::PhongUnsupported);
}

/// `render_in_compact_bands` in bands of 8 rows with band buffers of `band` elements and the
/// scratch sized by `CompactSizes`; counts the bands drawn in `bands`.
fn render_with(
    r: &SceneRenderer<'_, 4>,
    band: [usize; 2],
    bands: &mut usize,
) -> Result<(), RenderError> {
    let sizes = CompactSizes::of(r.scene());
    render_sized(
        r,
        band,
        [sizes.vertices, sizes.levels, sizes.polygons],
        bands,
    )
}

fn render_sized(
    r: &SceneRenderer<'_, 4>,
    [pixels, depths]: [usize; 2],
    [vertices, levels, polygons]: [usize; 3],
    bands: &mut usize,
) -> Result<(), RenderError> {
    let (mut px, mut zs) = (vec![0u8; pixels], vec![0u16; depths]);
    let mut v = vec![CompactVertex::default(); vertices];
    let mut l = vec![0u8; levels];
    let mut p = vec![PolygonTop::default(); polygons];
    render_in_compact_bands(
        r,
        (&mut px, &mut zs),
        (W, H, 8),
        CompactBandScratch {
            vertices: &mut v,
            levels: &mut l,
            polygons: &mut p,
        },
        &mut RenderStats::default(),
        |_, _| {
            *bands += 1;
            Ok::<(), RenderError>(())
        },
    )
}

/// Each part one element short is refused with its name and both sizes, nothing drawn; the
/// exact sizes draw every band; the formula adds up the buffers' bytes.
#[test]
fn short_memory_is_named_and_the_formula_adds_up() {
    let m = Meshes::new();
    let objects = [
        lit(&m.sphere, ShadeMode::GouraudExact, Vec3::ZERO, 0),
        lit(&m.torus, ShadeMode::Flat, Vec3::ZERO, 30),
    ];
    let scene = Scene {
        camera: camera(Vec3::from_int(0, 1, 5)),
        objects: &objects,
        background: 0,
        ambient: 40,
        lights: &[],
    };
    let r = Renderer::for_scene(&scene).unwrap();
    let sizes = CompactSizes::of(&scene);
    assert_eq!(
        (sizes.vertices, sizes.levels, sizes.polygons),
        (SPHERE.0 + TORUS.0, SPHERE.0, (SPHERE.1 + TORUS.1) / 3)
    );
    let band = W as usize * 8;
    let exact = [sizes.vertices, sizes.levels, sizes.polygons];
    let mut bands = 0;
    render_sized(&r, [band, band], exact, &mut bands).unwrap();
    assert_eq!(bands, (H as usize).div_ceil(8));
    let parts = [
        BandPart::Pixels,
        BandPart::Depths,
        BandPart::Vertices,
        BandPart::Levels,
        BandPart::Polygons,
    ];
    for (k, part) in parts.into_iter().enumerate() {
        let mut b = [band, band];
        let mut s = exact;
        let needed = if k < 2 { band } else { exact[k - 2] };
        if k < 2 {
            b[k] -= 1;
        } else {
            s[k - 2] -= 1;
        }
        let mut bands = 0;
        let e = render_sized(&r, b, s, &mut bands).unwrap_err();
        let given = needed - 1;
        assert_eq!(
            e,
            RenderError::BandMemoryTooSmall {
                part,
                given,
                needed
            }
        );
        let text = e.to_string();
        assert!(
            text.contains(&given.to_string()) && text.contains(&needed.to_string()),
            "{text}"
        );
        assert_eq!(bands, 0);
    }
    // Bytes: band pixels and 16-bit depths, 8 per vertex, 1 per lit vertex and per polygon.
    let bytes = band * (1 + 2) + 8 * sizes.vertices + sizes.levels + sizes.polygons;
    assert_eq!(sizes.bytes(W, 8, 2), bytes);
    assert_eq!(
        sizes.bytes(W, 8, 2),
        band * (1 + size_of::<u16>())
            + sizes.vertices * size_of::<CompactVertex>()
            + sizes.levels
            + sizes.polygons * size_of::<PolygonTop>()
    );
    // The bunny of the module doc: 320 × 240 in bands of 11 rows, 16-bit depth.
    let bunny = CompactSizes {
        vertices: 1839,
        levels: 0,
        polygons: 3674,
    };
    assert_eq!(bunny.bytes(320, 11, 2), 28_946);
    // The tallest band within a budget: the bunny's 28,946 bytes hold 11 rows, one byte less
    // 10; below the scratch alone, none; a large budget, the whole picture.
    assert_eq!(bunny.band_rows_within(28_946, 320, 240, 2), 11);
    assert_eq!(bunny.band_rows_within(28_945, 320, 240, 2), 10);
    assert_eq!(bunny.band_rows_within(18_385, 320, 240, 2), 0);
    assert_eq!(bunny.band_rows_within(1 << 20, 320, 240, 2), 240);
    for budget in [18_386, 20_000, 25_000, 40_000] {
        let rows = bunny.band_rows_within(budget, 320, 240, 2);
        assert!(bunny.bytes(320, rows, 2) <= budget, "{budget}");
        assert!(
            rows == 240 || bunny.bytes(320, rows + 1, 2) > budget,
            "{budget}"
        );
    }
}
