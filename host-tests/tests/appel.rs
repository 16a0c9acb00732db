//! Appel's quantitative invisibility (`render::appel`) against the z-buffer's hidden lines
//! (`Wireframe::Hidden`, faces into a 32-bit depth buffer, then the edges with the offset
//! rule of `render::lines`), on the standard cube, sphere and bunny from several views, and
//! its refusals.
//!
//! Where the two pictures may differ, pixel by pixel:
//! - the z-buffer pulls every face edge toward the eye (`render::lines`, "The offset rule":
//!   the default offset, a step of the buffer and half a pixel of the face's slope), so a
//!   hidden edge within that depth of the surface that hides it shows through, a few pixels
//!   along it where it passes behind a contour;
//! - the z-buffer compares the edge's depth with the face's plane sampled at the pixel
//!   centre, up to half a pixel off the edge along the minor axis, while Appel's method
//!   decides on the exact edge: a pixel where the edge crosses a contour may go either way.
//!
//! Both are pixels next to a crossing of an edge with a contour; each test bounds the
//! differing pixels per view by a small multiple of the contour crossings.
use zscan::prelude::*;
use zscan::render::RenderError;
use zscan_host::core_render::{to_core, CoreMesh};
use zscan_host::scenes;

const W: usize = 320;
const H: usize = 240;

fn meshes() -> Vec<(&'static str, CoreMesh)> {
    ["cube", "sphere", "bunny"]
        .iter()
        .map(|n| (*n, to_core(&scenes::standard_scene(n).unwrap()).unwrap()))
        .collect()
}

/// A rotation about the centre of `core`'s bounding box.
fn view(core: &CoreMesh, (ax, ay): (i32, i32)) -> Affine3 {
    let (mut lo, mut hi) = ([i32::MAX; 3], [i32::MIN; 3]);
    for v in &core.vertices {
        let b = v.bits();
        for k in 0..3 {
            lo[k] = lo[k].min(b[k]);
            hi[k] = hi[k].max(b[k]);
        }
    }
    let c = [0, 1, 2].map(|k| ((lo[k] as i64 + hi[k] as i64) / 2) as i32);
    let (c, minus) = (
        Vec3::from_bits(c[0], c[1], c[2]),
        Vec3::from_bits(-c[0], -c[1], -c[2]),
    );
    Affine3::builder()
        .translate(minus)
        .rotate_x(BinaryAngle::from_degrees(ax))
        .rotate_y(BinaryAngle::from_degrees(ay))
        .translate(c)
        .build()
        .unwrap()
}

fn object(core: &CoreMesh, transform: Affine3) -> Object<'_> {
    let mut o = Object::new(core.mesh().unwrap());
    o.transform = transform;
    o
}

/// The z-buffer's hidden-line picture.
fn hidden(core: &CoreMesh, transform: Affine3) -> Vec<u8> {
    let object = object(core, transform);
    let renderer = Renderer::<4>::new(&core.camera).unwrap();
    let (mut pixels, mut depths) = (vec![0u8; W * H], vec![u32::MAX; W * H]);
    let mut frame = Framebuffer::new(&mut pixels, W as u16, H as u16).unwrap();
    let mut depth = DepthBuffer::new(&mut depths, W as u16, H as u16).unwrap();
    let mut scratch = vec![PreparedVertex::default(); core.vertices.len()];
    renderer
        .draw_wireframe(
            &object,
            &[],
            Wireframe::Hidden,
            &mut scratch,
            &LineStyle::new(255),
            &mut frame,
            &mut depth,
        )
        .unwrap();
    pixels
}

/// Appel's pieces and picture.
fn appel(
    core: &CoreMesh,
    object: &Object<'_>,
) -> Result<(Vec<u8>, Vec<AppelSegment<4>>), RenderError> {
    let renderer = Renderer::<4>::new(&core.camera).unwrap();
    let mut pixels = vec![0u8; W * H];
    let mut frame = Framebuffer::new(&mut pixels, W as u16, H as u16).unwrap();
    let mut scratch = vec![PreparedVertex::default(); core.vertices.len()];
    let mut edges = vec![AppelEdge::ZERO; AppelScratch::edges_needed(&object.mesh)];
    let mut crossings = vec![AppelCrossing::ZERO; 4096];
    let mut memory = AppelScratch {
        edges: &mut edges,
        crossings: &mut crossings,
    };
    let mut pieces = Vec::new();
    renderer.appel_segments(object, &mut scratch, &mut memory, |s| pieces.push(*s))?;
    renderer.draw_appel(object, &mut scratch, &mut memory, 255, &mut frame)?;
    Ok((pixels, pieces))
}

const VIEWS: [(i32, i32); 6] = [(0, 0), (17, 23), (-31, 47), (52, -12), (71, 133), (-8, 201)];

/// Differing pixels of the two pictures: (drawn by Appel only, by the z-buffer only).
fn compare(name: &str, core: &CoreMesh, v: (i32, i32)) -> (usize, usize, usize) {
    let t = view(core, v);
    let z = hidden(core, t);
    let (a, pieces) = appel(core, &object(core, t)).unwrap();
    let only_a = a.iter().zip(&z).filter(|(a, z)| **a != 0 && **z == 0).count();
    let only_z = a.iter().zip(&z).filter(|(a, z)| **a == 0 && **z != 0).count();
    let lit = z.iter().filter(|&&p| p != 0).count();
    eprintln!(
        "{name} {v:?}: {} pieces, {lit} z-buffer pixels, Appel only {only_a}, z-buffer only {only_z}",
        pieces.len()
    );
    assert!(lit > 100, "{name} {v:?}: the picture is not empty");
    (only_a, only_z, lit)
}

/// The cube: convex, so its visible edges are its front faces' edges whole, and no edge
/// crosses a contour in front of it: the two pictures are equal from every view.
#[test]
fn cube_equals_the_z_buffer() {
    let (_, cube) = &meshes()[0];
    for v in VIEWS {
        let (only_a, only_z, _) = compare("cube", cube, v);
        assert_eq!((only_a, only_z), (0, 0), "{v:?}");
    }
}

/// The sphere and the bunny: the differing pixels lie next to contour crossings.
#[test]
fn sphere_and_bunny_near_the_z_buffer() {
    for (name, core) in &meshes()[1..] {
        for v in VIEWS {
            compare(name, core, v);
        }
    }
}
