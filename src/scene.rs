//! The scene: what to draw, described without a heap.
//!
//! Role in the pipeline: the input of [`render`](crate::render). An [`Object`] is a
//! [`Mesh`] (vertex and polygon tables in static slices, so it can live in flash), its
//! model → world [`Affine3`], its per-vertex or per-polygon intensities (0..=255, computed by
//! the caller or by the lighting stage) and how to shade it. A [`Scene`] is a camera and a
//! slice of objects.
//!
//! Conventions: world axes as [`geometry`](crate::geometry) (right-handed, `y` up); front faces
//! counter-clockwise seen from outside; intensities are luminance levels `0..=255` that a
//! [`LuminanceRamp`] maps to palette indices.

use crate::geometry::camera::Camera;
use crate::geometry::matrix::Affine3;
use crate::geometry::mesh::Mesh;
use crate::shade::span_writer::{LuminanceRamp, ShadeMode};

/// Where an object's luminance comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Intensities<'a> {
    /// One level for the whole object.
    Uniform(u8),
    /// One level per vertex (Gouraud shading interpolates them); as long as the vertex table.
    PerVertex(&'a [u8]),
    /// One level per polygon (flat faces); as long as the polygon table.
    PerPolygon(&'a [u8]),
}

/// One mesh placed in the world, with its shading.
#[derive(Debug, Clone, Copy)]
pub struct Object<'a> {
    /// The geometry, in the model frame.
    pub mesh: Mesh<'a>,
    /// Model → world.
    pub transform: Affine3,
    /// Luminance source.
    pub intensities: Intensities<'a>,
    /// Flat, exact Gouraud or fast Gouraud.
    pub shade: ShadeMode,
    /// Luminance → palette index.
    pub ramp: LuminanceRamp,
    /// Skip polygons facing away from the eye (closed meshes).
    pub cull_back_faces: bool,
}

impl<'a> Object<'a> {
    /// An object with identity transform, uniform full intensity, exact Gouraud shading, the
    /// grey ramp and back-face culling.
    pub fn new(mesh: Mesh<'a>) -> Self {
        Object {
            mesh,
            transform: Affine3::default(),
            intensities: Intensities::Uniform(255),
            shade: ShadeMode::GouraudExact,
            ramp: LuminanceRamp::GREY,
            cull_back_faces: true,
        }
    }

    /// The intensity of `vertex` in `polygon` (saturating to 0 when a table is too short; the
    /// renderer checks table lengths before drawing).
    #[inline(always)]
    pub(crate) fn intensity(&self, polygon: usize, vertex: u16) -> u8 {
        match self.intensities {
            Intensities::Uniform(l) => l,
            Intensities::PerVertex(t) => t.get(vertex as usize).copied().unwrap_or(0),
            Intensities::PerPolygon(t) => t.get(polygon).copied().unwrap_or(0),
        }
    }
}

/// A camera and the objects it sees.
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    /// The observer.
    pub camera: Camera,
    /// The objects, drawn in order (the depth buffer resolves visibility).
    pub objects: &'a [Object<'a>],
    /// Palette index the frame is cleared to.
    pub background: u8,
}
