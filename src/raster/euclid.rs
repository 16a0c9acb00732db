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
#[inline(always)]
pub fn div_floor_i64(a: i64, b: i64) -> (i64, i64) {
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
