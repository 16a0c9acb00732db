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
    /// A visibility method that stores triangles before drawing them (painter, scan-line,
    /// Warnock) was given more front triangles than its caller memory holds.
    TriangleStoreFull {
        /// Triangles the store holds.
        capacity: usize,
    },
    /// The painter's overlap resolution needed more splits (Newell's test 6) than its budget.
    SplitBudgetExhausted {
        /// Splits the caller's budget allows.
        budget: usize,
    },
    /// A piece of the painter's would need more than [`MAX_CUTS`](crate::visibility::MAX_CUTS)
    /// cuts.
    PieceCutTooOften {
        /// Cuts a piece may carry.
        cuts: usize,
    },
    /// The painter's tests could not order a group of triangles that no split separates
    /// (its tests judge a piece by its whole triangle, so some cycles of pieces stay): the
    /// frame is refused rather than drawn in a wrong order.
    PainterCycle,
    /// Warnock's subdivision needed more windows on its stack than the caller's memory holds.
    SubdivisionStackFull {
        /// Windows the stack holds.
        capacity: usize,
    },
    /// Warnock's subdivision needed more candidate entries (the lists of the windows being
    /// subdivided, one after the other) than the caller's memory holds.
    SubdivisionCandidatesFull {
        /// Entries the candidate stack holds.
        capacity: usize,
    },
    /// The scan-line method's active table holds fewer triangles than reach one band.
    ActiveTableFull {
        /// Triangles the active table holds.
        capacity: usize,
    },
    /// The visibility methods that store triangles keep a level per corner; a Phong object
    /// carries normals (draw it with the z-buffer or back-face only).
    PhongUnsupported,
    /// A scene with more objects than a stored triangle can name (256).
    TooManyObjects,
    /// A drawing order names an object the scene does not have.
    NoSuchObject {
        /// The index named.
        index: u16,
        /// Objects in the scene.
        objects: usize,
    },
    /// [`render_in_bands`](crate::render::render_in_bands) was asked for bands of
    /// `band_rows` rows, below its minimum of 1.
    BadBandRows {
        /// The rows asked for.
        band_rows: u16,
    },
    /// A part of a compact banded frame's caller memory
    /// ([`render_in_compact_bands`](super::render_in_compact_bands)) holds fewer elements
    /// than the scene needs.
    BandMemoryTooSmall {
        /// Which part.
        part: BandPart,
        /// Elements it holds.
        given: usize,
        /// Elements the scene needs.
        needed: usize,
    },
    /// A vertex has no compact form (it lies outside the frustum's guard band, so a polygon
    /// needs the clipper, or its sub-pixel position leaves 16 bits): compact bands cannot draw
    /// the frame; `render_in_bands` with its full scratch can.
    NotCompact {
        /// The object's index in the scene.
        object: usize,
        /// The vertex's index in its mesh.
        vertex: usize,
    },
}

/// A part of a compact banded frame's caller memory ([`RenderError::BandMemoryTooSmall`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BandPart {
    /// The band's pixels (`width × band_rows`).
    Pixels,
    /// The band's depth samples (`width × band_rows`).
    Depths,
    /// The compact vertices (every object's vertices).
    Vertices,
    /// The level bytes (the vertices of lit Gouraud objects).
    Levels,
    /// The polygon table (every object's polygons).
    Polygons,
}

impl core::fmt::Display for BandPart {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            BandPart::Pixels => "band pixels",
            BandPart::Depths => "band depth samples",
            BandPart::Vertices => "compact vertices",
            BandPart::Levels => "vertex levels",
            BandPart::Polygons => "polygon table entries",
        })
    }
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
            RenderError::TriangleStoreFull { capacity } => write!(
                f,
                "more front triangles than the triangle store's {capacity}"
            ),
            RenderError::SplitBudgetExhausted { budget } => write!(
                f,
                "the painter's overlaps need more than its budget of {budget} splits"
            ),
            RenderError::PieceCutTooOften { cuts } => {
                write!(f, "a painter's piece would need more than {cuts} cuts")
            }
            RenderError::PainterCycle => write!(
                f,
                "the painter's tests cannot order a cycle of pieces (use the scan-line or z-buffer)"
            ),
            RenderError::SubdivisionStackFull { capacity } => write!(
                f,
                "Warnock's subdivision needs more than its stack of {capacity} windows"
            ),
            RenderError::SubdivisionCandidatesFull { capacity } => write!(
                f,
                "Warnock's subdivision needs more than its {capacity} candidate entries"
            ),
            RenderError::ActiveTableFull { capacity } => write!(
                f,
                "more triangles reach one band than the active table's {capacity}"
            ),
            RenderError::PhongUnsupported => write!(
                f,
                "a Phong object cannot be stored by this visibility method (use the z-buffer)"
            ),
            RenderError::TooManyObjects => write!(f, "more than 256 objects in the scene"),
            RenderError::NoSuchObject { index, objects } => write!(
                f,
                "the drawing order names object index {index}, but the scene has {objects} \
                 objects (indices 0 to {objects} − 1)"
            ),
            RenderError::BadBandRows { band_rows } => {
                write!(f, "bands of {band_rows} rows: a band needs at least 1 row")
            }
            RenderError::BandMemoryTooSmall {
                part,
                given,
                needed,
            } => write!(f, "{given} {part} given, the frame needs {needed}"),
            RenderError::NotCompact { object, vertex } => write!(
                f,
                "vertex {vertex} of object {object} needs clipping or leaves the 16-bit screen \
                 range: compact bands need every vertex inside the guard band \
                 (use render_in_bands)"
            ),
        }
    }
}

impl From<ClipError> for RenderError {
    fn from(e: ClipError) -> Self {
        RenderError::Clip(e)
    }
}
