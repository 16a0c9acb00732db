//! Whether and how the polygon stage draws a polygon, decided in one place for every vertex
//! source (prepared or compact vertices) and every frame (one pass, bands, compact bands'
//! table): rejection on the vertices' outcodes, the band's rows, and back-face culling, on the
//! projected polygon's signed area (exact integers) when every vertex projected, in the
//! observer frame (exact `i128`) otherwise. [`PolygonStage::decide`] decides any polygon;
//! `decide_triangle` is the same decision for a triangle whose three vertices projected, from
//! one read of each. The one back-face test of a projected triangle is [`front_triangle`].
//!
//! Numeric contract: projected coordinates are within `±MAX_COORD = ±(2^28 − 1)` (the
//! projector rejects others), so screen differences fit `i32` and each product is exact in
//! `i64`; where every difference is within `±(2^15 − 1)` ([`narrow_span`], compact vertices
//! spanning less than `2^15` sub-pixel units), the triangle's products are exact in `i32`
//! and it is culled so; observer-frame coordinates are I16F16 (`|c| < 2^31` raw), edge vectors below `2^32`,
//! cross products below `2^65`, the final dot below `2^102`: exact in `i128`.

use super::polygon_stage::{triangle_rows, Path, PolygonStage, VertexSource};
use super::vertex_stage::UNPROJECTED;
use super::{PolygonRows, RenderError, RenderStats};
use crate::clip::frustum::ClipVolume;
use crate::clip::frustum::MAX_POLYGON_VERTICES;
use crate::geometry::vector::Vec3;
use crate::raster::triangle::twice_area;
use crate::raster::SubpixelPoint;

/// What [`PolygonStage::outcodes`] returns for a polygon wholly outside one plane (no real
/// union of outcodes has every bit set: bit 6 is unused).
const REJECTED: u8 = 0xFF;

impl<const S: u32, V: ?Sized + VertexSource<S>, T: ?Sized> PolygonStage<'_, '_, S, V, T> {
    /// The one decision of whether and how a polygon is drawn: [`Path::Skip`] when it is
    /// rejected (wholly outside one plane, counted), outside the buffers' rows (projected
    /// polygons in a band, tested before culling and not counted as culled) or culled
    /// (counted; on the projected signed area when every vertex projected, in the observer
    /// frame otherwise), [`Path::Projected`] or [`Path::Clip`] otherwise (a source that does
    /// not clip skips a polygon that would need it, uncounted). The caller counts the polygon
    /// in `polygons_in`.
    #[inline(always)]
    pub(super) fn decide(
        &self,
        poly: &[u16],
        stats: &mut RenderStats,
    ) -> Result<Path<'_, V::Vertex>, RenderError> {
        let any = self.outcodes(poly, stats)?;
        if any == REJECTED {
            return Ok(Path::Skip);
        }
        let vertex = |k: usize| self.prepared.vertex(poly[k]);
        let cull = self.object.cull_back_faces;
        if any == 0 {
            if self.banded && !self.projected_rows(poly).meets(self.rows) {
                return Ok(Path::Skip);
            }
            // Every index is in range here (an index out of range is unprojected).
            let screen = |k: usize| vertex(k).map_or(SubpixelPoint::new(0, 0), V::screen);
            if cull && screen_area(poly.len(), screen) >= 0 {
                stats.culled += 1;
                return Ok(Path::Skip);
            }
            return Ok(Path::Projected);
        }
        if !V::CLIPS {
            return Ok(Path::Skip);
        }
        let parallel = self.renderer.frustum.screen_affine();
        let view = |k: usize| vertex(k).map_or(Vec3::ZERO, V::view);
        if cull && !faces_eye_observer(poly.len(), view, parallel) {
            stats.culled += 1;
            return Ok(Path::Skip);
        }
        Ok(Path::Clip)
    }

    /// [`decide`](Self::decide) for a triangle whose three vertices `v` are in range and
    /// inside every plane: [`Path::Triangle`] or [`Path::Skip`]. `UNBANDED_CULLED` when the
    /// buffers hold every row and the object culls back faces (the flags are then not read).
    /// Culled in `i32` when `NARROW` (the source is narrow, [`front_triangle`]).
    #[inline(always)]
    pub(super) fn decide_triangle<'p, const UNBANDED_CULLED: bool, const NARROW: bool>(
        &self,
        v: [&'p V::Vertex; 3],
        stats: &mut RenderStats,
    ) -> Path<'p, V::Vertex> {
        if !UNBANDED_CULLED && self.banded {
            let (top, bottom) = triangle_rows::<S, V>(v);
            if !PolygonRows::rows(top, bottom).meets(self.rows) {
                return Path::Skip;
            }
        }
        let cull = UNBANDED_CULLED || self.object.cull_back_faces;
        let [a, b, c] = v.map(V::screen);
        if cull && !front_triangle(a, b, c, NARROW) {
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
            let c = self.prepared.vertex(i).map_or(UNPROJECTED, V::outcode);
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

/// True when a projected triangle is a front face, [`screen_area`]`(3, …) < 0`.
///
/// With `narrow` false, computed as `bx·cy + by·(−cx)` (one multiply and one
/// multiply-accumulate): projected coordinates are within `±MAX_COORD`, so the differences and
/// their negations are below `2^29` in magnitude and each product below `2^58`, the sum exact
/// in `i64`, equal to `screen_area`'s. With `narrow` (the caller's promise, [`narrow_span`]:
/// every coordinate difference within `±(2^15 − 1)`), computed in `i32` as `bx·cy − by·cx`:
/// each product is below `2^30` in magnitude and their difference below `2^31`, exact, with
/// the same sign (two 32-bit multiplies instead of 64-bit ones, which a Cortex-M0 calls a
/// library routine for).
#[inline(always)]
pub(super) fn front_triangle<const S: u32>(
    a: SubpixelPoint<S>,
    b: SubpixelPoint<S>,
    c: SubpixelPoint<S>,
    narrow: bool,
) -> bool {
    if narrow {
        let (bx, by) = (b.x.wrapping_sub(a.x), b.y.wrapping_sub(a.y));
        let (cx, cy) = (c.x.wrapping_sub(a.x), c.y.wrapping_sub(a.y));
        bx.wrapping_mul(cy).wrapping_sub(by.wrapping_mul(cx)) < 0
    } else {
        twice_area(a, b, c) < 0
    }
}

/// True when coordinates bounded by `x_lo ..= x_hi` and `y_lo ..= y_hi` span less than `2^15`
/// on each axis, so that every difference of two of them is within `±(2^15 − 1)` and
/// [`front_triangle`] may cull in `i32` (an empty set, `lo > hi`, is narrow).
#[inline(always)]
pub(super) fn narrow_span((x_lo, x_hi): (i32, i32), (y_lo, y_hi): (i32, i32)) -> bool {
    let span = |lo: i32, hi: i32| (hi as i64 - lo as i64) < 1 << 15;
    span(x_lo, x_hi) && span(y_lo, y_hi)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The `i32` cull of narrow spans agrees with the `i64` one at the range's extremes and
    /// on random triangles; a span of `2^15` is not narrow.
    #[test]
    fn narrow_cull_agrees_with_wide_cull() {
        let mut rng = crate::test_rng::XorShift(0x5EED_0FC0_4AC7_u64);
        let p = |x: i32, y: i32| SubpixelPoint::<4>::new(x, y);
        let bounds = |t: &[SubpixelPoint<4>]| {
            let xs = t.iter().map(|q| q.x);
            let ys = t.iter().map(|q| q.y);
            (
                (xs.clone().min().unwrap(), xs.max().unwrap()),
                (ys.clone().min().unwrap(), ys.max().unwrap()),
            )
        };
        let mut agree = 0;
        for n in 0..20_000 {
            let (base, span) = if n % 2 == 0 {
                (-16384, 32767)
            } else {
                (-40, 80)
            };
            let mut c = || base + (rng.next_u64() % (span as u64 + 1)) as i32;
            let mut t = [p(c(), c()), p(c(), c()), p(c(), c())];
            if n < 8 {
                let (lo, hi) = (-16384, 16383);
                t = [
                    p(lo, lo),
                    p(hi, [lo, hi][n % 2]),
                    p([lo, hi][n / 2 % 2], hi),
                ];
                if n >= 4 {
                    t.swap(1, 2);
                }
            }
            let (x, y) = bounds(&t);
            assert!(narrow_span(x, y));
            let narrow = front_triangle(t[0], t[1], t[2], true);
            let exact = front_triangle(t[0], t[1], t[2], false);
            assert_eq!(narrow, exact, "{t:?}");
            assert_eq!(exact, screen_area(3, |k| t[k]) < 0, "{t:?}");
            agree += exact as u32;
        }
        assert!((5_000..15_000).contains(&agree), "{agree}");
        assert!(!narrow_span((-16384, 16384), (0, 0)));
        assert!(narrow_span((-16384, 16383), (0, 0)));
        assert!(!narrow_span((0, 0), (i32::MIN, i32::MAX)));
        assert!(narrow_span((1, 0), (1, 0)));
    }
}
