//! The planner's target: from a seed, a random scene of hard meshes ([`random_world`]), each
//! mesh's `MeshFacts` computed into a buffer of random length, a random budget (none, any
//! size from 1 byte to 4 MiB uniform in its bits, or unbounded) and a drawing-order slice
//! sometimes too short; then `plan`, `plan_frame` with a vertex scratch of random length, and
//! `draw_plan` with every slice of [`PlanMemory`] of random length (exact, longer or shorter,
//! [`memory`]).
//!
//! Properties: `plan` and `plan_frame` make the same plan and order; the plan's bytes are
//! within the budget and are [`PlanSizes`]' bytes; a refusal (facts, plan or frame) is an error
//! in words, and a buffer shorter than needed always is one; a plan drawn (by `draw_plan`,
//! or `plan_frame`'s back-face frame) is the z-buffer's picture pixel for pixel, 16-bit where
//! the plan chose 16 bits, whenever every slice is long enough (and also when a short slice is
//! not reached). An orthographic camera is refused in words.

use zscan::output::Framebuffer;
use zscan::render::{
    CompactVertex, PolygonRows, PolygonTop, PreparedVertex, RenderStats, Renderer,
};
use zscan::visibility::{
    draw_plan, plan, plan_frame, DepthWidth, MeshFacts, PlanMemory, PlanSizes, PlannedFrame,
};

use super::values::{bits_size, chance, memory, one_of, size};
use super::world::{first_difference, random_world, zbuffer, Shades};
use super::{hash, Outcome, Rng};

/// One case of the target (module doc).
pub(super) fn run(seed: u64) -> Result<Outcome, String> {
    let mut rng = Rng::new(seed);
    let world = match random_world(&mut rng, true, Shades::All) {
        Ok(w) => w,
        Err(e) => return Ok(Err(e)),
    };
    let objects = world.objects()?;
    let scene = world.scene(&objects);
    let (w, _) = world.size();
    // The facts, each into a buffer of random length.
    let mut short_words = false;
    let mut words: Vec<Vec<u32>> = objects
        .iter()
        .map(|o| {
            let needed = MeshFacts::words_needed(&o.mesh);
            let n = if chance(&mut rng, 90) {
                needed
            } else {
                memory(&mut rng, needed)
            };
            short_words |= n < needed;
            vec![0; n]
        })
        .collect();
    let facts: Result<Vec<MeshFacts<'_>>, String> = objects
        .iter()
        .zip(words.iter_mut())
        .enumerate()
        .map(|(i, (o, w))| MeshFacts::of(&o.mesh, w).map_err(|e| format!("object {i}: {e}")))
        .collect();
    let facts = match facts {
        Ok(f) if short_words => return Err(format!("facts made from a short buffer: {f:?}")),
        Ok(f) => f,
        Err(e) if short_words => return Ok(Err(e)),
        Err(e) => return Err(format!("facts refused with enough words: {e}")),
    };
    let budget = match size(&mut rng, 0, 9) {
        0 => 0,
        1 => usize::MAX,
        _ => bits_size(&mut rng, 1 << 22),
    };
    let slots = if chance(&mut rng, 5) {
        size(&mut rng, 0, objects.len())
    } else {
        objects.len()
    };
    let mut order = vec![0u16; slots];
    let planned = plan::<4>(&scene, &facts, budget, &mut order);
    let plan = match planned {
        Ok(p) => p,
        Err(e) => {
            if world.camera.is_orthographic() || slots < objects.len() {
                return Ok(Err(e.to_string()));
            }
            // Over the budget is the one refusal of a perspective scene with enough slots.
            return match e {
                zscan::visibility::PlanError::OverBudget { needed, .. } if needed > budget => {
                    Ok(Err(e.to_string()))
                }
                _ => Err(format!("plan refused: {e}")),
            };
        }
    };
    if world.camera.is_orthographic() {
        return Err(format!("an orthographic camera was planned: {plan}"));
    }
    if plan.ram_bytes() > budget {
        return Err(format!("over the budget of {budget}: {plan}"));
    }
    let sizes = PlanSizes::of(&plan, &scene);
    if sizes.bytes::<4>() != plan.buffers.total() {
        return Err(format!("sizes {sizes:?} are not the plan's bytes: {plan}"));
    }
    let renderer = match Renderer::for_scene(&scene) {
        Ok(r) => r,
        Err(e) => return Err(format!("planned, but the renderer refuses: {e}; {plan}")),
    };
    // `plan_frame` with a scratch of random length: the same plan and order.
    let largest = objects.iter().map(|o| o.mesh.vertices().len()).max();
    let scratch_needed = largest.unwrap_or(0);
    let mut scratch = vec![PreparedVertex::<4>::default(); memory(&mut rng, scratch_needed)];
    let mut frame_order = vec![0u16; slots];
    let framed = plan_frame(&renderer, &facts, budget, &mut frame_order, &mut scratch)
        .map_err(|e| format!("plan_frame refused what plan made ({plan}): {e}"))?;
    if *framed.plan() != plan {
        return Err(format!("plan_frame made {} against {plan}", framed.plan()));
    }
    let bits16 = plan.depth == DepthWidth::U16;
    let want = zbuffer(&renderer, bits16);
    let mut fingerprint = vec![hash([
        plan.visibility as u64,
        plan.depth.bytes() as u64,
        plan.band_rows as u64,
        plan.buffers.total() as u64,
    ])];
    if let PlannedFrame::BackFace(frame) = framed {
        if frame.order() != &order[..objects.len()] {
            return Err(format!(
                "plan_frame's order {:?} against {order:?}",
                frame.order()
            ));
        }
        let (vw, vh) = world.size();
        let mut pixels = vec![0u8; vw as usize * vh as usize];
        let mut fb = Framebuffer::new(&mut pixels, vw, vh).map_err(|e| e.to_string())?;
        let drawn = frame.render(&mut fb, &mut RenderStats::default());
        let short = scratch.len() < scratch_needed;
        match (drawn, &want) {
            (Ok(()), Ok(z)) => {
                if let Some(d) = first_difference(&pixels, z, w) {
                    return Err(format!("plan_frame's back faces: {d}; {plan}"));
                }
                fingerprint.push(hash(pixels.iter().map(|&p| p as u64)));
            }
            (Err(e), _) if short || want.is_err() => {
                fingerprint.push(hash(e.to_string().bytes().map(u64::from)))
            }
            (Err(e), _) => return Err(format!("plan_frame's back faces refused: {e}; {plan}")),
            (Ok(()), Err(e)) => return Err(format!("planned, the z-buffer refuses: {e}; {plan}")),
        }
    }
    // `draw_plan` with slices of random lengths.
    let n = PlanSizes {
        pixels: memory(&mut rng, sizes.pixels),
        depth16: memory(&mut rng, sizes.depth16),
        depth32: memory(&mut rng, sizes.depth32),
        vertices: memory(&mut rng, sizes.vertices),
        polygons: memory(&mut rng, sizes.polygons),
        compact_vertices: memory(&mut rng, sizes.compact_vertices),
        levels: memory(&mut rng, sizes.levels),
        tops: memory(&mut rng, sizes.tops),
        mask: memory(&mut rng, sizes.mask),
    };
    let enough = [
        (n.pixels, sizes.pixels),
        (n.depth16, sizes.depth16),
        (n.depth32, sizes.depth32),
        (n.vertices, sizes.vertices),
        (n.polygons, sizes.polygons),
        (n.compact_vertices, sizes.compact_vertices),
        (n.levels, sizes.levels),
        (n.tops, sizes.tops),
        (n.mask, sizes.mask),
    ]
    .iter()
    .all(|(given, needed)| given >= needed);
    let junk = one_of(&mut rng, &[0u8, 0x5A, 0xFF]);
    let (mut pixels, mut depth16, mut depth32) = (
        vec![junk; n.pixels],
        vec![junk as u16; n.depth16],
        vec![junk as u32; n.depth32],
    );
    let mut vertices = vec![PreparedVertex::<4>::default(); n.vertices];
    let mut polygons = vec![PolygonRows::default(); n.polygons];
    let mut compact_vertices = vec![CompactVertex::default(); n.compact_vertices];
    let (mut levels, mut tops) = (vec![junk; n.levels], vec![PolygonTop::default(); n.tops]);
    let mut mask = vec![junk as u32; n.mask];
    let mem = PlanMemory {
        pixels: &mut pixels,
        depth16: &mut depth16,
        depth32: &mut depth32,
        vertices: &mut vertices,
        polygons: &mut polygons,
        compact_vertices: &mut compact_vertices,
        levels: &mut levels,
        tops: &mut tops,
        mask: &mut mask,
    };
    let (vw, vh) = world.size();
    let mut picture = vec![scene.background; vw as usize * vh as usize];
    let mut outside = false;
    let drawn = draw_plan(
        &renderer,
        &plan,
        &order,
        mem,
        &mut RenderStats::default(),
        |band| {
            for (y, row) in band.rows() {
                let at = y as usize * vw as usize;
                match picture.get_mut(at..at + vw as usize) {
                    Some(dst) if row.len() == vw as usize => dst.copy_from_slice(row),
                    _ => outside = true,
                }
            }
            Ok::<(), zscan::visibility::VisibilityError>(())
        },
    );
    if outside {
        return Err(format!(
            "draw_plan handed a band row outside the picture; {plan}"
        ));
    }
    match (drawn, &want) {
        (Ok(()), Ok(z)) => {
            if let Some(d) = first_difference(&picture, z, w) {
                return Err(format!("draw_plan: {d}; {plan}"));
            }
            fingerprint.push(hash(picture.iter().map(|&p| p as u64)));
        }
        (Err(e), _) if !enough || want.is_err() => {
            fingerprint.push(hash(e.to_string().bytes().map(u64::from)))
        }
        (Err(e), _) => return Err(format!("draw_plan refused with enough memory: {e}; {plan}")),
        (Ok(()), Err(e)) => return Err(format!("drawn, but the z-buffer refuses: {e}; {plan}")),
    }
    Ok(Ok(fingerprint))
}
