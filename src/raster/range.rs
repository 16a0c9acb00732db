//! The raster stage's input contract, shared by the polygon and the triangle fill: the
//! coordinate range every fill accepts, its check, and the error a fill returns.
//!
//! Numeric contract: vertices within `|x|, |y| ≤ MAX_COORD = 2^28 − 1` sub-pixel units and
//! `S ≤ MAX_SUBPIXEL_BITS = 16` (see [`edge_walker`](super::edge_walker)); the check itself
//! is one wrapping add and one unsigned compare per coordinate, so it cannot overflow.

use super::triangle::edge_walker::{MAX_COORD, MAX_SUBPIXEL_BITS};
use super::SubpixelPoint;

/// Why a polygon could not be filled. Nothing is drawn when an error is returned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FillError {
    /// More non-horizontal edges than the fill's capacity `MAX_EDGES`.
    TooManyEdges {
        /// The capacity.
        capacity: usize,
    },
    /// A vertex outside `|x|, |y| ≤ MAX_COORD`, or `S > MAX_SUBPIXEL_BITS`.
    CoordinateOutOfRange {
        /// Index of the offending vertex (`usize::MAX` for a bad `S`).
        vertex: usize,
    },
}

impl core::fmt::Display for FillError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FillError::TooManyEdges { capacity } => {
                write!(f, "polygon has more than {capacity} non-horizontal edges")
            }
            FillError::CoordinateOutOfRange { vertex: usize::MAX } => write!(
                f,
                "sub-pixel bits exceed the fill's maximum of {MAX_SUBPIXEL_BITS}"
            ),
            FillError::CoordinateOutOfRange { vertex } => write!(
                f,
                "vertex {vertex} is outside the fill's range of ±{MAX_COORD} sub-pixel units"
            ),
        }
    }
}

/// Checks the documented coordinate range.
#[inline]
pub(crate) fn check_range<const S: u32>(v: &[SubpixelPoint<S>]) -> Result<(), FillError> {
    if S > MAX_SUBPIXEL_BITS {
        return Err(FillError::CoordinateOutOfRange { vertex: usize::MAX });
    }
    // |t| > MAX_COORD exactly when t + MAX_COORD (wrapping) leaves 0..=2·MAX_COORD.
    let out = |t: i32| t.wrapping_add(MAX_COORD) as u32 > 2 * MAX_COORD as u32;
    match v.iter().position(|p| out(p.x) | out(p.y)) {
        Some(i) => Err(FillError::CoordinateOutOfRange { vertex: i }),
        None => Ok(()),
    }
}
