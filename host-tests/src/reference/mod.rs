//! Reference implementations, independent of the production code, used by the tests.

pub mod bresenham;
pub mod compare;
pub mod exact_fill;
pub mod exact_texture;
pub mod float_lighting;
pub mod float_render;
