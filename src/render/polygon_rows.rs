//! A polygon's rows: [`PolygonRows`], the 4-byte entry of `render_in_bands`' polygon table,
//! that table's scan (its [`BandTable`] side: which polygons a band visits), and the exact
//! rows of a projected polygon ([`exact_rows`]), which every band table and band test reads.
//!
//! Numeric contract: band rows are `0..=65535` (a viewport's height is a `u16`); a polygon's
//! rows are clamped to that range, which keeps the overlap test with any band exact.
//! Projected `y` are within `±(2^28 − 1)` sub-pixel units, so `⌈y / 2^S⌉` fits `i32`.
//!
//! Conventions: an entry's rows are conservative (a band they meet may hold none of the
//! polygon's pixels; the raster writes only the rows it covers). The low bit of `top` says
//! how the polygon is drawn: even, from its prepared vertices; odd, through the clipper (a
//! clipped polygon's rows are those of its clipped projection, found once per frame, so that
//! bands it does not reach skip it without clipping). A projected polygon's top is rounded
//! down to even, a clipped one's down to odd, and a clipped polygon from row 0 has a top of
//! 65535 (`CLIPPED_FROM_ROW_0`, read as 0): at most one band more than the exact rows is visited.

use super::polygon_stage::{BandTable, Reach};
use super::RenderError;
use crate::raster::triangle::edge_walker::ceil_shift;

/// A polygon's fate in a frame drawn in bands, decided once by
/// [`Renderer::polygon_rows`](super::Renderer::polygon_rows):
/// never drawn (rejected or culled), or the rows `top..bottom` its projection can touch
/// (clamped to `0..=65535`) and whether the bands it reaches draw it from its prepared vertices
/// or through the clipper (the module doc gives the encoding). 4 bytes: one word,
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
    /// The zeroed entry ([`Default`]), for a polygon table built at compile time: a `static`
    /// of them is zero-initialised memory (`.bss`). The renderer writes every entry it reads.
    pub const ZERO: PolygonRows = PolygonRows::pack(0, 0);
    /// Rejected or culled: no band draws it.
    pub const NEVER: PolygonRows = PolygonRows::pack(u16::MAX, 0);
    /// Crosses a frustum plane, rows unknown: every band runs the clipper (and the raster's
    /// own band limit).
    pub const CLIP: PolygonRows = PolygonRows::pack(Self::CLIPPED_FROM_ROW_0, u16::MAX);
    /// The `top` of a clipped polygon whose rows start at row 0 (0 is even, which would read
    /// as drawn from the prepared vertices): read as row 0 by [`meets`](Self::meets) and by
    /// the band scan's packed pre-test (`PolygonStage::in_table`).
    pub(super) const CLIPPED_FROM_ROW_0: u16 = u16::MAX;

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

    /// A polygon drawn from its prepared vertices on rows `top..bottom` (half-open, any
    /// `i32`), clamped to `0..=65535` (band rows are within that range, so the overlap test
    /// is unchanged) and `top` rounded down to even.
    pub fn rows(top: i32, bottom: i32) -> PolygonRows {
        PolygonRows::pack(clamp_row(top) & !1, clamp_row(bottom))
    }

    /// A polygon drawn through the clipper, whose clipped projection touches rows
    /// `top..bottom` (clamped as [`rows`](Self::rows)), `top` rounded down to odd (65535 for
    /// row 0).
    pub fn clipped(top: i32, bottom: i32) -> PolygonRows {
        let top = match clamp_row(top) {
            0 => Self::CLIPPED_FROM_ROW_0,
            t => t - (1 - (t & 1)),
        };
        PolygonRows::pack(top, clamp_row(bottom))
    }

    /// True when the bands draw the polygon through the clipper.
    #[inline(always)]
    pub(super) const fn is_clipped(self) -> bool {
        self.top() & 1 == 1
    }

    /// True when the polygon may touch rows `band.0..band.1`.
    #[inline(always)]
    pub(super) fn meets(self, band: (i32, i32)) -> bool {
        let top = match self.top() {
            Self::CLIPPED_FROM_ROW_0 => 0,
            t => t as i32,
        };
        (self.bottom() as i32) > band.0 && top < band.1
    }
}

/// A row clamped to the band rows' range `0..=65535`.
fn clamp_row(r: i32) -> u16 {
    r.clamp(0, u16::MAX as i32) as u16
}

/// The exact rows `⌈y_lo / 2^S⌉ .. ⌈y_hi / 2^S⌉` of a projected polygon whose sub-pixel `y`
/// run from `y_lo` to `y_hi`.
#[inline(always)]
pub(super) fn exact_rows<const S: u32>(y_lo: i32, y_hi: i32) -> (i32, i32) {
    (ceil_shift(y_lo, S), ceil_shift(y_hi, S))
}

/// The 4-byte table of `render_in_bands`: each entry tells the band its polygon's exact rows
/// (conservative, see the module doc) and whether it is drawn through the clipper.
impl BandTable for [PolygonRows] {
    #[inline(always)]
    fn reach(&self, pi: usize, band: (i32, i32)) -> Option<Reach> {
        let r = *self.get(pi)?;
        match (r.meets(band), r.is_clipped()) {
            (false, _) => None,
            (true, true) => Some(Reach::Clip),
            (true, false) => Some(Reach::Meets),
        }
    }

    #[inline(always)]
    fn scan(
        &self,
        n: usize,
        band: (i32, i32),
        mut one: impl FnMut(usize, Reach) -> Result<(), RenderError>,
    ) -> Result<(), RenderError> {
        let table = self.get(..n).unwrap_or(self);
        // The scan finds the entries that `reach` may send with one or two tests for most: rows
        // below the band's end (clamped so that rows up to 65535 pass) and above its start (or
        // a clipped polygon from row 0, `PolygonRows::CLIPPED_FROM_ROW_0`); `reach` then decides
        // exactly.
        let (b0, b1) = band;
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
        // One call site for every candidate, so that `one` (the band's drawing) inlines into
        // the scan once: with a call site for each entry of a pair and one for the odd entry,
        // it stayed out of line (Cortex-M4 frame_bunny_bands16 3,019,639 instructions with one
        // call site kept out of line, 3,008,720 inline).
        let mut pi = 0;
        loop {
            pi = next_candidate(table, pi, &maybe);
            let Some(&r) = table.get(pi) else {
                return Ok(());
            };
            if r.meets(band) {
                let reach = match r.is_clipped() {
                    true => Reach::Clip,
                    false => Reach::Meets,
                };
                one(pi, reach)?;
            }
            pi += 1;
        }
    }
}

/// The index of the first entry of `table` from `from` on that `maybe` accepts, or the
/// table's length. Two entries a step: most pairs are passed over with two tests.
#[inline(always)]
fn next_candidate(
    table: &[PolygonRows],
    from: usize,
    maybe: &impl Fn(&PolygonRows) -> bool,
) -> usize {
    let Some(rest) = table.get(from..) else {
        return table.len();
    };
    let mut at = from;
    let mut pairs = rest.chunks_exact(2);
    for pair in &mut pairs {
        if let [r0, r1] = pair {
            if maybe(r0) || maybe(r1) {
                return if maybe(r0) { at } else { at + 1 };
            }
        }
        at += 2;
    }
    match pairs.remainder() {
        [r] if !maybe(r) => at + 1,
        _ => at,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compile-time entry is the derived default (zero bits, `.bss` in a static) and, not
    /// yet written by the renderer, reaches no band.
    #[test]
    fn zero_entry_is_default_and_meets_no_band() {
        assert_eq!(PolygonRows::ZERO, PolygonRows::default());
        for band in [(0, 16), (16, 32), (224, 240), (0, 65_536)] {
            assert!(!PolygonRows::ZERO.meets(band), "{band:?}");
        }
    }

    /// The scan sends exactly the entries that `reach` sends, in order, for tables of odd and
    /// even lengths, clipped entries (from row 0 too) and bands on both sides of the rows.
    #[test]
    fn scan_sends_what_reach_decides() {
        let entries = [
            PolygonRows::rows(0, 5),
            PolygonRows::NEVER,
            PolygonRows::rows(10, 20),
            PolygonRows::clipped(0, 7),
            PolygonRows::clipped(15, 40),
            PolygonRows::CLIP,
            PolygonRows::rows(30, 31),
            PolygonRows::rows(-5, 70_000),
            PolygonRows::ZERO,
        ];
        for n in 0..=entries.len() {
            let table = &entries[..n];
            for band in [
                (0, 16),
                (16, 32),
                (5, 10),
                (30, 31),
                (-16, 0),
                (64, 80),
                (0, 65_536),
            ] {
                let mut sent = heapless::Vec::<(usize, Reach), 16>::new();
                table
                    .scan(n, band, |pi, reach| {
                        sent.push((pi, reach)).unwrap();
                        Ok(())
                    })
                    .unwrap();
                let expected: heapless::Vec<(usize, Reach), 16> = (0..n)
                    .filter_map(|pi| table.reach(pi, band).map(|r| (pi, r)))
                    .collect();
                assert_eq!(sent, expected, "{n} entries, band {band:?}");
            }
        }
    }
}
