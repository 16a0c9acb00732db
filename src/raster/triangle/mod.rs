//! How a triangle is drawn: one folder, in the order the work runs.
//!
//! Role in the pipeline: after projection (sub-pixel screen vertices with their depths and
//! luminances or Phong's attributes), before the output buffers. Everything a triangle
//! crosses from its three projected vertices to the pixels it stores lives here:
//!
//! | step | module | what it does |
//! |---|---|---|
//! | set-up | `setup` | sorted vertices, twice-area and orientation, bounding box, the three edges, once per triangle |
//! | edges | `edge_walker` | TIPE's `Parcours`: the edge walkers side by side (incremental, by division), the raster's range |
//! | fill | [`fill`] | the rows and spans of a set-up triangle (same coverage as [`polygon`](super::polygon)) |
//! | decision | `draw` | the one dispatch: which span kind, whether the tiny writer, which plane ([`draw_triangle`]) |
//! | planes | `interpolants`, `small_plane`, `plane`, `wide_plane` | exact incremental interpolation: small (32-bit), general (64-bit), wide (`i128`) |
//! | tiny writer | `tiny` | small triangles' set-up, edges and both planes in one place |
//! | spans | `spans` | one triangle's spans: the plane of its kind, the loop over the fill's spans |
//! | span kinds | `kinds` | what a span writes: flat, exact or fast Gouraud, depth only, Phong |
//! | mask | `mask_span` | the reverse painter's per-pixel test: a span's bits of the mask of painted pixels, in place of the depth test |
//! | textured | `textured` | the textured span kind: texels exact (ratio of two exact planes), subdivided or affine |
//! | span loop | `span` | the per-pixel loop: depth test, palette index, stores; luminance → index ([`LuminanceRamp`], the `Quantizer`s) |
//! | dither | `dither` | the 4×4 ordered-dither quantizer |
//! | transparency | [`transparency`] | the screen door's mask and the blend, as quantizers of the span loop |
//! | slices | `slices` | the frame's and depth buffer's rows handed to each span as slices |
//!
//! Numeric contract (each module states its own): vertices within the raster's range
//! (`|x|, |y| ≤ MAX_COORD = 2^28 − 1` sub-pixel units, `S ≤ 16`), checked once per
//! triangle by [`draw_triangle`] or once per vertex by the projector; depths are the
//! projection's 32-bit normalised depth (smaller nearer), luminance `0..=255`; every pixel
//! receives the correctly rounded interpolated value (quotient and remainder steps).
//!
//! Conventions: pixels are lattice points, `y` down; the fill rule is TIPE 2010's (left
//! edges in, right edges out, rows `y_low ≤ y < y_high`), owned by [`raster`](super).

mod dither;
mod draw;
pub(crate) mod edge_walker;
pub mod fill;
mod interpolants;
mod kinds;
mod mask_span;
pub(crate) mod plane;
pub(crate) mod setup;
mod slices;
mod small_plane;
mod span;
mod spans;
mod textured;
mod tiny;
pub mod transparency;
mod wide_plane;

pub use draw::{
    draw_triangle, draw_triangle_phong, draw_triangle_textured, DrawError, PhongContext,
    PhongVertex, ShadeMode,
};
pub use fill::{fill_triangle, fill_triangle_with};
pub use setup::twice_area;
pub use span::LuminanceRamp;

pub(crate) use dither::Bayer4;
#[cfg(test)]
pub(crate) use draw::draw_tiny_or_planar;
pub(crate) use draw::{draw_depth_only, draw_in_range, draw_phong_on, draw_textured_on};
pub(crate) use slices::{drawable_window, DepthTarget, RasterTarget, SpanTarget};
pub(crate) use span::{CountWritten, SkipWritten, WrittenCount};
pub(crate) use textured::TexCorner;
#[cfg(feature = "transparency")]
pub(crate) use transparency::{Blend, ScreenDoor};
pub use transparency::{Opacity, OpacityError};
