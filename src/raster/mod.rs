//! The raster stage: from screen-space primitives to pixels.
//!
//! Role in the pipeline: after projection, before the target. Everything here is integer-only.
//!
//! Conventions (owned here):
//! - **Pixels are lattice points**: pixel `(x, y)` is the point with integer coordinates
//!   `(x, y)`; `x` grows right, `y` grows **down**.
//! - **Windows are half-open**: a [`Window`] `{x0, y0, x1, y1}` holds the pixels with
//!   `x0 ≤ x < x1` and `y0 ≤ y < y1`.
//! - **Spans are half-open**: a [`Span`] covers `x0 ≤ x < x1` on row `y`.
//! - **Sub-pixel vertices**: [`SubpixelPoint<S>`] holds coordinates in units of `2^-S` pixel.
//!
//! Modules: [`line`](mod@line) (Bresenham, lattice and sub-pixel end points),
//! [`depth_line`] (3D lines: exact depth along a line, depth-tested), [`circle`] (midpoint circle), `edge_walker` (TIPE's
//! `Parcours`: exact edge stepping by Euclidean division; crate-private), [`polygon`] (TIPE's `Remplissage`
//! for arbitrary polygons), [`triangle`] (the fast path with the same coverage).

pub mod circle;
pub mod convex_window;
pub mod depth_line;
pub mod line;
pub(crate) mod outcode;
pub mod polygon;
pub(crate) mod range;
pub mod triangle;

pub use crate::output::Window;
pub use triangle::edge_walker::{MAX_COORD, MAX_SUBPIXEL_BITS};

/// A run of pixels on one row: `x0 ≤ x < x1` at row `y`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Span {
    /// Row.
    pub y: i32,
    /// First pixel.
    pub x0: i32,
    /// One past the last pixel.
    pub x1: i32,
}

/// A screen point in fixed point with `S` fractional bits: the pixel-unit coordinates are
/// `x / 2^S` and `y / 2^S`. `S = 0` is TIPE's integer lattice; `S = 4` (1/16 pixel) is the default.
///
/// Range: the fill accepts `|x|, |y| ≤ `[`MAX_COORD`] (that is `2^28 - 1` units,
/// ±16.7 M pixels at `S = 4`); see [`polygon`] for why nothing overflows in that range.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SubpixelPoint<const S: u32> {
    /// Column, in units of `2^-S` pixel.
    pub x: i32,
    /// Row (growing downward), in units of `2^-S` pixel.
    pub y: i32,
}

impl<const S: u32> SubpixelPoint<S> {
    /// The point with raw fixed-point coordinates `(x, y)` (units of `2^-S` pixel).
    pub const fn new(x: i32, y: i32) -> Self {
        SubpixelPoint { x, y }
    }

    /// The point at whole pixel `(x, y)` (`x << S`, `y << S`; wraps silently only outside
    /// the documented range).
    pub const fn from_pixel(x: i32, y: i32) -> Self {
        SubpixelPoint {
            x: x << S,
            y: y << S,
        }
    }
}

/// The default sub-pixel precision: 4 fractional bits (1/16 pixel).
pub type ScreenPoint = SubpixelPoint<4>;
