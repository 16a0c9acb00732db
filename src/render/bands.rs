//! Bands: a picture drawn through one band-sized pair of buffers ([`render_in_bands`]), and the
//! polygon table ([`PolygonRows`], [`Renderer::polygon_rows`]) that decides each polygon's fate
//! once per frame, through the polygon stage's one loop (`polygon_stage.rs`) with a visitor
//! that records rows; [`render_in_compact_bands`], the same frame over compact vertices and
//! their one-byte table (`compact.rs`), through the same loop.
//!
//! Numeric contract: band rows are `0..=65535` (a viewport's height is a `u16`); see
//! `polygon_rows.rs` for the table entries.

use super::compact::{compact_refusal, vertex_lit, CompactObject, CompactRefusal, Rows};
use super::polygon_stage::{triangle_rows, Path, PolygonStage, Visitor};
use super::{
    check_transparency, draw_order, render_scene, BandPart, CompactSizes, CompactVertex, Draws,
    PolygonRows, PolygonTop, PreparedVertex, RenderError, RenderStats, Renderer, SceneRenderer,
    StatsSink, TargetBuffer,
};
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::scene::{Object, Scene};

impl<const S: u32> Renderer<S> {
    /// Each polygon's entry of the band table: never drawn, or the rows its projection
    /// touches (clipped once here when it crosses a plane) and how bands draw it.
    /// Counts `polygons_in`, `rejected` and `culled` into `stats`.
    pub fn polygon_rows(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        out: &mut [PolygonRows],
        stats: &mut impl StatsSink,
    ) -> Result<(), RenderError> {
        let stats = stats.counts();
        let mesh = &object.mesh;
        let needed = mesh.vertices().len();
        let prepared = scratch.get(..needed).ok_or(RenderError::ScratchTooSmall {
            given: scratch.len(),
            needed,
        })?;
        let given = out.len();
        let out = out
            .get_mut(..mesh.polygon_count())
            .ok_or(RenderError::PolygonTableTooSmall {
                given,
                needed: mesh.polygon_count(),
            })?;
        let stage = PolygonStage {
            renderer: self,
            object,
            prepared,
            rows: (0, 0),
            banded: false,
            table: None,
        };
        // The polygon stage's loop, recording each polygon's rows instead of drawing it.
        stage.each(
            stats,
            &mut Classify {
                out: out.iter_mut(),
            },
        )
    }
}

/// The band pre-pass's visitor: each polygon's rows ([`PolygonRows::NEVER`] when skipped; a
/// polygon that needs the clipper is clipped once here for its rows), written in mesh order.
struct Classify<'a> {
    out: core::slice::IterMut<'a, PolygonRows>,
}

impl<const S: u32> Visitor<S, [PreparedVertex<S>], [PolygonRows]> for Classify<'_> {
    #[inline(always)]
    fn polygon(
        &mut self,
        stage: &PolygonStage<'_, '_, S>,
        _: usize,
        poly: &[u16],
        path: Path<'_, PreparedVertex<S>>,
        _: &mut RenderStats,
    ) -> Result<(), RenderError> {
        if let Some(o) = self.out.next() {
            *o = match path {
                Path::Skip => PolygonRows::NEVER,
                Path::Projected => stage.projected_rows(poly),
                Path::Triangle(v) => {
                    let (top, bottom) = triangle_rows::<S, [PreparedVertex<S>]>(v);
                    PolygonRows::rows(top, bottom)
                }
                Path::Clip => match stage.clipped_rows(poly)? {
                    Some((top, bottom)) => PolygonRows::clipped(top, bottom),
                    None => PolygonRows::NEVER,
                },
            };
        }
        Ok(())
    }
}

/// Caller memory of [`render_in_bands`]; each part is a documented memory/time switch.
#[derive(Debug)]
pub struct BandScratch<'a, const S: u32> {
    /// Prepared vertices (28 bytes each). Holding the vertices of **all** objects together,
    /// the vertex stage runs once per frame; holding only the largest object's, it runs again
    /// for every band.
    pub vertices: &'a mut [PreparedVertex<S>],
    /// Polygon table (4 bytes per polygon), used when `vertices` holds all objects and this
    /// holds all objects' polygons: rejection, culling and each polygon's rows (a clipped
    /// polygon's after clipping) are decided once per frame ([`Renderer::polygon_rows`]) and
    /// a band visits only the polygons that reach it. Otherwise (e.g. `&mut []`) every band
    /// tests every polygon, and clips every clipped polygon again: bands × clipped polygons
    /// clipper runs, which a tall picture in thin bands feels.
    pub polygons: &'a mut [PolygonRows],
}

/// Draws a `width × height` picture of the renderer's scene band by band through one
/// band-sized pair of buffers:
/// for each band of `band_rows` rows (the last may be shorter) it clears and draws the band,
/// then calls `band_done` with the finished band, mutable (draw an overlay into it there, with
/// embedded-graphics text or shapes, since a [`Framebuffer`] is a `DrawTarget`), and flush it to
/// the display (e.g. [`flush`](crate::output::flush)). An error returned by `band_done` stops
/// the frame and is returned; `E` is the caller's error type, which a [`RenderError`] converts
/// into (`zscan::Error`, `Box<dyn Error>`, or [`RenderError`] itself). The picture is the same
/// as one pass (the raster stage writes exactly the rows a buffer holds), whatever the scratch
/// ([`BandScratch`]).
///
/// `band_rows` is at least 1 ([`RenderError::BadBandRows`] names a 0); a band taller than the
/// picture is allowed and draws the picture in one band, whose buffers then need only
/// `width × height` elements. Otherwise the band's buffers `(pixels, depths)` need
/// `width × band_rows` elements each. Statistics
/// are added to `stats` (a [`StatsSink`], as for [`render_scene`]) summed over bands: pixel
/// counts add up to the picture's and `clipped` counts each band's clipper runs. With
/// the polygon table, `polygons_in`, `rejected` and `culled` are counted once per frame;
/// without it, once per band pass (`culled` then counts, per band, the back faces that reach
/// the band's rows: a band skips projected polygons above or below it first).
///
/// A 32 × 24 picture in bands of 8 rows, each flushed to a display as it is finished:
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565};
/// use zscan::prelude::*;
///
/// let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
/// let up = Vec3::from_int(0, 1, 0);
/// let camera = Camera::look_at(Vec3::from_int(2, 1, 3), Vec3::ZERO, up, lens, Viewport::new(32, 24))?;
/// let objects = [Object::new(unit_cube())];
/// let scene = Scene { camera, objects: &objects, background: 0, ambient: 255, lights: &[] };
/// let renderer = Renderer::for_scene(&scene)?;
/// // One band's buffers (32 × 8), reused for the picture's 3 bands.
/// let (mut pixels, mut depths) = ([0u8; 32 * 8], [0u16; 32 * 8]);
/// let (mut vertices, mut polygons) = ([PreparedVertex::default(); 8], [PolygonRows::NEVER; 6]);
/// let scratch = BandScratch { vertices: &mut vertices, polygons: &mut polygons };
/// static LUT: Lut<Rgb565> = Lut::<Rgb565>::GREY;
/// let mut display = MockDisplay::<Rgb565>::new();
/// let mut stats = RenderStats::default();
/// let buffers = (&mut pixels[..], &mut depths[..]);
/// render_in_bands(&renderer, buffers, (32, 24, 8), scratch, &mut stats,
///     // The callback's return type names the error type `E`: from `Ok(())` alone the
///     // compiler cannot choose it (error E0283, "type annotations needed").
///     |band, _depth| -> Result<(), zscan::Error> {
///         flush(band, &LUT, &mut display, None).map_err(|_| zscan::Error::Display)?;
///         Ok(())
///     },
/// )?;
/// assert!(stats.pixels_covered > 0);
/// # Ok::<(), zscan::Error>(())
/// ```
///
/// `E` may be any type a [`RenderError`] converts into: [`zscan::Error`](crate::Error),
/// [`RenderError`], `Box<dyn std::error::Error>` or an application's own error type.
pub fn render_in_bands<D: DepthValue, E: From<RenderError>, const S: u32>(
    scene_renderer: &SceneRenderer<'_, S>,
    (pixels, depths): (&mut [u8], &mut [D]),
    (width, height, band_rows): (u16, u16, u16),
    scratch: BandScratch<'_, S>,
    stats: &mut impl StatsSink,
    band_done: impl FnMut(&mut Framebuffer<'_>, &DepthBuffer<'_, D>) -> Result<(), E>,
) -> Result<(), E> {
    let (scene, renderer) = (scene_renderer.scene(), scene_renderer.renderer());
    let BandScratch { vertices, polygons } = scratch;
    let band_rows = band_height(renderer, (width, height, band_rows))?;
    check_transparency(scene, "the z-buffer", Draws::Both)?;
    let total: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let total_polygons: usize = scene.objects.iter().map(|o| o.mesh.polygon_count()).sum();
    let prepare_once = vertices.len() >= total;
    let table = prepare_once && polygons.len() >= total_polygons;
    if prepare_once {
        let (mut at, mut pat) = (0, 0);
        for object in scene.objects {
            let (n, np) = (object.mesh.vertices().len(), object.mesh.polygon_count());
            renderer.prepare(object, &mut vertices[at..at + n])?;
            if table {
                let out = &mut polygons[pat..pat + np];
                renderer.polygon_rows(object, &vertices[at..at + n], out, stats)?;
            }
            (at, pat) = (at + n, pat + np);
        }
    }
    each_band(
        (pixels, depths),
        (width, height, band_rows),
        |frame, depth| {
            if prepare_once {
                frame.clear(scene.background);
                depth.clear();
                for i in draw_order(renderer, scene.objects) {
                    let object = &scene.objects[i];
                    // The object's vertices and polygon rows follow those of the objects
                    // before it in the scene.
                    let before = &scene.objects[..i];
                    let at: usize = before.iter().map(|o| o.mesh.vertices().len()).sum();
                    let pat: usize = before.iter().map(|o| o.mesh.polygon_count()).sum();
                    let (n, np) = (object.mesh.vertices().len(), object.mesh.polygon_count());
                    let prepared = &vertices[at..at + n];
                    let st = &mut *stats;
                    if table {
                        let t = &polygons[pat..pat + np];
                        renderer.rasterize_rows(object, prepared, t, frame, depth, st)?;
                    } else {
                        renderer.rasterize(object, prepared, frame, depth, st)?;
                    }
                }
                Ok(())
            } else {
                render_scene(scene_renderer, frame, depth, vertices, stats)
            }
        },
        band_done,
    )
}

/// The rows of each band of every banded entry (`render_in_bands`, `render_in_compact_bands`
/// and the scan-line's `render_scan_lines`): `band_rows`, at least 1
/// ([`RenderError::BadBandRows`] names a 0); a band taller than the picture is the whole
/// picture in one band. The `width × height` picture must hold the camera's viewport
/// ([`RenderError::TargetSmallerThanViewport`]).
pub(crate) fn band_height<const S: u32>(
    renderer: &Renderer<S>,
    (width, height, band_rows): (u16, u16, u16),
) -> Result<u16, RenderError> {
    renderer.check_covers(TargetBuffer::Frame, (width, height), false)?;
    if band_rows == 0 {
        return Err(RenderError::BadBandRows { band_rows });
    }
    Ok(band_rows.min(height.max(1)))
}

/// The band loop of both banded entries: for each band of `band_rows` rows of a `width ×
/// height` picture (the last may be shorter), the band's buffers from the front of `pixels`
/// and `depths`, drawn by `draw` (which clears them), then handed to `band_done`.
pub(super) fn each_band<D: DepthValue, E: From<RenderError>>(
    (pixels, depths): (&mut [u8], &mut [D]),
    (width, height, band_rows): (u16, u16, u16),
    mut draw: impl FnMut(&mut Framebuffer<'_>, &mut DepthBuffer<'_, D>) -> Result<(), RenderError>,
    mut band_done: impl FnMut(&mut Framebuffer<'_>, &DepthBuffer<'_, D>) -> Result<(), E>,
) -> Result<(), E> {
    let mut top = 0u16;
    while top < height {
        let rows = band_rows.min(height - top);
        let (mut frame, mut depth) = band_buffers((pixels, depths), (width, rows, top))?;
        draw(&mut frame, &mut depth)?;
        band_done(&mut frame, &depth)?;
        top += rows;
    }
    Ok(())
}

/// The band of rows `top..top + rows` of a `width`-wide picture, from the front of `pixels`
/// and `depths`: [`RenderError::BandMemoryTooSmall`] names the buffer shorter than
/// `width × rows` and both sizes (what every banded entry draws through).
pub(crate) fn band_buffers<'b, D: DepthValue>(
    (pixels, depths): (&'b mut [u8], &'b mut [D]),
    (width, rows, top): (u16, u16, u16),
) -> Result<(Framebuffer<'b>, DepthBuffer<'b, D>), RenderError> {
    let needed = width as usize * rows as usize;
    let short = |part, given| RenderError::BandMemoryTooSmall {
        part,
        given,
        needed,
    };
    let given = (pixels.len(), depths.len());
    let pixels = pixels
        .get_mut(..needed)
        .ok_or(short(BandPart::Pixels, given.0))?;
    let depths = depths
        .get_mut(..needed)
        .ok_or(short(BandPart::Depths, given.1))?;
    // The slices hold `width × rows` elements: only a zero width or row count is refused.
    let frame =
        Framebuffer::band(pixels, width, rows, top).map_err(|_| short(BandPart::Pixels, 0))?;
    let depth =
        DepthBuffer::band(depths, width, rows, top).map_err(|_| short(BandPart::Depths, 0))?;
    Ok((frame, depth))
}

/// Caller memory of [`render_in_compact_bands`] besides the band's buffers; sizes from
/// [`CompactSizes::of`] (the `compact.rs` module doc gives the formula).
#[derive(Debug)]
pub struct CompactBandScratch<'a> {
    /// Every object's vertices, 8 bytes each.
    pub vertices: &'a mut [CompactVertex],
    /// One level byte per vertex of the lit Gouraud objects (may be empty otherwise).
    pub levels: &'a mut [u8],
    /// Every object's polygons, one byte each.
    pub polygons: &'a mut [PolygonTop],
}

/// [`render_in_bands`] in the least memory: the vertex stage runs once per frame into
/// [`CompactVertex`]es (8 bytes per vertex instead of 28) and each polygon's rows into a
/// one-byte [`PolygonTop`] (instead of 4), so that each band visits only the polygons that
/// reach it; the pixels and counts are the full frame's (and `render_in_bands`'s). The memory
/// is `width·band_rows·(1 + size_of::<D>()) + 8·V + L + P` bytes ([`CompactSizes::bytes`]):
/// the standard bunny at 320 × 240 in bands of 10 rows with 16-bit depth takes 27,986 bytes.
/// `band_rows` is at least 1 ([`RenderError::BadBandRows`]); a band taller than the picture
/// draws the picture in one band.
///
/// It applies when every vertex projects inside the frustum's guard band within the 16-bit
/// sub-pixel range (the vertex stage checks it: [`RenderError::NotCompact`] names the first
/// object and vertex that does not; draw that frame with `render_in_bands`), and not to Phong
/// objects ([`RenderError::PhongUnsupported`]). Buffers shorter than the scene needs are
/// [`RenderError::BandMemoryTooSmall`], naming the part and both sizes; nothing is drawn
/// then. `polygons_in` and `culled` are counted once per frame.
pub fn render_in_compact_bands<D: DepthValue, E: From<RenderError>, const S: u32>(
    scene_renderer: &SceneRenderer<'_, S>,
    (pixels, depths): (&mut [u8], &mut [D]),
    (width, height, band_rows): (u16, u16, u16),
    scratch: CompactBandScratch<'_>,
    stats: &mut impl StatsSink,
    band_done: impl FnMut(&mut Framebuffer<'_>, &DepthBuffer<'_, D>) -> Result<(), E>,
) -> Result<(), E> {
    let CompactBandScratch {
        vertices,
        levels,
        polygons,
    } = scratch;
    let (scene, renderer) = (scene_renderer.scene(), scene_renderer.renderer());
    let band_rows = band_height(renderer, (width, height, band_rows))?;
    let sizes = CompactSizes::of(scene);
    let band = width as usize * band_rows as usize;
    check_compact_memory(
        scene,
        [
            (BandPart::Pixels, pixels.len(), band),
            (BandPart::Depths, depths.len(), band),
            (BandPart::Vertices, vertices.len(), sizes.vertices),
            (BandPart::Levels, levels.len(), sizes.levels),
            (BandPart::Polygons, polygons.len(), sizes.polygons),
        ],
    )?;
    // Once per frame: the vertex stage and each polygon's table entry.
    let mut rows = Rows::new(height, band_rows);
    let (mut at, mut lat, mut pat) = (0, 0, 0);
    for (index, object) in scene.objects.iter().enumerate() {
        let n = object.mesh.vertices().len();
        let nl = if sizes.levels > 0 && vertex_lit(object) {
            n
        } else {
            0
        };
        let np = object.mesh.polygon_count();
        let v = &mut vertices[at..at + n];
        renderer.prepare_compact((index, object), v, &mut levels[lat..lat + nl])?;
        let (t, st) = (&mut polygons[pat..pat + np], stats.counts());
        renderer.compact_table(object, v, t, &mut rows, st)?;
        (at, lat, pat) = (at + n, lat + nl, pat + np);
    }
    let rows = rows;
    each_band(
        (pixels, depths),
        (width, height, band_rows),
        |frame, depth| {
            frame.clear(scene.background);
            depth.clear();
            for i in draw_order(renderer, scene.objects) {
                let object = &scene.objects[i];
                let lit_levels = |o: &Object<'_>| {
                    if sizes.levels > 0 && vertex_lit(o) {
                        o.mesh.vertices().len()
                    } else {
                        0
                    }
                };
                // The object's parts follow those of the objects before it in the scene.
                let before = &scene.objects[..i];
                let at: usize = before.iter().map(|o| o.mesh.vertices().len()).sum();
                let lat: usize = before.iter().map(lit_levels).sum();
                let pat: usize = before.iter().map(|o| o.mesh.polygon_count()).sum();
                let (n, nl) = (object.mesh.vertices().len(), lit_levels(object));
                let np = object.mesh.polygon_count();
                let scratch = CompactObject {
                    vertices: &vertices[at..at + n],
                    levels: &levels[lat..lat + nl],
                };
                let table = (&polygons[pat..pat + np], &rows);
                renderer.draw_compact_band(object, &scratch, table, frame, depth, stats)?;
            }
            Ok(())
        },
        band_done,
    )
}

/// Refuses a compact frame before any work: a part of its memory shorter than the scene
/// needs (`(part, given, needed)`), or a Phong object (its normals have no compact form).
fn check_compact_memory(
    scene: &Scene<'_>,
    parts: [(BandPart, usize, usize); 5],
) -> Result<(), RenderError> {
    for (part, given, needed) in parts {
        if given < needed {
            return Err(RenderError::BandMemoryTooSmall {
                part,
                given,
                needed,
            });
        }
    }
    for (object, o) in scene.objects.iter().enumerate() {
        match compact_refusal(o) {
            None => {}
            Some(CompactRefusal::Textured) => {
                return Err(RenderError::TextureUnsupported {
                    object,
                    method: "compact bands",
                })
            }
            Some(CompactRefusal::LitPhong) => return Err(RenderError::PhongUnsupported),
        }
    }
    check_transparency(scene, "compact bands", Draws::Both)?;
    Ok(())
}
