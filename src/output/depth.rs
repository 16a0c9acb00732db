//! The depth buffer (z-buffer) over a caller-provided `&mut [u16]` or `&mut [u32]`.
//!
//! Numeric contract: a stored depth is an unsigned integer where **smaller is nearer**;
//! [`DepthValue::FAR`] (all ones) is the cleared value and never wins a test. The raster stage
//! computes depth as a 32-bit quantity ([`DepthValue::from_depth32`]) and each width keeps its
//! top bits, so one code path serves both widths: `u16` resolves 1/65 536 of the depth range,
//! `u32` 1/4 294 967 296. The test is strict, nearer wins (course algorithm 3.3, TIPE §2):
//! equal depths keep the first surface drawn.
//!
//! **Every surface inside `[near, far]` can win against the cleared buffer.** The triangle
//! writers clamp each triangle's three vertex depths to [`DepthValue::MAX_DEPTH32`], the
//! largest 32-bit depth whose stored value is below `FAR` (`u16`: the last step, 32-bit depths
//! `≥ 2^32 − 2^16`, i.e. surfaces within `Δz ≈ z²(far − near)/(far·near·2^16)` of `far`;
//! `u32`: the depth `2^32 − 1` of a point at `far` or within the projection's rounding of it).
//! An interpolated depth lies between its vertices' (the planes are exact), so no stored depth
//! reaches `FAR`. Those surfaces used to store `FAR` and never pass the strict test against
//! the clear, so they vanished; triangles with no vertex that deep are drawn unchanged (the
//! same pictures). The cost is three `min`s per triangle (a `min` per pixel, measured first,
//! cost the standard frames 10–15 %).

use super::{check_layout, BufferError};

/// An unsigned depth sample width (`u16` or `u32`).
pub trait DepthValue: Copy + Ord + core::fmt::Debug + 'static {
    /// The cleared value: farther than anything drawn.
    const FAR: Self;
    /// Bits stored per sample.
    const BITS: u32;
    /// The largest 32-bit depth whose stored value is below [`Self::FAR`]: the triangle
    /// writers clamp vertex depths to it, so that every surface can win against the cleared
    /// value (module doc).
    const MAX_DEPTH32: u32;
    /// Keeps the top [`Self::BITS`] bits of a 32-bit depth (smaller is nearer).
    fn from_depth32(d: u32) -> Self;
    /// The depth test: whether a surface at `self` replaces the stored `stored` (strict, nearer
    /// wins). [`NoDepth`] passes every test.
    #[inline(always)]
    fn nearer(self, stored: Self) -> bool {
        self < stored
    }
    /// Sets every sample of `dst` to [`Self::FAR`] ([`DepthBuffer::clear`]). `u16` and `u32`
    /// write 32 bytes per loop iteration as runs of word stores.
    #[inline]
    fn fill_far(dst: &mut [Self]) {
        dst.fill(Self::FAR);
    }
}

impl DepthValue for u16 {
    const FAR: Self = u16::MAX;
    const BITS: u32 = 16;
    const MAX_DEPTH32: u32 = 0xFFFE_FFFF;
    #[inline(always)]
    fn from_depth32(d: u32) -> Self {
        (d >> 16) as u16
    }
    #[inline]
    fn fill_far(dst: &mut [Self]) {
        super::fill_u16(dst, Self::FAR);
    }
}

impl DepthValue for u32 {
    const FAR: Self = u32::MAX;
    const BITS: u32 = 32;
    const MAX_DEPTH32: u32 = u32::MAX - 1;
    #[inline(always)]
    fn from_depth32(d: u32) -> Self {
        d
    }
    #[inline]
    fn fill_far(dst: &mut [Self]) {
        super::fill_u32(dst, Self::FAR);
    }
}

/// No depth at all: a zero-sized sample whose test always passes, so a
/// `DepthBuffer<NoDepth>` takes no memory and the span loops compile without a depth
/// interpolant, compare or store. Drawing through one paints triangles in the order given:
/// what the visibility methods that need no depth buffer use (back-face only, the painter;
/// [`visibility`](crate::visibility)). An array of them is zero bytes at any length:
///
/// ```
/// use zscan::output::{DepthBuffer, NoDepth};
///
/// let mut samples = [NoDepth; 320 * 240]; // zero bytes
/// assert_eq!(core::mem::size_of_val(&samples), 0);
/// let depth = DepthBuffer::new(&mut samples, 320, 240)?;
/// # Ok::<(), zscan::output::BufferError>(())
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
pub struct NoDepth;

impl DepthValue for NoDepth {
    const FAR: Self = NoDepth;
    const BITS: u32 = 0;
    const MAX_DEPTH32: u32 = u32::MAX;
    #[inline(always)]
    fn from_depth32(_: u32) -> Self {
        NoDepth
    }
    #[inline(always)]
    fn nearer(self, _: Self) -> bool {
        true
    }
    #[inline(always)]
    fn fill_far(_: &mut [Self]) {}
}

/// A depth buffer of `D` samples (possibly a band of a taller picture, like the framebuffer).
///
/// ```
/// use zscan::output::{DepthBuffer, DepthValue};
///
/// let mut samples = [0u16; 8 * 4]; // your memory: 16 bits per pixel (u32 for finer depth)
/// let mut depth = DepthBuffer::new(&mut samples, 8, 4)?;
/// depth.clear(); // everything far
/// assert_eq!(depth.get(7, 3), Some(u16::FAR));
/// assert_eq!(depth.get(8, 0), None);
/// # Ok::<(), zscan::output::BufferError>(())
/// ```
#[derive(Debug)]
pub struct DepthBuffer<'a, D: DepthValue> {
    samples: &'a mut [D],
    width: u16,
    height: u16,
    top: i32,
    /// Made by [`band`](Self::band): some rows of a taller picture, by design.
    band: bool,
}

impl<'a, D: DepthValue> DepthBuffer<'a, D> {
    /// Wraps `samples` as a `width × height` depth buffer (rows packed).
    pub fn new(samples: &'a mut [D], width: u16, height: u16) -> Result<Self, BufferError> {
        check_layout(samples.len(), width, height, width as usize)?;
        Ok(DepthBuffer {
            samples,
            width,
            height,
            top: 0,
            band: false,
        })
    }

    /// Wraps `samples` as the band of rows `top..top + height`.
    pub fn band(
        samples: &'a mut [D],
        width: u16,
        height: u16,
        top: u16,
    ) -> Result<Self, BufferError> {
        let mut d = Self::new(samples, width, height)?;
        d.top = top as i32;
        d.band = true;
        Ok(d)
    }

    /// Made by [`band`](Self::band), not by [`new`](Self::new) (see
    /// `Framebuffer::is_band`).
    pub(crate) fn is_band(&self) -> bool {
        self.band
    }

    /// Width in samples.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Rows held.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// Absolute row of the first row held.
    pub fn top(&self) -> i32 {
        self.top
    }

    /// Sets every sample to [`DepthValue::FAR`] ([`DepthValue::fill_far`]: 128 bytes per loop
    /// iteration for `u16` and `u32`); samples past `width × height` are left untouched.
    pub fn clear(&mut self) {
        let n = self.width as usize * self.height as usize;
        D::fill_far(&mut self.samples[..n]);
    }

    /// Row `y` (absolute) as a slice, or `None` outside the buffer.
    pub fn row(&self, y: i32) -> Option<&[D]> {
        let r = y.checked_sub(self.top)?;
        if r < 0 || r >= self.height as i32 {
            return None;
        }
        let s = r as usize * self.width as usize;
        self.samples.get(s..s + self.width as usize)
    }

    /// Row `y` (absolute) as a mutable slice, or `None` outside the buffer.
    #[inline]
    pub fn row_mut(&mut self, y: i32) -> Option<&mut [D]> {
        let r = y.checked_sub(self.top)?;
        if r < 0 || r >= self.height as i32 {
            return None;
        }
        let s = r as usize * self.width as usize;
        self.samples.get_mut(s..s + self.width as usize)
    }

    /// The whole buffer (rows `width` apart, the first row at absolute row [`top`](Self::top)),
    /// for loops that slice many spans and have checked their rows and columns once (the
    /// triangle writers, against the window both buffers hold).
    #[inline(always)]
    pub fn samples_mut(&mut self) -> &mut [D] {
        self.samples
    }

    /// Samples `x0..x1` of row `y` (absolute), or `None` unless `x0 ≤ x1 ≤ width` and the row
    /// is held. One range check: what the raster's span loops use.
    #[inline(always)]
    pub fn span_mut(&mut self, y: i32, x0: usize, x1: usize) -> Option<&mut [D]> {
        let r = y.wrapping_sub(self.top) as u32;
        if r >= self.height as u32 || x1 > self.width as usize || x0 > x1 {
            return None;
        }
        let start = r as usize * self.width as usize;
        self.samples.get_mut(start + x0..start + x1)
    }

    /// The sample at `(x, y)`, or `None` outside.
    pub fn get(&self, x: i32, y: i32) -> Option<D> {
        if x < 0 {
            return None;
        }
        self.row(y).and_then(|r| r.get(x as usize).copied())
    }
}
