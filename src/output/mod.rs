//! Render targets: where the raster stage's pixels end up.
//!
//! Role in the pipeline: the last stage. The raster stage writes palette indices into a
//! caller-provided [`Framebuffer`] (one `u8` per pixel) and, when a scene needs hidden-surface
//! removal, depth values into a caller-provided [`DepthBuffer`]. A [`Lut`] maps the 256 indices
//! to display colours (and a [`BlendTable`] maps two indices to the index of their mix, for
//! blended transparency), and [`flush()`] sends the frame (or only its dirty rectangle) to any
//! embedded-graphics `DrawTarget` through `fill_contiguous`, the fast path display drivers
//! implement.
//!
//! Memory always comes from the caller: nothing here allocates. A frame may also be a *band*
//! (rows `top..top + height` of a taller picture), so a 320×240 display can be drawn in a few KB.
//!
//! Conventions: `x` grows to the right, `y` downward; row `y` of a buffer starts at
//! `(y - top) * stride`. Sizes are `u16` (a display is at most 65 535 pixels wide), so every
//! index computed here fits `usize` on 16-bit and wider targets without overflow.

mod blend;
mod depth;
mod flush;
mod framebuffer;
mod lut;
mod mask;
mod pages;
mod palette_index;
mod window;

pub use blend::{BlendError, BlendTable, BLEND_ENTRIES};
pub use depth::{DepthBuffer, DepthValue, NoDepth};
pub use flush::flush;
pub use framebuffer::Framebuffer;
pub use lut::{shaded_index, Lut, LutError};
pub use mask::{mask_words_needed, PaintedMask};
pub use pages::{pack_pages, page_bytes};
pub use palette_index::PaletteIndex;
pub use window::Window;

/// Why a caller buffer could not be wrapped as a framebuffer, depth buffer or mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BufferError {
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
    /// A buffer packed into 8-row pages ([`pack_pages`]) does not start on a page or does not
    /// hold whole pages.
    NotWholePages {
        /// Its first row (absolute).
        top: i32,
        /// Its rows.
        height: u16,
    },
}

impl core::fmt::Display for BufferError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BufferError::ZeroSize => write!(f, "width and height must be at least 1"),
            BufferError::StrideTooSmall { stride, width } => {
                write!(f, "stride {stride} is smaller than the width {width}")
            }
            BufferError::BufferTooSmall { needed, len } => {
                write!(f, "buffer holds {len} elements but {needed} are needed")
            }
            BufferError::SizeMismatch => write!(f, "depth buffer and framebuffer differ in size"),
            BufferError::NotWholePages { top, height } => write!(
                f,
                "pages are 8 rows: a buffer packed into pages starts on a multiple of 8 rows and \
                 holds whole pages, this one holds {height} rows from row {top}"
            ),
        }
    }
}

impl core::error::Error for BufferError {}

/// Bytes the buffer clears ([`fill_u8`], [`fill_u16`], [`fill_u32`]) write per loop iteration.
pub(crate) const FILL_CHUNK_BYTES: usize = 128;

// The buffer clears. `slice::fill` with a value whose bytes are all equal (any `u8`, the depth
// buffers' all-ones `FAR`) becomes a call to the C library's `memset`, which on a Cortex-M4
// stores one word per iteration of its loop (about 3 instructions per word for an unaligned
// destination, 1.5 aligned). Here the buffer is split at its first and last 8-byte boundaries
// (`<[T]>::align_to_mut::<u64>`): the few elements outside are set one by one, the aligned
// middle as `u64` words of the pattern, [`FILL_CHUNK_BYTES`] per loop iteration, which the
// compiler stores as pairs of words (`strd` on the Cortex-M3/M4). Because the middle is
// aligned, cores without unaligned word stores (Cortex-M0/M0+) get word stores too. The pattern
// goes through `core::hint::black_box` once per call so that the loop is not turned back into
// a `memset` call (LLVM's loop-idiom pass does so for stores of a constant byte pattern); its
// value is the splat of `v` whatever the optimiser does, so correctness does not depend on it.
//
// The split is the core's one `unsafe` block (`align_to_mut` is `unsafe` because it
// reinterprets memory; the proof is at the block). Why not safe code: safe Rust cannot tell the
// compiler that the middle of a `u8` or `u16` slice is 8-byte aligned, and without that the
// Cortex-M4 stores one word per instruction instead of two. Measured with `zscan bench --m0`
// against the same loop over 8-byte chunks in safe code (and `memset` on the Cortex-M0): the
// 320×240 clear (colour and 16-bit depth) takes 31,770 instead of 58,714 Cortex-M4
// instructions and 63,077 instead of 134,469 Cortex-M0 ones, +26,953 and +71,399 on every
// z-buffered frame (frame_quad +5.4 % and +9.0 %). The split was `bytemuck::pod_align_to_mut`
// before; the core keeps to its four dependencies instead.

/// The integer element types the clears reinterpret: every bit pattern of 8 bytes is a valid
/// run of them, and every bit pattern of theirs a valid part of a `u64` (no padding, no
/// invalid values). Sealed: implemented for `u8`, `u16` and `u32` only.
trait PlainInteger: Copy {}
impl PlainInteger for u8 {}
impl PlainInteger for u16 {}
impl PlainInteger for u32 {}

/// Sets every element of `dst` to `v`, given `word`, the `u64` whose bytes are those of `v`
/// repeated: the elements before the first 8-byte boundary and after the last one by one, the
/// aligned middle as `word`s, [`FILL_CHUNK_BYTES`] per loop iteration.
#[inline]
#[allow(unsafe_code)]
fn fill_aligned<T: PlainInteger>(dst: &mut [T], v: T, word: u64) {
    // SAFETY: `align_to_mut` requires that any bit pattern of the middle's `u64`s be valid for
    // `T` and the converse, which holds for the plain integers of `PlainInteger` (`u8`, `u16`,
    // `u32`: no padding, every bit pattern valid; `size_of::<u64>()` is a multiple of each
    // size, so a `u64` is exactly a whole number of `T`s). It returns three disjoint slices
    // that borrow `dst` mutably for their lifetime, the middle one aligned for `u64` and within
    // `dst`'s bounds, so no write leaves `dst` and no alias exists while they live.
    let (head, body, tail) = unsafe { dst.align_to_mut::<u64>() };
    head.fill(v);
    tail.fill(v);
    let word = core::hint::black_box(word);
    let mut chunks = body.chunks_exact_mut(FILL_CHUNK_BYTES / 8);
    for c in &mut chunks {
        c.fill(word);
    }
    chunks.into_remainder().fill(word);
}

/// Sets every byte of `dst` to `v`.
#[inline]
pub(crate) fn fill_u8(dst: &mut [u8], v: u8) {
    fill_aligned(dst, v, u64::from_ne_bytes([v; 8]));
}

/// Sets every element of `dst` to `v`.
#[inline]
pub(crate) fn fill_u16(dst: &mut [u16], v: u16) {
    fill_aligned(dst, v, u64::from(v) * 0x0001_0001_0001_0001);
}

/// Sets every element of `dst` to `v`.
#[inline]
pub(crate) fn fill_u32(dst: &mut [u32], v: u32) {
    fill_aligned(dst, v, u64::from(v) * 0x0000_0001_0000_0001);
}

/// Checks a `width × height` buffer with `stride` against a slice length; returns the length needed.
pub(crate) fn check_layout(
    len: usize,
    width: u16,
    height: u16,
    stride: usize,
) -> Result<usize, BufferError> {
    if width == 0 || height == 0 {
        return Err(BufferError::ZeroSize);
    }
    if stride < width as usize {
        return Err(BufferError::StrideTooSmall { stride, width });
    }
    // (height - 1) * stride + width, computed with checked arithmetic: a huge stride must not wrap.
    let needed = (height as usize - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(width as usize))
        .ok_or(BufferError::BufferTooSmall {
            needed: usize::MAX,
            len,
        })?;
    if len < needed {
        return Err(BufferError::BufferTooSmall { needed, len });
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
