//! The first step of "model no more than a scene needs": which hidden-surface method a scene
//! allows, from what is cheap to know about it.
//!
//! Today's rule: one object with back-face culling whose mesh is convex
//! ([`Mesh::is_convex`](crate::geometry::mesh::Mesh::is_convex), computed once and passed in)
//! needs no depth buffer ([`Visibility::BackFace`]); every other scene takes the z-buffer.
//! The painter and the scan-line are never picked yet (the painter costs more than the
//! z-buffer beyond a few dozen triangles, the scan-line more than bands of the z-buffer: see
//! `docs/BENCHMARKS.md`); separable objects, depth precision and memory budgets are the
//! planner issue's.

use super::Visibility;
use crate::scene::Scene;

/// Why [`plan`] chose its method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanReason {
    /// One object, culled, convex: its front faces never overlap.
    OneConvexObject,
    /// More than one object: their faces may overlap.
    SeveralObjects,
    /// The object's mesh is not convex (or its convexity is not known).
    NotConvex,
    /// The object draws its back faces too.
    BackFacesDrawn,
    /// Nothing to draw.
    Empty,
}

impl core::fmt::Display for PlanReason {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            PlanReason::OneConvexObject => "one convex object with back faces culled",
            PlanReason::SeveralObjects => "several objects may overlap",
            PlanReason::NotConvex => "the mesh is not convex",
            PlanReason::BackFacesDrawn => "the object draws its back faces",
            PlanReason::Empty => "no object",
        })
    }
}

/// A method and the reason for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Plan {
    /// The method.
    pub visibility: Visibility,
    /// Why.
    pub reason: PlanReason,
}

/// The cheapest method that draws `scene` exactly as the z-buffer does, given `convex[i]`,
/// whether object `i`'s mesh is convex (missing entries count as not convex).
pub fn plan(scene: &Scene<'_>, convex: &[bool]) -> Plan {
    let (visibility, reason) = match scene.objects {
        [] => (Visibility::BackFace, PlanReason::Empty),
        [one] if !one.cull_back_faces => (Visibility::ZBuffer, PlanReason::BackFacesDrawn),
        [_] if convex.first() == Some(&true) => (Visibility::BackFace, PlanReason::OneConvexObject),
        [_] => (Visibility::ZBuffer, PlanReason::NotConvex),
        _ => (Visibility::ZBuffer, PlanReason::SeveralObjects),
    };
    Plan { visibility, reason }
}
