//! Exact 32×32→64-bit products, the one place that knows how a core multiplies wide.
//!
//! Role: every stage that needs a full product of two `i32` (the vertex transform, the
//! projection, the outcodes, the back-face test, the reciprocal divisions of
//! [`euclid`](super::euclid), the reciprocal [`reciprocal`] of the projection, the lighting and
//! the shadow pass) takes it here. Where the core has the instruction (`smull`,
//! `umull`, `imul`) it is the plain product; on ARMv6-M ([`NARROW_MULTIPLY`])
//! it is four 16×16-bit products inline instead of a library call.
//!
//! Numeric contract: any `i32` (`u32`) operands; the results are exact (`|a·b| ≤ 2^62`,
//! `a·b < 2^64`) and equal to the plain product on every input (tested).

use super::NARROW_MULTIPLY;

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

/// `r ≈ 2^62 / (z·2^n)` with `n = z.leading_zeros()`, returned as `(r, n)`; `r ∈ [2^30, 2^31)`
/// and `0 ≤ exact − r ≤ 2` (exact being the real quotient). `z = 0` gives `(2^31, 32)`.
///
/// One 32-bit division (a 16-bit estimate) and two Newton–Raphson steps `r += r·(1 − z_n·r)`,
/// all in 32-bit registers (each step is one 32×32→64 unsigned and one signed multiply):
/// - the seed `r_0 = ⌊(2^32 − 1)/(⌊z_n/2^16⌋ + 1)⌋·2^14 < 2^31` is below `2^62/z_n` (the
///   divisor is rounded up), and Newton's iteration for a reciprocal never overshoots
///   (`r' = 1/m − m·(1/m − r)²` in exact arithmetic, and both floors below only lower it), so
///   every iterate lies in `[0, 2^62/z_n] ⊂ [0, 2^31]`;
/// - `e = ⌊(2^62 − z_n·r)/2^30⌋` (Q32 of `1 − m·r`) is `≥ 0` and `< 2^18` after the seed, and
///   small after one step, so it is the low word of the 64-bit shift: bits 30..61 of
///   `−z_n·r mod 2^64` (the `2^62` only touches bits 62 and 63);
/// - `⌊r·e/2^32⌋` is the high word of a signed 32×32 product (`r < 2^31` before each step).
///
/// The iterate ends in `[2^30 − 1, 2^31)`; only `z_n = 2^32 − 1` gives `2^30 − 1`, which the
/// final `max` raises to `2^30` (within 2 of the exact `2^30 + 2^-2`). This is exactly the
/// former 64-bit formulation (kept as the tests' oracle; equal on every `z`, checked
/// exhaustively by the ignored test `reciprocal_matches_64_bit_oracle_everywhere` and densely
/// by the default tests).
#[inline]
pub fn reciprocal(z: u32) -> (u32, u32) {
    if z == 0 {
        return (1 << 31, 32);
    }
    let n = z.leading_zeros();
    let zn = z << n; // [2^31, 2^32)
    let d16 = (zn >> 16) + 1; // (2^15, 2^16], rounds the divisor up: r0 is an underestimate
    let mut r = (u32::MAX / d16) << 14; // Q30 of 1/m, m = zn/2^32; < 2^31
    for _ in 0..2 {
        let prod = mul_wide_u(zn, r); // ≈ 2^62, below 2^63
        let e = (prod.wrapping_neg() >> 30) as u32 as i32; // ⌊(2^62 − prod)/2^30⌋, |e| < 2^18
        let d = (mul_wide(r as i32, e) >> 32) as i32; // r < 2^31
        r = r.wrapping_add(d as u32); // stays in [0, 2^31] (doc)
    }
    (r.max(1 << 30), n)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

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
}
