//! The reverse painter (`zscan::visibility::render_reverse_painter`, course ch. 3 algorithm
//! 3.2) against the 32-bit z-buffer: on random scenes of separable convex objects (unit cubes
//! and UV spheres, turned and scaled, overlapping on screen at distinct depths) its picture is
//! the z-buffer's pixel for pixel; a scene outside the planner's rule 1 is refused in words,
//! exactly where the planner refuses back faces alone; a short mask names its words.

use zscan::geometry::camera::{Camera, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::{
    torus, torus_sizes, unit_cube, uv_sphere, uv_sphere_normals, uv_sphere_sizes,
};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::Mesh;
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::lighting::{Light, Material};
use zscan::output::{mask_words_needed, Framebuffer};
use zscan::raster::triangle::ShadeMode;
use zscan::render::{BandPart, PreparedVertex, RenderError, RenderStats, Renderer};
use zscan::scene::{Intensities, Object, Scene};
use zscan::visibility::{render_reverse_painter, MethodReason, Visibility, VisibilityError};
use zscan_host::core_render::{
    mesh_facts, render_planned, render_visible, reverse_picture, scene_of,
};
use zscan_host::test_rng::XorShift;

fn camera(w: u16, h: u16) -> Camera {
    let lens = Lens::new(
        BinaryAngle::from_degrees(60),
        Coord::lit("0.5"),
        Coord::lit("50"),
    );
    let eye = Vec3::from_int(0, 0, 6);
    Camera::look_at(
        eye,
        Vec3::ZERO,
        Vec3::from_int(0, 1, 0),
        lens,
        Viewport::new(w, h),
    )
    .unwrap()
}

/// One random object: a mesh (a unit cube centred by its transform, or a UV sphere), its
/// levels and its transform.
struct Tables {
    mesh: Option<(Vec<Vec3>, Vec<u16>)>,
    levels: Vec<u8>,
    normals: Vec<Vec3>,
    transform: Affine3,
    shade: ShadeMode,
    lit: bool,
}

const LIGHTS: [Light; 1] = [Light::Directional {
    toward: Vec3::from_int(1, 2, 3),
    intensity: 200,
}];

fn random_object(rng: &mut XorShift, z: f64, spread: f64) -> Tables {
    let c = Coord::from_num;
    let (mesh, normals, size) = if rng.below(2) == 0 {
        let corner = |k: i32| Vec3::from_int(2 * (k & 1) - 1, (k & 2) - 1, (k & 4) / 2 - 1);
        (None, (0..8).map(corner).collect(), rng.uniform(0.4, 1.2))
    } else {
        let (seg, rings) = (4 + rng.below(10) as u16, 3 + rng.below(7) as u16);
        let (nv, ni) = uv_sphere_sizes(seg, rings);
        let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
        uv_sphere(seg, rings, Coord::ONE, &mut vs, &mut is).unwrap();
        let mut ns = vec![Vec3::ZERO; nv];
        uv_sphere_normals(seg, rings, &mut ns).unwrap();
        (Some((vs, is)), ns, rng.uniform(0.3, 0.8))
    };
    let n = normals.len();
    let centre = if mesh.is_none() { -0.5 } else { 0.0 };
    let transform = Affine3::builder()
        .translate(Vec3::new(c(centre), c(centre), c(centre)))
        .scale(c(size))
        .rotate_x(BinaryAngle::from_degrees(rng.below(360) as i32))
        .rotate_y(BinaryAngle::from_degrees(rng.below(360) as i32))
        .translate(Vec3::new(
            c(rng.uniform(-spread, spread)),
            c(rng.uniform(-spread, spread) * 0.75),
            c(z),
        ))
        .build()
        .unwrap();
    let kind = rng.below(5) as usize;
    let shade = [
        ShadeMode::GouraudExact,
        ShadeMode::GouraudFast,
        ShadeMode::Flat,
        ShadeMode::Phong,
        ShadeMode::GouraudExact,
    ][kind];
    Tables {
        mesh,
        levels: (0..n).map(|_| rng.below(256) as u8).collect(),
        normals,
        transform,
        shade,
        lit: kind >= 3,
    }
}

fn object(t: &Tables) -> Object<'_> {
    let mesh = match &t.mesh {
        Some((vs, is)) => {
            Mesh::new(vs, is, zscan::geometry::mesh::PolygonSizes::Uniform(3)).unwrap()
        }
        None => unit_cube(),
    };
    let mut o = Object::new(mesh);
    o.transform = t.transform;
    o.intensities = match t.lit {
        true => Intensities::Lit {
            material: Material::from_thousandths(100, 700, 300, 8),
            normals: &t.normals,
        },
        false => Intensities::PerVertex(&t.levels),
    };
    o.shade = t.shade;
    o
}

/// `objects` seen by [`camera`], lit by [`LIGHTS`].
fn lit_scene<'a>(objects: &'a [Object<'a>]) -> Scene<'a> {
    Scene {
        lights: &LIGHTS,
        ambient: 40,
        ..scene_of(objects, camera(64, 48))
    }
}

/// The reverse painter's picture of `scene` (whole frame), or its refusal.
fn reverse(scene: &Scene<'_>) -> Result<(Vec<u8>, RenderStats), VisibilityError> {
    let renderer = Renderer::for_scene(scene).unwrap();
    let vp = *scene.camera.viewport();
    reverse_picture(&renderer, (vp.width, vp.height))
}

fn zbuffer(scene: &Scene<'_>) -> Vec<u8> {
    let renderer = Renderer::for_scene(scene).unwrap();
    let vp = *scene.camera.viewport();
    let size = (vp.width, vp.height);
    render_visible(&renderer, size, Visibility::ZBuffer, None, vp.height)
        .unwrap()
        .0
}

/// 600 random scenes of 1 to 5 cubes and spheres (given levels, or lit: Gouraud or Phong), at
/// depths 0.3 to 2.5 units apart (overlapping on screen, apart or not in depth): wherever the
/// reverse painter draws, the 32-bit z-buffer's picture, pixel for pixel; wherever it
/// refuses, the planner refuses back faces alone too, for the reason the refusal names. The
/// planner's own frame (`plan_frame`, `draw_plan`) is the z-buffer's too, and it picks the
/// reverse painter exactly where a Phong object's screen box meets a nearer one's (rule 1b).
#[test]
fn random_separable_scenes_draw_the_z_buffer_picture() {
    let mut rng = XorShift::new(0x3e_2e5);
    let (mut drawn, mut several, mut hidden, mut refused) = (0, 0, 0, 0);
    let mut planned_reverse = 0;
    for case in 0..600 {
        let n = 1 + rng.below(5) as usize;
        let spread = [0.3, 1.0, 2.0][rng.below(3) as usize];
        let gap = rng.uniform(0.3, 2.5);
        let tables: Vec<Tables> = (0..n)
            .map(|k| random_object(&mut rng, 1.5 - gap * k as f64, spread))
            .collect();
        let objects: Vec<Object<'_>> = tables.iter().map(object).collect();
        let scene = lit_scene(&objects);
        let mut words = Vec::new();
        let facts = mesh_facts(&scene, &mut words).unwrap();
        let renderer = Renderer::for_scene(&scene).unwrap();
        let planned = render_planned(&renderer, &facts, usize::MAX).unwrap();
        let plan = planned.plan;
        let z = zbuffer(&scene);
        let differ = |p: &[u8]| p.iter().zip(&z).filter(|(a, b)| a != b).count();
        assert_eq!(differ(&planned.pixels), 0, "case {case}: {plan}");
        if plan.visibility == Visibility::ReversePainter {
            planned_reverse += 1;
            let MethodReason::HiddenPixelsLitPerPixel { object, nearer } = plan.method_reason
            else {
                panic!("case {case}: {plan}");
            };
            assert_eq!(objects[object].shade, ShadeMode::Phong);
            // Near to far: the nearer object is drawn first.
            let at = |i: usize| planned.order.iter().position(|&k| k as usize == i);
            assert!(at(nearer) < at(object), "case {case}: {:?}", planned.order);
            assert_eq!(
                plan.buffers.tables,
                4 * mask_words_needed(64, 48),
                "case {case}"
            );
        }
        match reverse(&scene) {
            Ok((pixels, stats)) => {
                assert_eq!(differ(&pixels), 0, "case {case}: {n} objects");
                assert!(
                    matches!(
                        plan.visibility,
                        Visibility::BackFace | Visibility::ReversePainter
                    ),
                    "case {case}: {plan}"
                );
                drawn += 1;
                several += (n > 1) as u32;
                // Pixels covered more than once, the mask deciding: what back faces alone
                // paint twice.
                hidden += (stats.pixels_covered > stats.pixels_written) as u32;
            }
            Err(VisibilityError::ReverseRefused(reason)) => {
                assert_eq!(plan.visibility, Visibility::ZBuffer, "case {case}");
                assert_eq!(plan.method_reason, reason, "case {case}");
                refused += 1;
            }
            Err(e) => panic!("case {case}: {e}"),
        }
    }
    println!(
        "drawn {drawn} (several objects {several}, objects hiding others {hidden}), refused \
         {refused}, planned as the reverse painter {planned_reverse}"
    );
    assert!(several > 50 && hidden > 20 && refused > 20 && planned_reverse > 10);
}

/// A torus (not convex) is refused before anything is drawn, naming the object; so is a scene
/// of two cubes at one depth, overlapping on screen.
#[test]
fn scenes_outside_the_rule_are_refused_in_words() {
    let (nv, ni) = torus_sizes(8, 5);
    let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
    torus(8, 5, Coord::lit("0.6"), Coord::lit("0.2"), &mut vs, &mut is).unwrap();
    let quads = Mesh::new(&vs, &is, zscan::geometry::mesh::PolygonSizes::Uniform(4)).unwrap();
    let objects = [Object::new(quads)];
    let e = reverse(&scene_of(&objects, camera(64, 48))).unwrap_err();
    assert!(
        e.to_string().contains("object 0's mesh is not convex"),
        "{e}"
    );

    let mut a = Object::new(unit_cube());
    a.transform = Affine3::translation(Vec3::new(Coord::lit("-0.7"), Coord::ZERO, Coord::ZERO));
    let mut b = Object::new(unit_cube());
    b.transform = Affine3::translation(Vec3::new(Coord::lit("-0.2"), Coord::ZERO, Coord::ZERO));
    let objects = [a, b];
    let e = reverse(&scene_of(&objects, camera(64, 48))).unwrap_err();
    assert!(
        e.to_string()
            .contains("objects 0 and 1 overlap on screen and in depth"),
        "{e}"
    );
}

/// A mask one word short is refused naming the words given and needed; nothing is drawn.
#[test]
fn a_short_mask_names_its_words() {
    let objects = [Object::new(unit_cube())];
    let scene = scene_of(&objects, camera(50, 30));
    let renderer = Renderer::for_scene(&scene).unwrap();
    let mut words = Vec::new();
    let facts = mesh_facts(&scene, &mut words).unwrap();
    let needed = mask_words_needed(50, 30);
    assert_eq!(needed, 47); // 1,500 pixels, 32 a word
    let mut pixels = vec![7u8; 50 * 30];
    let mut frame = Framebuffer::new(&mut pixels, 50, 30).unwrap();
    let mut mask = vec![0u32; needed - 1];
    let mut scratch = vec![PreparedVertex::default(); 8];
    let mut order = [0u16];
    let e = render_reverse_painter(
        &renderer,
        &facts,
        &mut order,
        &mut frame,
        &mut mask,
        &mut scratch,
        &mut RenderStats::default(),
    )
    .unwrap_err();
    assert_eq!(
        e,
        VisibilityError::Render(RenderError::BandMemoryTooSmall {
            part: BandPart::MaskWords,
            given: 46,
            needed: 47
        })
    );
    assert!(pixels.iter().all(|&p| p == 7), "nothing drawn");
}
