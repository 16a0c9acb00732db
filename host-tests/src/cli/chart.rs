//! `zscan chart`: speed against accuracy of the shading modes, as an SVG (plotters' SVG
//! backend; no font library: every text is written as plain SVG `<text>` by this module) and
//! the table behind it.
//!
//! ## What is measured
//! For the standard sphere and bunny scenes (SCENES.md camera, 320×240) lit by one directional
//! light along the scenes' `normalize(1, 1, 1)` (intensity 255, ambient 255) with the material
//! `k_a = 0.15, k_d = 0.55, k_s = 0.45, n = 20`, each variant — flat (per-face lighting at the
//! centroid), fast Gouraud, exact Gouraud (per-vertex lighting), Phong (per-pixel lighting),
//! each with and without the 4×4 ordered dither — renders a frame through a 32-level ramp:
//! vertex normals, lighting, vertex stage, culling, fill, depth test, shading (the core's
//! renderer with a lit object, `Intensities::Lit`).
//!
//! - **x, host**: instructions of the whole frame (valgrind callgrind, only inside
//!   `zscan_chart_region`) divided by the covered pixels.
//! - **x, Cortex-M4** (second panel, with `--m4 FILE`): the same frames as bench cases
//!   `lit_<scene>_<mode>[_dither]` (`scene::lit` in `benches/cases.rs`, calling the same
//!   renderer with the same light, material and ramp), counted by `zscan bench
//!   --no-host > FILE` (QEMU mps2-an386 + qemu-icount, harness overhead subtracted) and divided
//!   by the same covered-pixel counts. The firmware's framebuffer checksums equal the host's.
//! - **y**: per covered pixel, the error in LUT levels of the index against the `f64` reference
//!   level `L·32/256 − 1/2`, `L` the `f64` Phong illumination (`reference::float_lighting`) at
//!   the visible surface point of `reference::float_render` (perspective-correct position and
//!   smooth area-weighted normal interpolated in 3D): the picture every mode approximates.
//!   Maximum and mean over pixels covered in both frames. For the sphere the reference
//!   normal is the true sphere's at the visible point (the radial direction), not the
//!   interpolated one: the surface the mesh approximates.
//! - **Analytic normals** (course ch. 4 §2.5): the sphere again and a torus (32 rings ×
//!   16 sides, radii 0.8 and 0.3, turned 60° about `x`, same camera), in exact Gouraud and
//!   Phong, with the mesh's averaged vertex normals and with the generators' analytic ones
//!   (`uv_sphere_normals`, `torus_normals`, given as a table: the frame does not compute
//!   them); the torus's reference normal is its true normal at the visible point (from the
//!   tube's centre line). Ringed marks; host panel only (not bench cases).
use super::{visibility_chart, CliError};
use crate::reference::float_lighting::{unit, FloatLight, FloatLighting, FloatMaterial, V3};
use crate::reference::float_render;
use crate::scenes::{self, Scene};
use std::path::PathBuf;
use std::process::Command;
use zscan::geometry::camera::Camera;
use zscan::geometry::generators::{torus, torus_normals, torus_sizes, uv_sphere_normals};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::Mesh;
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::lighting::{Light, Material};
use zscan::output::{DepthBuffer, Framebuffer};
use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
use zscan::render::{PreparedVertex, RenderStats, Renderer};
use zscan::scene::{Intensities, Object};

/// Arguments of `zscan chart`.
#[derive(clap::Args, Debug)]
pub struct ChartArgs {
    /// Where to write the SVG (default `docs/chart.svg`; `docs/texture_chart.svg` with
    /// `--textures`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the error table only (no callgrind, no SVG).
    #[arg(long)]
    pub no_measure: bool,
    /// A saved `zscan bench --no-host` table with the `lit_*` cases (the Cortex-M4 panel).
    #[arg(long)]
    pub m4: Option<PathBuf>,
    /// Instead of the shading chart: the RAM-against-instructions chart of the visibility
    /// methods from this data file (`docs/plan_chart.csv`: rows scene,method,ram,m4,m0,kind,
    /// whole positive numbers, each checked), the planner's pick marked.
    #[arg(long, value_name = "CSV")]
    pub plan_data: Option<PathBuf>,
    /// Instead of the shading chart: the texture modes on SCENES.md's textured scenes, their
    /// instructions per frame (the `frame_tex_*` bench cases) against the share of pixels
    /// showing another texel than the `f64` definition (`texture_chart`).
    #[arg(long)]
    pub textures: bool,
    /// Internal: render one variant inside the measured region (what callgrind runs).
    #[arg(long, hide = true)]
    pub run_variant: Option<String>,
    /// Internal: draw one visibility point (`trap:method`) inside the measured region.
    #[arg(long, hide = true)]
    pub run_visibility: Option<String>,
}

const LEVELS: u16 = 32;
const BACKGROUND: u8 = 255;
const AMBIENT: u8 = 255;
const LIGHT: u8 = 255;
const MATERIAL: Material = Material::from_thousandths(150, 550, 450, 20);

const MODES: [(ShadeMode, &str); 4] = [
    (ShadeMode::Flat, "flat"),
    (ShadeMode::GouraudFast, "gouraud_fast"),
    (ShadeMode::GouraudExact, "gouraud_exact"),
    (ShadeMode::Phong, "phong"),
];
const SCENES: [&str; 2] = ["sphere", "bunny"];
/// Every scene of the chart: the standard two and the torus (analytic-normal comparison).
const ALL_SCENES: [&str; 3] = ["sphere", "bunny", "torus"];

/// The smooth-shading modes drawn with both kinds of vertex normals (sphere and torus).
const NORMAL_MODES: [(ShadeMode, &str); 2] = [
    (ShadeMode::GouraudExact, "gouraud_exact"),
    (ShadeMode::Phong, "phong"),
];

/// The torus of the analytic-normal comparison: 32 rings, 16 sides, radii 0.8 and 0.3, turned
/// 60° about `x` (its hole toward the camera), in the standard scenes' camera.
const TORUS: (u16, u16, f64, f64, i32) = (32, 16, 0.8, 0.3, 60);

/// One point of the chart.
#[derive(Debug, Clone, Copy)]
struct Variant {
    scene: &'static str,
    mode: ShadeMode,
    mode_name: &'static str,
    dither: bool,
    /// The generator's analytic vertex normals (`uv_sphere_normals`, `torus_normals`) instead
    /// of the mesh's averaged ones.
    analytic: bool,
}

impl Variant {
    fn name(&self) -> String {
        format!(
            "{}_{}{}{}",
            self.scene,
            self.mode_name,
            if self.analytic { "_analytic" } else { "" },
            if self.dither { "_dither" } else { "" }
        )
    }

    fn all() -> Vec<Variant> {
        let mut v = Vec::new();
        for scene in SCENES {
            for (mode, mode_name) in MODES {
                for dither in [false, true] {
                    v.push(Variant {
                        scene,
                        mode,
                        mode_name,
                        dither,
                        analytic: false,
                    });
                }
            }
        }
        // Averaged against analytic normals: the sphere's averaged rows are above.
        for (scene, kinds) in [("sphere", &[true][..]), ("torus", &[false, true][..])] {
            for (mode, mode_name) in NORMAL_MODES {
                for &analytic in kinds {
                    v.push(Variant {
                        scene,
                        mode,
                        mode_name,
                        dither: false,
                        analytic,
                    });
                }
            }
        }
        v
    }
}

/// The torus's points in `f64` (the generator's layout: vertex `i·sides + j` at azimuth
/// `2πi/rings` about `y` and tube angle `2πj/sides`), turned by `TORUS`'s angle about `x`,
/// and its triangles (each quad `a, b, c, d` as `a, b, c` and `a, c, d`, as the renderer
/// splits it).
fn torus_scene() -> Scene {
    let (rings, sides, major, minor, _) = TORUS;
    let (nr, ns) = (rings as usize, sides as usize);
    let tau = std::f64::consts::TAU;
    let mut vertices = Vec::with_capacity(nr * ns);
    for i in 0..nr {
        let phi = tau * i as f64 / nr as f64;
        for j in 0..ns {
            let theta = tau * j as f64 / ns as f64;
            let rc = major + minor * theta.cos();
            vertices.push(torus_turn([
                rc * phi.cos(),
                minor * theta.sin(),
                -rc * phi.sin(),
            ]));
        }
    }
    let mut triangles = Vec::with_capacity(2 * nr * ns);
    for i in 0..nr {
        for j in 0..ns {
            let (i1, j1) = ((i + 1) % nr, (j + 1) % ns);
            let q = [i * ns + j, i1 * ns + j, i1 * ns + j1, i * ns + j1];
            triangles.push([q[0], q[1], q[2]]);
            triangles.push([q[0], q[2], q[3]]);
        }
    }
    Scene {
        name: "torus".into(),
        camera: scenes::Camera::standard(),
        intensities: vec![[0; 3]; triangles.len()],
        vertices,
        triangles,
        scale: 1.0,
    }
}

/// The torus's turn about `x` (positive: `y` toward `z`).
fn torus_turn(p: V3) -> V3 {
    let (s, c) = (TORUS.4 as f64).to_radians().sin_cos();
    [p[0], p[1] * c - p[2] * s, p[1] * s + p[2] * c]
}

/// The true unit normal of the turned torus at world point `p` (the surface point nearest to
/// `p` is reached along it): from the tube's centre line through `p`'s azimuth.
fn torus_true_normal(p: V3) -> V3 {
    let (s, c) = (TORUS.4 as f64).to_radians().sin_cos();
    let m = [p[0], p[1] * c + p[2] * s, -p[1] * s + p[2] * c]; // back to the model frame
    let r = (m[0] * m[0] + m[2] * m[2]).sqrt().max(1e-12);
    let centre = [m[0] / r * TORUS.2, 0.0, m[2] / r * TORUS.2];
    torus_turn(unit(scenes::sub(m, centre)))
}

/// A scene in core form plus the buffers a frame needs (allocated outside the measured region).
struct Prepared {
    scene: Scene,
    vertices: Vec<Vec3>,
    indices: Vec<u16>,
    camera: Camera,
    /// Model → world of the core's object (the torus's turn; identity otherwise).
    transform: Affine3,
    scratch: Vec<PreparedVertex<4>>,
    normals: Vec<Vec3>,
    /// The generator's analytic vertex normals (model frame), for the sphere and the torus.
    analytic: Vec<Vec3>,
    pixels: Vec<u8>,
    depth: Vec<u16>,
}

impl Prepared {
    fn new(name: &str) -> Result<Prepared, CliError> {
        let c = crate::core_render::coord;
        let (scene, vertices, transform, analytic) = if name == "torus" {
            // The core's own torus and analytic normals, turned by the object's transform;
            // the f64 scene is built independently above (checked to agree below).
            let (rings, sides, major, minor, turn) = TORUS;
            let (nv, ni) = torus_sizes(rings, sides);
            let (mut v, mut quads) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            torus(rings, sides, c(major), c(minor), &mut v, &mut quads)
                .map_err(|e| format!("{e:?}"))?;
            let mut n = vec![Vec3::ZERO; nv];
            torus_normals(rings, sides, &mut n).map_err(|e| format!("{e:?}"))?;
            let turn = Affine3::rotation_x(BinaryAngle::from_degrees(turn));
            let scene = torus_scene();
            for (core, f) in v.iter().zip(&scene.vertices) {
                let w = turn
                    .transform_point(*core)
                    .bits()
                    .map(|b| b as f64 / 65536.0);
                if (0..3).any(|k| (w[k] - f[k]).abs() > 1e-3) {
                    return Err(format!("torus: core {w:?} against f64 {f:?}").into());
                }
            }
            (scene, v, turn, n)
        } else {
            let scene = scenes::standard_scene(name)?;
            let vertices: Vec<Vec3> = scene
                .vertices
                .iter()
                .map(|v| Vec3::new(c(v[0]), c(v[1]), c(v[2])))
                .collect();
            let mut n = Vec::new();
            if name == "sphere" {
                n = vec![Vec3::ZERO; vertices.len()];
                uv_sphere_normals(
                    scenes::SPHERE_SEGMENTS as u16,
                    scenes::SPHERE_RINGS as u16,
                    &mut n,
                )
                .map_err(|e| format!("{e:?}"))?;
            }
            (scene, vertices, Affine3::IDENTITY, n)
        };
        let camera = crate::core_render::core_camera(&scene.camera)?;
        let indices: Vec<u16> = scene
            .triangles
            .iter()
            .flatten()
            .map(|&i| u16::try_from(i))
            .collect::<Result<_, _>>()
            .map_err(|_| "more than 65536 vertices")?;
        let (w, h) = (scene.camera.width as usize, scene.camera.height as usize);
        let nv = vertices.len();
        Ok(Prepared {
            scratch: vec![PreparedVertex::default(); nv],
            normals: vec![Vec3::ZERO; nv],
            analytic,
            pixels: vec![0; w * h],
            depth: vec![0; w * h],
            scene,
            vertices,
            indices,
            camera,
            transform,
        })
    }

    fn size(&self) -> (u16, u16) {
        (
            self.scene.camera.width as u16,
            self.scene.camera.height as u16,
        )
    }
}

/// The light in the world frame.
fn light() -> Light {
    let d = scenes::light_direction();
    let c = crate::core_render::coord;
    Light::Directional {
        toward: Vec3::new(c(d[0]), c(d[1]), c(d[2])),
        intensity: LIGHT,
    }
}

/// One frame of `v` into `p.pixels` through the core's renderer (the code the bench cases run
/// on the Cortex-M4): vertex normals, lighting, vertex stage, culling, drawing. Returns the
/// covered pixels, or an error message.
fn render(p: &mut Prepared, v: &Variant) -> Result<u32, String> {
    let (w, h) = p.size();
    let mesh = Mesh::triangles(&p.vertices, &p.indices).map_err(|e| format!("{e:?}"))?;
    let renderer = Renderer::<4>::new(&p.camera)
        .and_then(|r| r.with_lights(AMBIENT, &[light()]))
        .map_err(|e| e.to_string())?;
    let mut fb = Framebuffer::new(&mut p.pixels, w, h).map_err(|e| e.to_string())?;
    let mut zb = DepthBuffer::new(&mut p.depth, w, h).map_err(|e| e.to_string())?;
    fb.clear(BACKGROUND);
    zb.clear();
    if v.mode != ShadeMode::Flat && !v.analytic {
        mesh.vertex_normals(&mut p.normals)
            .map_err(|e| format!("{e:?}"))?;
    }
    let mut object = Object::new(mesh);
    object.transform = p.transform;
    object.intensities = Intensities::Lit {
        material: MATERIAL,
        normals: if v.analytic { &p.analytic } else { &p.normals },
    };
    object.shade = v.mode;
    object.ramp = LuminanceRamp {
        first: 0,
        levels: LEVELS,
    };
    object.dither = v.dither;
    let mut stats = RenderStats::default();
    renderer
        .draw_object(&object, &mut p.scratch, &mut fb, &mut zb, &mut stats)
        .map_err(|e| e.to_string())?;
    Ok(stats.pixels_covered)
}

/// Smooth normals of SCENES.md (area-weighted sum of face normals, normalised), `f64`.
fn smooth_normals(scene: &Scene) -> Vec<V3> {
    let mut n = vec![[0.0; 3]; scene.vertices.len()];
    for t in &scene.triangles {
        let [a, b, c] = t.map(|i| scene.vertices[i]);
        let f = scenes::cross(scenes::sub(b, a), scenes::sub(c, a));
        for &i in t {
            n[i] = scenes::add(n[i], f);
        }
    }
    n.into_iter().map(unit).collect()
}

/// Error statistics of one frame against the reference levels.
#[derive(Debug, Clone, Copy, Default)]
struct Errors {
    max: f64,
    mean: f64,
    pixels: usize,
}

/// The `f64` reference level (continuous, `L·levels/256 − 1/2`) at every pixel the reference
/// covers.
fn reference_levels(scene: &Scene) -> Result<Vec<Option<f64>>, CliError> {
    let frame = float_render::render(scene)?;
    let cam = &scene.camera;
    let (f, (cx, cy)) = (cam.focal(), cam.principal);
    // The surface every mode approximates: the true sphere and torus (their normal at the
    // visible point), the bunny's smooth interpolated normals (it has no other).
    let truth: Option<fn(V3) -> V3> = match scene.name.as_str() {
        "sphere" => Some(unit),
        "torus" => Some(torus_true_normal),
        _ => None,
    };
    let normals = smooth_normals(scene);
    let lighting = FloatLighting {
        eye: cam.eye,
        ambient: AMBIENT as f64,
        lights: vec![FloatLight::Directional(
            scenes::light_direction(),
            LIGHT as f64,
        )],
    };
    let m = FloatMaterial {
        ka: 0.15,
        kd: 0.55,
        ks: 0.45,
        n: 20,
    };
    let mut out = vec![None; frame.pixels.len()];
    for y in 0..frame.height {
        for x in 0..frame.width {
            let Some(frag) = frame.at(x, y) else { continue };
            let tri = scene.triangles[frag.triangle];
            let [a, b, c] = tri.map(|i| cam.to_view(scene.vertices[i]));
            let r = [(x as f64 - cx) / f, -(y as f64 - cy) / f, 1.0];
            let p = scenes::scale(r, frag.depth);
            // Barycentric coordinates of p in the 3D triangle.
            let n = scenes::cross(scenes::sub(b, a), scenes::sub(c, a));
            let nn = scenes::dot(n, n);
            let wb = scenes::dot(scenes::cross(scenes::sub(p, a), scenes::sub(c, a)), n) / nn;
            let wc = scenes::dot(scenes::cross(scenes::sub(b, a), scenes::sub(p, a)), n) / nn;
            let w = [1.0 - wb - wc, wb, wc];
            let mut pw = [0.0; 3];
            let mut nw = [0.0; 3];
            for k in 0..3 {
                pw = scenes::add(pw, scenes::scale(scene.vertices[tri[k]], w[k]));
                nw = scenes::add(nw, scenes::scale(normals[tri[k]], w[k]));
            }
            let nw = truth.map_or(nw, |t| t(pw));
            let l = lighting.intensity(&m, pw, nw);
            out[(y * frame.width + x) as usize] = Some(l * LEVELS as f64 / 256.0 - 0.5);
        }
    }
    Ok(out)
}

fn errors(pixels: &[u8], reference: &[Option<f64>]) -> Errors {
    let mut e = Errors::default();
    let mut sum = 0.0;
    for (&p, r) in pixels.iter().zip(reference) {
        if let (true, Some(r)) = (p != BACKGROUND, r) {
            let d = (p as f64 - r).abs();
            e.max = e.max.max(d);
            sum += d;
            e.pixels += 1;
        }
    }
    e.mean = sum / e.pixels.max(1) as f64;
    e
}

/// Host instructions inside `zscan_chart_region` of `zscan chart FLAG TAG` (one frame), by
/// running this tool under callgrind.
fn host_instructions(flag: &str, tag: &str) -> Result<u64, CliError> {
    let exe = std::env::current_exe()?;
    let dir = std::env::temp_dir().join(format!("zscan-chart-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let out_file = dir.join(format!("callgrind.{}", tag.replace(':', "-")));
    let out = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg("--collect-atstart=no")
        .arg("--toggle-collect=zscan_chart_region")
        .arg(format!("--callgrind-out-file={}", out_file.display()))
        .arg(&exe)
        .args(["chart", flag, tag])
        .output()
        .map_err(|e| format!("valgrind (is it installed?): {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "callgrind run of {tag} failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
        .into());
    }
    let text = std::fs::read_to_string(&out_file)?;
    let _ = std::fs::remove_file(&out_file);
    text.lines()
        .find_map(|l| {
            l.strip_prefix("totals:")
                .or_else(|| l.strip_prefix("summary:"))
        })
        .and_then(|v| v.split_whitespace().next()?.parse::<u64>().ok())
        .ok_or_else(|| format!("no totals in {}", out_file.display()).into())
}

/// One row of the table.
#[derive(Debug, Clone)]
struct Row {
    variant: Variant,
    covered: u32,
    instructions: Option<u64>,
    errors: Errors,
}

impl Row {
    fn per_pixel(&self) -> Option<f64> {
        Some(self.instructions? as f64 / self.covered.max(1) as f64)
    }
}

/// Runs `zscan chart`.
pub fn run(args: ChartArgs) -> Result<(), CliError> {
    if args.textures {
        return super::texture_chart::run(&args);
    }
    let out = args.out.clone().unwrap_or_else(|| "docs/chart.svg".into());
    if let Some(data) = &args.plan_data {
        let svg = plan_chart(data)?;
        std::fs::write(&out, svg).map_err(|e| format!("{}: {e}", out.display()))?;
        crate::outln!("wrote {}", out.display())?;
        return Ok(());
    }
    if let Some(name) = &args.run_variant {
        return run_variant(name);
    }
    if let Some(tag) = &args.run_visibility {
        return visibility_chart::run_one(tag);
    }
    if cfg!(debug_assertions) && !args.no_measure {
        crate::note!(
            "zscan chart: warning: a debug build; run with --release for meaningful figures"
        );
    }
    let rows = shading_rows(!args.no_measure)?;
    print_rows(&rows)?;
    let count: visibility_chart::Counter<'_> = &host_instructions;
    let visibility = visibility_chart::points((!args.no_measure).then_some(count))?;
    visibility_chart::print(&visibility)?;
    if args.no_measure {
        return Ok(());
    }
    let m4 = m4_per_pixel(&rows, args.m4.as_deref())?;
    let svg = chart(&rows, &m4, &visibility)?;
    std::fs::write(&out, svg)?;
    crate::note!("zscan chart: wrote {}", out.display());
    Ok(())
}

/// What callgrind runs: one shading variant's frame in the measured region.
fn run_variant(name: &str) -> Result<(), CliError> {
    let v = Variant::all()
        .into_iter()
        .find(|v| v.name() == name)
        .ok_or_else(|| format!("no variant {name:?}"))?;
    let mut p = Prepared::new(v.scene)?;
    render(&mut p, &v)?; // warm-up
    let covered = crate::core_render::measured(|| render(std::hint::black_box(&mut p), &v));
    crate::outln!("{} covered={}", v.name(), covered?)?;
    Ok(())
}

/// Every shading variant's row: covered pixels, errors and (when `measure`) host
/// instructions.
fn shading_rows(measure: bool) -> Result<Vec<Row>, CliError> {
    let mut rows = Vec::new();
    for scene in ALL_SCENES {
        let mut p = Prepared::new(scene)?;
        let reference = reference_levels(&p.scene)?;
        for v in Variant::all().into_iter().filter(|v| v.scene == scene) {
            let covered = render(&mut p, &v)?;
            let errors = errors(&p.pixels, &reference);
            let instructions = if measure {
                Some(host_instructions("--run-variant", &v.name())?)
            } else {
                None
            };
            rows.push(Row {
                variant: v,
                covered,
                instructions,
                errors,
            });
        }
    }
    Ok(rows)
}

fn print_rows(rows: &[Row]) -> Result<(), super::out::OutputError> {
    crate::outln!(
        "{:<28} {:>8} {:>12} {:>10} {:>9} {:>9}",
        "variant",
        "covered",
        "host instr",
        "instr/px",
        "max err",
        "mean err"
    )?;
    for r in rows {
        crate::outln!(
            "{:<28} {:>8} {:>12} {:>10} {:>9.3} {:>9.3}",
            r.variant.name(),
            r.covered,
            r.instructions.map_or("-".into(), |i| i.to_string()),
            r.per_pixel().map_or("-".into(), |x| format!("{x:.1}")),
            r.errors.max,
            r.errors.mean
        )?;
    }
    Ok(())
}

/// Cortex-M4 instructions per covered pixel of each row from the bench table at `path` (none
/// without one), printed.
fn m4_per_pixel(
    rows: &[Row],
    path: Option<&std::path::Path>,
) -> Result<Vec<Option<f64>>, CliError> {
    let m4_counts = match path {
        Some(p) => read_m4(p)?,
        None => Default::default(),
    };
    let m4: Vec<Option<f64>> = rows
        .iter()
        .map(|r| {
            let n = *m4_counts.get(&r.variant.name())?;
            Some(n as f64 / r.covered.max(1) as f64)
        })
        .collect();
    if !m4_counts.is_empty() {
        crate::outln!("\n{:<28} {:>12} {:>10}", "variant", "M4 instr", "instr/px")?;
        for (r, x) in rows.iter().zip(&m4) {
            let n = m4_counts.get(&r.variant.name());
            crate::outln!(
                "{:<28} {:>12} {:>10}",
                r.variant.name(),
                n.map_or("-".into(), |n| n.to_string()),
                x.map_or("-".into(), |x| format!("{x:.1}"))
            )?;
        }
    }
    Ok(m4)
}

/// Colours of the modes (flat, fast Gouraud, exact Gouraud, Phong).
const COLOURS: [(u8, u8, u8); 4] = [(120, 120, 120), (230, 140, 0), (200, 30, 30), (30, 90, 200)];

fn mode_index(m: ShadeMode) -> usize {
    MODES.iter().position(|(x, _)| *x == m).unwrap_or(0)
}

/// Draws one panel (x = `xs[i]`, instructions per covered pixel) into `area`, collecting
/// its texts (tick labels, panel title) as SVG elements.
fn panel<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    rows: &[Row],
    xs: &[Option<f64>],
    title: &str,
    ymax: f64,
    texts: &mut Vec<String>,
) -> Result<(), CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    let xmax = xs.iter().flatten().fold(0.0, |a: f64, b| a.max(*b)) * 1.08;
    if xmax <= 0.0 {
        return Ok(());
    }
    let mut chart = ChartBuilder::on(area)
        .margin_left(MARGINS.0)
        .margin_top(MARGINS.1)
        .margin_right(MARGINS.2)
        .margin_bottom(MARGINS.3)
        .build_cartesian_2d(0f64..xmax, 0f64..ymax)
        .map_err(|x| e(&x))?;
    linear_grid(
        &mut chart,
        (xmax, ymax),
        12,
        &|x| format!("{x}"),
        &|y| format!("{y:.0}"),
        texts,
    )?;
    let (tx, ty) = chart.backend_coord(&(0.0, ymax));
    texts.push(format!(
        r#"<text x="{}" y="{}" font-size="14" font-weight="bold">{title}</text>"#,
        tx + 8,
        ty + 16
    ));
    let (bx, by) = chart.backend_coord(&(xmax / 2.0, 0.0));
    texts.push(format!(
        r#"<text x="{bx}" y="{}" text-anchor="middle" font-size="13">instructions per covered pixel (whole frame: lighting, vertex stage, fill, shading)</text>"#,
        by + 34
    ));
    for (r, x) in rows.iter().zip(xs) {
        let Some(x) = *x else { continue };
        let (cr, cg, cb) = COLOURS[mode_index(r.variant.mode)];
        let colour = RGBColor(cr, cg, cb);
        let style = if r.variant.dither {
            colour.stroke_width(2)
        } else {
            colour.filled()
        };
        chart
            .draw_series(LineSeries::new(
                [(x, r.errors.mean), (x, r.errors.max)],
                colour.stroke_width(1),
            ))
            .map_err(|q| e(&q))?;
        chart
            .draw_series(std::iter::once(Cross::new(
                (x, r.errors.max),
                4,
                colour.stroke_width(1),
            )))
            .map_err(|q| e(&q))?;
        let at = (x, r.errors.mean);
        match r.variant.scene {
            "sphere" => chart
                .draw_series(std::iter::once(Circle::new(at, 5, style)))
                .map(|_| ()),
            "torus" => chart
                .draw_series(std::iter::once(
                    EmptyElement::at(at) + Rectangle::new([(-5, -5), (5, 5)], style),
                ))
                .map(|_| ()),
            _ => chart
                .draw_series(std::iter::once(TriangleMarker::new(at, 6, style)))
                .map(|_| ()),
        }
        .map_err(|q| e(&q))?;
        if r.variant.analytic {
            // Analytic normals: a black ring around the mark.
            chart
                .draw_series(std::iter::once(Circle::new(at, 9, BLACK.stroke_width(2))))
                .map_err(|q| e(&q))?;
        }
    }
    Ok(())
}

/// A grid step for an axis from 0 to `max`: the smallest of 1, 2, 5 or 10 times a power of
/// ten giving at most about six steps.
pub(super) fn nice_step(max: f64) -> f64 {
    let raw = max / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(raw)
}

/// Horizontal grid lines in `grey` every `step` from 0 to `ymax` across `x0..x1` of `chart`,
/// each labelled on the left at font size `size` (the texts collected in `texts`).
pub(super) fn y_grid<DB, X>(
    chart: &mut plotters::prelude::ChartContext<
        '_,
        DB,
        plotters::prelude::Cartesian2d<X, plotters::coord::types::RangedCoordf64>,
    >,
    (x0, x1): (f64, f64),
    (ymax, step): (f64, f64),
    (grey, size): (plotters::prelude::RGBColor, u32),
    label: &dyn Fn(f64) -> String,
    texts: &mut Vec<String>,
) -> Result<(), CliError>
where
    DB: plotters::prelude::DrawingBackend,
    X: plotters::prelude::Ranged<ValueType = f64>,
{
    use plotters::prelude::*;
    let mut y = 0.0;
    while y <= ymax {
        chart
            .draw_series(LineSeries::new([(x0, y), (x1, y)], grey))
            .map_err(|q| q.to_string())?;
        let (px, py) = chart.backend_coord(&(x0, y));
        texts.push(format!(
            r#"<text x="{}" y="{}" text-anchor="end" font-size="{size}">{}</text>"#,
            px - 6,
            py + 4,
            label(y)
        ));
        y += step;
    }
    Ok(())
}

/// A linear panel's grid and axes: grey lines every [`nice_step`] of each axis from 0 to
/// `xmax` and `ymax`, labelled (font size `size`) below by `x_label` and on the left by
/// `y_label`, and the two axes in black (the texts collected in `texts`).
pub(super) fn linear_grid<DB>(
    chart: &mut plotters::prelude::ChartContext<
        '_,
        DB,
        plotters::prelude::Cartesian2d<
            plotters::coord::types::RangedCoordf64,
            plotters::coord::types::RangedCoordf64,
        >,
    >,
    (xmax, ymax): (f64, f64),
    size: u32,
    x_label: &dyn Fn(f64) -> String,
    y_label: &dyn Fn(f64) -> String,
    texts: &mut Vec<String>,
) -> Result<(), CliError>
where
    DB: plotters::prelude::DrawingBackend,
{
    use plotters::prelude::*;
    let grey = RGBColor(220, 220, 220);
    let (sx, sy) = (nice_step(xmax), nice_step(ymax));
    let mut x = 0.0;
    while x <= xmax {
        chart
            .draw_series(LineSeries::new([(x, 0.0), (x, ymax)], grey))
            .map_err(|q| q.to_string())?;
        let (px, py) = chart.backend_coord(&(x, 0.0));
        texts.push(format!(
            r#"<text x="{px}" y="{}" text-anchor="middle" font-size="{size}">{}</text>"#,
            py + 16,
            x_label(x)
        ));
        x += sx;
    }
    y_grid(chart, (0.0, xmax), (ymax, sy), (grey, size), y_label, texts)?;
    chart
        .draw_series(LineSeries::new(
            [(0.0, ymax), (0.0, 0.0), (xmax, 0.0)],
            BLACK,
        ))
        .map_err(|q| q.to_string())?;
    Ok(())
}

/// Panel margins: left, top, right, bottom.
pub(super) const MARGINS: (i32, i32, i32, i32) = (70, 40, 250, 50);

/// The SVG: one panel per platform (host, Cortex-M4 when given), x = instructions per covered
/// pixel (linear), y = error in LUT levels; a marker at the mean error joined to a cross at
/// the maximum. Circles: sphere, triangles: bunny; filled: plain ramp, hollow: dithered.
fn chart(
    rows: &[Row],
    m4: &[Option<f64>],
    visibility: &[visibility_chart::Point],
) -> Result<String, CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    let ymax = rows.iter().map(|r| r.errors.max).fold(0.0, f64::max) * 1.08;
    let host: Vec<Option<f64>> = rows.iter().map(Row::per_pixel).collect();
    let panels: Vec<(&str, &[Option<f64>])> = if m4.iter().any(Option::is_some) {
        vec![
            ("host x86-64 (valgrind callgrind)", &host[..]),
            ("Cortex-M4 (QEMU mps2-an386, qemu-icount)", m4),
        ]
    } else {
        vec![("host x86-64 (valgrind callgrind)", &host[..])]
    };
    let (width, panel_h) = (900u32, 440u32);
    let shading_h = 60 + panel_h * panels.len() as u32;
    let traps = crate::failures::Trap::ALL.len() as u32;
    let height = shading_h + visibility_chart::HEADING + visibility_chart::PANEL_HEIGHT * traps;
    let mut svg = String::new();
    let mut texts: Vec<String> = Vec::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let (upper, lower) = root.split_vertically(shading_h);
        let body = upper.margin(50, 10, 0, 0);
        let areas = body.split_evenly((panels.len(), 1));
        for (area, (title, xs)) in areas.iter().zip(&panels) {
            panel(area, rows, xs, title, ymax, &mut texts)?;
        }
        let at = (width as i32, shading_h as i32);
        visibility_chart::draw(&lower, visibility, at, &mut texts)?;
        root.present().map_err(|x| e(&x))?;
    }
    shading_legend(width as i32, shading_h as i32, &mut texts);
    Ok(with_texts(svg, &texts))
}

/// `svg` with the SVG elements `texts` added before its closing tag (the charts draw their
/// lines with plotters and their texts as plain SVG, so that no font library is needed).
pub(super) fn with_texts(svg: String, texts: &[String]) -> String {
    let body = texts.join("\n");
    match svg.rfind("</svg>") {
        Some(i) => format!("{}{}\n{}", &svg[..i], body, &svg[i..]),
        None => svg,
    }
}

/// The shading half's title, axis name and legend as plain SVG text (no font library needed),
/// for a figure `w` wide whose shading panels end at `bottom`.
fn shading_legend(w: i32, bottom: i32, texts: &mut Vec<String>) {
    texts.push(format!(
        r#"<text x="{}" y="28" text-anchor="middle" font-size="16" font-weight="bold">zscan shading: speed vs accuracy (standard sphere and bunny, a torus, 320x240, 32-level ramp)</text>"#,
        w / 2
    ));
    let mid = 50 + (bottom - 50) / 2;
    texts.push(format!(
        r#"<text x="18" y="{mid}" text-anchor="middle" font-size="13" transform="rotate(-90 18 {mid})">error vs f64 per-pixel Phong, LUT levels (marker: mean, cross: max)</text>"#
    ));
    let lx = w - MARGINS.2 + 30;
    let mut ly = 100;
    let names = [
        "flat",
        "Gouraud fast (DDA)",
        "Gouraud exact",
        "Phong (per pixel)",
    ];
    for (i, n) in names.iter().enumerate() {
        let (r, g, b) = COLOURS[i];
        texts.push(format!(
            r#"<rect x="{lx}" y="{}" width="12" height="12" fill="rgb({r},{g},{b})"/><text x="{}" y="{}" font-size="13">{n}</text>"#,
            ly - 10,
            lx + 18,
            ly
        ));
        ly += 22;
    }
    ly += 10;
    for line in [
        "circle: sphere",
        "triangle: bunny",
        "square: torus",
        "black ring: analytic normals",
        "(sphere, torus: error vs the true surface)",
        "filled: plain ramp",
        "hollow: 4x4 Bayer dither",
        "line from mean up to max",
    ] {
        texts.push(format!(
            r#"<text x="{lx}" y="{ly}" font-size="12">{line}</text>"#
        ));
        ly += 20;
    }
}

/// Cortex-M4 instructions per case from a saved `zscan bench` table (cases `lit_<variant>`),
/// keyed by variant.
fn read_m4(path: &std::path::Path) -> Result<std::collections::HashMap<String, u64>, CliError> {
    read_counts(path, "lit_")
}

/// Instructions per case from a saved `zscan bench` table, for the cases named `prefix…`
/// (keyed by the rest of the name): the first instruction column after the pixel count.
pub(super) fn read_counts(
    path: &std::path::Path,
    prefix: &str,
) -> Result<std::collections::HashMap<String, u64>, CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut out = std::collections::HashMap::new();
    for line in text.lines() {
        let mut cols = line.split('|');
        let (Some(head), Some(m4)) = (cols.next(), cols.next()) else {
            continue;
        };
        let Some(name) = head.split_whitespace().next() else {
            continue;
        };
        let Some(variant) = name.strip_prefix(prefix) else {
            continue;
        };
        if let Some(n) = m4.split_whitespace().next().and_then(|v| v.parse().ok()) {
            out.insert(variant.to_string(), n);
        }
    }
    Ok(out)
}

/// One point of the plan chart: `(scene, method, ram bytes, [Cortex-M4, Cortex-M0]
/// instructions (`None` where not measured), peer)`.
type PlanPoint = (String, String, f64, [Option<f64>; 2], bool);

/// The scenes of the plan chart, one panel each per core.
const PLAN_SCENES: [&str; 4] = ["quad", "cube", "sphere", "bunny"];

/// Largest `ram` of a plan-data row, bytes (4 GiB).
const MAX_PLAN_RAM: u64 = 1 << 32;

/// Largest instruction count of a plan-data row (10^12).
const MAX_PLAN_INSTRUCTIONS: u64 = 1_000_000_000_000;

/// Reads the plan chart's data (`docs/plan_chart.csv`): `#` comment lines, blank lines, and
/// rows `scene,method,ram,m4,m0,kind` of exactly six fields:
/// - `scene`: one of [`PLAN_SCENES`];
/// - `kind`: `zscan` (a method of this crate) or `peer` (another renderer);
/// - `method`: for `zscan`, a method's name ([`Visibility::name`](zscan::visibility::Visibility::name))
///   alone or followed by a variant (digits, or `_` and letters or digits:
///   `scanline16`, `zbuffer_compact`); for `peer`, a name of letters, digits, `-` and `_`;
/// - `ram`: bytes of caller memory, a whole number in `1..=`[`MAX_PLAN_RAM`];
/// - `m4`, `m0`: Cortex-M4 and Cortex-M0 instructions per frame, whole numbers in
///   `1..=`[`MAX_PLAN_INSTRUCTIONS`], or `-` where not measured (not both).
///
/// Each (scene, method, kind) appears once, and every panel (each scene on each core) needs at
/// least one count. Anything else is an error naming `name`, the line, the field and what is
/// accepted; NaN, infinities, zero, negative and fractional numbers are not numbers here.
fn parse_plan_data(text: &str, name: &str) -> Result<Vec<PlanPoint>, String> {
    let mut points: Vec<PlanPoint> = Vec::new();
    let mut lines_of: Vec<usize> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let at = format!("{name}:{}", n + 1);
        if line.trim_start().starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 6 {
            return Err(format!(
                "{at}: {} fields, expected 6: scene,method,ram,m4,m0,kind",
                f.len()
            ));
        }
        let scene = f[0];
        if !PLAN_SCENES.contains(&scene) {
            return Err(format!(
                "{at}: field 1 `scene` = {scene:?} is not one of {}",
                PLAN_SCENES.join(", ")
            ));
        }
        let peer = match f[5] {
            "zscan" => false,
            "peer" => true,
            other => {
                return Err(format!(
                    "{at}: field 6 `kind` = {other:?} is not zscan or peer"
                ))
            }
        };
        let method = f[1];
        if !plan_method_ok(method, peer) {
            let names: Vec<_> = zscan::visibility::Visibility::ALL
                .iter()
                .map(|v| v.name())
                .collect();
            return Err(if peer {
                format!(
                    "{at}: field 2 `method` = {method:?}: a peer's name is letters, digits, \
                     `-` and `_`"
                )
            } else {
                format!(
                    "{at}: field 2 `method` = {method:?} is not a zscan method: one of {}, \
                     alone or followed by a variant (digits, or `_` and letters or digits)",
                    names.join(", ")
                )
            });
        }
        let whole = |k: usize, key: &str, (max, unit, or): (u64, &str, &str)| {
            let v = f[k];
            v.parse::<u64>()
                .ok()
                .filter(|n| (1..=max).contains(n))
                .ok_or_else(|| {
                    format!(
                        "{at}: field {} `{key}` = {v:?} is not a whole number of {unit} in \
                         1..={max}{or}",
                        k + 1
                    )
                })
        };
        let ram = whole(2, "ram", (MAX_PLAN_RAM, "bytes", ""))?;
        let count = |k: usize, key: &str| -> Result<Option<f64>, String> {
            if f[k] == "-" {
                return Ok(None);
            }
            let accepted = (
                MAX_PLAN_INSTRUCTIONS,
                "instructions",
                " (or - where not measured)",
            );
            whole(k, key, accepted).map(|n| Some(n as f64))
        };
        let counts = [count(3, "m4")?, count(4, "m0")?];
        if counts == [None, None] {
            return Err(format!(
                "{at}: `m4` and `m0` are both - : a row needs at least one count"
            ));
        }
        if let Some(k) = points
            .iter()
            .position(|p| p.0 == scene && p.1 == method && p.4 == peer)
        {
            return Err(format!(
                "{at}: {scene},{method},{} appears twice (first on line {})",
                f[5], lines_of[k]
            ));
        }
        points.push((scene.into(), method.into(), ram as f64, counts, peer));
        lines_of.push(n + 1);
    }
    if points.is_empty() {
        return Err(format!(
            "{name}: no data rows (expected lines scene,method,ram,m4,m0,kind)"
        ));
    }
    for scene in PLAN_SCENES {
        for (core, key) in ["m4", "m0"].iter().enumerate() {
            if !points.iter().any(|p| p.0 == scene && p.3[core].is_some()) {
                return Err(format!(
                    "{name}: scene {scene} has no `{key}` count: every panel (each scene on \
                     each core) needs at least one"
                ));
            }
        }
    }
    Ok(points)
}

/// `method` is a plan-data method name ([`parse_plan_data`]).
fn plan_method_ok(method: &str, peer: bool) -> bool {
    let word = |s: &str, extra: &[char]| {
        s.chars()
            .all(|c| c.is_ascii_alphanumeric() || extra.contains(&c))
    };
    if peer {
        return !method.is_empty() && word(method, &['-', '_']);
    }
    zscan::visibility::Visibility::ALL.iter().any(|v| {
        method.strip_prefix(v.name()).is_some_and(|rest| {
            rest.is_empty()
                || rest.chars().all(|c| c.is_ascii_digit())
                || rest
                    .strip_prefix('_')
                    .is_some_and(|r| !r.is_empty() && word(r, &[]))
        })
    })
}

/// The x range of the plan chart (bytes, log scale): 20,000 to 600,000, widened to hold every
/// point (a quarter beyond the extreme ones).
fn plan_x_range(points: &[PlanPoint]) -> (f64, f64) {
    let lo = points.iter().map(|p| p.2).fold(f64::INFINITY, f64::min);
    let hi = points.iter().map(|p| p.2).fold(0.0, f64::max);
    ((lo / 1.25).min(20_000.0), (hi * 1.25).max(600_000.0))
}

/// The planner's pick on standard scene `name` (no budget limit), as the data file's method.
fn planner_pick(name: &str) -> Result<String, CliError> {
    let core = crate::core_render::to_core(&scenes::standard_scene(name)?)?;
    let objects = [core.object(ShadeMode::GouraudExact)?];
    let scene = crate::core_render::scene_of(&objects, core.camera);
    let mut pairs = Vec::new();
    let facts = crate::core_render::mesh_facts(&scene, &mut pairs)?;
    let plan = zscan::visibility::plan::<4>(&scene, &facts, usize::MAX, &mut [0])
        .map_err(|e| e.to_string())?;
    Ok(plan.visibility.name().to_string())
}

/// The RAM (x, log scale) against Cortex-M4 instructions (y) chart of every method on each
/// standard scene, one panel per scene, from the data file (module doc of the file itself),
/// with the planner's pick (computed here) ringed and the peers as grey squares.
fn plan_chart(data: &std::path::Path) -> Result<String, CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    let text = std::fs::read_to_string(data).map_err(|x| format!("{}: {x}", data.display()))?;
    let points = parse_plan_data(&text, &data.display().to_string())?;
    let x_range = plan_x_range(&points);
    let (width, height) = (1600u32, 800u32);
    let mut svg = String::new();
    let mut texts: Vec<String> = Vec::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let areas = root.margin(50, 60, 10, 10).split_evenly((2, 4));
        let panels = [0, 1]
            .into_iter()
            .flat_map(|core| PLAN_SCENES.map(|name| (core, name)));
        for (area, (core, name)) in areas.iter().zip(panels) {
            plan_panel(area, (name, core), (&points, x_range), &mut texts)?;
        }
        root.present().map_err(|x| e(&x))?;
    }
    let w = width as i32;
    texts.push(format!(r#"<text x="{}" y="26" text-anchor="middle" font-size="16" font-weight="bold">Visibility methods: caller RAM against instructions per frame, Cortex-M4 (top) and Cortex-M0 (bottom), standard scenes at 320x240</text>"#, w / 2));
    texts.push(format!(r#"<text x="{}" y="46" text-anchor="middle" font-size="12">blue: zscan methods; ringed red: the planner's pick (no budget limit); grey squares: peers (frame + depth, SCENES.md; Cortex-M4F only). x: bytes, log scale; data: docs/plan_chart.csv</text>"#, w / 2));
    Ok(with_texts(svg, &texts))
}

/// One panel of the plan chart: scene `name`'s points on core `core` (0: Cortex-M4, 1:
/// Cortex-M0) over the bytes `x0..x1`, the planner's pick ringed.
fn plan_panel<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    (name, core): (&str, usize),
    (points, (x0, x1)): (&[PlanPoint], (f64, f64)),
    texts: &mut Vec<String>,
) -> Result<(), CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    let pick = planner_pick(name)?;
    let rows: Vec<(&PlanPoint, f64)> = points
        .iter()
        .filter(|p| p.0 == name)
        .filter_map(|p| p.3[core].map(|i| (p, i)))
        .collect();
    let ymax = rows.iter().map(|p| p.1).fold(0.0, f64::max) * 1.15 / 1e6;
    let mut chart = ChartBuilder::on(area)
        .margin(30)
        .build_cartesian_2d((x0..x1).log_scale(), 0f64..ymax)
        .map_err(|x| e(&x))?;
    chart
        .draw_series(LineSeries::new([(x0, ymax), (x0, 0.0), (x1, 0.0)], BLACK))
        .map_err(|x| e(&x))?;
    // Grid lines at powers of two of KB within the range, at most 6 (every other, every
    // third, … power when the data widen the range).
    let kbs: Vec<u64> = (0..32u32)
        .map(|k| 1u64 << k)
        .filter(|&kb| (x0..=x1).contains(&(kb as f64 * 1024.0)))
        .collect();
    let every = kbs.len().div_ceil(6).max(1);
    for &kb in kbs.iter().step_by(every) {
        let x = kb as f64 * 1024.0;
        let label = match kb {
            kb if kb >= 1 << 20 => format!("{} GB", kb >> 20),
            kb if kb >= 1 << 10 => format!("{} MB", kb >> 10),
            kb => format!("{kb} KB"),
        };
        chart
            .draw_series(LineSeries::new(
                [(x, 0.0), (x, ymax)],
                RGBColor(225, 225, 225),
            ))
            .map_err(|q| e(&q))?;
        let (px, py) = chart.backend_coord(&(x, 0.0));
        texts.push(format!(
            r#"<text x="{px}" y="{}" text-anchor="middle" font-size="11">{label}</text>"#,
            py + 14
        ));
    }
    let (tx, ty) = chart.backend_coord(&(x0, ymax));
    let core_name = ["Cortex-M4", "Cortex-M0"][core];
    texts.push(format!(
        r#"<text x="{}" y="{}" font-size="14" font-weight="bold">{name}, {core_name}</text>"#,
        tx + 6,
        ty + 14
    ));
    let (lx, ly) = chart.backend_coord(&(x0, 0.0));
    texts.push(format!(
        r#"<text x="{}" y="{}" text-anchor="end" font-size="11">0</text>"#,
        lx - 4,
        ly
    ));
    texts.push(format!(
        r#"<text x="{}" y="{}" text-anchor="end" font-size="11">{:.1} M</text>"#,
        lx - 4,
        ty + 10,
        ymax
    ));
    for (p, count) in rows {
        let (x, y) = (p.2, count / 1e6);
        let (px, py) = chart.backend_coord(&(x, y));
        if p.4 {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x / 1.04, y - ymax / 80.0), (x * 1.04, y + ymax / 80.0)],
                    RGBColor(150, 150, 150).filled(),
                )))
                .map_err(|q| e(&q))?;
        } else {
            chart
                .draw_series(std::iter::once(Circle::new(
                    (x, y),
                    5,
                    RGBColor(30, 90, 200).filled(),
                )))
                .map_err(|q| e(&q))?;
        }
        if !p.4 && p.1 == pick {
            chart
                .draw_series(std::iter::once(Circle::new(
                    (x, y),
                    10,
                    RGBColor(200, 30, 30).stroke_width(2),
                )))
                .map_err(|q| e(&q))?;
        }
        let label = if p.1 == "zbuffer" {
            "zbuffer (16-bit)".to_string()
        } else {
            p.1.clone()
        };
        // The painter sits on or near back faces' point on the quad and cube: label it on the
        // left; the compact bands near the 16-row bands: below.
        let (dx, dy, anchor) = match p.1.as_str() {
            "painter" => (-9, 4, "end"),
            "zbuffer_compact" => (9, 16, "start"),
            _ => (9, -6, "start"),
        };
        texts.push(format!(
            r#"<text x="{}" y="{}" text-anchor="{anchor}" font-size="11">{label}</text>"#,
            px + dx,
            py + dy
        ));
    }
    Ok(())
}
