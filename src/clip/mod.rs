//! Clipping: Sutherland–Hodgman against planes in 3D.
//!
//! Role in the pipeline: between geometry and projection (the frustum's near and far planes,
//! and a guard band around the view). The 2D lines' Cohen–Sutherland outcodes against the
//! window belong to the raster stage ([`raster::outcode`](crate::raster)).

pub(crate) mod fan;
pub mod frustum;
