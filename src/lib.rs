//! # zscan
//!
//! A `#![no_std]`, allocation-free 3D rasterizer for microcontrollers with small displays.
//! The core uses only integer and fixed-point arithmetic on every path that runs per frame.
//!
//! The modules follow the pipeline in data-flow order:
//!
//! | stage | module | what it does |
//! |---|---|---|
//! | geometry | [`geometry`] | fixed-point vectors, matrices, sine/cosine, meshes, the observer camera |
//! | clipping | [`clip`] | Cohen–Sutherland outcodes (2D), Sutherland–Hodgman against planes (3D) |
//! | projection | [`project`] | observer frame → sub-pixel screen coordinates |
//! | raster | [`raster`] | Bresenham lines, midpoint circles, the exact scanline polygon fill (TIPE 2010) |
//! | shading | [`shade`] | incremental integer attribute interpolation (depth, luminance) |
//! | target | [`target`] | the caller's 8-bit indexed framebuffer, depth buffer, the colour LUT, `DrawTarget` output |
//!
//! [`scene`] describes what to draw (meshes in static slices, transforms, intensities) and
//! [`render`] runs the stages above in order for a whole frame or a band of it.
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
#![deny(unsafe_code)]
#![deny(rustdoc::broken_intra_doc_links)]

pub(crate) mod arith;
pub mod clip;
pub mod geometry;
pub mod project;
pub mod raster;
pub mod render;
pub mod scene;
pub mod shade;
pub mod target;
#[cfg(test)]
mod test_rng;
