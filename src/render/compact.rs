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
//! culls them (the exact projected signed area of `cull.rs`; for triangles in `i32` when the
//! vertices span less than `2^15` sub-pixel units, where that is exact) and stores each front
//! polygon's top row in one byte. For each band: the table is scanned, and the polygons whose rows meet
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
//! 320 × 240 in bands of 10 rows with 16-bit depth: 9,600 + 14,712 + 3,674 = 27,986 bytes
//! (`scripts/footprint.sh` draws it so in 32 KB of RAM, the stack included).
//!
//! # Cost
//! Beside the full frame's work: each band scans the whole table (out of line, about five
//! Cortex-M0 instructions per entry), and a polygon that crosses a band boundary is set up
//! again by the writer in every band it reaches (rows outside the band are not walked). On
//! the standard bunny in 22 bands of 11 rows (Cortex-M0): 540 of the 1,903 triangle set-ups
//! are repeats, about 1.0 M instructions, and the scans about 0.5 M; the vertex stage and the
//! culling run once, as in the full frame (`docs/BENCHMARKS.md`, "32 KB footprint").
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
use super::cull::{front_triangle, screen_area};
use super::polygon_stage::{draw_counted, fan};
use super::{RenderError, RenderStats, Renderer, StatsSink};
use crate::clip::frustum::MAX_POLYGON_VERTICES;
use crate::geometry::mesh::PolygonSizes;
use crate::geometry::vector::Vec3;
use crate::lighting::light_polygon;
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::raster::triangle::edge_walker::ceil_shift;
use crate::raster::triangle::{RasterTarget, ShadeMode};
use crate::raster::SubpixelPoint;
use crate::scene::{Intensities, Object, Scene};

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

    /// The tallest band (at most `height` rows) whose frame fits `budget` bytes by
    /// [`bytes`](Self::bytes), or 0 when not even one row fits. The budget is the caller
    /// memory only: a device keeps room for its stack beside it (the footprint firmware's
    /// stack needs 3.3 KB more on a Cortex-M0, `docs/BENCHMARKS.md`).
    pub const fn band_rows_within(
        &self,
        budget: usize,
        width: u16,
        height: u16,
        depth_bytes: usize,
    ) -> u16 {
        let fixed = self.bytes(width, 0, depth_bytes);
        let row = width as usize * (1 + depth_bytes);
        if budget < fixed || row == 0 {
            return if budget >= fixed { height } else { 0 };
        }
        let rows = (budget - fixed) / row;
        if rows > height as usize {
            height
        } else {
            rows as u16
        }
    }
}

/// Why compact bands cannot draw an object, whatever the view: the one statement of what they
/// draw, read by the frame's check (`render::bands`) and by the planner (`visibility::plan`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CompactRefusal {
    /// A core-lit Phong object: its per-pixel normals have no compact form
    /// ([`RenderError::PhongUnsupported`]).
    LitPhong,
    /// A textured object: compact vertices carry no texture coordinates
    /// ([`RenderError::TextureUnsupported`]).
    Textured,
}

/// `None` when compact bands can draw `object` (in a view that keeps its vertices within the
/// compact range, which the vertex stage checks), else why not. Texture comes first: a
/// textured Phong object is refused for its texture.
pub(crate) fn compact_refusal(object: &Object<'_>) -> Option<CompactRefusal> {
    if object.texture.is_some() {
        Some(CompactRefusal::Textured)
    } else if matches!(object.intensities, Intensities::Lit { .. })
        && object.shade == ShadeMode::Phong
    {
        Some(CompactRefusal::LitPhong)
    } else {
        None
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
    /// Out of line, as the two below: the frame's stack peak is then the deepest of the three
    /// passes, not their sum (measured on the Cortex-M0 footprint firmware).
    #[inline(never)]
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
    #[inline(never)]
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
        if let PolygonSizes::Uniform(3) = object.mesh.sizes() {
            stats.polygons_in += table.len().min(object.mesh.polygon_count()) as u32;
            // Within a span below 2^15 on both axes every coordinate difference fits `i16`,
            // and the cull's cross product fits `i32` (module doc).
            if narrow_span(vertices) {
                classify_triangles::<S, true>(object, vertices, table, rows, stats);
            } else {
                classify_triangles::<S, false>(object, vertices, table, rows, stats);
            }
            return Ok(());
        }
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
    #[inline(never)]
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
            Intensities::PerVertex(t) => {
                // Read from the table as the full frame reads its copy in the prepared vertex.
                let level = |_, poly: &[u16], k: usize| {
                    t.get(poly[k] as usize).copied().unwrap_or(0) as i32
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
        let tall = self.rows.tall_seen;
        let (level, draw) = (&level, &mut draw);
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            // The scan is the band's per-polygon cost: out of line, four entries a step, one
            // subtraction and one comparison each; only candidates come back here.
            let mut pi = 0;
            loop {
                pi = match tall {
                    false => next_candidate::<false>(self.table, pi, lo, width),
                    true => next_candidate::<true>(self.table, pi, lo, width),
                };
                let Some(&e) = self.table.get(pi) else {
                    return Ok(());
                };
                self.visit_triangle::<S>(pi, e, g0, stats, level, draw)?;
                pi += 1;
            }
        }
        for (pi, (poly, &e)) in self.object.mesh.polygons().zip(self.table).enumerate() {
            if is_candidate::<true>(e, lo, width) {
                self.visit::<S>(pi, poly, e, g0, stats, level, draw)?;
            }
        }
        Ok(())
    }

    /// [`visit`](Self::visit) for triangle `pi` of a triangle mesh (out of line, so that the
    /// scan keeps its registers).
    #[inline(never)]
    fn visit_triangle<const S: u32>(
        &self,
        pi: usize,
        e: PolygonTop,
        g0: i32,
        stats: &mut RenderStats,
        level: &impl Fn(usize, &[u16], usize) -> i32,
        draw: &mut impl TriangleConsumer<S, 1>,
    ) -> Result<(), RenderError> {
        match self.object.mesh.indices().get(3 * pi..3 * pi + 3) {
            Some(poly) => self.visit::<S>(pi, poly, e, g0, stats, level, draw),
            None => Ok(()),
        }
    }

    /// Draws polygon `pi` (`poly`, table entry `e`) when its rows meet the band (group `g0`
    /// is the band's first): without reading its vertices when groups are rows and it starts
    /// inside the band, else from their rows.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn visit<const S: u32>(
        &self,
        pi: usize,
        poly: &[u16],
        e: PolygonTop,
        g0: i32,
        stats: &mut RenderStats,
        level: &impl Fn(usize, &[u16], usize) -> i32,
        draw: &mut impl TriangleConsumer<S, 1>,
    ) -> Result<(), RenderError> {
        let starts_inside = self.rows.shift == 0 && e.0 as i32 >= g0 && e != PolygonTop::TALL;
        if !starts_inside && !self.meets::<S>(poly) {
            return Ok(());
        }
        let corner = |k: usize| {
            let v = self.vertices.get(poly[k] as usize).copied();
            let v = v.unwrap_or_default();
            Corner {
                screen: v.screen(),
                depth: v.depth,
                // The level writer reads no observer position (only Phong and the clipper do,
                // and neither runs here).
                view: Vec3::ZERO,
                attrs: [level(pi, poly, k)],
            }
        };
        if let [_, _, _] = poly {
            draw_counted(pi, [corner(0), corner(1), corner(2)], draw, stats)
        } else {
            fan(pi, poly.len(), corner, draw, stats)
        }
    }

    /// True when the rows of `poly` (from its compact vertices) meet the band.
    #[inline(always)]
    fn meets<const S: u32>(&self, poly: &[u16]) -> bool {
        let (mut lo, mut hi) = (i32::MAX, i32::MIN);
        for &i in poly {
            let y = self.vertices.get(i as usize).map_or(0, |v| v.y as i32);
            (lo, hi) = (lo.min(y), hi.max(y));
        }
        ceil_shift(hi, S) > self.band.0 && ceil_shift(lo, S) < self.band.1
    }
}

/// True when the compact vertices' `x` and `y` each span less than `2^15` sub-pixel units
/// (so every difference of two coordinates is within `±(2^15 − 1)`).
fn narrow_span(vertices: &[CompactVertex]) -> bool {
    let (mut x0, mut x1, mut y0, mut y1) = (i16::MAX, i16::MIN, i16::MAX, i16::MIN);
    for v in vertices {
        (x0, x1) = (x0.min(v.x), x1.max(v.x));
        (y0, y1) = (y0.min(v.y), y1.max(v.y));
    }
    let span = |lo: i16, hi: i16| (hi as i32 - lo as i32) < 1 << 15;
    vertices.is_empty() || span(x0, x1) && span(y0, y1)
}

/// The table entries of a triangle mesh's triangles (see `compact_table`), culled in `i32`
/// when `NARROW` (every coordinate difference within `±(2^15 − 1)`: each product below
/// `2^30`, their difference below `2^31`, the sign of [`front_triangle`]'s exact sum), else
/// by [`front_triangle`]. Counts `culled`.
#[inline(always)]
fn classify_triangles<const S: u32, const NARROW: bool>(
    object: &Object<'_>,
    vertices: &[CompactVertex],
    table: &mut [PolygonTop],
    rows: &mut Rows,
    stats: &mut RenderStats,
) {
    let cull = object.cull_back_faces;
    let front = |a: CompactVertex, b: CompactVertex, c: CompactVertex| {
        if NARROW {
            let (bx, by) = (b.x as i32 - a.x as i32, b.y as i32 - a.y as i32);
            let (cx, cy) = (c.x as i32 - a.x as i32, c.y as i32 - a.y as i32);
            bx * cy - by * cx < 0
        } else {
            front_triangle::<S>(a.screen(), b.screen(), c.screen())
        }
    };
    let vertex = |i: u16| vertices.get(i as usize).copied();
    for (entry, t) in table.iter_mut().zip(object.mesh.indices().chunks_exact(3)) {
        *entry = match (vertex(t[0]), vertex(t[1]), vertex(t[2])) {
            (Some(a), Some(b), Some(c)) => {
                if cull && !front(a, b, c) {
                    stats.culled += 1;
                    PolygonTop::NEVER
                } else {
                    let (lo, hi) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
                    rows.entry(ceil_shift(lo as i32, S), ceil_shift(hi as i32, S))
                }
            }
            _ => PolygonTop::NEVER,
        };
    }
}

/// True when entry `e` may meet a band whose candidates are the groups `lo .. lo + width` (or
/// the tall code, when `TALL`). `e − lo` is taken in `u32`: below `lo` it wraps above `width`.
#[inline(always)]
fn is_candidate<const TALL: bool>(e: PolygonTop, lo: i32, width: u32) -> bool {
    ((e.0 as i32).wrapping_sub(lo) as u32) < width || (TALL && e == PolygonTop::TALL)
}

/// The index of the first entry of `table` from `from` on that is a candidate
/// ([`is_candidate`]), or the table's length. Four entries a step, with no other value live
/// than the bounds: on a Cortex-M0 about five instructions per entry.
#[inline(never)]
fn next_candidate<const TALL: bool>(
    table: &[PolygonTop],
    from: usize,
    lo: i32,
    width: u32,
) -> usize {
    let hit = |e: &PolygonTop| is_candidate::<TALL>(*e, lo, width);
    let mut at = from.min(table.len());
    let mut steps = table[at..].chunks_exact(4);
    for c in &mut steps {
        if hit(&c[0]) || hit(&c[1]) || hit(&c[2]) || hit(&c[3]) {
            break;
        }
        at += 4;
    }
    // Within the step that hit, or the last entries.
    match table[at..].iter().position(hit) {
        Some(k) => at + k,
        None => table.len(),
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

    /// The scan finds exactly the candidates, from any start, with or without the tall code.
    #[test]
    fn next_candidate_finds_each_candidate_in_order() {
        let codes: [u8; 23] = [
            255, 3, 254, 7, 9, 255, 0, 8, 253, 255, 255, 255, 255, 6, 254, 10, 12, 255, 5, 5, 1,
            255, 9,
        ];
        let table = codes.map(PolygonTop);
        for (lo, width) in [(5, 4), (-3, 5), (0, 254), (11, 3), (250, 4)] {
            for tall in [false, true] {
                let expect: heapless::Vec<usize, 32> = (0..table.len())
                    .filter(|&i| {
                        let e = codes[i] as i32;
                        (lo..lo + width as i32).contains(&e) && e < 254 || tall && e == 254
                    })
                    .collect();
                let mut found = heapless::Vec::<usize, 32>::new();
                let mut at = 0;
                loop {
                    at = match tall {
                        false => next_candidate::<false>(&table, at, lo, width),
                        true => next_candidate::<true>(&table, at, lo, width),
                    };
                    if at == table.len() {
                        break;
                    }
                    found.push(at).unwrap();
                    at += 1;
                }
                assert_eq!(found, expect, "lo {lo} width {width} tall {tall}");
            }
        }
    }

    /// The `i32` cull of narrow spans agrees with `front_triangle` at the range's extremes and
    /// on random triangles; a span of `2^15` is not narrow.
    #[test]
    fn narrow_cull_agrees_with_front_triangle() {
        let mut rng = crate::test_rng::XorShift(0x5EED_0FC0_4AC7_u64);
        let v = |x: i32, y: i32| CompactVertex {
            x: x as i16,
            y: y as i16,
            depth: 0,
        };
        let mut agree = 0;
        for n in 0..20_000 {
            let (base, span) = if n % 2 == 0 {
                (-16384, 32767)
            } else {
                (-40, 80)
            };
            let mut c = || base + (rng.next_u64() % (span as u64 + 1)) as i32;
            let mut t = [v(c(), c()), v(c(), c()), v(c(), c())];
            if n < 8 {
                let (lo, hi) = (-16384, 16383);
                t = [
                    v(lo, lo),
                    v(hi, [lo, hi][n % 2]),
                    v([lo, hi][n / 2 % 2], hi),
                ];
                if n >= 4 {
                    t.swap(1, 2);
                }
            }
            assert!(narrow_span(&t));
            let (a, b, c2) = (t[0], t[1], t[2]);
            let (bx, by) = (b.x as i32 - a.x as i32, b.y as i32 - a.y as i32);
            let (cx, cy) = (c2.x as i32 - a.x as i32, c2.y as i32 - a.y as i32);
            let narrow = bx * cy - by * cx < 0;
            let exact = front_triangle::<4>(a.screen(), b.screen(), c2.screen());
            assert_eq!(narrow, exact, "{t:?}");
            agree += exact as u32;
        }
        assert!((5_000..15_000).contains(&agree), "{agree}");
        assert!(!narrow_span(&[v(-16384, 0), v(16384, 0)]));
        assert!(narrow_span(&[v(-16384, 0), v(16383, 0)]));
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
