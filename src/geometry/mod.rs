//! Geometry: fixed-point vectors and matrices, sine and cosine, meshes, the observer camera.
//!
//! Role in the pipeline: the first stage, producing observer-frame coordinates.
