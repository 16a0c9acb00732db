//! The frame: geometry → clipping → projection → raster → shading → target, for whole scenes.
//!
//! Role in the pipeline: the glue that runs every stage in order. A [`Renderer`] holds what is
//! fixed for a frame (projector, frustum, view transform, lights); a [`SceneRenderer`] is one
//! built from a scene's camera and lights, holding the scene, and is what the scene entries
//! draw (one source of camera and lights, `renderer.rs`). For each
//! [`Object`](crate::scene::Object):
//!
//! 1. **Vertex stage** (`vertex_stage.rs`, [`Renderer::prepare`]), once per vertex: model →
//!    observer frame, outcode, projection, and the vertex's level, into caller scratch (one
//!    [`PreparedVertex`] per mesh vertex).
//! 2. **Polygon stage** (`polygon_stage.rs`, [`Renderer::rasterize`]), once per polygon, one
//!    loop over the mesh or the band table: rejection, the band's rows and culling decided in
//!    `cull.rs`, Sutherland–Hodgman clipping, projection and fans of triangles (`clip::fan`,
//!    shared with the shadow map's pass 1). `object.rs` picks what each corner carries (a
//!    level, or a normal for Phong) and which consumer takes the triangles.
//! 3. **The seam** (`consumer.rs`): each culled, clipped, projected triangle goes to a
//!    `TriangleConsumer`. Today's consumers draw through the depth buffer at once
//!    (`LevelWriter` into `draw_triangle_on`,
//!    `PhongWriter` into [`draw_triangle_phong`](crate::raster::triangle::draw_triangle_phong));
//!    other visibility methods plug in here.
//!
//! `frame.rs` holds the entries ([`Renderer::draw_object`], [`render_scene`]), `bands.rs` the
//! banded frames ([`render_in_bands`], [`render_in_compact_bands`]) with their polygon tables
//! (`polygon_rows.rs`, `compact.rs`), `double_bands.rs` the double-buffered output of
//! `render_in_bands` ([`DoubleBands`]: band `n + 1` drawn while band `n` is sent, through a
//! [`BandSink`] a DMA driver implements), `stats.rs` the counts, `error.rs` the error.
//!
//! ## Bands
//! Frame and depth buffer may be a band of rows
//! ([`Framebuffer::band`](crate::output::Framebuffer::band)): the raster stage writes only the
//! rows the buffers hold, so drawing a picture band by band, flushing each band to the display
//! before the next, gives the same pixels as one pass (tested). [`render_in_bands`] runs the
//! vertex stage once per frame when its scratch holds every object's vertices, and with a
//! polygon table ([`PolygonRows`], [`Renderer::polygon_rows`]) decides rejection, culling and
//! each polygon's rows once, so that each band visits only the polygons that reach it.
//! [`render_in_compact_bands`] does the same in the least memory, when no vertex needs the
//! clipper: 8 bytes per vertex ([`CompactVertex`]) and 1 per polygon ([`PolygonTop`]) besides
//! the band, `width·band_rows·(1 + depth bytes) + 8·V + L + P` bytes in all
//! ([`CompactSizes`]; `L`: one level byte per vertex of lit Gouraud objects). The standard
//! bunny at 320 × 240 in bands of 10 rows takes 27,986 bytes, drawn with its stack in 32 KB of
//! RAM on a Cortex-M0 (`scripts/footprint.sh`).
//!
//! ## Numeric contract
//! Mesh coordinates `|c| ≤ 1024`
//! ([`MAX_MESH_COORD_BITS`](crate::geometry::mesh::MAX_MESH_COORD_BITS)); observer-frame
//! positions are I16F16 and saturate (see `vertex_stage.rs`). Projected vertices are within
//! the frustum's guard band (at most 4 screen extents from the principal point, capped by the
//! raster's `±(2^28 − 1)` sub-pixel range), and every triangle of that range is drawn with the
//! exact planes, whatever its size: those too large for the 32-bit stepping plane (`2·area ≥
//! 2^30` sub-pixel units², a quad filling a 512×512 view and up) take the wide plane
//! (`raster::triangle::wide_plane::WidePlane`), out of line. So any viewport the
//! [`Viewport`](crate::geometry::camera::Viewport) holds (sides up to 65 535 pixels) and any
//! principal point render. Intensities are `0..=255`. Culling in the observer frame uses `i128` (see `cull.rs`).

mod appel;
mod bands;
pub(crate) mod compact;
pub(crate) mod consumer;
mod cull;
pub(crate) use cull::screen_area;
mod double_bands;
mod error;
mod frame;
mod lines;
mod object;
mod polygon_rows;
mod polygon_stage;
mod renderer;
mod transparency;
mod vertex_stage;

pub use crate::clip::frustum::{ClipError, MAX_POLYGON_VERTICES};
pub use crate::project::ProjectError;
pub use crate::stats::{RenderStats, StatsSink, StatsWithoutWritten};
pub use appel::{AppelCrossing, AppelEdge, AppelError, AppelScratch, AppelSegment, AppelTable};
pub(crate) use bands::{band_buffers, band_height};
pub use bands::{render_in_bands, render_in_compact_bands, BandScratch, CompactBandScratch};
pub use compact::{CompactSizes, CompactVertex, PolygonTop};
pub use double_bands::{BandSink, DisplaySink, DoubleBandError, DoubleBands};
pub use error::{BandPart, IntensityTable, RenderError, TargetBuffer};
pub use frame::render_scene;
pub use lines::{LineStyle, Wireframe, DEFAULT_DEPTH_OFFSET, MAX_POINT_SIZE};
pub use polygon_rows::PolygonRows;
pub use renderer::{Renderer, SceneRenderer};
pub use transparency::TransparencyKind;
pub(crate) use transparency::{check as check_transparency, draw_order, Draws};
pub use vertex_stage::PreparedVertex;
