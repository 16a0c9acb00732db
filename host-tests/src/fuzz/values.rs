//! Random values with stated ranges: the one way the planner's, the methods' and the fill's
//! targets draw their inputs (over the workspace's xorshift, [`XorShift`]). Every function
//! names its range in its signature or its doc; none draws outside it.

use crate::test_rng::XorShift;

/// An integer in `lo..=hi` (`lo ≤ hi`), uniformly.
pub fn int(rng: &mut XorShift, lo: i64, hi: i64) -> i64 {
    rng.range(lo, hi)
}

/// A size in `lo..=hi` (`lo ≤ hi`), uniformly.
pub fn size(rng: &mut XorShift, lo: usize, hi: usize) -> usize {
    rng.range(lo as i64, hi as i64) as usize
}

/// A real in `[lo, hi)`, uniformly.
pub fn real(rng: &mut XorShift, lo: f64, hi: f64) -> f64 {
    rng.uniform(lo, hi)
}

/// A real in `[lo, hi)` (`0 < lo < hi`), uniform in its logarithm: every scale of the range
/// equally often (sizes and distances from tiny to large).
pub fn scale(rng: &mut XorShift, lo: f64, hi: f64) -> f64 {
    (lo.ln() + (hi.ln() - lo.ln()) * rng.unit()).exp()
}

/// A size in `0..=hi`, uniform in its number of bits (small sizes as often as large ones).
pub fn bits_size(rng: &mut XorShift, hi: usize) -> usize {
    let bits = rng.range(0, (usize::BITS - hi.leading_zeros()) as i64) as u32;
    let top = if bits == 0 { 0 } else { (1usize << bits) - 1 };
    size(rng, 0, top.min(hi))
}

/// True with probability `percent / 100` (`percent ≤ 100`).
pub fn chance(rng: &mut XorShift, percent: u64) -> bool {
    rng.chance(percent)
}

/// One element of `items` (not empty), uniformly.
pub fn one_of<T: Copy>(rng: &mut XorShift, items: &[T]) -> T {
    items[rng.below(items.len() as u64) as usize]
}

/// The length of a caller buffer that needs `needed` elements: exactly `needed` (half the
/// time), 1 to 3 more (3 in 8), or anything from none up to `needed` (1 in 8: with four
/// buffers to a call, about half the calls are given enough).
pub fn memory(rng: &mut XorShift, needed: usize) -> usize {
    match rng.below(8) {
        0..=3 => needed,
        4..=6 => needed + size(rng, 1, 3),
        _ => size(rng, 0, needed),
    }
}
