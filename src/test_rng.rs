//! The one pseudo-random generator of the workspace's tests: Marsaglia's 64-bit xorshift
//! (shifts 13, 7, 17). Every test seeds its own, so every run draws the same inputs. The core's
//! unit tests use it as `crate::test_rng::XorShift`; the host crate compiles this same file as
//! `zscan_host::test_rng` for the integration tests. Not part of the library.

/// Marsaglia's xorshift64: the state is the last word drawn (never zero for a non-zero state).
#[derive(Debug, Clone)]
pub struct XorShift(pub u64);

#[allow(dead_code)] // each crate that compiles this file uses a different subset
impl XorShift {
    /// A generator for any seed (zero and small seeds included): the seed goes through
    /// SplitMix64's finaliser first, so nearby seeds give unrelated sequences, and a zero state
    /// (which xorshift never leaves) becomes a fixed non-zero one.
    pub fn new(seed: u64) -> Self {
        let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        XorShift(if z == 0 { 0x2545_F491_4F6C_DD1D } else { z })
    }

    /// The next word of the sequence.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Below `m` (`m > 0`; the modulo's bias is below `m / 2^64`).
    pub fn below(&mut self, m: u64) -> u64 {
        self.next_u64() % m
    }

    /// In `lo..=hi` (`lo ≤ hi`, `hi − lo < 2^63`).
    pub fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % ((hi - lo) as u64 + 1)) as i64
    }

    /// True with probability `percent / 100`.
    pub fn chance(&mut self, percent: u64) -> bool {
        self.next_u64() % 100 < percent
    }

    /// In `[0, 1)`, 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// In `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}
