//! TIPE's `Division_euclidienne(A, B)`: quotient and remainder with `0 ≤ R < B`, for a
//! positive divisor, in one hardware (or runtime) division.
//!
//! Role in the pipeline: every exact step of the raster stage (edge walkers, attribute planes)
//! divides with this. `i64::div_euclid` followed by `i64::rem_euclid` performs two divisions;
//! here `/` and `%` share one (`idiv` on x86-64, `__aeabi_ldivmod` on Cortex-M), and one fix-up
//! turns the truncated result into the floored one.
//!
//! Numeric contract: `b > 0` (callers guarantee it; `b ≤ 0` would give an unspecified but
//! non-panicking result for `b < 0`; `b == 0` is never passed). No overflow for any `a`.

/// `(q, r)` with `a = b·q + r` and `0 ≤ r < b`, for `b > 0`.
///
/// On 32-bit targets a 64-bit division is a library call (`__aeabi_ldivmod`, about a hundred
/// instructions on a Cortex-M4) while a 32-bit one is a single `sdiv` (Cortex-M3/M4) or a much
/// shorter call (Cortex-M0): operands that fit `i32` take the 32-bit division there. On 64-bit
/// targets the hardware divides 64 bits directly and the check would only cost.
#[inline(always)]
pub fn div_floor_i64(a: i64, b: i64) -> (i64, i64) {
    if cfg!(not(target_pointer_width = "64")) && a == a as i32 as i64 && b == b as i32 as i64 {
        let (q, r) = div_floor_i32(a as i32, b as i32);
        return (q as i64, r as i64);
    }
    let (q, r) = (a / b, a % b);
    if r < 0 {
        (q - 1, r + b)
    } else {
        (q, r)
    }
}

/// `(q, r)` with `a = b·q + r` and `0 ≤ r < b`, for `b > 0`.
#[inline(always)]
pub fn div_floor_i32(a: i32, b: i32) -> (i32, i32) {
    let (q, r) = (a / b, a % b);
    if r < 0 {
        (q - 1, r + b)
    } else {
        (q, r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_euclidean_division() {
        for a in [
            -1_000_003i64,
            -7,
            -6,
            -1,
            0,
            1,
            5,
            6,
            7,
            999_999_937,
            i64::MIN + 1,
            i64::MAX,
        ] {
            for b in [1i64, 2, 3, 6, 7, 1 << 40, i64::MAX] {
                assert_eq!(
                    div_floor_i64(a, b),
                    (a.div_euclid(b), a.rem_euclid(b)),
                    "{a} {b}"
                );
                let (a32, b32) = (a as i32, (b as i32).max(1));
                assert_eq!(
                    div_floor_i32(a32, b32),
                    (a32.div_euclid(b32), a32.rem_euclid(b32))
                );
            }
        }
    }
}
