//! Whether and how the polygon stage draws a polygon, decided in one place: rejection on the
//! vertices' outcodes, the band's rows, and back-face culling, on the projected polygon's signed
//! area (exact integers) when every vertex projected, in the observer frame (exact `i128`)
//! otherwise. [`PolygonStage::decide`] decides any polygon; `decide_triangle` is the same
//! decision for a triangle whose three vertices projected, from one read of each.
//!
//! Numeric contract: projected coordinates are within `±MAX_COORD = ±(2^28 − 1)` (the
//! projector rejects others), so screen differences fit `i32` and each product is exact in
//! `i64`; observer-frame coordinates are I16F16 (`|c| < 2^31` raw), edge vectors below `2^32`,
//! cross products below `2^65`, the final dot below `2^102`: exact in `i128`.

use super::polygon_rows::triangle_rows;
use super::polygon_stage::{Path, PolygonStage};
use super::vertex_stage::UNPROJECTED;
use super::{PreparedVertex, RenderError, RenderStats};
use crate::clip::frustum::ClipVolume;
use crate::clip::frustum::MAX_POLYGON_VERTICES;
use crate::geometry::vector::Vec3;
use crate::raster::triangle::twice_area;
use crate::raster::SubpixelPoint;

/// What [`PolygonStage::outcodes`] returns for a polygon wholly outside one plane (no real
/// union of outcodes has every bit set: bit 6 is unused).
const REJECTED: u8 = 0xFF;

impl<const S: u32> PolygonStage<'_, '_, S> {
    /// The one decision of whether and how a polygon is drawn: [`Path::Skip`] when it is
    /// rejected (wholly outside one plane, counted), outside the buffers' rows (projected
    /// polygons in a band, tested before culling and not counted as culled) or culled
    /// (counted; on the projected signed area when every vertex projected, in the observer
    /// frame otherwise), [`Path::Projected`] or [`Path::Clip`] otherwise. The caller counts the
    /// polygon in `polygons_in`.
    #[inline(always)]
    pub(super) fn decide(
        &self,
        poly: &[u16],
        stats: &mut RenderStats,
    ) -> Result<Path<'_, S>, RenderError> {
        let any = self.outcodes(poly, stats)?;
        if any == REJECTED {
            return Ok(Path::Skip);
        }
        let vertex = |k: usize| &self.prepared[poly[k] as usize];
        let cull = self.object.cull_back_faces;
        if any == 0 {
            if self.banded && !self.projected_rows(poly).meets(self.rows) {
                return Ok(Path::Skip);
            }
            if cull && screen_area(poly.len(), |k| vertex(k).screen) >= 0 {
                stats.culled += 1;
                return Ok(Path::Skip);
            }
            return Ok(Path::Projected);
        }
        let parallel = self.renderer.frustum.screen_affine();
        if cull && !faces_eye_observer(poly.len(), |k| vertex(k).view, parallel) {
            stats.culled += 1;
            return Ok(Path::Skip);
        }
        Ok(Path::Clip)
    }

    /// [`decide`](Self::decide) for a triangle whose three vertices `v` are in range and
    /// inside every plane: [`Path::Triangle`] or [`Path::Skip`]. `UNBANDED_CULLED` when the
    /// buffers hold every row and the object culls back faces (the flags are then not read).
    #[inline(always)]
    pub(super) fn decide_triangle<'p, const UNBANDED_CULLED: bool>(
        &self,
        v: [&'p PreparedVertex<S>; 3],
        stats: &mut RenderStats,
    ) -> Path<'p, S> {
        if !UNBANDED_CULLED && self.banded && !triangle_rows(v).meets(self.rows) {
            return Path::Skip;
        }
        let cull = UNBANDED_CULLED || self.object.cull_back_faces;
        if cull && !front_triangle(v[0].screen, v[1].screen, v[2].screen) {
            stats.culled += 1;
            return Path::Skip;
        }
        Path::Triangle(v)
    }

    /// The union of the polygon's vertex outcodes, or [`REJECTED`] (counted) when all are
    /// outside one plane.
    #[inline(always)]
    fn outcodes(&self, poly: &[u16], stats: &mut RenderStats) -> Result<u8, RenderError> {
        if poly.len() > MAX_POLYGON_VERTICES {
            return Err(RenderError::PolygonTooLarge);
        }
        let (mut any, mut all) = (0u8, 0xFFu8);
        for &i in poly {
            let c = self
                .prepared
                .get(i as usize)
                .map_or(UNPROJECTED, |p| p.outcode);
            any |= c;
            all &= c;
        }
        if all & !UNPROJECTED != 0 {
            stats.rejected += 1;
            return Ok(REJECTED);
        }
        Ok(any)
    }
}

/// Twice the signed area of a projected polygon (fan sum). Projected coordinates are within
/// `±MAX_COORD = ±(2^28 − 1)` (the projector rejects others), so coordinate differences fit
/// `i32` (`< 2^29`) and each product `i32 × i32` is exact in `i64` (one `smull` on a
/// Cortex-M), each triangle's term below `2^59`. The sum wraps modulo `2^64`, so it is exact
/// whenever the true value fits `i64`: always for simple polygons, whose twice-area is at most
/// twice their bounding box's, `2·(2^29)² = 2^59`. Front faces (counter-clockwise seen from
/// outside, with `y` up) are clockwise on a `y`-down screen: negative area.
#[inline(always)]
pub(crate) fn screen_area<const S: u32>(n: usize, p: impl Fn(usize) -> SubpixelPoint<S>) -> i64 {
    let o = p(0);
    let mut sum = 0i64;
    for k in 1..n - 1 {
        let (b, c) = (p(k), p(k + 1));
        sum = sum.wrapping_add(twice_area(o, b, c));
    }
    sum
}

/// True when a projected triangle is a front face, [`screen_area`]`(3, …) < 0`, computed as
/// `bx·cy + by·(−cx)` (one multiply and one multiply-accumulate). Projected coordinates are
/// within `±MAX_COORD`, so the differences and their negations are below `2^29` in magnitude
/// and each product below `2^58`: the sum is exact in `i64`, equal to `screen_area`'s.
#[inline(always)]
pub(super) fn front_triangle<const S: u32>(
    a: SubpixelPoint<S>,
    b: SubpixelPoint<S>,
    c: SubpixelPoint<S>,
) -> bool {
    twice_area(a, b, c) < 0
}

/// Back-face test in the observer frame (eye at the origin): the face is front-facing when
/// `(0 − P0)·N > 0` with `N` the outward normal. The observer frame is left-handed (x right,
/// y up, z forward), so the winding cross product there is `−N`: front ⇔ `P0·Σ cross > 0`.
/// Under a parallel projection (`parallel`) the direction toward the eye is `−z` everywhere:
/// front ⇔ `−N_z > 0` ⇔ `(Σ cross)_z > 0`.
pub(super) fn faces_eye_observer(n: usize, p: impl Fn(usize) -> Vec3, parallel: bool) -> bool {
    let w = |v: Vec3| v.bits().map(|c| c as i128);
    let o = w(p(0));
    let mut nrm = [0i128; 3];
    for k in 1..n - 1 {
        let (a, b) = (w(p(k)), w(p(k + 1)));
        let e1 = [a[0] - o[0], a[1] - o[1], a[2] - o[2]];
        let e2 = [b[0] - o[0], b[1] - o[1], b[2] - o[2]];
        nrm[0] += e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] += e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] += e1[0] * e2[1] - e1[1] * e2[0];
    }
    if parallel {
        return nrm[2] > 0;
    }
    // |o| < 2^31, |nrm| < 2^66·n: the dot stays below 2^102.
    o[0] * nrm[0] + o[1] * nrm[1] + o[2] * nrm[2] > 0
}
