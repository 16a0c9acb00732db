//! A polygon's rows: [`PolygonRows`], the 4-byte entry of a band's polygon table, and the rows
//! a projected triangle touches.
//!
//! Numeric contract: band rows are `0..=65535` (a viewport's height is a `u16`); a polygon's
//! rows are clamped to that range, which keeps the overlap test with any band exact.
//! Projected `y` are within `±(2^28 − 1)` sub-pixel units, so `⌈y / 2^S⌉` fits `i32`.

use super::PreparedVertex;
use crate::raster::edge_walker::ceil_shift;

/// A polygon's fate in a frame drawn in bands, decided once by
/// [`Renderer::polygon_rows`](super::Renderer::polygon_rows):
/// the rows `top..bottom` its projection can touch (clamped to `0..=65535`), never drawn
/// (rejected or culled), or needing the clipper in every band it reaches. 4 bytes: one word,
/// `top | bottom << 16`, so that a band's scan tests `bottom` with one comparison.
#[derive(Clone, Copy, PartialEq, Eq, Default)]
pub struct PolygonRows {
    pub(super) packed: u32,
}

impl core::fmt::Debug for PolygonRows {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PolygonRows")
            .field("top", &self.top())
            .field("bottom", &self.bottom())
            .finish()
    }
}

impl PolygonRows {
    /// Rejected or culled: no band draws it.
    pub const NEVER: PolygonRows = PolygonRows::pack(u16::MAX, 0);
    /// Crosses a frustum plane: every band runs the clipper (and the raster's own band limit).
    pub const CLIP: PolygonRows = PolygonRows::pack(u16::MAX, u16::MAX);

    const fn pack(top: u16, bottom: u16) -> PolygonRows {
        PolygonRows {
            packed: top as u32 | (bottom as u32) << 16,
        }
    }

    #[inline(always)]
    pub(super) const fn top(self) -> u16 {
        self.packed as u16
    }

    #[inline(always)]
    const fn bottom(self) -> u16 {
        (self.packed >> 16) as u16
    }

    /// Rows `top..bottom` (half-open, any `i32`), clamped to `0..=65535` (band rows are
    /// within that range, so the overlap test is unchanged). A clamped `(65535, 65535)` is
    /// [`CLIP`](Self::CLIP), which draws the same pixels by the slower path.
    pub fn rows(top: i32, bottom: i32) -> PolygonRows {
        let c = |r: i32| r.clamp(0, u16::MAX as i32) as u16;
        PolygonRows::pack(c(top), c(bottom))
    }

    /// True when the polygon may touch rows `band.0..band.1`.
    #[inline(always)]
    pub(super) fn meets(self, band: (i32, i32)) -> bool {
        (self.bottom() as i32) > band.0 && (self.top() as i32) < band.1
    }
}

/// The rows of a triangle whose vertices all projected: `⌈y_min⌉ .. ⌈y_max⌉`, as
/// `PolygonStage::projected_rows` gives for any polygon.
#[inline(always)]
pub(super) fn triangle_rows<const S: u32>(v: [&PreparedVertex<S>; 3]) -> PolygonRows {
    let (y0, y1, y2) = (v[0].screen.y, v[1].screen.y, v[2].screen.y);
    let (lo, hi) = (y0.min(y1).min(y2), y0.max(y1).max(y2));
    PolygonRows::rows(ceil_shift(lo, S), ceil_shift(hi, S))
}
