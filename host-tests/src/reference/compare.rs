//! Helpers for comparing a core frame with the `f64` reference ([`super::float_render`]):
//! the projected (unsnapped) outlines of a scene's triangles, distances from pixels to them,
//! the inverse of the core's depth mapping `D(z)` and per-pixel plane facts (depth, gradients).
//!
//! Everything here is `f64` and independent of the core: it re-derives from the host
//! [`Scene`] what the reference renderer computes, so tests can explain each pixel on which
//! the core and the reference disagree.
use crate::scenes::{cross, dot, sub, Scene, Vec3};

/// A triangle of the scene as the reference draws it: front-facing, clipped to the near and far
/// planes, projected without snapping.
#[derive(Debug, Clone, PartialEq)]
pub struct Outline {
    /// Index of the scene triangle.
    pub triangle: usize,
    /// The clipped polygon on screen (lattice-point pixels, `y` down), 3 to 5 vertices.
    pub screen: Vec<(f64, f64)>,
    /// The triangle's corners in view space (`x` right, `y` up, `d` forward), unclipped.
    pub view: [Vec3; 3],
    /// Whether the near or far plane cut it (then `screen` holds clip points).
    pub clipped: bool,
}

/// The outlines of every triangle of `scene` the reference would draw (front-facing by its
/// world-space test, not wholly beyond the near or far plane), in the scene's order. With
/// `include_back_faces` culled triangles are included too.
pub fn outlines(scene: &Scene, include_back_faces: bool) -> Vec<Outline> {
    let cam = &scene.camera;
    let mut out = Vec::new();
    for (t, tri) in scene.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|i| scene.vertices[i]);
        let front = dot(cross(sub(b, a), sub(c, a)), sub(cam.eye, a)) > 0.0;
        if !front && !include_back_faces {
            continue;
        }
        let view = tri.map(|i| cam.to_view(scene.vertices[i]));
        let clipped = view.iter().any(|v| v[2] < cam.near || v[2] > cam.far);
        let poly = clip(&view, |v| v[2] - cam.near);
        let poly = clip(&poly, |v| cam.far - v[2]);
        if poly.len() < 3 {
            continue;
        }
        out.push(Outline {
            triangle: t,
            screen: poly.iter().map(|&v| cam.project_view(v)).collect(),
            view,
            clipped,
        });
    }
    out
}

/// Sutherland–Hodgman against `dist(v) ≥ 0` (points on the plane kept).
pub fn clip(poly: &[Vec3], dist: impl Fn(Vec3) -> f64) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (dp, dq) = (dist(p), dist(q));
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            let s = dp / (dp - dq);
            out.push([0, 1, 2].map(|k| p[k] + s * (q[k] - p[k])));
        }
    }
    out
}

/// Euclidean distance from `p` to the segment `a–b`.
pub fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (a.0 + t * dx, a.1 + t * dy);
    ((p.0 - qx).powi(2) + (p.1 - qy).powi(2)).sqrt()
}

/// Distance from `p` to the nearest edge of one outline.
pub fn distance_to_outline(p: (f64, f64), o: &Outline) -> f64 {
    let n = o.screen.len();
    (0..n)
        .map(|i| distance_to_segment(p, o.screen[i], o.screen[(i + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}

/// Distance from `p` to the nearest edge of any of `outlines`.
pub fn distance_to_outlines(p: (f64, f64), outlines: &[Outline]) -> f64 {
    outlines
        .iter()
        .map(|o| distance_to_outline(p, o))
        .fold(f64::INFINITY, f64::min)
}

/// Whether `p` lies inside or on the closed projected polygon (convex, either orientation).
pub fn inside_closed(p: (f64, f64), poly: &[(f64, f64)]) -> bool {
    let n = poly.len();
    let (mut pos, mut neg) = (false, false);
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let s = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        pos |= s > 0.0;
        neg |= s < 0.0;
    }
    !(pos && neg)
}

/// The view-space depth `z` whose normalised depth is `d` (the inverse of the core's
/// `D(z) = (2^32 − 1)·far·(z − near) / (z·(far − near))`, see `project.rs`):
/// `z = K / (A − D)` with `A = (2^32 − 1)·far/(far − near)`, `K = A·near`.
pub fn depth_from_d32(d: u32, near: f64, far: f64) -> f64 {
    let a = 4294967295.0 * far / (far - near);
    a * near / (a - d as f64)
}

/// `dz/dD` at depth `z`: the change of `z` per unit of the 32-bit normalised depth,
/// `z²·(far − near) / ((2^32 − 1)·far·near)`.
pub fn dz_per_d32_unit(z: f64, near: f64, far: f64) -> f64 {
    z * z * (far - near) / (4294967295.0 * far * near)
}

/// The view-space depth and its screen gradient `(∂z/∂x, ∂z/∂y)` (per pixel) of the plane of
/// the triangle with view corners `view`, along the ray through pixel `(x, y)`;
/// `None` when the ray is parallel to the plane.
pub fn plane_depth(scene: &Scene, view: &[Vec3; 3], x: f64, y: f64) -> Option<(f64, f64, f64)> {
    let cam = &scene.camera;
    let f = cam.focal();
    let (cx, cy) = cam.principal;
    let n = cross(sub(view[1], view[0]), sub(view[2], view[0]));
    let na = dot(n, view[0]);
    let ray = [(x - cx) / f, -(y - cy) / f, 1.0];
    let den = dot(n, ray);
    if den == 0.0 || na == 0.0 {
        return None;
    }
    let z = na / den;
    // z = na / (n·r): ∂z/∂x = −z²·n0/(f·na), ∂z/∂y = +z²·n1/(f·na).
    Some((z, -z * z * n[0] / (f * na), z * z * n[1] / (f * na)))
}

/// The screen-space gradient magnitude (levels per pixel) of the screen-affine interpolant of
/// `levels` over the projected triangle `screen` (3 vertices); 0 for a degenerate triangle.
pub fn affine_gradient(screen: &[(f64, f64)], levels: [f64; 3]) -> f64 {
    let (a, b, c) = (screen[0], screen[1], screen[2]);
    let d = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if d == 0.0 {
        return 0.0;
    }
    let (l1, l2) = (levels[1] - levels[0], levels[2] - levels[0]);
    let gx = (l1 * (c.1 - a.1) - l2 * (b.1 - a.1)) / d;
    let gy = (l2 * (b.0 - a.0) - l1 * (c.0 - a.0)) / d;
    (gx * gx + gy * gy).sqrt()
}

/// The workspace's test generator, under the name the reference helpers export.
pub use crate::test_rng::XorShift as Rng;
