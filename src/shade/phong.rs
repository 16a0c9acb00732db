//! Phong shading: normals (and observer-frame positions) interpolated across a triangle and
//! lit at every pixel (course chapter 4, §2.3) — the costly mode, which keeps specular
//! highlights that fall inside large faces.
//!
//! Role in the pipeline: an alternative to the Gouraud span shading of
//! [`span_writer`](super::span_writer). [`draw_triangle_phong`] sets up one
//! [`AttributePlane<7, S>`] (depth, the three normal components, the three position
//! components), and runs the generic [`depth_span`] with [`PhongShading`], whose `index`
//! renormalises the interpolated normal with the integer square root (the course's warning:
//! interpolated normals are not unit vectors) and evaluates [`Illumination`] — only for pixels
//! that pass the depth test. The renderer draws lit objects with
//! [`ShadeMode::Phong`](super::span_writer::ShadeMode::Phong) through it
//! ([`Renderer::rasterize`](crate::render::Renderer::rasterize)), after culling and 3D
//! clipping, which carries the observer-frame normals as three attributes.
//!
//! ## Numeric contract
//! - Normals are normalised to Q15 at the vertices and stored offset,
//!   `n + 32768 ∈ [0, 65536]`; positions are raw I16F16 observer coordinates stored offset by
//!   `2^31` (`u32`). Interpolated values are convex combinations of the vertex values, so they
//!   stay in those ranges, and each pixel receives the correctly rounded affine interpolant
//!   ([`Exact`](super::attributes::Exact)).
//! - Interpolation is affine in screen space (as the course's scanline algorithm); the
//!   position therefore drifts from the true surface point on receding triangles by the
//!   perspective error, which only moves `L` and `V` (not the normal) by a fraction of the
//!   triangle.
//! - Lighting as [`lighting`](super::lighting): integer only.

use super::attributes::{Interpolant, SpanStarts};
use super::dither::Bayer4;
use super::lighting::{unit_q15, Illumination, Material, ONE};
use super::span_writer::{
    depth_span, draw_general_exact, DrawError, LuminanceRamp, Quantizer, RasterTarget, Shading,
    SpanKind, WrittenCount,
};
use crate::geometry::vector::Vec3;
use crate::raster::setup::TriangleSetup;
use crate::raster::SubpixelPoint;
use crate::target::{DepthBuffer, DepthValue, Framebuffer};

/// Offset of stored positions (`i32` raw → `u32`).
const POS_OFFSET: u32 = 1 << 31;

/// One triangle corner for Phong shading.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PhongVertex<const S: u32> {
    /// Sub-pixel screen position.
    pub screen: SubpixelPoint<S>,
    /// Normalised depth (as [`draw_triangle`](super::span_writer::draw_triangle)).
    pub depth: u32,
    /// Observer-frame position.
    pub position: Vec3,
    /// Observer-frame normal (any non-zero length; zero lights with ambient only).
    pub normal: Vec3,
}

/// What is fixed for a Phong-shaded object: lights, material, ramp, and whether to dither.
#[derive(Debug, Clone, Copy)]
pub struct PhongContext<'a> {
    /// The frame's lights in the observer frame.
    pub illumination: &'a Illumination,
    /// The object's material.
    pub material: Material,
    /// Intensity → palette index.
    pub ramp: LuminanceRamp,
    /// Ordered 4×4 dithering between adjacent levels (`dither`).
    pub dither: bool,
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
        let a = &self.attrs;
        let n = [0, 1, 2].map(|k| a[k].value() as i64 - ONE as i64);
        let p = [3, 4, 5].map(|k| (a[k].value() ^ POS_OFFSET) as i32);
        self.illumination
            .intensity(&self.material, Vec3::from_bits(p[0], p[1], p[2]), n)
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

/// The 7 stored attributes of a corner: depth, offset unit normal, offset position.
fn corner_values<const S: u32>(v: &PhongVertex<S>) -> [u32; 7] {
    let b = v.normal.bits();
    let n = unit_q15([b[0] as i64, b[1] as i64, b[2] as i64]).unwrap_or([0; 3]);
    let p = v.position.bits();
    [
        v.depth,
        (n[0] + ONE) as u32,
        (n[1] + ONE) as u32,
        (n[2] + ONE) as u32,
        p[0] as u32 ^ POS_OFFSET,
        p[1] as u32 ^ POS_OFFSET,
        p[2] as u32 ^ POS_OFFSET,
    ]
}

/// Draws a depth-tested, Phong-shaded triangle. Pixels, bands and the return value
/// `(covered, written)` as [`draw_triangle`](super::span_writer::draw_triangle): vertices
/// outside the raster's range are [`DrawError::Fill`] (checked once, by the set-up), any
/// triangle within it is drawn (one too large for the `AttributePlane` through the
/// `WidePlane`, out of line).
pub fn draw_triangle_phong<D: DepthValue, const S: u32>(
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    corners: [PhongVertex<S>; 3],
    ctx: &PhongContext<'_>,
) -> Result<(u32, u32), DrawError> {
    draw_phong_on(&mut RasterTarget::new(frame, depth), corners, ctx)
}

/// [`draw_triangle_phong`] into a prepared [`RasterTarget`] (the renderer's form: one target
/// per object and band), counting written pixels as the target says.
pub(crate) fn draw_phong_on<D: DepthValue, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    corners: [PhongVertex<S>; 3],
    ctx: &PhongContext<'_>,
) -> Result<(u32, u32), DrawError> {
    let t = TriangleSetup::new(corners.map(|c| c.screen)).map_err(DrawError::Fill)?;
    // Depths clamp to the deepest value that stores below FAR (target::depth's module doc).
    let values = corners.map(|c| {
        let mut a = corner_values(&c);
        a[0] = a[0].min(D::MAX_DEPTH32);
        a
    });
    Ok(draw_general_exact(target, &t, values, PhongKind(ctx)))
}

/// Phong's span kind: depth, and the normal and position lit at every pixel (7 exact
/// attributes), through the ramp or dithered.
struct PhongKind<'c, 'a>(&'c PhongContext<'a>);

impl SpanKind<7> for PhongKind<'_, '_> {
    #[inline(always)]
    fn write<D: DepthValue, I: Interpolant, St: SpanStarts<7>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: &mut [D],
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::lighting::Light;

    /// A triangle whose three normals lean outward: the interpolated normal faces the eye at
    /// the centre, where the per-pixel highlight peaks.
    #[test]
    fn highlight_at_the_centre() {
        let ill = Illumination::observer(
            0,
            &[Light::Directional {
                toward: Vec3::from_int(0, 0, -1),
                intensity: 255,
            }],
        )
        .unwrap();
        let ctx = PhongContext {
            illumination: &ill,
            material: Material::from_thousandths(0, 0, 1000, 50),
            ramp: LuminanceRamp::GREY,
            dither: false,
        };
        let corner = |x: i32, y: i32, nx: i32, ny: i32| PhongVertex::<4> {
            screen: SubpixelPoint::from_pixel(x, y),
            depth: 1000,
            position: Vec3::from_int(x - 16, 16 - y, 100),
            normal: Vec3::from_int(nx, ny, -4),
        };
        let tri = [
            corner(0, 0, -2, 2),
            corner(32, 0, 2, 2),
            corner(16, 32, 0, -2),
        ];
        let mut px = [0u8; 32 * 32];
        let mut zs = [0u16; 32 * 32];
        let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, 32, 32).unwrap();
        zb.clear();
        let (covered, written) = draw_triangle_phong(&mut fb, &mut zb, tri, &ctx).unwrap();
        assert!(covered > 400 && written == covered);
        let max = fb
            .rows()
            .flat_map(|(_, r)| r.iter().copied())
            .max()
            .unwrap();
        assert!(max > 200, "{max}");
        assert!(fb.pixel(1, 0).unwrap() < 20);
    }
}
