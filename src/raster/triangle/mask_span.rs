//! The reverse painter's per-pixel test: a span's bits of the mask of painted pixels, plugged
//! into the one span loop in place of the depth test.
//!
//! Role in the pipeline: a [`SpanTest`] (`span`) and a [`SpanTarget`] (`slices`) over a
//! [`PaintedMask`]: [`MaskTargets`] hands each span its pixels of the frame and its bits of the
//! mask ([`MaskSpan`]); a pixel passes when its bit is clear (course ch. 3, algorithm 3.2: "si
//! le pixel n'a pas encore été peint"), and passing sets it. The depth is not tested: the test's
//! depth type is [`NoDepth`], whose one value makes every triangle's depth constant, so the
//! writers set up no depth plane (as for back faces alone). Everything else (the fill, the
//! planes, the shading, the stores) is the z-buffer's own code.
//!
//! Numeric contract: the mask's layout (`output/mask.rs`): pixel `i = (y − top) · width + x`
//! is bit `i mod 32` of word `⌊i / 32⌋`. A span's words are one checked `get` (a span outside
//! the mask is skipped, never a panic); the words are `Cell`s, so the bits of one word are
//! tested and set one pixel after another without `unsafe`.

use core::cell::Cell;

use super::slices::{RasterTarget, SpanTarget};
use super::span::{PixelTest, SpanTest, WrittenCount};
use crate::output::{Framebuffer, NoDepth, PaintedMask};
use crate::raster::{Span, Window};

/// The frame's pixels and the mask's bits, sliced per span ([`SpanTarget`]), like
/// [`Targets`](super::slices::Targets) for a depth buffer.
#[derive(Debug)]
pub(crate) struct MaskTargets<'t> {
    colours: &'t mut [u8],
    colour_stride: usize,
    colour_top: i32,
    words: &'t [Cell<u32>],
    width: usize,
    top: i32,
}

impl<'t, C: WrittenCount> RasterTarget<'t, NoDepth, C, MaskTargets<'t>> {
    /// Borrows `frame` and `mask` for drawing, counting written pixels as `count` says: the
    /// pixels both hold.
    pub(crate) fn masked(
        frame: &'t mut Framebuffer<'_>,
        mask: &'t mut PaintedMask<'_>,
        count: C,
    ) -> Self {
        let window = frame.window().intersect(&Window::new(
            0,
            mask.top(),
            mask.width() as i32,
            mask.top() + mask.height() as i32,
        ));
        let (width, top) = (mask.width() as usize, mask.top());
        let targets = MaskTargets {
            colour_stride: frame.stride(),
            colour_top: frame.top(),
            colours: frame.pixels_mut(),
            words: Cell::from_mut(mask.words_mut()).as_slice_of_cells(),
            width,
            top,
        };
        RasterTarget::over(window, targets, count)
    }
}

impl SpanTarget for MaskTargets<'_> {
    type Depth = NoDepth;
    type Test<'s>
        = MaskSpan<'s>
    where
        Self: 's;

    #[inline(always)]
    fn span(&mut self, s: &Span) -> Option<(&mut [u8], MaskSpan<'_>)> {
        let len = s.x1.wrapping_sub(s.x0) as usize;
        let row = s.y.wrapping_sub(self.colour_top) as usize;
        let c = row
            .wrapping_mul(self.colour_stride)
            .wrapping_add(s.x0 as usize);
        let first = (s.y.wrapping_sub(self.top) as usize)
            .wrapping_mul(self.width)
            .wrapping_add(s.x0 as usize);
        let words = self
            .words
            .get(first / 32..first.wrapping_add(len).div_ceil(32))?;
        Some((
            self.colours.get_mut(c..c.wrapping_add(len))?,
            MaskSpan {
                words,
                bit: (first % 32) as u32,
                len,
            },
        ))
    }
}

/// One span's bits of the mask: `len` bits from bit `bit` of the first of `words`.
#[derive(Debug)]
pub(crate) struct MaskSpan<'s> {
    words: &'s [Cell<u32>],
    bit: u32,
    len: usize,
}

/// One pixel's bit: passes when clear, and is set by the test.
#[derive(Debug)]
pub(crate) struct MaskPixel<'s> {
    word: &'s Cell<u32>,
    bit: u32,
}

impl PixelTest<NoDepth> for MaskPixel<'_> {
    #[inline(always)]
    fn pass(self, _: NoDepth) -> bool {
        let w = self.word.get();
        self.word.set(w | self.bit);
        w & self.bit == 0
    }

    /// A blended surface is never drawn by the reverse painter (it refuses blended objects):
    /// the pixel passes while unpainted, and stays unpainted.
    #[inline(always)]
    fn passes(self, _: NoDepth) -> bool {
        self.word.get() & self.bit == 0
    }
}

/// The bits of a [`MaskSpan`], left to right.
#[derive(Debug)]
pub(crate) struct MaskBits<'s> {
    words: core::slice::Iter<'s, Cell<u32>>,
    word: Option<&'s Cell<u32>>,
    bit: u32,
    left: usize,
}

impl<'s> Iterator for MaskBits<'s> {
    type Item = MaskPixel<'s>;

    #[inline(always)]
    fn next(&mut self) -> Option<MaskPixel<'s>> {
        if self.left == 0 {
            return None;
        }
        if self.bit == 0 {
            self.word = self.words.next();
            self.bit = 1;
        }
        let pixel = MaskPixel {
            word: self.word?,
            bit: self.bit,
        };
        self.bit <<= 1; // past bit 31: 0, the next word
        self.left -= 1;
        Some(pixel)
    }
}

impl<'s> SpanTest for MaskSpan<'s> {
    type Depth = NoDepth;
    type Pixel = MaskPixel<'s>;

    #[inline(always)]
    fn pixels(self) -> impl Iterator<Item = MaskPixel<'s>> {
        let mut words = self.words.iter();
        let word = words.next();
        MaskBits {
            words,
            word,
            bit: 1 << self.bit,
            left: self.len,
        }
    }

    /// A word at a time: the span's bits of each word tested and set at once, the unpainted
    /// pixels filled (a word with none unpainted writes nothing).
    #[inline(always)]
    fn constant<C: WrittenCount>(self, colours: &mut [u8], _: NoDepth, index: u8) -> u32 {
        let (mut written, mut x, mut bit) = (0u32, 0usize, self.bit);
        for word in self.words {
            let n = (32 - bit as usize).min(self.len.saturating_sub(x));
            if n == 0 {
                break;
            }
            // `n` bits from `bit`: 1 ≤ n ≤ 32 − bit.
            let range = (u32::MAX >> (32 - n)) << bit;
            let w = word.get();
            word.set(w | range);
            let mut free = !w & range;
            if free == range {
                if let Some(run) = colours.get_mut(x..x + n) {
                    run.fill(index);
                }
                written += n as u32 * C::COUNTS as u32;
            } else {
                while free != 0 {
                    let at = x + (free.trailing_zeros() - bit) as usize;
                    if let Some(c) = colours.get_mut(at) {
                        *c = index;
                    }
                    written += C::COUNTS as u32;
                    free &= free - 1;
                }
            }
            x += n;
            bit = 0;
        }
        written
    }
}
