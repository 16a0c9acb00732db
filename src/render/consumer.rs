//! The seam after the polygon stage: every culled, clipped, projected triangle of an object
//! goes to one [`TriangleConsumer`], with its three [`Corner`]s and the index of the polygon it
//! came from.
//!
//! The polygon stage (`polygon_stage.rs`) knows nothing of how a triangle becomes pixels: it
//! decides rejection, culling and clipping, projects, fans polygons into triangles, and counts.
//! A consumer decides what a triangle is for. Today's consumers draw at once through the depth
//! buffer: [`LevelWriter`] (a luminance level per corner: flat, exact or fast Gouraud, plain
//! or dithered, opaque or transparent: a screen door or a blend) and [`PhongWriter`] (a normal per corner, lit per pixel). A visibility method
//! that needs every triangle before drawing any (a depth sort, a scan-line edge table, an area
//! subdivision) is another consumer: it stores what it is handed (the corners hold the exact
//! sub-pixel position, the 32-bit depth and the attributes, so a later pass draws the same
//! pixels), then draws in its own order.
//!
//! Numeric contract of a [`Corner`]: `screen` within the projector's `±(2^28 − 1)` sub-pixel
//! range, `depth` the projection's 32-bit normalised depth, `view` the observer-frame position
//! (I16F16), `attrs` a level (`0..=255` at prepared vertices, interpolated at clipped ones)
//! or an observer-frame normal (Q15 components).

use super::RenderError;
use crate::geometry::vector::Vec3;
use crate::output::DepthValue;
use crate::raster::triangle::setup::TriangleSetup;
use crate::raster::triangle::Bayer4;
use crate::raster::triangle::{draw_depth_only, DepthTarget};
use crate::raster::triangle::{draw_in_range, RasterTarget, SpanTarget, WrittenCount};
use crate::raster::triangle::{draw_phong_on, PhongContext, PhongVertex};
use crate::raster::triangle::{draw_textured_on, TexCorner};
#[cfg(feature = "transparency")]
use crate::raster::triangle::{Blend, ScreenDoor};
use crate::raster::SubpixelPoint;
use crate::scene::Object;
#[cfg(feature = "transparency")]
use crate::scene::Transparency;
use crate::texture::Texturing;

/// One triangle corner handed to a consumer: screen position, depth, observer-frame position
/// and `N` attributes (a level, or a normal), from the vertex stage or the clipper.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Corner<const S: u32, const N: usize> {
    /// Sub-pixel screen position.
    pub(crate) screen: SubpixelPoint<S>,
    /// 32-bit normalised depth (smaller is nearer).
    pub(crate) depth: u32,
    /// Observer-frame position.
    pub(crate) view: Vec3,
    /// The corner's attributes.
    pub(crate) attrs: [i32; N],
}

/// What the polygon stage hands its triangles to.
pub(crate) trait TriangleConsumer<const S: u32, const N: usize> {
    /// Bit `i` set when attribute `i` is linear in the observer frame (texture coordinates,
    /// drawn perspective-correct), not in screen space (levels, Phong's normals): a corner the
    /// clipper adds then takes its value along the 3D edge (`clip::frustum`).
    const SPACE_LINEAR: u8 = 0;

    /// Takes one triangle of polygon `polygon` (its index in the mesh). Returns `(covered,
    /// written)`: the pixels it covered inside the buffers and those it wrote (0 where the
    /// consumer does not count them, or draws later).
    fn triangle(
        &mut self,
        polygon: usize,
        corners: [Corner<S, N>; 3],
    ) -> Result<(u32, u32), RenderError>;
}

impl<T: TriangleConsumer<S, N>, const S: u32, const N: usize> TriangleConsumer<S, N> for &mut T {
    const SPACE_LINEAR: u8 = T::SPACE_LINEAR;

    #[inline(always)]
    fn triangle(
        &mut self,
        polygon: usize,
        corners: [Corner<S, N>; 3],
    ) -> Result<(u32, u32), RenderError> {
        (**self).triangle(polygon, corners)
    }
}

/// The z-buffer consumer of luminance triangles (flat or Gouraud, plain or dithered): corners
/// whose one attribute is a level, clamped to `0..=255` (clipped corners are interpolated),
/// drawn at once into a [`RasterTarget`] prepared once per object.
pub(crate) struct LevelWriter<'a, 't, 'o, D, C, T> {
    /// The object's frame and depth buffer (or mask).
    pub(crate) target: &'a mut RasterTarget<'t, D, C, T>,
    /// The object (its ramp, dither and shading mode).
    pub(crate) object: &'a Object<'o>,
}

impl<D: DepthValue, C: WrittenCount, T: SpanTarget<Depth = D>, const S: u32> TriangleConsumer<S, 1>
    for LevelWriter<'_, '_, '_, D, C, T>
{
    #[inline(always)]
    fn triangle(&mut self, _: usize, c: [Corner<S, 1>; 3]) -> Result<(u32, u32), RenderError> {
        let v = c.map(|c| c.screen);
        let values = c.map(|c| [c.depth, c.attrs[0].clamp(0, 255) as u32]);
        let (ramp, shade) = (self.object.ramp, self.object.shade);
        // Without the feature no transparent object gets here (the entries refused it), and
        // no call is made: an empty call per triangle cost its arguments' stores.
        if cfg!(feature = "transparency") {
            if let Some(drawn) = transparent(self.target, v, values, self.object) {
                return Ok(drawn);
            }
        }
        Ok(if self.object.dither {
            draw_in_range(self.target, v, values, shade, |x, y| Bayer4::at(ramp, x, y))
        } else {
            draw_in_range(self.target, v, values, shade, |_, _| ramp)
        })
    }
}

/// The z-buffer consumer of textured triangles: corners whose attributes are a level and the
/// Q8.8 texture coordinates `u`, `v` (interpolated along the 3D edge at clipped corners, where
/// they are affine: [`TriangleConsumer::SPACE_LINEAR`]), and whose perspective weight is `A − D` from the corner's depth
/// (`origin = Some(A)`; an orthographic camera's weights are equal), drawn at once.
pub(crate) struct TextureWriter<'a, 't, D, C, T> {
    /// The object's frame and depth buffer (or mask).
    pub(crate) target: &'a mut RasterTarget<'t, D, C, T>,
    /// The texture, its mode and shade table.
    pub(crate) texturing: Texturing<'a>,
    /// The depth's `A`, or `None` for equal weights.
    pub(crate) origin: Option<u64>,
}

impl<D: DepthValue, C: WrittenCount, T: SpanTarget<Depth = D>, const S: u32> TriangleConsumer<S, 3>
    for TextureWriter<'_, '_, D, C, T>
{
    /// `u` and `v` (attributes 1 and 2) are affine in the observer frame.
    const SPACE_LINEAR: u8 = 0b110;

    #[inline(always)]
    fn triangle(&mut self, _: usize, c: [Corner<S, 3>; 3]) -> Result<(u32, u32), RenderError> {
        let v = c.map(|c| c.screen);
        let values = c.map(|c| [c.depth, c.attrs[0].clamp(0, 255) as u32]);
        let corners = c.map(|c| TexCorner {
            uv: [c.attrs[1], c.attrs[2]],
            weight: self.origin.map_or(1, |a| a.saturating_sub(c.depth as u64)),
        });
        Ok(draw_textured_on(
            self.target,
            v,
            values,
            corners,
            &self.texturing,
        ))
    }
}

/// A luminance triangle of a transparent object, drawn through its screen-door or blending
/// quantizer (`raster::triangle::transparency`), or `None` for an opaque object. Out of line:
/// the opaque objects' writer keeps its registers.
#[inline(never)]
fn transparent<D: DepthValue, C: WrittenCount, T: SpanTarget<Depth = D>, const S: u32>(
    target: &mut RasterTarget<'_, D, C, T>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    object: &Object<'_>,
) -> Option<(u32, u32)> {
    let (ramp, shade, dither) = (object.ramp, object.shade, object.dither);
    // Without the feature the entries refused the object (`render::transparency`).
    if !cfg!(feature = "transparency") {
        return None;
    }
    #[cfg(feature = "transparency")]
    return Some(match object.transparency {
        Transparency::Opaque => return None,
        Transparency::ScreenDoor(o) => draw_in_range(target, v, values, shade, |x, y| {
            ScreenDoor::at(ramp, dither, o, x, y)
        }),
        Transparency::Blended(t) => draw_in_range(target, v, values, shade, |x, y| {
            Blend::at(ramp, dither, t, x, y)
        }),
    });
    #[cfg(not(feature = "transparency"))]
    {
        let _ = (target, v, values, ramp, shade, dither);
        None
    }
}

/// The z-buffer consumer of Phong triangles: corners whose three attributes are the
/// observer-frame normal, lit per pixel ([`draw_phong_on`]), drawn at once into a
/// [`RasterTarget`] prepared once per object.
pub(crate) struct PhongWriter<'a, 't, D, C, T> {
    /// The object's frame and depth buffer (or mask).
    pub(crate) target: &'a mut RasterTarget<'t, D, C, T>,
    /// Lights, material, ramp and dither.
    pub(crate) context: PhongContext<'a>,
}

impl<D: DepthValue, C: WrittenCount, T: SpanTarget<Depth = D>, const S: u32> TriangleConsumer<S, 3>
    for PhongWriter<'_, '_, D, C, T>
{
    #[inline(always)]
    fn triangle(&mut self, _: usize, c: [Corner<S, 3>; 3]) -> Result<(u32, u32), RenderError> {
        let corner = |c: &Corner<S, 3>| PhongVertex {
            screen: c.screen,
            depth: c.depth,
            position: c.view,
            normal: Vec3::from_bits(c.attrs[0], c.attrs[1], c.attrs[2]),
        };
        let corners = [corner(&c[0]), corner(&c[1]), corner(&c[2])];
        draw_phong_on(self.target, corners, &self.context).map_err(RenderError::Draw)
    }
}

/// The depth-only consumer (a hidden-line wireframe's first pass): each triangle's exact depth
/// plane into the z-buffer alone, through the writer's depth-only kind ([`draw_depth_only`]),
/// with the vertex depths clamped as [`LevelWriter`]'s are (so that a face stores the depths
/// it would store drawn shaded). Returns the samples covered, none counted as written.
pub(crate) struct DepthOnlyWriter<'a, 't, D> {
    /// The z-buffer's samples.
    pub(crate) target: &'a mut DepthTarget<'t, D>,
}

impl<D: DepthValue, const S: u32, const N: usize> TriangleConsumer<S, N>
    for DepthOnlyWriter<'_, '_, D>
{
    #[inline(always)]
    fn triangle(&mut self, _: usize, c: [Corner<S, N>; 3]) -> Result<(u32, u32), RenderError> {
        let t = TriangleSetup::in_range(c.map(|c| c.screen));
        let depths = c.map(|c| c.depth.min(D::MAX_DEPTH32));
        Ok((draw_depth_only(self.target, &t, depths), 0))
    }
}
