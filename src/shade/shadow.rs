//! Shadows by the course's two-pass z-buffer method (chapter 4, §1.3), for a directional
//! light.
//!
//! Role in the pipeline: beside lighting. Pass 1 ([`ShadowMap::render`]) draws every
//! occluder's depth *as seen from the light* into a caller-provided `u16` map (orthographic
//! projection along the light, the exact triangle fill and exact depth interpolation of the
//! raster stage, nearest wins). Pass 2 ([`ShadowMap::is_lit`]) moves a visible point into the
//! light's frame and compares its depth with the map's nearest texel: the light reaches it when
//! `depth(P) ≤ map + bias` (the course's `S_i`: 0 in shadow, 1 lit).
//!
//! ## Resolution and bias (the two failure modes)
//! The map covers a sphere of radius `r` around `centre`: `w × h` texels over `2r × 2r`, so a
//! texel is `2r/w` world units; depth `0..=65535` spans `2r` (`65535/2r` units per world unit).
//! A surface at angle `θ` to the light changes depth by `tan θ` per unit across it, and the
//! nearest texel's centre can be `√2/2` texel away, so a lit surface compares its depth with a
//! stored value up to `δ = (√2/2)·(2r/w)·tan θ` world units nearer, plus half a depth unit of
//! rounding:
//! - **acne** (too little bias): with `bias < δ` a lit surface shadows itself in a pattern
//!   of stripes;
//! - **leaking** (too much bias): with `bias` larger than the distance along the light from an
//!   occluder to the surface behind it, the shadow disappears where objects touch or nearly
//!   touch.
//!
//! [`ShadowMap::texel_depth`] gives `(2r/w)` in depth units: a bias of
//! `texel_depth · tan θ_max · 0.71 + 1` is the smallest free of acne for surfaces up to
//! `θ_max`. Measured on a test scene in `host-tests/tests/lighting.rs`.
//!
//! ## Numeric contract
//! Light-frame coordinates are I16F16 relative to `centre` (the view transform of a
//! [`Camera`] placed at `centre` looking along the light); points farther than `r` from the
//! centre map outside the map (treated as lit) or clamp in depth. Texel positions are sub-pixel
//! (`S = 4`) `i64` products `(x + r)·w·16 / 2r` with `|x|, r < 2^31` and `w ≤ 2^15`: below
//! 2^51. Depth `(z + r)·65535 / 2r` below 2^48, clamped to `0..=65535`. Memory: the caller's
//! `w·h` samples; nothing allocated.

use super::attributes::{AttributePlane, Interpolant};
use crate::geometry::camera::{Camera, FovAxis, Lens, Viewport};
use crate::geometry::fixed::Coord;
use crate::geometry::matrix::Affine3;
use crate::geometry::mesh::Mesh;
use crate::geometry::trig::Angle;
use crate::geometry::vector::Vec3;
use crate::raster::triangle::fill_triangle;
use crate::raster::{SubpixelPoint, Window};

/// Why a shadow map could not be set up or drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShadowError {
    /// The sample slice is shorter than `width × height`, or a size is zero.
    BadSize,
    /// Zero light direction, non-positive radius, or a frame that cannot be built.
    BadLight,
    /// An occluder's transform overflowed.
    Transform,
}

/// A depth map seen from a directional light, in caller memory.
#[derive(Debug)]
pub struct ShadowMap<'a> {
    samples: &'a mut [u16],
    width: u16,
    height: u16,
    /// World → light frame (origin at the centre, `z` along the light's travel).
    frame: Affine3,
    /// Radius `r`, raw I16F16 (> 0).
    radius: i64,
}

impl<'a> ShadowMap<'a> {
    /// A cleared map of `width × height` texels over the sphere (`centre`, `radius`), for
    /// light arriving from direction `toward` (pointing from the scene toward the light).
    pub fn new(
        samples: &'a mut [u16],
        width: u16,
        height: u16,
        toward: Vec3,
        centre: Vec3,
        radius: Coord,
    ) -> Result<Self, ShadowError> {
        let n = width as usize * height as usize;
        if n == 0 || width > 1 << 14 || height > 1 << 14 {
            return Err(ShadowError::BadSize);
        }
        let samples = samples.get_mut(..n).ok_or(ShadowError::BadSize)?;
        if radius.to_bits() <= 0 {
            return Err(ShadowError::BadLight);
        }
        let travel = toward.neg();
        // Any up not parallel to the light: world y unless the light is nearly vertical.
        let t = travel.bits();
        let up = if (t[1] as i64).abs() * 10 > ((t[0] as i64).abs() + (t[2] as i64).abs()) * 9 {
            Vec3::from_int(1, 0, 0)
        } else {
            Vec3::from_int(0, 1, 0)
        };
        let lens = Lens {
            fov: Angle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: Coord::from_bits(1),
            far: Coord::from_bits(2),
        };
        let cam = Camera::new(centre, travel, up, lens, Viewport::new(width, height))
            .map_err(|_| ShadowError::BadLight)?;
        samples.fill(u16::MAX);
        Ok(ShadowMap {
            samples,
            width,
            height,
            frame: *cam.view_transform(),
            radius: radius.to_bits() as i64,
        })
    }

    /// Depth units per texel width (see the module doc's bias rule).
    pub fn texel_depth(&self) -> u32 {
        (65_535 / self.width as u32).max(1)
    }

    /// Light-frame position of world point `p`: sub-pixel texel coordinates (`S = 4`) and
    /// depth `0..=65535`.
    #[inline]
    fn to_map(&self, light: Vec3) -> (i64, i64, u32) {
        to_map(self.radius, self.width, self.height, light)
    }

    /// Pass 1: draws the depth of every polygon of `mesh` (placed by `transform`), both
    /// faces, keeping the nearest. Pixels follow the raster's fill rule on texel lattice points.
    pub fn render(&mut self, mesh: &Mesh<'_>, transform: &Affine3) -> Result<(), ShadowError> {
        let m = transform
            .then(&self.frame)
            .map_err(|_| ShadowError::Transform)?;
        let window = Window::new(0, 0, self.width as i32, self.height as i32);
        let vertices = mesh.vertices();
        let w = self.width as usize;
        let lim = (i32::MAX >> 1) as i64;
        let (radius, width, height) = (self.radius, self.width, self.height);
        for poly in mesh.polygons() {
            if poly.len() < 3 {
                continue;
            }
            let corner = |k: usize| {
                let v = vertices
                    .get(poly[k] as usize)
                    .copied()
                    .unwrap_or(Vec3::ZERO);
                let (x, y, d) = to_map(radius, width, height, m.transform_point(v));
                (
                    SubpixelPoint::<4>::new(x.clamp(-lim, lim) as i32, y.clamp(-lim, lim) as i32),
                    d,
                )
            };
            let c0 = corner(0);
            for k in 1..poly.len() - 1 {
                let (c1, c2) = (corner(k), corner(k + 1));
                let v = [c0.0, c1.0, c2.0];
                let Ok(plane) = AttributePlane::<1, 4>::new(v, [[c0.1], [c1.1], [c2.1]]) else {
                    continue; // degenerate (edge-on to the light) or larger than the limit
                };
                let samples = &mut *self.samples;
                let _ = fill_triangle(v, &window, |s| {
                    let mut z = plane.exact(0, s.x0, s.y);
                    let row = s.y as usize * w;
                    if let Some(span) = samples.get_mut(row + s.x0 as usize..row + s.x1 as usize) {
                        for stored in span {
                            let d = z.value().min(65_535) as u16;
                            if d < *stored {
                                *stored = d;
                            }
                            z.step();
                        }
                    }
                });
            }
        }
        Ok(())
    }

    /// Pass 2: true when the light reaches world point `p` (its depth is at most the nearest
    /// texel's plus `bias`, in depth units). Points outside the map are lit.
    pub fn is_lit(&self, p: Vec3, bias: u32) -> bool {
        let (sx, sy, d) = self.to_map(self.frame.transform_point(p));
        // Nearest texel: round the sub-pixel position.
        let (x, y) = ((sx + 8) >> 4, (sy + 8) >> 4);
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return true;
        }
        let stored = self.samples[y as usize * self.width as usize + x as usize] as u32;
        d <= stored + bias
    }

    /// The stored depth at texel `(x, y)` (`u16::MAX` where nothing was drawn).
    pub fn sample(&self, x: u16, y: u16) -> Option<u16> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.samples
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }
}

/// Light-frame point → sub-pixel texel coordinates (`S = 4`) and depth `0..=65535`.
#[inline]
fn to_map(r: i64, width: u16, height: u16, light: Vec3) -> (i64, i64, u32) {
    let b = light.bits();
    let two_r = 2 * r;
    let sx = ((b[0] as i64 + r) * width as i64 * 16).div_euclid(two_r);
    let sy = ((r - b[1] as i64) * height as i64 * 16).div_euclid(two_r);
    let d = ((b[2] as i64 + r) * 65_535)
        .div_euclid(two_r)
        .clamp(0, 65_535) as u32;
    (sx, sy, d)
}
