//! Scan-line visibility (the survey's "rendu scan-line"; TIPE's edge tables, `TAG`/`TAD`,
//! per row): a triangle table bucketed by first row, an active table updated band by band,
//! and spans drawn through a depth buffer of one band of rows only.
//!
//! The frame needs the triangle table and one band of depth (one row at `band_rows = 1`)
//! instead of a frame of depth. Each band draws its active triangles through the z-buffer's
//! writer into the band's buffers, which write exactly the rows they hold, in the order the
//! polygon stage produced them (the active table is kept in that order), so every pixel, ties
//! included, is the z-buffer's at the band's depth width `D`: a band of `u16` samples quantises
//! and compares depth as the 16-bit z-buffer does (`DepthValue::from_depth32`, the same
//! writer), a band of `u32` as the 32-bit one. A triangle's set-up runs once per band it reaches: the cost of
//! thin bands, measured in `docs/BENCHMARKS.md`.
//!
//! Refused in words: a core-lit Phong object ([`RenderError::PhongUnsupported`]: a stored
//! corner keeps a level, not a normal; draw it with the z-buffer).
//!
//! Memory: a stored triangle (52 bytes) and a `u32` of order per front triangle, a `u32` per
//! active triangle, and the band's pixels and depth samples (`width × band_rows` each).

use super::error::through;
use super::store::{collect, sort_order, StoredTriangle};
use super::VisibilityError;
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::raster::triangle::RasterTarget;
use crate::render::{
    band_buffers, band_height, PreparedVertex, RenderError, RenderStats, SceneRenderer, StatsSink,
};
use crate::render::{check_transparency, Draws};
use crate::scene::Scene;

/// Caller memory of [`render_scan_lines`].
#[derive(Debug)]
pub struct ScanLineMemory<'a, D, const S: u32 = 4> {
    /// The front triangles.
    pub triangles: &'a mut [StoredTriangle<S>],
    /// The triangle table: indices by first row (as long as `triangles`).
    pub order: &'a mut [u32],
    /// The active table: triangles reaching the current band.
    pub active: &'a mut [u32],
    /// The band's pixels (`width × band_rows`).
    pub pixels: &'a mut [u8],
    /// The band's depth samples (`width × band_rows`).
    pub depths: &'a mut [D],
}

/// Draws a `width × height` picture of the renderer's scene band by band (`band_rows` rows each, the last may be
/// shorter) from the scene's front triangles, calling `band_done` with each finished band
/// as [`render_in_bands`](crate::render::render_in_bands) does. The pixels are the
/// z-buffer's at the depth width `D` of `memory.depths` (module doc): `u16` samples give the
/// 16-bit z-buffer's picture, `u32` the 32-bit one. `band_rows` is at least 1
/// ([`RenderError::BadBandRows`] names a 0); a band taller than the picture draws the picture
/// in one band. A core-lit Phong object is [`RenderError::PhongUnsupported`]. More front
/// triangles than `memory.triangles` and `memory.order` hold is
/// [`VisibilityError::TriangleStoreFull`], more triangles reaching one band than
/// `memory.active` holds [`VisibilityError::ActiveTableFull`]. Errors reach the caller
/// through `E`, as the callback's own do.
#[allow(clippy::too_many_arguments)]
pub fn render_scan_lines<D: DepthValue, T: StatsSink, E: From<VisibilityError>, const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    (width, height, band_rows): (u16, u16, u16),
    scratch: &mut [PreparedVertex<S>],
    memory: ScanLineMemory<'_, D, S>,
    stats: &mut T,
    mut band_done: impl FnMut(&mut Framebuffer<'_>, &DepthBuffer<'_, D>) -> Result<(), E>,
) -> Result<(), E> {
    let scene = renderer.scene();
    let band_rows =
        band_height(renderer.renderer(), (width, height, band_rows)).map_err(through::<E>)?;
    check_transparency(renderer.scene(), "the scan-line", Draws::ScreenDoor)
        .map_err(through::<E>)?;
    let ScanLineMemory {
        triangles,
        order,
        active,
        pixels,
        depths,
    } = memory;
    let counts = stats.counts();
    let capacity = triangles.len().min(order.len());
    let n = collect(renderer, scratch, &mut triangles[..capacity], counts)?;
    let (triangles, order) = (&triangles[..n], &mut order[..n]);
    sort_order(order, |i| triangles[i].rows().0);
    let (mut next, mut live) = (0usize, 0usize);
    let mut top = 0u16;
    while top < height {
        let rows = band_rows.min(height - top);
        let end = top as i32 + rows as i32;
        // Triangles starting above the band's end join the active table, in stored order.
        while next < n && triangles[order[next] as usize].rows().0 < end {
            let t = order[next];
            next += 1;
            if triangles[t as usize].rows().1 < top as i32 {
                continue; // wholly above the frame's first band
            }
            let capacity = active.len();
            if live == capacity {
                return Err(VisibilityError::ActiveTableFull { capacity }.into());
            }
            let at = active[..live].partition_point(|&a| a < t);
            active.copy_within(at..live, at + 1);
            active[at] = t;
            live += 1;
        }
        counts.method.active_peak = counts.method.active_peak.max(live as u32);
        let (mut frame, mut depth) =
            band_buffers((&mut *pixels, &mut *depths), (width, rows, top)).map_err(through::<E>)?;
        frame.clear(scene.background);
        depth.clear();
        {
            let mut target = RasterTarget::with_count(&mut frame, &mut depth, T::Count::default());
            draw_active(scene, triangles, &active[..live], &mut target, counts)
                .map_err(through::<E>)?;
        }
        band_done(&mut frame, &depth)?;
        // Triangles ending in this band leave the table.
        let mut kept = 0;
        for i in 0..live {
            let t = active[i];
            if triangles[t as usize].rows().1 >= end {
                active[kept] = t;
                kept += 1;
            }
        }
        live = kept;
        top += rows;
    }
    Ok(())
}

/// Draws the active triangles into the band's target, counting.
fn draw_active<D: DepthValue, C: crate::raster::triangle::WrittenCount, const S: u32>(
    scene: &Scene<'_>,
    triangles: &[StoredTriangle<S>],
    active: &[u32],
    target: &mut RasterTarget<'_, D, C>,
    stats: &mut RenderStats,
) -> Result<(), RenderError> {
    for &t in active {
        stats.add_triangle(triangles[t as usize].draw(scene, target)?);
    }
    Ok(())
}
