//! # zscan
//!
//! A `#![no_std]`, allocation-free 3D rasterizer for microcontrollers with small displays.
//! The core uses only integer and fixed-point arithmetic on every path that runs per frame.
//!
//! A frame goes through these stages, in data-flow order; what you name at each is in
//! [`prelude`]:
//!
//! | stage | what you name | what it does |
//! |---|---|---|
//! | geometry | [`Mesh`](prelude::Mesh), [`Affine3`](prelude::Affine3), [`Camera`](prelude::Camera), [`BinaryAngle`](prelude::BinaryAngle) | fixed-point vectors, transforms, table-free sine/cosine, meshes in your tables, the observer camera |
//! | scene | [`Scene`](prelude::Scene), [`Object`](prelude::Object), [`Light`](prelude::Light), [`Material`](prelude::Material) | what to draw, where, lit how and shaded how ([`ShadeMode`](prelude::ShadeMode)) |
//! | renderer | [`Renderer`](prelude::Renderer), [`render_scene`](prelude::render_scene), [`render_in_bands`](prelude::render_in_bands) | the vertex stage (transform, clipping against the frustum, projection to sub-pixel screen coordinates) and the polygon stage (culling, fans), a whole frame or band by band |
//! | raster | (inside the renderer) | TIPE 2010's exact scanline fill, correctly rounded depth and luminance at every pixel, Phong, shadows |
//! | output | [`Framebuffer`](prelude::Framebuffer), [`DepthBuffer`](prelude::DepthBuffer), [`Lut`](prelude::Lut), [`flush`](prelude::flush) | your 8-bit indexed frame and depth memory, the colour table, any embedded-graphics `DrawTarget` |
//!
//! The public modules hold the rest of each stage's vocabulary (its errors, its less common
//! entries); [`visibility`] holds the hidden-surface methods that can replace the z-buffer
//! and the planner that chooses among them.
//!
//! ## A frame
//!
//! Everything lives in memory the caller owns (statics, the stack); [`prelude`] names what a
//! frame needs and [`Error`] takes every stage's error with `?`. A lit sphere, 48 × 32 pixels:
//!
//! ```
//! use zscan::prelude::*;
//!
//! // The mesh: a UV sphere written into your tables, and its vertex normals.
//! let (nv, ni) = uv_sphere_sizes(16, 8);
//! let (mut vertices, mut indices) = ([Vec3::ZERO; 114], [0u16; 672]);
//! assert_eq!((nv, ni), (vertices.len(), indices.len()));
//! let mesh = uv_sphere(16, 8, Coord::ONE, &mut vertices, &mut indices)?;
//! let mut normals = [Vec3::ZERO; 114];
//! mesh.vertex_normals(&mut normals)?;
//!
//! let mut sphere = Object::new(mesh);
//! sphere.intensities = Intensities::Lit {
//!     material: Material::from_thousandths(100, 700, 300, 20),
//!     normals: &normals,
//! };
//! sphere.shade = ShadeMode::GouraudExact;
//! let lights = [Light::Directional { toward: Vec3::from_int(1, 1, 1), intensity: 255 }];
//! let lens = Lens::new(BinaryAngle::from_degrees(50), Coord::lit("0.5"), Coord::lit("10"));
//! let up = Vec3::from_int(0, 1, 0);
//! let camera = Camera::look_at(Vec3::from_int(0, 0, 4), Vec3::ZERO, up, lens, Viewport::new(48, 32))?;
//! let objects = [sphere];
//! let scene = Scene { camera, ambient: 20, lights: &lights, objects: &objects, background: 0 };
//!
//! // The frame: 8-bit palette indices, 16-bit depth, vertex scratch.
//! let (mut pixels, mut depths) = ([0u8; 48 * 32], [0u16; 48 * 32]);
//! let mut frame = Framebuffer::new(&mut pixels, 48, 32)?;
//! let mut depth = DepthBuffer::new(&mut depths, 48, 32)?;
//! let mut scratch = [PreparedVertex::default(); 114];
//! let mut stats = RenderStats::default();
//! let renderer = Renderer::for_scene(&scene)?;
//! render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats)?;
//!
//! // The sphere covers the middle of the picture, lit brighter toward the light (up right).
//! assert_eq!(frame.pixel(0, 0), Some(0));
//! let (centre, lit, shaded) = (frame.pixel(24, 16), frame.pixel(27, 13), frame.pixel(19, 21));
//! assert!(centre > Some(0) && lit > shaded, "{centre:?} {lit:?} {shaded:?}");
//! # Ok::<(), zscan::Error>(())
//! ```
//!
//! Then [`flush`](prelude::flush) sends the frame through a [`Lut`](prelude::Lut) to any
//! embedded-graphics `DrawTarget`; [`render_in_bands`](prelude::render_in_bands) draws the same
//! picture through band-sized buffers.
//!
//! ## Conventions (stated once, owned by the modules named)
//! - **Pixels are lattice points.** Pixel `(x, y)` is the point with integer coordinates `(x, y)`;
//!   `x` grows to the right, `y` grows **downward** (screen convention). See [`raster`].
//! - **Fill rule.** A pixel is covered when it lies inside a polygon; points exactly on a left
//!   edge are in, on a right edge out; each edge covers the rows `y_low ≤ y < y_high`
//!   (the top-left rule). See [`raster::polygon`].
//! - **Sub-pixel vertices.** Screen vertices are fixed point with `S` fractional bits
//!   ([`raster::SubpixelPoint`]); `S = 0` is TIPE's integer case, `S = 4` the default.
//! - **Errors, not panics.** Bad sizes, over-capacity polygons and out-of-range inputs return
//!   a `Result` with a descriptive error; nothing in the core panics or writes out of bounds.
#![no_std]
#![deny(missing_docs)]
#![deny(missing_debug_implementations)]
// `unsafe` is denied everywhere but in one function, the buffer clears' aligned split
// (`fill_aligned`), which carries its proof and its measured reason.
#![deny(unsafe_code)]
#![deny(rustdoc::broken_intra_doc_links)]

pub(crate) mod arith;
pub(crate) mod clip;
mod error;
pub mod geometry;
pub mod lighting;
pub mod output;
pub mod prelude;
pub(crate) mod project;
pub mod raster;
pub mod render;
pub mod scene;
pub mod shadow;
pub(crate) mod stats;
#[cfg(test)]
mod test_rng;
pub mod texture;
pub mod visibility;

pub use error::Error;

/// Internal stages, for the host harness (`zscan-host`) and the benchmark cases
/// (`benches/cases.rs`) only: not part of the API, not documented, no stability promise.
///
/// Why it exists: the harness tests stages against independent references it owns (the
/// edge walkers and the triangle fill against an exact rational fill, the clipper and the
/// projector against `f64`, the Phong writer and the lighting functions against `f64`
/// lighting), and the benchmarks measure the bare fill with each edge walker. Those references
/// need `std` and floats, which the `no_std` core does not carry into its own unit tests, and
/// the benchmark cases are compiled both into the host harness and into the Cortex-M firmware
/// (an example crate, which sees only `pub` items). Everything a user names lives at the crate
/// root, in [`prelude`] and in the public modules; the modules these come from are
/// `pub(crate)`.
#[doc(hidden)]
pub mod internals {
    pub use crate::clip::frustum::{ClipVertex, ClipVolume, Frustum, NEAR};
    pub use crate::project::Projector;
    pub use crate::raster::triangle::edge_walker::{
        DivisionWalker, Edge, EdgeWalker, IncrementalWalker,
    };
    pub use crate::raster::triangle::{draw_triangle_phong, PhongContext, PhongVertex};
}
