//! Span writers: the per-pixel loops that turn a triangle's spans into framebuffer writes.
//!
//! Role in the pipeline: the last step of the raster stage. [`draw_triangle`] sets up the
//! triangle's [`AttributePlane`] once (attribute 0 is depth, the others feed the [`Shader`]),
//! then for each span of [`fill_triangle`] runs one loop: depth test (strict, nearer wins,
//! see [`DepthValue`]), palette index from the shader, two stores.
//!
//! A fast path: when no attribute but depth varies (flat shading) the index is computed once
//! per triangle instead of once per pixel.
//!
//! Numeric contract: as [`attributes`](super::attributes); depth values are the 32-bit
//! normalised depth of the projection stage, stored through [`DepthValue::from_depth32`].

use super::attributes::{AttributeCursor, AttributePlane, AttributeStep, PlaneError};
use crate::raster::polygon::FillError;
use crate::raster::triangle::fill_triangle;
use crate::raster::{SubpixelPoint, Window};
use crate::target::{DepthBuffer, DepthValue, Framebuffer};

/// Maps a pixel's interpolated attributes (after depth, attribute 0) to a palette index.
pub trait Shader<const N: usize> {
    /// The index for attribute values `values` (`values[0]` is the depth).
    fn index(&self, values: &[u32; N]) -> u8;
}

/// Luminance (attribute 1, `0..=255`) to a ramp of `levels` entries starting at `first`:
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
}

impl Shader<2> for LuminanceRamp {
    #[inline(always)]
    fn index(&self, values: &[u32; 2]) -> u8 {
        let l = values[1].min(255);
        self.first
            .wrapping_add(((l * self.levels as u32) >> 8) as u8)
    }
}

/// Why a triangle was not drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawError {
    /// The fill rejected the vertices.
    Fill(FillError),
    /// The triangle is too large for exact attribute interpolation.
    TooLarge,
}

/// Writes one span with a depth test: pixels `x0..x1` of `colours`/`depths`, starting with
/// the attribute values of `cursor`. Callers pass row slices and in-bounds `x0 ≤ x1 ≤ len`.
#[inline(always)]
pub fn depth_span<D: DepthValue, const N: usize>(
    colours: &mut [u8],
    depths: &mut [D],
    mut cursor: AttributeCursor<N>,
    step: &AttributeStep<N>,
    shader: &impl Shader<N>,
) {
    for (c, z) in colours.iter_mut().zip(depths.iter_mut()) {
        let d = D::from_depth32(cursor.values[0]);
        if d < *z {
            *z = d;
            *c = shader.index(&cursor.values);
        }
        cursor.step(step);
    }
}

/// Draws a depth-tested, shaded triangle into a frame and its depth buffer.
///
/// `values[i]` are vertex `i`'s attributes: `[depth, ...]`. Pixels follow the fill rule of
/// [`polygon`](crate::raster::polygon), limited to the rows both buffers hold. Returns the
/// number of pixels the triangle covers inside the buffers (tested or not). Zero-area
/// triangles draw nothing and return `Ok(0)`.
pub fn draw_triangle<D: DepthValue, const N: usize, const S: u32>(
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; N]; 3],
    shader: &impl Shader<N>,
) -> Result<u32, DrawError> {
    let plane = match AttributePlane::<N, S>::new(v, values) {
        Ok(p) => p,
        Err(PlaneError::Degenerate) => return Ok(0),
        Err(PlaneError::TooLarge) => return Err(DrawError::TooLarge),
    };
    let fw = frame.window();
    let window = fw.intersect(&Window::new(
        0,
        depth.top(),
        depth.width() as i32,
        depth.top() + depth.height() as i32,
    ));
    let mut covered = 0u32;
    let shade_varies = (1..N).any(|i| !plane.is_constant(i));
    let flat_index = shader.index(&plane.vertex0_values());
    let step = *plane.step_x();
    fill_triangle(v, &window, |s| {
        let (x0, x1) = (s.x0 as usize, s.x1 as usize);
        covered += (x1 - x0) as u32;
        let (Some(crow), Some(zrow)) = (frame.row_mut(s.y), depth.row_mut(s.y)) else {
            return;
        };
        let (Some(crow), Some(zrow)) = (crow.get_mut(x0..x1), zrow.get_mut(x0..x1)) else {
            return;
        };
        let cursor = plane.at(s.x0, s.y);
        if shade_varies {
            depth_span(crow, zrow, cursor, &step, shader);
        } else {
            depth_span(crow, zrow, cursor, &step, &Flat(flat_index));
        }
    })
    .map_err(DrawError::Fill)?;
    Ok(covered)
}

/// The shader of a triangle whose shading attributes are constant.
struct Flat(u8);

impl<const N: usize> Shader<N> for Flat {
    #[inline(always)]
    fn index(&self, _: &[u32; N]) -> u8 {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: i32, y: i32) -> SubpixelPoint<4> {
        SubpixelPoint::from_pixel(x, y)
    }

    /// Two overlapping triangles at constant depths: the nearer wins whatever the order, and
    /// equal depths keep the first drawn (strict test).
    #[test]
    fn nearer_wins_in_any_order() {
        let near = [p(0, 0), p(16, 0), p(0, 16)];
        let far = [p(2, 2), p(14, 2), p(2, 14)];
        for order in [[true, false], [false, true]] {
            let mut px = [0u8; 16 * 16];
            let mut zs = [0u16; 16 * 16];
            let mut fb = Framebuffer::new(&mut px, 16, 16).unwrap();
            let mut zb = DepthBuffer::new(&mut zs, 16, 16).unwrap();
            zb.clear();
            for is_near in order {
                let (tri, d, lum) = if is_near {
                    (near, 1000u32 << 16, 200)
                } else {
                    (far, 2000u32 << 16, 100)
                };
                draw_triangle(&mut fb, &mut zb, tri, [[d, lum]; 3], &LuminanceRamp::GREY).unwrap();
            }
            assert_eq!(fb.pixel(3, 3), Some(200));
            assert_eq!(zb.get(3, 3), Some(1000));
            assert_eq!(fb.pixel(15, 15), Some(0));
            assert_eq!(zb.get(15, 15), Some(u16::MAX));
        }
        // Equal depth: the first triangle drawn keeps the pixel.
        let mut px = [0u8; 16 * 16];
        let mut zs = [0u32; 16 * 16];
        let mut fb = Framebuffer::new(&mut px, 16, 16).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, 16, 16).unwrap();
        zb.clear();
        draw_triangle(&mut fb, &mut zb, near, [[7, 10]; 3], &LuminanceRamp::GREY).unwrap();
        draw_triangle(&mut fb, &mut zb, far, [[7, 20]; 3], &LuminanceRamp::GREY).unwrap();
        assert_eq!(fb.pixel(3, 3), Some(10));
    }

    /// Gouraud luminance through the ramp: a horizontal gradient 0 → 255 across 16 pixels.
    #[test]
    fn luminance_gradient_and_band_clipping() {
        let tri = [p(0, 0), p(16, 0), p(0, 16)];
        let vals = [[5u32, 0], [5, 256], [5, 0]];
        let mut px = [0u8; 16 * 4];
        let mut zs = [0u16; 16 * 4];
        // A band holding rows 4..8 only: rows outside are not touched, no panic.
        let mut fb = Framebuffer::band(&mut px, 16, 4, 4).unwrap();
        let mut zb = DepthBuffer::band(&mut zs, 16, 4, 4).unwrap();
        zb.clear();
        let covered = draw_triangle(&mut fb, &mut zb, tri, vals, &LuminanceRamp::GREY).unwrap();
        // Rows 4..8 of the triangle x + y < 16 cover 12 + 11 + 10 + 9 pixels.
        assert_eq!(covered, 42);
        // Luminance at (x, y) is exactly 16·x, clamped to 255 by the ramp.
        for y in 4..8 {
            for x in 0..(16 - y) {
                assert_eq!(fb.pixel(x, y), Some((16 * x).min(255) as u8), "({x},{y})");
            }
        }
    }
}
