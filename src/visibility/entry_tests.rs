//! The scene renderer's entry points side by side: the z-buffer (whole and in bands), back
//! faces only, the painter and the scan-line method draw a scene with the scene's own camera
//! and lights, the picture a renderer built from them directly gives.

use super::{
    render_back_faces, render_painter, render_scan_lines, Normal, PainterMemory, ScanLineMemory,
    SplitPolicy, StoredTriangle,
};
use crate::geometry::camera::{Camera, Lens, Viewport};
use crate::geometry::fixed::Coord;
use crate::geometry::generators::unit_cube;
use crate::geometry::matrix::Affine3;
use crate::geometry::trig::BinaryAngle;
use crate::geometry::vector::Vec3;
use crate::lighting::Light;
use crate::lighting::Material;
use crate::output::{DepthBuffer, Framebuffer};
use crate::render::{render_in_bands, render_scene, BandScratch, PreparedVertex, RenderStats};
use crate::render::{Renderer, SceneRenderer};
use crate::scene::Intensities;
use crate::scene::{Object, Scene};

const W: u16 = 32;
const H: u16 = 24;
const N: usize = W as usize * H as usize;

/// A flat-lit cube seen from `eye`, lit by a point light at `light`.
fn camera(eye: Vec3) -> Camera {
    let lens = Lens::new(
        BinaryAngle::from_degrees(50),
        Coord::lit("0.5"),
        Coord::lit("20"),
    );
    let up = Vec3::from_int(0, 1, 0);
    Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(W, H)).unwrap()
}

fn cube() -> Object<'static> {
    let mut cube = Object::new(unit_cube());
    cube.transform = Affine3::builder()
        .translate(Vec3::from_bits(-1 << 15, -1 << 15, -1 << 15))
        .build()
        .unwrap();
    cube.intensities = Intensities::Lit {
        material: Material::from_thousandths(100, 800, 0, 1),
        normals: &[],
    };
    cube.shade = crate::raster::triangle::ShadeMode::Flat;
    cube
}

/// The picture of `objects` drawn one by one, through the depth buffer, with a renderer
/// built from `camera`, `ambient` and `lights` directly (not from a scene).
fn reference(camera: &Camera, ambient: u8, lights: &[Light], objects: &[Object<'_>]) -> [u8; N] {
    let r = Renderer::<4>::new(camera)
        .unwrap()
        .with_lights(ambient, lights)
        .unwrap();
    let (mut pixels, mut depths) = ([0u8; N], [0u16; N]);
    let mut frame = Framebuffer::new(&mut pixels, W, H).unwrap();
    let mut depth = DepthBuffer::new(&mut depths, W, H).unwrap();
    frame.clear(0);
    depth.clear();
    let mut scratch = [PreparedVertex::default(); 8];
    for o in objects {
        let stats = &mut RenderStats::default();
        r.draw_object(o, &mut scratch, &mut frame, &mut depth, stats)
            .unwrap();
    }
    pixels
}

/// The pictures of every scene entry for `renderer`: render_scene, render_in_bands,
/// back faces alone, the painter and the scan-line.
fn entries(renderer: &SceneRenderer<'_, 4>) -> [[u8; N]; 5] {
    let mut out = [[0u8; N]; 5];
    let mut scratch = [PreparedVertex::default(); 8];
    let stats = &mut RenderStats::default();
    let mut depths = [0u16; N];
    {
        let mut frame = Framebuffer::new(&mut out[0], W, H).unwrap();
        let mut depth = DepthBuffer::new(&mut depths, W, H).unwrap();
        render_scene(renderer, &mut frame, &mut depth, &mut scratch, stats).unwrap();
    }
    let (mut band, mut band_depth) = ([0u8; W as usize * 5], [0u16; W as usize * 5]);
    let copy = |picture: &mut [u8; N], f: &mut Framebuffer<'_>| {
        for (y, row) in f.rows() {
            let at = y as usize * W as usize;
            picture[at..at + row.len()].copy_from_slice(row);
        }
        Ok::<(), crate::visibility::VisibilityError>(())
    };
    let scratch_b = BandScratch {
        vertices: &mut scratch,
        polygons: &mut [],
    };
    render_in_bands(
        renderer,
        (&mut band, &mut band_depth),
        (W, H, 5),
        scratch_b,
        stats,
        |f, _| copy(&mut out[1], f),
    )
    .unwrap();
    {
        let mut frame = Framebuffer::new(&mut out[2], W, H).unwrap();
        render_back_faces(renderer, &mut frame, &mut scratch, stats).unwrap();
    }
    let (mut triangles, mut order) = ([StoredTriangle::DEFAULT; 16], [0u32; 16]);
    {
        let mut frame = Framebuffer::new(&mut out[3], W, H).unwrap();
        let mut normals = [Normal::DEFAULT; 16];
        let memory = PainterMemory {
            triangles: &mut triangles,
            order: &mut order,
            normals: &mut normals,
        };
        let policy = SplitPolicy::Budget(4);
        render_painter(renderer, &mut frame, &mut scratch, memory, policy, stats).unwrap();
    }
    let mut active = [0u32; 16];
    let memory = ScanLineMemory {
        triangles: &mut triangles,
        order: &mut order,
        active: &mut active,
        pixels: &mut band,
        depths: &mut band_depth,
    };
    render_scan_lines(renderer, (W, H, 5), &mut scratch, memory, stats, |f, _| {
        copy(&mut out[4], f)
    })
    .unwrap();
    out
}

/// The scene is the one source of the camera and lights it is drawn with: no entry takes a
/// scene beside its renderer, so scene B cannot be drawn with the camera and lights of a
/// renderer built for scene A (the mismatch the former `render_scene(&renderer, &scene,
/// …)` allowed). Every entry draws its renderer's scene exactly as a renderer built from
/// that scene's camera and lights draws its objects; scenes A and B differ, so an entry
/// that used other parts would fail; and new objects under a renderer
/// ([`SceneRenderer::with_objects`]) keep that renderer's camera and lights.
#[test]
fn scene_entries_draw_with_the_scenes_own_camera_and_lights() {
    let objects = [cube()];
    let (lights_a, lights_b) = (
        [Light::Point {
            position: Vec3::from_int(3, 4, 5),
            intensity: 255,
        }],
        [Light::Directional {
            toward: Vec3::from_int(-1, 0, 1),
            intensity: 120,
        }],
    );
    let a = Scene {
        camera: camera(Vec3::from_int(1, 1, 2)),
        objects: &objects,
        background: 0,
        ambient: 20,
        lights: &lights_a,
    };
    let b = Scene {
        camera: camera(Vec3::from_int(-2, 1, 1)),
        ambient: 60,
        lights: &lights_b,
        ..a
    };
    let picture_a = reference(&a.camera, a.ambient, a.lights, a.objects);
    let picture_b = reference(&b.camera, b.ambient, b.lights, b.objects);
    assert_ne!(picture_a, picture_b, "the two scenes must look different");
    assert!(picture_b.iter().filter(|&&p| p != 0).count() > 50);
    for (scene, picture) in [(&a, &picture_a), (&b, &picture_b)] {
        let renderer = Renderer::for_scene(scene).unwrap();
        assert_eq!(renderer.renderer().camera(), &scene.camera);
        for (entry, drawn) in entries(&renderer).iter().enumerate() {
            assert!(
                drawn == picture,
                "entry {entry} drew another camera or lights"
            );
        }
    }
    // Objects moved under A's renderer: A's camera and lights, the new objects.
    let mut moved = cube();
    moved.transform = Affine3::builder()
        .rotate_y(BinaryAngle::from_degrees(30))
        .build()
        .unwrap();
    let moved = [moved];
    let under_a = Renderer::for_scene(&a).unwrap();
    let under_a = under_a.with_objects(&moved);
    assert_eq!(under_a.scene().camera, a.camera);
    let expected = reference(&a.camera, a.ambient, a.lights, &moved);
    assert_ne!(expected, picture_a);
    assert!(entries(&under_a)[0] == expected);
}
