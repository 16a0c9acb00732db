//! The reverse painter (course ch. 3 §2.1, algorithm 3.2, "algorithme du peintre inversé"):
//! polygons drawn front to back, a mask of one bit per pixel recording the pixels already
//! painted, each pixel painted (and shaded) once, by the first surface that reaches it.
//!
//! Correct where the painter's order is: the order must put, at every pixel, the surface the
//! z-buffer keeps before every other surface there. Here that is the planner's rule 1
//! (`plan.rs`): every object culls its back faces, its mesh is convex and its drawn faces
//! cover each pixel at most once in this view (`facts.rs`), and any two objects that overlap
//! on screen are apart in depth (Schumacker's clusters). Objects are drawn near to far, the
//! reverse of back faces alone's order. At a pixel two objects both cover, the nearer one's
//! depth range lies wholly before the farther one's, so the z-buffer keeps it, and drawn
//! first, its bit set, it stays. Within an object no two drawn triangles share a sample, so
//! the mask never decides there. No two surfaces tie at a pixel (the ranges are strictly
//! apart), so the picture is the z-buffer's, ties included, pixel for pixel
//! (`host-tests/tests/reverse_painter.rs`: random separable convex scenes against the 32-bit
//! z-buffer). A scene outside the rule is refused, in words ([`VisibilityError::ReverseRefused`]
//! with the planner's [`MethodReason`](super::MethodReason)), never drawn wrong.
//!
//! What it saves against back faces alone (the same order, far to near, no mask): a pixel
//! that several objects cover is shaded and stored once, by the nearest, instead of once per
//! object; what it costs: the mask's clear (a word store per 32 pixels) and a test and set of
//! a bit per covered pixel, in the one span loop (the `SpanTest` seam of
//! `raster/triangle/span.rs`, `raster/triangle/mask_span.rs`), and a fill of a flat span a
//! word of the mask at a time. So it pays where objects hide each other and shading a pixel
//! costs more than testing its bit (Phong lighting per pixel; the planner's rule,
//! `plan.rs`).
//!
//! Memory beside the frame: `⌈w · h / 32⌉` `u32` words of caller memory
//! ([`mask_words_needed`](crate::output::mask_words_needed): a 320 × 240 frame, 9,600 bytes),
//! and the vertex scratch of the largest mesh. A shorter mask is refused naming the words given
//! and needed.
//!
//! Numeric contract: as back faces alone (positions within the projector's range, 32-bit
//! depths, levels `0..=255`); the mask's bit layout is `output/mask.rs`'s.

use super::facts::MeshFacts;
use super::plan::{back_faces_allowed, Placing};
use super::VisibilityError;
use crate::output::{BufferError, Framebuffer, PaintedMask};
use crate::render::{BandPart, PreparedVertex, RenderError, SceneRenderer, StatsSink};

/// Clears `frame` to the scene's background and draws the renderer's scene front to back
/// through a mask of painted pixels over `mask` (at least
/// [`mask_words_needed`](crate::output::mask_words_needed) words of the frame): the
/// z-buffer's picture, ties included (module doc). `facts[i]` are object `i`'s mesh facts;
/// `order[..objects]` receives the drawing order, near to far. `scratch` holds at least the
/// largest mesh's vertices.
///
/// Errors: [`VisibilityError::ReverseRefused`] naming why the scene is outside the method's
/// rule, checked before anything is drawn; more than 65,536 objects
/// ([`VisibilityError::TooManyObjects`]); an order or facts slice shorter than the scene's
/// objects ([`VisibilityError::NoSuchObject`]); a short mask
/// ([`RenderError::BandMemoryTooSmall`] with [`BandPart::MaskWords`]) and the renderer's own
/// errors, as [`VisibilityError::Render`].
pub fn render_reverse_painter<const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    facts: &[MeshFacts<'_>],
    order: &mut [u16],
    frame: &mut Framebuffer<'_>,
    mask: &mut [u32],
    scratch: &mut [PreparedVertex<S>],
    stats: &mut impl StatsSink,
) -> Result<(), VisibilityError> {
    let (scene, r) = (renderer.scene(), renderer.renderer());
    let n = scene.objects.len();
    let max = u16::MAX as usize + 1;
    if n > max {
        return Err(VisibilityError::TooManyObjects { max });
    }
    let order =
        order
            .get_mut(..n)
            .filter(|_| facts.len() >= n)
            .ok_or(VisibilityError::NoSuchObject {
                index: n.min(u16::MAX as usize) as u16,
                objects: n,
            })?;
    for (k, o) in order.iter_mut().enumerate() {
        *o = k as u16; // (n ≤ 2^16: a scene names at most 256 objects, `TooManyObjects`)
    }
    if n > 0 {
        let view = Placing {
            projector: r.projector(),
            frustum: r.frustum(),
        };
        back_faces_allowed(scene, facts, &view, order, None)
            .map_err(VisibilityError::ReverseRefused)?;
        order.reverse(); // far to near → near to far
    }
    draw_front_to_back(renderer, order, frame, mask, scratch, stats)?;
    Ok(())
}

/// Clears `frame` and `mask` and draws the objects `order` names (near to far, as the
/// planner's rule 1 allows: the caller has checked it) through the mask.
pub(super) fn draw_front_to_back<const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    order: &[u16],
    frame: &mut Framebuffer<'_>,
    mask: &mut [u32],
    scratch: &mut [PreparedVertex<S>],
    stats: &mut impl StatsSink,
) -> Result<(), VisibilityError> {
    let (scene, r) = (renderer.scene(), renderer.renderer());
    r.check_frame(frame)?;
    let objects = scene.objects.len();
    if let Some(&index) = order.iter().find(|&&i| i as usize >= objects) {
        return Err(VisibilityError::NoSuchObject { index, objects });
    }
    let given = mask.len();
    let mut mask = PaintedMask::for_frame(mask, frame).map_err(|e| match e {
        BufferError::BufferTooSmall { needed, len } => RenderError::BandMemoryTooSmall {
            part: BandPart::MaskWords,
            given: len,
            needed,
        },
        _ => RenderError::BandMemoryTooSmall {
            part: BandPart::MaskWords,
            given,
            needed: usize::MAX,
        },
    })?;
    frame.clear(scene.background);
    mask.clear();
    for &i in order {
        let object = &scene.objects[i as usize];
        r.prepare(object, scratch)?;
        r.rasterize_masked(object, scratch, frame, &mut mask, stats)?;
    }
    Ok(())
}
