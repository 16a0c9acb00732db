//! Render targets: where the raster stage's pixels end up.
//!
//! Role in the pipeline: the last stage. The raster stage writes palette indices into a
//! caller-provided [`Framebuffer`] (one `u8` per pixel) and, when a scene needs hidden-surface
//! removal, depth values into a caller-provided [`DepthBuffer`]. A [`Lut`] maps the 256 indices
//! to display colours, and [`flush()`] sends the frame (or only its dirty rectangle) to any
//! embedded-graphics `DrawTarget` through `fill_contiguous`, the fast path display drivers
//! implement.
//!
//! Memory always comes from the caller: nothing here allocates. A frame may also be a *band*
//! (rows `top..top + height` of a taller picture), so a 320×240 display can be drawn in a few KB.
//!
//! Conventions: `x` grows to the right, `y` downward; row `y` of a buffer starts at
//! `(y - top) * stride`. Sizes are `u16` (a display is at most 65 535 pixels wide), so every
//! index computed here fits `usize` on 16-bit and wider targets without overflow.

mod depth;
mod flush;
mod framebuffer;
mod lut;
mod palette_index;

pub use depth::{DepthBuffer, DepthValue, NoDepth};
pub use flush::flush;
pub use framebuffer::Framebuffer;
pub use lut::{shaded_index, Lut, LutError};
pub use palette_index::PaletteIndex;

/// Why a buffer could not be wrapped as a render target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TargetError {
    /// Width or height is zero.
    ZeroSize,
    /// The stride is smaller than the width.
    StrideTooSmall {
        /// The stride given.
        stride: usize,
        /// The width it must at least be.
        width: u16,
    },
    /// The slice is too short for `height` rows of `stride` elements (the last row needs only `width`).
    BufferTooSmall {
        /// Elements needed.
        needed: usize,
        /// Elements given.
        len: usize,
    },
    /// A depth buffer does not have the framebuffer's size.
    SizeMismatch,
}

impl core::fmt::Display for TargetError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TargetError::ZeroSize => write!(f, "width and height must be at least 1"),
            TargetError::StrideTooSmall { stride, width } => {
                write!(f, "stride {stride} is smaller than the width {width}")
            }
            TargetError::BufferTooSmall { needed, len } => {
                write!(f, "buffer holds {len} elements but {needed} are needed")
            }
            TargetError::SizeMismatch => write!(f, "depth buffer and framebuffer differ in size"),
        }
    }
}

impl core::error::Error for TargetError {}

/// Bytes the buffer clears ([`fill_u8`], [`fill_u16`], [`fill_u32`]) write per loop iteration.
pub(crate) const FILL_CHUNK_BYTES: usize = 128;

// The buffer clears, in safe code. `slice::fill` with a value whose bytes are all equal (any
// `u8`, the depth buffers' all-ones `FAR`) becomes a call to the C library's `memset`, which
// on a Cortex-M4 stores one word per iteration of its loop (about 3 instructions per word for
// an unaligned destination, 1.5 aligned). Where the core stores words at any address
// ([`UNALIGNED_STORES`](crate::arith::UNALIGNED_STORES): x86-64, AArch64, Cortex-M3/M4/M7),
// the buffer is written instead as 8-byte copies of the pattern, [`FILL_CHUNK_BYTES`] per loop
// iteration: one 32-bit store per word on the Cortex-M4 (about 1.1 instructions per word with
// the loop), 16-byte vector stores on x86-64. The pattern goes through `core::hint::black_box`
// once per call so that the loop is not turned back into a `memset` call (LLVM's loop-idiom
// pass does so for stores of a constant byte pattern); its value is the splat of `v` whatever
// the optimiser does, so correctness does not depend on it. Safe code cannot tell the compiler
// that the middle of a `u8` or `u16` buffer is 8-byte aligned (that took a reinterpreting
// split, `bytemuck::pod_align_to_mut`, removed with the dependency), so the Cortex-M4's
// doubleword stores (`strd`, 2 words per instruction) are not used. Cores that store words
// only at aligned addresses (Cortex-M0/M0+) would get byte stores here, and take `memset`
// (aligned word stores) instead.

/// Sets every element of `dst` to `v`, given `pattern`, `8 / size_of::<T>()` copies of `v`
/// (8 bytes): as 8-byte copies of the pattern, [`FILL_CHUNK_BYTES`] per loop iteration, the
/// last elements one by one; on cores without unaligned word stores, `slice::fill`.
#[inline]
fn fill_pattern<T: Copy, const N: usize>(dst: &mut [T], v: T, pattern: [T; N]) {
    if !crate::arith::UNALIGNED_STORES {
        dst.fill(v);
        return;
    }
    let pattern = core::hint::black_box(pattern);
    let mut chunks = dst.chunks_exact_mut(FILL_CHUNK_BYTES / core::mem::size_of::<T>());
    for c in &mut chunks {
        for w in c.chunks_exact_mut(N) {
            w.copy_from_slice(&pattern);
        }
    }
    let mut words = chunks.into_remainder().chunks_exact_mut(N);
    for w in &mut words {
        w.copy_from_slice(&pattern);
    }
    words.into_remainder().fill(v);
}

/// Sets every byte of `dst` to `v`.
#[inline]
pub(crate) fn fill_u8(dst: &mut [u8], v: u8) {
    fill_pattern(dst, v, [v; 8]);
}

/// Sets every element of `dst` to `v`.
#[inline]
pub(crate) fn fill_u16(dst: &mut [u16], v: u16) {
    fill_pattern(dst, v, [v; 4]);
}

/// Sets every element of `dst` to `v`.
#[inline]
pub(crate) fn fill_u32(dst: &mut [u32], v: u32) {
    fill_pattern(dst, v, [v; 2]);
}

/// Checks a `width × height` buffer with `stride` against a slice length; returns the length needed.
pub(crate) fn check_layout(
    len: usize,
    width: u16,
    height: u16,
    stride: usize,
) -> Result<usize, TargetError> {
    if width == 0 || height == 0 {
        return Err(TargetError::ZeroSize);
    }
    if stride < width as usize {
        return Err(TargetError::StrideTooSmall { stride, width });
    }
    // (height - 1) * stride + width, computed with checked arithmetic: a huge stride must not wrap.
    let needed = (height as usize - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(width as usize))
        .ok_or(TargetError::BufferTooSmall {
            needed: usize::MAX,
            len,
        })?;
    if len < needed {
        return Err(TargetError::BufferTooSmall { needed, len });
    }
    Ok(needed)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every start offset (aligned or not) and every length up to a few chunks, inside a
    /// larger buffer whose bytes outside the range must stay untouched.
    #[test]
    fn fills_write_exactly_their_range() {
        for start in 0..9 {
            for len in 0..(3 * FILL_CHUNK_BYTES + 5) {
                let mut b = [0x5Au8; 4 * FILL_CHUNK_BYTES + 16];
                fill_u8(&mut b[start..start + len], 0xC3);
                for (i, &x) in b.iter().enumerate() {
                    let inside = (start..start + len).contains(&i);
                    assert_eq!(x, if inside { 0xC3 } else { 0x5A }, "u8 {start} {len} {i}");
                }
                let mut h = [0x1234u16; 2 * FILL_CHUNK_BYTES + 16];
                let len16 = len.min(h.len() - start);
                fill_u16(&mut h[start..start + len16], 0xFEDC);
                for (i, &x) in h.iter().enumerate() {
                    let inside = (start..start + len16).contains(&i);
                    assert_eq!(
                        x,
                        if inside { 0xFEDC } else { 0x1234 },
                        "u16 {start} {len} {i}"
                    );
                }
                let mut w = [7u32; FILL_CHUNK_BYTES + 16];
                let len32 = len.min(w.len() - start);
                fill_u32(&mut w[start..start + len32], u32::MAX);
                for (i, &x) in w.iter().enumerate() {
                    let inside = (start..start + len32).contains(&i);
                    assert_eq!(
                        x,
                        if inside { u32::MAX } else { 7 },
                        "u32 {start} {len} {i}"
                    );
                }
            }
        }
        // Values whose bytes differ (no byte-splat shortcut may be assumed).
        let mut h = [0u16; 37];
        fill_u16(&mut h[1..], 0x00FF);
        assert_eq!(h[0], 0);
        assert!(h[1..].iter().all(|&x| x == 0x00FF));
    }

    /// Framebuffer and depth clears: packed frames, bands, strides wider than the rows (the
    /// bytes between rows untouched), slices starting at odd addresses, widths that are not a
    /// multiple of the chunk, and slices longer than the buffer (the rest untouched).
    #[test]
    fn clears_cover_the_buffer_and_nothing_else() {
        for (w, h, stride) in [
            (1u16, 1u16, 1usize),
            (3, 5, 3),
            (3, 5, 4),
            (17, 3, 17),
            (33, 4, 40),
            (320, 16, 320),
            (320, 3, 333),
            (31, 9, 31),
        ] {
            for offset in 0..5 {
                let need = (h as usize - 1) * stride + w as usize;
                let mut buf = [0xEEu8; 6000];
                {
                    let pixels = &mut buf[offset..offset + need + 7];
                    let mut fb = Framebuffer::with_stride(pixels, w, h, stride).unwrap();
                    fb.clear(9);
                }
                for (i, &x) in buf.iter().enumerate() {
                    let j = i.wrapping_sub(offset);
                    let inside = i >= offset && j < need && j % stride < w as usize;
                    assert_eq!(
                        x,
                        if inside { 9 } else { 0xEE },
                        "fb {w}x{h}/{stride} +{offset} @{i}"
                    );
                }
                let n = w as usize * h as usize;
                let mut d16 = [3u16; 6000];
                {
                    let mut zb =
                        DepthBuffer::band(&mut d16[offset..offset + n + 5], w, h, 7).unwrap();
                    zb.clear();
                    assert_eq!(zb.row(7).map(|r| r.len()), Some(w as usize));
                }
                for (i, &x) in d16.iter().enumerate() {
                    let inside = (offset..offset + n).contains(&i);
                    assert_eq!(
                        x,
                        if inside { u16::MAX } else { 3 },
                        "u16 depth {w}x{h} +{offset} @{i}"
                    );
                }
                let mut d32 = [3u32; 6000];
                DepthBuffer::new(&mut d32[offset..offset + n + 5], w, h)
                    .unwrap()
                    .clear();
                for (i, &x) in d32.iter().enumerate() {
                    let inside = (offset..offset + n).contains(&i);
                    assert_eq!(
                        x,
                        if inside { u32::MAX } else { 3 },
                        "u32 depth {w}x{h} +{offset} @{i}"
                    );
                }
            }
        }
    }
}
