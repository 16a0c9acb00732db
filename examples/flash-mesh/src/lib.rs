//! The standard bunny compiled into flash: `bunny.rs` is written by
//! `zscan mesh host-tests/meshes/bunny.obj --centre --turn-y 90 --fit 0.7 -o examples/flash-mesh/src/bunny.rs`
//! (static vertex, index and normal tables, the mesh validated at compile time and the
//! planner's facts), so that a device computes nothing at start: [`frame`] plans a frame from
//! the stored facts and draws it through [`draw_plan`] into the caller's memory.
//!
//! `coarse.rs`, the bunny for small one-bit displays (243 triangles, whose front edges stay
//! apart at 128 × 64), is written by vertex clustering on a 6 × 6 × 6 grid:
//! `zscan mesh host-tests/meshes/bunny.obj --cluster 6 --centre --turn-y 90 --fit 0.7 -o examples/flash-mesh/src/coarse.rs`
//!
//! Build for a Cortex-M0+ (no linker needed, it is a library):
//! `cargo build --release --target thumbv6m-none-eabi` in this folder.
//! `host-tests/tests/mesh_module.rs` checks that the module is what the tool writes and that
//! it draws `frame_bunny`'s checksum.
#![no_std]

/// The generated tables (`zscan mesh`).
#[allow(clippy::all)]
pub mod bunny {
    include!("bunny.rs");
}

/// The coarse bunny's generated tables (`zscan mesh --cluster 6`).
#[allow(clippy::all)]
pub mod coarse {
    include!("coarse.rs");
}

use zscan::prelude::*;
use zscan::visibility::{Plan, PlanError};

/// The bunny lit by the scene's lights with `material`, Gouraud shaded, its normals from flash.
pub fn lit_bunny(material: Material) -> Object<'static> {
    let mut o = Object::new(bunny::MESH);
    o.intensities = Intensities::Lit {
        material,
        normals: &bunny::NORMALS,
    };
    o
}

/// Plans `scene` (its objects all the bunny: their facts are [`bunny::FACTS`], read from
/// flash) within `budget` bytes, `order` receiving the drawing order; the plan sizes the
/// memory ([`PlanSizes`]). At most 8 objects (more: the planner refuses, `TooFewSlots`).
pub fn plan_bunnies(
    scene: &Scene<'_>,
    budget: usize,
    order: &mut [u16],
) -> Result<Plan, PlanError> {
    const MOST: usize = 8;
    let facts = [bunny::FACTS; MOST];
    let n = scene.objects.len().min(MOST);
    plan::<4>(scene, &facts[..n], budget, order)
}

/// Draws `plan` of `scene` from `memory`, each finished band handed to `flush`.
pub fn frame<E: From<VisibilityError>>(
    scene: &Scene<'_>,
    plan: &Plan,
    order: &[u16],
    memory: PlanMemory<'_>,
    stats: &mut RenderStats,
    flush: impl FnMut(&mut Framebuffer<'_>) -> Result<(), E>,
) -> Result<(), E> {
    let renderer = Renderer::for_scene(scene).map_err(VisibilityError::from)?;
    draw_plan(&renderer, plan, order, memory, stats, flush)
}
