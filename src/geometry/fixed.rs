//! The fixed-point formats of the geometry stage, and the rounding helpers every module shares.
//!
//! Role in the pipeline: vocabulary. Every other geometry module, the 3D clipper and the
//! projector speak these formats.
//!
//! ## Formats
//! | alias | `fixed` type | raw | range | resolution | used for |
//! |---|---|---|---|---|---|
//! | [`Coord`] | `I16F16` | `i32` | ±32 768 | 2^-16 ≈ 1.5·10^-5 | world, model and observer coordinates, lengths |
//! | [`Linear`] | `I8F24` | `i32` | ±128 (matrices keep `|entry| ≤ 64`) | 2^-24 ≈ 6·10^-8 | the linear (rotation × scale) part of [`Affine3`](super::matrix::Affine3), camera basis vectors |
//! | [`Unit`] | `I2F30` | `i32` | ±2 | 2^-30 ≈ 9.3·10^-10 | sine and cosine ([`trig`](super::trig)) |
//!
//! Arithmetic is done on the raw integers (`to_bits`) with `i64` intermediates; each module
//! states its widest intermediate. Results that do not fit their format **saturate** (documented
//! per function) or are reported as errors; nothing wraps and nothing panics.
//!
//! Conversions from floating point (`Coord::from_num(0.5)`) are the `fixed` crate's; on the target
//! they belong in set-up code (or in the host), never per frame.

/// World/observer coordinate: signed 16.16 fixed point, range ±32 768, resolution 2^-16.
pub type Coord = fixed::types::I16F16;

/// Linear-map entry: signed 8.24 fixed point (resolution 2^-24). Matrices keep `|entry| ≤ 64`.
pub type Linear = fixed::types::I8F24;

/// Sine/cosine value: signed 2.30 fixed point, `1.0 = 2^30`, resolution 2^-30.
pub type Unit = fixed::types::I2F30;

/// Fractional bits of [`Coord`].
pub const COORD_FRAC: u32 = 16;
/// Fractional bits of [`Linear`].
pub const LINEAR_FRAC: u32 = 24;
/// Fractional bits of [`Unit`].
pub const UNIT_FRAC: u32 = 30;

/// Saturates an `i64` to the `i32` range.
///
/// Written as "the low word, unless it does not sign-extend back to `v`": on a 32-bit core the
/// common in-range case is one shift, one compare and a branch (the two-sided clamp compiled to
/// about 15 instructions per value on a Cortex-M4 in the vertex transform).
#[inline(always)]
pub(crate) const fn saturate_i32(v: i64) -> i32 {
    let low = v as i32;
    if low as i64 == v {
        low
    } else if v < 0 {
        i32::MIN
    } else {
        i32::MAX
    }
}

/// Rounded shifts live with the integer arithmetic (`arith`); re-exported for the fixed-point
/// formats' users.
pub(crate) use crate::arith::shr_round;

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn shr_round_matches_definition() {
        for v in [
            -9i64,
            -8,
            -7,
            -5,
            -4,
            -3,
            -1,
            0,
            1,
            3,
            4,
            5,
            7,
            8,
            9,
            i64::MAX,
            i64::MIN,
        ] {
            for s in 1..=4u32 {
                let expected = ((v as f64) / (1u64 << s) as f64 + 0.5).floor() as i64;
                if v.unsigned_abs() < 1 << 40 {
                    assert_eq!(shr_round(v, s), expected, "v={v} s={s}");
                } else {
                    let _ = shr_round(v, s); // no overflow at the extremes
                }
            }
        }
        assert_eq!(shr_round(5, 0), 5);
        assert_eq!(shr_round(i64::MAX, 63), 0);
    }

    #[test]
    fn saturation() {
        assert_eq!(saturate_i32(1 << 40), i32::MAX);
        assert_eq!(saturate_i32(-(1 << 40)), i32::MIN);
        assert_eq!(saturate_i32(-5), -5);
    }
}
