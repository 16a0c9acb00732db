//! The four standard benchmark scenes of `docs/SCENES.md` (`quad`, `cube`, `sphere`,
//! `bunny`), built in `f64` exactly as that document defines them, and the generic
//! "camera + triangles" description [`Scene`] that the float reference renderer
//! ([`crate::reference::float_render`]) draws and `zscan export-scenes` writes out.
//!
//! ## Conventions (those of SCENES.md)
//! - World: right-handed, `x` right, `y` up, `z` toward the viewer. Positive rotation angles are
//!   counter-clockwise looking down the axis toward the origin (right-hand rule), so
//!   `R_y(a)·(1, 0, 0) = (cos a, 0, −sin a)`.
//! - Camera ([`Camera::standard`]): eye `(0, 0, 3)`, target the origin, up `+y`, vertical field of
//!   view 60°, near 0.5, far 10, 320 × 240 pixels. Pixels are lattice points (zscan's
//!   convention), so the principal point is `(159.5, 119.5)`: that draws the same picture as
//!   pixel centres `(i + 0.5, j + 0.5)` with the optical axis at `(160, 120)`.
//! - Front faces are counter-clockwise seen from outside; every scene here is built that way.
//! - Per-corner intensity `I = clamp(0.1 + 0.9·max(0, N·L), 0, 1)`, stored as `round(255·I)`,
//!   with `L = normalize(1, 1, 1)`; `N` is the face normal (quad, cube) or the normalised sum of
//!   the un-normalised cross products of the adjacent triangles (sphere, bunny).
//! - "Fit to F": a uniform scale `s` about the origin such that the `y` extent of the vertices'
//!   perspective projections (continuous screen units) is `F × 240`. The projection is not
//!   linear in `s`, so [`fit_scale`] solves for it by bisection (the extent grows monotonically
//!   with `s` while the object stays in front of the eye).
//!
//! ## Scene-specific choices SCENES.md leaves open (documented here)
//! - quad: vertices `(−,−) (+,−) (+,+) (−,+)`, triangles `[0,1,2]` and `[0,2,3]` (the split
//!   along `(−,−)–(+,+)`).
//! - cube: 8 shared vertices, vertex `i` has `x = ±0.5` from bit 0, `y` from bit 1, `z` from
//!   bit 2 (bit set = `+`); each face split along the diagonal through its lowest-index corner.
//! - sphere: azimuth grows by the right-hand rule about `+y`: segment `j` of ring `k` is at
//!   `(sin θ cos φ, cos θ, −sin θ sin φ)` with `θ = πk/16`, `φ = 2πj/32`.
//! - bunny: the mesh is read with [`crate::obj::load_obj`] as stored (outward winding), polygons
//!   fanned as `(0, i, i+1)` (the file holds triangles only).
use std::f64::consts::PI;

/// A 3-vector of `f64` (world or view space).
pub type Vec3 = [f64; 3];

/// The light direction of every standard scene, `normalize(1, 1, 1)`, in the world frame.
pub fn light_direction() -> Vec3 {
    normalize([1.0, 1.0, 1.0])
}

/// A pinhole camera: where it is, where it looks, and the screen it projects to.
///
/// Projection (see [`Camera::project`]): in the camera frame (`right`, `up`, `forward`), a point
/// at depth `d` along `forward` lands on screen at
/// `(principal.0 + f·x/d, principal.1 − f·y/d)` with `f = (height/2) / tan(fov_y/2)`, `y` down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Position of the eye (world).
    pub eye: Vec3,
    /// A point the camera looks at (world).
    pub target: Vec3,
    /// The world direction that appears up on screen (need not be orthogonal to the view).
    pub up: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f64,
    /// Near plane: distance along the view direction.
    pub near: f64,
    /// Far plane: distance along the view direction.
    pub far: f64,
    /// Screen width in pixels.
    pub width: u32,
    /// Screen height in pixels.
    pub height: u32,
    /// Where the optical axis meets the screen, in pixel units with lattice-point pixels
    /// (`(159.5, 119.5)` for the standard 320 × 240 screen).
    pub principal: (f64, f64),
}

impl Camera {
    /// The standard benchmark camera of SCENES.md, with lattice-point pixels.
    pub fn standard() -> Camera {
        Camera {
            eye: [0.0, 0.0, 3.0],
            target: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_y: 60f64.to_radians(),
            near: 0.5,
            far: 10.0,
            width: 320,
            height: 240,
            principal: (159.5, 119.5),
        }
    }

    /// The focal length in pixels: `(height / 2) / tan(fov_y / 2)`.
    pub fn focal(&self) -> f64 {
        (self.height as f64 / 2.0) / (self.fov_y / 2.0).tan()
    }

    /// The camera frame `(right, up, forward)` as unit world vectors.
    pub fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let forward = normalize(sub(self.target, self.eye));
        let right = normalize(cross(forward, self.up));
        let up = cross(right, forward);
        (right, up, forward)
    }

    /// World → view: `(x right, y up, d forward)`, `d` the depth along the view direction.
    pub fn to_view(&self, p: Vec3) -> Vec3 {
        let (r, u, f) = self.basis();
        let q = sub(p, self.eye);
        [dot(q, r), dot(q, u), dot(q, f)]
    }

    /// View → screen (lattice-point pixels, `y` down). Only meaningful for `d > 0`.
    pub fn project_view(&self, v: Vec3) -> (f64, f64) {
        let f = self.focal();
        (
            self.principal.0 + f * v[0] / v[2],
            self.principal.1 - f * v[1] / v[2],
        )
    }

    /// World → screen; `None` when the point is not in front of the eye (`d ≤ 0`).
    pub fn project(&self, p: Vec3) -> Option<(f64, f64)> {
        let v = self.to_view(p);
        (v[2] > 0.0).then(|| self.project_view(v))
    }

    /// Checks that the camera is usable: a proper frame, `0 < near < far`, a field of view in
    /// `(0, π)`, a non-empty screen.
    pub fn validate(&self) -> Result<(), String> {
        let fwd = sub(self.target, self.eye);
        if !dot(fwd, fwd).is_finite() || dot(fwd, fwd) <= 0.0 {
            return Err("camera eye and target coincide".into());
        }
        let side = cross(normalize(fwd), self.up);
        if dot(side, side).is_nan() || dot(side, side) <= 1e-24 {
            return Err("camera up vector is parallel to the view direction".into());
        }
        if !(self.near > 0.0 && self.far > self.near && self.far.is_finite()) {
            return Err(format!(
                "camera planes must satisfy 0 < near < far (near {}, far {})",
                self.near, self.far
            ));
        }
        if !(self.fov_y > 0.0 && self.fov_y < PI) {
            return Err(format!(
                "field of view {} rad is outside (0, π)",
                self.fov_y
            ));
        }
        if self.width == 0 || self.height == 0 {
            return Err("screen has no pixels".into());
        }
        Ok(())
    }
}

/// A camera and a triangle mesh with per-corner intensities: a standard scene or any random one.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Short name (`"quad"`, `"cube"`, `"sphere"`, `"bunny"` for the standard scenes).
    pub name: String,
    /// The camera.
    pub camera: Camera,
    /// World-space vertex positions (after placement and fit scale).
    pub vertices: Vec<Vec3>,
    /// Triangles as vertex indices, counter-clockwise seen from the front.
    pub triangles: Vec<[usize; 3]>,
    /// Per-triangle, per-corner intensity 0..=255 (`intensities[t][c]` belongs to
    /// `triangles[t][c]`).
    pub intensities: Vec<[u8; 3]>,
    /// The uniform scale applied by the fit (1 when there was none).
    pub scale: f64,
}

impl Scene {
    /// A scene from independent triangles ("triangle soup"): each triangle gets its own three
    /// vertices. Convenient for random scenes.
    pub fn from_triangles(
        name: &str,
        camera: Camera,
        triangles: &[[Vec3; 3]],
        intensities: &[[u8; 3]],
    ) -> Result<Scene, String> {
        if triangles.len() != intensities.len() {
            return Err(format!(
                "{} triangles but {} intensity triples",
                triangles.len(),
                intensities.len()
            ));
        }
        let scene = Scene {
            name: name.to_string(),
            camera,
            vertices: triangles.iter().flatten().copied().collect(),
            triangles: (0..triangles.len())
                .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
                .collect(),
            intensities: intensities.to_vec(),
            scale: 1.0,
        };
        scene.validate()?;
        Ok(scene)
    }

    /// Checks sizes, indices, finiteness and the camera.
    pub fn validate(&self) -> Result<(), String> {
        self.camera.validate()?;
        if self.intensities.len() != self.triangles.len() {
            return Err(format!(
                "scene {}: {} triangles but {} intensity triples",
                self.name,
                self.triangles.len(),
                self.intensities.len()
            ));
        }
        if let Some(i) = self
            .vertices
            .iter()
            .position(|v| v.iter().any(|c| !c.is_finite()))
        {
            return Err(format!("scene {}: vertex {i} is not finite", self.name));
        }
        if let Some(t) = self
            .triangles
            .iter()
            .position(|t| t.iter().any(|&i| i >= self.vertices.len()))
        {
            return Err(format!(
                "scene {}: triangle {t} indexes past the {} vertices",
                self.name,
                self.vertices.len()
            ));
        }
        Ok(())
    }

    /// The un-normalised face normal `(b − a) × (c − a)` of triangle `t` (twice its area).
    pub fn face_cross(&self, t: usize) -> Vec3 {
        let [a, b, c] = self.triangles[t].map(|i| self.vertices[i]);
        cross(sub(b, a), sub(c, a))
    }
}

/// The names of the standard scenes, in SCENES.md's order.
pub const STANDARD_SCENES: [&str; 4] = ["quad", "cube", "sphere", "bunny"];

/// Builds a standard scene by name (`quad`, `cube`, `sphere`, `bunny`).
pub fn standard_scene(name: &str) -> Result<Scene, String> {
    match name {
        "quad" => Ok(quad()),
        "cube" => Ok(cube()),
        "sphere" => Ok(sphere()),
        "bunny" => bunny(),
        _ => Err(format!(
            "unknown scene {name:?}; the standard scenes are {}",
            STANDARD_SCENES.join(", ")
        )),
    }
}

/// All four standard scenes in SCENES.md's order.
pub fn standard_scenes() -> Result<Vec<Scene>, String> {
    STANDARD_SCENES.iter().map(|n| standard_scene(n)).collect()
}

/// `quad`: the square `(±2.45, ±1.85, 0)` facing the camera, split along `(−,−)–(+,+)`,
/// covering the whole screen. Scale 1; flat face-normal lighting.
pub fn quad() -> Scene {
    let vertices = vec![
        [-2.45, -1.85, 0.0],
        [2.45, -1.85, 0.0],
        [2.45, 1.85, 0.0],
        [-2.45, 1.85, 0.0],
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3]];
    finish_flat("quad", vertices, triangles, 1.0)
}

/// `cube`: corners `(±0.5, ±0.5, ±0.5)`, rotated 30° about Y then 20° about X
/// (`v' = R_x·R_y·v`), fitted to 0.60 of the screen height. Flat face-normal lighting.
pub fn cube() -> Scene {
    let corners: Vec<Vec3> = (0..8)
        .map(|i| {
            let c = |bit: usize| if i >> bit & 1 == 1 { 0.5 } else { -0.5 };
            [c(0), c(1), c(2)]
        })
        .collect();
    // Faces as corner quads, counter-clockwise seen from outside.
    let faces: [[usize; 4]; 6] = [
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
    ];
    let triangles: Vec<[usize; 3]> = faces
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    let rot = mat_mul(rot_x(20f64.to_radians()), rot_y(30f64.to_radians()));
    let placed: Vec<Vec3> = corners.iter().map(|&v| mat_vec(rot, v)).collect();
    let s = fit_scale(&placed, &Camera::standard(), 0.60);
    let vertices = placed.iter().map(|&v| scale(v, s)).collect();
    finish_flat("cube", vertices, triangles, s)
}

/// Segments of the standard UV sphere.
pub const SPHERE_SEGMENTS: usize = 32;
/// Rings of the standard UV sphere (15 vertex rings between the poles).
pub const SPHERE_RINGS: usize = 16;

/// `sphere`: the UV sphere of SCENES.md (32 segments, 16 rings, 482 vertices, 960 triangles;
/// vertex 0 the north pole, then 15 rings of 32 from north to south, then the south pole; band
/// quads split along `(ring k, j)–(ring k+1, j+1)`), fitted to 0.70. Smooth vertex-normal
/// lighting.
pub fn sphere() -> Scene {
    let (n_seg, n_ring) = (SPHERE_SEGMENTS, SPHERE_RINGS);
    let mut unit = vec![[0.0, 1.0, 0.0]];
    for k in 1..n_ring {
        let theta = PI * k as f64 / n_ring as f64;
        for j in 0..n_seg {
            let phi = 2.0 * PI * j as f64 / n_seg as f64;
            let r = theta.sin();
            unit.push([r * phi.cos(), theta.cos(), -r * phi.sin()]);
        }
    }
    unit.push([0.0, -1.0, 0.0]);
    let south = unit.len() - 1;
    // Index of ring k (1..=15), segment j (wrapping).
    let at = |k: usize, j: usize| 1 + (k - 1) * n_seg + j % n_seg;
    let mut triangles = Vec::with_capacity(2 * n_seg * (n_ring - 1));
    for j in 0..n_seg {
        triangles.push([0, at(1, j), at(1, j + 1)]);
    }
    for k in 1..n_ring - 1 {
        for j in 0..n_seg {
            triangles.push([at(k, j), at(k + 1, j), at(k + 1, j + 1)]);
            triangles.push([at(k, j), at(k + 1, j + 1), at(k, j + 1)]);
        }
    }
    for j in 0..n_seg {
        triangles.push([at(n_ring - 1, j), south, at(n_ring - 1, j + 1)]);
    }
    let s = fit_scale(&unit, &Camera::standard(), 0.70);
    let vertices = unit.iter().map(|&v| scale(v, s)).collect();
    finish_smooth("sphere", vertices, triangles, s)
}

/// The Stanford bunny (public domain), `host-tests/meshes/bunny.obj`, built into the binary so
/// that the tool and the tests find it wherever they run from.
pub const BUNNY_OBJ: &str = include_str!("../meshes/bunny.obj");

/// The bunny mesh parsed from [`BUNNY_OBJ`].
pub fn bunny_mesh() -> Result<crate::obj::ObjMesh, String> {
    crate::obj::parse_obj(BUNNY_OBJ).map_err(|e| format!("built-in bunny mesh: {e}"))
}

/// `bunny`: `host-tests/meshes/bunny.obj` with its bounding box centred, rotated +90° about Y (it
/// then faces the camera), centred again, fitted to 0.70 ([`place`], as `zscan mesh --centre
/// --turn-y 90 --fit 0.7` places it). Smooth vertex-normal lighting.
pub fn bunny() -> Result<Scene, String> {
    let mesh = bunny_mesh()?;
    // Polygons fanned as (0, i, i + 1); the bunny's are all triangles already.
    let triangles: Vec<[usize; 3]> = mesh
        .polygons
        .iter()
        .flat_map(|p| (1..p.len() - 1).map(move |i| [p[0], p[i], p[i + 1]]))
        .collect();
    let (vertices, s) = place(&mesh.vertices, &STANDARD_BUNNY);
    Ok(finish_smooth("bunny", vertices, triangles, s))
}

/// How [`place`] puts a mesh read from a file in the model frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Centre the bounding box on the origin (again after the turn, when there is one).
    pub centre: bool,
    /// Turn about `+y` by this many degrees (right-hand rule), after centring.
    pub turn_y_degrees: Option<f64>,
    /// The size, last.
    pub size: Size,
}

/// The size [`place`] gives a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Size {
    /// As read.
    Keep,
    /// A uniform scale about the origin.
    Scale(f64),
    /// "Fit to F" of SCENES.md ([`fit_scale`] with [`Camera::standard`]).
    Fit(f64),
}

/// The standard bunny's placement (SCENES.md).
pub const STANDARD_BUNNY: Placement = Placement {
    centre: true,
    turn_y_degrees: Some(90.0),
    size: Size::Fit(0.70),
};

/// `vertices` placed as `p` says (centre, turn, centre again, then the size), and the scale
/// applied (1 for [`Size::Keep`]).
pub fn place(vertices: &[Vec3], p: &Placement) -> (Vec<Vec3>, f64) {
    let centre = |v: Vec<Vec3>| if p.centre { centre_bounding_box(&v) } else { v };
    let mut placed = centre(vertices.to_vec());
    if let Some(degrees) = p.turn_y_degrees {
        let rot = rot_y(degrees.to_radians());
        placed = centre(placed.iter().map(|&v| mat_vec(rot, v)).collect());
    }
    let s = match p.size {
        Size::Keep => 1.0,
        Size::Scale(s) => s,
        Size::Fit(f) => fit_scale(&placed, &Camera::standard(), f),
    };
    (placed.iter().map(|&v| scale(v, s)).collect(), s)
}

/// The per-corner intensity of SCENES.md for a unit normal `n`:
/// `round(255 · clamp(0.1 + 0.9·max(0, n·L), 0, 1))`.
pub fn intensity(n: Vec3) -> u8 {
    let i = (0.1 + 0.9 * dot(n, light_direction()).max(0.0)).clamp(0.0, 1.0);
    (i * 255.0).round() as u8
}

/// The uniform scale `s` about the origin for which the `y` extent of the projections of
/// `s·v` through `camera` is `fraction × camera.height` pixels (bisection to full `f64`
/// precision). Assumes the object contains or surrounds the origin and stays in front of the
/// eye over the search range.
pub fn fit_scale(vertices: &[Vec3], camera: &Camera, fraction: f64) -> f64 {
    let goal = fraction * camera.height as f64;
    let extent = |s: f64| {
        let ys = vertices
            .iter()
            .filter_map(|&v| camera.project(scale(v, s)).map(|p| p.1));
        let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
            (lo.min(y), hi.max(y))
        });
        hi - lo
    };
    // Largest scale keeping every vertex in front of the near plane's eye-side half-space.
    let d_eye = |v: Vec3| dot(sub(v, camera.eye), camera.basis().2);
    let mut hi = 1.0;
    while extent(hi) < goal && hi < 1e12 {
        hi *= 2.0;
        if vertices.iter().any(|&v| d_eye(scale(v, hi)) <= 0.0) {
            break;
        }
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if extent(mid) < goal {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

fn finish_flat(name: &str, vertices: Vec<Vec3>, triangles: Vec<[usize; 3]>, s: f64) -> Scene {
    let mut scene = Scene {
        name: name.to_string(),
        camera: Camera::standard(),
        vertices,
        triangles,
        intensities: Vec::new(),
        scale: s,
    };
    scene.intensities = (0..scene.triangles.len())
        .map(|t| [intensity(normalize(scene.face_cross(t))); 3])
        .collect();
    scene
}

fn finish_smooth(name: &str, vertices: Vec<Vec3>, triangles: Vec<[usize; 3]>, s: f64) -> Scene {
    let mut scene = Scene {
        name: name.to_string(),
        camera: Camera::standard(),
        vertices,
        triangles,
        intensities: Vec::new(),
        scale: s,
    };
    let mut normals = vec![[0.0; 3]; scene.vertices.len()];
    for t in 0..scene.triangles.len() {
        let c = scene.face_cross(t);
        for &i in &scene.triangles[t] {
            normals[i] = add(normals[i], c);
        }
    }
    let level: Vec<u8> = normals.iter().map(|&n| intensity(normalize(n))).collect();
    scene.intensities = scene
        .triangles
        .iter()
        .map(|t| t.map(|i| level[i]))
        .collect();
    scene
}

fn centre_bounding_box(v: &[Vec3]) -> Vec<Vec3> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in v {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    let c = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
    v.iter().map(|&p| sub(p, c)).collect()
}

type Mat3 = [[f64; 3]; 3];

/// Rotation about X by `a` radians (right-hand rule).
fn rot_x(a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}

/// Rotation about Y by `a` radians (right-hand rule).
fn rot_y(a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn mat_mul(a: Mat3, b: Mat3) -> Mat3 {
    let mut m = [[0.0; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().enumerate() {
            *e = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

fn mat_vec(m: Mat3, v: Vec3) -> Vec3 {
    m.map(|row| dot(row, v))
}

/// `a + b`.
pub fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a − b`.
pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s·v`.
pub fn scale(v: Vec3, s: f64) -> Vec3 {
    [v[0] * s, v[1] * s, v[2] * s]
}

/// `a · b`.
pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a × b`.
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v / |v|` (`v` unchanged when it is zero).
pub fn normalize(v: Vec3) -> Vec3 {
    let n = dot(v, v).sqrt();
    if n > 0.0 {
        scale(v, 1.0 / n)
    } else {
        v
    }
}
