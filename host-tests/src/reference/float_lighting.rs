//! An independent `f64` evaluation of the course's Phong illumination model (chapter 4, §1),
//! written from the formula, sharing nothing with the zscan core:
//!
//! ```text
//! I = k_a·I_a + Σ_i I_p,i·(k_d·cos θ_i + k_s·(cos⁺α_i)^n),  cos θ = N·L,  cos α = R·V,
//! R = 2N(N·L) − L
//! ```
//!
//! with a local light's intensity scaled by its distance attenuation `1/(c + l·d + q·d²)` and,
//! for a spot, by `clamp((cos φ − cos outer)/(cos inner − cos outer), 0, 1)` (`φ` the angle
//! between the spot's axis and the ray to the point),
//! evaluated in the **world** frame with the eye position (angles and lengths do not depend on
//! the rigid frame, so this equals the observer-frame evaluation). A light with `N·L ≤ 0` is
//! behind the surface and contributes nothing. The result is clamped to `[0, 255]`, unrounded.
//!
//! Also: the course's vertex normals (§2.5, normalised mean of the normalised face normals)
//! and the three shading methods evaluated at a point of a planar polygon (elementary model,
//! Gouraud, Phong).

/// A 3-vector.
pub type V3 = [f64; 3];

/// A light source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FloatLight {
    /// Point source at a position.
    Point(V3, f64),
    /// Source at infinity in a direction (toward the light).
    Directional(V3, f64),
    /// Point source at a position, intensity scaled by `1/(c + l·d + q·d²)` (`[c, l, q]`).
    Attenuated(V3, f64, [f64; 3]),
    /// Spot at a position pointing along an axis, with inner and outer half-angles in
    /// degrees and attenuation `[c, l, q]`: full within the inner angle, zero beyond the
    /// outer, linear in the cosine between.
    Spot {
        /// Position.
        position: V3,
        /// Direction the spot points to.
        axis: V3,
        /// Inner half-angle, degrees.
        inner: f64,
        /// Outer half-angle, degrees.
        outer: f64,
        /// `[c, l, q]`.
        attenuation: [f64; 3],
        /// Intensity.
        intensity: f64,
    },
}

/// `1/(c + l·d + q·d²)` at distance `d`.
fn attenuation(k: [f64; 3], d: f64) -> f64 {
    1.0 / (k[0] + k[1] * d + k[2] * d * d)
}

/// Reflection coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloatMaterial {
    /// Ambient.
    pub ka: f64,
    /// Diffuse.
    pub kd: f64,
    /// Specular.
    pub ks: f64,
    /// Specular exponent.
    pub n: i32,
}

/// Scene-wide lighting: eye, ambient intensity, lights.
#[derive(Debug, Clone, PartialEq)]
pub struct FloatLighting {
    /// The observer position (world).
    pub eye: V3,
    /// Ambient intensity `I_a`.
    pub ambient: f64,
    /// Light sources.
    pub lights: Vec<FloatLight>,
}

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// `v / |v|` (zero stays zero).
pub fn unit(v: V3) -> V3 {
    let l = dot(v, v).sqrt();
    if l == 0.0 {
        v
    } else {
        [v[0] / l, v[1] / l, v[2] / l]
    }
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl FloatLighting {
    /// Intensity at world point `p` with normal `n` (normalised here), unrounded, clamped.
    pub fn intensity(&self, m: &FloatMaterial, p: V3, n: V3) -> f64 {
        let n = unit(n);
        let v = unit(sub(self.eye, p));
        let mut i = m.ka * self.ambient;
        for light in &self.lights {
            let (l, ip) = match *light {
                FloatLight::Point(q, ip) => (unit(sub(q, p)), ip),
                FloatLight::Directional(d, ip) => (unit(d), ip),
                FloatLight::Attenuated(q, ip, k) => {
                    let d = sub(q, p);
                    (unit(d), ip * attenuation(k, dot(d, d).sqrt()))
                }
                FloatLight::Spot {
                    position,
                    axis,
                    inner,
                    outer,
                    attenuation: k,
                    intensity,
                } => {
                    let d = sub(position, p);
                    let l = unit(d);
                    let cos_phi = -dot(l, unit(axis));
                    let (ci, co) = (inner.to_radians().cos(), outer.to_radians().cos());
                    let cone = ((cos_phi - co) / (ci - co)).clamp(0.0, 1.0);
                    (l, intensity * cone * attenuation(k, dot(d, d).sqrt()))
                }
            };
            let cos_theta = dot(n, l);
            if cos_theta <= 0.0 {
                continue;
            }
            let r = [
                2.0 * cos_theta * n[0] - l[0],
                2.0 * cos_theta * n[1] - l[1],
                2.0 * cos_theta * n[2] - l[2],
            ];
            let cos_alpha = dot(r, v).max(0.0);
            i += ip * (m.kd * cos_theta + m.ks * cos_alpha.powi(m.n));
        }
        i.clamp(0.0, 255.0)
    }
}

/// The unit outward normal of a planar polygon (counter-clockwise seen from outside).
pub fn face_normal(p: &[V3]) -> V3 {
    let mut s = [0.0; 3];
    for k in 1..p.len() - 1 {
        let c = cross(sub(p[k], p[0]), sub(p[k + 1], p[0]));
        s = [s[0] + c[0], s[1] + c[1], s[2] + c[2]];
    }
    unit(s)
}

/// Vertex normals (course §2.5): the normalised sum of the unit normals of the faces around
/// each vertex.
pub fn vertex_normals(vertices: &[V3], faces: &[Vec<usize>]) -> Vec<V3> {
    let mut sums = vec![[0.0; 3]; vertices.len()];
    for f in faces {
        let pts: Vec<V3> = f.iter().map(|&i| vertices[i]).collect();
        let n = face_normal(&pts);
        for &i in f {
            sums[i] = [sums[i][0] + n[0], sums[i][1] + n[1], sums[i][2] + n[2]];
        }
    }
    sums.into_iter().map(unit).collect()
}

/// The three shading methods at the centre of a polygon whose centre is the mean of its
/// corners with equal weights (squares, parallelograms): `(elementary, gouraud, phong)`.
/// - elementary: lighting evaluated at the centre with the face normal;
/// - Gouraud: the mean of the corner intensities (the bilinear interpolant at the centre);
/// - Phong: the mean of the corner normals, normalised, lit at the centre.
pub fn centre_intensities(
    lighting: &FloatLighting,
    m: &FloatMaterial,
    corners: &[V3],
    corner_normals: &[V3],
) -> (f64, f64, f64) {
    let k = corners.len() as f64;
    let mean = |vs: &[V3]| {
        let mut s = [0.0; 3];
        for v in vs {
            s = [s[0] + v[0], s[1] + v[1], s[2] + v[2]];
        }
        [s[0] / k, s[1] / k, s[2] / k]
    };
    let centre = mean(corners);
    let elementary = lighting.intensity(m, centre, face_normal(corners));
    let gouraud = corners
        .iter()
        .zip(corner_normals)
        .map(|(p, n)| lighting.intensity(m, *p, *n))
        .sum::<f64>()
        / k;
    let phong = lighting.intensity(m, centre, mean(corner_normals));
    (elementary, gouraud, phong)
}
