//! The interpolants: values that step one pixel right at a time, the interface every span
//! loop is generic over, and where a span's exact starts come from.
//!
//! Role in the pipeline: between the attribute planes (`small_plane`, `plane`, `wide_plane`,
//! which set a triangle up) and the span loop (`span`, which steps them). [`Exact`] is the
//! correctly rounded value with its quotient-and-remainder step (no drift on any span
//! length, the exact variant of course exercise 18), [`ExactRun`] the same as one 32.32
//! accumulator on short enough runs, [`Constant`] a flat attribute (free to step), [`Dda`] the
//! fast 16.16 variant; [`SpanStarts`] is what the span loop asks a plane for at each span.
//!
//! Numeric contract: values are `u32`, added with wrapping arithmetic (exact at covered
//! pixels, where the true value is a convex combination of the vertex values); an [`Exact`]
//! keeps `0 ≤ rem < 2D < 2^31`, so `rem + r` cannot overflow. Conventions and the definition
//! of the rounded value: the `plane` module's doc.

use crate::arith::euclid::Divisor;

/// A value that moves one pixel right at a time: the interface span loops are generic over.
pub trait Interpolant: Copy {
    /// True for [`Constant`]: lets span loops pick a branch-free, vectorisable form at compile time.
    const IS_CONSTANT: bool = false;
    /// The value at the current pixel.
    fn value(&self) -> u32;
    /// Moves one pixel to the right.
    fn step(&mut self);
}

/// The correctly rounded value of an affine attribute, stepped exactly (quotient, remainder).
#[derive(Debug, Clone, Copy)]
pub struct Exact {
    pub(super) value: u32,
    /// Remainder of `2M + D` by `2D`, in `0..two_d`.
    pub(super) rem: u32,
    /// Quotient added per pixel (mod 2^32).
    pub(super) q: u32,
    /// Remainder added per pixel, in `0..two_d`.
    pub(super) r: u32,
    /// `2D`, the carry threshold (`< 2^31`).
    pub(super) two_d: u32,
}

impl Exact {
    /// The state from its parts: `value`, its remainder `rem < two_d`, and the per-pixel
    /// quotient `q` and remainder `r < two_d` (`two_d < 2^31`).
    #[inline(always)]
    pub(crate) fn from_parts(value: u32, rem: u32, (q, r): (u32, u32), two_d: u32) -> Self {
        Exact {
            value,
            rem,
            q,
            r,
            two_d,
        }
    }

    /// Moves by a precomputed quotient and remainder (`r < 2D`), carrying once.
    #[inline(always)]
    pub fn advance(&mut self, (q, r): (u32, u32)) {
        let t = self.rem + r;
        let carry = (t >= self.two_d) as u32;
        self.rem = t - carry * self.two_d;
        self.value = self.value.wrapping_add(q).wrapping_add(carry);
    }

    /// The longest run of pixels an [`ExactRun`] started from this plane's values keeps
    /// correctly rounded: `⌊(2^32 − 1) / 2D⌋` (at least 2, since `2D < 2^31`).
    #[cfg(test)]
    pub fn run_limit(&self) -> u32 {
        u32::MAX / self.two_d
    }

    /// The remainder of the value's numerator, `0 ≤ rem < 2D` (the value's exact fraction is
    /// `rem / 2D − 1/2`, its rounding residue).
    #[cfg(test)]
    pub fn remainder(&self) -> (u32, u32) {
        (self.rem, self.two_d)
    }
}

impl Interpolant for Exact {
    #[inline(always)]
    fn value(&self) -> u32 {
        self.value
    }

    #[inline(always)]
    fn step(&mut self) {
        self.advance((self.q, self.r)); // rem, r < 2^31: the sum cannot overflow
    }
}

/// The exact interpolant as one 32.32 fixed-point accumulator: one add per pixel, and still
/// correctly rounded on runs of at most `2^32 / 2D − 1` pixels ([`Exact::run_limit`]).
///
/// Why: the exact value is `⌊V⌋` with `V = T / 2D`, whose fraction is a multiple of `1/2D`.
/// Starting from `V` rounded **up** to 2^-32 and adding the step rounded up to 2^-32, after `k`
/// steps the accumulator exceeds `V` by less than `(k + 1)·2^-32`, which stays below `1/2D` —
/// too little to reach the next integer — while `(k + 1)·2D < 2^32`. Span loops use it when
/// every span of a triangle is that short (all triangles of the standard sphere and bunny) and
/// fall back to [`Exact`] otherwise.
#[derive(Debug, Clone, Copy)]
pub struct ExactRun {
    acc: u64,
    inc: u64,
}

impl ExactRun {
    /// The 32.32 step of `e` and `2D` prepared for the starts (per triangle: neither depends
    /// on the span).
    #[inline]
    pub fn prepare(e: &Exact) -> (u64, Divisor) {
        let two_d = Divisor::new(e.two_d as i64);
        (Self::ceil_frac(e.q, e.r, &two_d), two_d)
    }

    /// `(q << 32) + ⌈r·2^32 / 2D⌉` for `r < 2D` (wrapping in the integer part).
    #[inline(always)]
    fn ceil_frac(q: u32, r: u32, two_d: &Divisor) -> u64 {
        let (f, rem) = two_d.div_floor((r as i64) << 32);
        ((q as u64) << 32).wrapping_add(f as u64 + (rem != 0) as u64)
    }

    /// Starts at the exact state `e` with the step and divisor of [`ExactRun::prepare`].
    #[inline(always)]
    pub fn start(e: &Exact, (inc, two_d): &(u64, Divisor)) -> Self {
        // rem < 2D, so the rounded-up fraction stays below 2^32.
        ExactRun {
            acc: Self::ceil_frac(e.value, e.rem, two_d),
            inc: *inc,
        }
    }
}

impl Interpolant for ExactRun {
    #[inline(always)]
    fn value(&self) -> u32 {
        (self.acc >> 32) as u32
    }

    #[inline(always)]
    fn step(&mut self) {
        self.acc = self.acc.wrapping_add(self.inc);
    }
}

/// An attribute with the same value at every pixel: stepping is free.
#[derive(Debug, Clone, Copy)]
pub struct Constant(pub u32);

impl Interpolant for Constant {
    const IS_CONSTANT: bool = true;

    #[inline(always)]
    fn value(&self) -> u32 {
        self.0
    }

    #[inline(always)]
    fn step(&mut self) {}
}

/// The fast variant: the value in 16.16 fixed point plus a 16.16 increment per pixel. Each
/// span starts from the plane's value (exact to 2^-16); along the span the increment's
/// truncation (< 2^-16 per pixel) accumulates, so after `n` pixels the value may be low by up
/// to `n · 2^-16` plus the final rounding. For attributes below `2^15` (luminance, not depth).
#[derive(Debug, Clone, Copy)]
pub struct Dda {
    pub(super) acc: u32,
    pub(super) inc: u32,
}

impl Interpolant for Dda {
    #[inline(always)]
    fn value(&self) -> u32 {
        self.acc >> 16
    }

    #[inline(always)]
    fn step(&mut self) {
        self.acc = self.acc.wrapping_add(self.inc);
    }
}

/// Where the exact span starts of one triangle come from: [`RowStarts`] over an
/// [`AttributePlane`] (`2D < 2^31`), a [`SmallPlane`] (32-bit arithmetic), or a
/// [`WidePlane`] (any triangle of the raster's range). Span loops are generic over it, so all
/// three feed the same span machinery.
pub trait SpanStarts<const N: usize> {
    /// The exact interpolant a span starts from: [`Exact`], or [`ExactWide`] for a
    /// [`WidePlane`].
    type Exact: Interpolant;
    /// The exact values at `(x, y)`, a covered pixel, ready to step right.
    fn exact_at(&mut self, x: i32, y: i32) -> [Self::Exact; N];
    /// Attribute `i < N` at `(x, y)` (a covered pixel) as [`AttributePlane::dda`] gives it.
    fn dda_at(&self, i: usize, x: i32, y: i32) -> Dda;
}
