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
pub const fn saturate_i32(v: i64) -> i32 {
    let low = v as i32;
    if low as i64 == v {
        low
    } else if v < 0 {
        i32::MIN
    } else {
        i32::MAX
    }
}

/// True on cores without a 32×32→64-bit multiply (ARMv6-M: Cortex-M0/M0+, recognised on
/// stable Rust as 32-bit Arm without 32-bit atomics). There LLVM turns `a as i64 * b as i64`
/// into a call of `__aeabi_lmul`, a full 64×64-bit multiply (about 37 instructions, and the
/// call's clobbered registers spill around it), and [`mul_wide`] takes four 16×16-bit
/// products inline instead. Elsewhere the plain product is one instruction (`smull`, `imul`).
/// The choice changes speed, never results.
pub const NARROW_MULTIPLY: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// `a·b` exactly (`|a·b| ≤ 2^62`): the plain `i64` product, or [`mul_wide_split`] where
/// [`NARROW_MULTIPLY`].
#[inline(always)]
pub const fn mul_wide(a: i32, b: i32) -> i64 {
    if NARROW_MULTIPLY {
        mul_wide_split(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// `a·b` exactly (`< 2^64`): the plain `u64` product, or [`mul_wide_u_split`] where
/// [`NARROW_MULTIPLY`].
#[inline(always)]
pub const fn mul_wide_u(a: u32, b: u32) -> u64 {
    if NARROW_MULTIPLY {
        mul_wide_u_split(a, b)
    } else {
        a as u64 * b as u64
    }
}

/// `a·b` from 16-bit halves, each product in 32 bits: with `a = ah·2^16 + al` (`ah` signed
/// `−2^15..2^15`, `al` in `0..2^16`) and likewise `b`, `al·bl < 2^32` (unsigned),
/// `|ah·bl|, |al·bh| < 2^31` (signed `i32`) and `|ah·bh| ≤ 2^30`; the three columns are summed
/// in `i64`. Equal to `a as i64 * b as i64` for every input (tested on the extremes and at
/// random).
#[inline(always)]
pub const fn mul_wide_split(a: i32, b: i32) -> i64 {
    let (al, bl) = ((a & 0xFFFF) as u32, (b & 0xFFFF) as u32);
    let (ah, bh) = (a >> 16, b >> 16);
    let low = (al * bl) as i64;
    let middle = (ah * bl as i32) as i64 + (al as i32 * bh) as i64;
    let high = (ah * bh) as i64;
    (high << 32) + (middle << 16) + low
}

/// [`mul_wide_split`] unsigned: `al·bl`, `ah·bl`, `al·bh`, `ah·bh` each below `2^32`.
#[inline(always)]
pub const fn mul_wide_u_split(a: u32, b: u32) -> u64 {
    let (al, bl) = (a & 0xFFFF, b & 0xFFFF);
    let (ah, bh) = (a >> 16, b >> 16);
    let middle = (ah * bl) as u64 + (al * bh) as u64;
    ((((ah * bh) as u64) << 32) + (middle << 16)) + (al * bl) as u64
}

/// `v / 2^s` rounded to nearest (ties toward +∞); `s = 0` returns `v`, `s > 62` gives 0.
/// Never overflows: the rounding bit is added after the shift.
#[inline(always)]
pub const fn shr_round(v: i64, s: u32) -> i64 {
    if s == 0 {
        v
    } else if s > 62 {
        0
    } else {
        // |v >> s| ≤ 2^62, so adding the rounding bit cannot overflow.
        (v >> s) + ((v >> (s - 1)) & 1)
    }
}

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

    /// The 16-bit-halves products equal the plain ones: every pair of extremes (0, ±1,
    /// ±2^15 ± 1, ±2^16 ± 1, the type's ends) and a million random pairs of every magnitude.
    #[test]
    fn split_products_are_exact() {
        let mut edges = std::vec::Vec::new();
        for v in [
            0i64, 1, 2, 0x7FFF, 0x8000, 0x8001, 0xFFFF, 0x1_0000, 0x1_0001,
        ] {
            edges.extend([v, -v]);
        }
        edges.extend([
            i32::MAX as i64,
            i32::MIN as i64,
            i32::MIN as i64 + 1,
            0x7FFF_0000,
        ]);
        let mut rng = crate::test_rng::XorShift(0x5DEE_CE66_D1CE_4E5B);
        let mut pairs: std::vec::Vec<(i32, i32)> = edges
            .iter()
            .flat_map(|&a| edges.iter().map(move |&b| (a as i32, b as i32)))
            .collect();
        for _ in 0..1_000_000 {
            let r = rng.next_u64();
            pairs.push((
                (r as i32) >> (r >> 59),
                ((r >> 32) as i32) >> ((r >> 27) & 31),
            ));
        }
        for (a, b) in pairs {
            assert_eq!(mul_wide_split(a, b), a as i64 * b as i64, "{a} {b}");
            let (ua, ub) = (a as u32, b as u32);
            assert_eq!(mul_wide_u_split(ua, ub), ua as u64 * ub as u64, "{ua} {ub}");
            assert_eq!(mul_wide(a, b), a as i64 * b as i64);
            assert_eq!(mul_wide_u(ua, ub), ua as u64 * ub as u64);
        }
    }

    #[test]
    fn saturation() {
        assert_eq!(saturate_i32(1 << 40), i32::MAX);
        assert_eq!(saturate_i32(-(1 << 40)), i32::MIN);
        assert_eq!(saturate_i32(-5), -5);
    }
}
