//! `zscan mesh`'s module of the standard bunny (`examples/flash-mesh/src/bunny.rs`, written by
//! `zscan mesh host-tests/meshes/bunny.obj --centre --turn-y 90 --fit 0.7`): it is what the
//! tool writes today, it `include!`s and builds, its tables are the standard bunny's, its
//! normals and planner facts are what a device would compute, and it draws `frame_bunny`'s
//! checksum (directly, and through the planner's entry from its `FACTS`).

mod bunny {
    include!("../../examples/flash-mesh/src/bunny.rs");
}

use zscan::output::{DepthBuffer, Framebuffer};
use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
use zscan::render::{
    CompactVertex, PolygonRows, PolygonTop, PreparedVertex, RenderStats, Renderer,
};
use zscan::scene::{Intensities, Object};
use zscan::visibility::{draw_plan, plan, MeshFacts, PlanMemory, PlanSizes};
use zscan_host::cli::bench::cases;
use zscan_host::cli::mesh::mesh_source;
use zscan_host::core_render::{scene_of, to_core};
use zscan_host::scenes::{bunny_mesh, standard_scene, STANDARD_BUNNY};

const MODULE: &str = include_str!("../../examples/flash-mesh/src/bunny.rs");

/// `frame_bunny`'s picture and checksum, as `zscan bench --checksums` prints it.
fn frame_bunny() -> (Vec<u8>, u32) {
    let case = cases::CASES
        .iter()
        .find(|c| c.name == "frame_bunny")
        .unwrap();
    let mut pixels = vec![0u8; cases::FB_LEN];
    let mut fb = Framebuffer::new(&mut pixels, cases::WIDTH, cases::HEIGHT).unwrap();
    let mut storage = Box::new(cases::Storage::new());
    (case.run)(&mut fb, &mut storage);
    let sum = cases::fnv1a(&pixels);
    (pixels, sum)
}

/// The generated bunny with the standard scene's per-vertex levels, Gouraud shaded.
fn object(levels: &[u8]) -> Object<'_> {
    let mut o = Object::new(bunny::MESH);
    o.intensities = Intensities::PerVertex(levels);
    o.shade = ShadeMode::GouraudExact;
    o.ramp = LuminanceRamp::GREY;
    o
}

#[test]
fn the_committed_module_is_what_the_tool_writes() {
    let mesh = bunny_mesh().unwrap();
    let text = mesh_source(
        &mesh,
        &STANDARD_BUNNY,
        "bunny.obj --centre --turn-y 90 --fit 0.7",
    )
    .unwrap();
    assert!(
        text == MODULE,
        "examples/flash-mesh/src/bunny.rs is stale: regenerate it with `zscan mesh \
         host-tests/meshes/bunny.obj --centre --turn-y 90 --fit 0.7 -o \
         examples/flash-mesh/src/bunny.rs`"
    );
}

#[test]
fn its_tables_normals_and_facts_are_the_standard_bunnys() {
    let standard = to_core(&standard_scene("bunny").unwrap()).unwrap();
    assert_eq!(bunny::VERTICES.as_slice(), standard.vertices.as_slice());
    assert_eq!(bunny::INDICES.as_slice(), standard.indices.as_slice());
    let mut normals = vec![Default::default(); bunny::VERTICES.len()];
    bunny::MESH.vertex_normals(&mut normals).unwrap();
    assert_eq!(bunny::NORMALS.as_slice(), normals.as_slice());
    let mut words = vec![0u32; MeshFacts::words_needed(&bunny::MESH)];
    assert_eq!(
        bunny::FACTS,
        MeshFacts::of(&bunny::MESH, &mut words).unwrap()
    );
}

/// Drawn as `frame_bunny` draws (whole frame, 16-bit depth, the standard camera and levels):
/// the same checksum.
#[test]
fn it_draws_frame_bunnys_checksum() {
    let standard = to_core(&standard_scene("bunny").unwrap()).unwrap();
    assert!(standard.per_vertex);
    let objects = [object(&standard.intensities)];
    let scene = scene_of(&objects, standard.camera);
    let renderer = Renderer::for_scene(&scene).unwrap();
    let (mut pixels, mut depths) = (vec![0u8; cases::FB_LEN], vec![0u16; cases::FB_LEN]);
    let mut fb = Framebuffer::new(&mut pixels, cases::WIDTH, cases::HEIGHT).unwrap();
    let mut depth = DepthBuffer::new(&mut depths, cases::WIDTH, cases::HEIGHT).unwrap();
    let mut scratch = vec![PreparedVertex::default(); bunny::VERTICES.len()];
    let mut stats = RenderStats::default();
    zscan::render::render_scene(&renderer, &mut fb, &mut depth, &mut scratch, &mut stats).unwrap();
    let (_, expected) = frame_bunny();
    assert_eq!(cases::fnv1a(&pixels), expected);
}

/// Planned from its `FACTS` (nothing computed at start) under 1 MB, 64 KB and 32 KB and drawn
/// through `draw_plan`: `frame_bunny`'s picture in every layout the budgets bring.
#[test]
fn planned_from_its_facts_it_draws_frame_bunny() {
    let standard = to_core(&standard_scene("bunny").unwrap()).unwrap();
    let objects = [object(&standard.intensities)];
    let scene = scene_of(&objects, standard.camera);
    let renderer = Renderer::for_scene(&scene).unwrap();
    let (expected, sum) = frame_bunny();
    for budget in [1 << 20, 64 << 10, 32 << 10] {
        let mut order = [0u16];
        let plan = plan::<4>(&scene, &[bunny::FACTS], budget, &mut order).unwrap();
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
        let mut picture = vec![0u8; cases::FB_LEN];
        let w = cases::WIDTH as usize;
        let mut stats = RenderStats::default();
        draw_plan(&renderer, &plan, &order, memory, &mut stats, |band| {
            for (y, row) in band.rows() {
                picture[y as usize * w..][..w].copy_from_slice(row);
            }
            Ok::<(), zscan::visibility::VisibilityError>(())
        })
        .unwrap();
        let wrong = picture
            .iter()
            .zip(&expected)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(wrong, 0, "within {budget}: {plan}");
        assert_eq!(cases::fnv1a(&picture), sum);
    }
}

/// `examples/flash-mesh/src/coarse.rs`, the one-bit boards' bunny, is what `zscan mesh
/// --cluster 6` writes today from the standard bunny.
#[test]
fn the_committed_coarse_module_is_what_the_tool_writes() {
    let mesh = zscan_host::cluster::cluster(&bunny_mesh().unwrap(), 6).unwrap();
    let text = mesh_source(
        &mesh,
        &STANDARD_BUNNY,
        "bunny.obj --cluster 6 --centre --turn-y 90 --fit 0.7",
    )
    .unwrap();
    assert!(
        text == include_str!("../../examples/flash-mesh/src/coarse.rs"),
        "examples/flash-mesh/src/coarse.rs is stale: regenerate it with `zscan mesh \
         host-tests/meshes/bunny.obj --cluster 6 --centre --turn-y 90 --fit 0.7 -o \
         examples/flash-mesh/src/coarse.rs`"
    );
}
