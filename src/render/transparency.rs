//! The frame's order and refusals for transparent objects (`raster::triangle::transparency`).
//!
//! Role in the pipeline: the frame stage, before any object is drawn. A screen-door object
//! needs no order (its mask depends on the pixel alone): every method that draws the
//! z-buffer's picture draws it, but Warnock's, whose *front* verdict paints one surrounding
//! surface over a whole window and would paint it over the mask's holes. A blended object
//! needs the opaque surfaces drawn first and the blended ones after, far to near: the
//! z-buffer's whole, banded and compact banded frames draw in [`draw_order`] (and the planner
//! gives a scene holding one the z-buffer); the methods without a depth buffer or with their
//! own order (back faces alone, the painter, the scan-line, Warnock's) refuse it. A core-lit Phong object is drawn opaque only (its span kind has
//! no transparency quantizer). Each refusal is [`RenderError::TransparencyRefused`], naming
//! the object, its kind of transparency and the method ([`check`]).
//!
//! The order: the opaque and screen-door objects in scene order, then the blended ones by the
//! observer depth of the centre of their mesh's bounding box, farthest first, scene order on
//! ties. One key per object is the painter's
//! order of whole objects (the course, ch. 3 §2.1): right for blended objects that a plane
//! separates along the line of sight, and within an object the mesh's order (a closed convex
//! mesh with its back faces culled covers each pixel once).
//!
//! Without the crate's `transparency` feature (off by default: the two transparent writers
//! add about 95 KB of flash to the RP2040 board example) every transparent object is refused
//! in words, never drawn opaque.
//!
//! Numeric contract: the key is the I16F16 observer `z` of the box centre (the mean of two
//! I16F16 values, in `i64`; the transforms saturate: objects past ±32768 units tie, and keep
//! scene order); the order is found by selection with no memory, `O(b²)` key evaluations for
//! `b` blended objects, each a pass over the mesh's vertices.

use super::{RenderError, Renderer};
use crate::geometry::vector::Vec3;
use crate::raster::triangle::ShadeMode;
use crate::scene::{Intensities, Object, Scene, Transparency};

/// A kind of transparency ([`RenderError::TransparencyRefused`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TransparencyKind {
    /// [`Transparency::ScreenDoor`].
    ScreenDoor,
    /// [`Transparency::Blended`].
    Blended,
}

impl core::fmt::Display for TransparencyKind {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            TransparencyKind::ScreenDoor => "screen-door transparent",
            TransparencyKind::Blended => "blended",
        })
    }
}

/// What a method can draw of transparent objects.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Draws {
    /// Screen doors and blends (the z-buffer's frames, in [`draw_order`]).
    Both,
    /// Screen doors only.
    ScreenDoor,
    /// Neither (Warnock's subdivision).
    Neither,
}

/// The object's kind of transparency, `None` when opaque (a screen door of opacity 16 too).
pub(crate) fn kind(object: &Object<'_>) -> Option<TransparencyKind> {
    match object.transparency {
        Transparency::Opaque => None,
        Transparency::ScreenDoor(o) if o.pixels() == 16 => None,
        Transparency::ScreenDoor(_) => Some(TransparencyKind::ScreenDoor),
        Transparency::Blended(_) => Some(TransparencyKind::Blended),
    }
}

/// Refuses, before any drawing, the first object of `scene` that `method` (named in the
/// error) cannot draw as `draws` says, or a transparent core-lit Phong object.
pub(crate) fn check(
    scene: &Scene<'_>,
    method: &'static str,
    draws: Draws,
) -> Result<(), RenderError> {
    for (object, o) in scene.objects.iter().enumerate() {
        let Some(kind) = kind(o) else {
            continue;
        };
        let refused = |method| RenderError::TransparencyRefused {
            object: Some(object),
            kind,
            method,
        };
        if !cfg!(feature = "transparency") {
            return Err(refused(WITHOUT_FEATURE));
        }
        if is_phong(o) {
            return Err(refused("Phong shading"));
        }
        match (draws, kind) {
            (Draws::Both, _) | (Draws::ScreenDoor, TransparencyKind::ScreenDoor) => {}
            _ => return Err(refused(method)),
        }
    }
    Ok(())
}

/// The refusal's method when the crate is built without its `transparency` feature.
pub(crate) const WITHOUT_FEATURE: &str = "a build without the transparency feature";

/// True for an object lit per pixel (its span kind is Phong's).
pub(crate) fn is_phong(object: &Object<'_>) -> bool {
    object.shade == ShadeMode::Phong && matches!(object.intensities, Intensities::Lit { .. })
}

/// The blended objects' sort key: the observer `z` of the centre of the mesh's bounding box
/// (larger is farther).
fn key<const S: u32>(renderer: &Renderer<S>, object: &Object<'_>) -> i32 {
    let (mut lo, mut hi) = ([i32::MAX; 3], [i32::MIN; 3]);
    for v in object.mesh.vertices() {
        for (k, c) in v.bits().into_iter().enumerate() {
            lo[k] = lo[k].min(c);
            hi[k] = hi[k].max(c);
        }
    }
    // The mean of two I16F16 values fits I16F16 (an empty mesh: its origin).
    let centre = core::array::from_fn::<i32, 3, _>(|k| {
        if lo[k] > hi[k] {
            0
        } else {
            ((lo[k] as i64 + hi[k] as i64) >> 1) as i32
        }
    });
    let world = object
        .transform
        .transform_point(Vec3::from_bits(centre[0], centre[1], centre[2]));
    renderer.view.transform_point(world).z.to_bits()
}

/// The indices of `objects` in drawing order (module doc): the others in scene order, then
/// the blended far to near.
pub(crate) fn draw_order<'s, const S: u32>(
    renderer: &'s Renderer<S>,
    objects: &'s [Object<'s>],
) -> impl Iterator<Item = usize> + 's {
    let blended = |o: &Object<'_>| matches!(o.transparency, Transparency::Blended(_));
    let first = (0..objects.len()).filter(move |&i| !blended(&objects[i]));
    // Each next blended object: the farthest after the last one in (key descending, index
    // ascending) order.
    let mut last: Option<(i32, usize)> = None;
    let rest = core::iter::from_fn(move || {
        let mut best: Option<(i32, usize)> = None;
        for (i, o) in objects.iter().enumerate() {
            if !blended(o) {
                continue;
            }
            let k = key(renderer, o);
            let after = last.is_none_or(|(lk, li)| k < lk || (k == lk && i > li));
            let better = best.is_none_or(|(bk, _)| k > bk);
            if after && better {
                best = Some((k, i));
            }
        }
        last = best;
        best.map(|(_, i)| i)
    });
    first.chain(rest)
}
