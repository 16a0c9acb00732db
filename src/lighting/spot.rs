//! Distance attenuation and the spot cone: the two factors that scale a local light's
//! intensity `I_p` in the course's model (chapter 4, §1) before its diffuse and specular terms.
//!
//! Role in the pipeline: part of the lighting stage. [`Attenuation`] and [`Cone`] are what a
//! user writes in a [`Light`](super::Light); [`LocalFactors`] is their checked, observer-frame
//! form, evaluated by [`Illumination`](super::Illumination) at every lit point (a vertex for
//! Gouraud, a polygon centre for flat shading, a pixel for Phong), so every shading mode sees
//! the same factors. The course's point source has neither; both are the usual extensions of
//! its `I_p` (a source whose light falls off with distance, a source that lights a cone):
//!
//! ```text
//! I_p,i · f_att · f_spot
//! f_att  = 1 / (k_c + k_l·d + k_q·d²)                         d = |light − point|
//! f_spot = clamp((cos φ − cos φ_outer) / (cos φ_inner − cos φ_outer), 0, 1)
//! cos φ  = −L·A                                               A the spot's unit axis
//! ```
//! (`L` the unit vector from the point toward the light, as in the model): full intensity
//! inside the inner half-angle, none outside the outer one, linear in `cos φ` between.
//!
//! ## Numeric contract
//! - Attenuation coefficients are unsigned Q16 (`65536 = 1.0`): `k_c` in
//!   `[`[`MIN_CONSTANT`]`, `[`MAX_COEFFICIENT`]`]` (1.0 to 256.0: the factor never exceeds
//!   1), `k_l` (per world unit) and `k_q` (per square world unit) in `[0, MAX_COEFFICIENT]`;
//!   anything else is [`LightingError::AttenuationOutOfRange`](super::LightingError).
//! - The distance is `d = D·L` with `D` the raw I16F16 light − point vector (`|D| < 2^33`)
//!   and `L` its Q15 unit vector: `L`'s direction error only enters to second order, its length
//!   error (a relative `2^-14`) to first, so `d` is within a relative `2^-13` of `|D|`.
//! - The denominator `k_c·2^32 + k_l·d·2^16 + k_q·d²` (Q48, below `2^91`) is a `u128`; its top
//!   32 bits go through [`reciprocal`](crate::arith::wide::reciprocal) (relative error
//!   `2^-29`), so `f_att` is the Q15 value of `1/(k_c + k_l·d + k_q·d²)` within one unit
//!   plus the distance's error.
//! - A cone's half-angles satisfy `0 ≤ inner < outer ≤ 90°` and
//!   `cos inner − cos outer ≥ `[`MIN_CONE_GAP`]` / 2^15` (1/64: the ramp's slope, hence the
//!   amplification of the `cos φ` rounding, is at most 64); otherwise
//!   [`LightingError::ConeOutOfRange`](super::LightingError). `cos φ` is a Q15 dot product of
//!   two Q15 unit vectors (within 3 units of the exact cosine); `f_spot` is
//!   `(cos φ − cos_outer)·⌊2^30/gap⌉ / 2^15` clamped to `[0, 2^15]`: within
//!   `3·2^15/gap + 1` Q15 units of the exact factor (at most 193 units, 0.6 %, at the minimum
//!   gap).
//! - The two factors multiply in Q15 (`≤ 2^30`), rounded once.

use super::{dot_q15, unit_q15, FRAC, ONE};
use crate::geometry::trig::{sin_cos_bits, BinaryAngle};

/// Smallest constant attenuation coefficient, Q16 (1.0): the factor is at most 1.
pub const MIN_CONSTANT: u32 = 1 << 16;
/// Largest attenuation coefficient of any kind, Q16 (256.0).
pub const MAX_COEFFICIENT: u32 = 1 << 24;
/// Smallest `cos inner − cos outer` of a spot cone, Q15 (1/64).
pub const MIN_CONE_GAP: i32 = ONE / 64;

/// Distance attenuation of a local light, `1 / (k_c + k_l·d + k_q·d²)` with `d` in world
/// units. Coefficients are Q16 (`65536 = 1.0`): `k_c` in `1.0..=256.0`
/// ([`MIN_CONSTANT`]`..=`[`MAX_COEFFICIENT`], so the factor never exceeds 1), `k_l` and `k_q`
/// in `0..=256.0`; a light outside these ranges is refused when it is set up
/// ([`LightingError::AttenuationOutOfRange`](super::LightingError::AttenuationOutOfRange)).
/// The factor is evaluated as a Q15 value within one unit of the exact one for the distance,
/// which is within a relative `2^-13` of the exact distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Attenuation {
    /// `k_c`, Q16, `65536..=2^24` (1.0 to 256.0).
    pub constant: u32,
    /// `k_l` per world unit, Q16, `0..=2^24`.
    pub linear: u32,
    /// `k_q` per square world unit, Q16, `0..=2^24`.
    pub quadratic: u32,
}

impl Attenuation {
    /// No attenuation: `k_c = 1`, `k_l = k_q = 0`.
    pub const NONE: Attenuation = Attenuation {
        constant: MIN_CONSTANT,
        linear: 0,
        quadratic: 0,
    };

    /// Coefficients in thousandths (`1000` = 1.0), rounded to Q16. The result is checked when
    /// the light is set up, not here.
    pub const fn from_thousandths(constant: u32, linear: u32, quadratic: u32) -> Attenuation {
        const fn q16(t: u32) -> u32 {
            let v = (t as u64 * 65_536 + 500) / 1000;
            if v > u32::MAX as u64 {
                u32::MAX
            } else {
                v as u32
            }
        }
        Attenuation {
            constant: q16(constant),
            linear: q16(linear),
            quadratic: q16(quadratic),
        }
    }

    /// Whether every coefficient is in its range.
    pub fn in_range(&self) -> bool {
        (MIN_CONSTANT..=MAX_COEFFICIENT).contains(&self.constant)
            && self.linear <= MAX_COEFFICIENT
            && self.quadratic <= MAX_COEFFICIENT
    }
}

/// A spot's cone: half-angles from its axis. Full intensity within `inner`, none beyond
/// `outer`, linear in the cosine between; `0 ≤ inner < outer ≤ 90°` with
/// `cos inner − cos outer ≥ 1/64` ([`MIN_CONE_GAP`]), otherwise refused when the light is set
/// up ([`LightingError::ConeOutOfRange`](super::LightingError::ConeOutOfRange)). The fall-off
/// is a Q15 factor within `3·2^15/gap + 1` units of the exact one (`gap` the cosines'
/// difference in Q15: at most 0.6 % of full intensity at the smallest gap).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cone {
    /// Half-angle of full intensity.
    pub inner: BinaryAngle,
    /// Half-angle beyond which the spot gives nothing.
    pub outer: BinaryAngle,
}

impl Cone {
    /// `(cos inner, cos outer)` in Q15, or `None` outside the cone's ranges.
    pub(crate) fn cosines(&self) -> Option<(i32, i32)> {
        if self.inner >= self.outer || self.outer > BinaryAngle::QUARTER_TURN {
            return None;
        }
        let q15 = |a: BinaryAngle| (sin_cos_bits(a).1 + (1 << 14)) >> 15;
        let (ci, co) = (q15(self.inner), q15(self.outer));
        (ci - co >= MIN_CONE_GAP).then_some((ci, co))
    }
}

/// The set-up form of a local light's factors, in the observer frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LocalFactors {
    attenuation: Attenuation,
    /// A spot: `(unit axis Q15, cos outer Q15, ⌊2^30/gap⌉)`.
    spot: Option<([i32; 3], i32, u32)>,
}

/// Why a local light's factors were refused.
pub(crate) enum FactorError {
    Attenuation,
    ZeroAxis,
    Cone,
}

impl LocalFactors {
    /// Checked factors: `axis` (observer frame, any length) and `cone` for a spot.
    pub(crate) fn new(
        attenuation: Attenuation,
        spot: Option<([i64; 3], Cone)>,
    ) -> Result<LocalFactors, FactorError> {
        if !attenuation.in_range() {
            return Err(FactorError::Attenuation);
        }
        let spot = match spot {
            None => None,
            Some((axis, cone)) => {
                let a = unit_q15(axis).ok_or(FactorError::ZeroAxis)?;
                let (ci, co) = cone.cosines().ok_or(FactorError::Cone)?;
                let gap = (ci - co) as u32; // in [512, 32768]
                Some((a, co, ((1u32 << 30) + gap / 2) / gap))
            }
        };
        Ok(LocalFactors { attenuation, spot })
    }

    /// `f_att·f_spot` in Q15 (`0..=32768`) for a point seen along `l` (Q15 unit, toward the
    /// light) at raw I16F16 offset `to_light` (light − point).
    #[inline]
    pub(crate) fn factor(&self, to_light: [i64; 3], l: [i32; 3]) -> u32 {
        let spot = match self.spot {
            None => ONE as u32,
            Some((axis, cos_outer, inv_gap)) => {
                let c = -dot_q15(l, axis) - cos_outer;
                if c <= 0 {
                    return 0;
                }
                // c < 2^16, inv_gap ≤ 2^21: the product is below 2^37.
                ((c as u64 * inv_gap as u64 + (1 << 14)) >> 15).min(ONE as u64) as u32
            }
        };
        let att = self.attenuation_q15(to_light, l);
        (att * spot + (1 << (FRAC - 1))) >> FRAC
    }

    /// `f_att` in Q15 (see the module doc).
    #[inline]
    fn attenuation_q15(&self, to_light: [i64; 3], l: [i32; 3]) -> u32 {
        let a = self.attenuation;
        if a.linear == 0 && a.quadratic == 0 && a.constant == MIN_CONSTANT {
            return ONE as u32;
        }
        // d = D·L, Q16 (|D| < 2^33, so each product is below 2^48).
        let d = (to_light[0] * l[0] as i64 + to_light[1] * l[1] as i64 + to_light[2] * l[2] as i64)
            .max(0) as u128
            >> FRAC;
        // Q48: k_c·2^32 < 2^57, k_l·d·2^16 < 2^74, k_q·d² < 2^91.
        let den = ((a.constant as u128) << 32)
            + ((a.linear as u128 * d) << 16)
            + a.quadratic as u128 * d * d;
        // den ≥ 2^48 (k_c ≥ 1): keep its top 32 bits, z = den / 2^s with s ≥ 17.
        let s = 96 - den.leading_zeros();
        let z = (den >> s) as u32;
        // 2^63/den = 2^63/(z·2^s) ≈ r·2^(1 − s − n) with r ≈ 2^62/(z·2^n).
        let (r, n) = crate::arith::wide::reciprocal(z);
        let shift = s + n - 1; // ≥ 16
        ((r as u64 + (1u64 << (shift - 1))) >> shift).min(ONE as u64) as u32
    }
}
