//! Clipping: Cohen–Sutherland outcodes in 2D and Sutherland–Hodgman against planes in 3D.
//!
//! Role in the pipeline: between geometry and projection (3D, near plane) and inside the raster
//! stage (2D lines against the window).

pub(crate) mod fan;
pub mod frustum;
pub mod outcode;
