//! The scene: what to draw, described without a heap.
//!
//! Role in the pipeline: the input of [`render`](crate::render). An [`Object`] is a
//! [`Mesh`] (vertex and polygon tables in static slices, so it can live in flash), its
//! model → world [`Affine3`], where its luminance comes from and how to shade it. A [`Scene`]
//! is a camera, the lights and a slice of objects.
//!
//! Luminance comes either from the caller (a uniform level, or per-vertex or per-polygon
//! tables `0..=255`) or from the lighting stage ([`Intensities::Lit`]: a [`Material`] and the
//! mesh's vertex normals, lit by the scene's lights with the course's model,
//! [`lighting`](crate::lighting)). What each [`ShadeMode`] does with a lit object:
//!
//! | mode | lighting evaluated | interpolated |
//! |---|---|---|
//! | `Flat` | once per polygon, at its centroid with its face normal | nothing |
//! | `GouraudExact`, `GouraudFast` | once per vertex (vertex stage), with its vertex normal | levels |
//! | `Phong` | at every pixel that passes the depth test | normals and positions |
//!
//! Conventions: world axes as [`geometry`](crate::geometry) (right-handed, `y` up); front faces
//! counter-clockwise seen from outside; intensities are luminance levels `0..=255` that a
//! [`LuminanceRamp`] maps to palette indices (optionally dithered, [`Object::dither`]).

use crate::geometry::camera::Camera;
use crate::geometry::matrix::Affine3;
use crate::geometry::mesh::Mesh;
use crate::geometry::vector::Vec3;
use crate::lighting::{Light, Material};
use crate::output::BlendTable;
use crate::raster::triangle::{LuminanceRamp, Opacity, ShadeMode};
use crate::texture::Texturing;

/// Where an object's luminance comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Intensities<'a> {
    /// One level for the whole object.
    Uniform(u8),
    /// One level per vertex (Gouraud shading interpolates them); as long as the vertex table.
    PerVertex(&'a [u8]),
    /// One level per polygon (flat faces); as long as the polygon table.
    PerPolygon(&'a [u8]),
    /// Lit by the scene's lights ([`Renderer::with_lights`](crate::render::Renderer::with_lights)).
    Lit {
        /// Reflection coefficients.
        material: Material,
        /// Vertex normals in the model frame (any non-zero length), as long as the vertex
        /// table; flat shading does not read them (it uses face normals) and may pass `&[]`.
        /// Static meshes can keep them in flash beside the vertices, or compute them once with
        /// [`Mesh::vertex_normals`].
        normals: &'a [Vec3],
    },
}

/// One mesh placed in the world, with its shading.
///
/// ```
/// use zscan::geometry::{fixed::Coord, generators::unit_cube, matrix::Affine3};
/// use zscan::geometry::{trig::BinaryAngle, vector::Vec3};
/// use zscan::scene::{Intensities, Object};
/// use zscan::{lighting::Material, raster::triangle::{LuminanceRamp, ShadeMode}};
///
/// let mut cube = Object::new(unit_cube()); // the mesh's tables stay where they are (flash)
/// cube.transform = Affine3::builder()
///     .scale(Coord::from_num(2))
///     .translate(Vec3::from_int(-1, -1, -1)) // the unit cube [0, 1]³ becomes [−1, 1]³…
///     .rotate_y(BinaryAngle::from_degrees(30)) // …then turns and moves away
///     .translate(Vec3::from_int(0, 0, -3))
///     .build()?;
/// cube.intensities = Intensities::Lit {
///     material: Material::from_thousandths(150, 600, 300, 20),
///     normals: &[], // flat shading uses face normals
/// };
/// cube.shade = ShadeMode::Flat;
/// cube.ramp = LuminanceRamp { first: 0, levels: 64 }; // palette indices 0..64
/// # Ok::<(), zscan::geometry::matrix::MatrixError>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Object<'a> {
    /// The geometry, in the model frame.
    pub mesh: Mesh<'a>,
    /// Model → world.
    pub transform: Affine3,
    /// Luminance source.
    pub intensities: Intensities<'a>,
    /// Flat, exact Gouraud, fast Gouraud or Phong (Phong needs [`Intensities::Lit`]: with
    /// given levels it interpolates them as exact Gouraud).
    pub shade: ShadeMode,
    /// Luminance → palette index.
    pub ramp: LuminanceRamp,
    /// Ordered 4×4 dithering between adjacent ramp levels
    /// (`dither`), against banding on short ramps.
    pub dither: bool,
    /// Skip polygons facing away from the eye (closed meshes).
    pub cull_back_faces: bool,
    /// A texture over the mesh's texture coordinates ([`Mesh::with_uvs`]): the texel, through
    /// the shade table at the object's level when lit, replaces the ramp. `None`: untextured.
    pub texture: Option<Texturing<'a>>,
    /// Opaque, a screen door or blended ([`Transparency`]).
    pub transparency: Transparency<'a>,
}

/// How an object lets through what lies behind it, without refraction
/// ([`transparency`](crate::raster::triangle::transparency)).
#[derive(Debug, Clone, Copy, Default)]
pub enum Transparency<'a> {
    /// Every covered pixel drawn.
    #[default]
    Opaque,
    /// Covered pixels thinned by the 4×4 ordered mask of the opacity, in any drawing order and
    /// by every visibility method but Warnock's.
    ScreenDoor(Opacity),
    /// Each pixel in front of the opaque surfaces blended with the one under it through the
    /// table (depth tested, not stored); drawn after the opaque objects, far to near, by the
    /// z-buffer's frames (whole, banded, compact banded) only.
    Blended(BlendTable<'a>),
}

impl<'a> Object<'a> {
    /// An object with identity transform, uniform full intensity, exact Gouraud shading, the
    /// grey ramp without dithering, back-face culling, opaque.
    pub fn new(mesh: Mesh<'a>) -> Self {
        Object {
            mesh,
            transform: Affine3::default(),
            intensities: Intensities::Uniform(255),
            shade: ShadeMode::GouraudExact,
            ramp: LuminanceRamp::GREY,
            dither: false,
            cull_back_faces: true,
            texture: None,
            transparency: Transparency::Opaque,
        }
    }

    /// The given intensity of `vertex` in `polygon` (saturating to 0 when a table is too
    /// short — the renderer checks table lengths before drawing — and 0 for lit objects, whose
    /// levels the renderer computes).
    #[inline(always)]
    pub(crate) fn intensity(&self, polygon: usize, vertex: u16) -> u8 {
        match self.intensities {
            Intensities::Uniform(l) => l,
            Intensities::PerVertex(t) => t.get(vertex as usize).copied().unwrap_or(0),
            Intensities::PerPolygon(t) => t.get(polygon).copied().unwrap_or(0),
            Intensities::Lit { .. } => 0,
        }
    }
}

/// A camera, its lights and the objects it sees.
///
/// ```
/// use zscan::geometry::camera::{Camera, Lens, Viewport};
/// use zscan::geometry::{fixed::Coord, generators::unit_cube, trig::BinaryAngle, vector::Vec3};
/// use zscan::scene::{Object, Scene};
/// use zscan::lighting::Light;
///
/// let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
/// let up = Vec3::from_int(0, 1, 0);
/// let camera = Camera::look_at(Vec3::from_int(3, 2, 4), Vec3::ZERO, up, lens, Viewport::new(320, 240))?;
/// let lights = [
///     Light::Point { position: Vec3::from_int(-2, 5, 3), intensity: 200 },
///     Light::Directional { toward: Vec3::from_int(1, 1, 0), intensity: 60 },
/// ];
/// let objects = [Object::new(unit_cube())];
/// let scene = Scene { camera, ambient: 30, lights: &lights, objects: &objects, background: 0 };
/// assert_eq!(scene.objects.len(), 1);
/// # Ok::<(), zscan::geometry::camera::CameraError>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    /// The observer.
    pub camera: Camera,
    /// Ambient intensity `I_a` (`0..=255`) for lit objects.
    pub ambient: u8,
    /// Lights in the world frame (at most [`MAX_LIGHTS`](crate::lighting::MAX_LIGHTS)),
    /// for lit objects.
    pub lights: &'a [Light],
    /// The objects, drawn in order (the depth buffer resolves visibility).
    pub objects: &'a [Object<'a>],
    /// Palette index the frame is cleared to.
    pub background: u8,
}
