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
//! Compact bands keep only what is theirs: their vertex format and their band table. The
//! polygon loop, rejection, culling, rows and fans are the one polygon stage's
//! (`polygon_stage.rs`, decisions in `cull.rs`), which reads the compact vertices as a
//! [`VertexSource`] (`CompactSource`: every vertex projected, nothing to clip) and the table
//! as a [`BandTable`] (`CompactTable`); the levels are chosen per object as in the full frame
//! (`object.rs`, `run_levels`). Once per frame, for each object: the vertex stage into
//! [`CompactVertex`]es (and, for lit Gouraud objects only, one level byte per vertex), then
//! the polygon stage's loop over every polygon, which culls it (in `i32` when the object's
//! vertices span less than `2^15` sub-pixel units, where that is exact) and records each front
//! polygon's top row in one byte. For each band: the table's scan sends the polygons whose
//! rows may meet the band to the same loop, which draws them from the compact vertices as
//! fans through the one seam (`Corner`s to a [`LevelWriter`]), in mesh order, so that every
//! pixel sees its polygons in the order the full frame draws them: the same pixels, depths
//! and counts.
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
//! Beside the full frame's work: each band scans the whole table (out of line, about four and
//! a half Cortex-M0 instructions per entry), and a polygon that crosses a band boundary is set
//! up again by the writer in every band it reaches (rows outside the band are not walked). On
//! the standard bunny in 24 bands of 10 rows (Cortex-M0, `scripts/m4-profile.sh --m0
//! frame_bunny_compact`): 571 of the 1,931 triangle set-ups are repeats, about 1.1 M
//! instructions (the writer and its divisions), the scans about 0.5 M and sending the
//! candidates to the polygon stage about 0.25 M; the vertex stage and the culling run once, as
//! in the full frame (`docs/BENCHMARKS.md`, "32 KB footprint").
//!
//! # Numeric contract
//! A [`CompactVertex`] holds the projector's sub-pixel position as `i16` (checked per vertex)
//! and its 32-bit depth unchanged, so the triangle writer gets the values the full frame's
//! `PreparedVertex` holds. A table entry is the polygon's top row `⌈y_min / 2^S⌉` (clamped to
//! the picture) shifted right by `g`, the smallest shift that brings the picture's last row
//! to 253 or less (`g = 0`, exact rows, up to 254 rows); 254 marks a polygon taller than two
//! bands (its rows are read from its vertices in every band), 255 one never drawn (culled, or
//! no row inside the picture). The frame's tallest other polygon spans `H` row groups, so a
//! band whose rows are the groups `g0..=g1` draws exactly the entries within `g0 − H ..= g1`
//! whose rows (from the vertices where the entry alone does not decide) meet it.

use super::consumer::LevelWriter;
use super::cull::narrow_span;
use super::polygon_stage::{
    triangle_rows, BandTable, Path, PolygonStage, Reach, VertexSource, Visitor,
};
use super::{RenderError, RenderStats, Renderer, StatsSink};
use crate::geometry::vector::Vec3;
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
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
    /// Taller than two bands: its rows are read from its vertices in every band.
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
/// height (in groups) from which a polygon is [`PolygonTop::TALL`] (twice a band's: a
/// polygon up to two bands tall stays in the scan's window, whose test is then one
/// comparison per entry when no polygon is taller), and the tallest other polygon's span in
/// groups, `H`, found by the classification.
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
            tall: (2 * (band_rows as i32 >> shift)).max(1),
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
    /// table), from its compact vertices: the polygon stage's loop and decisions (`cull.rs`;
    /// culled in `i32` when the vertices span less than `2^15` sub-pixel units), recording
    /// each polygon's rows; counts `polygons_in` and `culled`.
    #[inline(never)]
    pub(super) fn compact_table(
        &self,
        object: &Object<'_>,
        vertices: &[CompactVertex],
        table: &mut [PolygonTop],
        rows: &mut Rows,
        stats: &mut RenderStats,
    ) -> Result<(), RenderError> {
        let (mut x, mut y) = ((i32::MAX, i32::MIN), (i32::MAX, i32::MIN));
        for v in vertices {
            x = (x.0.min(v.x as i32), x.1.max(v.x as i32));
            y = (y.0.min(v.y as i32), y.1.max(v.y as i32));
        }
        let source = CompactSource {
            vertices,
            levels: &[],
            narrow: narrow_span(x, y),
        };
        let stage: PolygonStage<'_, '_, S, CompactSource<'_>> = PolygonStage {
            renderer: self,
            object,
            prepared: &source,
            rows: (0, 0),
            banded: false,
            table: None,
        };
        let out = table.iter_mut();
        stage.each(stats, &mut Tops { out, rows })
    }

    /// Draws the polygons of `object` that meet the band's rows through the band's buffers
    /// (`frame`, `depth`), from its compact scratch and table: the polygon stage over the
    /// compact vertices and table, with the levels of the full frame (`run_levels`).
    #[inline(never)]
    pub(super) fn draw_compact_band<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &CompactObject<'_>,
        (tops, rows): (&[PolygonTop], &Rows),
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        if let Some(CompactRefusal::LitPhong) = compact_refusal(object) {
            return Err(RenderError::PhongUnsupported);
        }
        let stats = stats.counts();
        let band = (frame.top(), frame.top() + frame.height() as i32);
        // Levels given per vertex are read from the scene's table, as the full frame reads
        // its copy in the prepared vertex.
        let levels = match object.intensities {
            Intensities::PerVertex(t) => t,
            _ => scratch.levels,
        };
        let source = CompactSource {
            vertices: scratch.vertices,
            levels,
            narrow: false,
        };
        let table = CompactTable { tops, rows };
        let stage = PolygonStage {
            renderer: self,
            object,
            prepared: &source,
            rows: band,
            banded: true,
            table: Some(&table),
        };
        let mut target = RasterTarget::with_count(frame, depth, T::Count::default());
        let writer = LevelWriter {
            target: &mut target,
            object,
        };
        self.run_levels(&stage, stats, writer, |l, _, _| [l])
    }
}

/// Compact vertices as the polygon stage's vertex source: every vertex projected (no
/// outcode; no observer-frame position, which only the clipper and Phong read, and neither
/// runs here), the levels in their own bytes.
pub(super) struct CompactSource<'a> {
    vertices: &'a [CompactVertex],
    /// One level per vertex: the vertex stage's (lit Gouraud) or the scene's table (given per
    /// vertex); empty (never read) otherwise.
    levels: &'a [u8],
    /// The vertices span less than `2^15` sub-pixel units on each axis (`cull.rs`).
    narrow: bool,
}

impl<const S: u32> VertexSource<S> for CompactSource<'_> {
    type Vertex = CompactVertex;
    const CLIPS: bool = false;
    #[inline(always)]
    fn vertex(&self, i: u16) -> Option<&CompactVertex> {
        self.vertices.get(i as usize)
    }
    #[inline(always)]
    fn screen(v: &CompactVertex) -> SubpixelPoint<S> {
        v.screen()
    }
    #[inline(always)]
    fn depth(v: &CompactVertex) -> u32 {
        v.depth
    }
    #[inline(always)]
    fn outcode(_: &CompactVertex) -> u8 {
        0
    }
    #[inline(always)]
    fn view(_: &CompactVertex) -> Vec3 {
        Vec3::ZERO
    }
    #[inline(always)]
    fn level(&self, i: u16, _: &CompactVertex) -> u8 {
        self.levels.get(i as usize).copied().unwrap_or(0)
    }
    #[inline(always)]
    fn narrow(&self) -> bool {
        self.narrow
    }
}

/// The compact table pass's visitor: each polygon's entry ([`PolygonTop::NEVER`] when
/// skipped or with fewer than 3 corners), written in mesh order, widening the frame's spread.
struct Tops<'a, 'r> {
    out: core::slice::IterMut<'a, PolygonTop>,
    rows: &'r mut Rows,
}

impl<const S: u32, T: ?Sized> Visitor<S, CompactSource<'_>, T> for Tops<'_, '_> {
    #[inline(always)]
    fn polygon(
        &mut self,
        stage: &PolygonStage<'_, '_, S, CompactSource<'_>, T>,
        _: usize,
        poly: &[u16],
        path: Path<'_, CompactVertex>,
        _: &mut RenderStats,
    ) -> Result<(), RenderError> {
        if let Some(o) = self.out.next() {
            *o = match path {
                Path::Triangle(v) => {
                    let (top, bottom) = triangle_rows::<S, CompactSource<'_>>(v);
                    self.rows.entry(top, bottom)
                }
                Path::Projected if poly.len() >= 3 => {
                    let (top, bottom) = stage.exact_rows(poly);
                    self.rows.entry(top, bottom)
                }
                _ => PolygonTop::NEVER,
            };
        }
        Ok(())
    }
}

/// One object's compact band table: its one-byte entries and the frame's row groups.
pub(super) struct CompactTable<'a> {
    tops: &'a [PolygonTop],
    rows: &'a Rows,
}

/// The entries a band may draw: the groups `lo .. lo + width` (and the tall code), from the
/// band's first group `g0`.
struct Window {
    g0: i32,
    lo: i32,
    width: u32,
}

impl CompactTable<'_> {
    /// The candidates of the band of rows `band.0 .. band.1`: a band whose rows are the groups
    /// `g0 ..= g1` draws the entries within `g0 − H ..= g1` (`H`, the spread, module doc).
    #[inline(always)]
    fn window(&self, band: (i32, i32)) -> Window {
        let Rows { shift, spread, .. } = *self.rows;
        let (g0, g1) = (band.0 >> shift, (band.1 - 1) >> shift);
        // Entries `lo ..= g1` may meet the band; 254 and 255 never pass (g1 ≤ 253).
        let lo = g0 - spread;
        Window {
            g0,
            lo,
            width: (g1 - lo + 1) as u32,
        }
    }

    /// How the band reaches candidate `e`: drawn without reading its vertices' rows when
    /// groups are rows and it starts inside the band, else from them.
    #[inline(always)]
    fn reach_of(&self, e: PolygonTop, w: &Window) -> Reach {
        if self.rows.shift == 0 && e.0 as i32 >= w.g0 && e != PolygonTop::TALL {
            Reach::Meets
        } else {
            Reach::Maybe
        }
    }
}

impl BandTable for CompactTable<'_> {
    #[inline(always)]
    fn reach(&self, pi: usize, band: (i32, i32)) -> Option<Reach> {
        let e = *self.tops.get(pi)?;
        let w = self.window(band);
        is_candidate::<true>(e, w.lo, w.width).then(|| self.reach_of(e, &w))
    }

    /// The scan is the band's per-polygon cost: out of line, eight entries a step, one
    /// subtraction and one comparison each; only candidates come back, and are drawn out of
    /// line (so that the scan keeps its registers).
    #[inline(always)]
    fn scan(
        &self,
        n: usize,
        band: (i32, i32),
        mut one: impl FnMut(usize, Reach) -> Result<(), RenderError>,
    ) -> Result<(), RenderError> {
        let table = self.tops.get(..n).unwrap_or(self.tops);
        let w = self.window(band);
        let tall = self.rows.tall_seen;
        let mut pi = 0;
        loop {
            pi = match tall {
                false => next_candidate::<false>(table, pi, w.lo, w.width),
                true => next_candidate::<true>(table, pi, w.lo, w.width),
            };
            let Some(&e) = table.get(pi) else {
                return Ok(());
            };
            out_of_line(&mut one, pi, self.reach_of(e, &w))?;
            pi += 1;
        }
    }
}

/// `one(pi, reach)`, out of line.
#[inline(never)]
fn out_of_line(
    one: &mut impl FnMut(usize, Reach) -> Result<(), RenderError>,
    pi: usize,
    reach: Reach,
) -> Result<(), RenderError> {
    one(pi, reach)
}

/// True when entry `e` may meet a band whose candidates are the groups `lo .. lo + width` (or
/// the tall code, when `TALL`). `e − lo` is taken in `u32`: below `lo` it wraps above `width`.
#[inline(always)]
fn is_candidate<const TALL: bool>(e: PolygonTop, lo: i32, width: u32) -> bool {
    ((e.0 as i32).wrapping_sub(lo) as u32) < width || (TALL && e == PolygonTop::TALL)
}

/// The index of the first entry of `table` from `from` on that is a candidate
/// ([`is_candidate`]), or the table's length. Eight entries a step, with no other value live
/// than the bounds: on a Cortex-M0 about four and a half instructions per entry.
#[inline(never)]
fn next_candidate<const TALL: bool>(
    table: &[PolygonTop],
    from: usize,
    lo: i32,
    width: u32,
) -> usize {
    let hit = |e: &PolygonTop| is_candidate::<TALL>(*e, lo, width);
    let mut at = from.min(table.len());
    for c in table[at..].chunks_exact(8) {
        if hit(&c[0]) || hit(&c[1]) || hit(&c[2]) || hit(&c[3]) {
            break;
        }
        if hit(&c[4]) || hit(&c[5]) || hit(&c[6]) || hit(&c[7]) {
            at += 4;
            break;
        }
        at += 8;
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

    /// The row-group shift keeps every top row of the picture below the codes, and a polygon
    /// taller than two bands is marked tall.
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
        assert_eq!(r.entry(100, 125), PolygonTop(100));
        assert_eq!(r.spread, 24);
        assert_eq!(r.entry(100, 126), PolygonTop::TALL);
        assert_eq!(r.entry(239, 1000), PolygonTop(239));
        assert_eq!(r.spread, 24);
    }
}
