//! Drawing a plan: one entry, [`draw_plan`], that draws any [`Plan`] the planner makes (back
//! faces alone, or the z-buffer whole, in bands with the vertex stage once or per band, in
//! compact bands; 16- or 32-bit depth) from caller memory the plan sizes, handing each
//! finished band (the whole frame for a whole-frame plan) to the caller's callback.
//!
//! ## The caller memory: typed, not one byte arena
//! A plan's buffers hold pixels (`u8`), depth samples (`u16` or `u32`), prepared vertices,
//! polygon rows, compact vertices, level bytes and polygon tops. One `&mut [u8]` arena cut
//! into those slices needs a reinterpreting cast (`align_to_mut`, `bytemuck`), which is
//! `unsafe` or a dependency built on it; the core has no `unsafe`. So the memory is a struct of
//! typed slices, [`PlanMemory`], and [`PlanSizes::of`] gives the length of each for a plan:
//! the caller fills the fields the plan uses and leaves the others empty (`Default`). The
//! slices' bytes are [`Plan::buffers`] exactly (`PlanSizes::bytes`, tested against it), so the
//! budget the planner kept is the memory given. What this costs: memory reserved for one type
//! cannot serve another, so a program that keeps static buffers for every plan a budget may
//! bring reserves each type's largest need.
//!
//! ## Dispatch
//! - [`Visibility::BackFace`]: the whole frame, no depth, objects in the plan's `order`
//!   ([`render_back_faces_in_order`](super::render_back_faces_in_order)); the callback gets
//!   the frame once.
//! - [`Visibility::ReversePainter`]: the whole frame, no depth, the mask of painted pixels
//!   ([`PlanMemory::mask`]), objects in the plan's `order` (near to far); the callback gets
//!   the frame once.
//! - [`Visibility::ZBuffer`] at [`DepthWidth::U16`] or [`DepthWidth::U32`]: the layout
//!   ([`LayoutReason`]) picks [`render_in_compact_bands`] for compact bands, else
//!   [`render_in_bands`], whose scratch decides the vertex stage: every object's vertices and
//!   the polygon table for [`LayoutReason::BandsVertexStageOnce`], the largest mesh's vertices
//!   and no table otherwise (a whole frame is one band). Slices longer than the plan's sizes
//!   are cut to them, so the frame runs as planned whatever the caller gave.
//! - Any other method or depth width (a `Plan` built by hand: the planner never makes one) is
//!   [`VisibilityError::NotPlanned`].
//!
//! Every layout draws the z-buffer's pixels (`render_in_bands`' contract), and back faces alone
//! draw them where the planner chose it (`plan.rs`, rule 1).
//!
//! Numeric contract: sizes are element counts as `usize` (saturating products); a slice
//! shorter than its size is [`RenderError::BandMemoryTooSmall`] (as
//! [`VisibilityError::Render`]) naming the part, the elements given and needed, checked before
//! anything is drawn.

use super::backface::render_back_faces_in_order;
use super::error::Through;
use super::plan::{DepthWidth, LayoutReason, Plan};
use super::reverse::draw_front_to_back;
use super::{Visibility, VisibilityError};
use crate::output::{mask_words_needed, DepthBuffer, DepthValue, Framebuffer};
use crate::render::{
    render_in_bands, render_in_compact_bands, BandPart, BandScratch, CompactBandScratch,
    CompactSizes, CompactVertex, PolygonRows, PolygonTop, PreparedVertex, RenderError,
    SceneRenderer, StatsSink,
};
use crate::scene::Scene;

/// The caller memory a plan draws with (module doc): one typed slice per kind of buffer,
/// each at least as long as [`PlanSizes::of`] says; the fields a plan does not use may stay
/// empty.
#[derive(Debug, Default)]
pub struct PlanMemory<'m, const S: u32 = 4> {
    /// The frame's pixels (back faces alone, a whole-frame z-buffer) or one band's.
    pub pixels: &'m mut [u8],
    /// Depth samples of a [`DepthWidth::U16`] plan.
    pub depth16: &'m mut [u16],
    /// Depth samples of a [`DepthWidth::U32`] plan.
    pub depth32: &'m mut [u32],
    /// Prepared vertices (every layout but compact bands).
    pub vertices: &'m mut [PreparedVertex<S>],
    /// The polygon table of [`LayoutReason::BandsVertexStageOnce`].
    pub polygons: &'m mut [PolygonRows],
    /// Compact bands' vertices.
    pub compact_vertices: &'m mut [CompactVertex],
    /// Compact bands' level bytes (the vertices of lit Gouraud objects).
    pub levels: &'m mut [u8],
    /// Compact bands' polygon tops.
    pub tops: &'m mut [PolygonTop],
    /// The reverse painter's mask of painted pixels
    /// ([`mask_words_needed`](crate::output::mask_words_needed) words).
    pub mask: &'m mut [u32],
}

/// Elements of each [`PlanMemory`] slice a plan draws with (0 for the slices it does not
/// use).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PlanSizes {
    /// [`PlanMemory::pixels`].
    pub pixels: usize,
    /// [`PlanMemory::depth16`].
    pub depth16: usize,
    /// [`PlanMemory::depth32`].
    pub depth32: usize,
    /// [`PlanMemory::vertices`].
    pub vertices: usize,
    /// [`PlanMemory::polygons`].
    pub polygons: usize,
    /// [`PlanMemory::compact_vertices`].
    pub compact_vertices: usize,
    /// [`PlanMemory::levels`].
    pub levels: usize,
    /// [`PlanMemory::tops`].
    pub tops: usize,
    /// [`PlanMemory::mask`].
    pub mask: usize,
}

impl PlanSizes {
    /// The sizes `plan` draws `scene` with (the scene it was made for).
    pub fn of(plan: &Plan, scene: &Scene<'_>) -> PlanSizes {
        let vp = scene.camera.viewport();
        let (w, h) = (vp.width as usize, vp.height as usize);
        let meshes = scene.objects.iter().map(|o| o.mesh);
        let largest = meshes.clone().map(|m| m.vertices().len()).max();
        let all = meshes.clone().map(|m| m.vertices().len()).sum();
        let polygons = meshes.map(|m| m.polygon_count()).sum();
        let rows = (plan.band_rows as usize).min(h);
        let mut sizes = PlanSizes {
            pixels: w.saturating_mul(rows),
            ..PlanSizes::default()
        };
        match plan.depth {
            DepthWidth::U16 => sizes.depth16 = sizes.pixels,
            DepthWidth::U32 => sizes.depth32 = sizes.pixels,
            DepthWidth::None => {}
        }
        match (plan.visibility, plan.layout_reason) {
            (Visibility::ZBuffer, LayoutReason::CompactBands) => {
                let c = CompactSizes::of(scene);
                (sizes.compact_vertices, sizes.levels, sizes.tops) =
                    (c.vertices, c.levels, c.polygons);
            }
            (Visibility::ZBuffer, LayoutReason::BandsVertexStageOnce) => {
                (sizes.vertices, sizes.polygons) = (all, polygons);
            }
            _ => sizes.vertices = largest.unwrap_or(0),
        }
        if plan.visibility == Visibility::ReversePainter {
            sizes.mask = mask_words_needed(vp.width, vp.height);
        }
        sizes
    }

    /// Their bytes at `S` sub-pixel bits (the plan's [`Buffers::total`](super::Buffers::total)
    /// for the plan they were computed for).
    pub fn bytes<const S: u32>(&self) -> usize {
        use core::mem::size_of;
        [
            (self.pixels, 1),
            (self.depth16, 2),
            (self.depth32, 4),
            (self.vertices, size_of::<PreparedVertex<S>>()),
            (self.polygons, size_of::<PolygonRows>()),
            (self.compact_vertices, size_of::<CompactVertex>()),
            (self.levels, 1),
            (self.tops, size_of::<PolygonTop>()),
            (self.mask, 4),
        ]
        .iter()
        .fold(0usize, |sum, &(n, b)| {
            sum.saturating_add(n.saturating_mul(b))
        })
    }
}

/// `slice[..needed]`, or [`RenderError::BandMemoryTooSmall`] naming `part`.
fn cut<T>(slice: &mut [T], needed: usize, part: BandPart) -> Result<&mut [T], VisibilityError> {
    let given = slice.len();
    slice
        .get_mut(..needed)
        .ok_or(VisibilityError::Render(RenderError::BandMemoryTooSmall {
            part,
            given,
            needed,
        }))
}

/// Draws the scene of `renderer` as `plan` says (the module doc's dispatch), with `memory`
/// (each slice at least [`PlanSizes::of`] long) and the drawing order `order` the planner
/// wrote (read by back faces alone and the reverse painter; the z-buffer draws in scene
/// order). `band_done` receives
/// each finished band, top to bottom (for a whole-frame plan, the frame once): flush it to the
/// display there. Errors: the frame's ([`VisibilityError`], through `E`: a slice shorter than
/// the plan needs names the part and both sizes; a hand-made plan the planner never makes is
/// [`VisibilityError::NotPlanned`]), or the callback's own.
///
/// ```
/// use zscan::prelude::*;
/// use zscan::visibility::{draw_plan, plan, MeshFacts, PlanMemory, PlanSizes};
///
/// let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
/// let up = Vec3::from_int(0, 1, 0);
/// let camera = Camera::look_at(Vec3::from_int(2, 1, 3), Vec3::ZERO, up, lens, Viewport::new(64, 48))?;
/// let objects = [Object::new(unit_cube())];
/// let scene = Scene { camera, objects: &objects, background: 0, ambient: 255, lights: &[] };
/// let mut words = [0u32; 48]; // MeshFacts::words_needed: two words per corner (24 corners)
/// let facts = [MeshFacts::of(&objects[0].mesh, &mut words)?];
/// let mut order = [0u16; 1];
/// let plan = plan::<4>(&scene, &facts, 4_000, &mut order)?; // bands of 32-bit depth
/// let sizes = PlanSizes::of(&plan, &scene);
/// let (mut pixels, mut depths) = ([0u8; 4_000], [0u32; 1_000]);
/// let mut vertices = [PreparedVertex::default(); 8];
/// let memory = PlanMemory {
///     pixels: &mut pixels[..sizes.pixels],
///     depth32: &mut depths,
///     vertices: &mut vertices,
///     ..PlanMemory::default()
/// };
/// let (renderer, mut stats, mut rows) = (Renderer::for_scene(&scene)?, RenderStats::default(), 0);
/// draw_plan(&renderer, &plan, &order, memory, &mut stats, |band| {
///     rows += band.height(); // flush `band.rows()` to the display here
///     Ok::<(), Error>(())
/// })?;
/// assert_eq!((rows, stats.pixels_covered > 0), (48, true));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn draw_plan<E: From<VisibilityError>, const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    plan: &Plan,
    order: &[u16],
    mut memory: PlanMemory<'_, S>,
    stats: &mut impl StatsSink,
    mut band_done: impl FnMut(&mut Framebuffer<'_>) -> Result<(), E>,
) -> Result<(), E> {
    let scene = renderer.scene();
    let sizes = PlanSizes::of(plan, scene);
    let vp = scene.camera.viewport();
    let (w, h) = (vp.width, vp.height);
    match (plan.visibility, plan.depth) {
        (Visibility::BackFace, DepthWidth::None) => {
            let pixels = cut(memory.pixels, sizes.pixels, BandPart::Pixels)?;
            let vertices = cut(memory.vertices, sizes.vertices, BandPart::PreparedVertices)?;
            // `cut` gave exactly the plan's `width × height` pixels, which `new` accepts.
            let given = pixels.len();
            let mut frame = Framebuffer::new(pixels, w, h)
                .map_err(|_| RenderError::BandMemoryTooSmall {
                    part: BandPart::Pixels,
                    given,
                    needed: sizes.pixels,
                })
                .map_err(VisibilityError::Render)?;
            render_back_faces_in_order(renderer, order, &mut frame, vertices, stats)?;
            band_done(&mut frame)
        }
        (Visibility::ReversePainter, DepthWidth::None) => {
            let pixels = cut(memory.pixels, sizes.pixels, BandPart::Pixels)?;
            let vertices = cut(memory.vertices, sizes.vertices, BandPart::PreparedVertices)?;
            let mask = cut(memory.mask, sizes.mask, BandPart::MaskWords)?;
            let given = pixels.len();
            let mut frame = Framebuffer::new(pixels, w, h)
                .map_err(|_| RenderError::BandMemoryTooSmall {
                    part: BandPart::Pixels,
                    given,
                    needed: sizes.pixels,
                })
                .map_err(VisibilityError::Render)?;
            draw_front_to_back(renderer, order, &mut frame, mask, vertices, stats)?;
            band_done(&mut frame)
        }
        (Visibility::ZBuffer, DepthWidth::U16) => {
            let depths = cut(
                core::mem::take(&mut memory.depth16),
                sizes.depth16,
                BandPart::Depths,
            )?;
            zbuffer(renderer, plan, &sizes, depths, memory, stats, band_done)
        }
        (Visibility::ZBuffer, DepthWidth::U32) => {
            let depths = cut(
                core::mem::take(&mut memory.depth32),
                sizes.depth32,
                BandPart::Depths,
            )?;
            zbuffer(renderer, plan, &sizes, depths, memory, stats, band_done)
        }
        (visibility, depth) => Err(VisibilityError::NotPlanned {
            method: visibility.name(),
            depth_bytes: depth.bytes(),
        }
        .into()),
    }
}

/// The z-buffer's layouts of [`draw_plan`] at depth `D`, `depths` already cut to the plan's
/// size (its `memory.depth*` fields are not read).
fn zbuffer<D: DepthValue, E: From<VisibilityError>, const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    plan: &Plan,
    sizes: &PlanSizes,
    depths: &mut [D],
    memory: PlanMemory<'_, S>,
    stats: &mut impl StatsSink,
    mut band_done: impl FnMut(&mut Framebuffer<'_>) -> Result<(), E>,
) -> Result<(), E> {
    let vp = renderer.scene().camera.viewport();
    let frame = (vp.width, vp.height, plan.band_rows);
    let pixels = cut(memory.pixels, sizes.pixels, BandPart::Pixels)?;
    // The banded entries take an error type that takes the pipeline's errors: `Through<E>`.
    let flush =
        |band: &mut Framebuffer<'_>, _: &DepthBuffer<'_, D>| band_done(band).map_err(Through);
    if plan.layout_reason == LayoutReason::CompactBands {
        let scratch = CompactBandScratch {
            vertices: cut(
                memory.compact_vertices,
                sizes.compact_vertices,
                BandPart::Vertices,
            )?,
            levels: cut(memory.levels, sizes.levels, BandPart::Levels)?,
            polygons: cut(memory.tops, sizes.tops, BandPart::Polygons)?,
        };
        render_in_compact_bands(renderer, (pixels, depths), frame, scratch, stats, flush)
            .map_err(|Through(e)| e)
    } else {
        let scratch = BandScratch {
            vertices: cut(memory.vertices, sizes.vertices, BandPart::PreparedVertices)?,
            polygons: cut(memory.polygons, sizes.polygons, BandPart::PolygonRows)?,
        };
        render_in_bands(renderer, (pixels, depths), frame, scratch, stats, flush)
            .map_err(|Through(e)| e)
    }
}
