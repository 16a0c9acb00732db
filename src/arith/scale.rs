//! A constant ratio `num/den` as a multiplier and a shift, `m·2^-sh`: the parallel
//! projections' per-point scale (the camera's orthographic projector in `project`, the shadow
//! map's directional projection), one multiply and one rounding shift per use.
//!
//! Numeric contract: built at set-up from `num ≤ 2^60` and `den > 0` with the largest
//! `sh ≤ 62` that keeps `m < 2^bits` (rounded to nearest), so the stored ratio is within a
//! relative `2^-(bits − 1)` of the exact one whenever `sh < 62`. Applied to `v` with
//! `|v·m| < 2^63` (the caller states why), rounded to nearest, ties up.

use super::shr_round;

/// `num/den` as `m·2^-sh` with `m < 2^bits` and the largest `sh ≤ 62` (set-up only).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct Scale {
    pub(crate) m: u64,
    pub(crate) sh: u32,
}

impl Scale {
    /// `num ≤ 2^60`, `den > 0`; `None` when even `sh = 0` gives `m ≥ 2^bits`.
    ///
    /// Never inlined: its 128-bit division is about 9 KB of code on a Cortex-M0+ (no divide
    /// instruction), and a firmware whose camera may be orthographic (a run-time choice, so
    /// every firmware) would otherwise carry one copy per call site (three in the projector's
    /// set-up, 28 KB).
    #[inline(never)]
    pub(crate) fn new(num: u128, den: u128, bits: u32) -> Option<Scale> {
        if den == 0 || num > 1 << 60 || bits > 64 {
            return None;
        }
        // `m(sh) = ⌊(num·2^sh + ⌊den/2⌋) / den⌋ < 2^bits` exactly when
        // `num·2^sh < 2^bits·den − ⌊den/2⌋ =: limit` (`num·2^sh ≤ 2^122`, no overflow); the
        // largest such `sh` comes from the bit lengths and one step either way, so only the
        // final quotient divides. A limit past `u128` admits every `sh ≤ 62`.
        let limit = match den.checked_mul(1u128 << bits) {
            Some(t) => t - den / 2,
            None => u128::MAX,
        };
        if num >= limit {
            return None; // not even `sh = 0`
        }
        let sh = if num == 0 {
            62
        } else {
            // `num·2^sh < limit` holds at `sh = len(limit) − len(num) − 1` and fails two above.
            let mut sh = (num.leading_zeros() - limit.leading_zeros()).saturating_sub(1);
            while sh < 62 && num << (sh + 1) < limit {
                sh += 1;
            }
            sh.min(62)
        };
        let m = ((num << sh) + den / 2) / den; // < 2^bits ≤ 2^64
        Some(Scale { m: m as u64, sh })
    }

    /// `v·num/den` rounded, for `|v·m| < 2^63`.
    #[inline(always)]
    pub(crate) fn signed(&self, v: i64) -> i64 {
        shr_round(v * self.m as i64, self.sh)
    }

    /// `v·num/den` rounded, for `v·m < 2^63`.
    #[inline(always)]
    pub(crate) fn unsigned(&self, v: u64) -> u64 {
        shr_round((v * self.m) as i64, self.sh) as u64
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// Against the exact rounded quotient: within one unit plus the stored ratio's relative
    /// error on the value.
    #[test]
    fn scale_is_the_ratio() {
        let s = Scale::new(240 << 4, 3 << 16, 31).unwrap();
        assert!(s.m < 1 << 31 && s.m >= 1 << 30);
        for v in [-(1i64 << 31), -65536, -1, 0, 1, 65535, (1 << 31) - 1] {
            let exact = (v as f64) * (240.0 * 16.0) / (3.0 * 65536.0);
            let got = s.signed(v) as f64;
            assert!(
                (got - exact).abs() <= 0.5 + exact.abs() * 2f64.powi(-30),
                "{v}"
            );
        }
        assert_eq!(Scale::new(1, 0, 31), None);
        assert_eq!(Scale::new((1 << 60) + 1, 1, 31), None);
        assert_eq!(Scale::new(1 << 40, 1, 31), None);
    }

    /// The definition: the largest `sh ≤ 62` whose rounded quotient stays below `2^bits`,
    /// found by trying every shift from 62 down.
    fn by_trial(num: u128, den: u128, bits: u32) -> Option<Scale> {
        if den == 0 || num > 1 << 60 {
            return None;
        }
        (0..=62u32).rev().find_map(|sh| {
            let m = ((num << sh) + den / 2) / den;
            (m < 1u128 << bits).then_some(Scale { m: m as u64, sh })
        })
    }

    /// The shift from bit lengths equals the trial's on the callers' shapes, at the bounds
    /// and on random ratios.
    #[test]
    fn shift_from_bit_lengths_is_the_largest_that_fits() {
        let mut cases = std::vec![
            (0u128, 1u128, 31u32),
            (0, 7, 32),
            (1, 1, 31),
            (1 << 60, 1, 31),
            (1 << 60, 1, 64),
            (1 << 60, u128::MAX, 32),
            (1, u128::MAX, 32),
            (3, u128::MAX >> 40, 1),
            ((1u128 << 31) - 1, 1, 31),
            (1u128 << 31, 1, 31),
            (u32::MAX as u128, 2, 32),
            (240 << 4, 3 << 16, 31),
            ((320u128 << 4) << 4, 1000 << 16, 31),
        ];
        let mut rng = crate::test_rng::XorShift::new(0x5ca1e);
        for _ in 0..20_000 {
            let num = (rng.next_u64() as u128) >> (rng.next_u64() % 64);
            let den = ((rng.next_u64() as u128) << (rng.next_u64() % 64)) >> (rng.next_u64() % 64);
            let bits = 1 + (rng.next_u64() % 64) as u32;
            cases.push((num.min(1 << 60), den, bits));
        }
        for (num, den, bits) in cases {
            assert_eq!(
                Scale::new(num, den, bits),
                by_trial(num, den, bits),
                "{num} / {den}, {bits} bits"
            );
        }
    }
}
