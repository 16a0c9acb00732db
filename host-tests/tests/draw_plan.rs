//! The plan's one draw entry (`zscan::visibility::draw_plan`): every plan the planner makes,
//! under budgets from 8 KB to 1 MB, draws the z-buffer's picture (the 16-bit one where it
//! chose 16 bits) pixel for pixel from memory of exactly the plan's sizes, or the planner
//! refuses in words; on the standard scenes and on 1,000 random scenes (spheres, tori and
//! cubes, lit and unlit, Gouraud, flat and Phong, in four viewports).

use std::collections::BTreeMap;

use zscan::geometry::camera::{Camera, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::{torus, torus_sizes, unit_cube, uv_sphere, uv_sphere_sizes};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::lighting::{Light, Material};
use zscan::raster::triangle::ShadeMode;
use zscan::render::{BandPart, BandScratch, PreparedVertex, RenderError, RenderStats, Renderer};
use zscan::scene::{Intensities, Object, Scene};
use zscan::visibility::{
    draw_plan, plan, DepthWidth, LayoutReason, Plan, PlanMemory, PlanSizes, Visibility,
    VisibilityError,
};
use zscan_host::core_render::{self, mesh_facts, render_picture, scene_of, to_core};
use zscan_host::scenes::standard_scene;
use zscan_host::test_rng::XorShift;

/// The z-buffer's whole-frame picture at 16 or 32 bits.
fn zbuffer(scene: &Scene<'_>, bits16: bool) -> Vec<u8> {
    let renderer = Renderer::for_scene(scene).unwrap();
    let vp = *scene.camera.viewport();
    let nv: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let mut scratch = vec![PreparedVertex::default(); nv.max(1)];
    let band = BandScratch {
        vertices: &mut scratch,
        polygons: &mut [],
    };
    let size = (vp.width, vp.height);
    if bits16 {
        render_picture::<u16, 4>(&renderer, size, None, band)
            .unwrap()
            .0
    } else {
        render_picture::<u32, 4>(&renderer, size, None, band)
            .unwrap()
            .0
    }
}

/// What the plan chose, for the tally.
type Key = (&'static str, usize, String);

/// Plans `scene` within `budget` and draws it through the entry (the host's `draw_plan`,
/// memory of exactly [`PlanSizes`]); checks the sizes' bytes against the plan's and the
/// picture against the z-buffer's. `Err` is the planner's refusal in words.
fn check(scene: &Scene<'_>, budget: usize, what: &str) -> Result<Key, String> {
    let mut pairs = Vec::new();
    let facts = mesh_facts(scene, &mut pairs)?;
    let mut order = vec![0u16; scene.objects.len()];
    let plan = plan::<4>(scene, &facts, budget, &mut order).map_err(|e| e.to_string())?;
    let sizes = PlanSizes::of(&plan, scene);
    assert_eq!(sizes.bytes::<4>(), plan.buffers.total(), "{what}: {plan}");
    assert!(plan.buffers.total() <= budget, "{what}: {plan}");
    let renderer = Renderer::for_scene(scene).unwrap();
    let (pixels, _) = core_render::draw_plan(&renderer, &plan, &order)
        .unwrap_or_else(|e| panic!("{what}: {plan}\n{e}"));
    let z = zbuffer(scene, plan.depth == DepthWidth::U16);
    let wrong = pixels.iter().zip(&z).filter(|(a, b)| a != b).count();
    assert_eq!(wrong, 0, "{what}: {plan}");
    Ok((
        plan.visibility.name(),
        plan.depth.bytes(),
        format!("{:?}", plan.layout_reason),
    ))
}

const BUDGETS: [usize; 8] = [
    8 << 10,
    16 << 10,
    32 << 10,
    64 << 10,
    128 << 10,
    256 << 10,
    512 << 10,
    1 << 20,
];

#[test]
fn the_standard_scenes_draw_through_the_entry_under_every_budget() {
    let mut seen = BTreeMap::new();
    for name in ["quad", "cube", "sphere", "bunny"] {
        let core = to_core(&standard_scene(name).unwrap()).unwrap();
        let objects = [core.object(ShadeMode::GouraudExact).unwrap()];
        let scene = scene_of(&objects, core.camera);
        for budget in BUDGETS {
            match check(&scene, budget, &format!("{name} within {budget}")) {
                Ok(key) => *seen.entry(key).or_insert(0) += 1,
                Err(e) => assert!(e.contains("bytes"), "{name} within {budget}: {e}"),
            }
        }
    }
    println!("standard scenes: {seen:?}");
    assert!(seen.keys().any(|k| k.0 == "backface"));
    assert!(seen.keys().any(|k| k.2 == "CompactBands"));
}

/// One random object's tables: a sphere, a torus or the unit cube, with its levels and
/// normals.
struct Tables {
    vertices: Vec<Vec3>,
    indices: Vec<u16>,
    levels: Vec<u8>,
    normals: Vec<Vec3>,
    transform: Affine3,
    kind: u64,
}

fn c(v: f64) -> Coord {
    Coord::from_num(v)
}

fn random_tables(rng: &mut XorShift) -> Tables {
    let (vertices, indices) = match rng.below(3) {
        0 => {
            let (seg, rings) = (4 + rng.below(37) as u16, 3 + rng.below(22) as u16);
            let (nv, ni) = uv_sphere_sizes(seg, rings);
            let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            uv_sphere(seg, rings, c(rng.uniform(0.3, 1.0)), &mut vs, &mut is).unwrap();
            (vs, is)
        }
        1 => {
            let (seg, sides) = (6 + rng.below(10) as u16, 3 + rng.below(5) as u16);
            let (nv, ni) = torus_sizes(seg, sides);
            let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            let (a, b) = (rng.uniform(0.4, 0.9), rng.uniform(0.1, 0.3));
            torus(seg, sides, c(a), c(b), &mut vs, &mut is).unwrap();
            let tris = is
                .chunks(4)
                .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
                .collect();
            (vs, tris)
        }
        _ => {
            let cube = unit_cube();
            (cube.vertices().to_vec(), triangles(&cube))
        }
    };
    let levels = (0..vertices.len()).map(|_| rng.below(256) as u8).collect();
    let mesh = Mesh::new(&vertices, &indices, PolygonSizes::Uniform(3)).unwrap();
    let mut normals = vec![Vec3::ZERO; vertices.len()];
    mesh.vertex_normals(&mut normals).unwrap();
    let spread = |rng: &mut XorShift| c(rng.uniform(-2.0, 2.0));
    let transform = Affine3::builder()
        .rotate_x(BinaryAngle::from_degrees(rng.below(360) as i32))
        .rotate_y(BinaryAngle::from_degrees(rng.below(360) as i32))
        .translate(Vec3::new(
            spread(rng),
            spread(rng),
            c(rng.uniform(-6.0, 2.5)),
        ))
        .build()
        .unwrap();
    Tables {
        vertices,
        indices,
        levels,
        normals,
        transform,
        kind: rng.below(5),
    }
}

/// A mesh's polygons fanned into triangles.
fn triangles(mesh: &Mesh<'_>) -> Vec<u16> {
    let fan = |p: &[u16]| {
        (1..p.len() - 1)
            .flat_map(|i| [p[0], p[i], p[i + 1]])
            .collect::<Vec<_>>()
    };
    mesh.polygons().flat_map(fan).collect()
}

/// The object of `t`: per-vertex levels (Gouraud), flat per-vertex levels, or lit by the
/// scene's light (Gouraud, flat or Phong).
fn object(t: &Tables) -> Object<'_> {
    let mesh = Mesh::new(&t.vertices, &t.indices, PolygonSizes::Uniform(3)).unwrap();
    let mut o = Object::new(mesh);
    o.transform = t.transform;
    let lit = Intensities::Lit {
        material: Material::from_thousandths(100, 700, 300, 8),
        normals: &t.normals,
    };
    (o.intensities, o.shade) = match t.kind {
        0 => (Intensities::PerVertex(&t.levels), ShadeMode::GouraudExact),
        1 => (Intensities::PerVertex(&t.levels), ShadeMode::Flat),
        2 => (lit, ShadeMode::GouraudExact),
        3 => (lit, ShadeMode::Flat),
        _ => (lit, ShadeMode::Phong),
    };
    o
}

const LIGHTS: [Light; 1] = [Light::Directional {
    toward: Vec3::from_int(1, 2, 3),
    intensity: 200,
}];

fn camera(w: u16, h: u16) -> Camera {
    let lens = Lens::new(
        BinaryAngle::from_degrees(60),
        Coord::lit("0.5"),
        Coord::lit("40"),
    );
    let up = Vec3::from_int(0, 1, 0);
    Camera::look_at(
        Vec3::from_int(0, 0, 6),
        Vec3::ZERO,
        up,
        lens,
        Viewport::new(w, h),
    )
    .unwrap()
}

/// 1,000 random scenes of 1 to 4 objects in a 64 × 48 to 160 × 120 frame, each under a budget
/// from 8 KB to 1 MB (log-uniform, or one in two at an edge where one band row fits with
/// 16-bit depth and not with 32-bit: with the vertex stage per band, or in compact bands): the entry draws the
/// z-buffer's picture, or the planner refuses in words. The plans met cover back faces alone,
/// every z-buffer layout at 32 bits, and compact bands and bands with the vertex stage per band
/// at 16 bits: the planner takes 16 bits only when no 32-bit layout fits, not even one row with
/// the vertex stage per band (`5·w + 28·V` bytes for the largest mesh's `V` vertices), and a
/// whole frame or bands with every object's vertices at 16 bits then need more than that
/// (`3·w·h`; `3·w + 28·ΣV + 4·P` with `P > w/2` for these meshes), so it never makes them here.
#[test]
fn random_scenes_draw_through_the_entry_or_are_refused_in_words() {
    let mut rng = XorShift::new(0x28_0002);
    let mut seen = BTreeMap::new();
    let mut refused = 0;
    let frames = [(64, 48), (96, 64), (128, 96), (160, 120)];
    for case in 0..1000 {
        let n = 1 + rng.below(4) as usize;
        let tables: Vec<Tables> = (0..n).map(|_| random_tables(&mut rng)).collect();
        let objects: Vec<Object<'_>> = tables.iter().map(object).collect();
        let (w, h) = frames[rng.below(4) as usize];
        let scene = Scene {
            lights: &LIGHTS,
            ambient: 30,
            ..scene_of(&objects, camera(w, h))
        };
        let largest = tables.iter().map(|t| t.vertices.len()).max().unwrap_or(0);
        let compact = zscan::render::CompactSizes::of(&scene).bytes(w, 1, 2);
        let budget = match rng.below(4) {
            0 => 28 * largest + 4 * w as usize,
            1 => compact + w as usize,
            _ => (8192.0 * 128f64.powf(rng.unit())) as usize,
        }
        .clamp(8 << 10, 1 << 20);
        match check(&scene, budget, &format!("case {case} within {budget}")) {
            Ok(key) => *seen.entry(key).or_insert(0) += 1,
            Err(e) => {
                assert!(e.contains("bytes"), "case {case}: {e}");
                refused += 1;
            }
        }
    }
    println!("random scenes: {seen:?}, refused {refused}");
    assert!(seen.keys().any(|k| k.0 == "backface"));
    let layouts = [
        (4, LayoutReason::WholeFrame),
        (4, LayoutReason::BandsVertexStageOnce),
        (4, LayoutReason::CompactBands),
        (4, LayoutReason::BandsVertexStagePerBand),
        (2, LayoutReason::CompactBands),
        (2, LayoutReason::BandsVertexStagePerBand),
    ];
    for (depth, layout) in layouts {
        assert!(
            seen.contains_key(&("zbuffer", depth, format!("{layout:?}"))),
            "no plan of {depth}-byte depth in {layout:?}: {seen:?}"
        );
    }
}

/// The standard bunny's plan within 32 KB (compact bands), drawn from memory one element
/// short in each part it uses: the entry names the part and both sizes, and draws nothing.
#[test]
fn a_short_part_of_the_memory_is_named_with_its_sizes() {
    let core = to_core(&standard_scene("bunny").unwrap()).unwrap();
    let objects = [core.object(ShadeMode::GouraudExact).unwrap()];
    let scene = scene_of(&objects, core.camera);
    let mut pairs = Vec::new();
    let facts = mesh_facts(&scene, &mut pairs).unwrap();
    let mut order = [0u16];
    let plan = plan::<4>(&scene, &facts, 32 << 10, &mut order).unwrap();
    assert_eq!(plan.layout_reason, LayoutReason::CompactBands, "{plan}");
    let renderer = Renderer::for_scene(&scene).unwrap();
    let n = PlanSizes::of(&plan, &scene);
    let depth_is_16 = plan.depth == DepthWidth::U16;
    for short in [
        BandPart::Pixels,
        BandPart::Depths,
        BandPart::Vertices,
        BandPart::Polygons,
    ] {
        let less = |part: BandPart, k: usize| k - (part == short) as usize;
        let mut pixels = vec![0u8; less(BandPart::Pixels, n.pixels)];
        let depth = if depth_is_16 { n.depth16 } else { n.depth32 };
        let (mut d16, mut d32) = (vec![0u16; n.depth16], vec![0u32; n.depth32]);
        if depth_is_16 {
            d16.truncate(less(BandPart::Depths, depth));
        } else {
            d32.truncate(less(BandPart::Depths, depth));
        }
        let mut cv = vec![Default::default(); less(BandPart::Vertices, n.compact_vertices)];
        let mut tops = vec![Default::default(); less(BandPart::Polygons, n.tops)];
        let memory = PlanMemory {
            pixels: &mut pixels,
            depth16: &mut d16,
            depth32: &mut d32,
            compact_vertices: &mut cv,
            tops: &mut tops,
            ..PlanMemory::default()
        };
        let mut bands = 0;
        let mut stats = RenderStats::default();
        let e = draw_plan(&renderer, &plan, &order, memory, &mut stats, |_| {
            bands += 1;
            Ok::<(), VisibilityError>(())
        })
        .unwrap_err();
        let needed = match short {
            BandPart::Pixels => n.pixels,
            BandPart::Depths => depth,
            BandPart::Vertices => n.compact_vertices,
            _ => n.tops,
        };
        let expected = VisibilityError::Render(RenderError::BandMemoryTooSmall {
            part: short,
            given: needed - 1,
            needed,
        });
        assert_eq!((e, bands), (expected, 0));
        let words = e.to_string();
        assert!(words.contains(&needed.to_string()), "{words}");
    }
}

/// A plan the planner never makes (the painter; a z-buffer without depth) is refused in
/// words, nothing drawn.
#[test]
fn a_hand_made_plan_is_refused_in_words() {
    let objects = [Object::new(unit_cube())];
    let scene = scene_of(&objects, camera(32, 24));
    let mut order = [0u16];
    let made = plan::<4>(
        &scene,
        &mesh_facts(&scene, &mut Vec::new()).unwrap(),
        1 << 20,
        &mut order,
    )
    .unwrap();
    let renderer = Renderer::for_scene(&scene).unwrap();
    for (visibility, depth) in [
        (Visibility::Painter, DepthWidth::None),
        (Visibility::ZBuffer, DepthWidth::None),
        (Visibility::BackFace, DepthWidth::U32),
    ] {
        let hand = Plan {
            visibility,
            depth,
            ..made
        };
        let mut pixels = vec![0u8; 32 * 24];
        let mut vertices = vec![PreparedVertex::default(); 8];
        let memory = PlanMemory {
            pixels: &mut pixels,
            vertices: &mut vertices,
            ..PlanMemory::default()
        };
        let mut stats = RenderStats::default();
        let e = draw_plan(&renderer, &hand, &order, memory, &mut stats, |_| {
            Ok::<(), VisibilityError>(())
        })
        .unwrap_err();
        assert_eq!(
            e,
            VisibilityError::NotPlanned {
                method: visibility.name(),
                depth_bytes: depth.bytes()
            }
        );
        assert!(e.to_string().contains("not one the planner makes"), "{e}");
        assert_eq!(stats.pixels_covered, 0);
    }
}

/// The plan's sizes in bytes are the plan's buffers, for the layouts of the standard bunny
/// from 1 MB down to a few kilobytes (the unused slices stay empty).
#[test]
fn plan_sizes_are_the_plan_buffers() {
    let core = to_core(&standard_scene("bunny").unwrap()).unwrap();
    let objects = [core.object(ShadeMode::GouraudExact).unwrap()];
    let scene = scene_of(&objects, core.camera);
    let mut pairs = Vec::new();
    let facts = mesh_facts(&scene, &mut pairs).unwrap();
    let mut order = [0u16];
    for budget in [1 << 20, 200_000, 80_000, 40_000, 30_000] {
        let plan = plan::<4>(&scene, &facts, budget, &mut order).unwrap();
        let n = PlanSizes::of(&plan, &scene);
        assert_eq!(n.bytes::<4>(), plan.buffers.total(), "{plan}");
        let rows = core.camera.viewport().width as usize * plan.band_rows as usize;
        assert_eq!(n.pixels, rows, "{plan}");
        let depth = [n.depth16, n.depth32];
        assert_eq!(
            depth,
            if plan.depth == DepthWidth::U16 {
                [rows, 0]
            } else {
                [0, rows]
            }
        );
    }
}
