//! Why a frame or an object could not be rendered: [`RenderError`], one variant per stage of
//! the shared pipeline (set-up, vertex and polygon stages, writer, buffers, bands, lines).
//!
//! The hidden-surface methods' own refusals (a store or stack too small, a split budget, a
//! scene outside a method's rule) are not here: they are `visibility`'s vocabulary
//! (`visibility::VisibilityError`), which wraps this one. So `render` names no method and
//! does not import `visibility`.

use super::TransparencyKind;
use crate::clip::frustum::{ClipError, MAX_POLYGON_VERTICES};
use crate::geometry::matrix::MatrixError;
use crate::lighting::LightingError;
use crate::project::ProjectError;
use crate::raster::triangle::DrawError;

/// Why a frame or object could not be rendered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RenderError {
    /// The vertex scratch is shorter than the mesh's vertex table.
    ScratchTooSmall {
        /// Vertices the scratch holds.
        given: usize,
        /// Vertices in the mesh.
        needed: usize,
    },
    /// The polygon table ([`PolygonRows`](super::PolygonRows)) is shorter than the mesh's
    /// polygon count.
    PolygonTableTooSmall {
        /// Entries the table holds.
        given: usize,
        /// Polygons in the mesh.
        needed: usize,
    },
    /// An object's intensity table is shorter than the vertex or polygon table it describes.
    IntensitiesTooShort {
        /// Which table.
        table: IntensityTable,
        /// Entries it holds.
        given: usize,
        /// Entries the mesh needs (its vertices or its polygons).
        needed: usize,
    },
    /// A framebuffer or depth buffer does not hold the camera's viewport: it is narrower, or,
    /// made whole (`new`, not `band`), shorter. Drawing would crop the picture, so nothing is
    /// drawn. A band (`Framebuffer::band`) holds some rows by design and needs only the width.
    TargetSmallerThanViewport {
        /// Which buffer.
        buffer: TargetBuffer,
        /// Its width and height in pixels.
        size: (u16, u16),
        /// The camera's viewport, width and height in pixels.
        viewport: (u16, u16),
    },
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
    /// The lights could not be set up (too many, a zero direction).
    Lighting(LightingError),
    /// The visibility methods that store triangles keep a level per corner; a Phong object
    /// carries normals (draw it with the z-buffer or back-face only).
    PhongUnsupported,
    /// A textured object given to a method that does not draw textures (the visibility
    /// methods that store triangles, compact bands): draw it with the depth buffer, whole or
    /// in bands.
    TextureUnsupported {
        /// The object's index in the scene.
        object: usize,
        /// The method that refused it.
        method: &'static str,
    },
    /// A textured object whose mesh has no texture coordinates, or that asks for Phong
    /// shading (a textured object is lit per vertex or per face, through its shade table).
    TextureNotDrawable {
        /// What is missing or refused.
        reason: &'static str,
    },
    /// An object's transparency that the method cannot draw (`render::transparency`): a
    /// blended object outside the z-buffer's frames, a screen door in
    /// Warnock's subdivision, or either on a core-lit Phong object.
    TransparencyRefused {
        /// The object's index in the scene (`None` when drawn alone, by
        /// [`Renderer::rasterize`](super::Renderer::rasterize)).
        object: Option<usize>,
        /// Its kind of transparency.
        kind: TransparencyKind,
        /// The method or shading that refuses it.
        method: &'static str,
    },
    /// [`render_in_bands`](crate::render::render_in_bands) was asked for bands of
    /// `band_rows` rows, below its minimum of 1.
    BadBandRows {
        /// The rows asked for.
        band_rows: u16,
    },
    /// A part of a banded frame's caller memory holds fewer elements than the frame needs:
    /// the band's pixels or depth samples (`width × band_rows` each) of any banded entry, or
    /// a part of [`render_in_compact_bands`](super::render_in_compact_bands)'s or
    /// [`draw_plan`](crate::visibility::draw_plan)'s memory.
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
    /// A 3D line list's segment names a vertex its object's mesh has not
    /// ([`Renderer::draw_lines`](super::Renderer::draw_lines), a wireframe's edge table).
    SegmentOutOfRange {
        /// The segment's index in the list.
        segment: usize,
        /// The vertex index it names.
        vertex: u16,
        /// Vertices in the mesh.
        vertices: usize,
    },
    /// Appel's quantitative invisibility refused the object (`render::appel`).
    Appel(super::AppelError),
    /// [`Renderer::draw_points`](super::Renderer::draw_points) was asked for squares of
    /// `size` pixels, outside `1..=max`.
    PointSizeOutOfRange {
        /// The side asked for.
        size: u8,
        /// The largest side ([`MAX_POINT_SIZE`](super::MAX_POINT_SIZE)).
        max: u8,
    },
}

/// A part of a banded frame's caller memory ([`RenderError::BandMemoryTooSmall`]).
/// `Pixels` and `Depths` are every banded entry's band buffers; the others are
/// [`render_in_compact_bands`](super::render_in_compact_bands)'s.
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
    /// The prepared vertices of [`render_in_bands`](super::render_in_bands) (a plan's vertex
    /// scratch).
    PreparedVertices,
    /// The polygon rows of [`render_in_bands`](super::render_in_bands) (a plan's polygon table).
    PolygonRows,
    /// The reverse painter's mask of painted pixels (`u32` words,
    /// [`mask_words_needed`](crate::output::mask_words_needed)).
    MaskWords,
}

impl core::fmt::Display for BandPart {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            BandPart::Pixels => "band pixels",
            BandPart::Depths => "band depth samples",
            BandPart::Vertices => "compact vertices",
            BandPart::Levels => "vertex levels",
            BandPart::Polygons => "polygon table entries",
            BandPart::PreparedVertices => "prepared vertices",
            BandPart::PolygonRows => "polygon rows",
            BandPart::MaskWords => "mask words",
        })
    }
}

/// An object's intensity table ([`RenderError::IntensitiesTooShort`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntensityTable {
    /// [`Intensities::PerVertex`](crate::scene::Intensities::PerVertex): a level per vertex.
    PerVertex,
    /// [`Intensities::PerPolygon`](crate::scene::Intensities::PerPolygon): a level per polygon.
    PerPolygon,
    /// The vertex normals of [`Intensities::Lit`](crate::scene::Intensities::Lit) (Gouraud and
    /// Phong objects).
    Normals,
}

impl core::fmt::Display for IntensityTable {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            IntensityTable::PerVertex => "per-vertex intensity table",
            IntensityTable::PerPolygon => "per-polygon intensity table",
            IntensityTable::Normals => "vertex normal table",
        })
    }
}

impl IntensityTable {
    /// What one entry of the table describes, plural.
    fn entries(self) -> &'static str {
        match self {
            IntensityTable::PerPolygon => "polygons",
            _ => "vertices",
        }
    }
}

/// A caller buffer that must hold the camera's viewport
/// ([`RenderError::TargetSmallerThanViewport`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TargetBuffer {
    /// The framebuffer (or the frame size given to a banded entry).
    Frame,
    /// The depth buffer.
    Depth,
}

impl core::fmt::Display for TargetBuffer {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            TargetBuffer::Frame => "framebuffer",
            TargetBuffer::Depth => "depth buffer",
        })
    }
}

impl core::fmt::Display for RenderError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::ScratchTooSmall { given, needed } => write!(
                f,
                "the vertex scratch holds {given} vertices, the mesh has {needed}"
            ),
            RenderError::PolygonTableTooSmall { given, needed } => write!(
                f,
                "the polygon table holds {given} entries, the mesh has {needed} polygons"
            ),
            RenderError::IntensitiesTooShort {
                table,
                given,
                needed,
            } => write!(
                f,
                "the object's {table} holds {given} entries, its mesh has {needed} {}",
                table.entries()
            ),
            RenderError::TargetSmallerThanViewport {
                buffer,
                size,
                viewport,
            } => write!(
                f,
                "the {buffer} is {} × {} pixels, smaller than the camera's {} × {} viewport: \
                 the picture would be cropped (a whole frame needs the viewport's size, a band \
                 its width)",
                size.0, size.1, viewport.0, viewport.1
            ),
            RenderError::PolygonTooLarge => {
                write!(f, "polygon with more than {MAX_POLYGON_VERTICES} vertices")
            }
            RenderError::Transform(e) => write!(f, "transform: {e}"),
            RenderError::Projection(e) => write!(f, "projection: {e}"),
            RenderError::Clip(e) => write!(f, "clipping: {e}"),
            RenderError::Draw(e) => write!(f, "raster: {e}"),
            RenderError::Lighting(e) => write!(f, "lighting: {e}"),
            RenderError::PhongUnsupported => write!(
                f,
                "a Phong object cannot be stored by this visibility method (use the z-buffer)"
            ),
            RenderError::TextureUnsupported { object, method } => write!(
                f,
                "object {object} is textured, which {method} does not draw (draw it with the \
                 depth buffer, whole or in bands)"
            ),
            RenderError::TextureNotDrawable { reason } => {
                write!(f, "a textured object cannot be drawn: {reason}")
            }
            RenderError::TransparencyRefused {
                object,
                kind,
                method,
            } => {
                match object {
                    Some(i) => write!(f, "object {i}")?,
                    None => write!(f, "the object")?,
                }
                write!(f, " is {kind}, which {method} cannot draw ")?;
                f.write_str(match (kind, *method) {
                    (_, "a build without the transparency feature") => {
                        "(enable zscan's transparency feature)"
                    }
                    (_, "Phong shading") => {
                        "(a per-pixel lit object is drawn opaque only: use Gouraud shading)"
                    }
                    (TransparencyKind::ScreenDoor, _) => {
                        "(its front windows would cover the mask's holes: use the scan-line, \
                         the painter or the z-buffer)"
                    }
                    (TransparencyKind::Blended, _) => {
                        "(blended objects are drawn after the opaque ones, far to near, by the \
                         z-buffer's frames only)"
                    }
                })
            }
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
            RenderError::SegmentOutOfRange {
                segment,
                vertex,
                vertices,
            } => write!(
                f,
                "segment {segment} names vertex {vertex}, but the mesh has {vertices} vertices \
                 (indices 0 to {vertices} − 1)"
            ),
            RenderError::Appel(e) => write!(f, "Appel's hidden lines: {e}"),
            RenderError::PointSizeOutOfRange { size, max } => write!(
                f,
                "points of {size} × {size} pixels: the side must be 1 to {max}"
            ),
        }
    }
}

impl From<ClipError> for RenderError {
    fn from(e: ClipError) -> Self {
        RenderError::Clip(e)
    }
}
