//! The shadow map itself: construction for each kind of light, pass 1 (occluders' depths from
//! the light) and the per-point test of pass 2.
//!
//! Role in the pipeline: see the [parent module](super). Construction and
//! [`ShadowMap::plane_bias`] are set-up (`u64`/`u128` arithmetic and divisions, a few dozen
//! sines for the framing search); [`ShadowMap::render`] runs once per occluder and frame (or
//! once for a static scene); [`ShadowMap::classify`] once per tested point.
//!
//! ## Numeric contract
//! - Occluder vertices: model → light frame by one composed [`Affine3`] (I16F16, saturating);
//!   every polygon is tested against the six clip planes ([`Plane::distance`], exact `i64`),
//!   then takes the renderer's polygon-to-triangles path (`clip::fan`): clipped by
//!   Sutherland–Hodgman only against the planes it crosses, projected
//!   ([`Projection::project`]) and drawn as a fan of triangles by the renderer's triangle
//!   writer with its depth-only span kind (`raster::triangle::draw_depth_only`: the one
//!   triangle set-up, the writer's plane choice and span loop; exact, correctly rounded 32-bit
//!   depth at every texel, the nearer kept). The parent module's size limits keep every triangle
//!   within the raster's range; a vertex beyond it is an error, never skipped.
//! - The test compares `D::from_depth32(d − bias)` with the stored sample (`d − bias`
//!   saturating at 0): the bias is in 32-bit depth units for both storage widths.

use heapless::Vec;

use super::projection::{Orthographic, Projection, SUBPIXEL_BITS};
use super::{ShadowError, Visibility};
use crate::arith::isqrt::isqrt_u64;
use crate::clip::fan::clip_project_fan;
use crate::clip::frustum::{
    ClipError, ClipVertex, ClipVolume, Frustum, Plane, CLIP_CAPACITY, MAX_POLYGON_VERTICES,
};
use crate::geometry::camera::{Camera, CameraError, FovAxis, Lens, Viewport};
use crate::geometry::fixed::Coord;
use crate::geometry::matrix::Affine3;
use crate::geometry::mesh::Mesh;
use crate::geometry::trig::{sin_cos_bits, BinaryAngle};
use crate::geometry::vector::{unit_bits, Vec3};
use crate::lighting::Light;
use crate::output::DepthValue;
use crate::project::{require_perspective, Projector};
use crate::raster::triangle::setup::TriangleSetup;
use crate::raster::triangle::{draw_depth_only, DepthTarget};
use crate::raster::SubpixelPoint;

/// Largest full field of view of a framed point-light map (120°): wider cones waste texels
/// on their rim, and a light inside its bounding sphere cannot frame it anyway.
pub const MAX_POINT_FOV_DEGREES: i32 = 120;
/// The framed point-light map's near plane is at least `far / NEAR_FAR_RATIO`.
pub const NEAR_FAR_RATIO: i32 = 256;
/// Guard band of the perspective map's clipper, in map extents (see the parent module).
const GUARD: u16 = 2;
/// Lateral slop of the bias rule, in 32nds of a texel: half a texel to the nearest lattice
/// point, plus half a sub-pixel unit (1/32 texel) of rounding of the tested point's projection
/// and as much for the occluder vertices' projections (which shift the interpolated plane).
const SLOP_32THS: u128 = 18;
/// Depth rounding allowance of the bias rule (projection ≤ 6 per vertex and per point, plus
/// the interpolation's half unit).
const ROUNDING_UNITS: u128 = 16;

/// A pass-1 error on the clipper's path: a clipped fan triangle beyond the clipper's capacity
/// is [`ShadowError::PolygonTooLarge`].
struct PassError(ShadowError);

impl From<ShadowError> for PassError {
    fn from(e: ShadowError) -> Self {
        PassError(e)
    }
}

impl From<ClipError> for PassError {
    fn from(_: ClipError) -> Self {
        PassError(ShadowError::PolygonTooLarge)
    }
}

/// A depth map seen from a light, in caller memory (`u16` or `u32` samples).
#[derive(Debug)]
pub struct ShadowMap<'a, D: DepthValue = u16> {
    samples: &'a mut [D],
    width: u16,
    height: u16,
    /// The light's camera: its view transform is the light frame; its lens is the
    /// perspective map's (unused for an orthographic map).
    camera: Camera,
    /// World → light frame.
    frame: Affine3,
    projection: Projection,
    /// Near, far, left, right, bottom, top, in the light frame.
    planes: [Plane; 6],
}

/// Checks the map size and returns the first `w·h` samples.
fn check_size<D>(samples: &mut [D], w: u16, h: u16, min: u16) -> Result<&mut [D], ShadowError> {
    let n = w as usize * h as usize;
    if w < min.max(1) || h < min.max(1) || w > 1 << 14 || h > 1 << 14 || n > 1 << 19 {
        return Err(ShadowError::BadSize);
    }
    samples.get_mut(..n).ok_or(ShadowError::BadSize)
}

/// An approximate up vector not parallel to `dir`: world `y`, or `x` for a nearly vertical
/// direction.
fn up_for(dir: Vec3) -> Vec3 {
    let t = dir.bits();
    if (t[1] as i64).abs() * 10 > ((t[0] as i64).abs() + (t[2] as i64).abs()) * 9 {
        Vec3::from_int(1, 0, 0)
    } else {
        Vec3::from_int(0, 1, 0)
    }
}

/// `⌊√n⌋` for any `u128`, to within the precision lost by shifting `n` below `2^64` (set-up).
fn isqrt_u128(n: u128) -> u64 {
    let bits = 128 - n.leading_zeros();
    let k = bits.saturating_sub(62).div_ceil(2);
    (isqrt_u64((n >> (2 * k)) as u64) as u64) << k
}

/// The smallest half-angle in `(0, cap]` for which `fits` holds (`fits` monotonic on that
/// range), by binary search on binary-angle units; `None` when even `cap` does not fit.
fn narrowest_half_angle(
    cap: BinaryAngle,
    fits: impl Fn(BinaryAngle) -> bool,
) -> Option<BinaryAngle> {
    if !fits(cap) {
        return None;
    }
    let (mut lo, mut hi) = (0u32, cap.0);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if fits(BinaryAngle(mid)) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(BinaryAngle(hi))
}

fn camera_error(e: CameraError) -> ShadowError {
    match e {
        CameraError::OutOfRange | CameraError::FocalTooLong => ShadowError::OutOfRange,
        _ => ShadowError::BadLight,
    }
}

impl<'a, D: DepthValue> ShadowMap<'a, D> {
    /// A cleared orthographic map of `width × height` texels over the sphere (`centre`,
    /// `radius`) for a **directional** light arriving from direction `toward` (pointing from
    /// the scene toward the light, any non-zero length). `0 < radius ≤ 8192`.
    pub fn new(
        samples: &'a mut [D],
        width: u16,
        height: u16,
        toward: Vec3,
        centre: Vec3,
        radius: Coord,
    ) -> Result<Self, ShadowError> {
        let samples = check_size(samples, width, height, 1)?;
        let r = radius.to_bits();
        if r <= 0 {
            return Err(ShadowError::BadLight);
        }
        if r > 1 << 29 {
            return Err(ShadowError::OutOfRange);
        }
        let travel = toward.neg();
        if travel == Vec3::ZERO {
            return Err(ShadowError::BadLight);
        }
        // The lens is unused: only the frame (origin at the centre, z along the travel).
        let lens = Lens {
            fov: BinaryAngle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: Coord::from_bits(1),
            far: Coord::from_bits(2),
        };
        let vp = Viewport::new(width, height);
        let camera = Camera::new(centre, travel, up_for(travel), lens, vp).map_err(camera_error)?;
        let ortho = Orthographic::new(width, height, r).ok_or(ShadowError::OutOfRange)?;
        let c = |v: i32| Coord::from_bits(v);
        let (one, minus, zero, two_r) = (c(1 << 16), c(-(1 << 16)), c(0), c(2 * r));
        let p = |a, b, cc, d| Plane::new(a, b, cc, d).map_err(|_| ShadowError::OutOfRange);
        let planes = [
            p(zero, zero, one, c(r))?,
            p(zero, zero, minus, c(r))?,
            p(one, zero, zero, two_r)?,
            p(minus, zero, zero, two_r)?,
            p(zero, one, zero, two_r)?,
            p(zero, minus, zero, two_r)?,
        ];
        samples.fill(D::FAR);
        Ok(ShadowMap {
            samples,
            width,
            height,
            frame: *camera.view_transform(),
            camera,
            projection: Projection::Orthographic(ortho),
            planes,
        })
    }

    /// A cleared perspective map for a **point light** at `position` that must cover the
    /// sphere (`centre`, `radius`): the light's camera looks at the centre (straight down,
    /// world `−y`, when the light is at the centre) with the narrowest field of view whose
    /// picture holds the sphere with a margin of one texel, `far = d + r` and
    /// `near = max(d − r, far/256)` (`d` = distance from the light to the centre). When the
    /// sphere needs more than [`MAX_POINT_FOV_DEGREES`] (the light inside or near it) the
    /// field of view is that maximum and points outside its pyramid are lit. `width, height ≥ 4`.
    ///
    /// Errors: [`ShadowError::BadSize`], [`ShadowError::BadLight`] (non-positive radius),
    /// [`ShadowError::OutOfRange`] (the light so far that `d + r` leaves I16F16, or the sphere
    /// so small from there that the focal length reaches 2^15 texels: use a directional map).
    pub fn point(
        samples: &'a mut [D],
        width: u16,
        height: u16,
        position: Vec3,
        centre: Vec3,
        radius: Coord,
    ) -> Result<Self, ShadowError> {
        check_size(samples, width, height, 4)?;
        let r = radius.to_bits();
        if r <= 0 {
            return Err(ShadowError::BadLight);
        }
        let diff: [i64; 3] =
            core::array::from_fn(|i| centre.bits()[i] as i64 - position.bits()[i] as i64);
        let d2: u128 = diff.iter().map(|&c| (c as i128 * c as i128) as u128).sum();
        let d = isqrt_u128(d2) as i64; // raw I16F16, < 2^33
        let far = d + r as i64;
        if far > i32::MAX as i64 {
            return Err(ShadowError::OutOfRange);
        }
        let near = (d - r as i64).max(far / NEAR_FAR_RATIO as i64).max(1);
        let dir = if d == 0 {
            Vec3::from_int(0, -1, 0)
        } else {
            // |diff| < 2^33: scaled to i32 keeping the direction.
            let unit = unit_bits(diff, 16).ok_or(ShadowError::BadLight)?;
            Vec3::from_bits(unit[0], unit[1], unit[2])
        };
        // The field of view: the smallest half-angle a with
        // tan a·(e − 1)/e ≥ tan α = r/√(d² − r²), e the half-extent (in texels) of the
        // smaller side, capped at half of MAX_POINT_FOV_DEGREES.
        let (axis, two_e) = if height <= width {
            (FovAxis::Vertical, height as u128)
        } else {
            (FovAxis::Horizontal, width as u128)
        };
        let cap = BinaryAngle::from_degrees(MAX_POINT_FOV_DEGREES).half();
        let q = if d > r as i64 {
            isqrt_u128(d2 - (r as u128) * (r as u128)) as u128
        } else {
            0
        };
        let fits = |a: BinaryAngle| {
            let (s, c) = sin_cos_bits(a);
            // s·(2e − 2)·q ≥ c·2e·r: Q30 × 2^15 × 2^33 < 2^79, in u128.
            s as u128 * (two_e - 2) * q >= c.max(0) as u128 * two_e * r as u128
        };
        let half = if q == 0 {
            cap
        } else {
            narrowest_half_angle(cap, fits).unwrap_or(cap)
        };
        let lens = Lens {
            fov: BinaryAngle(half.0.saturating_mul(2)),
            axis,
            near: Coord::from_bits(near as i32),
            far: Coord::from_bits(far as i32),
        };
        let vp = Viewport::new(width, height);
        let camera = Camera::new(position, dir, up_for(dir), lens, vp).map_err(camera_error)?;
        Self::from_camera(samples, &camera)
    }

    /// A cleared perspective map for a **spot** at `position` pointing along `axis` (any
    /// non-zero length) with the cone's outer half-angle `outer`: the light's camera looks
    /// along the axis with the narrowest field of view whose picture holds the cone with a
    /// margin of one texel (the cone's circle inscribed in the smaller side); its near and far
    /// planes frame the sphere (`centre`, `radius`) along the axis, `far = a + r` and
    /// `near = max(a − r, far/256)`, `a` the centre's depth along the axis. Outside the cone
    /// the spot lights nothing, so the map misses no shadow. `width, height ≥ 4`.
    ///
    /// Errors: [`ShadowError::SpotConeTooWide`] when the cone and its margin need more than
    /// [`MAX_POINT_FOV_DEGREES`] of field of view (the projection's limit for a map);
    /// [`ShadowError::BadLight`] for a zero axis, a non-positive radius or a sphere wholly
    /// behind the spot; [`ShadowError::BadSize`], [`ShadowError::OutOfRange`] as
    /// [`ShadowMap::point`].
    #[allow(clippy::too_many_arguments)]
    pub fn spot(
        samples: &'a mut [D],
        width: u16,
        height: u16,
        position: Vec3,
        axis: Vec3,
        outer: BinaryAngle,
        centre: Vec3,
        radius: Coord,
    ) -> Result<Self, ShadowError> {
        check_size(samples, width, height, 4)?;
        let r = radius.to_bits() as i64;
        let a = axis.bits().map(|c| c as i64);
        let unit = unit_bits(a, 16).ok_or(ShadowError::BadLight)?;
        if r <= 0 {
            return Err(ShadowError::BadLight);
        }
        // The centre's depth along the axis: |diff| < 2^33 times a Q16 unit, below 2^50.
        let depth: i64 = (0..3)
            .map(|i| (centre.bits()[i] as i64 - position.bits()[i] as i64) * unit[i] as i64)
            .sum::<i64>()
            >> 16;
        let far = depth + r;
        if far <= 0 {
            return Err(ShadowError::BadLight);
        }
        if far > i32::MAX as i64 {
            return Err(ShadowError::OutOfRange);
        }
        let near = (depth - r).max(far / NEAR_FAR_RATIO as i64).max(1);
        let (fov_axis, two_e) = if height <= width {
            (FovAxis::Vertical, height as i128)
        } else {
            (FovAxis::Horizontal, width as i128)
        };
        // tan a·(e − 1)/e ≥ tan outer, i.e. sin a·cos o·(2e − 2) ≥ cos a·sin o·2e: Q30 × Q30
        // × 2^15 < 2^75, in i128.
        let (so, co) = sin_cos_bits(outer);
        if outer > BinaryAngle::QUARTER_TURN {
            return Err(ShadowError::SpotConeTooWide);
        }
        let fits = |h: BinaryAngle| {
            let (s, c) = sin_cos_bits(h);
            s as i128 * co as i128 * (two_e - 2) >= c as i128 * so as i128 * two_e
        };
        let cap = BinaryAngle::from_degrees(MAX_POINT_FOV_DEGREES).half();
        let half = narrowest_half_angle(cap, fits).ok_or(ShadowError::SpotConeTooWide)?;
        let lens = Lens {
            fov: BinaryAngle(half.0.saturating_mul(2)),
            axis: fov_axis,
            near: Coord::from_bits(near as i32),
            far: Coord::from_bits(far as i32),
        };
        let dir = Vec3::from_bits(unit[0], unit[1], unit[2]);
        let vp = Viewport::new(width, height);
        let camera = Camera::new(position, dir, up_for(dir), lens, vp).map_err(camera_error)?;
        Self::from_camera(samples, &camera)
    }

    /// A cleared perspective map from any camera placed at a point light (a spot, one face of
    /// a cube map): its viewport gives the map size (`≥ 4` texels a side), its lens the field
    /// of view, near and far planes.
    ///
    /// An orthographic camera is refused ([`ShadowError::Projection`]): a directional light's
    /// map is [`ShadowMap::new`]'s.
    pub fn from_camera(samples: &'a mut [D], camera: &Camera) -> Result<Self, ShadowError> {
        require_perspective(camera, "a perspective shadow map").map_err(ShadowError::Projection)?;
        let vp = camera.viewport();
        let samples = check_size(samples, vp.width, vp.height, 4)?;
        let projector = Projector::<SUBPIXEL_BITS>::new(camera).map_err(ShadowError::Projection)?;
        let frustum =
            Frustum::new::<SUBPIXEL_BITS>(camera, GUARD).map_err(|_| ShadowError::OutOfRange)?;
        samples.fill(D::FAR);
        Ok(ShadowMap {
            samples,
            width: vp.width,
            height: vp.height,
            camera: *camera,
            frame: *camera.view_transform(),
            projection: Projection::Perspective(projector),
            planes: *frustum.planes(),
        })
    }

    /// The map of a [`Light`]: [`ShadowMap::new`] for a directional light,
    /// [`ShadowMap::point`] for a point light (attenuated or not), [`ShadowMap::spot`] for a
    /// spot (the intensity and attenuation are not used).
    pub fn for_light(
        samples: &'a mut [D],
        width: u16,
        height: u16,
        light: &Light,
        centre: Vec3,
        radius: Coord,
    ) -> Result<Self, ShadowError> {
        match *light {
            Light::Directional { toward, .. } => {
                Self::new(samples, width, height, toward, centre, radius)
            }
            Light::Point { position, .. } | Light::AttenuatedPoint { position, .. } => {
                Self::point(samples, width, height, position, centre, radius)
            }
            Light::Spot {
                position,
                axis,
                cone,
                ..
            } => Self::spot(
                samples, width, height, position, axis, cone.outer, centre, radius,
            ),
        }
    }

    /// Width in texels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// The world → light-frame transform.
    pub fn light_frame(&self) -> &Affine3 {
        &self.frame
    }

    /// The light's camera for a perspective map (position, basis, focal lengths, near and
    /// far), `None` for an orthographic one.
    pub fn light_camera(&self) -> Option<&Camera> {
        match self.projection {
            Projection::Perspective(_) => Some(&self.camera),
            Projection::Orthographic(_) => None,
        }
    }

    /// The projection both passes use.
    pub fn projection(&self) -> &Projection {
        &self.projection
    }

    /// Sets every texel to far (nothing drawn), before drawing a new frame's occluders.
    pub fn clear(&mut self) {
        self.samples.fill(D::FAR);
    }

    /// Depth units (32-bit) per texel step across a surface at 45° to the map's axis: for an
    /// orthographic map `(2^32 − 1)/w` everywhere (multiply by `tan θ` for other slopes); for
    /// a perspective map the same slope at the near plane, `A/f_x` (it falls as `1/z`; prefer
    /// [`ShadowMap::plane_bias`]).
    pub fn texel_depth(&self) -> u32 {
        match &self.projection {
            Projection::Orthographic(_) => (u32::MAX / self.width as u32).max(1),
            Projection::Perspective(p) => {
                let (a, _, _) = p.depth_constants();
                let f = self.camera.focal_x().to_bits().max(1) as u128;
                ((a as u128 * 65_536 / f).min(u32::MAX as u128) as u32).max(1)
            }
        }
    }

    /// The bias (32-bit depth units) the parent module's rule gives for a receiver plane
    /// through world point `point` with world normal `normal` (any length, either sign): the
    /// depth slope across `18/32` texel on each axis, plus the conversion of `slack` (world
    /// units of error in the tested points: zero for exact points,
    /// [`observer_depth_slack`](super::observer_depth_slack) for pixels of a frame) and of the
    /// coordinates' rounding, plus 16 units. `u32::MAX` for a plane seen edge-on (through a
    /// point light, or parallel to a directional one) or a zero normal.
    pub fn plane_bias(&self, normal: Vec3, point: Vec3, slack: Coord) -> u32 {
        let n = self.frame.transform_vector(normal).bits();
        let Some(n) = unit_bits([n[0] as i64, n[1] as i64, n[2] as i64], 15) else {
            return u32::MAX;
        };
        let [nx, ny, nz] = n.map(|c| c.unsigned_abs() as u128);
        let slack = slack.to_bits().max(0) as u128 + 2; // + the I16F16 rounding, raw units
        let (w, h) = (self.width as u128, self.height as u128);
        let total = match &self.projection {
            Projection::Orthographic(o) => {
                if nz == 0 {
                    return u32::MAX;
                }
                // (2^32 − 1)·(|n_x|/w + |n_y|/h)/|n_z| per texel; (2^32 − 1)/2r per raw unit.
                let full = u32::MAX as u128;
                let grad = (full * (nx * h + ny * w)).div_ceil(w * h * nz);
                let per_raw = full.div_ceil(2 * o.radius_bits() as u128);
                (SLOP_32THS * grad).div_ceil(32) + slack * per_raw
            }
            Projection::Perspective(p) => {
                let (_, km, ke) = p.depth_constants();
                let k = (km as u128) << ke; // K = A·near (depth units × raw units), < 2^93
                let q = self.frame.transform_point(point).bits();
                let c = (0..3)
                    .map(|i| n[i] as i128 * q[i] as i128)
                    .sum::<i128>()
                    .unsigned_abs(); // |n·P|, Q15 × raw, < 2^49
                if c == 0 {
                    return u32::MAX;
                }
                let fx = self.camera.focal_x().to_bits().max(1) as u128;
                let fy = self.camera.focal_y().to_bits().max(1) as u128;
                // ∂D/∂u = K·n̂_x/(f·h) with f in pixels (raw/2^16), n̂_x = n_x/2^15 and
                // h = n·P/2^15 raw: K·2^16·|n_x|/(f_x·|n·P|), split as
                // (K·2^16/(f_x·|n·P|))·|n_x| (< 2^109·2^15).
                let gx = ((k << 16) / (fx * c) + 1) * nx;
                let gy = ((k << 16) / (fy * c) + 1) * ny;
                let grad = gx.saturating_add(gy);
                // z_min² = max(near², h²·cos²β), cos²β = 1/(1 + t_x² + t_y²), t = e/f.
                let near = self.camera.lens().near.to_bits() as u128;
                let vp = self.camera.viewport();
                let e = |n: u16, f: u128| ((n as u128) << 15) * 256 / f.max(1); // Q8 of e/f
                let (tx, ty) = (e(vp.width, fx), e(vp.height, fy));
                let cos2_q30 = (1u128 << 46) / ((1 << 16) + tx * tx + ty * ty); // Q30
                let hh = c >> 15; // the plane's distance, raw (c/2^15)
                let zmin2 = (near * near).max((hh * hh * cos2_q30) >> 30).max(1);
                (SLOP_32THS * grad).div_ceil(32) + (slack * k).div_ceil(zmin2)
            }
        };
        (total + ROUNDING_UNITS).min(u32::MAX as u128) as u32
    }

    /// Pass 1: draws the depth of every polygon of `mesh` (placed by `transform`), both
    /// faces, keeping the nearest. Texels follow the raster's fill rule on lattice points;
    /// polygons are clipped to the map's volume first (parent module: near plane).
    pub fn render(&mut self, mesh: &Mesh<'_>, transform: &Affine3) -> Result<(), ShadowError> {
        let m = transform
            .then(&self.frame)
            .map_err(|_| ShadowError::Transform)?;
        let (planes, projection) = (self.planes, self.projection);
        let mut target = DepthTarget::new(self.samples, self.width, self.height);
        for poly in mesh.polygons() {
            polygon(&planes, &projection, &mut target, mesh.vertices(), poly, &m)?;
        }
        Ok(())
    }

    /// Pass 2 for one world point: lit, shadowed, or outside the map (lit). `bias` in 32-bit
    /// depth units (parent module).
    #[inline]
    pub fn classify(&self, p: Vec3, bias: u32) -> Visibility {
        self.classify_light_frame(self.frame.transform_point(p), bias)
    }

    /// [`ShadowMap::classify`] for a point already in the light frame.
    #[inline]
    pub fn classify_light_frame(&self, q: Vec3, bias: u32) -> Visibility {
        let Some((sx, sy, d)) = self.projection.project(q) else {
            return Visibility::Outside;
        };
        // Nearest texel: round the sub-pixel position.
        let half = 1i64 << (SUBPIXEL_BITS - 1);
        let (x, y) = ((sx + half) >> SUBPIXEL_BITS, (sy + half) >> SUBPIXEL_BITS);
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return Visibility::Outside;
        }
        let stored = self.samples[y as usize * self.width as usize + x as usize];
        if D::from_depth32(d.saturating_sub(bias)) <= stored {
            Visibility::Lit
        } else {
            Visibility::Shadowed
        }
    }

    /// Pass 2: true when the light reaches world point `p` (its depth minus `bias` is at
    /// most the nearest texel's; `bias` in 32-bit depth units). Points outside the map are
    /// lit.
    pub fn is_lit(&self, p: Vec3, bias: u32) -> bool {
        self.classify(p, bias).is_lit()
    }

    /// The stored depth at texel `(x, y)` (`D::FAR` where nothing was drawn).
    pub fn sample(&self, x: u16, y: u16) -> Option<D> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.samples
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }
}

/// One polygon of pass 1 (`poly`, indices into `vertices`, placed in the light frame by `m`),
/// through the polygon stage's path ([`clip_project_fan`]): rejected when wholly outside one of
/// the map's `planes`, clipped against the planes it crosses, projected by `projection`, and
/// drawn into `target` as a fan of depth-only triangles ([`draw_triangle`]).
fn polygon<D: DepthValue>(
    planes: &[Plane; 6],
    projection: &Projection,
    target: &mut DepthTarget<'_, D>,
    vertices: &[Vec3],
    poly: &[u16],
    m: &Affine3,
) -> Result<(), ShadowError> {
    if poly.len() < 3 {
        return Ok(());
    }
    if poly.len() > MAX_POLYGON_VERTICES {
        return Err(ShadowError::PolygonTooLarge);
    }
    let mut pts: Vec<ClipVertex<0>, CLIP_CAPACITY> = Vec::new();
    let (mut any, mut all) = (0u8, 0xFFu8);
    for &i in poly {
        let v = *vertices.get(i as usize).ok_or(ShadowError::Raster)?;
        let p = m.transform_point(v);
        let code = planes.outcode(p);
        any |= code;
        all &= code;
        // Capacity holds: poly.len() ≤ MAX_POLYGON_VERTICES < CLIP_CAPACITY.
        let _ = pts.push(ClipVertex::new(p, []));
    }
    if all != 0 {
        return Ok(()); // wholly outside one plane
    }
    let lim = crate::raster::triangle::edge_walker::MAX_COORD as i64;
    let project = |v: &ClipVertex<0>| {
        let (sx, sy, d) = projection.project(v.pos).ok_or(ShadowError::Raster)?;
        if sx.abs() > lim || sy.abs() > lim {
            return Err(ShadowError::Raster.into());
        }
        Ok((SubpixelPoint::new(sx as i32, sy as i32), d))
    };
    clip_project_fan(planes, &pts, any != 0, 0, project, |tri| {
        draw_triangle(target, tri).map_err(PassError)
    })
    .map_err(|e: PassError| e.0)
}

/// One triangle of depths (corners: sub-pixel position and 32-bit depth), the nearer kept at
/// every texel: the one set-up, then the writer's depth-only kind ([`draw_depth_only`]).
fn draw_triangle<D: DepthValue>(
    target: &mut DepthTarget<'_, D>,
    c: [(SubpixelPoint<SUBPIXEL_BITS>, u32); 3],
) -> Result<(), ShadowError> {
    let t = TriangleSetup::new(c.map(|c| c.0)).map_err(|_| ShadowError::Raster)?;
    draw_depth_only(target, &t, c.map(|c| c.1));
    Ok(())
}
