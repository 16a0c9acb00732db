//! Random 3D scenes for the planner's and the methods' targets: 1 to 4 objects of the planner's
//! hard mesh kinds and ordinary ones, turned at random and placed at every distance from the
//! near plane to far away, seen by a perspective or an orthographic camera in a small
//! viewport (so that a case stays fast).
//!
//! Mesh kinds (each with its ranges, [`random_mesh`]): turned boxes from 0.001 to 0.8 units
//! across each side (thin slabs included); UV spheres of 3 to 10 segments and 2 to 6 rings,
//! radius 0.01 to 0.8 (tiny ones a pixel across); thin convex bicones (0.0005 to 0.05 thick,
//! long edges); a box with a decal (a coplanar triangle on its own vertices); a self-
//! intersecting quad (a bow-tie) inside a box of quads; a zero-area triangle inside a box; a
//! planar pentagram; two coplanar triangles overlapping, or folded on a shared edge; a soup of
//! 1 to 8 random triangles (interpenetrating); a torus (not convex). An object may repeat an
//! earlier one's mesh and place exactly (every depth ties), with other levels.
//!
//! Levels per vertex, per polygon or uniform, shading flat, exact or fast Gouraud, back faces
//! culled or not, dithered or not. The camera sits at `(0, 0, 6)` looking near the origin;
//! objects lie from half the near plane's distance to past the far plane, at most 80
//! units in front of it (some across the near or far plane), within 1.2
//! times the view's half-height of its axis, half of them scaled to 5 % to 150 % of it; the field of
//! view is 20° to 120°, `near` 0.01 to 1, `far/near` 10 to 10,000; the viewport 1 to 40 by 1 to
//! 32 pixels, its principal point sometimes anywhere within three widths of the picture.
//! Positions are rounded to I16F16 once, here.

use zscan::geometry::camera::{Camera, Lens, OrthoView, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::generators::{torus, torus_sizes, uv_sphere, uv_sphere_sizes};
use zscan::geometry::matrix::Affine3;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::raster::triangle::ShadeMode;
use zscan::render::{BandScratch, PreparedVertex, SceneRenderer};
use zscan::scene::{Intensities, Object, Scene};

use super::values::{chance, int, one_of, real, scale, size};
use crate::core_render::{render_picture, scene_of};
use crate::test_rng::XorShift as Rng;

/// One mesh's tables, all its polygons of `size` corners.
#[derive(Debug, Clone)]
pub struct Tables {
    /// What kind of mesh (for messages).
    pub kind: &'static str,
    /// Positions.
    pub vertices: Vec<Vec3>,
    /// Polygon corners.
    pub indices: Vec<u16>,
    /// Corners per polygon.
    pub size: u8,
}

impl Tables {
    fn new(kind: &'static str, points: &[[f64; 3]], indices: Vec<u16>, size: u8) -> Tables {
        let vertices = points.iter().map(|p| Vec3::new(c(p[0]), c(p[1]), c(p[2])));
        Tables {
            kind,
            vertices: vertices.collect(),
            indices,
            size,
        }
    }

    /// The core mesh (the generators here only make valid tables).
    pub fn mesh(&self) -> Result<Mesh<'_>, String> {
        Mesh::new(
            &self.vertices,
            &self.indices,
            PolygonSizes::Uniform(self.size),
        )
        .map_err(|e| format!("{}: {e}", self.kind))
    }

    fn polygons(&self) -> usize {
        self.indices.len() / self.size as usize
    }
}

/// How an object of a [`World`] is drawn.
#[derive(Debug, Clone)]
pub struct Placed {
    /// Index of its mesh in [`World::meshes`].
    pub mesh: usize,
    /// Model to world.
    pub transform: Affine3,
    /// Its levels: per vertex, per polygon, or one (`levels.len() == 1`).
    pub levels: Vec<u8>,
    /// Whether `levels` is per vertex.
    pub per_vertex: bool,
    /// Its shading.
    pub shade: ShadeMode,
    /// Back faces culled.
    pub cull: bool,
    /// Dithered.
    pub dither: bool,
}

/// A random scene: meshes, objects and the camera.
#[derive(Debug, Clone)]
pub struct World {
    /// The meshes.
    pub meshes: Vec<Tables>,
    /// The objects, in scene order.
    pub objects: Vec<Placed>,
    /// The camera.
    pub camera: Camera,
}

impl World {
    /// The core objects, in scene order.
    pub fn objects(&self) -> Result<Vec<Object<'_>>, String> {
        self.objects
            .iter()
            .map(|p| {
                let mut o = Object::new(self.meshes[p.mesh].mesh()?);
                o.transform = p.transform;
                o.intensities = match (p.levels.len(), p.per_vertex) {
                    (1, _) => Intensities::Uniform(p.levels[0]),
                    (_, true) => Intensities::PerVertex(&p.levels),
                    (_, false) => Intensities::PerPolygon(&p.levels),
                };
                o.shade = p.shade;
                o.cull_back_faces = p.cull;
                o.dither = p.dither;
                Ok(o)
            })
            .collect()
    }

    /// The scene of `objects` (from [`World::objects`]) seen by the camera, unlit.
    pub fn scene<'a>(&self, objects: &'a [Object<'a>]) -> Scene<'a> {
        scene_of(objects, self.camera)
    }

    /// The viewport's size.
    pub fn size(&self) -> (u16, u16) {
        let vp = self.camera.viewport();
        (vp.width, vp.height)
    }
}

fn c(v: f64) -> Coord {
    Coord::from_num(v)
}

/// The corners of the box `±s` and its 6 faces as quads, counter-clockwise from outside.
fn box_quads(s: [f64; 3]) -> (Vec<[f64; 3]>, Vec<u16>) {
    let points = (0..8)
        .map(|k| [0, 1, 2].map(|a| if k >> a & 1 == 0 { -s[a] } else { s[a] }))
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    (points, quads.concat())
}

/// Quads as two triangles each.
fn triangles(quads: &[u16]) -> Vec<u16> {
    quads
        .chunks(4)
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect()
}

/// A random mesh of one of the kinds of the module doc.
pub fn random_mesh(rng: &mut Rng) -> Tables {
    match int(rng, 0, 10) {
        0 | 1 => {
            let s = [0; 3].map(|_| scale(rng, 0.0005, 0.4));
            let (points, quads) = box_quads(s);
            Tables::new("box", &points, triangles(&quads), 3)
        }
        2 => {
            let (seg, rings) = (int(rng, 3, 10) as u16, int(rng, 2, 6) as u16);
            let (nv, ni) = uv_sphere_sizes(seg, rings);
            let (mut vertices, mut indices) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            let r = c(scale(rng, 0.01, 0.8));
            match uv_sphere(seg, rings, r, &mut vertices, &mut indices).map(|_| ()) {
                Ok(()) => Tables {
                    kind: "sphere",
                    vertices,
                    indices,
                    size: 3,
                },
                Err(_) => Tables::new(
                    "box",
                    &box_quads([0.3; 3]).0,
                    triangles(&box_quads([0.3; 3]).1),
                    3,
                ),
            }
        }
        3 => {
            let n = int(rng, 3, 24) as u16;
            let (r, h) = (real(rng, 0.3, 1.2), scale(rng, 0.0005, 0.05));
            let mut points: Vec<[f64; 3]> = (0..n)
                .map(|k| {
                    let a = k as f64 * std::f64::consts::TAU / n as f64;
                    [r * a.cos(), 0.0, r * a.sin()]
                })
                .collect();
            points.extend([[0.0, h / 2.0, 0.0], [0.0, -h / 2.0, 0.0]]);
            let is = (0..n)
                .flat_map(|k| {
                    let j = (k + 1) % n;
                    [n, j, k, n + 1, k, j]
                })
                .collect();
            Tables::new("thin bicone", &points, is, 3)
        }
        4 => {
            let (points, quads) = box_quads([real(rng, 0.1, 0.7); 3]);
            let mut is = triangles(&quads);
            let top = is[6..9].to_vec();
            is.extend(top);
            Tables::new("decal on a box", &points, is, 3)
        }
        5 => {
            let (mut points, mut is) = box_quads([0.6; 3]);
            let b = points.len() as u16;
            let z = real(rng, -0.5, 0.5);
            points.extend([
                [-0.4, -0.4, z],
                [0.4, 0.4, z],
                [0.4, -0.4, z],
                [-0.4, 0.4, z],
            ]);
            is.extend([b, b + 1, b + 2, b + 3]);
            Tables::new("bow-tie in a box", &points, is, 4)
        }
        6 => {
            let (mut points, quads) = box_quads([0.6; 3]);
            let mut is = triangles(&quads);
            let b = points.len() as u16;
            let (p, d) = (
                [0.0; 3].map(|_| real(rng, -0.4, 0.4)),
                [0.0; 3].map(|_| real(rng, -0.2, 0.2)),
            );
            let t = real(rng, 0.2, 1.0);
            points.extend([
                p,
                [p[0] + d[0], p[1] + d[1], p[2] + d[2]],
                [p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]],
            ]);
            is.extend([b, b + 1, b + 2]);
            Tables::new("zero-area triangle in a box", &points, is, 3)
        }
        7 => {
            let r = real(rng, 0.2, 1.0);
            let star: Vec<[f64; 3]> = (0..5)
                .map(|k| {
                    let a =
                        std::f64::consts::FRAC_PI_2 + k as f64 * 4.0 * std::f64::consts::PI / 5.0;
                    [r * a.cos(), r * a.sin(), 0.0]
                })
                .collect();
            Tables::new("pentagram", &star, vec![0, 1, 2, 3, 4], 5)
        }
        8 => {
            let p = |rng: &mut Rng| [real(rng, -0.8, 0.8), real(rng, -0.8, 0.8), 0.0];
            if chance(rng, 50) {
                let points: Vec<[f64; 3]> = (0..6).map(|_| p(rng)).collect();
                Tables::new(
                    "overlapping coplanar triangles",
                    &points,
                    vec![0, 1, 2, 3, 4, 5],
                    3,
                )
            } else {
                let points: Vec<[f64; 3]> = (0..4).map(|_| p(rng)).collect();
                Tables::new(
                    "coplanar triangles on a shared edge",
                    &points,
                    vec![0, 1, 2, 0, 1, 3],
                    3,
                )
            }
        }
        9 => {
            let n = size(rng, 1, 8);
            let points: Vec<[f64; 3]> = (0..3 * n)
                .map(|_| [0; 3].map(|_| real(rng, -0.8, 0.8)))
                .collect();
            Tables::new("soup", &points, (0..3 * n as u16).collect(), 3)
        }
        _ => {
            let (rings, sides) = (int(rng, 3, 8) as u16, int(rng, 3, 6) as u16);
            let (nv, ni) = torus_sizes(rings, sides);
            let (mut vertices, mut indices) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            let (a, b) = (real(rng, 0.3, 0.7), real(rng, 0.05, 0.25));
            match torus(rings, sides, c(a), c(b), &mut vertices, &mut indices).map(|_| ()) {
                Ok(()) => Tables {
                    kind: "torus",
                    vertices,
                    indices,
                    size: 4,
                },
                Err(_) => Tables::new("pentagram", &[[0.0; 3]; 5], vec![0, 1, 2, 3, 4], 5),
            }
        }
    }
}

/// The shadings a world's objects take.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shades {
    /// Flat, exact Gouraud and fast Gouraud.
    All,
    /// Flat and exact Gouraud only.
    Exact,
}

/// A random world; `orthographic` allows an orthographic camera (one in four).
pub fn random_world(rng: &mut Rng, orthographic: bool, shades: Shades) -> Result<World, String> {
    let (w, h) = (int(rng, 1, 40) as u16, int(rng, 1, 32) as u16);
    let mut viewport = Viewport::new(w, h);
    if chance(rng, 15) {
        viewport.principal_x = c(real(rng, -3.0 * w as f64, 3.0 * w as f64));
        viewport.principal_y = c(real(rng, -3.0 * h as f64, 3.0 * h as f64));
    }
    let near = scale(rng, 0.01, 1.0);
    let far = (near * scale(rng, 10.0, 10_000.0)).min(32_000.0);
    let eye = Vec3::new(c(0.0), c(0.0), c(6.0));
    let target = Vec3::new(c(real(rng, -0.5, 0.5)), c(real(rng, -0.5, 0.5)), c(0.0));
    let up = Vec3::new(c(real(rng, -0.3, 0.3)), c(1.0), c(0.0));
    let ortho = orthographic && chance(rng, 25);
    let (extent, fov_deg) = (scale(rng, 0.5, 20.0), int(rng, 20, 120));
    let camera = if ortho {
        let view = OrthoView::new(c(extent), c(near), c(far));
        Camera::look_at_orthographic(eye, target, up, view, viewport)
    } else {
        let fov = BinaryAngle::from_degrees(fov_deg as i32);
        Camera::look_at(eye, target, up, Lens::new(fov, c(near), c(far)), viewport)
    }
    .map_err(|e| format!("camera: {e}"))?;
    // Half the view's height at a distance `d`: objects are placed within 1.2 times it of the
    // view's axis (most on the picture, some across its edges).
    let half = |d: f64| {
        if ortho {
            extent / 2.0
        } else {
            d * (fov_deg as f64 / 2.0).to_radians().tan()
        }
    };
    let mut meshes: Vec<Tables> = Vec::new();
    let mut objects: Vec<Placed> = Vec::new();
    // Packed (interpenetrating, overlapping on screen) or spread (separable) around a depth.
    // From half the near plane's distance to past the far plane (or 80 units).
    let (lo, hi) = ((near / 2.0).max(0.05), (far * 1.2).min(80.0));
    let distance = if lo < hi { scale(rng, lo, hi) } else { lo };
    let spread = one_of(rng, &[0.0, 0.3, 1.0, 3.0]);
    for _ in 0..size(rng, 1, 4) {
        let repeat = !objects.is_empty() && chance(rng, 15);
        let (mesh, transform) = if repeat {
            let earlier = &objects[size(rng, 0, objects.len() - 1)];
            (earlier.mesh, earlier.transform)
        } else {
            meshes.push(random_mesh(rng));
            let d = (distance + real(rng, -spread, spread)).max(0.05);
            let turn = |rng: &mut Rng| BinaryAngle(rng.next_u64() as u32);
            // Half the objects keep their size (tiny far away), half are scaled to 5 % to
            // 150 % of the view's half-height where they stand (at most 60 times,
            // within the matrices' range of 64).
            let size = if chance(rng, 50) {
                (half(d) * scale(rng, 0.05, 1.5)).clamp(0.01, 60.0)
            } else {
                1.0
            };
            let transform = Affine3::builder()
                .scale(c(size))
                .rotate_x(turn(rng))
                .rotate_y(turn(rng))
                .rotate_z(turn(rng))
                .translate(Vec3::new(
                    c(real(rng, -1.2, 1.2) * half(d)),
                    c(real(rng, -1.2, 1.2) * half(d)),
                    c(6.0 - d),
                ))
                .build()
                .map_err(|e| format!("transform: {e}"))?;
            (meshes.len() - 1, transform)
        };
        let t = &meshes[mesh];
        let per_vertex = chance(rng, 50);
        let n = match int(rng, 0, 5) {
            0 => 1,
            _ if per_vertex => t.vertices.len(),
            _ => t.polygons(),
        };
        let levels = (0..n).map(|_| int(rng, 0, 255) as u8).collect();
        let shade = match shades {
            Shades::All => one_of(
                rng,
                &[
                    ShadeMode::Flat,
                    ShadeMode::GouraudExact,
                    ShadeMode::GouraudFast,
                ],
            ),
            Shades::Exact => one_of(rng, &[ShadeMode::Flat, ShadeMode::GouraudExact]),
        };
        objects.push(Placed {
            mesh,
            transform,
            levels,
            per_vertex,
            shade,
            cull: !chance(rng, 15),
            dither: chance(rng, 15),
        });
    }
    Ok(World {
        meshes,
        objects,
        camera,
    })
}

/// The reference every method and plan is compared with: the z-buffer's whole-frame picture
/// at 16 or 32 bits (every object's vertices in scratch, one pass), or its error in words.
pub fn zbuffer(renderer: &SceneRenderer<'_, 4>, bits16: bool) -> Result<Vec<u8>, String> {
    let scene = renderer.scene();
    let vp = *scene.camera.viewport();
    let nv: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let mut scratch = vec![PreparedVertex::default(); nv.max(1)];
    let band = BandScratch {
        vertices: &mut scratch,
        polygons: &mut [],
    };
    let size = (vp.width, vp.height);
    let picture = if bits16 {
        render_picture::<u16, 4>(renderer, size, None, band).map(|p| p.0)
    } else {
        render_picture::<u32, 4>(renderer, size, None, band).map(|p| p.0)
    };
    picture.map_err(|e| e.to_string())
}

/// The first pixel where `got` differs from `want`, in words (`None`: the same picture).
pub fn first_difference(got: &[u8], want: &[u8], width: u16) -> Option<String> {
    if got.len() != want.len() {
        return Some(format!("{} pixels against {}", got.len(), want.len()));
    }
    let wrong = got.iter().zip(want).filter(|(a, b)| a != b).count();
    let at = got.iter().zip(want).position(|(a, b)| a != b)?;
    let w = width.max(1) as usize;
    Some(format!(
        "{wrong} pixels differ, the first at ({}, {}): {} against {}",
        at % w,
        at / w,
        got[at],
        want[at]
    ))
}
