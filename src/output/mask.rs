//! The reverse painter's mask of painted pixels: one bit per pixel, in caller memory.
//!
//! Role in the pipeline: beside the framebuffer, in place of a depth buffer, for the reverse
//! painter (course ch. 3, algorithm 3.2, "algorithme du peintre inversé": the polygons sorted
//! front to back, a pixel already painted is never painted again;
//! [`Visibility::ReversePainter`](crate::visibility::Visibility::ReversePainter)). A set bit
//! is a pixel painted this frame; the first surface to reach a pixel keeps it.
//!
//! Numeric contract: the buffer is `⌈width · height / 32⌉` `u32` words
//! ([`mask_words_needed`]): pixel `(x, y)` of a `width × height` mask whose first row is `top`
//! is bit `i mod 32` (least significant first) of word `⌊i / 32⌋`, `i = (y − top) · width + x`,
//! so a span's bits are consecutive. `width · height < 2^32`, so every index fits `usize` on
//! 32-bit targets; a shorter buffer is refused ([`BufferError::BufferTooSmall`], naming the
//! words given and needed), never cropped.

use super::{BufferError, Framebuffer};

/// The `u32` words a `width × height` mask needs: `⌈width · height / 32⌉` (a 320 × 240 frame:
/// 2,400 words, 9,600 bytes; a 16-bit depth buffer of the same frame is 153,600 bytes).
pub const fn mask_words_needed(width: u16, height: u16) -> usize {
    (width as usize * height as usize).div_ceil(32)
}

/// A mask of painted pixels over a caller's `u32` words (module doc): a whole frame, or a
/// band of rows like [`Framebuffer::band`].
///
/// ```
/// use zscan::output::{mask_words_needed, PaintedMask};
///
/// let mut words = [0u32; mask_words_needed(40, 30)]; // 38 words for 1,200 pixels
/// let mut mask = PaintedMask::new(&mut words, 40, 30)?;
/// mask.clear();
/// assert_eq!(mask.painted(39, 29), Some(false));
/// assert_eq!(mask.painted(40, 0), None);
/// # Ok::<(), zscan::output::BufferError>(())
/// ```
#[derive(Debug)]
pub struct PaintedMask<'a> {
    words: &'a mut [u32],
    width: u16,
    height: u16,
    top: i32,
}

impl<'a> PaintedMask<'a> {
    /// Wraps `words` as the mask of a `width × height` frame; fewer than
    /// [`mask_words_needed`] words is [`BufferError::BufferTooSmall`] (`needed`, `len`: words).
    pub fn new(words: &'a mut [u32], width: u16, height: u16) -> Result<Self, BufferError> {
        Self::band(words, width, height, 0)
    }

    /// Wraps `words` as the mask of the band of rows `top..top + height`.
    pub fn band(
        words: &'a mut [u32],
        width: u16,
        height: u16,
        top: u16,
    ) -> Result<Self, BufferError> {
        if width == 0 || height == 0 {
            return Err(BufferError::ZeroSize);
        }
        let needed = mask_words_needed(width, height);
        if words.len() < needed {
            return Err(BufferError::BufferTooSmall {
                needed,
                len: words.len(),
            });
        }
        Ok(PaintedMask {
            words: &mut words[..needed],
            width,
            height,
            top: top as i32,
        })
    }

    /// The mask of `frame`'s rows (its width and height, its first row) over `words`.
    pub fn for_frame(words: &'a mut [u32], frame: &Framebuffer<'_>) -> Result<Self, BufferError> {
        let top = u16::try_from(frame.top()).map_err(|_| BufferError::SizeMismatch)?;
        Self::band(words, frame.width(), frame.height(), top)
    }

    /// Width in pixels.
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

    /// Marks every pixel unpainted.
    pub fn clear(&mut self) {
        self.words.fill(0);
    }

    /// Whether pixel `(x, y)` (absolute row) is painted, or `None` outside the mask.
    pub fn painted(&self, x: i32, y: i32) -> Option<bool> {
        let r = y.checked_sub(self.top)?;
        if x < 0 || x >= self.width as i32 || r < 0 || r >= self.height as i32 {
            return None;
        }
        let i = r as usize * self.width as usize + x as usize;
        Some(self.words.get(i / 32)? >> (i % 32) & 1 == 1)
    }

    /// The pixels painted.
    pub fn painted_count(&self) -> u32 {
        self.words.iter().map(|w| w.count_ones()).sum()
    }

    /// The words, for the triangle writers (module doc's layout).
    pub(crate) fn words_mut(&mut self) -> &mut [u32] {
        self.words
    }
}
