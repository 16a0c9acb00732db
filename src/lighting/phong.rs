//! Phong's per-pixel lighting (course chapter 4, §2.3): the lighting of one pixel from its
//! interpolated normal and observer-frame position, and how a corner's normal and position
//! are stored as interpolated attributes.
//!
//! Role in the pipeline: the lighting half of Phong shading. The triangle writer
//! ([`raster::triangle`](crate::raster::triangle)) interpolates six attributes (the three
//! normal components, the three position components) beside the depth, exactly, and at every
//! pixel that passes the depth test asks [`intensity`] for the lit intensity, which
//! renormalises the interpolated normal with the integer square root (the course's warning:
//! interpolated normals are not unit vectors) and evaluates [`Illumination`].
//!
//! ## Numeric contract
//! - Normals are normalised to Q15 at the vertices and stored offset,
//!   `n + 32768 ∈ [0, 65536]`; positions are raw I16F16 observer coordinates stored offset by
//!   `2^31` (`u32`) ([`corner_attributes`]). Interpolated values are convex combinations of
//!   the vertex values, so they stay in those ranges, and each pixel receives the correctly
//!   rounded affine interpolant.
//! - Interpolation is affine in screen space (as the course's scanline algorithm); the
//!   position therefore drifts from the true surface point on receding triangles by the
//!   perspective error, which only moves `L` and `V` (not the normal) by a fraction of the
//!   triangle.
//! - Lighting as [`lighting`](super): integer only; the intensity is `0..=255`.

use super::{unit_q15, Illumination, Material, ONE};
use crate::geometry::vector::Vec3;

/// Offset of stored positions (`i32` raw → `u32`).
const POS_OFFSET: u32 = 1 << 31;

/// The six stored attributes of a corner: its offset unit normal (Q15 + 32768; a zero normal
/// stores 0, lit with ambient only) and its offset observer-frame position (raw I16F16
/// `^ 2^31`).
pub(crate) fn corner_attributes(position: Vec3, normal: Vec3) -> [u32; 6] {
    let b = normal.bits();
    let n = unit_q15([b[0] as i64, b[1] as i64, b[2] as i64]).unwrap_or([0; 3]);
    let p = position.bits();
    [
        (n[0] + ONE) as u32,
        (n[1] + ONE) as u32,
        (n[2] + ONE) as u32,
        p[0] as u32 ^ POS_OFFSET,
        p[1] as u32 ^ POS_OFFSET,
        p[2] as u32 ^ POS_OFFSET,
    ]
}

/// The intensity `0..=255` of a pixel whose interpolated attributes (as
/// [`corner_attributes`] stores them) are `a`: the normal renormalised and lit by
/// `illumination` with `material` at the pixel's observer-frame position.
#[inline]
pub(crate) fn intensity(illumination: &Illumination, material: &Material, a: [u32; 6]) -> u8 {
    let n = [0, 1, 2].map(|k| a[k] as i64 - ONE as i64);
    let p = [3, 4, 5].map(|k| (a[k] ^ POS_OFFSET) as i32);
    illumination.intensity(material, Vec3::from_bits(p[0], p[1], p[2]), n)
}
