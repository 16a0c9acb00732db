//! The frame entry: [`Renderer::draw_object`] (both stages for one object) and
//! [`render_scene`] (clear, then every object of a [`SceneRenderer`]'s scene).

use super::{
    check_transparency, draw_order, Draws, PreparedVertex, RenderError, Renderer, SceneRenderer,
    StatsSink,
};
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::scene::Object;

impl<const S: u32> Renderer<S> {
    /// Both stages for one object.
    pub fn draw_object<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &mut [PreparedVertex<S>],
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        self.prepare(object, scratch)?;
        self.rasterize(object, scratch, frame, depth, stats)
    }
}

/// Clears `frame` to the scene's background and `depth` to far, then draws every object of
/// the renderer's scene (the blended ones last, far to near: `render::transparency`) with that scene's camera and lights, adding the frame's counts to
/// `stats`: a [`RenderStats`](super::RenderStats) counts everything, a
/// [`StatsWithoutWritten`](super::StatsWithoutWritten) everything but the written pixels, whose
/// per-pixel add the span loops then leave out (the faster choice when the count is not read;
/// see its doc).
/// `scratch` must hold at least as many vertices as the largest mesh. `frame` and `depth` hold
/// the camera's whole viewport, or, made as bands, its width
/// ([`RenderError::TargetSmallerThanViewport`] otherwise: nothing is drawn).
pub fn render_scene<D: DepthValue, const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    scratch: &mut [PreparedVertex<S>],
    stats: &mut impl StatsSink,
) -> Result<(), RenderError> {
    let (scene, renderer) = (renderer.scene(), renderer.renderer());
    renderer.check_targets(frame, depth)?;
    check_transparency(scene, "the z-buffer", Draws::Both)?;
    frame.clear(scene.background);
    depth.clear();
    for i in draw_order(renderer, scene.objects) {
        renderer.draw_object(&scene.objects[i], scratch, frame, depth, stats)?;
    }
    Ok(())
}
