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
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::raster::triangle::ShadeMode;
use zscan::render::{
    BandScratch, PolygonRows, PreparedVertex, RenderError, Renderer, SceneRenderer,
};
use zscan::scene::{Intensities, Object};
use zscan::visibility::{Visibility, VisibilityError};

use zscan::output::DepthValue;

use crate::core_render::{
    render_compact_picture, render_picture, render_visible, scene_of, to_core,
};

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
    let lens = Lens::new(
        BinaryAngle::from_degrees(60),
        Coord::lit(near),
        Coord::lit("50"),
    );
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

/// The scenes of the failures and of the chart of the hidden-surface methods' speed against
/// accuracy (`zscan chart`): each traps at least one method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trap {
    /// [`cycle_of_three`] in the small frame at far/near 100.
    Cycle,
    /// [`interpenetrating`] in the small frame at far/near 100.
    Interpenetration,
    /// The standard bunny (Gouraud, as SCENES.md draws it), 320 × 240: not convex.
    Bunny,
    /// [`far_pair`]`(0.5)` in the small frame at far/near 1000.
    FarPair1000,
    /// [`far_pair`]`(0.5)` in the small frame at far/near 10,000.
    FarPair10000,
}

impl Trap {
    /// Every trap, in the docs' order.
    pub const ALL: [Trap; 5] = [
        Trap::Cycle,
        Trap::Interpenetration,
        Trap::Bunny,
        Trap::FarPair1000,
        Trap::FarPair10000,
    ];

    /// A short name (the chart's `--run-visibility` argument).
    pub const fn name(self) -> &'static str {
        match self {
            Trap::Cycle => "cycle",
            Trap::Interpenetration => "interpenetration",
            Trap::Bunny => "bunny",
            Trap::FarPair1000 => "far1000",
            Trap::FarPair10000 => "far10000",
        }
    }

    /// What the scene is, in words.
    pub const fn caption(self) -> &'static str {
        match self {
            Trap::Cycle => "cycle of three triangles, 160x120",
            Trap::Interpenetration => "two interpenetrating triangles, 160x120",
            Trap::Bunny => "standard bunny (not convex), 320x240",
            Trap::FarPair1000 => {
                "two surfaces 0.5 apart about 40 units away, far/near = 1000, 160x120"
            }
            Trap::FarPair10000 => {
                "two surfaces 0.5 apart about 40 units away, far/near = 10,000, 160x120"
            }
        }
    }

    /// `f` of the scene's renderer.
    pub fn with<R>(
        self,
        f: impl FnOnce(&SceneRenderer<'_, 4>) -> Result<R, VisibilityError>,
    ) -> Result<R, VisibilityError> {
        let (w, h) = SMALL;
        let (soup, camera) = match self {
            Trap::Bunny => {
                let scene = crate::scenes::standard_scene("bunny").expect("the standard bunny");
                let core = to_core(&scene).expect("the bunny in the core's tables");
                let objects = [core
                    .object(ShadeMode::GouraudExact)
                    .expect("the bunny object")];
                let scene = scene_of(&objects, core.camera);
                return f(&Renderer::for_scene(&scene)?);
            }
            Trap::Cycle => (cycle_of_three(), camera(w, h)),
            Trap::Interpenetration => (interpenetrating(), camera(w, h)),
            Trap::FarPair1000 => (far_pair(0.5), camera_with_near(w, h, near_for_ratio(1000))),
            Trap::FarPair10000 => (
                far_pair(0.5),
                camera_with_near(w, h, near_for_ratio(10_000)),
            ),
        };
        let objects = [soup_object(&soup.0, &soup.1, &soup.2)];
        let scene = scene_of(&objects, camera);
        f(&Renderer::for_scene(&scene)?)
    }
}

/// The painter's split budget where it runs test 6 (enough for every trap; the bunny's folds
/// need the most).
pub const PAINTER_SPLITS: usize = 64;

/// A hidden-surface method with its depth width and memory layout, as the chart of speed
/// against accuracy compares them; each draws the whole picture through `core_render`, whose
/// measured region holds exactly the core's frame call.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Back faces culled, front faces in scene order, no depth.
    BackFace,
    /// The painter with tests 1 to 5 only (no split: a cycle or an interpenetration stays).
    PainterWithoutTest6,
    /// The painter with its six tests ([`PAINTER_SPLITS`] splits at most).
    Painter,
    /// The scan-line in bands of 16 rows (32-bit depth).
    ScanLine,
    /// Warnock's area subdivision.
    Warnock,
    /// The whole-frame z-buffer with 16-bit depth.
    ZBuffer16,
    /// The whole-frame z-buffer with 32-bit depth: the reference.
    ZBuffer32,
    /// The z-buffer in bands of 16 rows, 16-bit depth, with the polygon table.
    Bands16,
    /// The compact bands of 11 rows, 16-bit depth.
    Compact11,
}

impl Method {
    /// Every method, the reference last.
    pub const ALL: [Method; 9] = [
        Method::BackFace,
        Method::PainterWithoutTest6,
        Method::Painter,
        Method::ScanLine,
        Method::Warnock,
        Method::ZBuffer16,
        Method::Bands16,
        Method::Compact11,
        Method::ZBuffer32,
    ];

    /// A short name (the chart's `--run-visibility` argument).
    pub const fn name(self) -> &'static str {
        match self {
            Method::BackFace => "backface",
            Method::PainterWithoutTest6 => "painter_no_test6",
            Method::Painter => "painter",
            Method::ScanLine => "scanline16",
            Method::Warnock => "warnock",
            Method::ZBuffer16 => "zbuffer16",
            Method::ZBuffer32 => "zbuffer32",
            Method::Bands16 => "bands16",
            Method::Compact11 => "compact11",
        }
    }

    /// What the method is, in words (the chart's labels).
    pub const fn label(self) -> &'static str {
        match self {
            Method::BackFace => "back faces alone",
            Method::PainterWithoutTest6 => "painter without test 6",
            Method::Painter => "painter",
            Method::ScanLine => "scan-line (16 rows, 32-bit)",
            Method::Warnock => "Warnock",
            Method::ZBuffer16 => "z-buffer 16-bit",
            Method::ZBuffer32 => "z-buffer 32-bit (reference)",
            Method::Bands16 => "z-buffer bands (16 rows, 16-bit)",
            Method::Compact11 => "compact bands (11 rows, 16-bit)",
        }
    }

    /// The whole picture of `renderer`'s scene drawn by this method (palette indices,
    /// row-major).
    pub fn draw(self, renderer: &SceneRenderer<'_, 4>) -> Result<Vec<u8>, VisibilityError> {
        let vp = *renderer.scene().camera.viewport();
        let size = (vp.width, vp.height);
        let visible = |method, splits, bands| {
            render_visible(renderer, size, method, splits, bands).map(|(pixels, _)| pixels)
        };
        match self {
            Method::BackFace => visible(Visibility::BackFace, None, 1),
            Method::PainterWithoutTest6 => visible(Visibility::Painter, None, 1),
            Method::Painter => visible(Visibility::Painter, Some(PAINTER_SPLITS), 1),
            Method::ScanLine => visible(Visibility::ScanLine, None, 16),
            Method::Warnock => visible(Visibility::Warnock, None, 1),
            Method::ZBuffer16 => Ok(z_buffer::<u16>(renderer, None)?),
            Method::ZBuffer32 => Ok(z_buffer::<u32>(renderer, None)?),
            Method::Bands16 => Ok(z_buffer::<u16>(renderer, Some(16))?),
            Method::Compact11 => Ok(render_compact_picture::<u16, 4>(renderer, size, 11)
                .map(|(pixels, _, _)| pixels)?),
        }
    }
}

/// The z-buffer's picture with `D` depth samples in bands of `band_rows` rows (`None`: one
/// band), the vertex stage once and the polygon table.
fn z_buffer<D: DepthValue>(
    renderer: &SceneRenderer<'_, 4>,
    band_rows: Option<u16>,
) -> Result<Vec<u8>, RenderError> {
    let scene = renderer.scene();
    let vp = *scene.camera.viewport();
    let vertices: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let polygons: usize = scene.objects.iter().map(|o| o.mesh.polygon_count()).sum();
    let mut scratch = vec![PreparedVertex::default(); vertices];
    let mut table = vec![PolygonRows::default(); polygons];
    let scratch = BandScratch {
        vertices: &mut scratch,
        polygons: &mut table,
    };
    render_picture::<D, 4>(renderer, (vp.width, vp.height), band_rows, scratch)
        .map(|(pixels, _, _)| pixels)
}

/// `method`'s picture of `trap` and the 32-bit z-buffer's.
pub fn against_z32(trap: Trap, method: Method) -> Result<(Vec<u8>, Vec<u8>), VisibilityError> {
    trap.with(|r| Ok((method.draw(r)?, Method::ZBuffer32.draw(r)?)))
}

/// `method` on the standard bunny (the painter with a split budget of `splits`, `None`: no
/// test 6) against the 32-bit z-buffer.
pub fn on_bunny(
    method: Visibility,
    splits: Option<usize>,
) -> Result<(Vec<u8>, Vec<u8>), VisibilityError> {
    Trap::Bunny.with(|r| {
        let vp = *r.scene().camera.viewport();
        let (m, _) = render_visible(r, (vp.width, vp.height), method, splits, 1)?;
        Ok((m, Method::ZBuffer32.draw(r)?))
    })
}

/// Every failure the docs show, in the docs' order.
pub fn failures() -> Result<Vec<Failure>, VisibilityError> {
    let case = |name, caption, trap: Trap, method| {
        let (method, reference) = against_z32(trap, method)?;
        let size = if trap == Trap::Bunny {
            (320, 240)
        } else {
            SMALL
        };
        Ok::<_, VisibilityError>(Failure {
            name,
            caption,
            size,
            method,
            reference,
        })
    };
    Ok(vec![
        case(
            "fail_painter_cycle",
            "painter without test 6, cycle of three triangles",
            Trap::Cycle,
            Method::PainterWithoutTest6,
        )?,
        case(
            "fail_painter_interpenetration",
            "painter without test 6, two interpenetrating triangles",
            Trap::Interpenetration,
            Method::PainterWithoutTest6,
        )?,
        case(
            "fail_backface_bunny",
            "back faces alone, standard bunny (not convex)",
            Trap::Bunny,
            Method::BackFace,
        )?,
        case(
            "fail_z16_ratio1000",
            "16-bit z-buffer, surfaces 0.5 apart, far/near = 1000",
            Trap::FarPair1000,
            Method::ZBuffer16,
        )?,
        case(
            "fail_z16_ratio10000",
            "16-bit z-buffer, surfaces 0.5 apart, far/near = 10,000",
            Trap::FarPair10000,
            Method::ZBuffer16,
        )?,
    ])
}
