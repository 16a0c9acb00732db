//! The span loop: the per-pixel work of every depth-buffered writer, one span at a time.
//!
//! Role in the pipeline: the innermost step of the raster stage. [`depth_span`] walks one
//! span's pixels with a depth interpolant and a [`Shading`] (the palette index at each pixel):
//! the pixel's test, index, stores. The test is the seam a visibility method plugs into
//! ([`SpanTest`]): the depth test (a span of depth samples: strict, nearer wins, see
//! [`DepthValue`]; the depth stored), or the reverse painter's mask (`mask_span`: a pixel
//! passes the first time, its bit set). The depth test through the seam inlines to the loop
//! it was (every bench case's checksum unchanged; `frame_bunny` 2,443,804 host instructions). A [`Quantizer`]
//! maps luminance to an index ([`LuminanceRamp`], or a dithered ramp), and [`WrittenCount`]
//! says at compile time whether written pixels are counted. `Targets` (`slices`) hands the
//! writers each span's pixels of the frame and depth buffer as two slices.
//!
//! The depth-only span (`depth_only_span`, the shadow map's pass 1) is the same loop, its core
//! `span_core`, with no colour: a `ColourPixel` that stores nothing and a `Shading` that is
//! never read. `DepthTargets` (`slices`) hands it each span's depth samples alone (a shadow map's, with
//! no framebuffer); both kinds of target are a `SpanTarget`, what the one triangle writer
//! (`spans`) slices spans from.
//!
//! Numeric contract: luminance `0..=255` (the writers saturate vertex values at 255, so the
//! interpolants stay in range and the loops map without a test); depth values are the
//! projection's 32-bit normalised depth, stored through [`DepthValue::from_depth32`]. Span
//! slices are checked `get_mut`s: a span outside the buffers is skipped, never a panic.

use super::interpolants::Interpolant;
use crate::arith::WIDE_REGISTERS;
use crate::output::DepthValue;

/// Luminance (`0..=255`) to a ramp of `levels` palette entries starting at `first`:
/// `index = first + ⌊lum · levels / 256⌋`. With `first = 0, levels = 256` the index is the
/// luminance itself (a grey LUT).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LuminanceRamp {
    /// First palette index of the ramp.
    pub first: u8,
    /// Entries in the ramp (1..=256).
    pub levels: u16,
}

impl LuminanceRamp {
    /// The ramp that maps luminance `l` to index `l`.
    pub const GREY: LuminanceRamp = LuminanceRamp {
        first: 0,
        levels: 256,
    };

    /// The palette index of luminance `lum`.
    #[inline(always)]
    pub fn index(&self, lum: u32) -> u8 {
        let l = lum.min(255);
        self.first
            .wrapping_add(((l * self.levels as u32) >> 8) as u8)
    }
}

/// Per-pixel colour of a span: the palette index at the current pixel, stepped right.
pub trait Shading: Copy {
    /// True when the index does not change along a span ([`FlatIndex`], flat [`Gouraud`]).
    const IS_CONSTANT: bool = false;
    /// True when every pixel that passes the depth test is stored as it is: no screen-door
    /// mask, no blend ([`Quantizer::PLAIN`]).
    const PLAIN: bool = true;
    /// True when the stored index is blended with the pixel under it and the depth is not
    /// stored ([`Quantizer::BLENDS`]).
    const BLENDS: bool = false;
    /// The palette index at the current pixel.
    fn index(&self) -> u8;
    /// Whether the current pixel is covered ([`Quantizer::covers`]).
    #[inline(always)]
    fn covers(&self) -> bool {
        true
    }
    /// The index stored over `dst` ([`Quantizer::blend`]).
    #[inline(always)]
    fn blend(&self, src: u8, _dst: u8) -> u8 {
        src
    }
    /// Moves one pixel to the right.
    fn step(&mut self);
}

/// Luminance → palette index at the current pixel, stepping right: the plain
/// [`LuminanceRamp`] or a dithered one ([`Bayer4`](super::dither::Bayer4)).
pub trait Quantizer: Copy {
    /// True for the plain ramp: the mapping does not change along a span.
    const IS_CONSTANT: bool = false;
    /// The palette index of luminance `lum` (`0..=255`, larger saturates) at the current pixel.
    fn index(&self, lum: u32) -> u8;
    /// [`Quantizer::index`] of a luminance known to be in range (no saturation test).
    #[inline(always)]
    fn index_byte(&self, lum: u8) -> u8 {
        self.index(lum as u32)
    }
    /// `Some(first)` when the mapping is `first + lum` (mod 256) at every pixel, as a ramp of
    /// 256 levels: the triangle writers then interpolate `first + lum` itself and store it.
    #[inline(always)]
    fn offset(&self) -> Option<u8> {
        None
    }
    /// False for the transparency quantizers (`transparency`): a screen-door mask or a blend.
    const PLAIN: bool = true;
    /// True for a blend: the index stored is [`Quantizer::blend`] of it and the pixel under
    /// it, and the depth is tested but not stored.
    const BLENDS: bool = false;
    /// Whether the current pixel is covered (a screen-door mask); the span loop tests it
    /// before the depth test, and only where [`Quantizer::PLAIN`] is false.
    #[inline(always)]
    fn covers(&self) -> bool {
        true
    }
    /// The index stored over a pixel of index `dst` (where [`Quantizer::BLENDS`]).
    #[inline(always)]
    fn blend(&self, src: u8, _dst: u8) -> u8 {
        src
    }
    /// Moves one pixel right.
    fn step(&mut self);
}

impl Quantizer for LuminanceRamp {
    const IS_CONSTANT: bool = true;

    #[inline(always)]
    fn index(&self, lum: u32) -> u8 {
        LuminanceRamp::index(self, lum)
    }

    #[inline(always)]
    fn index_byte(&self, lum: u8) -> u8 {
        self.first
            .wrapping_add(((lum as u32 * self.levels as u32) >> 8) as u8)
    }

    #[inline(always)]
    fn offset(&self) -> Option<u8> {
        (self.levels == 256).then_some(self.first)
    }

    #[inline(always)]
    fn step(&mut self) {}
}

/// Gouraud shading: an interpolated luminance through a [`Quantizer`] (by default the plain
/// ramp). With a [`Constant`](super::interpolants::Constant) luminance it is flat shading, and with the plain ramp it is
/// constant along the span, which [`depth_span`] exploits.
#[derive(Debug, Clone, Copy)]
pub struct Gouraud<L: Interpolant, Q: Quantizer = LuminanceRamp> {
    /// The interpolated luminance.
    pub luminance: L,
    /// Its mapping to palette indices.
    pub quantizer: Q,
}

impl<L: Interpolant, Q: Quantizer> Shading for Gouraud<L, Q> {
    const IS_CONSTANT: bool = L::IS_CONSTANT && Q::IS_CONSTANT;
    const PLAIN: bool = Q::PLAIN;
    const BLENDS: bool = Q::BLENDS;

    #[inline(always)]
    fn covers(&self) -> bool {
        self.quantizer.covers()
    }

    #[inline(always)]
    fn blend(&self, src: u8, dst: u8) -> u8 {
        self.quantizer.blend(src, dst)
    }

    #[inline(always)]
    fn index(&self) -> u8 {
        self.quantizer.index(self.luminance.value())
    }

    #[inline(always)]
    fn step(&mut self) {
        self.luminance.step();
        self.quantizer.step();
    }
}

/// [`Gouraud`] for a luminance that stays in `0..=255` by construction (interpolated from
/// vertex values clamped to 255: every covered pixel's value lies between them), mapped
/// without the saturation test (measured: 3 instructions per written pixel on the Cortex-M4).
#[derive(Debug, Clone, Copy)]
pub(crate) struct InRange<L: Interpolant, Q: Quantizer> {
    /// The luminance, in `0..=255` at every pixel.
    pub(crate) luminance: L,
    /// Luminance → index.
    pub(crate) quantizer: Q,
}

impl<L: Interpolant, Q: Quantizer> Shading for InRange<L, Q> {
    const IS_CONSTANT: bool = L::IS_CONSTANT && Q::IS_CONSTANT;
    const PLAIN: bool = Q::PLAIN;
    const BLENDS: bool = Q::BLENDS;

    #[inline(always)]
    fn covers(&self) -> bool {
        self.quantizer.covers()
    }

    #[inline(always)]
    fn blend(&self, src: u8, dst: u8) -> u8 {
        self.quantizer.blend(src, dst)
    }

    #[inline(always)]
    fn index(&self) -> u8 {
        self.quantizer.index_byte(self.luminance.value() as u8)
    }

    #[inline(always)]
    fn step(&mut self) {
        self.luminance.step();
        self.quantizer.step();
    }
}

/// In-range luminance (`0..=255`, or an index already offset for [`Direct`]) through
/// `quantizer`.
#[inline(always)]
pub(crate) fn in_range<L: Interpolant, Q: Quantizer>(luminance: L, quantizer: Q) -> impl Shading {
    InRange {
        luminance,
        quantizer,
    }
}

/// The identity mapping, for luminances already offset to palette indices
/// ([`Quantizer::offset`]): the index is the value's low byte.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Direct;

impl Quantizer for Direct {
    const IS_CONSTANT: bool = true;

    #[inline(always)]
    fn index(&self, lum: u32) -> u8 {
        lum as u8
    }

    #[inline(always)]
    fn index_byte(&self, lum: u8) -> u8 {
        lum
    }

    #[inline(always)]
    fn step(&mut self) {}
}

/// Whether the span loops count the pixels they write: [`CountWritten`] (one add per written
/// pixel and a register in the loop) or [`SkipWritten`] (no counter: the written count is 0).
/// Measured on the Cortex-M4, the count costs the standard cube 6 %, the sphere 3 % and the
/// bunny 1.6 % of their frames. A compile-time switch, so that the loop without it has no
/// trace of it.
pub trait WrittenCount: Copy + Default {
    /// True when written pixels are counted.
    const COUNTS: bool;
}

/// Span loops count the pixels that pass the depth test ([`WrittenCount`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CountWritten;

impl WrittenCount for CountWritten {
    const COUNTS: bool = true;
}

/// Span loops do not count written pixels and report 0 ([`WrittenCount`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SkipWritten;

impl WrittenCount for SkipWritten {
    const COUNTS: bool = false;
}

/// The per-pixel test of a span and its record: what decides whether a pixel of a triangle is
/// written, and remembers that it was. The seam a visibility method plugs into the one span
/// loop ([`span_core`]): the depth test (a span of depth samples, `&mut [D]`: strict, nearer
/// wins, the depth stored) and the reverse painter's mask (`MaskSpan`, `mask_span.rs`: a pixel
/// passes once, the first time, and its bit is set). The loop, the shading and the stores are
/// the same for both.
pub(crate) trait SpanTest {
    /// The depth the span's interpolant is converted to ([`DepthValue::from_depth32`]); a
    /// test that ignores depths takes [`NoDepth`](crate::output::NoDepth), whose one value
    /// makes every triangle's depth constant (no depth plane).
    type Depth: DepthValue;
    /// One pixel's test.
    type Pixel: PixelTest<Self::Depth>;
    /// The span's pixels' tests, left to right.
    fn pixels(self) -> impl Iterator<Item = Self::Pixel>;
    /// The span at constant depth `d` and colour `index` into `colours` (the span's pixels):
    /// the pixels written, counted as `C` says.
    fn constant<C: WrittenCount>(self, colours: &mut [u8], d: Self::Depth, index: u8) -> u32;
}

/// One pixel's test of a [`SpanTest`]: passes (and records the pixel) or not.
pub(crate) trait PixelTest<D> {
    /// Whether a surface at depth `d` is written here; when it is, the test records it.
    fn pass(self, d: D) -> bool;
    /// Whether a surface at depth `d` would be written here, without recording it (a blended
    /// surface: drawn over what lies behind, leaving the depth as it was).
    fn passes(self, d: D) -> bool;
}

/// The depth test: strict, nearer wins, the nearer depth stored ([`DepthValue::nearer`]).
impl<D: DepthValue> PixelTest<D> for &mut D {
    #[inline(always)]
    fn pass(self, d: D) -> bool {
        if d.nearer(*self) {
            *self = d;
            true
        } else {
            false
        }
    }

    #[inline(always)]
    fn passes(self, d: D) -> bool {
        d.nearer(*self)
    }
}

/// A span of depth samples: the z-buffer's per-pixel test.
impl<'s, D: DepthValue> SpanTest for &'s mut [D] {
    type Depth = D;
    type Pixel = &'s mut D;

    #[inline(always)]
    fn pixels(self) -> impl Iterator<Item = &'s mut D> {
        self.iter_mut()
    }

    #[inline(always)]
    fn constant<C: WrittenCount>(self, colours: &mut [u8], d: D, index: u8) -> u32 {
        // A sample of no bits (`NoDepth`) has one value: the test is the same at every pixel
        // and nothing is stored, so the span is one fill, inline (out of line, the call cost
        // the back-face frames about 9 instructions a span on the host).
        if D::BITS == 0 {
            if !d.nearer(d) {
                return 0;
            }
            colours.fill(index);
            return colours.len() as u32 * C::COUNTS as u32;
        }
        constant_span::<D, C>(colours, self, d, index)
    }
}

/// Writes one span through its per-pixel test `tests` ([`SpanTest`]: the depth test, or the
/// reverse painter's mask): every pixel of `colours` (the span's pixels, as many as the
/// tests), with depth `z` and colour `shading` at the first pixel. Returns the number of
/// pixels written (that passed the test), counted as `C` says (0 when it does not count).
#[inline(always)]
pub fn depth_span<G: SpanTest, Z: Interpolant, Sh: Shading, C: WrittenCount>(
    colours: &mut [u8],
    tests: G,
    z: Z,
    shading: Sh,
    count: C,
) -> u32 {
    if Z::IS_CONSTANT && Sh::IS_CONSTANT && Sh::PLAIN {
        return tests.constant::<C>(colours, G::Depth::from_depth32(z.value()), shading.index());
    }
    span_core(colours.iter_mut(), tests, z, shading, count)
}

/// The depth-only span: every sample of `depths` (the span's samples) replaced by the depth
/// `z` steps to where it is nearer, no colour stored ([`span_core`] with [`NoColour`]): the
/// shadow map's pass 1. Returns the samples written, counted as `C` says.
#[inline(always)]
pub(crate) fn depth_only_span<G: SpanTest, Z: Interpolant, C: WrittenCount>(
    depths: G,
    z: Z,
    count: C,
) -> u32 {
    span_core(core::iter::repeat(()), depths, z, NoColour, count)
}

/// Where a pixel that passes the depth test stores its palette index: a frame's pixel
/// (`&mut u8`), or nowhere (`()`, the depth-only span).
pub(crate) trait ColourPixel {
    /// Stores `index` (or nothing).
    fn store(self, index: u8);
    /// Stores `blend(index under it)` (or nothing).
    fn store_over(self, blend: impl FnOnce(u8) -> u8);
}

impl ColourPixel for &mut u8 {
    #[inline(always)]
    fn store(self, index: u8) {
        *self = index;
    }

    #[inline(always)]
    fn store_over(self, blend: impl FnOnce(u8) -> u8) {
        *self = blend(*self);
    }
}

impl ColourPixel for () {
    #[inline(always)]
    fn store(self, _: u8) {}

    #[inline(always)]
    fn store_over(self, _: impl FnOnce(u8) -> u8) {}
}

/// The shading of a depth-only span: no colour (its index is never stored).
#[derive(Debug, Clone, Copy)]
pub(crate) struct NoColour;

impl Shading for NoColour {
    const IS_CONSTANT: bool = true;

    #[inline(always)]
    fn index(&self) -> u8 {
        0
    }

    #[inline(always)]
    fn step(&mut self) {}
}

/// The one per-pixel loop of [`depth_span`] and [`depth_only_span`]: each pixel of `colours`
/// (one [`ColourPixel`] per test, or an endless run of `()` for no colour) zipped with the
/// span's [`SpanTest`], with depth `z` and colour `shading` at the first pixel: the test, then
/// the index stored where it passes.
#[inline(always)]
fn span_core<G: SpanTest, Z: Interpolant, Sh: Shading, C: WrittenCount, P: ColourPixel>(
    colours: impl Iterator<Item = P>,
    tests: G,
    mut z: Z,
    mut shading: Sh,
    _: C,
) -> u32 {
    let mut written = 0u32;
    // A shading constant along the span (flat) is mapped to its index once.
    let constant_index = shading.index();
    for (c, test) in colours.zip(tests.pixels()) {
        let d = G::Depth::from_depth32(z.value());
        // The transparency seam (`transparency`), compiled out for plain shadings: a pixel
        // outside the screen-door mask is not drawn, and a blend tests the pixel without
        // recording it (`PixelTest::passes`).
        let drawn = (Sh::PLAIN || shading.covers())
            && if Sh::BLENDS {
                test.passes(d)
            } else {
                test.pass(d)
            };
        if drawn {
            let index = if Sh::IS_CONSTANT {
                constant_index
            } else {
                shading.index()
            };
            if Sh::BLENDS {
                c.store_over(|dst| shading.blend(index, dst));
            } else {
                c.store(index);
            }
            written += C::COUNTS as u32;
        }
        z.step();
        shading.step();
    }
    written
}

/// [`depth_span`] for a constant depth `d` and colour `index`: a branch-free select the
/// compiler vectorises. Out of line: inlined into a triangle writer, whose other span kinds
/// keep many values live, its loop lost registers to the surrounding code (measured: the
/// standard quad, whose two triangles are flat at constant depth, +1 instruction per pixel on
/// the Cortex-M4).
#[inline(never)]
fn constant_span<D: DepthValue, C: WrittenCount>(
    colours: &mut [u8],
    depths: &mut [D],
    d: D,
    index: u8,
) -> u32 {
    let mut written = 0u32;
    let select = |c: &mut u8, stored: &mut D| {
        let nearer = d.nearer(*stored);
        *stored = if nearer { d } else { *stored };
        *c = if nearer { index } else { *c };
        (nearer & C::COUNTS) as u32
    };
    // Blocks of 16 pixels: when the whole block is farther (the common case on a fresh
    // buffer), two block fills; otherwise the per-pixel select. On 64-bit hosts the
    // all-farther test has a fixed trip count and no early exit, so it compiles to a few vector
    // compares; 32-bit cores have no vectors and take the early-exit form (the fixed one
    // spilled the block to the stack on the Cortex-M4: +1.3 instructions per pixel).
    let mut cs = colours.chunks_exact_mut(16);
    let mut zs = depths.chunks_exact_mut(16);
    for (cb, zb) in (&mut cs).zip(&mut zs) {
        let all_farther = if WIDE_REGISTERS {
            zb.iter().fold(true, |all, s| all & d.nearer(*s))
        } else {
            zb.iter().all(|s| d.nearer(*s))
        };
        if all_farther {
            zb.fill(d);
            cb.fill(index);
            written += 16 * C::COUNTS as u32;
        } else {
            for (c, stored) in cb.iter_mut().zip(zb.iter_mut()) {
                written += select(c, stored);
            }
        }
    }
    for (c, stored) in cs.into_remainder().iter_mut().zip(zs.into_remainder()) {
        written += select(c, stored);
    }
    written
}
