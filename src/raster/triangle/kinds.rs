//! The span kinds: what one span of a triangle writes, chosen once per triangle.
//!
//! Role in the pipeline: between the loop over a triangle's spans (`spans`) and the per-pixel
//! loop (`span`). A kind receives a span's exact interpolants at its start (attribute 0 the
//! depth) and runs the one per-pixel loop with its shading: flat colour over the depth plane
//! ([`FlatKind`]), exact Gouraud ([`ExactKind`]), fast Gouraud ([`FastKind`]), depth only
//! ([`DepthOnlyKind`], the shadow map's pass 1), and Phong's seven attributes lit at every
//! pixel ([`PhongKind`], the lighting evaluation of `lighting::phong`).
//!
//! Numeric contract: luminance `0..=255` at every pixel (saturated at the vertices), depth
//! the projection's 32-bit normalised depth; Phong's attributes as `lighting::phong` states.

use super::dither::Bayer4;
use super::draw::PhongContext;
use super::interpolants::{Constant, Interpolant, SpanStarts};
use super::span::{
    depth_only_span, depth_span, Gouraud, InRange, Quantizer, Shading, SpanTest, WrittenCount,
};
use crate::lighting::phong;
use crate::lighting::{Illumination, Material};

/// What one span of a triangle writes, given its `N` exact interpolants at the span start:
/// chosen once per triangle, so the span loop holds one kind only. The kinds: constant depth
/// and colour (no plane: [`TriangleSpans::constant`]), [`FlatKind`], [`ExactKind`],
/// [`FastKind`], [`DepthOnlyKind`] and [`PhongKind`].
pub(crate) trait SpanKind<const N: usize> {
    /// Writes the span (`colours`: its pixels, `depths`: their test, [`SpanTest`]) starting at
    /// pixel `(x, y)`; `attrs[0]` is the depth. Returns the pixels written (0 when `count` does not count them).
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<N>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: G,
        attrs: [I; N],
        starts: &St,
        at: (i32, i32),
        count: C,
    ) -> u32;
}

/// Flat colour over the exact depth plane (one attribute).
pub(super) struct FlatKind<QF> {
    pub(super) luminance: Constant,
    pub(super) quantizer_at: QF,
}

impl<Q: Quantizer, QF: Fn(i32, i32) -> Q> SpanKind<1> for FlatKind<QF> {
    #[inline(always)]
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<1>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: G,
        [z]: [I; 1],
        _: &St,
        (x, y): (i32, i32),
        count: C,
    ) -> u32 {
        let shading = Gouraud {
            luminance: self.luminance,
            quantizer: (self.quantizer_at)(x, y),
        };
        depth_span(colours, depths, z, shading, count)
    }
}

/// Exact Gouraud: depth and luminance planes.
pub(super) struct ExactKind<QF>(pub(super) QF);

impl<Q: Quantizer, QF: Fn(i32, i32) -> Q> SpanKind<2> for ExactKind<QF> {
    #[inline(always)]
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<2>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: G,
        [z, luminance]: [I; 2],
        _: &St,
        (x, y): (i32, i32),
        count: C,
    ) -> u32 {
        let shading = InRange {
            luminance,
            quantizer: (self.0)(x, y),
        };
        depth_span(colours, depths, z, shading, count)
    }
}

/// Fast Gouraud: the exact depth, the luminance as a 16.16 [`Dda`](super::interpolants::Dda)
/// (its start costs a division: only this kind computes it).
pub(super) struct FastKind<QF>(pub(super) QF);

impl<Q: Quantizer, QF: Fn(i32, i32) -> Q> SpanKind<2> for FastKind<QF> {
    #[inline(always)]
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<2>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: G,
        [z, _]: [I; 2],
        starts: &St,
        (x, y): (i32, i32),
        count: C,
    ) -> u32 {
        // The 16.16 value starts within 2^-16 + 1/2 above the exact one and its truncated
        // increment only lowers it: it stays in 0..=255 with the vertex values.
        let shading = InRange {
            luminance: starts.dda_at(1, x, y),
            quantizer: (self.0)(x, y),
        };
        depth_span(colours, depths, z, shading, count)
    }
}

/// Depth only: the exact depth plane (one attribute), the nearer depth stored, no colour
/// ([`depth_only_span`]). Drawn into a [`DepthTarget`], whose colour slices are empty.
pub(super) struct DepthOnlyKind;

impl SpanKind<1> for DepthOnlyKind {
    #[inline(always)]
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<1>, C: WrittenCount>(
        &self,
        _: &mut [u8],
        depths: G,
        [z]: [I; 1],
        _: &St,
        _: (i32, i32),
        count: C,
    ) -> u32 {
        depth_only_span(depths, z, count)
    }
}

/// Per-pixel Phong lighting along a span: the interpolated normal and position, lit on demand.
#[derive(Debug, Clone, Copy)]
pub struct PhongShading<'a, I: Interpolant, Q: Quantizer> {
    /// Normal x, y, z (offset Q15), position x, y, z (offset I16F16).
    pub attrs: [I; 6],
    /// Lights and material.
    pub illumination: &'a Illumination,
    /// The material.
    pub material: Material,
    /// Intensity → index at the current pixel.
    pub quantizer: Q,
}

impl<I: Interpolant, Q: Quantizer> PhongShading<'_, I, Q> {
    /// The intensity `0..=255` at the current pixel.
    #[inline]
    pub fn intensity(&self) -> u8 {
        let a = self.attrs.map(|a| a.value());
        phong::intensity(self.illumination, &self.material, a)
    }
}

impl<I: Interpolant, Q: Quantizer> Shading for PhongShading<'_, I, Q> {
    #[inline]
    fn index(&self) -> u8 {
        self.quantizer.index(self.intensity() as u32)
    }

    #[inline(always)]
    fn step(&mut self) {
        for a in self.attrs.iter_mut() {
            a.step();
        }
        self.quantizer.step();
    }
}

/// Phong's span kind: depth, and the normal and position lit at every pixel (7 exact
/// attributes), through the ramp or dithered.
pub(super) struct PhongKind<'c, 'a>(pub(super) &'c PhongContext<'a>);

impl SpanKind<7> for PhongKind<'_, '_> {
    #[inline(always)]
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<7>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: G,
        [z, attrs @ ..]: [I; 7],
        _: &St,
        (x, y): (i32, i32),
        count: C,
    ) -> u32 {
        let ctx = self.0;
        if ctx.dither {
            let sh = PhongShading {
                attrs,
                illumination: ctx.illumination,
                material: ctx.material,
                quantizer: Bayer4::at(ctx.ramp, x, y),
            };
            depth_span(colours, depths, z, sh, count)
        } else {
            let sh = PhongShading {
                attrs,
                illumination: ctx.illumination,
                material: ctx.material,
                quantizer: ctx.ramp,
            };
            depth_span(colours, depths, z, sh, count)
        }
    }
}
