//! Sine and cosine without floating point, and the integer angle unit.
//!
//! Role in the pipeline: set-up of rotations ([`matrix`](super::matrix)), of the camera's focal
//! distance ([`camera`](super::camera)) and of the generated meshes ([`generators`](super::generators)).
//!
//! ## Conventions
//! - A [`BinaryAngle`] is a `u32` in **binary angle units: 2^32 per turn** (one unit ≈ 1.46·10^-9 rad).
//!   Arithmetic wraps, which is exactly angle arithmetic modulo a turn. Positive angles turn
//!   counter-clockwise (right-hand rule about the rotation axis).
//! - Results are [`Unit`] (I2F30: `1.0 = 2^30`).
//!
//! ## Method and accuracy
//! No table: the angle is reduced to an octant (`0 ≤ t ≤ π/4`, using the symmetries
//! `sin(π/2 − t) = cos t` and quarter-turn rotations), converted to radians in Q60
//! (`t·2^60 = r·2π·2^60/2^32`, `r ≤ 2^29`), and the Taylor series are summed in Horner form in
//! Q60 with `u128` intermediates (products below 2^120): sine to `x^11`, cosine to `x^12`; their
//! truncation errors are below `10^-11`. The final rounding to I2F30 dominates: the tested
//! maximum error over a dense sweep (2^22 angles plus every octant boundary) is **≤ 0.51 unit
//! of 2^-30** (correctly rounded but for ties). Exact at multiples of a quarter turn.
//! The `u128` products are inline multiply chains on 32-bit targets and the divisions by the
//! series' small constants are `u64` ones: one [`sin_cos`] costs about 640 instructions on a
//! Cortex-M4 (measured with the bench's profile; it was 35,000 with `u128` divisions). Sine
//! and cosine are set-up work (a few per frame for rotating objects), never per vertex.

use super::fixed::Unit;

/// An angle in binary units: 2^32 per turn, wrapping (see the module doc).
///
/// Named for its unit rather than `Angle`, so that it never clashes with
/// `embedded_graphics::prelude::Angle` (an `f32` angle) when both preludes are glob-imported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct BinaryAngle(pub u32);

impl BinaryAngle {
    /// Zero.
    pub const ZERO: BinaryAngle = BinaryAngle(0);
    /// A quarter turn (90°).
    pub const QUARTER_TURN: BinaryAngle = BinaryAngle(1 << 30);
    /// Half a turn (180°).
    pub const HALF_TURN: BinaryAngle = BinaryAngle(1 << 31);

    /// `num / den` of a turn, rounded to the nearest unit; `den = 0` gives zero.
    /// Any `num` (reduced modulo `den` first, so negative fractions work).
    pub const fn from_turns(num: i64, den: u32) -> BinaryAngle {
        if den == 0 {
            return BinaryAngle(0);
        }
        let n = num.rem_euclid(den as i64) as u64; // < den < 2^32
                                                   // n·2^32 < 2^64 and adding den/2 < 2^31 stays below 2^64 (n ≤ den − 1).
        let v = ((n << 32) + (den as u64 / 2)) / den as u64;
        BinaryAngle(v as u32) // v ≤ 2^32: 2^32 wraps to 0, the same angle
    }

    /// `deg` degrees (any integer, wrapped to a turn), rounded to the nearest unit.
    pub const fn from_degrees(deg: i32) -> BinaryAngle {
        BinaryAngle::from_turns(deg as i64, 360)
    }

    /// `num / den` degrees (e.g. `(605, 10)` for 60.5°), rounded; `den = 0` gives zero.
    pub const fn from_degrees_ratio(num: i64, den: u32) -> BinaryAngle {
        // num/(den·360) of a turn; den·360 may exceed u32, so scale in u64 directly.
        if den == 0 {
            return BinaryAngle(0);
        }
        let d = den as u64 * 360; // < 2^41
        let n = num.rem_euclid(d as i64) as u64; // < 2^41
                                                 // n·2^32 could reach 2^73: split it as (n·2^16 / d)·2^16 plus the rounded remainder.
        let hi = (n << 16) / d; // n·2^16 < 2^57
        let rem = (n << 16) % d;
        let lo = ((rem << 16) + d / 2) / d; // rem·2^16 < 2^57
        BinaryAngle(((hi << 16) + lo) as u32)
    }

    /// Half of the angle taken in `[0, 1 turn)` (e.g. half a field of view).
    pub const fn half(self) -> BinaryAngle {
        BinaryAngle(self.0 >> 1)
    }

    /// Sine of the angle.
    pub fn sin(self) -> Unit {
        sin_cos(self).0
    }

    /// Cosine of the angle.
    pub fn cos(self) -> Unit {
        sin_cos(self).1
    }

    /// An angle from degrees in `f32` (set-up only, `float-setup` feature), rounded to
    /// 1/1024 degree first so that whole and common fractional degrees are exact (60.0 gives
    /// the same angle as `from_degrees(60)`); non-finite input gives zero.
    #[cfg(feature = "float-setup")]
    pub fn from_degrees_f32(deg: f32) -> BinaryAngle {
        use micromath::F32Ext;
        if !deg.is_finite() {
            return BinaryAngle(0);
        }
        let d = deg % 360.0; // exact in f32
        BinaryAngle::from_degrees_ratio(F32Ext::round(d * 1024.0) as i64, 1024)
    }
}

impl core::ops::Add for BinaryAngle {
    type Output = BinaryAngle;
    fn add(self, o: BinaryAngle) -> BinaryAngle {
        BinaryAngle(self.0.wrapping_add(o.0))
    }
}

impl core::ops::Sub for BinaryAngle {
    type Output = BinaryAngle;
    fn sub(self, o: BinaryAngle) -> BinaryAngle {
        BinaryAngle(self.0.wrapping_sub(o.0))
    }
}

impl core::ops::Neg for BinaryAngle {
    type Output = BinaryAngle;
    fn neg(self) -> BinaryAngle {
        BinaryAngle(self.0.wrapping_neg())
    }
}

/// `2π·2^60`, rounded.
const TAU_Q60: u128 = 7_244_019_458_077_122_842;
/// `1.0` in Q60.
const ONE_Q60: u128 = 1 << 60;

/// Sine and cosine in Q60 of `t = r·2π/2^32` for `0 ≤ r ≤ 2^29` (`0 ≤ t ≤ π/4`).
///
/// `u128` arithmetic (set-up code): every Horner term is in `[0, 1]` because the series
/// alternate with decreasing terms, so nothing goes negative; products are below 2^120.
fn octant_q60(r: u32) -> (u128, u128) {
    let x = (r as u128 * TAU_Q60) >> 32; // t in Q60
    let x2 = (x * x) >> 60;
    // `(x2·v) >> 60 ≤ 2^60`: the division by the small constant is a `u64` one (the same
    // quotient; a `u128` division is a slow library call on 32-bit targets).
    let term = |v: u128, k: u64| ONE_Q60 - ((((x2 * v) >> 60) as u64) / k) as u128;
    let mut s = ONE_Q60;
    for k in [110, 72, 42, 20, 6] {
        s = term(s, k);
    }
    let sin = (x * s) >> 60;
    let mut c = ONE_Q60;
    for k in [132, 90, 56, 30, 12, 2] {
        c = term(c, k);
    }
    (sin, c)
}

/// Sine and cosine (I2F30) of `a`, each within 1 unit of 2^-30 of the exact value.
pub fn sin_cos(a: BinaryAngle) -> (Unit, Unit) {
    let (s, c) = sin_cos_bits(a);
    (Unit::from_bits(s), Unit::from_bits(c))
}

/// Sine of `a` (I2F30).
pub fn sin(a: BinaryAngle) -> Unit {
    sin_cos(a).0
}

/// Cosine of `a` (I2F30).
pub fn cos(a: BinaryAngle) -> Unit {
    sin_cos(a).1
}

/// Sine and cosine of `a` as raw I2F30 integers (`1.0 = 2^30`), in `[-2^30, 2^30]`.
pub fn sin_cos_bits(a: BinaryAngle) -> (i32, i32) {
    let quadrant = a.0 >> 30;
    let r = a.0 & ((1 << 30) - 1);
    let (s0, c0) = if r <= 1 << 29 {
        octant_q60(r)
    } else {
        let (s, c) = octant_q60((1 << 30) - r);
        (c, s)
    };
    // Q60 → Q30 rounded to nearest; values are ≤ 1 so the results lie in [0, 2^30].
    let q30 = |v: u128| ((v + (1 << 29)) >> 30).min(1 << 30) as i32;
    let (s0, c0) = (q30(s0), q30(c0));
    match quadrant {
        0 => (s0, c0),
        1 => (c0, -s0),
        2 => (-s0, -c0),
        _ => (-c0, s0),
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    fn err_at(a: u32) -> (f64, f64) {
        let (s, c) = sin_cos_bits(BinaryAngle(a));
        let t = a as f64 * core::f64::consts::TAU / 4_294_967_296.0;
        let scale = (1u64 << 30) as f64;
        (
            (s as f64 - t.sin() * scale).abs(),
            (c as f64 - t.cos() * scale).abs(),
        )
    }

    #[test]
    fn dense_sweep_error_within_one_unit() {
        let mut worst = 0.0f64;
        let step = 1u32 << 10; // 2^22 samples
        let mut a = 0u32;
        loop {
            for d in [0u32, 1, 7, 333] {
                let (es, ec) = err_at(a.wrapping_add(d));
                worst = worst.max(es).max(ec);
            }
            let (n, o) = a.overflowing_add(step);
            if o {
                break;
            }
            a = n;
        }
        for k in 0..8u32 {
            for d in [-2i64, -1, 0, 1, 2] {
                let (es, ec) = err_at(((k as i64) << 29).wrapping_add(d) as u32);
                worst = worst.max(es).max(ec);
            }
        }
        assert!(worst <= 0.51, "worst error {worst} units of 2^-30");
    }

    #[test]
    fn exact_at_quarters() {
        assert_eq!(sin_cos_bits(BinaryAngle(0)), (0, 1 << 30));
        assert_eq!(sin_cos_bits(BinaryAngle::QUARTER_TURN), (1 << 30, 0));
        assert_eq!(sin_cos_bits(BinaryAngle::HALF_TURN), (0, -(1 << 30)));
        assert_eq!(sin_cos_bits(BinaryAngle(3 << 30)), (-(1 << 30), 0));
    }

    #[test]
    fn angle_constructors() {
        assert_eq!(BinaryAngle::from_degrees(90), BinaryAngle::QUARTER_TURN);
        assert_eq!(BinaryAngle::from_degrees(-90), BinaryAngle(3 << 30));
        assert_eq!(BinaryAngle::from_degrees(360), BinaryAngle(0));
        assert_eq!(BinaryAngle::from_degrees(180), BinaryAngle::HALF_TURN);
        assert_eq!(BinaryAngle::from_turns(1, 3), BinaryAngle(1_431_655_765));
        assert_eq!(BinaryAngle::from_turns(5, 0), BinaryAngle(0));
        assert_eq!(
            BinaryAngle::from_degrees_ratio(900, 10),
            BinaryAngle::QUARTER_TURN
        );
        assert_eq!(
            BinaryAngle::from_degrees_ratio(605, 10),
            BinaryAngle::from_turns(605, 3600)
        );
        assert_eq!(
            BinaryAngle::from_degrees(60).half(),
            BinaryAngle::from_degrees(30)
        );
        assert_eq!(BinaryAngle(5) - BinaryAngle(7), BinaryAngle(u32::MAX - 1));
    }
}
