//! Two objects drawn by the scene planner within 32 KB of caller memory: the plan picks the
//! method, depth width and bands ([`plan`]); [`draw_plan`] draws it from memory of the sizes
//! the plan gives ([`PlanSizes`]), each finished band flushed to a 160 × 120 "display" (here a
//! `Vec`). Run: `cargo run --example two_objects`.
use zscan::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut objects = [unit_cube(), unit_cube()].map(Object::new);
    objects[0].transform = Affine3::rotation_y(BinaryAngle::from_degrees(30));
    objects[1].transform = Affine3::translation(Vec3::from_int(1, 0, -1));
    let fov = BinaryAngle::from_degrees(60);
    let lens = Lens::new(fov, Coord::lit("0.5"), Coord::lit("20"));
    let (eye, up) = (Vec3::from_int(0, 1, 4), Vec3::from_int(0, 1, 0));
    let camera = Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(160, 120))?;
    let scene = Scene {
        camera,
        objects: &objects,
        background: 0,
        ambient: 255,
        lights: &[],
    };
    let mut words = objects
        .each_ref()
        .map(|o| vec![0; MeshFacts::words_needed(&o.mesh)]);
    let facts = (objects.iter().zip(&mut words)).map(|(o, w)| MeshFacts::of(&o.mesh, w));
    let facts = facts.collect::<Result<Vec<_>, _>>()?;
    let mut order = [0u16; 2];
    let plan = plan::<4>(&scene, &facts, 32 * 1024, &mut order)?;
    let n = PlanSizes::of(&plan, &scene);
    let memory = PlanMemory {
        pixels: &mut vec![0; n.pixels],
        depth16: &mut vec![0; n.depth16],
        depth32: &mut vec![0; n.depth32],
        vertices: &mut vec![PreparedVertex::default(); n.vertices],
        polygons: &mut vec![PolygonRows::default(); n.polygons],
        compact_vertices: &mut vec![CompactVertex::default(); n.compact_vertices],
        levels: &mut vec![0; n.levels],
        tops: &mut vec![PolygonTop::default(); n.tops],
        mask: &mut vec![0; n.mask],
    };
    let (renderer, mut stats) = (Renderer::for_scene(&scene)?, RenderStats::default());
    let mut display = vec![0u8; 160 * 120];
    draw_plan(&renderer, &plan, &order, memory, &mut stats, |band| {
        for (y, row) in band.rows() {
            display[y as usize * 160..][..160].copy_from_slice(row);
        }
        Ok::<(), Error>(())
    })?;
    println!("{plan}\n{} pixels drawn", stats.pixels_covered);
    Ok(())
}
