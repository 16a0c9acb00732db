//! The polygon stage, once per polygon: rejection, culling, clipping, projection and fans,
//! handing each triangle to a [`TriangleConsumer`] (the seam, `consumer.rs`).
//!
//! `PolygonStage::run` visits an object's polygons in one of two ways: every polygon
//! (`run_all`, deciding rejection, band rows and culling for each; triangle meshes have their
//! own loop, which reads each vertex once and, for an object drawn in one pass with culling,
//! tests no per-object flag per triangle), or the polygons a band's table sends
//! (`run_table`, rejection and culling decided once per frame by
//! [`Renderer::polygon_rows`](super::Renderer::polygon_rows)). Outcodes all outside one plane:
//! rejected; all inside: culled on the projected signed area and drawn from the prepared
//! vertices; otherwise culled in the observer frame, clipped by Sutherland–Hodgman against the
//! planes it crosses (course exercise 12) and projected. Polygons are drawn as fans of
//! triangles from corner 0, exact for convex polygons, whose fan triangles tile them under the
//! fill rule.
//!
//! Numeric contract: vertex indices are checked against the prepared vertices (an index out
//! of range makes the polygon unprojected, so it takes the clipper, which treats the vertex as
//! the origin); polygons above [`MAX_POLYGON_VERTICES`] are an error; counts are `u32`.

use heapless::Vec;

use super::consumer::{Corner, TriangleConsumer};
use super::cull::{faces_eye_observer, front_triangle, screen_area};
use super::polygon_rows::triangle_rows;
use super::vertex_stage::UNPROJECTED;
use super::{PolygonRows, PreparedVertex, RenderError, RenderStats, Renderer};
use crate::clip::frustum::{ClipVertex, CLIP_CAPACITY, MAX_POLYGON_VERTICES};
use crate::geometry::mesh::PolygonSizes;
use crate::geometry::vector::Vec3;
use crate::raster::edge_walker::ceil_shift;
use crate::scene::Object;

/// What [`PolygonStage::outcodes`] returns for a polygon wholly outside one plane (no real
/// union of outcodes has every bit set: bit 6 is unused).
const REJECTED: u8 = 0xFF;

/// What the polygon stage does with one polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Path {
    /// Rejected, culled, or outside the band.
    Skip,
    /// Every vertex projected: drawn from the prepared vertices.
    Projected,
    /// Crosses a frustum plane: clipped, projected, drawn.
    Clip,
}

/// The polygon stage of one object: rejection, culling, clipping, projection and fans, for
/// any per-corner attributes and triangle writer.
pub(super) struct PolygonStage<'r, 'o, const S: u32> {
    pub(super) renderer: &'r Renderer<S>,
    pub(super) object: &'r Object<'o>,
    pub(super) prepared: &'r [PreparedVertex<S>],
    /// Rows the buffers hold, `rows.0 .. rows.1`.
    pub(super) rows: (i32, i32),
    /// The buffers hold only part of the viewport's rows.
    pub(super) banded: bool,
    /// The object's band pre-pass ([`Renderer::polygon_rows`]), if any.
    pub(super) table: Option<&'r [PolygonRows]>,
}

impl<const S: u32> PolygonStage<'_, '_, S> {
    /// Runs every polygon: `attrs(polygon index, polygon, corner k)` gives a corner's
    /// attributes, `draw` writes one triangle and returns `(covered, written)`.
    #[inline(always)]
    pub(super) fn run<const N: usize>(
        &self,
        stats: &mut RenderStats,
        attrs: impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        mut draw: impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        // Two loops in separate functions, so that each keeps its drawing paths inline.
        match self.table {
            Some(table) => self.run_table(table, stats, &attrs, &mut draw),
            None => self.run_all(stats, &attrs, &mut draw),
        }
    }

    /// Every polygon, deciding rejection, band and culling for each.
    #[inline(never)]
    fn run_all<const N: usize>(
        &self,
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        // Triangle meshes (the common case) have their own loops, which read each vertex
        // once; other meshes go through `decide` and `follow`.
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            // The frame's common case, a culled object drawn in one pass, has its own loop.
            if !self.banded && self.object.cull_back_faces {
                self.triangles::<true, N>(stats, attrs, draw)?;
            } else {
                self.triangles::<false, N>(stats, attrs, draw)?;
            }
        } else {
            for (pi, poly) in self.object.mesh.polygons().enumerate() {
                stats.polygons_in += 1;
                self.polygon(pi, poly, stats, attrs, draw)?;
            }
        }
        Ok(())
    }

    /// Every triangle of a triangle mesh; `UNBANDED_CULLED` when the buffers hold every row
    /// and the object culls back faces (the flags are then not read per triangle).
    #[inline(always)]
    fn triangles<const UNBANDED_CULLED: bool, const N: usize>(
        &self,
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        // Every triangle is counted in, once (on an error, those up to the failing one). The
        // loop carries no polygon index: `at`, the triangle's first index position, is a
        // shift of the slice pointer, and the index `at / 3` is formed only where it is read
        // (attributes that read it; out of line on the rare paths). A division by 3 in the
        // loop is a multiply on the host and the Cortex-M4 but a library call on the
        // Cortex-M0, and the compiler hoisted it out of the rare paths into every triangle
        // (measured on frame_bunny: Cortex-M0 7.59 M against 7.13 M without it; on the host
        // seven instructions per triangle).
        let indices = self.object.mesh.indices();
        let start = indices.as_ptr() as usize;
        let triangles = indices.chunks_exact(3);
        let n = triangles.len();
        for poly in triangles {
            let at = (poly.as_ptr() as usize - start) / core::mem::size_of::<u16>();
            let r = self.triangle::<UNBANDED_CULLED, N>(at, poly, stats, attrs, draw);
            if r.is_err() {
                return failed_at(stats, at, r);
            }
        }
        stats.polygons_in += n as u32;
        Ok(())
    }

    /// One triangle of a triangle mesh (`poly`, 3 indices from position `at`, polygon
    /// `at / 3`) without a table, not counted in `polygons_in`: three vertices in range and
    /// projected (the common case) go straight to
    /// [`projected_triangle`](Self::projected_triangle), others through
    /// [`decide`](Self::decide).
    #[inline(always)]
    fn triangle<const UNBANDED_CULLED: bool, const N: usize>(
        &self,
        at: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        match self.prepared_triangle(poly) {
            Some(v) if v[0].outcode | v[1].outcode | v[2].outcode == 0 => {
                self.projected_triangle::<UNBANDED_CULLED, N>(at / 3, poly, v, stats, attrs, draw)
            }
            _ => self.polygon_at(at, poly, stats, attrs, draw),
        }
    }

    /// [`polygon`](Self::polygon) for the triangle at index position `at` (polygon `at / 3`,
    /// computed here, out of the triangle loop).
    #[inline(never)]
    fn polygon_at<const N: usize>(
        &self,
        at: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        self.polygon(at / 3, poly, stats, attrs, draw)
    }

    /// One polygon by [`decide`](Self::decide) and [`follow`](Self::follow), not counted in
    /// `polygons_in` (out of line: the triangle loops reach it rarely).
    #[inline(never)]
    fn polygon<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        let path = self.decide(poly, stats)?;
        self.follow(path, pi, poly, stats, attrs, draw)
    }

    /// The polygons the band table sends to this band (rejection and culling were decided
    /// once for all bands).
    #[inline(never)]
    fn run_table<const N: usize>(
        &self,
        table: &[PolygonRows],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        let path = |r: PolygonRows| match r.meets(self.rows) {
            false => Path::Skip,
            true if r.is_clipped() => Path::Clip,
            true => Path::Projected,
        };
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            let indices = self.object.mesh.indices();
            let table = table.get(..indices.len() / 3).unwrap_or(table);
            // The scan finds the entries that `path` may draw with one or two tests for most:
            // rows below the band's end (clamped so that rows up to 65535 pass) and above its
            // start (a top of 65535 is a clipped polygon from row 0); `path` then decides.
            let (b0, b1) = self.rows;
            let (c0, c1) = (
                b0.clamp(-1, u16::MAX as i32 - 1),
                b1.min(u16::MAX as i32 + 1),
            );
            // `bottom > c0` on the packed word: `c0 + 1` is in `0..=65535`.
            let below = ((c0 + 1) as u32) << 16;
            let maybe = |r: &PolygonRows| {
                r.packed >= below && ((r.top() as i32) < c1 || r.top() == u16::MAX)
            };
            let mut one = |pi: usize, r: PolygonRows| {
                let Some(poly) = indices.get(3 * pi..3 * pi + 3) else {
                    return Ok(());
                };
                match path(r) {
                    Path::Skip => Ok(()),
                    Path::Projected => self.table_triangle(pi, poly, stats, attrs, draw),
                    Path::Clip => self.clipped(pi, poly, stats, attrs, draw),
                }
            };
            // Two entries per step: most pairs are passed over with two tests.
            let pairs = table.chunks_exact(2);
            let odd = pairs.remainder();
            for (j, pair) in pairs.enumerate() {
                if let [r0, r1] = *pair {
                    if maybe(&r0) || maybe(&r1) {
                        if maybe(&r0) {
                            one(2 * j, r0)?;
                        }
                        if maybe(&r1) {
                            one(2 * j + 1, r1)?;
                        }
                    }
                }
            }
            if let [r] = *odd {
                if maybe(&r) {
                    one(table.len() - 1, r)?;
                }
            }
        } else {
            for ((pi, poly), r) in self.object.mesh.polygons().enumerate().zip(table) {
                self.follow(path(*r), pi, poly, stats, attrs, draw)?;
            }
        }
        Ok(())
    }

    /// A triangle of a table that found it projected and in the band: drawn from its prepared
    /// vertices as [`projected`](Self::projected) does.
    #[inline(always)]
    fn table_triangle<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        match self.prepared_triangle(poly) {
            Some(v) => self.draw_projected(pi, poly, v, stats, attrs, draw),
            None => self.projected(pi, poly, stats, attrs, draw),
        }
    }

    /// A triangle whose three vertices projected (`v`, the prepared vertices of `tri`): the
    /// band's rows, culling and drawing, as [`decide`](Self::decide) and
    /// [`projected`](Self::projected) do for it.
    #[inline(always)]
    fn projected_triangle<const UNBANDED_CULLED: bool, const N: usize>(
        &self,
        pi: usize,
        tri: &[u16],
        v: [&PreparedVertex<S>; 3],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        if !UNBANDED_CULLED && self.banded && !triangle_rows(v).meets(self.rows) {
            return Ok(());
        }
        let cull = UNBANDED_CULLED || self.object.cull_back_faces;
        if cull && !front_triangle(v[0].screen, v[1].screen, v[2].screen) {
            stats.culled += 1;
            return Ok(());
        }
        self.draw_projected(pi, tri, v, stats, attrs, draw)
    }

    /// Draws a triangle from its three prepared vertices `v` (those of `tri`).
    #[inline(always)]
    fn draw_projected<const N: usize>(
        &self,
        pi: usize,
        tri: &[u16],
        v: [&PreparedVertex<S>; 3],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        let corner = |k: usize| Corner::prepared(v[k], attrs(pi, tri, k, Some(v[k])));
        draw_counted(pi, [corner(0), corner(1), corner(2)], draw, stats)
    }

    /// Draws one polygon by the path decided for it.
    #[inline(always)]
    pub(super) fn follow<const N: usize>(
        &self,
        path: Path,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        match path {
            Path::Skip => Ok(()),
            Path::Projected => self.projected(pi, poly, stats, attrs, draw),
            Path::Clip => self.clipped(pi, poly, stats, attrs, draw),
        }
    }

    /// Without a table: rejection, the band's rows (before any other work for projected
    /// polygons in a band), culling. The caller counts the polygon in `polygons_in`.
    #[inline(always)]
    fn decide(&self, poly: &[u16], stats: &mut RenderStats) -> Result<Path, RenderError> {
        self.verdict(poly, stats, self.banded)
    }

    /// The one decision of whether and how a polygon is drawn: [`Path::Skip`] when it is
    /// rejected (wholly outside one plane, counted) or culled (counted; on the projected
    /// signed area when every vertex projected, in the observer frame otherwise),
    /// [`Path::Projected`] or [`Path::Clip`] otherwise. With `band_first`, a projected polygon
    /// outside the buffers' rows is skipped before the culling test (uncounted as culled).
    /// The triangle loops' fast paths make the same decision from one read of each vertex.
    #[inline(always)]
    pub(super) fn verdict(
        &self,
        poly: &[u16],
        stats: &mut RenderStats,
        band_first: bool,
    ) -> Result<Path, RenderError> {
        let any = self.outcodes(poly, stats)?;
        if any == REJECTED {
            return Ok(Path::Skip);
        }
        let vertex = |k: usize| &self.prepared[poly[k] as usize];
        let cull = self.object.cull_back_faces;
        if any == 0 {
            if band_first && !self.projected_rows(poly).meets(self.rows) {
                return Ok(Path::Skip);
            }
            if cull && screen_area(poly.len(), |k| vertex(k).screen) >= 0 {
                stats.culled += 1;
                return Ok(Path::Skip);
            }
            return Ok(Path::Projected);
        }
        if cull && !faces_eye_observer(poly.len(), |k| vertex(k).view) {
            stats.culled += 1;
            return Ok(Path::Skip);
        }
        Ok(Path::Clip)
    }

    /// The union of the polygon's vertex outcodes, or [`REJECTED`] (counted) when all are
    /// outside one plane.
    #[inline(always)]
    pub(super) fn outcodes(
        &self,
        poly: &[u16],
        stats: &mut RenderStats,
    ) -> Result<u8, RenderError> {
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

    /// The prepared vertices of `poly` when it is a triangle whose indices are all in range.
    #[inline(always)]
    pub(super) fn prepared_triangle(&self, poly: &[u16]) -> Option<[&PreparedVertex<S>; 3]> {
        let p = self.prepared;
        match *poly {
            [i0, i1, i2] => Some([
                p.get(i0 as usize)?,
                p.get(i1 as usize)?,
                p.get(i2 as usize)?,
            ]),
            _ => None,
        }
    }

    /// The rows of a polygon whose vertices all projected: `⌈y_min⌉ .. ⌈y_max⌉`.
    #[inline(always)]
    pub(super) fn projected_rows(&self, poly: &[u16]) -> PolygonRows {
        let (mut y_lo, mut y_hi) = (i32::MAX, i32::MIN);
        for &i in poly {
            let y = self.prepared[i as usize].screen.y;
            (y_lo, y_hi) = (y_lo.min(y), y_hi.max(y));
        }
        PolygonRows::rows(ceil_shift(y_lo, S), ceil_shift(y_hi, S))
    }

    /// Draws a polygon whose vertices all projected, as a fan.
    #[inline(always)]
    pub(super) fn projected<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        let corner = |k: usize| {
            let p = &self.prepared[poly[k] as usize];
            Corner::prepared(p, attrs(pi, poly, k, Some(p)))
        };
        fan(pi, poly.len(), corner, draw, stats)
    }

    /// Clips a polygon crossing the frustum (Sutherland–Hodgman), projects and draws it.
    pub(super) fn clipped<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError> {
        stats.clipped += 1;
        self.each_clipped_piece(pi, poly, attrs, |corners| {
            fan(pi, corners.len(), |k| corners[k], draw, stats)
        })
    }

    /// The rows `⌈y_min⌉ .. ⌈y_max⌉` of a clipped polygon's projection (all its pieces), for
    /// the band table: clipped once per frame, so that a band the polygon does not reach
    /// skips it without clipping (not counted in `clipped`, which counts the drawing runs).
    /// `None` when nothing of it projects.
    pub(super) fn clipped_rows(&self, poly: &[u16]) -> Result<Option<(i32, i32)>, RenderError> {
        let (mut lo, mut hi) = (i32::MAX, i32::MIN);
        self.each_clipped_piece(0, poly, &|_, _, _, _| [], |corners: &[Corner<S, 0>]| {
            for c in corners {
                (lo, hi) = (lo.min(c.screen.y), hi.max(c.screen.y));
            }
            Ok(())
        })?;
        Ok((lo <= hi).then(|| (ceil_shift(lo, S), ceil_shift(hi, S))))
    }

    /// Clips polygon `pi` (`poly`) against the frustum and hands each clipped piece's
    /// projected corners to `piece`. A non-convex polygon whose clip would exceed the capacity
    /// is clipped fan triangle by fan triangle instead (the same region as its unclipped fan),
    /// so it draws.
    fn each_clipped_piece<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        mut piece: impl FnMut(&[Corner<S, N>]) -> Result<(), RenderError>,
    ) -> Result<(), RenderError> {
        let mut input: Vec<ClipVertex<N>, CLIP_CAPACITY> = Vec::new();
        for (k, &i) in poly.iter().enumerate() {
            let p = self.prepared.get(i as usize);
            let view = p.map_or(Vec3::ZERO, |p| p.view);
            // Capacity holds: poly.len() ≤ MAX_POLYGON_VERTICES < CLIP_CAPACITY.
            let _ = input.push(ClipVertex::new(view, attrs(pi, poly, k, p)));
        }
        let frustum = &self.renderer.frustum;
        frustum.clip_fan::<N, CLIP_CAPACITY, RenderError>(&input, |clipped| {
            let mut corners: Vec<Corner<S, N>, CLIP_CAPACITY> = Vec::new();
            for c in clipped.iter() {
                let (screen, depth) = self
                    .renderer
                    .projector
                    .project_point(c.pos)
                    .map_err(RenderError::Projection)?;
                let _ = corners.push(Corner {
                    screen,
                    depth,
                    view: c.pos,
                    attrs: c.attrs,
                });
            }
            piece(&corners)
        })
    }
}

/// The triangle loop's error path: counts in the polygons up to the failing one, the triangle
/// at index position `at`, and returns its error `r`.
#[cold]
#[inline(never)]
fn failed_at(
    stats: &mut RenderStats,
    at: usize,
    r: Result<(), RenderError>,
) -> Result<(), RenderError> {
    stats.polygons_in += (at / 3) as u32 + 1;
    r
}

/// Draws polygon corners `0..n` as a fan of triangles from corner 0 (exact for convex
/// polygons, whose fan triangles tile them under the fill rule), counting into `stats`.
#[inline(always)]
pub(super) fn fan<const S: u32, const N: usize>(
    pi: usize,
    n: usize,
    corner: impl Fn(usize) -> Corner<S, N>,
    draw: &mut impl TriangleConsumer<S, N>,
    stats: &mut RenderStats,
) -> Result<(), RenderError> {
    // The clipper returns no vertices for a polygon that only touches the volume.
    if n < 3 {
        return Ok(());
    }
    let c0 = corner(0);
    for k in 1..n - 1 {
        draw_counted(pi, [c0, corner(k), corner(k + 1)], draw, stats)?;
    }
    Ok(())
}

/// Draws one triangle, counting it into `stats` when it covered or wrote pixels.
#[inline(always)]
pub(super) fn draw_counted<const S: u32, const N: usize>(
    pi: usize,
    tri: [Corner<S, N>; 3],
    draw: &mut impl TriangleConsumer<S, N>,
    stats: &mut RenderStats,
) -> Result<(), RenderError> {
    stats.add_triangle(draw.triangle(pi, tri)?);
    Ok(())
}
