//! The polygon stage, once per polygon: rejection, culling, clipping, projection and fans,
//! handing each triangle to a [`TriangleConsumer`] (the seam, `consumer.rs`).
//!
//! Role in the pipeline: the one loop over an object's polygons, whatever holds its vertices
//! and whatever band table its frame keeps. It reads vertex `i` through a [`VertexSource`]:
//! the vertex stage's [`PreparedVertex`]es (any view: outcodes, observer-frame positions for
//! the clipper, the level beside each vertex) or the 8-byte compact vertices of compact bands
//! (`compact.rs`: every vertex projected, nothing to clip, levels in their own bytes). It
//! visits the polygons in one of two ways: every polygon ([`PolygonStage::each`], deciding
//! rejection, band rows and culling for each in `cull.rs`), or the polygons a band's table
//! sends ([`PolygonStage::in_table`], rejection and culling decided once per frame). A band
//! table is a [`BandTable`]: the 4-byte [`PolygonRows`] of `render_in_bands` or the one-byte
//! entries of compact bands, each with its own scan (one memory/time trade each: 4 bytes per
//! polygon tell the exact rows and the clipper; one byte tells a top row group, and a band
//! reads the rows of the polygons that entry alone does not decide from their vertices).
//! What happens to each decided polygon is a [`Visitor`]: [`Draw`] fans it into triangles for
//! a consumer; the band pre-passes (`bands.rs`, `compact.rs`) record its rows instead,
//! through the same loop. Triangle meshes (the common case) have their own loop, which reads
//! each vertex once and, for an object drawn in one pass with culling, tests no per-object
//! flag per triangle. Outcodes all outside one plane: rejected; all inside: culled on the
//! projected signed area and drawn from the vertices; otherwise culled in the observer frame,
//! clipped by Sutherland–Hodgman against the planes it crosses (course exercise 12) and
//! projected. Polygons are drawn as fans of triangles from corner 0, exact for convex
//! polygons, whose fan triangles tile them under the fill rule.
//!
//! Numeric contract: vertex indices are checked against the vertex source (an index out of
//! range makes the polygon unprojected, so it takes the clipper, which treats the vertex as
//! the origin; a source without a clipper skips it); polygons above
//! [`MAX_POLYGON_VERTICES`](crate::clip::frustum::MAX_POLYGON_VERTICES) are an error; counts
//! are `u32`. Screen positions are the projector's (within `±(2^28 − 1)` sub-pixel units;
//! compact vertices within `±32767`), depths its 32-bit normalised depths, passed on unchanged.

use heapless::Vec;

use super::consumer::{Corner, TriangleConsumer};
use super::polygon_rows::exact_rows;
use super::{PolygonRows, PreparedVertex, RenderError, RenderStats, Renderer};
use crate::clip::fan::clip_project_fan;
use crate::clip::frustum::{ClipVertex, CLIP_CAPACITY};
use crate::geometry::mesh::PolygonSizes;
use crate::geometry::vector::Vec3;
use crate::raster::SubpixelPoint;
use crate::scene::Object;

/// Where the polygon stage reads an object's vertices: vertex `i`'s screen position, depth,
/// outcode, observer-frame position and level.
pub(super) trait VertexSource<const S: u32> {
    /// One vertex as the source stores it.
    type Vertex;
    /// False when every vertex projected (compact vertices): the source has no outcodes and
    /// no observer-frame positions, so nothing is clipped (a polygon that would need the
    /// clipper is skipped).
    const CLIPS: bool;
    /// Vertex `i`, or `None` out of range.
    fn vertex(&self, i: u16) -> Option<&Self::Vertex>;
    /// Sub-pixel screen position (valid when the outcode is 0).
    fn screen(v: &Self::Vertex) -> SubpixelPoint<S>;
    /// 32-bit normalised depth (valid when the outcode is 0).
    fn depth(v: &Self::Vertex) -> u32;
    /// Frustum outcode, 0 when projected.
    fn outcode(v: &Self::Vertex) -> u8;
    /// Observer-frame position (read by the clipper and Phong only).
    fn view(v: &Self::Vertex) -> Vec3;
    /// The level `0..=255` the vertex stage computed (lit Gouraud) or the scene gave (per
    /// vertex) for vertex `i`, `v`.
    fn level(&self, i: u16, v: &Self::Vertex) -> u8;
    /// True when every coordinate difference of two vertices is within `±(2^15 − 1)`: the
    /// cull's products then fit `i32` (`cull.rs`).
    fn narrow(&self) -> bool;

    /// The corner of vertex `v` with attributes `attrs`.
    #[inline(always)]
    fn corner<const N: usize>(v: &Self::Vertex, attrs: [i32; N]) -> Corner<S, N> {
        Corner {
            screen: Self::screen(v),
            depth: Self::depth(v),
            view: Self::view(v),
            attrs,
        }
    }
}

/// The vertex stage's output for any view.
impl<const S: u32> VertexSource<S> for [PreparedVertex<S>] {
    type Vertex = PreparedVertex<S>;
    const CLIPS: bool = true;
    #[inline(always)]
    fn vertex(&self, i: u16) -> Option<&PreparedVertex<S>> {
        self.get(i as usize)
    }
    #[inline(always)]
    fn screen(v: &PreparedVertex<S>) -> SubpixelPoint<S> {
        v.screen
    }
    #[inline(always)]
    fn depth(v: &PreparedVertex<S>) -> u32 {
        v.depth
    }
    #[inline(always)]
    fn outcode(v: &PreparedVertex<S>) -> u8 {
        v.outcode
    }
    #[inline(always)]
    fn view(v: &PreparedVertex<S>) -> Vec3 {
        v.view
    }
    #[inline(always)]
    fn level(&self, _: u16, v: &PreparedVertex<S>) -> u8 {
        v.level
    }
    /// Not measured per object: the `i64` cull (one `smull` and one `smlal` on a Cortex-M4)
    /// costs less than a pass over the vertices would.
    #[inline(always)]
    fn narrow(&self) -> bool {
        false
    }
}

/// How a band table says a band reaches a polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Reach {
    /// Its rows meet the band; drawn from its vertices.
    Meets,
    /// Its rows may meet the band: the band reads them from its vertices.
    Maybe,
    /// Drawn through the clipper (rows of its clipped projection meet the band).
    Clip,
}

/// A band table: each polygon's fate decided once per frame ([`PolygonRows`], or compact
/// bands' one-byte entries), read by every band.
pub(super) trait BandTable {
    /// How the band of rows `band.0 .. band.1` reaches polygon `pi`, `None` when it does not.
    fn reach(&self, pi: usize, band: (i32, i32)) -> Option<Reach>;
    /// For a triangle mesh of `n` triangles: calls `one(pi, reach)` for every triangle the
    /// band may reach, in mesh order ([`reach`](Self::reach) decides, with the table's own
    /// fast scan).
    fn scan(
        &self,
        n: usize,
        band: (i32, i32),
        one: impl FnMut(usize, Reach) -> Result<(), RenderError>,
    ) -> Result<(), RenderError>;
}

/// What the polygon stage does with one polygon (decided in `cull.rs`); `X` is the vertex
/// source's vertex.
#[derive(Debug)]
pub(super) enum Path<'p, X> {
    /// Rejected, culled, or outside the band.
    Skip,
    /// Every vertex projected: drawn from the source's vertices.
    Projected,
    /// A triangle whose three vertices projected: drawn from them (each read once).
    Triangle([&'p X; 3]),
    /// Crosses a frustum plane: clipped, projected, drawn.
    Clip,
}

/// The polygon stage of one object: rejection, culling, clipping, projection and fans, for
/// any per-corner attributes and triangle writer, its vertices read from `V` and its band
/// table (if any) a `T`.
pub(super) struct PolygonStage<
    'r,
    'o,
    const S: u32,
    V: ?Sized = [PreparedVertex<S>],
    T: ?Sized = [PolygonRows],
> {
    pub(super) renderer: &'r Renderer<S>,
    pub(super) object: &'r Object<'o>,
    pub(super) prepared: &'r V,
    /// Rows the buffers hold, `rows.0 .. rows.1`.
    pub(super) rows: (i32, i32),
    /// The buffers hold only part of the viewport's rows.
    pub(super) banded: bool,
    /// The object's band table (decided once per frame), if any.
    pub(super) table: Option<&'r T>,
}

/// What the stage's loop does with each polygon once its path is decided. The loop of
/// [`PolygonStage::each`] calls it exactly once per polygon, in mesh order.
pub(super) trait Visitor<const S: u32, V: ?Sized + VertexSource<S>, T: ?Sized> {
    /// Polygon `pi` (`poly`, its indices) on the path decided for it.
    fn polygon(
        &mut self,
        stage: &PolygonStage<'_, '_, S, V, T>,
        pi: usize,
        poly: &[u16],
        path: Path<'_, V::Vertex>,
        stats: &mut RenderStats,
    ) -> Result<(), RenderError>;
}

/// The drawing visitor: `attrs(polygon index, polygon, corner k, vertex)` gives a corner's
/// attributes, `draw` takes each triangle of the polygon's fan.
pub(super) struct Draw<'a, A, C, const N: usize> {
    pub(super) attrs: &'a A,
    pub(super) draw: &'a mut C,
}

impl<A, C, V, T, const S: u32, const N: usize> Visitor<S, V, T> for Draw<'_, A, C, N>
where
    V: ?Sized + VertexSource<S>,
    T: ?Sized,
    A: Fn(usize, &[u16], usize, Option<&V::Vertex>) -> [i32; N],
    C: TriangleConsumer<S, N>,
{
    #[inline(always)]
    fn polygon(
        &mut self,
        stage: &PolygonStage<'_, '_, S, V, T>,
        pi: usize,
        poly: &[u16],
        path: Path<'_, V::Vertex>,
        stats: &mut RenderStats,
    ) -> Result<(), RenderError> {
        let attrs = self.attrs;
        match path {
            Path::Skip => Ok(()),
            Path::Projected => {
                // Every index is in range (an index out of range is unprojected), so the
                // zero corner is never taken.
                let corner = |k: usize| match stage.prepared.vertex(poly[k]) {
                    Some(p) => V::corner(p, attrs(pi, poly, k, Some(p))),
                    None => Corner {
                        screen: SubpixelPoint::new(0, 0),
                        depth: 0,
                        view: Vec3::ZERO,
                        attrs: attrs(pi, poly, k, None),
                    },
                };
                fan(pi, poly.len(), corner, self.draw, stats)
            }
            Path::Triangle(v) => {
                let corner = |k: usize| V::corner(v[k], attrs(pi, poly, k, Some(v[k])));
                draw_counted(pi, [corner(0), corner(1), corner(2)], self.draw, stats)
            }
            Path::Clip => stage.clipped(pi, poly, stats, attrs, self.draw),
        }
    }
}

impl<const S: u32, V: ?Sized + VertexSource<S>, T: ?Sized> PolygonStage<'_, '_, S, V, T> {
    /// Runs every polygon, or the band table's: `attrs(polygon index, polygon, corner k,
    /// vertex)` gives a corner's attributes, `draw` writes one triangle and returns `(covered,
    /// written)`.
    #[inline(always)]
    pub(super) fn run<const N: usize>(
        &self,
        stats: &mut RenderStats,
        attrs: impl Fn(usize, &[u16], usize, Option<&V::Vertex>) -> [i32; N],
        mut draw: impl TriangleConsumer<S, N>,
    ) -> Result<(), RenderError>
    where
        T: BandTable,
    {
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
        visit: &mut impl Visitor<S, V, T>,
    ) -> Result<(), RenderError> {
        // Triangle meshes (the common case) have their own loops, which read each vertex
        // once; other meshes go through `polygon`.
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            // The frame's common case, a culled object drawn in one pass, has its own loop,
            // and so has a narrow source (a constant `false` for prepared vertices).
            let unbanded_culled = !self.banded && self.object.cull_back_faces;
            match (unbanded_culled, self.prepared.narrow()) {
                (true, false) => self.triangles::<true, false>(stats, visit),
                (false, false) => self.triangles::<false, false>(stats, visit),
                (true, true) => self.triangles::<true, true>(stats, visit),
                (false, true) => self.triangles::<false, true>(stats, visit),
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
    /// and the object culls back faces (the flags are then not read per triangle), `NARROW`
    /// when the source is narrow (culled in `i32`, `cull.rs`).
    #[inline(always)]
    fn triangles<const UNBANDED_CULLED: bool, const NARROW: bool>(
        &self,
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S, V, T>,
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
            let r = self.triangle::<UNBANDED_CULLED, NARROW>(at, poly, stats, visit);
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
    fn triangle<const UNBANDED_CULLED: bool, const NARROW: bool>(
        &self,
        at: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S, V, T>,
    ) -> Result<(), RenderError> {
        match self.vertex_triangle(poly) {
            Some(v) if V::outcode(v[0]) | V::outcode(v[1]) | V::outcode(v[2]) == 0 => {
                let path = self.decide_triangle::<UNBANDED_CULLED, NARROW>(v, stats);
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
        visit: &mut impl Visitor<S, V, T>,
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
        visit: &mut impl Visitor<S, V, T>,
    ) -> Result<(), RenderError> {
        let path = self.decide(poly, stats)?;
        visit.polygon(self, pi, poly, path, stats)
    }

    /// The polygons the band table sends to this band (rejection and culling were decided
    /// once for all bands): [`Reach::Maybe`] ones are drawn when the rows of their vertices
    /// meet the band.
    #[inline(never)]
    pub(super) fn in_table(
        &self,
        table: &T,
        stats: &mut RenderStats,
        visit: &mut impl Visitor<S, V, T>,
    ) -> Result<(), RenderError>
    where
        T: BandTable,
    {
        let band = self.rows;
        let meets = |(top, bottom): (i32, i32)| bottom > band.0 && top < band.1;
        let PolygonSizes::Uniform(3) = self.object.mesh.sizes() else {
            for (pi, poly) in self.object.mesh.polygons().enumerate() {
                let path = match table.reach(pi, band) {
                    None => Path::Skip,
                    Some(Reach::Clip) if V::CLIPS => Path::Clip,
                    Some(Reach::Clip) => Path::Skip,
                    Some(Reach::Meets) => Path::Projected,
                    Some(Reach::Maybe) => match meets(self.exact_rows(poly)) {
                        true => Path::Projected,
                        false => Path::Skip,
                    },
                };
                visit.polygon(self, pi, poly, path, stats)?;
            }
            return Ok(());
        };
        let indices = self.object.mesh.indices();
        table.scan(indices.len() / 3, band, |pi, reach| {
            let Some(poly) = indices.get(3 * pi..3 * pi + 3) else {
                return Ok(());
            };
            let path = match (reach, self.vertex_triangle(poly)) {
                (Reach::Clip, _) if V::CLIPS => Path::Clip,
                (Reach::Clip, _) => Path::Skip,
                (Reach::Meets, Some(v)) => Path::Triangle(v),
                (Reach::Meets, None) => Path::Projected,
                (Reach::Maybe, Some(v)) => match meets(triangle_rows::<S, V>(v)) {
                    true => Path::Triangle(v),
                    false => Path::Skip,
                },
                (Reach::Maybe, None) => Path::Skip,
            };
            visit.polygon(self, pi, poly, path, stats)
        })
    }

    /// The vertices of `poly` when it is a triangle whose indices are all in range.
    #[inline(always)]
    pub(super) fn vertex_triangle(&self, poly: &[u16]) -> Option<[&V::Vertex; 3]> {
        let p = self.prepared;
        match *poly {
            [i0, i1, i2] => Some([p.vertex(i0)?, p.vertex(i1)?, p.vertex(i2)?]),
            _ => None,
        }
    }

    /// The rows `⌈y_min⌉ .. ⌈y_max⌉` of a polygon whose vertices all projected (an index out
    /// of range reads as row 0).
    #[inline(always)]
    pub(super) fn exact_rows(&self, poly: &[u16]) -> (i32, i32) {
        let (mut y_lo, mut y_hi) = (i32::MAX, i32::MIN);
        for &i in poly {
            let y = self.prepared.vertex(i).map_or(0, |p| V::screen(p).y);
            (y_lo, y_hi) = (y_lo.min(y), y_hi.max(y));
        }
        exact_rows::<S>(y_lo, y_hi)
    }

    /// The band table's rows of a polygon whose vertices all projected.
    #[inline(always)]
    pub(super) fn projected_rows(&self, poly: &[u16]) -> PolygonRows {
        let (top, bottom) = self.exact_rows(poly);
        PolygonRows::rows(top, bottom)
    }

    /// Clips a polygon crossing the frustum (Sutherland–Hodgman), projects and draws it.
    pub(super) fn clipped<C: TriangleConsumer<S, N>, const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&V::Vertex>) -> [i32; N],
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
        Ok((lo <= hi).then(|| exact_rows::<S>(lo, hi)))
    }

    /// Clips polygon `pi` (`poly`) against the frustum, projects it and hands each triangle
    /// of its fan to `triangle`.
    fn each_clipped_triangle<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        attrs: &impl Fn(usize, &[u16], usize, Option<&V::Vertex>) -> [i32; N],
        space_linear: u8,
        triangle: impl FnMut([Corner<S, N>; 3]) -> Result<(), RenderError>,
    ) -> Result<(), RenderError> {
        let mut input: Vec<ClipVertex<N>, CLIP_CAPACITY> = Vec::new();
        for (k, &i) in poly.iter().enumerate() {
            let p = self.prepared.vertex(i);
            let view = p.map_or(Vec3::ZERO, V::view);
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

/// The rows `⌈y_min⌉ .. ⌈y_max⌉` of a triangle whose vertices all projected.
#[inline(always)]
pub(super) fn triangle_rows<const S: u32, V: ?Sized + VertexSource<S>>(
    v: [&V::Vertex; 3],
) -> (i32, i32) {
    let (y0, y1, y2) = (V::screen(v[0]).y, V::screen(v[1]).y, V::screen(v[2]).y);
    exact_rows::<S>(y0.min(y1).min(y2), y0.max(y1).max(y2))
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
