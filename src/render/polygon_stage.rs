//! The polygon stage, once per polygon: rejection, culling, clipping, projection and fans,
//! handing each triangle to a [`TriangleConsumer`] (the seam, `consumer.rs`).
//!
//! One loop visits an object's polygons, in one of two ways: every polygon
//! ([`PolygonStage::each`], deciding rejection, band rows and culling for each in `cull.rs`),
//! or the polygons a band's table sends ([`PolygonStage::in_table`], rejection and culling
//! decided once per frame by [`Renderer::polygon_rows`](super::Renderer::polygon_rows)). What
//! happens to each decided polygon is a [`Visitor`]: [`Draw`] fans it into triangles for a
//! consumer; the band pre-pass (`bands.rs`) records its rows instead, through the same loop.
//! Triangle meshes (the common case) have their own loop, which reads each vertex once and,
//! for an object drawn in one pass with culling, tests no per-object flag per triangle.
//! Outcodes all outside one plane: rejected; all inside: culled on the projected signed area
//! and drawn from the prepared vertices; otherwise culled in the observer frame, clipped by
//! Sutherland–Hodgman against the planes it crosses (course exercise 12) and projected.
//! Polygons are drawn as fans of triangles from corner 0, exact for convex polygons, whose fan
//! triangles tile them under the fill rule.
//!
//! Numeric contract: vertex indices are checked against the prepared vertices (an index out
//! of range makes the polygon unprojected, so it takes the clipper, which treats the vertex as
//! the origin); polygons above
//! [`MAX_POLYGON_VERTICES`](crate::clip::frustum::MAX_POLYGON_VERTICES) are an error; counts
//! are `u32`.

use heapless::Vec;

use super::consumer::{Corner, TriangleConsumer};
use super::{PolygonRows, PreparedVertex, RenderError, RenderStats, Renderer};
use crate::clip::fan::clip_project_fan;
use crate::clip::frustum::{ClipVertex, CLIP_CAPACITY};
use crate::geometry::mesh::PolygonSizes;
use crate::geometry::vector::Vec3;
use crate::raster::triangle::edge_walker::ceil_shift;
use crate::scene::Object;

/// What the polygon stage does with one polygon (decided in `cull.rs`).
#[derive(Debug, Clone, Copy)]
pub(super) enum Path<'p, const S: u32> {
    /// Rejected, culled, or outside the band.
    Skip,
    /// Every vertex projected: drawn from the prepared vertices.
    Projected,
    /// A triangle whose three vertices projected: drawn from them (each read once).
    Triangle([&'p PreparedVertex<S>; 3]),
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

/// What the stage's loop does with each polygon once its path is decided. The loop of
/// [`PolygonStage::each`] calls it exactly once per polygon, in mesh order.
pub(super) trait Visitor<const S: u32> {
    /// Polygon `pi` (`poly`, its indices) on the path decided for it.
    fn polygon(
        &mut self,
        stage: &PolygonStage<'_, '_, S>,
        pi: usize,
        poly: &[u16],
        path: Path<'_, S>,
        stats: &mut RenderStats,
    ) -> Result<(), RenderError>;
}

/// The drawing visitor: `attrs(polygon index, polygon, corner k, prepared vertex)` gives a
/// corner's attributes, `draw` takes each triangle of the polygon's fan.
pub(super) struct Draw<'a, A, C, const N: usize> {
    pub(super) attrs: &'a A,
    pub(super) draw: &'a mut C,
}

impl<A, C, const S: u32, const N: usize> Visitor<S> for Draw<'_, A, C, N>
where
    A: Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
    C: TriangleConsumer<S, N>,
{
    #[inline(always)]
    fn polygon(
        &mut self,
        stage: &PolygonStage<'_, '_, S>,
        pi: usize,
        poly: &[u16],
        path: Path<'_, S>,
        stats: &mut RenderStats,
    ) -> Result<(), RenderError> {
        let attrs = self.attrs;
        match path {
            Path::Skip => Ok(()),
            Path::Projected => {
                let corner = |k: usize| {
                    let p = &stage.prepared[poly[k] as usize];
                    Corner::prepared(p, attrs(pi, poly, k, Some(p)))
                };
                fan(pi, poly.len(), corner, self.draw, stats)
            }
            Path::Triangle(v) => {
                let corner = |k: usize| Corner::prepared(v[k], attrs(pi, poly, k, Some(v[k])));
                draw_counted(pi, [corner(0), corner(1), corner(2)], self.draw, stats)
            }
            Path::Clip => stage.clipped(pi, poly, stats, attrs, self.draw),
        }
    }
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
        let mut visit = Draw {
            attrs: &attrs,
            draw: &mut draw,
        };
        match self.table {
            Some(table) => self.in_table(table, stats, &mut visit),
            None => self.each(stats, &mut visit),
        }
    }

    /// Every polygon, counted in `polygons_in`, deciding rejection, band and culling for each
    /// (`cull.rs`) and handing it to `visit` (out of line, so that each visitor's loop keeps
    /// its paths inline).
    #[inline(never)]
    pub(super) fn each(
        &self,
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S>,
    ) -> Result<(), RenderError> {
        // Triangle meshes (the common case) have their own loops, which read each vertex
        // once; other meshes go through `polygon`.
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            // The frame's common case, a culled object drawn in one pass, has its own loop.
            if !self.banded && self.object.cull_back_faces {
                self.triangles::<true>(stats, visit)
            } else {
                self.triangles::<false>(stats, visit)
            }
        } else {
            for (pi, poly) in self.object.mesh.polygons().enumerate() {
                stats.polygons_in += 1;
                self.polygon(pi, poly, stats, visit)?;
            }
            Ok(())
        }
    }

    /// Every triangle of a triangle mesh; `UNBANDED_CULLED` when the buffers hold every row
    /// and the object culls back faces (the flags are then not read per triangle).
    #[inline(always)]
    fn triangles<const UNBANDED_CULLED: bool>(
        &self,
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S>,
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
            let r = self.triangle::<UNBANDED_CULLED>(at, poly, stats, visit);
            if r.is_err() {
                return failed_at(stats, at, r);
            }
        }
        stats.polygons_in += n as u32;
        Ok(())
    }

    /// One triangle of a triangle mesh (`poly`, 3 indices from position `at`, polygon
    /// `at / 3`), not counted in `polygons_in`: three vertices in range and projected (the
    /// common case) are decided from one read of each
    /// ([`decide_triangle`](Self::decide_triangle)), others by [`decide`](Self::decide).
    #[inline(always)]
    fn triangle<const UNBANDED_CULLED: bool>(
        &self,
        at: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S>,
    ) -> Result<(), RenderError> {
        match self.prepared_triangle(poly) {
            Some(v) if v[0].outcode | v[1].outcode | v[2].outcode == 0 => {
                let path = self.decide_triangle::<UNBANDED_CULLED>(v, stats);
                visit.polygon(self, at / 3, poly, path, stats)
            }
            _ => self.polygon_at(at, poly, stats, visit),
        }
    }

    /// [`polygon`](Self::polygon) for the triangle at index position `at` (polygon `at / 3`,
    /// computed here, out of the triangle loop).
    #[inline(never)]
    fn polygon_at(
        &self,
        at: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S>,
    ) -> Result<(), RenderError> {
        self.polygon(at / 3, poly, stats, visit)
    }

    /// One polygon, decided by [`decide`](Self::decide) and handed to `visit`, not counted in
    /// `polygons_in` (out of line: the triangle loops reach it rarely).
    #[inline(never)]
    fn polygon(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S>,
    ) -> Result<(), RenderError> {
        let path = self.decide(poly, stats)?;
        visit.polygon(self, pi, poly, path, stats)
    }

    /// The polygons the band table sends to this band (rejection and culling were decided
    /// once for all bands).
    #[inline(never)]
    pub(super) fn in_table(
        &self,
        table: &[PolygonRows],
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S>,
    ) -> Result<(), RenderError> {
        let path = |r: PolygonRows| -> Path<'_, S> {
            match r.meets(self.rows) {
                false => Path::Skip,
                true if r.is_clipped() => Path::Clip,
                true => Path::Projected,
            }
        };
        let PolygonSizes::Uniform(3) = self.object.mesh.sizes() else {
            for ((pi, poly), r) in self.object.mesh.polygons().enumerate().zip(table) {
                visit.polygon(self, pi, poly, path(*r), stats)?;
            }
            return Ok(());
        };
        let indices = self.object.mesh.indices();
        let table = table.get(..indices.len() / 3).unwrap_or(table);
        // The scan finds the entries that `path` may draw with one or two tests for most: rows
        // below the band's end (clamped so that rows up to 65535 pass) and above its start (or
        // a clipped polygon from row 0, `PolygonRows::CLIPPED_FROM_ROW_0`); `path` then decides
        // exactly.
        let (b0, b1) = self.rows;
        let (c0, c1) = (
            b0.clamp(-1, u16::MAX as i32 - 1),
            b1.min(u16::MAX as i32 + 1),
        );
        // `bottom > c0` on the packed word: `c0 + 1` is in `0..=65535`.
        let below = ((c0 + 1) as u32) << 16;
        let maybe = |r: &PolygonRows| {
            r.packed >= below
                && ((r.top() as i32) < c1 || r.top() == PolygonRows::CLIPPED_FROM_ROW_0)
        };
        let mut one = |pi: usize, r: PolygonRows| {
            let Some(poly) = indices.get(3 * pi..3 * pi + 3) else {
                return Ok(());
            };
            let path = match path(r) {
                Path::Projected => self
                    .prepared_triangle(poly)
                    .map_or(Path::Projected, Path::Triangle),
                p => p,
            };
            visit.polygon(self, pi, poly, path, stats)
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
        Ok(())
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

    /// Clips a polygon crossing the frustum (Sutherland–Hodgman), projects and draws it.
    pub(super) fn clipped<C: TriangleConsumer<S, N>, const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut C,
    ) -> Result<(), RenderError> {
        stats.clipped += 1;
        self.each_clipped_triangle(pi, poly, attrs, C::SPACE_LINEAR, |tri| {
            draw_counted(pi, tri, draw, stats)
        })
    }

    /// The rows `⌈y_min⌉ .. ⌈y_max⌉` of a clipped polygon's projection, for the band table:
    /// clipped once per frame, so that a band the polygon does not reach skips it without
    /// clipping (not counted in `clipped`, which counts the drawing runs). `None` when nothing
    /// of it projects.
    pub(super) fn clipped_rows(&self, poly: &[u16]) -> Result<Option<(i32, i32)>, RenderError> {
        let (mut lo, mut hi) = (i32::MAX, i32::MIN);
        self.each_clipped_triangle(0, poly, &|_, _, _, _| [], 0, |tri: [Corner<S, 0>; 3]| {
            for c in tri {
                (lo, hi) = (lo.min(c.screen.y), hi.max(c.screen.y));
            }
            Ok(())
        })?;
        Ok((lo <= hi).then(|| (ceil_shift(lo, S), ceil_shift(hi, S))))
    }

    /// Clips polygon `pi` (`poly`) against the frustum, projects it and hands each triangle
    /// of its fan to `triangle`.
    fn each_clipped_triangle<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        space_linear: u8,
        triangle: impl FnMut([Corner<S, N>; 3]) -> Result<(), RenderError>,
    ) -> Result<(), RenderError> {
        let mut input: Vec<ClipVertex<N>, CLIP_CAPACITY> = Vec::new();
        for (k, &i) in poly.iter().enumerate() {
            let p = self.prepared.get(i as usize);
            let view = p.map_or(Vec3::ZERO, |p| p.view);
            // Capacity holds: poly.len() ≤ MAX_POLYGON_VERTICES < CLIP_CAPACITY.
            let _ = input.push(ClipVertex::new(view, attrs(pi, poly, k, p)));
        }
        // A non-convex polygon whose clip would exceed the capacity is clipped fan triangle by
        // fan triangle instead (the same region as its unclipped fan), so it draws.
        let project = |c: &ClipVertex<N>| {
            let (screen, depth) = self
                .renderer
                .projector
                .project_point(c.pos)
                .map_err(RenderError::Projection)?;
            Ok(Corner {
                screen,
                depth,
                view: c.pos,
                attrs: c.attrs,
            })
        };
        let frustum = &self.renderer.frustum;
        clip_project_fan(frustum, &input, true, space_linear, project, triangle)
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

/// Draws polygon corners `0..n` as a fan of triangles from corner 0 ([`clip::fan`]),
/// counting into `stats`.
///
/// [`clip::fan`]: crate::clip::fan::fan
#[inline(always)]
pub(super) fn fan<const S: u32, const N: usize>(
    pi: usize,
    n: usize,
    corner: impl Fn(usize) -> Corner<S, N>,
    draw: &mut impl TriangleConsumer<S, N>,
    stats: &mut RenderStats,
) -> Result<(), RenderError> {
    crate::clip::fan::fan(n, corner, |tri| draw_counted(pi, tri, draw, stats))
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
