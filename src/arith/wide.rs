//! Exact 32×32→64-bit products, the one place that knows how a core multiplies wide.
//!
//! Role: every stage that needs a full product of two `i32` (the vertex transform, the
//! projection, the outcodes, the back-face test, the reciprocal divisions of
//! [`euclid`](super::euclid)) takes it here. Where the core has the instruction (`smull`,
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
