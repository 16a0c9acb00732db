//! Shading: per-pixel values from per-vertex ones, and the span writers that use them.
//!
//! Role in the pipeline: between the triangle fill (which gives spans) and the target (which
//! stores indices and depths). `attributes` interpolates any number of integer attributes
//! exactly and incrementally (depth and Gouraud luminance share it); [`span_writer`] holds the
//! per-pixel loops: depth test, luminance → palette index, writes.

pub(crate) mod attributes;
pub(crate) mod dither;
pub mod lighting;
pub(crate) mod phong;
pub mod shadow;
mod span;
pub mod span_writer;
mod tiny_triangle;
