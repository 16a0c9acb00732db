//! The unit tests' pseudo-random inputs: one generator, Marsaglia's 64-bit xorshift (shifts
//! 13, 7, 17), seeded by each test with its own constant so that every run draws the same
//! inputs. Tests map its raw words to their ranges themselves.

/// Marsaglia's xorshift64: the state is the last word drawn (never zero for a non-zero seed).
#[derive(Debug, Clone)]
pub(crate) struct XorShift(pub(crate) u64);

impl XorShift {
    /// The next word of the sequence.
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}
