//! Back-face culling alone (course ch. 3 §2; the survey's "élimination des faces arrière"):
//! every front-facing triangle drawn in scene order, with no depth buffer.
//!
//! Correct when no two front faces overlap on screen: one closed convex mesh (its front faces
//! tile its silhouette), or objects drawn back to front that a plane between them separates
//! (Schumacker's clusters in the survey: the order depends only on which side of the plane the
//! eye is). Elsewhere the last face drawn shows, which `tests/visibility.rs` counts against the
//! z-buffer (the bunny, a non-convex mesh).
//!
//! Memory: none beside the frame and the vertex scratch; the span loops run with the
//! zero-sized [`NoDepth`] sample, which compiles away the depth interpolant, test and store.

use super::VisibilityError;
use crate::output::{DepthBuffer, Framebuffer, NoDepth};
use crate::render::{check_transparency, Draws};
use crate::render::{BandPart, PreparedVertex, RenderError, Renderer, SceneRenderer, StatsSink};
use crate::scene::Scene;

/// Clears `frame` to the scene's background and draws every object of the renderer's scene in
/// order, back faces
/// culled, front faces painted as they come (no depth test). `scratch` holds at least the
/// largest mesh's vertices. The picture equals the z-buffer's when the scene qualifies
/// (the module doc of `visibility::backface`). Its errors are the pipeline's, as
/// [`VisibilityError::Render`].
pub fn render_back_faces<const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    frame: &mut Framebuffer<'_>,
    scratch: &mut [PreparedVertex<S>],
    stats: &mut impl StatsSink,
) -> Result<(), VisibilityError> {
    let n = renderer.scene().objects.len();
    Ok(draw_objects(
        renderer.renderer(),
        renderer.scene(),
        (0..n, false),
        frame,
        scratch,
        stats,
    )?)
}

/// [`render_back_faces`] with the objects drawn in `order` (indices into the scene's objects,
/// e.g. far to near as [`plan`](super::plan) sorts separable objects: Schumacker's clusters).
/// An index past the scene's objects is [`VisibilityError::NoSuchObject`], naming it; nothing is
/// drawn then.
pub fn render_back_faces_in_order<const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    order: &[u16],
    frame: &mut Framebuffer<'_>,
    scratch: &mut [PreparedVertex<S>],
    stats: &mut impl StatsSink,
) -> Result<(), VisibilityError> {
    let (scene, renderer) = (renderer.scene(), renderer.renderer());
    let objects = scene.objects.len();
    if let Some(&index) = order.iter().find(|&&i| i as usize >= objects) {
        return Err(VisibilityError::NoSuchObject { index, objects });
    }
    let order = order.iter().map(|&i| i as usize);
    Ok(draw_objects(
        renderer,
        scene,
        (order, false),
        frame,
        scratch,
        stats,
    )?)
}

/// Clears `frame` and draws the objects `order.0` names, with no depth buffer. When `order.1`,
/// `scratch` already holds the first object's vertices, prepared by `renderer` for it
/// ([`BackFaceFrame`](super::BackFaceFrame)): its vertex stage does not run again.
pub(super) fn draw_objects<const S: u32>(
    renderer: &Renderer<S>,
    scene: &Scene<'_>,
    (order, first_prepared): (impl Iterator<Item = usize>, bool),
    frame: &mut Framebuffer<'_>,
    scratch: &mut [PreparedVertex<S>],
    stats: &mut impl StatsSink,
) -> Result<(), RenderError> {
    renderer.check_frame(frame)?;
    check_transparency(scene, "back faces alone", Draws::ScreenDoor)?;
    frame.clear(scene.background);
    without_depth(frame, |frame, depth| {
        let objects = order
            .enumerate()
            .filter_map(|(k, i)| Some((k, scene.objects.get(i)?)));
        for (k, object) in objects {
            if k == 0 && first_prepared {
                renderer.rasterize(object, scratch, frame, depth, stats)?;
            } else {
                renderer.draw_object(object, scratch, frame, depth, stats)?;
            }
        }
        Ok(())
    })
}

/// Runs `draw` with `frame` and a [`NoDepth`] buffer of the same rows: what the methods that
/// paint without a depth test (back faces alone, the painter) draw through, reporting in
/// `draw`'s error type.
pub(super) fn without_depth<R, E: From<RenderError>>(
    frame: &mut Framebuffer<'_>,
    draw: impl FnOnce(&mut Framebuffer<'_>, &mut DepthBuffer<'_, NoDepth>) -> Result<R, E>,
) -> Result<R, E> {
    let (width, height) = (frame.width(), frame.height());
    // Zero bytes at any length (a frame has at most 2^24 pixels).
    let mut samples = [NoDepth; 1 << 24];
    let n = width as usize * height as usize;
    let short = RenderError::BandMemoryTooSmall {
        part: BandPart::Depths,
        given: samples.len(),
        needed: n,
    };
    let samples = samples.get_mut(..n).ok_or(short)?;
    let mut depth =
        DepthBuffer::band(samples, width, height, frame.top() as u16).map_err(|_| short)?;
    draw(frame, &mut depth)
}
