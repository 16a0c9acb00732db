//! What a frame did: the counts of [`RenderStats`], and whether the span loops count written
//! pixels ([`StatsSink`]: [`RenderStats`] counts everything, [`StatsWithoutWritten`] all but the
//! per-pixel written count).
//!
//! Role in the pipeline: beside every drawing entry point. The renderer
//! ([`render`](crate::render)) and the visibility methods ([`visibility`](crate::visibility))
//! add to the same counts, the methods' own in [`MethodCounts`]; both name these types (as
//! `render::RenderStats`, `visibility::MethodCounts`, …), and neither imports the other's for
//! them.
//!
//! Counts are `u32`: a frame of at most `2^16 × 2^16` pixels and `2^32 − 1` polygons cannot
//! exceed them, except `pixels_covered`/`pixels_written` summed over more than 65,536 full
//! overdraws (they then wrap; nothing reads them for control).

use crate::raster::triangle::{CountWritten, SkipWritten, WrittenCount};

/// What a frame did, for reports and tests.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Polygons read from the meshes.
    pub polygons_in: u32,
    /// Polygons skipped as back faces.
    pub culled: u32,
    /// Polygons wholly outside one frustum plane.
    pub rejected: u32,
    /// Polygons that went through the 3D clipper to be drawn (in bands: once per band that
    /// runs it; with the band polygon table only in the bands that a clipped polygon's clipped
    /// projection reaches, the table's one run per frame that finds those rows not counted).
    pub clipped: u32,
    /// Triangles that covered or wrote at least one pixel of the buffers (in bands: counted
    /// once per band that a triangle reaches; by the painter once per piece, by Warnock's
    /// subdivision once per window that draws it).
    pub triangles_drawn: u32,
    /// Pixels covered by drawn triangles inside the buffers (depth test passed or not).
    pub pixels_covered: u32,
    /// Pixels that passed the depth test and were written (not counted, 0, when drawn for a
    /// [`StatsWithoutWritten`]).
    pub pixels_written: u32,
    /// The visibility methods' own counts (zero for the others).
    pub method: MethodCounts,
}

/// What a visibility method ([`crate::visibility`]) did beyond drawing: a few adds per
/// triangle, pair or window, none per pixel.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MethodCounts {
    /// Painter: pair tests decided by Newell's test 1 to 5 (index 0 is test 1).
    pub painter_tests: [u32; 5],
    /// Painter: pairs no test 1–5 ordered (a triangle moved before another, or split).
    pub painter_ambiguities: u32,
    /// Painter: splits (test 6).
    pub painter_splits: u32,
    /// Painter, scan-line, Warnock: the front triangles stored.
    pub stored: u32,
    /// Painter: the pieces its splits stored after the front triangles.
    pub pieces: u32,
    /// Scan-line: the most triangles in the active table at once.
    pub active_peak: u32,
    /// Warnock: the windows visited, by verdict.
    pub windows: WindowCounts,
    /// Warnock: the most candidate entries on its stack at once.
    pub candidates_peak: u32,
    /// Warnock: the most windows on its stack at once.
    pub stack_peak: u32,
}

/// The windows Warnock's subdivision ([`render_warnock`](crate::visibility::render_warnock))
/// visited, by verdict (its module doc).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WindowCounts {
    /// No candidate: background.
    pub empty: u32,
    /// One candidate, drawn.
    pub one: u32,
    /// A surrounding candidate in front of all others, drawn.
    pub front: u32,
    /// One pixel, decided by its exact depths.
    pub pixel: u32,
    /// Split into sub-windows.
    pub split: u32,
}

impl core::ops::AddAssign for WindowCounts {
    /// Sums two frames' counts.
    fn add_assign(&mut self, o: WindowCounts) {
        self.empty += o.empty;
        self.one += o.one;
        self.front += o.front;
        self.pixel += o.pixel;
        self.split += o.split;
    }
}

impl WindowCounts {
    /// Every window visited.
    pub fn total(&self) -> u32 {
        self.empty + self.one + self.front + self.pixel + self.split
    }
}

/// Where the renderer adds its counts, and whether its span loops count written pixels:
/// [`RenderStats`] counts everything; [`StatsWithoutWritten`] everything but the written
/// pixels, whose per-pixel add the span loops then leave out
/// (`WrittenCount`).
pub trait StatsSink {
    /// `CountWritten` or `SkipWritten`.
    type Count: WrittenCount;
    /// The counts added to.
    fn counts(&mut self) -> &mut RenderStats;
}

impl StatsSink for RenderStats {
    type Count = CountWritten;
    fn counts(&mut self) -> &mut RenderStats {
        self
    }
}

/// [`RenderStats`] whose `pixels_written` stays 0: the span loops drawn for it have no
/// written-pixel counter (the Cortex-M4 frames of the standard cube, sphere and bunny take
/// 6.4 %, 9.8 % and 6.5 % fewer instructions). Every other count is kept. Pass one to
/// [`render_scene`](crate::render::render_scene) or [`render_in_bands`](crate::render::render_in_bands) when
/// nothing reads the written count.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StatsWithoutWritten(pub RenderStats);

impl StatsSink for StatsWithoutWritten {
    type Count = SkipWritten;
    fn counts(&mut self) -> &mut RenderStats {
        &mut self.0
    }
}

impl RenderStats {
    /// Counts one triangle handed to a writer, which returned `(covered, written)` pixels:
    /// `triangles_drawn` when it reached a pixel of the buffers.
    #[inline(always)]
    pub(crate) fn add_triangle(&mut self, (covered, written): (u32, u32)) {
        if covered > 0 || written > 0 {
            self.triangles_drawn += 1;
        }
        self.pixels_covered += covered;
        self.pixels_written += written;
    }
}

impl core::ops::AddAssign for RenderStats {
    /// Sums two frames' (or bands') counts.
    fn add_assign(&mut self, o: RenderStats) {
        self.polygons_in += o.polygons_in;
        self.culled += o.culled;
        self.rejected += o.rejected;
        self.clipped += o.clipped;
        self.triangles_drawn += o.triangles_drawn;
        self.pixels_covered += o.pixels_covered;
        self.pixels_written += o.pixels_written;
        let (m, n) = (&mut self.method, o.method);
        for (a, b) in m.painter_tests.iter_mut().zip(n.painter_tests) {
            *a += b;
        }
        m.painter_ambiguities += n.painter_ambiguities;
        m.painter_splits += n.painter_splits;
        m.stored = m.stored.max(n.stored);
        m.pieces = m.pieces.max(n.pieces);
        m.active_peak = m.active_peak.max(n.active_peak);
        m.candidates_peak = m.candidates_peak.max(n.candidates_peak);
        m.stack_peak = m.stack_peak.max(n.stack_peak);
        m.windows += n.windows;
    }
}
