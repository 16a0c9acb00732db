//! Illumination: the course's Phong reflection model (chapter 4, §1) in fixed point.
//!
//! Role in the pipeline: before the raster. It turns surface points and normals **in the
//! observer frame** (the eye at the origin, before perspective — the course's warning: lighting
//! after the projection would distort angles) into intensities `0..=255`, which the span writers
//! interpolate (Gouraud), use per polygon (flat) or which `phong` evaluates per
//! pixel.
//!
//! ## The model
//! ```text
//! I = k_a·I_a + Σ_i S_i·I_p,i·(k_d·cos⁺θ_i + k_s·(cos⁺α_i)^n)
//! cos θ = N·L,   cos α = R·V,   R = 2N(N·L) − L   so   R·V = 2(N·L)(N·V) − L·V
//! ```
//! `N` the unit normal, `L` the unit vector toward light `i` (from the point for a
//! [`Light::Point`], fixed for a [`Light::Directional`]), `V` the unit vector toward the
//! observer (`−P` in the observer frame). `S_i = 1` here: the shadow test
//! ([`shadow`](super::shadow)) is the caller's, which sets `S_i = 0` by leaving a light out.
//! A light with `N·L ≤ 0` is behind the surface and contributes nothing (neither diffuse nor
//! specular): the course's `cos θ` is taken as `cos⁺θ`, which is what the exercises assume.
//!
//! Local lights beyond the course's point source ([`Attenuation`], [`Cone`]): a [`Light::AttenuatedPoint`]
//! scales `I_p,i` by a distance attenuation `1/(k_c + k_l·d + k_q·d²)`, a [`Light::Spot`]
//! also by a cone fall-off around its axis. The factors enter the sum above wherever it is
//! evaluated (vertices, polygon centres, pixels), so every shading mode sees them.
//!
//! ## Numeric contract
//! - Coefficients `k_a, k_d, k_s` are unsigned Q15 (`32768 = 1.0`, up to `65535 ≈ 2.0`;
//!   [`Material::from_thousandths`] builds them from integers). Shininess `n` is `1..=200`
//!   (clamped).
//! - Intensities `I_a, I_p` are `u8` (`0..=255`); the result is rounded to nearest and clamped
//!   to `0..=255`.
//! - Unit vectors are Q15 in `i32` (`|c| ≤ 32768`), made by
//!   `unit_bits` (integer square root). A dot product of
//!   two of them is at most `(2^15 + 1)²·3 < 2^32` in magnitude, computed in `i64`, rounded back
//!   to Q15.
//! - `(cos⁺α)^n` by squaring in Q15 with `u32` products (`≤ 2^30`), rounded at each step: at
//!   most 15 products, each off by at most 2^-16, so the power is within `15·2^-16` of the exact
//!   power of the rounded cosine.
//! - A local light's factor `f_att·f_spot` is Q15 (`0..=32768`; ranges and precision in
//!   [`Attenuation`] and [`Cone`]) and
//!   scales that light's `k_d·cos θ + k_s·cos^n α` (below `2^32`), rounded once.
//! - The sum is accumulated in Q30 `u64`: each `k·cos` product is below `2^31`, times
//!   `I ≤ 255` below `2^39`, at most [`MAX_LIGHTS`] lights plus ambient: below `2^42`.
//!
//! Integer only (no `f32`): usable per pixel on an FPU-less core.

pub(crate) mod phong;
pub(crate) mod spot;

pub use spot::{Attenuation, Cone, MAX_COEFFICIENT, MIN_CONE_GAP, MIN_CONSTANT};
use spot::{FactorError, LocalFactors};

use crate::geometry::camera::Camera;
use crate::geometry::matrix::{Affine3, MatrixError};
use crate::geometry::mesh::{Mesh, MeshTable};
use crate::geometry::vector::{to_30_bits, Vec3};

/// Fractional bits of coefficients and unit vectors (Q15).
pub const FRAC: u32 = 15;
/// `1.0` in Q15.
pub const ONE: i32 = 1 << FRAC;
/// Most lights an [`Illumination`] holds.
pub const MAX_LIGHTS: usize = 4;
/// Largest specular exponent.
pub const MAX_SHININESS: u8 = 200;

/// Reflection coefficients of a surface (course: `k_a`, `k_d`, `k_s`, `n`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Material {
    /// Ambient reflection, Q15 (`32768 = 1.0`).
    pub ka: u16,
    /// Diffuse reflection, Q15.
    pub kd: u16,
    /// Specular reflection, Q15.
    pub ks: u16,
    /// Specular exponent `1..=200` (0 is treated as 1, above 200 as 200).
    pub n: u8,
}

impl Material {
    /// A material from coefficients in thousandths (`300` = 0.3), rounded to Q15 and
    /// saturating at `65535` (≈ 2.0).
    pub const fn from_thousandths(ka: u32, kd: u32, ks: u32, n: u8) -> Material {
        const fn q15(t: u32) -> u16 {
            let v = (t as u64 * ONE as u64 + 500) / 1000;
            if v > u16::MAX as u64 {
                u16::MAX
            } else {
                v as u16
            }
        }
        Material {
            ka: q15(ka),
            kd: q15(kd),
            ks: q15(ks),
            n,
        }
    }

    /// The exponent clamped to `1..=200`.
    #[inline(always)]
    pub fn shininess(&self) -> u32 {
        self.n.clamp(1, MAX_SHININESS) as u32
    }
}

/// A light source, in the world frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Light {
    /// A point source at `position` with intensity `0..=255`.
    Point {
        /// World position.
        position: Vec3,
        /// Intensity `I_p`.
        intensity: u8,
    },
    /// A source at infinity: `toward` points from the scene **toward** the light (any length).
    Directional {
        /// Direction toward the light (world frame, any non-zero length).
        toward: Vec3,
        /// Intensity `I_p`.
        intensity: u8,
    },
    /// A point source whose intensity falls with distance ([`Attenuation`]).
    AttenuatedPoint {
        /// World position.
        position: Vec3,
        /// Intensity `I_p` at zero distance (times `1/k_c`).
        intensity: u8,
        /// Distance attenuation.
        attenuation: Attenuation,
    },
    /// A spot: a point source at `position` lighting the cone around `axis` ([`Cone`]), with
    /// distance attenuation.
    Spot {
        /// World position.
        position: Vec3,
        /// Direction the spot points to, from the light (world frame, any non-zero length).
        axis: Vec3,
        /// Half-angles of full intensity and of cut-off.
        cone: Cone,
        /// Distance attenuation ([`Attenuation::NONE`] for none).
        attenuation: Attenuation,
        /// Intensity `I_p` on the axis at zero distance (times `1/k_c`).
        intensity: u8,
    },
}

/// Why lighting could not be set up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightingError {
    /// More than [`MAX_LIGHTS`] lights.
    TooManyLights,
    /// A directional light with a zero direction.
    ZeroDirection,
    /// An output or scratch slice is shorter than the mesh's table.
    OutputTooSmall {
        /// Which slice.
        table: MeshTable,
        /// Entries it holds.
        given: usize,
        /// Entries the mesh needs.
        needed: usize,
    },
    /// Composing the model and view transforms overflowed.
    Transform(MatrixError),
    /// A spot light's axis is the zero vector.
    ZeroAxis {
        /// Index of the light in the list given.
        light: usize,
    },
    /// A spot light's cone is outside `0 ≤ inner < outer ≤ 90°` with
    /// `cos inner − cos outer ≥ 1/64` ([`MIN_CONE_GAP`]).
    ConeOutOfRange {
        /// Index of the light in the list given.
        light: usize,
    },
    /// An attenuation coefficient is outside its range: `k_c` in `1.0..=256.0`, `k_l` and
    /// `k_q` in `0..=256.0` (Q16: [`MIN_CONSTANT`], [`MAX_COEFFICIENT`]).
    AttenuationOutOfRange {
        /// Index of the light in the list given.
        light: usize,
    },
}

/// A light moved to the observer frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ObserverLight {
    Point {
        position: Vec3,
        intensity: u8,
    },
    Directional {
        l: [i32; 3],
        intensity: u8,
    },
    /// An attenuated point or a spot.
    Local {
        position: Vec3,
        intensity: u8,
        factors: LocalFactors,
    },
}

/// The lights of a frame in the observer frame, and the ambient intensity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Illumination {
    ambient: u8,
    lights: [ObserverLight; MAX_LIGHTS],
    count: usize,
    /// The eye is at infinity along `−z` (an orthographic camera): `V = (0, 0, −1)`.
    parallel_view: bool,
}

/// `2^61 / √len2` for `len2 ∈ [2^58, 2^62)`, within a relative `2^-28`, with 32-bit
/// operations only: the squared length scaled by `4^k` into `x ∈ [2^62, 2^64)`; a 16-bit
/// square root of its top word (Heron's iteration from above with 32-bit divisions, exact
/// floor) as `t0` (relative error `< 2^-15`); one Newton step `t1 = (t0 + x/t0)/2` with
/// `x/t0` from the reciprocal of `reciprocal` (relative
/// `2^-30`), leaving `t1` within a relative `2^-29` of `√x`; then `2^(61+k)/t1` from a second
/// reciprocal.
#[inline]
pub(crate) fn inv_len_q61(len2: u64) -> u64 {
    // x = len2·4^k ∈ [2^62, 2^64), k ∈ {1, 2} for len2 ∈ [2^58, 2^62) (k = 0 above).
    let k = (len2.leading_zeros() / 2).min(31);
    let x = len2 << (2 * k);
    // The top word, h ∈ [2^30, 2^32).
    let h = (x >> 32) as u32;
    // ⌊√h⌋ ∈ [2^15, 2^16): Heron from above (s ≥ √h), stopping when it no longer decreases.
    let mut s = 1u32 << 16;
    loop {
        let t = (s + h / s) >> 1;
        if t >= s {
            break;
        }
        s = t;
    }
    // t0 = (s + ½)·2^16 ∈ [2^31, 2^32): √x up to the 16-bit root's error.
    let t0 = (s << 16) | (1 << 15);
    let (r0, n0) = crate::arith::wide::reciprocal(t0); // ≈ 2^62 / (t0·2^n0), n0 = 0
    let (xh, xl) = (x >> 32, x & 0xFFFF_FFFF);
    // x·r0 / 2^(62 − n0): x < 2^64 and r0 ≤ 2^31, split in words (each product < 2^63).
    let xr = (xh * r0 as u64 + ((xl * r0 as u64) >> 32)) >> (30 - n0.min(30));
    let t1 = ((t0 as u64 + xr) >> 1).clamp(1 << 31, u32::MAX as u64) as u32;
    // r1 ≈ 2^62 / t1 (n1 = 0).
    let (r1, n1) = crate::arith::wide::reciprocal(t1);
    // len = t1 / 2^k, so 2^61 / len = 2^(61 + k) / t1 = r1 · 2^(k − 1 + n1).
    let e = k as i32 - 1 + n1 as i32;
    if e >= 0 {
        (r1 as u64) << e
    } else {
        (r1 as u64) >> (-e)
    }
}

/// The Q15 unit vector along `v`, or `None` for zero: per-pixel work in Phong shading.
///
/// As [`unit_bits`](crate::geometry::vector::unit_bits) (the largest component brought to
/// `[2^29, 2^30)`, so the squared length is in `[2^58, 3·2^60)`) but without a 64-bit square
/// root or division, which are slow library loops on 32-bit cores (about 1,000 instructions
/// per call on a Cortex-M4): [`inv_len_q61`] gives `q ≈ 2^61 / len` (`len ∈ [2^29, 2^31)`, so
/// `q ∈ (2^30, 2^32]`) within a relative `2^-28`, and the components are
/// `round(c·q / 2^46)` (`|c·q| < 2^62`): within `2^-13` unit of the exactly computed ones,
/// hence within one unit of [`unit_bits`](crate::geometry::vector::unit_bits)`(v, 15)`
/// (tested); components are in `[-32768, 32768]`.
#[inline]
pub(crate) fn unit_q15(v: [i64; 3]) -> Option<[i32; 3]> {
    let w = to_30_bits(v)?;
    let len2: u64 = w.iter().map(|c| c.unsigned_abs().pow(2)).sum();
    let q = inv_len_q61(len2);
    Some(w.map(|c| {
        let m = ((c.unsigned_abs() * q + (1 << 45)) >> 46).min(ONE as u64) as i32;
        if c < 0 {
            -m
        } else {
            m
        }
    }))
}

/// Dot product of two Q15 unit vectors, rounded to Q15 (in `[-32769, 32769]`).
#[inline(always)]
pub(crate) fn dot_q15(a: [i32; 3], b: [i32; 3]) -> i32 {
    let s = a[0] as i64 * b[0] as i64 + a[1] as i64 * b[1] as i64 + a[2] as i64 * b[2] as i64;
    ((s + (1 << (FRAC - 1))) >> FRAC) as i32
}

/// `x^n` for `x` in Q15 `0..=32768`, by squaring, rounding each product to nearest.
#[inline]
pub(crate) fn pow_q15(x: u32, n: u32) -> u32 {
    let mul = |a: u32, b: u32| (a * b + (1 << (FRAC - 1))) >> FRAC; // a, b ≤ 2^15
    let mut base = x.min(ONE as u32);
    let mut e = n;
    let mut acc = ONE as u32;
    while e > 0 {
        if e & 1 == 1 {
            acc = mul(acc, base);
        }
        e >>= 1;
        if e > 0 {
            base = mul(base, base);
        }
    }
    acc
}

fn wide(v: Vec3) -> [i64; 3] {
    v.bits().map(|c| c as i64)
}

impl Illumination {
    /// Lights given in the world frame, moved to `camera`'s observer frame.
    pub fn new(camera: &Camera, ambient: u8, lights: &[Light]) -> Result<Self, LightingError> {
        let view = camera.view_transform();
        let moved = |l: &Light| match *l {
            Light::Point {
                position,
                intensity,
            } => Light::Point {
                position: view.transform_point(position),
                intensity,
            },
            Light::Directional { toward, intensity } => Light::Directional {
                toward: view.transform_vector(toward),
                intensity,
            },
            Light::AttenuatedPoint {
                position,
                intensity,
                attenuation,
            } => Light::AttenuatedPoint {
                position: view.transform_point(position),
                intensity,
                attenuation,
            },
            Light::Spot {
                position,
                axis,
                cone,
                attenuation,
                intensity,
            } => Light::Spot {
                position: view.transform_point(position),
                axis: view.transform_vector(axis),
                cone,
                attenuation,
                intensity,
            },
        };
        let mut obs = [Light::Directional {
            toward: Vec3::ZERO,
            intensity: 0,
        }; MAX_LIGHTS];
        if lights.len() > MAX_LIGHTS {
            return Err(LightingError::TooManyLights);
        }
        for (o, l) in obs.iter_mut().zip(lights) {
            *o = moved(l);
        }
        let mut lit = Self::observer(ambient, &obs[..lights.len()])?;
        lit.parallel_view = camera.is_orthographic();
        Ok(lit)
    }

    /// Lights already given in the observer frame (eye at the origin, `z` forward).
    pub fn observer(ambient: u8, lights: &[Light]) -> Result<Self, LightingError> {
        if lights.len() > MAX_LIGHTS {
            return Err(LightingError::TooManyLights);
        }
        let mut out = [ObserverLight::Directional {
            l: [0; 3],
            intensity: 0,
        }; MAX_LIGHTS];
        for (i, (o, l)) in out.iter_mut().zip(lights).enumerate() {
            let local = |attenuation, spot| {
                LocalFactors::new(attenuation, spot).map_err(|e| match e {
                    FactorError::Attenuation => LightingError::AttenuationOutOfRange { light: i },
                    FactorError::ZeroAxis => LightingError::ZeroAxis { light: i },
                    FactorError::Cone => LightingError::ConeOutOfRange { light: i },
                })
            };
            *o = match *l {
                Light::Point {
                    position,
                    intensity,
                } => ObserverLight::Point {
                    position,
                    intensity,
                },
                Light::Directional { toward, intensity } => ObserverLight::Directional {
                    l: unit_q15(wide(toward)).ok_or(LightingError::ZeroDirection)?,
                    intensity,
                },
                Light::AttenuatedPoint {
                    position,
                    intensity,
                    attenuation,
                } => ObserverLight::Local {
                    position,
                    intensity,
                    factors: local(attenuation, None)?,
                },
                Light::Spot {
                    position,
                    axis,
                    cone,
                    attenuation,
                    intensity,
                } => ObserverLight::Local {
                    position,
                    intensity,
                    factors: local(attenuation, Some((wide(axis), cone)))?,
                },
            };
        }
        Ok(Illumination {
            ambient,
            lights: out,
            count: lights.len(),
            parallel_view: false,
        })
    }

    /// The ambient intensity `I_a`.
    pub fn ambient(&self) -> u8 {
        self.ambient
    }

    /// The intensity at observer-frame point `p` with normal `n` (any length; zero gives the
    /// ambient term only).
    #[inline]
    pub fn intensity(&self, m: &Material, p: Vec3, n: [i64; 3]) -> u8 {
        match unit_q15(n) {
            Some(u) => self.intensity_unit(m, p, u),
            None => Self::finish(m.ka as u64 * self.ambient as u64 * ONE as u64),
        }
    }

    /// The intensity at observer-frame point `p` with Q15 unit normal `n`.
    #[inline]
    pub fn intensity_unit(&self, m: &Material, p: Vec3, n: [i32; 3]) -> u8 {
        let pw = wide(p);
        // V = −P toward the eye; at the eye itself, and for an eye at infinity (orthographic
        // camera), look back along −z.
        let v = match self.parallel_view {
            false => unit_q15(pw.map(|c| -c)).unwrap_or([0, 0, -ONE]),
            true => [0, 0, -ONE],
        };
        let ndv = dot_q15(n, v) as i64;
        let shininess = m.shininess();
        let mut acc = m.ka as u64 * self.ambient as u64 * ONE as u64; // Q30
        for light in &self.lights[..self.count.min(MAX_LIGHTS)] {
            let to = |q: Vec3| {
                let q = wide(q);
                [q[0] - pw[0], q[1] - pw[1], q[2] - pw[2]]
            };
            let (l, ip, factors) = match *light {
                ObserverLight::Point {
                    position,
                    intensity,
                } => match unit_q15(to(position)) {
                    Some(l) => (l, intensity, None),
                    None => continue,
                },
                ObserverLight::Directional { l, intensity } => (l, intensity, None),
                ObserverLight::Local {
                    position,
                    intensity,
                    ref factors,
                } => {
                    let d = to(position);
                    match unit_q15(d) {
                        Some(l) => (l, intensity, Some((factors, d))),
                        None => continue,
                    }
                }
            };
            let ndl = dot_q15(n, l);
            if ndl <= 0 {
                continue;
            }
            let ndl = ndl.min(ONE);
            let ldv = dot_q15(l, v) as i64;
            // R·V = 2(N·L)(N·V) − L·V, Q15.
            let rdv = ((2 * ndl as i64 * ndv + (1 << (FRAC - 1))) >> FRAC) - ldv;
            let spec = pow_q15(rdv.clamp(0, ONE as i64) as u32, shininess);
            let mut term = m.kd as u64 * ndl as u64 + m.ks as u64 * spec as u64; // < 2^32
            if let Some((factors, d)) = factors {
                // f_att·f_spot ≤ 2^15: the scaled term stays below 2^32.
                let f = factors.factor(d, l) as u64;
                term = (term * f + (1 << (FRAC - 1))) >> FRAC;
            }
            acc += ip as u64 * term;
        }
        Self::finish(acc)
    }

    /// Q30 sum → `0..=255`, rounded to nearest.
    #[inline(always)]
    fn finish(acc: u64) -> u8 {
        ((acc + (1 << (2 * FRAC - 1))) >> (2 * FRAC)).min(255) as u8
    }
}

/// Model → observer transform of an object.
fn model_view(transform: &Affine3, camera: &Camera) -> Result<Affine3, LightingError> {
    transform
        .then(camera.view_transform())
        .map_err(LightingError::Transform)
}

/// Per-vertex intensities for Gouraud shading: `out[i]` is the intensity at vertex `i` with
/// its smooth normal ([`Mesh::vertex_normals`], written to the caller's `normals` scratch),
/// both moved to the observer frame by `transform` (model → world) then the camera. Normals
/// go through the linear part of the transform: exact for rotations and uniform scales.
pub fn light_vertices(
    mesh: &Mesh<'_>,
    transform: &Affine3,
    camera: &Camera,
    illumination: &Illumination,
    material: &Material,
    normals: &mut [Vec3],
    out: &mut [u8],
) -> Result<(), LightingError> {
    let vertices = mesh.vertices();
    let short = |table, given| LightingError::OutputTooSmall {
        table,
        given,
        needed: vertices.len(),
    };
    let given = out.len();
    let out = out
        .get_mut(..vertices.len())
        .ok_or(short(MeshTable::Levels, given))?;
    mesh.vertex_normals(normals)
        .map_err(|_| short(MeshTable::VertexNormals, normals.len()))?;
    let m = model_view(transform, camera)?;
    for ((o, v), n) in out.iter_mut().zip(vertices).zip(normals.iter()) {
        let p = m.transform_point(*v);
        let n = m.transform_vector(*n);
        *o = illumination.intensity(material, p, wide(n));
    }
    Ok(())
}

/// Per-polygon intensities for flat shading (the course's elementary model): `out[k]` is the
/// intensity at the centroid of polygon `k` (mean of its vertices) with its face normal.
pub fn light_faces(
    mesh: &Mesh<'_>,
    transform: &Affine3,
    camera: &Camera,
    illumination: &Illumination,
    material: &Material,
    out: &mut [u8],
) -> Result<(), LightingError> {
    let given = out.len();
    let out = out
        .get_mut(..mesh.polygon_count())
        .ok_or(LightingError::OutputTooSmall {
            table: MeshTable::Levels,
            given,
            needed: mesh.polygon_count(),
        })?;
    let m = model_view(transform, camera)?;
    for (o, poly) in out.iter_mut().zip(mesh.polygons()) {
        *o = light_polygon(mesh, poly, &m, illumination, material);
    }
    Ok(())
}

/// The flat-shading intensity of one polygon of `mesh`: lit at its centroid (the mean of its
/// vertices, rounded) with its face normal, both moved to the observer frame by `model_view`
/// (model → observer). A degenerate polygon (no normal) gets the ambient term only.
pub(crate) fn light_polygon(
    mesh: &Mesh<'_>,
    polygon: &[u16],
    model_view: &Affine3,
    illumination: &Illumination,
    material: &Material,
) -> u8 {
    let vertices = mesh.vertices();
    let mut sum = [0i64; 3];
    for &i in polygon {
        let b = vertices
            .get(i as usize)
            .copied()
            .unwrap_or(Vec3::ZERO)
            .bits();
        for k in 0..3 {
            sum[k] += b[k] as i64;
        }
    }
    let count = polygon.len().max(1) as i64;
    // Mean rounded to nearest; |sum| < 2^31 · count, so the mean fits i32.
    let c = sum.map(|s| (s * 2 + count).div_euclid(2 * count) as i32);
    let centre = model_view.transform_point(Vec3::from_bits(c[0], c[1], c[2]));
    let n = mesh.face_normal(polygon).unwrap_or(Vec3::ZERO);
    illumination.intensity(material, centre, wide(model_view.transform_vector(n)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::vector::unit_bits;

    #[test]
    fn pow_by_squaring() {
        assert_eq!(pow_q15(ONE as u32, 200), ONE as u32);
        assert_eq!(pow_q15(0, 1), 0);
        assert_eq!(pow_q15(ONE as u32 / 2, 1), 16384);
        assert_eq!(pow_q15(ONE as u32 / 2, 2), 8192);
        assert_eq!(pow_q15(ONE as u32 / 2, 15), 1);
        for n in 1..=200u32 {
            for x in [1000u32, 16000, 30000, 32767] {
                let want = (x as f64 / 32768.0).powi(n as i32) * 32768.0;
                let got = pow_q15(x, n) as f64;
                assert!((got - want).abs() <= 16.0, "x {x} n {n}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn unit_q15_matches_unit_bits() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for i in 0..100_000 {
            let scale = i % 62;
            let v = [0; 3].map(|_| (next() as i64) >> scale);
            let (a, b) = (unit_q15(v), unit_bits(v, FRAC));
            match (a, b) {
                (Some(a), Some(b)) => {
                    for k in 0..3 {
                        assert!((a[k] - b[k]).abs() <= 1, "{v:?}: {a:?} vs {b:?}");
                    }
                }
                (a, b) => assert_eq!(a, b, "{v:?}"),
            }
        }
        assert_eq!(unit_q15([0, 0, 0]), None);
        assert_eq!(unit_q15([0, 0, -5]), Some([0, 0, -ONE]));
        assert_eq!(unit_q15([i64::MIN, 0, 0]), Some([-ONE, 0, 0]));
    }

    #[test]
    fn head_on_light_and_eye() {
        // Surface at z = 10 facing the eye, light at the eye: cos θ = cos α = 1.
        let ill = Illumination::observer(
            100,
            &[Light::Point {
                position: Vec3::ZERO,
                intensity: 100,
            }],
        )
        .unwrap();
        let m = Material::from_thousandths(300, 400, 600, 5);
        let i = ill.intensity(&m, Vec3::from_int(0, 0, 10), [0, 0, -1]);
        assert_eq!(i, 30 + 40 + 60);
        // Light behind the surface: ambient only.
        let i = ill.intensity(&m, Vec3::from_int(0, 0, 10), [0, 0, 1]);
        assert_eq!(i, 30);
        // Saturation.
        let strong = Material::from_thousandths(2000, 2000, 2000, 1);
        assert_eq!(
            ill.intensity(&strong, Vec3::from_int(0, 0, 10), [0, 0, -1]),
            255
        );
        assert_eq!(
            Illumination::observer(
                0,
                &[Light::Directional {
                    toward: Vec3::ZERO,
                    intensity: 1
                }]
            )
            .err(),
            Some(LightingError::ZeroDirection)
        );
    }
}
