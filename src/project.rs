//! Projection: observer frame → sub-pixel fixed-point screen coordinates.
