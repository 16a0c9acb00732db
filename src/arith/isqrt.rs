//! Integer square root: `floor(√n)` for `n: u64`, exact, without floating point.
//!
//! Role in the pipeline: vector lengths and normalisation (`geometry::vector`), the camera's
//! diagonal field of view. Set-up and per-normal work, not per pixel.
//!
//! Numeric contract: input any `u64`; output `u32` (`√(2^64 − 1) < 2^32`). The method is the
//! bit-by-bit (binary restoring) square root: 32 iterations of shifts, one compare and one
//! subtraction on `u64`, whose values never exceed `n`, so nothing overflows.

/// `floor(√n)`, exact for every `u64`.
pub const fn isqrt_u64(n: u64) -> u32 {
    let mut rem = n;
    let mut root: u64 = 0;
    // Highest power of four ≤ n (or 4^31 when n is large).
    let mut bit: u64 = 1 << 62;
    while bit > rem {
        bit >>= 2;
        if bit == 0 {
            return 0;
        }
    }
    while bit != 0 {
        if rem >= root + bit {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(n: u64) {
        let r = isqrt_u64(n) as u64;
        assert!(r * r <= n, "n={n} r={r}");
        // (r+1)^2 > n, computed without overflow.
        let r1 = r + 1;
        assert!(r1.checked_mul(r1).is_none_or(|sq| sq > n), "n={n} r={r}");
    }

    #[test]
    fn small_exhaustive() {
        for n in 0..100_000u64 {
            check(n);
        }
    }

    #[test]
    fn squares_and_neighbours() {
        for r in [
            1u64,
            2,
            3,
            255,
            65_535,
            65_536,
            1 << 31,
            (1 << 32) - 1,
            3_037_000_499,
        ] {
            let sq = r * r;
            check(sq);
            check(sq - 1);
            check(sq.saturating_add(1));
            assert_eq!(isqrt_u64(sq) as u64, r);
        }
        check(u64::MAX);
        assert_eq!(isqrt_u64(u64::MAX), u32::MAX);
    }

    #[test]
    fn pseudo_random() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            check(x);
            check(x >> (x % 64));
        }
    }
}
