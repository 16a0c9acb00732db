//! Why a frame or an object could not be rendered: [`RenderError`], one variant per stage.

use crate::clip::frustum::{ClipError, MAX_POLYGON_VERTICES};
use crate::geometry::matrix::MatrixError;
use crate::project::ProjectError;
use crate::shade::lighting::LightingError;
use crate::shade::span_writer::DrawError;

/// Why a frame or object could not be rendered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RenderError {
    /// The scratch slice is shorter than the mesh's vertex table.
    ScratchTooSmall {
        /// Vertices in the mesh.
        needed: usize,
    },
    /// An intensity table is shorter than the vertex or polygon table it describes.
    IntensitiesTooShort,
    /// A polygon has more than [`MAX_POLYGON_VERTICES`] vertices.
    PolygonTooLarge,
    /// Composing the object and view transforms overflowed.
    Transform(MatrixError),
    /// The camera cannot be used for projection (sub-pixel bits, ranges).
    Projection(ProjectError),
    /// Clipping failed (capacity, plane range).
    Clip(ClipError),
    /// A triangle was rejected by the raster stage (range or size limits).
    Draw(DrawError),
    /// The band buffers hold fewer than `width × band_rows` elements (or the size is zero).
    BufferTooSmall,
    /// The lights could not be set up (too many, a zero direction).
    Lighting(LightingError),
}

impl core::fmt::Display for RenderError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::ScratchTooSmall { needed } => {
                write!(f, "scratch holds fewer than the mesh's {needed} vertices")
            }
            RenderError::IntensitiesTooShort => {
                write!(f, "intensity table shorter than its mesh table")
            }
            RenderError::PolygonTooLarge => {
                write!(f, "polygon with more than {MAX_POLYGON_VERTICES} vertices")
            }
            RenderError::Transform(e) => write!(f, "transform: {e}"),
            RenderError::Projection(e) => write!(f, "projection: {e}"),
            RenderError::Clip(e) => write!(f, "clipping: {e}"),
            RenderError::Draw(e) => write!(f, "raster: {e}"),
            RenderError::BufferTooSmall => write!(f, "band buffers smaller than width × rows"),
            RenderError::Lighting(e) => write!(f, "lighting: {e}"),
        }
    }
}

impl From<ClipError> for RenderError {
    fn from(e: ClipError) -> Self {
        RenderError::Clip(e)
    }
}
