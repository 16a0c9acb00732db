//! Compact bands: a z-buffered picture drawn band by band with the vertex stage run once per
//! frame into 8 bytes per vertex ([`CompactVertex`]) and a one-byte table per polygon
//! ([`PolygonTop`]) that lets each band visit only the polygons that reach it.
//!
//! Role in the pipeline: the memory-bound form of [`render_in_bands`](super::render_in_bands)
//! ([`render_in_compact_bands`](super::render_in_compact_bands)). It applies when every vertex
//! of every object projects inside the frustum (near, far and the guard band) to a screen
//! position within `±32767` sub-pixel units: then no polygon needs the clipper, none is
//! rejected, and a projected vertex is its screen position and 32-bit depth, all the triangle
//! writer reads. The vertex stage ([`Renderer::prepare_with`]) says whether that holds: the
//! first vertex that does not is reported as [`RenderError::NotCompact`] (draw such a scene
//! with `render_in_bands` and its full scratch).
//!
//! Once per frame, for each object: the vertex stage into [`CompactVertex`]es (and, for lit
//! Gouraud objects only, one level byte per vertex), then one pass over the polygons that
//! culls them (the exact projected signed area of `cull.rs`) and stores each front polygon's
//! top row in one byte. For each band: the table is scanned, and the polygons whose rows meet
//! the band are drawn from the compact vertices as fans through the one seam (`Corner`s to a
//! [`LevelWriter`]), in mesh order, so that every pixel sees its polygons in the order the full
//! frame draws them: the same pixels, depths and counts.
//!
//! # Memory
//! For a `width × band_rows` band with `depth_bytes` per depth sample (2 for `u16`, 4 for
//! `u32`), `V` vertices, `L` vertices of lit Gouraud objects and `P` polygons over all objects:
//!
//! `bytes = width · band_rows · (1 + depth_bytes) + 8·V + L + P`
//!
//! ([`CompactSizes::of`] counts `V`, `L` and `P` for a scene, [`CompactSizes::bytes`] adds
//! them up.) The standard bunny (1,839 vertices, 3,674 triangles, levels given per vertex) at
//! 320 × 240 in bands of 12 rows with 16-bit depth: 11,520 + 14,712 + 3,674 = 29,906 bytes.
//!
//! # Numeric contract
//! A [`CompactVertex`] holds the projector's sub-pixel position as `i16` (checked per vertex)
//! and its 32-bit depth unchanged, so the triangle writer gets the values the full frame's
//! `PreparedVertex` holds. A table entry is the polygon's top row `⌈y_min / 2^S⌉` (clamped to
//! the picture) shifted right by `g`, the smallest shift that brings the picture's last row
//! to 253 or less (`g = 0`, exact rows, up to 254 rows); 254 marks a polygon taller than a
//! band (its rows are read from its vertices in every band), 255 one never drawn (culled, or
//! no row inside the picture). The frame's tallest other polygon spans `H` row groups, so a
//! band whose rows are the groups `g0..=g1` draws exactly the entries within `g0 − H ..= g1`
//! whose rows (from the vertices where the entry alone does not decide) meet it.

use core::cell::Cell;

use super::consumer::{Corner, LevelWriter, TriangleConsumer};
use super::cull::screen_area;
use super::polygon_stage::{draw_counted, fan};
use super::{RenderError, RenderStats, Renderer, StatsSink};
use crate::clip::frustum::MAX_POLYGON_VERTICES;
use crate::geometry::mesh::PolygonSizes;
use crate::geometry::vector::Vec3;
use crate::raster::edge_walker::ceil_shift;
use crate::raster::SubpixelPoint;
use crate::scene::{Intensities, Object, Scene};
use crate::shade::lighting::light_polygon;
use crate::shade::span_writer::{RasterTarget, ShadeMode};
use crate::target::{DepthBuffer, DepthValue, Framebuffer};

/// A vertex after the vertex stage, in 8 bytes: its sub-pixel screen position as `i16` and
/// its 32-bit normalised depth (see the module doc for when a vertex has this form).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CompactVertex {
    x: i16,
    y: i16,
    depth: u32,
}

impl CompactVertex {
    /// The compact form of a projected vertex, or `None` when it was not projected (outside
    /// the frustum) or its position leaves `i16`.
    #[inline(always)]
    fn new<const S: u32>(outcode: u8, screen: SubpixelPoint<S>, depth: u32) -> Option<Self> {
        if outcode != 0 {
            return None;
        }
        Some(CompactVertex {
            x: i16::try_from(screen.x).ok()?,
            y: i16::try_from(screen.y).ok()?,
            depth,
        })
    }

    /// The sub-pixel screen position.
    #[inline(always)]
    fn screen<const S: u32>(self) -> SubpixelPoint<S> {
        SubpixelPoint::new(self.x as i32, self.y as i32)
    }
}

/// One polygon's entry in the compact band table: its top row group, or one of two codes
/// (see the module doc). One byte.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PolygonTop(u8);

impl Default for PolygonTop {
    fn default() -> Self {
        PolygonTop::NEVER
    }
}

impl PolygonTop {
    /// Taller than a band: its rows are read from its vertices in every band.
    const TALL: PolygonTop = PolygonTop(254);
    /// Never drawn: culled, or without a row inside the picture.
    const NEVER: PolygonTop = PolygonTop(255);
    /// The largest top row group an entry holds.
    const MAX_GROUP: i32 = 253;
}

/// Element counts of the compact scratch a scene needs (see the module doc's formula).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CompactSizes {
    /// [`CompactVertex`]es: every object's vertices.
    pub vertices: usize,
    /// Level bytes: the vertices of lit Gouraud objects (whose levels the vertex stage
    /// computes); 0 when every object's levels are given or lit per polygon.
    pub levels: usize,
    /// [`PolygonTop`] entries: every object's polygons.
    pub polygons: usize,
}

impl CompactSizes {
    /// The counts for `scene`.
    pub fn of(scene: &Scene<'_>) -> CompactSizes {
        let mut sizes = CompactSizes {
            vertices: 0,
            levels: 0,
            polygons: 0,
        };
        for o in scene.objects {
            let n = o.mesh.vertices().len();
            sizes.vertices += n;
            sizes.levels += if vertex_lit(o) { n } else { 0 };
            sizes.polygons += o.mesh.polygon_count();
        }
        sizes
    }

    /// Bytes of caller memory a compact banded frame needs: the band's pixels and depths
    /// (`width × band_rows` of each, `depth_bytes` per depth sample) and this scratch:
    /// `width·band_rows·(1 + depth_bytes) + 8·vertices + levels + polygons`.
    pub const fn bytes(&self, width: u16, band_rows: u16, depth_bytes: usize) -> usize {
        let band = width as usize * band_rows as usize;
        band * (1 + depth_bytes)
            + core::mem::size_of::<CompactVertex>() * self.vertices
            + self.levels
            + self.polygons
    }
}

/// True when the vertex stage lights `object`'s vertices (lit Gouraud): its levels need a
/// byte per vertex.
pub(super) fn vertex_lit(object: &Object<'_>) -> bool {
    matches!(object.intensities, Intensities::Lit { .. })
        && !matches!(object.shade, ShadeMode::Flat | ShadeMode::Phong)
}

/// The band geometry of a compact frame: the picture's rows, the row-group shift, the
/// height (in groups) from which a polygon is [`PolygonTop::TALL`], and the tallest other
/// polygon's span in groups, `H`, found by the classification.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rows {
    pub(super) height: i32,
    shift: u32,
    tall: i32,
    pub(super) spread: i32,
    /// Some polygon is [`PolygonTop::TALL`] (the scan tests for the code only then).
    tall_seen: bool,
}

impl Rows {
    /// The geometry of a picture of `height` rows drawn in bands of `band_rows` (≥ 1).
    pub(super) fn new(height: u16, band_rows: u16) -> Rows {
        let last = (height.max(1) - 1) as i32;
        let mut shift = 0;
        while last >> shift > PolygonTop::MAX_GROUP {
            shift += 1;
        }
        Rows {
            height: height as i32,
            shift,
            tall: (band_rows as i32 >> shift).max(1),
            spread: 0,
            tall_seen: false,
        }
    }

    /// The entry of a front polygon covering rows `top..bottom` (any `i32`), widening
    /// `spread` to its span.
    #[inline(always)]
    fn entry(&mut self, top: i32, bottom: i32) -> PolygonTop {
        let (top, bottom) = (top.max(0), bottom.min(self.height));
        if top >= bottom {
            return PolygonTop::NEVER;
        }
        let (first, last) = (top >> self.shift, (bottom - 1) >> self.shift);
        if last - first > self.tall {
            self.tall_seen = true;
            return PolygonTop::TALL;
        }
        self.spread = self.spread.max(last - first);
        PolygonTop(first as u8)
    }
}

/// The compact scratch of one object: its vertices and, for lit Gouraud objects, its levels.
pub(super) struct CompactObject<'a> {
    pub(super) vertices: &'a [CompactVertex],
    pub(super) levels: &'a [u8],
}

impl<const S: u32> Renderer<S> {
    /// The vertex stage for `object` (the `index`-th of its scene) into `vertices` (and
    /// `levels` for a lit Gouraud object), each as long as its vertex table (the caller
    /// sliced them); [`RenderError::NotCompact`] names the first vertex without a compact form.
    pub(super) fn prepare_compact(
        &self,
        (index, object): (usize, &Object<'_>),
        vertices: &mut [CompactVertex],
        levels: &mut [u8],
    ) -> Result<(), RenderError> {
        let mut first_bad = None;
        let mut emit = |i: usize, out: &mut CompactVertex, p: super::PreparedVertex<S>| {
            match CompactVertex::new(p.outcode, p.screen, p.depth) {
                Some(c) => *out = c,
                None => {
                    first_bad.get_or_insert(i);
                }
            }
            if let Some(l) = levels.get_mut(i) {
                *l = p.level;
            }
        };
        self.prepare_with(object, vertices, &mut emit)?;
        match first_bad {
            Some(vertex) => Err(RenderError::NotCompact {
                object: index,
                vertex,
            }),
            None => Ok(()),
        }
    }

    /// The table entry of each polygon of `object` into `table` (as long as its polygon
    /// table), from its compact vertices; counts `polygons_in` and `culled`.
    pub(super) fn compact_table(
        &self,
        object: &Object<'_>,
        vertices: &[CompactVertex],
        table: &mut [PolygonTop],
        rows: &mut Rows,
        stats: &mut RenderStats,
    ) -> Result<(), RenderError> {
        let cull = object.cull_back_faces;
        let screen = |i: u16| vertices.get(i as usize).map(|v| v.screen::<S>());
        for (entry, poly) in table.iter_mut().zip(object.mesh.polygons()) {
            stats.polygons_in += 1;
            if poly.len() > MAX_POLYGON_VERTICES {
                return Err(RenderError::PolygonTooLarge);
            }
            // The vertex stage filled every vertex: an index out of range is the mesh's
            // (already checked by `Mesh::new`), so such a polygon is never drawn.
            let Some(first) = poly.first().and_then(|&i| screen(i)) else {
                *entry = PolygonTop::NEVER;
                continue;
            };
            let (mut lo, mut hi, mut ok) = (first.y, first.y, true);
            for &i in poly {
                match screen(i) {
                    Some(p) => (lo, hi) = (lo.min(p.y), hi.max(p.y)),
                    None => ok = false,
                }
            }
            let area = || screen_area(poly.len(), |k| screen(poly[k]).unwrap_or(first));
            if !ok {
                *entry = PolygonTop::NEVER;
            } else if cull && area() >= 0 {
                // (As the full frame: a polygon of fewer than 3 corners has no area, culled.)
                stats.culled += 1;
                *entry = PolygonTop::NEVER;
            } else if poly.len() < 3 {
                *entry = PolygonTop::NEVER;
            } else {
                *entry = rows.entry(ceil_shift(lo, S), ceil_shift(hi, S));
            }
        }
        Ok(())
    }

    /// Draws the polygons of `object` that meet the band's rows through the band's buffers
    /// (`frame`, `depth`), from its compact scratch and table.
    pub(super) fn draw_compact_band<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &CompactObject<'_>,
        (table, rows): (&[PolygonTop], &Rows),
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        let stats = stats.counts();
        let band = (frame.top(), frame.top() + frame.height() as i32);
        let mut target = RasterTarget::with_count(frame, depth, T::Count::default());
        let writer = LevelWriter {
            target: &mut target,
            object,
        };
        let pass = BandPass {
            object,
            vertices: scratch.vertices,
            table,
            rows,
            band,
        };
        match object.intensities {
            Intensities::Lit { material, .. } if object.shade == ShadeMode::Flat => {
                // One level per polygon, lit for its first corner and reused, as in the full
                // frame (`run_levels`).
                let model_view = self.model_view(object)?;
                let last = Cell::new((usize::MAX, 0u8));
                let level = |pi: usize, poly: &[u16], _| {
                    if last.get().0 != pi {
                        let l = light_polygon(
                            &object.mesh,
                            poly,
                            &model_view,
                            &self.illumination,
                            &material,
                        );
                        last.set((pi, l));
                    }
                    last.get().1 as i32
                };
                pass.run::<S>(stats, level, writer)
            }
            Intensities::Lit { .. } if object.shade == ShadeMode::Phong => {
                Err(RenderError::PhongUnsupported)
            }
            Intensities::Lit { .. } => {
                let levels = scratch.levels;
                let level = |_, poly: &[u16], k: usize| {
                    levels.get(poly[k] as usize).copied().unwrap_or(0) as i32
                };
                pass.run::<S>(stats, level, writer)
            }
            _ => pass.run::<S>(
                stats,
                |pi, poly: &[u16], k| object.intensity(pi, poly[k]) as i32,
                writer,
            ),
        }
    }
}

/// One object's polygons in one band: the table scan and the fans.
struct BandPass<'a, 'o> {
    object: &'a Object<'o>,
    vertices: &'a [CompactVertex],
    table: &'a [PolygonTop],
    rows: &'a Rows,
    /// The band's rows, `band.0 .. band.1`.
    band: (i32, i32),
}

impl BandPass<'_, '_> {
    /// Scans the table and draws every polygon whose rows meet the band, in mesh order, with
    /// `level(polygon index, polygon, corner k)` per corner, through `draw`.
    fn run<const S: u32>(
        &self,
        stats: &mut RenderStats,
        level: impl Fn(usize, &[u16], usize) -> i32,
        mut draw: impl TriangleConsumer<S, 1>,
    ) -> Result<(), RenderError> {
        let Rows { shift, spread, .. } = *self.rows;
        let (g0, g1) = (self.band.0 >> shift, (self.band.1 - 1) >> shift);
        // Entries `lo ..= g1` may meet the band; 254 and 255 never pass this test (g1 ≤ 253).
        let lo = g0 - spread;
        let width = (g1 - lo + 1) as u32;
        // An entry at or after the band's first row group starts inside the band when groups
        // are rows: drawn without reading its vertices.
        let exact = shift == 0;
        let mut one = |pi: usize, poly: &[u16], e: PolygonTop| -> Result<(), RenderError> {
            let starts_inside = exact && e.0 as i32 >= g0 && e != PolygonTop::TALL;
            if starts_inside || self.meets::<S>(poly) {
                let corner = |k: usize| {
                    let v = self.vertices.get(poly[k] as usize).copied();
                    let v = v.unwrap_or_default();
                    Corner {
                        screen: v.screen(),
                        depth: v.depth,
                        view: Vec3::ZERO,
                        attrs: [level(pi, poly, k)],
                    }
                };
                if let [_, _, _] = poly {
                    draw_counted(pi, [corner(0), corner(1), corner(2)], &mut draw, stats)?;
                } else {
                    fan(pi, poly.len(), corner, &mut draw, stats)?;
                }
            }
            Ok(())
        };
        let tall = self.rows.tall_seen;
        let candidate = |e: PolygonTop| {
            ((e.0 as i32).wrapping_sub(lo) as u32) < width || (tall && e == PolygonTop::TALL)
        };
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            let indices = self.object.mesh.indices();
            for (pi, &e) in self.table.iter().enumerate() {
                if candidate(e) {
                    if let Some(poly) = indices.get(3 * pi..3 * pi + 3) {
                        one(pi, poly, e)?;
                    }
                }
            }
        } else {
            for (pi, (poly, &e)) in self.object.mesh.polygons().zip(self.table).enumerate() {
                if candidate(e) {
                    one(pi, poly, e)?;
                }
            }
        }
        Ok(())
    }

    /// True when the rows of `poly` (from its compact vertices) meet the band.
    #[inline(never)]
    fn meets<const S: u32>(&self, poly: &[u16]) -> bool {
        let (mut lo, mut hi) = (i32::MAX, i32::MIN);
        for &i in poly {
            let y = self.vertices.get(i as usize).map_or(0, |v| v.y as i32);
            (lo, hi) = (lo.min(y), hi.max(y));
        }
        ceil_shift(hi, S) > self.band.0 && ceil_shift(lo, S) < self.band.1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A compact vertex is 8 bytes and an entry one, as the memory formula says.
    #[test]
    fn compact_sizes_are_eight_and_one_bytes() {
        assert_eq!(core::mem::size_of::<CompactVertex>(), 8);
        assert_eq!(core::mem::size_of::<PolygonTop>(), 1);
    }

    /// The row-group shift keeps every top row of the picture below the codes, and a polygon
    /// taller than a band is marked tall.
    #[test]
    fn row_groups_and_codes() {
        let r = Rows::new(240, 12);
        assert_eq!(r.shift, 0);
        assert_eq!(Rows::new(254, 8).shift, 0);
        assert_eq!(Rows::new(255, 8).shift, 1);
        let big = Rows::new(u16::MAX, 16);
        assert!((u16::MAX as i32 - 1) >> big.shift <= PolygonTop::MAX_GROUP);
        let mut r = Rows::new(240, 12);
        assert_eq!(r.entry(-5, 0), PolygonTop::NEVER);
        assert_eq!(r.entry(240, 250), PolygonTop::NEVER);
        assert_eq!(r.entry(10, 10), PolygonTop::NEVER);
        assert_eq!(r.entry(-3, 4), PolygonTop(0));
        assert_eq!(r.entry(100, 113), PolygonTop(100));
        assert_eq!(r.spread, 12);
        assert_eq!(r.entry(100, 114), PolygonTop::TALL);
        assert_eq!(r.entry(239, 1000), PolygonTop(239));
        assert_eq!(r.spread, 12);
    }
}
