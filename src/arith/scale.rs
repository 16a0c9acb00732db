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
        if den == 0 || num > 1 << 60 {
            return None;
        }
        let mut sh = 62u32;
        loop {
            let m = ((num << sh) + den / 2) / den; // < 2^123
            if m < 1u128 << bits {
                return Some(Scale { m: m as u64, sh });
            }
            if sh == 0 {
                return None;
            }
            sh -= 1;
        }
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
}
