//! Pass 2 over a rendered frame: every written pixel back-projected from the depth buffer to
//! the observer frame, moved to the light frame and tested against the shadow map; the caller
//! remaps the palette index of each tested pixel.
//!
//! Role in the pipeline: after the renderer has drawn a frame or a band
//! ([`render_scene`](crate::render::render_scene) into a
//! [`Framebuffer::band`](crate::output::Framebuffer::band) and
//! [`DepthBuffer::band`](crate::output::DepthBuffer::band)), before it is flushed. This is the
//! course's second pass (chapter 4, §1.3) done after the z-buffer pass instead of inside it:
//! the depth buffer already holds, for each pixel, the visible point `Q`, and TIPE's screen
//! mapping inverted gives its observer coordinates.
//!
//! ## Back-projection (integer only)
//! For pixel `(i, j)` (absolute picture coordinates: a band's rows are `top..top + height`)
//! with stored depth `s`:
//! 1. `D̂ = s` for a `u32` buffer; for a `u16` buffer the middle of the 32-bit depths it
//!    keeps, `D̂ = s·2^16 + 2^15` ([`DepthSample::to_depth32`]).
//! 2. `z = K/(A − D̂)`, inverting the renderer's `D(z) = A − K/z` with the projector's own
//!    constants ([`Projector::depth_constants`]): `A − D̂` (`≤ 2^61`) is normalised to 32
//!    significant bits and inverted by `reciprocal` (one 32-bit division and two Newton
//!    steps, relative error `< 2^-29`); `K_m·r < 2^63`, one rounding shift. Saturates to the
//!    I16F16 range.
//! 3. `x = (i − i0)·z/f_x`, `y = (j0 − j)·z/f_y` (TIPE's `i = i0 + f_x·x/z`,
//!    `j = j0 − f_y·y/z` solved for `x`, `y`), raw: `(i·2^16 − i0)·z` with
//!    `|i·2^16 − i0| < 2^32` (checked at set-up) and `z < 2^31` is below `2^63`, divided by
//!    `f` (raw Q16) with `arith::euclid::Divisor` (a reciprocal and at most two corrections on 32-bit
//!    cores), rounded to nearest.
//! 4. Observer → light frame by one [`Affine3`]: the camera's rigid inverse
//!    ([`Affine3::inverse_rigid`]) composed with the map's light frame at set-up.
//! 5. [`ShadowMap::classify_light_frame`]; the pixel's index becomes `remap(index, lit)`.
//!
//! ## Conventions
//! - Pixels whose depth is still [`DepthValue::FAR`] (background after the clear; a drawn
//!   surface stores at most `FAR − 1`, see `output::depth`) are left
//!   alone: `remap` is not called for them.
//! - Pixels are visited row by row from the band's top, left to right; the result depends
//!   only on the pixel's position, depth and index, so a picture processed band by band is
//!   identical to the same picture processed in one pass (tested).
//! - Points the map does not cover ([`Visibility::Outside`]) are lit.
//!
//! ## Error budget
//! The back-projected point lies on the pixel's eye ray; a `u16` depth buffer puts it up to
//! half a depth step from the true surface along that ray
//! (`Δz = z²(far − near)/(far·near·2^16)`, stretched by `1/cos` of the ray's angle to the
//! axis). [`observer_depth_slack`] gives that distance in world units, to pass as `slack` to
//! [`ShadowMap::plane_bias`]; with a `u32` buffer it is about one I16F16 unit.

use super::map::ShadowMap;
use super::{ShadowError, Visibility};
use crate::arith::euclid::Divisor;
use crate::arith::isqrt::isqrt_u64;
use crate::arith::wide::reciprocal;
use crate::geometry::camera::Camera;
use crate::geometry::fixed::{saturate_i32, shr_round, Coord};
use crate::geometry::matrix::Affine3;
use crate::geometry::vector::Vec3;
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::project::{require_perspective, Projector};

/// A depth buffer sample the back-projection can read (`u16` and `u32`).
pub trait DepthSample: DepthValue {
    /// The 32-bit normalised depth this sample stands for: itself for `u32`, the middle of
    /// the `2^16` depths it keeps for `u16`.
    fn to_depth32(self) -> u32;
}

impl DepthSample for u16 {
    #[inline(always)]
    fn to_depth32(self) -> u32 {
        ((self as u32) << 16) | 0x8000
    }
}

impl DepthSample for u32 {
    #[inline(always)]
    fn to_depth32(self) -> u32 {
        self
    }
}

/// What one application of the pass did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ShadowStats {
    /// Written pixels tested (depth not far).
    pub tested: u32,
    /// Of those, in shadow.
    pub shadowed: u32,
    /// Of those, outside the map (counted lit).
    pub outside: u32,
}

impl core::ops::AddAssign for ShadowStats {
    /// Sums two bands' counts.
    fn add_assign(&mut self, o: ShadowStats) {
        self.tested += o.tested;
        self.shadowed += o.shadowed;
        self.outside += o.outside;
    }
}

/// Pass 2 set up for one observer camera, one shadow map and one bias.
#[derive(Debug)]
pub struct ShadowPass<'m, 'a, M: DepthValue> {
    map: &'m ShadowMap<'a, M>,
    /// Observer frame → light frame.
    to_light: Affine3,
    bias: u32,
    width: u16,
    height: u16,
    /// Principal point, raw Q16 pixels.
    i0: i64,
    j0: i64,
    fx: Divisor,
    fy: Divisor,
    /// Rounding offsets `⌊f/2⌋`.
    half_fx: i64,
    half_fy: i64,
    /// The renderer's depth constants (`D = A − K_m·2^K_e / z`).
    depth_a: u64,
    depth_km: u32,
    depth_ke: u32,
}

impl<'m, 'a, M: DepthValue> ShadowPass<'m, 'a, M> {
    /// Pass 2 of `map` for frames rendered by `camera`, with `bias` in 32-bit depth units of
    /// the map (see [`ShadowMap::plane_bias`]).
    ///
    /// Errors: [`ShadowError::Projection`] (the camera cannot be projected, or is
    /// orthographic: the back-projection inverts the perspective depth `A − K/z`),
    /// [`ShadowError::Transform`] (its view transform is not rigid or the composition
    /// overflows), [`ShadowError::FrameMismatch`] (a viewport so wide or a principal point so
    /// far off that `|i − i0| ≥ 2^16` pixels).
    pub fn new(map: &'m ShadowMap<'a, M>, camera: &Camera, bias: u32) -> Result<Self, ShadowError> {
        require_perspective(camera, "the shadow pass (pass 2)").map_err(ShadowError::Projection)?;
        let projector = Projector::<4>::new(camera).map_err(ShadowError::Projection)?;
        let (depth_a, depth_km, depth_ke) = projector.depth_constants();
        let to_light = camera
            .view_transform()
            .inverse_rigid()
            .and_then(|inv| inv.then(map.light_frame()))
            .map_err(|_| ShadowError::Transform)?;
        let vp = camera.viewport();
        let (i0, j0) = (
            vp.principal_x.to_bits() as i64,
            vp.principal_y.to_bits() as i64,
        );
        let fits = |n: u16, c: i64| {
            let last = ((n.max(1) as i64 - 1) << 16) - c;
            c.abs() < 1 << 32 && last.abs() < 1 << 32
        };
        if !fits(vp.width, i0) || !fits(vp.height, j0) {
            return Err(ShadowError::FrameMismatch);
        }
        let (fx, fy) = (
            camera.focal_x().to_bits().max(1) as i64,
            camera.focal_y().to_bits().max(1) as i64,
        );
        Ok(ShadowPass {
            map,
            to_light,
            bias,
            width: vp.width,
            height: vp.height,
            i0,
            j0,
            fx: Divisor::new(fx),
            fy: Divisor::new(fy),
            half_fx: fx / 2,
            half_fy: fy / 2,
            depth_a,
            depth_km,
            depth_ke,
        })
    }

    /// The bias this pass uses.
    pub fn bias(&self) -> u32 {
        self.bias
    }

    /// Observer-frame `z` (raw I16F16) of a 32-bit depth (module doc, step 2).
    #[inline]
    fn observer_z(&self, d: u32) -> i32 {
        let v = self.depth_a.saturating_sub(d as u64); // K/z, > 0 below the far clamp
        if v == 0 {
            return i32::MAX;
        }
        let n = v.leading_zeros(); // v < 2^61: n ≥ 3
        let v32 = ((v << n) >> 32) as u32; // [2^31, 2^32): v ≈ v32·2^(32−n)
        let (r, _) = reciprocal(v32); // ≈ 2^62/v32, so 1/v ≈ r·2^(n−94)
        let t = self.depth_km as u64 * r as u64; // < 2^63
        let s = self.depth_ke as i32 + n as i32 - 94;
        let z = if s <= 0 {
            shr_round(t as i64, (-s) as u32)
        } else if s < 63 && t >> (63 - s) == 0 {
            (t << s) as i64
        } else {
            i64::MAX
        };
        saturate_i32(z)
    }

    /// The observer-frame point seen at pixel `(x, y)` (absolute picture coordinates) whose
    /// 32-bit depth is `depth` (module doc, steps 2–3).
    ///
    /// The pixel must lie in the camera's viewport (`0 ≤ x < width`, `0 ≤ y < height`): the
    /// set-up bounds `|x·2^16 − i0|`, `|y·2^16 − j0|` below `2^32` there, which keeps the
    /// products below `2^63`. Any other pixel is [`ShadowError::PixelOutOfRange`], returned
    /// before any arithmetic.
    #[inline]
    pub fn observer_point(&self, x: i32, y: i32, depth: u32) -> Result<Vec3, ShadowError> {
        self.check_pixel(x, y)?;
        Ok(self.observer_point_in(x, y, depth))
    }

    /// `Ok` when `(x, y)` is in the viewport.
    #[inline]
    fn check_pixel(&self, x: i32, y: i32) -> Result<(), ShadowError> {
        if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
            return Err(ShadowError::PixelOutOfRange {
                x,
                y,
                width: self.width,
                height: self.height,
            });
        }
        Ok(())
    }

    /// [`ShadowPass::observer_point`] for a pixel known to be in the viewport.
    #[inline]
    fn observer_point_in(&self, x: i32, y: i32, depth: u32) -> Vec3 {
        let z = self.observer_z(depth) as i64;
        let di = ((x as i64) << 16) - self.i0;
        let dj = self.j0 - ((y as i64) << 16);
        let ox = self.fx.div_floor(di * z + self.half_fx).0;
        let oy = self.fy.div_floor(dj * z + self.half_fy).0;
        Vec3::from_bits(saturate_i32(ox), saturate_i32(oy), z as i32)
    }

    /// The shadow test of the point seen at pixel `(x, y)` with 32-bit depth `depth`; the
    /// pixel must be in the viewport ([`ShadowPass::observer_point`], same error).
    #[inline]
    pub fn classify_pixel(&self, x: i32, y: i32, depth: u32) -> Result<Visibility, ShadowError> {
        self.check_pixel(x, y)?;
        Ok(self.classify_pixel_in(x, y, depth))
    }

    /// [`ShadowPass::classify_pixel`] for a pixel known to be in the viewport.
    #[inline]
    fn classify_pixel_in(&self, x: i32, y: i32, depth: u32) -> Visibility {
        let p = self.observer_point_in(x, y, depth);
        self.map
            .classify_light_frame(self.to_light.transform_point(p), self.bias)
    }

    /// Runs the pass over `frame` (a whole picture or a band) and its `depth` buffer:
    /// each pixel whose depth is not far gets `remap(index, lit)` as its new index
    /// (module doc: order, background, bands).
    ///
    /// Errors: [`ShadowError::FrameMismatch`] when the frame and depth buffer differ in
    /// width, rows or top, or do not lie inside the camera's viewport.
    pub fn apply<D: DepthSample>(
        &self,
        frame: &mut Framebuffer<'_>,
        depth: &DepthBuffer<'_, D>,
        mut remap: impl FnMut(u8, bool) -> u8,
    ) -> Result<ShadowStats, ShadowError> {
        let (top, rows) = (frame.top(), frame.height() as i32);
        if frame.width() != depth.width()
            || frame.height() != depth.height()
            || top != depth.top()
            || frame.width() != self.width
            || top < 0
            || top + rows > self.height as i32
        {
            return Err(ShadowError::FrameMismatch);
        }
        let mut stats = ShadowStats::default();
        for y in top..top + rows {
            let (Some(out), Some(depths)) = (frame.row_mut(y), depth.row(y)) else {
                return Err(ShadowError::FrameMismatch);
            };
            for (x, (index, &s)) in out.iter_mut().zip(depths).enumerate() {
                if s == D::FAR {
                    continue;
                }
                // In the viewport: the frame was checked against it above.
                let vis = self.classify_pixel_in(x as i32, y, s.to_depth32());
                stats.tested += 1;
                stats.shadowed += (vis == Visibility::Shadowed) as u32;
                stats.outside += (vis == Visibility::Outside) as u32;
                *index = remap(*index, vis.is_lit());
            }
        }
        Ok(stats)
    }
}

/// World-unit error of points back-projected from a `D` depth buffer of `camera` up to
/// observer depth `z_max`, to pass as `slack` to [`ShadowMap::plane_bias`]:
/// `(2^(31−b) + 8)·z_max²/K · √(1 + t_x² + t_y²) + 1` raw units — half a storage step of a
/// `b`-bit buffer plus the depth's rounding, converted with `dz/dD = z²/K`, along the eye ray
/// to the picture's corner (`t = (extent/2)/f`), plus the rounding of the coordinates.
pub fn observer_depth_slack<D: DepthSample>(
    camera: &Camera,
    z_max: Coord,
) -> Result<Coord, ShadowError> {
    require_perspective(camera, "the shadow pass's depth slack")
        .map_err(ShadowError::Projection)?;
    let p = Projector::<4>::new(camera).map_err(ShadowError::Projection)?;
    let (_, km, ke) = p.depth_constants();
    let k = ((km as u128) << ke).max(1);
    let z = z_max.to_bits().max(0) as u128;
    let err = (1u128 << (31 - D::BITS.min(31))) + 8;
    let dz_q16 = ((z * z * err) << 16).div_ceil(k); // < 2^62·2^32·2^16: fits u128
    let vp = camera.viewport();
    let t = |n: u16, f: Coord| ((n as u128) << 31) / f.to_bits().max(1) as u128; // Q16 of e/f
    let (tx, ty) = (
        t(vp.width, camera.focal_x()),
        t(vp.height, camera.focal_y()),
    );
    let sec2 = (1u128 << 32) + tx * tx + ty * ty; // Q32
    let sec_q16 = isqrt_u64(sec2.min(u64::MAX as u128) as u64) as u128 + 1;
    let raw = (dz_q16 * sec_q16).div_ceil(1 << 32) + 1;
    Ok(Coord::from_bits(raw.min(i32::MAX as u128) as i32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::camera::{FovAxis, Lens, Viewport};
    use crate::geometry::trig::BinaryAngle;

    /// A 4 × 4 orthographic map of a light straight overhead, over radius 4 at the origin
    /// (the tests below use only its frame).
    fn overhead_map(store: &mut [u16; 16]) -> ShadowMap<'_> {
        ShadowMap::new(
            store,
            4,
            4,
            Vec3::from_int(0, 1, 0),
            Vec3::ZERO,
            Coord::from_num(4),
        )
        .unwrap()
    }

    fn camera(near: f64, far: f64) -> Camera {
        let lens = Lens {
            fov: BinaryAngle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: Coord::from_num(near),
            far: Coord::from_num(far),
        };
        let c = |x: f64, y: f64, z: f64| {
            Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
        };
        Camera::look_at(
            c(1.0, 2.0, 3.0),
            c(0.0, 0.0, 0.0),
            c(0.0, 1.0, 0.0),
            lens,
            Viewport::new(160, 120),
        )
        .unwrap()
    }

    /// Back-projection then projection returns to the pixel (within a sub-pixel unit) and to
    /// the depth (within the projector's own error plus `z`'s rounding, `K/z²` per raw unit).
    #[test]
    fn back_projection_round_trip() {
        for (near, far) in [(0.5, 10.0), (0.1, 1000.0), (1.0, 2.0)] {
            let cam = camera(near, far);
            let projector = Projector::<4>::new(&cam).unwrap();
            let (_, km, ke) = projector.depth_constants();
            let k = ((km as u128) << ke) as f64;
            let mut store = [0u16; 16];
            let map = overhead_map(&mut store);
            let pass = ShadowPass::new(&map, &cam, 0).unwrap();
            let mut s: u32 = 5;
            for _ in 0..20_000 {
                s ^= s << 13;
                s ^= s >> 17;
                s ^= s << 5;
                let (x, y) = ((s % 160) as i32, ((s >> 8) % 120) as i32);
                let d = s.min(u32::MAX - 1);
                let q = pass.observer_point(x, y, d).unwrap();
                let z = q.bits()[2] as f64;
                let Ok((p, d2)) = projector.project_point(q) else {
                    panic!("{x} {y} {d}: {q:?}");
                };
                assert!((p.x - (x << 4)).abs() <= 1, "{x} {y} {d}: {p:?}");
                assert!((p.y - (y << 4)).abs() <= 1, "{x} {y} {d}: {p:?}");
                let allow = 8.0 + k / (z * z);
                assert!(((d2 as f64) - d as f64).abs() <= allow, "{d} {d2} {allow}");
            }
        }
    }

    /// Issue "hostile inputs" #8: a pixel outside the viewport (a far one would overflow the
    /// `i64` back-projection) is an error, checked before any arithmetic.
    #[test]
    fn far_pixels_are_rejected() {
        let cam = Camera::look_at(
            Vec3::from_int(0, 0, 5),
            Vec3::ZERO,
            Vec3::from_int(0, 1, 0),
            Lens {
                fov: BinaryAngle::from_degrees(60),
                axis: FovAxis::Vertical,
                near: Coord::from_num(0.5),
                far: Coord::from_num(10),
            },
            Viewport::new(160, 120),
        )
        .unwrap();
        let mut store = [0u16; 16];
        let map = overhead_map(&mut store);
        let pass = ShadowPass::new(&map, &cam, 0).unwrap();
        for (x, y) in [
            (i32::MAX, 0),
            (0, i32::MIN),
            (i32::MIN, i32::MAX),
            (160, 0),
            (0, 120),
            (-1, 5),
        ] {
            let want = Err(ShadowError::PixelOutOfRange {
                x,
                y,
                width: 160,
                height: 120,
            });
            assert_eq!(pass.observer_point(x, y, 1 << 31), want);
            assert_eq!(
                pass.classify_pixel(x, y, 1 << 31),
                want.map(|_| Visibility::Lit)
            );
        }
        assert!(pass.observer_point(159, 119, 1 << 31).is_ok());
        assert!(pass.classify_pixel(0, 0, u32::MAX).is_ok());
    }
}
