//! The planned frame: the scene planner ([`plan`](super::plan)) and the frame it plans as one
//! entry, [`plan_frame`], so that what the planner computed for its check is not computed
//! again by the frame.
//!
//! The per-view check of a mesh (`facts.rs`) needs the mesh's
//! vertices on screen exactly as the vertex stage places them; back faces alone then run that
//! same vertex stage again. [`plan_frame`] runs the renderer's own vertex stage
//! ([`Renderer::prepare`](crate::render::Renderer::prepare)) into the caller's vertex scratch
//! for the check, and when the plan is back faces alone hands back a [`BackFaceFrame`] whose
//! [`render`](BackFaceFrame::render) rasterizes the object drawn first from those prepared
//! vertices. The objects are checked in reverse drawing order, so the one whose
//! vertices the scratch keeps is the one drawn first (for a single object, always it).
//!
//! Safety of the reuse: a [`BackFaceFrame`] borrows the [`SceneRenderer`] it was planned for
//! (its scene, camera and lights cannot change meanwhile) and holds the scratch by exclusive
//! borrow (nothing else writes it), and [`render`](BackFaceFrame::render) consumes it (a
//! second draw would find the scratch holding another object): stale vertices cannot be drawn.
//!
//! Numeric contract: the prepared vertices are the vertex stage's (`render/vertex_stage.rs`);
//! the check reads their screen positions (`±(2^28 − 1)` sub-pixel units, outcode 0) exactly
//! as it would place them itself, so [`plan_frame`]'s plan equals [`plan`](super::plan)'s for
//! the same scene and budget (tested on the standard, random and trap scenes of
//! `host-tests/tests/plan.rs`, order included).

use super::backface::draw_objects;
use super::facts::MeshFacts;
use super::plan::{plan_with, Lent, Placing, Plan, PlanError};
use super::{Visibility, VisibilityError};
use crate::output::Framebuffer;
use crate::render::{PreparedVertex, SceneRenderer, StatsSink};

/// What [`plan_frame`] returns: the plan, and for back faces alone the frame ready to draw.
#[derive(Debug)]
pub enum PlannedFrame<'f, 'a, const S: u32 = 4> {
    /// Back faces alone: draw it with [`BackFaceFrame::render`].
    BackFace(BackFaceFrame<'f, 'a, S>),
    /// The z-buffer, in the plan's layout (whole frame or bands, depth width): draw it with
    /// [`render_scene`](crate::render::render_scene),
    /// [`render_in_bands`](crate::render::render_in_bands) or
    /// [`render_in_compact_bands`](crate::render::render_in_compact_bands) and buffers of the
    /// plan's sizes, in scene order. Nothing prepared while planning is reused.
    ZBuffer(Plan),
    /// The reverse painter ([`Visibility::ReversePainter`]): draw it with
    /// [`draw_plan`](super::draw_plan) and the plan's order (near to far) and mask.
    ReversePainter(Plan),
}

impl<const S: u32> PlannedFrame<'_, '_, S> {
    /// The plan.
    pub fn plan(&self) -> &Plan {
        match self {
            PlannedFrame::BackFace(f) => &f.plan,
            PlannedFrame::ZBuffer(p) | PlannedFrame::ReversePainter(p) => p,
        }
    }
}

/// A frame planned as back faces alone ([`PlannedFrame::BackFace`]): the renderer it was
/// planned for, the drawing order, and the vertex scratch holding the first object's prepared
/// vertices when the planner ran its vertex stage (module doc).
#[derive(Debug)]
pub struct BackFaceFrame<'f, 'a, const S: u32 = 4> {
    renderer: &'f SceneRenderer<'a, S>,
    plan: Plan,
    order: &'f [u16],
    scratch: &'f mut [PreparedVertex<S>],
    /// `scratch` holds the vertices of the object `order[0]` names, prepared by `renderer`.
    first_prepared: bool,
}

impl<const S: u32> BackFaceFrame<'_, '_, S> {
    /// The plan ([`Visibility::BackFace`]).
    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// The drawing order (far to near).
    pub fn order(&self) -> &[u16] {
        self.order
    }

    /// Clears `frame` to the scene's background and draws the objects in the plan's order,
    /// back faces culled, no depth buffer (as
    /// [`render_back_faces_in_order`](super::render_back_faces_in_order)): the z-buffer's
    /// picture. The object drawn first is not prepared again when the planner prepared it.
    /// Errors are the frame's ([`VisibilityError::Render`]: a scratch shorter than a mesh's vertex table,
    /// intensity tables too short, a frame too large, …).
    pub fn render(
        self,
        frame: &mut Framebuffer<'_>,
        stats: &mut impl StatsSink,
    ) -> Result<(), VisibilityError> {
        let order = self.order.iter().map(|&i| i as usize);
        let (scene, renderer) = (self.renderer.scene(), self.renderer.renderer());
        let draw = (order, self.first_prepared);
        Ok(draw_objects(
            renderer,
            scene,
            draw,
            frame,
            self.scratch,
            stats,
        )?)
    }
}

/// Plans the scene of `renderer` as [`plan`](super::plan) does (same `facts`, `budget` and
/// `order`, same [`Plan`]), with `scratch` as vertex scratch: the per-view check of each
/// mesh runs the renderer's vertex stage there when the scratch holds the mesh's vertex
/// table (otherwise it places the vertices it needs itself), and a plan of back faces alone
/// comes back as a [`BackFaceFrame`] that reuses them (module doc). `scratch` needs
/// [`Buffers::vertices`](super::Buffers) bytes (the largest mesh's vertices) for the frame.
///
/// ```
/// use zscan::prelude::*;
/// use zscan::visibility::{plan_frame, MeshFacts, PlannedFrame, Visibility};
///
/// let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
/// let up = Vec3::from_int(0, 1, 0);
/// let camera = Camera::look_at(Vec3::from_int(2, 1, 3), Vec3::ZERO, up, lens, Viewport::new(32, 24))?;
/// let cube = Object::new(unit_cube());
/// let scene = Scene { camera, objects: &[cube], background: 0, ambient: 255, lights: &[] };
/// let mut words = [0u32; 72]; // MeshFacts::words_needed: twice the mesh's corners
/// let facts = [MeshFacts::of(&cube.mesh, &mut words)?]; // once per mesh, kept beside it
/// let renderer = Renderer::for_scene(&scene)?;
/// let (mut order, mut scratch) = ([0u16; 1], [PreparedVertex::default(); 8]);
/// let (mut pixels, mut stats) = ([0u8; 32 * 24], RenderStats::default());
/// let mut frame = Framebuffer::new(&mut pixels, 32, 24)?;
/// let planned = plan_frame(&renderer, &facts, 4096, &mut order, &mut scratch)?;
/// assert_eq!(planned.plan().visibility, Visibility::BackFace); // convex: no depth buffer
/// match planned {
///     PlannedFrame::BackFace(planned) => planned.render(&mut frame, &mut stats)?,
///     // The z-buffer's plan (the reverse painter's draws the same picture; `draw_plan` draws
///     // it through its mask of painted pixels).
///     PlannedFrame::ZBuffer(_) | PlannedFrame::ReversePainter(_) => {
///         let mut depths = [0u16; 32 * 24];
///         let mut depth = DepthBuffer::new(&mut depths, 32, 24)?;
///         render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats)?;
///     }
/// }
/// assert!(stats.pixels_covered > 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn plan_frame<'f, 'a, const S: u32>(
    renderer: &'f SceneRenderer<'a, S>,
    facts: &[MeshFacts<'_>],
    budget: usize,
    order: &'f mut [u16],
    scratch: &'f mut [PreparedVertex<S>],
) -> Result<PlannedFrame<'f, 'a, S>, PlanError> {
    let r = renderer.renderer();
    let view = Placing {
        projector: r.projector(),
        frustum: r.frustum(),
    };
    let mut lent = Lent {
        renderer: r,
        vertices: scratch,
        holds: None,
    };
    let plan = plan_with(
        renderer.scene(),
        facts,
        budget,
        order,
        &view,
        Some(&mut lent),
    )?;
    match plan.visibility {
        Visibility::BackFace => {}
        Visibility::ReversePainter => return Ok(PlannedFrame::ReversePainter(plan)),
        _ => return Ok(PlannedFrame::ZBuffer(plan)),
    }
    let order = &order[..renderer.scene().objects.len()];
    let first_prepared = lent.holds.is_some() && lent.holds == order.first().map(|&i| i as usize);
    Ok(PlannedFrame::BackFace(BackFaceFrame {
        renderer,
        plan,
        order,
        scratch: lent.vertices,
        first_prepared,
    }))
}
