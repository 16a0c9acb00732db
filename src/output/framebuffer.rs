//! The 8-bit indexed framebuffer over a caller-provided `&mut [u8]`.
//!
//! One byte per pixel, a palette index resolved by a [`Lut`](super::Lut) at flush time. Rows are
//! exposed as slices ([`Framebuffer::row_mut`]) so raster loops write whole spans with
//! `slice::fill`, which compiles to a `memset`-like loop.
//!
//! A framebuffer may be a *band*: `height` rows starting at absolute row `top` of a taller
//! picture. All coordinates taken and returned here are absolute picture coordinates.

use super::{check_layout, BufferError, Window};

/// An 8-bit indexed framebuffer (possibly a band of a taller picture).
///
/// ```
/// use zscan::output::Framebuffer;
///
/// let mut pixels = [0u8; 8 * 4]; // your memory: one palette index per pixel
/// let mut frame = Framebuffer::new(&mut pixels, 8, 4)?;
/// frame.clear(3);
/// frame.set_pixel(2, 1, 200);
/// assert_eq!((frame.pixel(2, 1), frame.pixel(0, 0)), (Some(200), Some(3)));
/// assert_eq!(frame.pixel(8, 0), None); // outside: no pixel, no panic
///
/// // Rows 16..20 of a taller picture: coordinates stay absolute.
/// let mut band_pixels = [0u8; 8 * 4];
/// let mut band = Framebuffer::band(&mut band_pixels, 8, 4, 16)?;
/// band.set_pixel(0, 17, 9);
/// assert_eq!(band.pixel(0, 17), Some(9));
/// assert_eq!(band.pixel(0, 1), None);
/// # Ok::<(), zscan::output::BufferError>(())
/// ```
#[derive(Debug)]
pub struct Framebuffer<'a> {
    pixels: &'a mut [u8],
    width: u16,
    height: u16,
    stride: usize,
    top: i32,
    /// Made by [`band`](Self::band): some rows of a taller picture, by design.
    band: bool,
}

impl<'a> Framebuffer<'a> {
    /// Wraps `pixels` as a `width × height` frame with rows packed (`stride == width`).
    ///
    /// Errors: [`BufferError::ZeroSize`] for a zero dimension, [`BufferError::BufferTooSmall`]
    /// when `pixels` is shorter than `width * height`. A longer slice is accepted (the rest is
    /// left untouched).
    pub fn new(pixels: &'a mut [u8], width: u16, height: u16) -> Result<Self, BufferError> {
        Self::with_stride(pixels, width, height, width as usize)
    }

    /// Wraps `pixels` with an explicit row stride (elements between the starts of two rows).
    pub fn with_stride(
        pixels: &'a mut [u8],
        width: u16,
        height: u16,
        stride: usize,
    ) -> Result<Self, BufferError> {
        check_layout(pixels.len(), width, height, stride)?;
        Ok(Framebuffer {
            pixels,
            width,
            height,
            stride,
            top: 0,
            band: false,
        })
    }

    /// Wraps `pixels` as the band of rows `top..top + height` of a `width`-wide picture.
    pub fn band(
        pixels: &'a mut [u8],
        width: u16,
        height: u16,
        top: u16,
    ) -> Result<Self, BufferError> {
        let mut fb = Self::new(pixels, width, height)?;
        fb.top = top as i32;
        fb.band = true;
        Ok(fb)
    }

    /// Width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Number of rows held.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// Absolute row of the first row held (0 unless this is a band).
    pub fn top(&self) -> i32 {
        self.top
    }

    /// Made by [`band`](Self::band) (some rows of a taller picture), not by
    /// [`new`](Self::new) or [`with_stride`](Self::with_stride) (a whole picture, which the
    /// renderer requires to hold its camera's whole viewport).
    pub(crate) fn is_band(&self) -> bool {
        self.band
    }

    /// Elements between the starts of two rows.
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The rectangle of absolute pixel coordinates this buffer holds, half-open.
    pub fn window(&self) -> Window {
        Window::new(
            0,
            self.top,
            self.width as i32,
            self.top + self.height as i32,
        )
    }

    /// The whole buffer (rows `stride` apart), for loops that walk it by offsets.
    #[inline(always)]
    pub fn pixels_mut(&mut self) -> &mut [u8] {
        self.pixels
    }

    /// Row `y` (absolute) as a slice of `width` indices, or `None` outside the buffer.
    pub fn row(&self, y: i32) -> Option<&[u8]> {
        let start = self.row_start(y)?;
        Some(&self.pixels[start..start + self.width as usize])
    }

    /// Row `y` (absolute) as a mutable slice of `width` indices, or `None` outside the buffer.
    #[inline]
    pub fn row_mut(&mut self, y: i32) -> Option<&mut [u8]> {
        let start = self.row_start(y)?;
        let w = self.width as usize;
        self.pixels.get_mut(start..start + w)
    }

    /// Pixels `x0..x1` of row `y` (absolute), or `None` unless `x0 ≤ x1 ≤ width` and the row is
    /// held. One range check: what the raster's span loops use.
    #[inline(always)]
    pub fn span_mut(&mut self, y: i32, x0: usize, x1: usize) -> Option<&mut [u8]> {
        let r = y.wrapping_sub(self.top) as u32; // rows above `top` wrap to huge values
        if r >= self.height as u32 || x1 > self.width as usize || x0 > x1 {
            return None;
        }
        let start = r as usize * self.stride;
        self.pixels.get_mut(start + x0..start + x1)
    }

    #[inline]
    fn row_start(&self, y: i32) -> Option<usize> {
        let r = y.checked_sub(self.top)?;
        if r < 0 || r >= self.height as i32 {
            return None;
        }
        Some(r as usize * self.stride)
    }

    /// The index at `(x, y)`, or `None` outside the buffer.
    pub fn pixel(&self, x: i32, y: i32) -> Option<u8> {
        if x < 0 || x >= self.width as i32 {
            return None;
        }
        self.row(y).map(|r| r[x as usize])
    }

    /// Sets the index at `(x, y)`; points outside the buffer are ignored (documented, tested).
    #[inline]
    pub fn set_pixel(&mut self, x: i32, y: i32, index: u8) {
        if x < 0 || x >= self.width as i32 {
            return;
        }
        if let Some(r) = self.row_mut(y) {
            r[x as usize] = index;
        }
    }

    /// Fills every pixel with `index` (bytes between rows, when `stride > width`, are left
    /// untouched). Packed rows are cleared as one run (word stores, 128 bytes per loop
    /// iteration, at any alignment; `memset` on the Cortex-M0: `output/mod.rs`).
    pub fn clear(&mut self, index: u8) {
        let (w, h) = (self.width as usize, self.height as usize);
        if self.stride == w {
            // check_layout: the slice holds at least width·height bytes.
            super::fill_u8(&mut self.pixels[..w * h], index);
        } else {
            for row in self.pixels.chunks_mut(self.stride).take(h) {
                super::fill_u8(&mut row[..w], index);
            }
        }
    }

    /// Rows of the buffer in order, each `width` long, paired with their absolute row number.
    pub fn rows(&self) -> impl Iterator<Item = (i32, &[u8])> + '_ {
        (0..self.height as usize).map(move |r| {
            let start = r * self.stride;
            (
                self.top + r as i32,
                &self.pixels[start..start + self.width as usize],
            )
        })
    }
}
