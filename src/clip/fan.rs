//! Polygons to triangles: a polygon's corners as a fan from corner 0, and a polygon crossing a
//! [`ClipVolume`] clipped (Sutherland–Hodgman, course exercise 12), projected and fanned. The
//! one path from a polygon's vertices to projected triangles, shared by the renderer's polygon
//! stage (`render::polygon_stage`, perspective projection, corners with attributes) and the
//! shadow map's pass 1 (`shadow`, orthographic or perspective, depth only): each
//! passes its projection and its triangle consumer.
//!
//! Numeric contract: none of its own; the clipped polygon holds at most [`CLIP_CAPACITY`]
//! vertices (a non-convex polygon whose clip would exceed it is clipped fan triangle by fan
//! triangle, [`ClipVolume::clip_fan`]); corners `0..n` give `n − 2` triangles, none when
//! `n < 3` (a polygon that only touches the volume).

use heapless::Vec;

use super::frustum::{ClipError, ClipVertex, ClipVolume, CLIP_CAPACITY};

/// Hands polygon corners `0..n` to `triangle` as a fan of triangles from corner 0 (exact for
/// convex polygons, whose fan triangles tile them under the fill rule).
#[inline(always)]
pub(crate) fn fan<P: Copy, E>(
    n: usize,
    corner: impl Fn(usize) -> P,
    mut triangle: impl FnMut([P; 3]) -> Result<(), E>,
) -> Result<(), E> {
    // The clipper returns no vertices for a polygon that only touches the volume.
    if n < 3 {
        return Ok(());
    }
    let c0 = corner(0);
    for k in 1..n - 1 {
        triangle([c0, corner(k), corner(k + 1)])?;
    }
    Ok(())
}

/// Clips polygon `input` to `volume` (unless `crosses` is false: every vertex is inside),
/// projects each corner of the result with `project` and hands its fan to `triangle`.
/// Attributes whose bit is set in `space_linear` are linear in the observer frame (texture
/// coordinates; [`ClipVolume::clip_attributes`]).
pub(crate) fn clip_project_fan<V: ClipVolume, const A: usize, P: Copy, E: From<ClipError>>(
    volume: &V,
    input: &[ClipVertex<A>],
    crosses: bool,
    space_linear: u8,
    project: impl Fn(&ClipVertex<A>) -> Result<P, E>,
    mut triangle: impl FnMut([P; 3]) -> Result<(), E>,
) -> Result<(), E> {
    let mut project_fan = |polygon: &[ClipVertex<A>]| {
        let mut corners: Vec<P, CLIP_CAPACITY> = Vec::new();
        for c in polygon {
            corners
                .push(project(c)?)
                .map_err(|_| ClipError::CapacityExceeded)?;
        }
        fan(corners.len(), |k| corners[k], &mut triangle)
    };
    if crosses {
        volume.clip_fan::<A, CLIP_CAPACITY, E>(input, space_linear, project_fan)
    } else {
        project_fan(input)
    }
}
