//! Where the hidden-surface methods fail, as scenes, counts and pictures: what
//! `zscan failures` draws into `docs/images/` and `tests/visibility.rs` asserts.
//!
//! Each [`Failure`] is one method on one scene against a reference drawn by the 32-bit
//! z-buffer: the painter without Newell's test 6 on a cycle of three triangles and on two
//! interpenetrating triangles, back faces alone on the (non-convex) standard bunny, and a
//! 16-bit z-buffer on two surfaces 0.5 units apart about 40 units away at far/near = 1000 and
//! 10,000 (z-fighting). A *wrong pixel* is one whose palette index differs from the
//! reference's. The picture ([`Failure::marked`]) is the method's frame dimmed to half its
//! grey, with every wrong pixel in [`WRONG_COLOUR`], scaled up by a whole factor (nearest
//! pixel) so that single pixels show in the docs.
//!
//! Everything here is set-up (`f64` vertices rounded once to I16F16, as `core_render`); the
//! frames are the core's.

use zscan::geometry::camera::{Camera, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::trig::Angle;
use zscan::geometry::vector::Vec3;
use zscan::render::{BandScratch, PolygonRows, PreparedVertex, RenderError, Renderer};
use zscan::scene::{Intensities, Object, Scene};
use zscan::shade::span_writer::ShadeMode;
use zscan::visibility::Visibility;

use crate::core_render::{render_picture, render_visible, to_core};

/// The colour of a wrong pixel in [`Failure::marked`].
pub const WRONG_COLOUR: [u8; 3] = [255, 40, 40];

/// The frame size of the small failure scenes (the bunny is the standard 320 × 240).
pub const SMALL: (u16, u16) = (160, 120);

/// A triangle soup: vertices, indices (three per triangle), one level per triangle.
pub type Soup = (Vec<Vec3>, Vec<u16>, Vec<u8>);

/// `(x, y, z)` rounded to I16F16.
pub fn v(x: f64, y: f64, z: f64) -> Vec3 {
    let c = |a: f64| Coord::from_num(a);
    Vec3::new(c(x), c(y), c(z))
}

/// The small scenes' camera: at `(0, 0, 6)` looking at the origin, 60°, near `near`, far 50.
pub fn camera_with_near(w: u16, h: u16, near: &str) -> Camera {
    let lens = Lens::new(Angle::from_degrees(60), Coord::lit(near), Coord::lit("50"));
    let up = Vec3::from_int(0, 1, 0);
    Camera::look_at(
        Vec3::from_int(0, 0, 6),
        Vec3::ZERO,
        up,
        lens,
        Viewport::new(w, h),
    )
    .expect("a valid camera")
}

/// [`camera_with_near`] at near 0.5 (far/near = 100).
pub fn camera(w: u16, h: u16) -> Camera {
    camera_with_near(w, h, "0.5")
}

/// An object of one triangle soup, flat, levels per triangle, back faces drawn (both sides
/// show).
pub fn soup_object<'a>(vertices: &'a [Vec3], indices: &'a [u16], levels: &'a [u8]) -> Object<'a> {
    let mesh = Mesh::new(vertices, indices, PolygonSizes::Uniform(3)).expect("a valid soup");
    let mut o = Object::new(mesh);
    o.cull_back_faces = false;
    o.intensities = Intensities::PerPolygon(levels);
    o.shade = ShadeMode::Flat;
    o
}

/// Three long triangles each over the next and under the one before (the survey's cycle):
/// no order of the three is right, so the painter needs test 6.
pub fn cycle_of_three() -> Soup {
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

/// Two triangles that pass through each other: each is in front of the other on one side of
/// their intersection.
pub fn interpenetrating() -> Soup {
    let vs = vec![
        v(-2.0, -1.0, -1.0),
        v(2.0, -1.0, 1.0),
        v(0.0, 1.5, 0.0),
        v(-2.0, -1.0, 1.0),
        v(2.0, -1.0, -1.0),
        v(0.0, 1.2, 0.2),
    ];
    (vs, (0..6).collect(), vec![100, 200])
}

/// Two parallel quads `gap` units apart about 34–46 units from the eye (their depth falls 0.4
/// per unit of `x`), the farther one stored first so that a depth tie keeps it (a wrong pixel).
pub fn far_pair(gap: f64) -> Soup {
    let mut vs = Vec::new();
    for z in [-34.0 - gap, -34.0] {
        for (x, y) in [(-14.0, -9.0), (14.0, -9.0), (14.0, 9.0), (-14.0, 9.0)] {
            vs.push(v(x, y, z - 0.4 * x));
        }
    }
    let is = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
    (vs, is, vec![80, 80, 200, 200])
}

/// The near plane giving far/near = `ratio` with the far plane at 50 (1000 or 10,000).
pub fn near_for_ratio(ratio: u32) -> &'static str {
    match ratio {
        1000 => "0.05",
        10_000 => "0.005",
        _ => "0.5",
    }
}

/// One method's frame against its reference.
#[derive(Debug, Clone)]
pub struct Failure {
    /// File stem of the picture (`docs/images/<name>.png`).
    pub name: &'static str,
    /// What is drawn, against what.
    pub caption: &'static str,
    /// Frame size.
    pub size: (u16, u16),
    /// The method's frame (palette indices = grey levels, row-major).
    pub method: Vec<u8>,
    /// The reference frame (the 32-bit z-buffer's).
    pub reference: Vec<u8>,
}

impl Failure {
    /// Pixels whose index differs from the reference's.
    pub fn wrong(&self) -> usize {
        self.method
            .iter()
            .zip(&self.reference)
            .filter(|(a, b)| a != b)
            .count()
    }

    /// The picture of the module doc, `scale` times the frame's size: RGB, row-major.
    pub fn marked(&self, scale: usize) -> Vec<u8> {
        let (w, h) = (self.size.0 as usize, self.size.1 as usize);
        let mut out = Vec::with_capacity(w * h * scale * scale * 3);
        for y in 0..h * scale {
            for x in 0..w * scale {
                let at = (y / scale) * w + x / scale;
                let (m, r) = (self.method[at], self.reference[at]);
                let rgb = if m == r { [m / 2; 3] } else { WRONG_COLOUR };
                out.extend_from_slice(&rgb);
            }
        }
        out
    }
}

/// The frames of `method` (the painter: split budget `splits`, `None` without test 6) and of
/// the 32-bit z-buffer on `scene`.
fn against_z32(
    scene: &Scene<'_>,
    method: Visibility,
    splits: Option<usize>,
) -> Result<(Vec<u8>, Vec<u8>), RenderError> {
    let vp = *scene.camera.viewport();
    let size = (vp.width, vp.height);
    let renderer = Renderer::for_scene(scene)?;
    let (m, _) = render_visible(&renderer, size, method, splits, 1)?;
    let (z, _) = render_visible(&renderer, size, Visibility::ZBuffer, None, vp.height)?;
    Ok((m, z))
}

/// The painter on `soup` at far/near 100, without test 6 (`splits = None`) or with it.
pub fn painter_on(soup: &Soup, splits: Option<usize>) -> Result<(Vec<u8>, Vec<u8>), RenderError> {
    let objects = [soup_object(&soup.0, &soup.1, &soup.2)];
    let scene = crate::core_render::scene_of(&objects, camera(SMALL.0, SMALL.1));
    against_z32(&scene, Visibility::Painter, splits)
}

/// `method` on the standard bunny (Gouraud, as SCENES.md draws it) against the 32-bit
/// z-buffer.
pub fn on_bunny(
    method: Visibility,
    splits: Option<usize>,
) -> Result<(Vec<u8>, Vec<u8>), RenderError> {
    let scene = crate::scenes::standard_scene("bunny").expect("the standard bunny");
    let core = to_core(&scene).expect("the bunny in the core's tables");
    let objects = [core
        .object(ShadeMode::GouraudExact)
        .expect("the bunny object")];
    let scene = crate::core_render::scene_of(&objects, core.camera);
    against_z32(&scene, method, splits)
}

/// The 16-bit z-buffer's frame of [`far_pair`]`(gap)` at far/near = `ratio`, and the 32-bit
/// one's.
pub fn z16_on_far_pair(gap: f64, ratio: u32) -> Result<(Vec<u8>, Vec<u8>), RenderError> {
    let (w, h) = SMALL;
    let (vs, is, ls) = far_pair(gap);
    let objects = [soup_object(&vs, &is, &ls)];
    let scene =
        crate::core_render::scene_of(&objects, camera_with_near(w, h, near_for_ratio(ratio)));
    let renderer = Renderer::for_scene(&scene)?;
    let mut scratch = vec![PreparedVertex::default(); vs.len()];
    let mut table = vec![PolygonRows::default(); is.len() / 3];
    let scratch = BandScratch {
        vertices: &mut scratch,
        polygons: &mut table,
    };
    let (z16, _, _) = render_picture::<u16, 4>(&renderer, (w, h), None, scratch)?;
    let (z32, _) = render_visible(&renderer, (w, h), Visibility::ZBuffer, None, h)?;
    Ok((z16, z32))
}

/// Every failure the docs show, in the docs' order.
pub fn failures() -> Result<Vec<Failure>, RenderError> {
    let small = |name, caption, (method, reference)| Failure {
        name,
        caption,
        size: SMALL,
        method,
        reference,
    };
    let bunny = on_bunny(Visibility::BackFace, None)?;
    Ok(vec![
        small(
            "fail_painter_cycle",
            "painter without test 6, cycle of three triangles",
            painter_on(&cycle_of_three(), None)?,
        ),
        small(
            "fail_painter_interpenetration",
            "painter without test 6, two interpenetrating triangles",
            painter_on(&interpenetrating(), None)?,
        ),
        Failure {
            name: "fail_backface_bunny",
            caption: "back faces alone, standard bunny (not convex)",
            size: (320, 240),
            method: bunny.0,
            reference: bunny.1,
        },
        small(
            "fail_z16_ratio1000",
            "16-bit z-buffer, surfaces 0.5 apart, far/near = 1000",
            z16_on_far_pair(0.5, 1000)?,
        ),
        small(
            "fail_z16_ratio10000",
            "16-bit z-buffer, surfaces 0.5 apart, far/near = 10,000",
            z16_on_far_pair(0.5, 10_000)?,
        ),
    ])
}
