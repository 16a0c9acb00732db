//! One-bit displays: the 8-bit frame (or a band of it) packed into *pages*, the byte layout of
//! the SSD1306 family of monochrome OLED controllers (SSD1306, SH1106, SSD1309).
//!
//! Role in the pipeline: the last stage, in place of [`flush`](super::flush()) for a display
//! that takes its pixels as bits (the course's "écran (bitmap)" taken literally: one bit a
//! pixel). Each palette index goes through an on/off table, a [`Lut`] of embedded-graphics'
//! `BinaryColor` ([`Lut::<BinaryColor>::threshold`](Lut::threshold) builds the usual one);
//! the bits land in the caller's byte buffer in the controller's page order, ready to be sent
//! as they are (one write of `width × height / 8` bytes after the controller's address window
//! is set, in its horizontal addressing mode).
//!
//! Why pages and not only [`flush`](super::flush()): `flush` with a `Lut<BinaryColor>` already
//! drives any `DrawTarget<Color = BinaryColor>`, but a driver's buffered mode keeps a second
//! copy of the picture (1 KB for 128 × 64) and sets it pixel by pixel. Packed here, the bytes
//! are built eight rows at a time from the framebuffer's rows and go to the bus without that
//! copy.
//!
//! Numeric contract and layout: a page is 8 rows. For a buffer holding rows `top..top +
//! height`, `top` and `height` are multiples of 8 ([`BufferError::NotWholePages`] otherwise:
//! the controller cannot write part of a page, and a packed page with invented rows would send
//! a wrong picture); the output holds [`page_bytes`]`(width, height)` bytes (fewer is
//! [`BufferError::BufferTooSmall`], naming both sizes; nothing is written then). Pixel
//! `(x, y)` is bit `(y − top) mod 8` (least significant bit the top row) of byte
//! `⌊(y − top) / 8⌋ · width + x`; a set bit is a pixel whose index the table maps to
//! `BinaryColor::On`. Sizes are `u16`, so every index fits `usize`.

use super::{BufferError, Framebuffer, Lut};
use embedded_graphics_core::pixelcolor::BinaryColor;

/// Rows in a page.
const PAGE_ROWS: u16 = 8;

/// The bytes of a `width × height` picture (or band) in pages: `width · ⌈height / 8⌉` (a
/// 128 × 64 SSD1306: 1,024 bytes).
pub const fn page_bytes(width: u16, height: u16) -> usize {
    width as usize * height.div_ceil(PAGE_ROWS) as usize
}

/// Packs `frame` into `pages` in the SSD1306's page layout (module doc), each index through
/// the on/off table `lut`; returns the bytes written, [`page_bytes`]`(width, height)`. The
/// bytes past them are untouched. A band is packed as the pages of its rows: send them to
/// pages `frame.top() / 8` onward.
///
/// ```
/// use embedded_graphics_core::pixelcolor::BinaryColor;
/// use zscan::prelude::*;
///
/// let mut pixels = [0u8; 16 * 8];
/// let mut frame = Framebuffer::new(&mut pixels, 16, 8)?;
/// frame.set_pixel(3, 0, 255); // top row of the page
/// frame.set_pixel(3, 7, 200); // bottom row
/// frame.set_pixel(4, 2, 90); // below the threshold: off
/// static ON_OFF: Lut<BinaryColor> = Lut::<BinaryColor>::threshold(128); // 128..=255 on
/// let mut bytes = [0u8; page_bytes(16, 8)]; // 16 bytes, one per column
/// let n = pack_pages(&frame, &ON_OFF, &mut bytes)?;
/// assert_eq!((n, bytes[3], bytes[4]), (16, 0b1000_0001, 0));
/// # Ok::<(), zscan::Error>(())
/// ```
///
/// Errors: [`BufferError::NotWholePages`] when the frame's first row or height is not a
/// multiple of 8, [`BufferError::BufferTooSmall`] (bytes needed and given) when `pages` is
/// shorter than [`page_bytes`].
pub fn pack_pages(
    frame: &Framebuffer<'_>,
    lut: &Lut<BinaryColor>,
    pages: &mut [u8],
) -> Result<usize, BufferError> {
    let (width, height, top) = (frame.width(), frame.height(), frame.top());
    if top % PAGE_ROWS as i32 != 0 || height % PAGE_ROWS != 0 {
        return Err(BufferError::NotWholePages { top, height });
    }
    let needed = page_bytes(width, height);
    let len = pages.len();
    let out = pages
        .get_mut(..needed)
        .ok_or(BufferError::BufferTooSmall { needed, len })?;
    // One page (8 rows) after the other: its bytes cleared, then each row's bits or-ed in.
    let mut rows = frame.rows();
    for page in out.chunks_exact_mut(width as usize) {
        page.fill(0);
        for (bit, (_, row)) in (&mut rows).take(PAGE_ROWS as usize).enumerate() {
            for (byte, &index) in page.iter_mut().zip(row) {
                *byte |= (lut.get(index).is_on() as u8) << bit;
            }
        }
    }
    Ok(needed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::XorShift;

    /// Bit `(x, y)` of a packed buffer, by the layout's definition (module doc).
    fn bit(pages: &[u8], width: usize, top: i32, x: usize, y: i32) -> bool {
        let r = (y - top) as usize;
        pages[r / 8 * width + x] >> (r % 8) & 1 == 1
    }

    /// Random frames, bands and strides against the layout's definition pixel by pixel, each
    /// index through a table built entry by entry (a random on/off per index); the bytes past
    /// the packed ones stay as they were.
    #[test]
    fn packed_bits_are_the_pixels_through_the_table() {
        let mut rng = XorShift::new(0x0051_3060);
        for case in 0..200 {
            let width = rng.range(1, 40) as u16;
            let height = 8 * rng.range(1, 5) as u16;
            let stride = width as usize + rng.below(3) as usize;
            let top = 8 * rng.range(0, 6) as u16;
            let mut on = [false; 256];
            for o in on.iter_mut() {
                *o = rng.below(2) == 1;
            }
            let mut lut = Lut::filled(BinaryColor::Off);
            for (i, &o) in on.iter().enumerate() {
                if o {
                    lut.set(i as u8, BinaryColor::On);
                }
            }
            let mut pixels = [0u8; 42 * 40];
            for p in pixels.iter_mut() {
                *p = rng.below(256) as u8;
            }
            let copy = pixels;
            let frame = if case % 2 == 1 {
                // A band (packed rows) of rows `top..top + height`.
                Framebuffer::band(&mut pixels, width, height, top).unwrap()
            } else {
                Framebuffer::with_stride(&mut pixels, width, height, stride).unwrap()
            };
            let (top, stride) = (frame.top(), frame.stride());
            let mut out = [0xA5u8; 40 * 5 + 7];
            let n = pack_pages(&frame, &lut, &mut out).unwrap();
            assert_eq!(n, width as usize * height as usize / 8, "case {case}");
            for y in top..top + height as i32 {
                for x in 0..width as usize {
                    let index = copy[(y - top) as usize * stride + x];
                    assert_eq!(
                        bit(&out, width as usize, top, x, y),
                        on[index as usize],
                        "case {case}: ({x}, {y}) index {index}"
                    );
                }
            }
            assert!(out[n..].iter().all(|&b| b == 0xA5), "case {case}");
        }
    }

    /// Whole pages, and a height that is not (the last page counted whole).
    #[test]
    fn page_bytes_counts_whole_pages() {
        assert_eq!(page_bytes(128, 64), 1024);
        assert_eq!(page_bytes(128, 32), 512);
        assert_eq!(page_bytes(5, 9), 10);
        assert_eq!(page_bytes(u16::MAX, u16::MAX), 65535 * 8192);
    }

    /// The threshold table: index `i` on exactly when `i ≥ first_on`.
    #[test]
    fn threshold_turns_on_the_indices_from_its_level() {
        for first_on in [0u8, 1, 127, 128, 255] {
            let lut = Lut::<BinaryColor>::threshold(first_on);
            for i in 0..=255u8 {
                assert_eq!(lut.get(i).is_on(), i >= first_on, "{first_on} {i}");
            }
        }
    }

    /// A buffer one byte short is refused with both sizes, and left untouched.
    #[test]
    fn short_buffer_is_refused_with_its_sizes() {
        let mut pixels = [255u8; 128 * 16];
        let frame = Framebuffer::new(&mut pixels, 128, 16).unwrap();
        let lut = Lut::<BinaryColor>::threshold(1);
        let mut out = [7u8; 255];
        assert_eq!(
            pack_pages(&frame, &lut, &mut out),
            Err(BufferError::BufferTooSmall {
                needed: 256,
                len: 255
            })
        );
        assert!(out.iter().all(|&b| b == 7));
        let mut out = [7u8; 256];
        assert_eq!(pack_pages(&frame, &lut, &mut out), Ok(256));
        assert!(out.iter().all(|&b| b == 0xFF));
    }

    /// A band that does not start on a page or hold whole pages is refused, naming both.
    #[test]
    fn partial_pages_are_refused() {
        let lut = Lut::<BinaryColor>::threshold(1);
        let mut out = [0u8; 1024];
        for (height, top) in [(8u16, 4u16), (12, 0), (7, 8), (16, 1)] {
            let mut pixels = [0u8; 16 * 16];
            let frame = Framebuffer::band(&mut pixels, 16, height, top).unwrap();
            assert_eq!(
                pack_pages(&frame, &lut, &mut out),
                Err(BufferError::NotWholePages {
                    top: top as i32,
                    height
                }),
                "{height} rows from {top}"
            );
        }
        assert!(out.iter().all(|&b| b == 0));
    }
}
