//! Shading: incremental integer interpolation of per-vertex attributes (depth, luminance).
