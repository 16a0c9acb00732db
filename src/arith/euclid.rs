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

use super::wide::mul_wide_u;
use super::WIDE_REGISTERS;
use core::num::NonZeroU32;

/// `(q, r)` with `a = b·q + r` and `0 ≤ r < b`, for `b > 0`.
///
/// On 32-bit targets a 64-bit division is a library call (`__aeabi_ldivmod`, about a hundred
/// instructions on a Cortex-M4) while a 32-bit one is a single `sdiv` (Cortex-M3/M4) or a much
/// shorter call (Cortex-M0): operands that fit `i32` take the 32-bit division there. On 64-bit
/// targets the hardware divides 64 bits directly and the check would only cost.
#[inline(always)]
pub fn div_floor_i64(a: i64, b: i64) -> (i64, i64) {
    if !WIDE_REGISTERS && a == a as i32 as i64 && b == b as i32 as i64 {
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

/// `(q, r)` with `a = b·q + r` and `0 ≤ r < b`, for `b > 0`, of `i128` operands.
///
/// A 128-bit division has no library routine on 32-bit targets: the compiler expands it into
/// a bit-serial loop of a couple of thousand instructions on a Cortex-M4. Operands that fit
/// `i64` (the common case of set-ups whose products need `i128` only at the extremes of
/// their ranges) take [`div_floor_i64`] instead: the same quotient and remainder. No overflow
/// for any `a` and `b > 0`.
#[inline(always)]
pub fn div_floor_i128(a: i128, b: i128) -> (i128, i128) {
    if a == a as i64 as i128 && b == b as i64 as i128 {
        let (q, r) = div_floor_i64(a as i64, b as i64);
        return (q as i128, r as i128);
    }
    (a.div_euclid(b), a.rem_euclid(b))
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

/// A positive divisor prepared for many floored divisions: on 32-bit targets by its
/// reciprocal (one 64-bit division to set up, then a 64×64→128-bit multiply of 32-bit limbs and
/// at most two corrections per division, about 20 instructions instead of a ~100-instruction
/// `__aeabi_ldivmod`); on 64-bit targets by the hardware division.
///
/// Numeric contract: `1 ≤ d < 2^62`, dividends `|a| < 2^63`. With `m = ⌊(2^64 − 1)/d⌋`, the
/// estimate `⌊|a|·m / 2^64⌋` is at most 2 below `⌊|a|/d⌋` (the error of `m` is below one part
/// in `2^64/d`, times `|a| < 2^63`), so two correction steps make it exact.
#[derive(Debug, Clone)]
pub struct Divisor {
    d: u64,
    /// `⌊(2^64 − 1)/d⌋`, computed at the first division that needs it (0 until then).
    m: core::cell::Cell<u64>,
}

impl Divisor {
    /// Prepares `d` (`1 ≤ d < 2^62`; smaller values are treated as 1). Costs nothing until a
    /// division needs the reciprocal.
    #[inline]
    pub fn new(d: i64) -> Self {
        Divisor {
            d: d.max(1) as u64,
            m: core::cell::Cell::new(0),
        }
    }

    /// `(q, r)` with `a = d·q + r`, `0 ≤ r < d`, for `|a| < 2^63`. Operands that fit `i32`
    /// take [`div_floor_i64`]'s 32-bit division (inline); others the reciprocal (out of line).
    #[inline(always)]
    pub fn div_floor(&self, a: i64) -> (i64, i64) {
        let d = self.d as i64;
        if WIDE_REGISTERS || (a == a as i32 as i64 && d == d as i32 as i64) {
            return div_floor_i64(a, d);
        }
        self.div_floor_wide(a)
    }

    #[inline(never)]
    fn div_floor_wide(&self, a: i64) -> (i64, i64) {
        let mut m = self.m.get();
        if m == 0 {
            m = u64::MAX / self.d;
            self.m.set(m);
        }
        let (q, r) = reciprocal_divide(a.unsigned_abs(), self.d, m);
        if a >= 0 {
            (q as i64, r as i64)
        } else if r == 0 {
            (-(q as i64), 0)
        } else {
            (-(q as i64) - 1, (self.d - r) as i64)
        }
    }
}

/// A non-zero `u32` divisor prepared for many divisions of `u32` dividends: the hardware
/// division where there is one ([`HARDWARE_DIVIDE`](super::HARDWARE_DIVIDE)); elsewhere (Cortex-M0/M0+, whose
/// division is a library loop of about 90 instructions) a reciprocal taken once, after which
/// each division is one 32×32→64-bit product ([`mul_wide_u`]) and at most two corrections.
///
/// Numeric contract: with `m = ⌊(2^32 − 1)/d⌋ ≤ 2^32/d`, the estimate `q0 = ⌊n·m / 2^32⌋`
/// satisfies `n/d − 2 < q0 ≤ n/d` for every `n < 2^32` (`m > 2^32/d − 2`), so `n − q0·d` lies in
/// `0..3d` and two conditional subtractions at most make it the remainder.
#[derive(Debug, Clone, Copy)]
pub struct DivisorU32 {
    d: NonZeroU32,
    /// `⌊(2^32 − 1)/d⌋`, kept only where there is no hardware division.
    #[cfg(not(hardware_divide))]
    m: u32,
}

impl DivisorU32 {
    /// The divisor 1 (a placeholder where nothing is divided).
    pub const ONE: Self = DivisorU32 {
        d: NonZeroU32::MIN,
        #[cfg(not(hardware_divide))]
        m: u32::MAX,
    };

    /// Prepares `d` (one division where there is no hardware division).
    #[inline(always)]
    pub fn new(d: NonZeroU32) -> Self {
        DivisorU32 {
            d,
            #[cfg(not(hardware_divide))]
            m: u32::MAX / d,
        }
    }

    /// `2d` prepared, for `d < 2^31`, without a division: `⌊⌊(2^32 − 1)/d⌋ / 2⌋ =
    /// ⌊(2^32 − 1)/2d⌋`.
    #[inline(always)]
    pub fn doubled(&self) -> Self {
        DivisorU32 {
            d: self.d.saturating_add(self.d.get()),
            #[cfg(not(hardware_divide))]
            m: self.m >> 1,
        }
    }

    /// The divisor.
    #[inline(always)]
    pub fn get(&self) -> u32 {
        self.d.get()
    }

    /// `⌊(2^32 − 1)/d⌋`, the largest quotient (the reciprocal itself where it is kept).
    #[inline(always)]
    #[cfg(test)]
    pub fn max_quotient(&self) -> u32 {
        #[cfg(not(hardware_divide))]
        return self.m;
        #[cfg(hardware_divide)]
        return u32::MAX / self.d;
    }

    /// `(⌊n/d⌋, n mod d)`.
    #[inline(always)]
    pub fn div_rem(&self, n: u32) -> (u32, u32) {
        self.add_div_rem(0, n)
    }

    /// `(base + ⌊n/d⌋ mod 2^32, n mod d)`: a value's whole part and remainder. (Written in this
    /// order where the hardware divides: computing the quotient first and adding it after
    /// measured +2 % on the x86-64 frames, through register allocation.)
    #[inline(always)]
    pub fn add_div_rem(&self, base: u32, n: u32) -> (u32, u32) {
        #[cfg(not(hardware_divide))]
        let out = {
            let (q, r) = reciprocal_divide_u32(n, self.d.get(), self.m);
            (base.wrapping_add(q), r)
        };
        #[cfg(hardware_divide)]
        let out = (base.wrapping_add(n / self.d), n % self.d);
        out
    }
}

/// `(⌊n/d⌋, n mod d)` from `m = ⌊(2^32 − 1)/d⌋` ([`DivisorU32`]'s contract). Tested on every
/// target; used where there is no hardware division.
#[cfg_attr(hardware_divide, allow(dead_code))]
#[inline(always)]
fn reciprocal_divide_u32(n: u32, d: u32, m: u32) -> (u32, u32) {
    let mut q = (mul_wide_u(n, m) >> 32) as u32;
    let mut r = n - q * d;
    while r >= d {
        q += 1;
        r -= d;
    }
    (q, r)
}

/// `(⌊a/d⌋, a mod d)` from `m = ⌊(2^64 − 1)/d⌋` (see [`Divisor`]): at most two corrections.
#[inline(always)]
fn reciprocal_divide(a: u64, d: u64, m: u64) -> (u64, u64) {
    let mut q = mul_high(a, m);
    let mut r = a - q.wrapping_mul(d);
    while r >= d {
        q += 1;
        r -= d;
    }
    (q, r)
}

/// The high 64 bits of the 128-bit product `a·b`, from four 32×32→64-bit products
/// ([`mul_wide_u`]: what a 32-bit core multiplies natively, or its 16-bit split on the
/// Cortex-M0).
#[inline(always)]
pub fn mul_high(a: u64, b: u64) -> u64 {
    let (a0, a1) = (a as u32, (a >> 32) as u32);
    let (b0, b1) = (b as u32, (b >> 32) as u32);
    let lo = mul_wide_u(a0, b0);
    let mid1 = mul_wide_u(a1, b0);
    let mid2 = mul_wide_u(a0, b1);
    let hi = mul_wide_u(a1, b1);
    // Carry from the middle column: (lo >> 32) + low halves of mid1 and mid2, each < 2^32.
    let carry = ((lo >> 32) + (mid1 & 0xFFFF_FFFF) + (mid2 & 0xFFFF_FFFF)) >> 32;
    hi + (mid1 >> 32) + (mid2 >> 32) + carry
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// `build.rs` sets `cfg(hardware_divide)` on the test host (x86-64 or AArch64).
    #[test]
    fn the_test_host_divides_in_hardware() {
        let host = cfg!(any(
            target_arch = "x86",
            target_arch = "x86_64",
            target_arch = "aarch64"
        ));
        assert_eq!(crate::arith::HARDWARE_DIVIDE, host);
    }

    /// [`DivisorU32`]'s reciprocal path (forced: the host divides in hardware) equals the
    /// division for divisors and dividends of every magnitude and at the extremes: `d` of 1,
    /// powers of two and their neighbours, `2^32 − 1`; `n` of 0, `d − 1`, `d`, `2^32 − 1`.
    #[test]
    fn u32_reciprocal_division_is_exact() {
        let mut rng = crate::test_rng::XorShift(0x2545_F491_4F6C_DD1D);
        let mut divisors = std::vec![1u32, 2, 3, u32::MAX, u32::MAX - 1, 1 << 31, (1 << 31) + 1];
        for k in 1..32 {
            divisors.extend([(1u32 << k) - 1, 1 << k, (1u32 << k).wrapping_add(1)]);
        }
        for _ in 0..2000 {
            let r = rng.next_u64();
            divisors.push(((r as u32) >> (r >> 59)).max(1));
        }
        for &d in &divisors {
            let m = u32::MAX / d;
            let mut dividends =
                std::vec![0u32, d - 1, d, d.wrapping_mul(2), u32::MAX, u32::MAX - 1];
            for _ in 0..200 {
                let r = rng.next_u64();
                dividends.push((r as u32) >> ((r >> 40) % 32));
            }
            for n in dividends {
                assert_eq!(reciprocal_divide_u32(n, d, m), (n / d, n % d), "{n} / {d}");
                let div = DivisorU32::new(NonZeroU32::new(d).unwrap());
                assert_eq!(div.div_rem(n), (n / d, n % d));
                assert_eq!(div.max_quotient(), u32::MAX / d);
                if d < 1 << 31 {
                    let twice = div.doubled();
                    assert_eq!(twice.get(), 2 * d);
                    assert_eq!(twice.max_quotient(), u32::MAX / (2 * d));
                    assert_eq!(
                        reciprocal_divide_u32(n, 2 * d, m >> 1),
                        (n / (2 * d), n % (2 * d))
                    );
                }
            }
        }
    }

    #[test]
    fn reciprocal_division_is_exact() {
        let mut rng = crate::test_rng::XorShift(0x9E37_79B9_7F4A_7C15u64);
        let mut rnd = || rng.next_u64();
        for i in 0..200_000 {
            let d = (rnd() >> (2 + (i % 62))).max(1) as i64;
            let a = (rnd() as i64) >> (1 + (i % 63) as u32 / 2);
            // The reciprocal path, forced (the 64-bit host would otherwise divide directly).
            let (ud, ua) = (d as u64, a.unsigned_abs());
            let m = u64::MAX / ud;
            // The estimate is at most two below the quotient.
            assert!(ua / ud - mul_high(ua, m) <= 2, "{a} / {d}");
            assert_eq!(
                reciprocal_divide(ua, ud, m),
                (ua / ud, ua % ud),
                "{a} / {d}"
            );
            assert_eq!(
                Divisor::new(d).div_floor(a),
                (a.div_euclid(d), a.rem_euclid(d))
            );
            let b = rnd();
            assert_eq!(mul_high(ua, b), ((ua as u128 * b as u128) >> 64) as u64);
        }
    }

    #[test]
    fn i128_division_matches_on_both_sides_of_the_i64_range() {
        let big = i64::MAX as i128;
        for a in [
            -(1i128 << 100),
            -big - 2,
            -big - 1,
            -big,
            -1_000_003,
            -7,
            -1,
            0,
            6,
            999_999_937,
            big,
            big + 1,
            1 << 100,
        ] {
            for b in [1i128, 2, 7, 1 << 40, big, big + 1, 1 << 90] {
                assert_eq!(
                    div_floor_i128(a, b),
                    (a.div_euclid(b), a.rem_euclid(b)),
                    "{a} {b}"
                );
            }
        }
    }

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
