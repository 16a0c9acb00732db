//! The observer (course chapter 1, §3.1–3.5): position `Ω`, orthonormal basis `(W, V, U)`,
//! field of view, focal distance, and the screen grid with possibly non-square pixels.
//!
//! Role in the pipeline: set-up. A [`Camera`] yields the world → observer transform
//! ([`Camera::view_transform`]) and the numbers the projector needs
//! ([`Projector`](crate::project::Projector)).
//!
//! ## Conventions
//! - **Basis.** `U` = the normalised view direction (observer `z`, depth). `V` = the approximate
//!   up `V'` made orthogonal to `U` and normalised, `V = (V' − (U·V')U)/|…|` (observer `y`, up).
//!   `W = U × V` (observer `x`, to the viewer's right). With the right-handed world of SCENES.md,
//!   `(W, V, U)` is a **left-handed** frame (x right, y up, z into the screen). The course writes
//!   `W = V ∧ U`, which names the same vector in a left-handed world; here the sign is chosen so
//!   that world `+x` appears on the right for a camera on `+z` looking at the origin.
//! - **Observer coordinates** of a world point `P`: `x = (P − Ω)·W`, `y = (P − Ω)·V`,
//!   `z = (P − Ω)·U` (the rows of the view transform are `W`, `V`, `U`).
//! - **Screen grid** (TIPE 2010 §1): `i = i0 + f_x·x/z`, `j = j0 − f_y·y/z` in pixels, with `j`
//!   growing downward; pixels are lattice points, so a pixel-centred picture of `W × H` pixels
//!   has its principal point at `((W − 1)/2, (H − 1)/2)` ([`Viewport::new`]).
//! - **Focal distance** (course eq. 1.7): `d = r / tan(φ/2)` where `r` is the half-extent of the
//!   image along the axis the field of view `φ` is measured on ([`FovAxis`]: vertical,
//!   horizontal, or the course's diagonal, the radius of the circle containing the image).
//!   With pixels of physical size `pixel_width × pixel_height` (the TIPE's `r_x`, `r_y`), `r` is
//!   in those physical units and the focal lengths in pixels are `f_x = d / pixel_width`,
//!   `f_y = d / pixel_height`.
//!
//! - **Parallel projection** (course ch. 1 §3.2, its figure of both projections):
//!   [`Camera::orthographic`] takes an [`OrthoView`] instead of a [`Lens`]: the view's extent
//!   in world units along one [`FovAxis`] (its height, width or diagonal) replaces the field
//!   of view. The screen grid becomes `i = i0 + s_x·x`, `j = j0 − s_y·y` with `s_x = 2r /
//!   (extent·pixel_width)`, `s_y = 2r / (extent·pixel_height)` pixels per world unit (`r` the
//!   physical half-extent as above); [`Camera::focal_x`] and [`Camera::focal_y`] hold these
//!   scales, rounded to I16F16, and [`Camera::projection`] tells the two kinds apart. Depth
//!   still runs along `U`, from `near` to `far`.
//!
//! ## Numeric contract
//! Set-up only (runs once per camera change): `u64`/`u128` intermediates and divisions are
//! used freely. Basis vectors are [`Linear`](super::fixed::Linear) (2^-24). Focal lengths and the
//! principal point are I16F16 pixels; `f < 32 768` pixels (a field of view of 60° on a
//! 240-row screen gives `f_y = 207.85`). Image extents in physical units (`width·pixel_width`,
//! `height·pixel_height`) must be at most 2^20. Orthographic: the extent is `0 < extent` (raw
//! I16F16, so at least 2^-16 world units) and the scales `s_x`, `s_y` lie in
//! `[2^-16, 2^15)` pixels per world unit (a 240-row view 4 units high: `s_y = 60`); the
//! projector takes them from the exact ratio, not from the rounded I16F16 value. Everything out
//! of range is a [`CameraError`].

use super::fixed::{Coord, LINEAR_FRAC};
use super::matrix::Affine3;
use super::trig::{sin_cos_bits, BinaryAngle};
use super::vector::{unit_bits, Vec3};
use crate::arith::isqrt::isqrt_u64;

/// What went wrong building a camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CameraError {
    /// The view direction (or `target − position`) is the zero vector.
    ZeroViewDirection,
    /// The approximate up vector is zero or parallel to the view direction.
    UpParallelToView,
    /// The field of view is not strictly between 0 and half a turn.
    FovOutOfRange,
    /// The field of view is so narrow that a focal length reaches 32 768 pixels.
    FocalTooLong,
    /// Zero width, height or pixel size, or an image extent above 2^20 physical units.
    BadViewport,
    /// Not `0 < near < far`.
    BadDepthRange,
    /// A derived position or distance leaves the I16F16 range.
    OutOfRange,
    /// An orthographic extent that is not positive, or whose scale (pixels per world unit)
    /// leaves `[2^-16, 2^15)`.
    BadExtent,
}

/// How the camera maps the observer frame onto the screen (course ch. 1 §3.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Projection {
    /// Central projection from the eye: `i = i0 + f_x·x/z` (the [`Lens`]'s field of view).
    Perspective,
    /// Parallel projection along `U`: `i = i0 + s_x·x` (an [`OrthoView`]).
    Orthographic {
        /// The view's extent in world units along [`Lens::axis`].
        extent: Coord,
    },
}

/// The lens of a parallel (orthographic) projection: the view's extent in world units along
/// `axis` (top to bottom, left to right, or corner to corner), and the depth range.
///
/// ```
/// use zscan::geometry::camera::{Camera, FovAxis, OrthoView, Projection, Viewport};
/// use zscan::geometry::{fixed::Coord, vector::Vec3};
///
/// // A view 4 units high on a 240-row screen: 60 pixels per unit.
/// let view = OrthoView::new(Coord::lit("4"), Coord::lit("0.5"), Coord::lit("20"));
/// let camera = Camera::orthographic(
///     Vec3::from_int(0, 0, 5), Vec3::from_int(0, 0, -1), Vec3::from_int(0, 1, 0),
///     view, Viewport::new(320, 240),
/// )?;
/// assert_eq!(camera.focal_y(), Coord::lit("60"));
/// assert_eq!(camera.projection(), Projection::Orthographic { extent: Coord::lit("4") });
/// # Ok::<(), zscan::geometry::camera::CameraError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct OrthoView {
    /// The view's extent along `axis`, world units, `> 0`.
    pub extent: Coord,
    /// The extent `extent` spans.
    pub axis: FovAxis,
    /// Near plane distance along `U`, `> 0`.
    pub near: Coord,
    /// Far plane distance, `> near`.
    pub far: Coord,
}

impl OrthoView {
    /// A view `extent` world units **high**, depth range `near..far`
    /// ([`with_axis`](OrthoView::with_axis) measures the extent on another axis).
    pub const fn new(extent: Coord, near: Coord, far: Coord) -> OrthoView {
        OrthoView {
            extent,
            axis: FovAxis::Vertical,
            near,
            far,
        }
    }

    /// The same view with its extent measured on `axis`.
    pub const fn with_axis(self, axis: FovAxis) -> OrthoView {
        OrthoView { axis, ..self }
    }
}

/// Which extent of the image the field of view spans.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum FovAxis {
    /// Top to bottom (SCENES.md's convention).
    #[default]
    Vertical,
    /// Left to right.
    Horizontal,
    /// Corner to corner: the course's `r`, radius of the circle containing the image.
    Diagonal,
}

/// The lens: field of view and the depth range.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Lens {
    /// Full field of view `φ`, strictly between 0 and half a turn.
    pub fov: BinaryAngle,
    /// The extent `φ` spans.
    pub axis: FovAxis,
    /// Near plane distance (`z = near`, observer frame), `> 0`.
    pub near: Coord,
    /// Far plane distance, `> near`.
    pub far: Coord,
}

impl Lens {
    /// A lens with a **vertical** field of view `fov` and the depth range `near..far`
    /// (usable in a `const`; [`Camera::new`] checks `0 < fov < half a turn` and
    /// `0 < near < far`). [`with_axis`](Lens::with_axis) measures the field of view on
    /// another extent.
    ///
    /// ```
    /// use zscan::geometry::camera::{FovAxis, Lens};
    /// use zscan::geometry::{fixed::Coord, trig::BinaryAngle};
    ///
    /// const LENS: Lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
    /// assert_eq!(LENS.axis, FovAxis::Vertical);
    /// let wide = LENS.with_axis(FovAxis::Horizontal);
    /// assert_eq!((wide.fov, wide.near, wide.far), (LENS.fov, LENS.near, LENS.far));
    /// ```
    pub const fn new(fov: BinaryAngle, near: Coord, far: Coord) -> Lens {
        Lens {
            fov,
            axis: FovAxis::Vertical,
            near,
            far,
        }
    }

    /// The same lens with its field of view measured on `axis`.
    pub const fn with_axis(self, axis: FovAxis) -> Lens {
        Lens { axis, ..self }
    }
}

/// The screen: size in pixels, principal point, pixel shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Viewport {
    /// Width in pixels.
    pub width: u16,
    /// Height in pixels.
    pub height: u16,
    /// Principal point `i0` (where the optical axis meets the screen), in pixels (I16F16).
    pub principal_x: Coord,
    /// Principal point `j0`, in pixels, rows growing downward.
    pub principal_y: Coord,
    /// Physical pixel width `r_x` (any unit shared with `pixel_height`).
    pub pixel_width: u16,
    /// Physical pixel height `r_y`.
    pub pixel_height: u16,
}

impl Viewport {
    /// `width × height` square pixels with the principal point at the picture's centre,
    /// `((width − 1)/2, (height − 1)/2)` (pixel-centred sampling on lattice pixels).
    pub fn new(width: u16, height: u16) -> Viewport {
        let half = |n: u16| Coord::from_bits((n as i32 - 1) << 15); // (n − 1)/2, ≤ 32 767
        Viewport {
            width,
            height,
            principal_x: half(width),
            principal_y: half(height),
            pixel_width: 1,
            pixel_height: 1,
        }
    }
}

/// The observer: position, basis, focal lengths and screen (see the module doc).
///
/// ```
/// use zscan::geometry::camera::{Camera, Lens, Viewport};
/// use zscan::geometry::{fixed::Coord, trig::BinaryAngle, vector::Vec3};
///
/// let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
/// let eye = Vec3::from_int(0, 0, 5);
/// let up = Vec3::from_int(0, 1, 0);
/// let camera = Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(320, 240))?;
/// // The target is straight ahead: on the optical axis (x = y = 0), 5 units deep.
/// assert_eq!(camera.to_observer(Vec3::ZERO), Vec3::from_int(0, 0, 5));
/// // World +x appears on the viewer's right.
/// assert_eq!(camera.to_observer(Vec3::from_int(1, 0, 0)), Vec3::from_int(1, 0, 5));
/// # Ok::<(), zscan::geometry::camera::CameraError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Camera {
    position: Vec3,
    view: Affine3,
    focal_x: i32,
    focal_y: i32,
    viewport: Viewport,
    lens: Lens,
    projection: Projection,
}

/// Physical half-extent of the image along `axis` in Q16, checked.
fn half_extent_q16(axis: FovAxis, vp: &Viewport) -> Result<u64, CameraError> {
    let w = vp.width as u64 * vp.pixel_width as u64;
    let h = vp.height as u64 * vp.pixel_height as u64;
    if w == 0 || h == 0 || w > 1 << 20 || h > 1 << 20 {
        return Err(CameraError::BadViewport);
    }
    Ok(match axis {
        FovAxis::Vertical => h << 15,
        FovAxis::Horizontal => w << 15,
        // √(w² + h²)/2: the sum is ≤ 2^41, shifted by 22 stays < 2^64; the root is in Q11.
        FovAxis::Diagonal => (isqrt_u64((w * w + h * h) << 22) as u64) << 4,
    })
}

/// `target − position`, refused when a component leaves I16F16.
fn look_direction(position: Vec3, target: Vec3) -> Result<Vec3, CameraError> {
    if target
        .bits()
        .iter()
        .zip(position.bits())
        .any(|(a, b)| (*a as i64 - b as i64).abs() > i32::MAX as i64)
    {
        return Err(CameraError::OutOfRange);
    }
    Ok(target.sub(position))
}

/// Pixels per world unit of an orthographic view `extent` across along `axis`, per screen
/// axis, as exact ratios `s = 2r / (extent·pixel size)`: with `r` the physical half-extent in
/// Q16 (`< 2^37`) and the extent raw I16F16, `(2r, extent_raw·pixel_size)` (the two `2^16`
/// cancel), below `2^38` and `2^47`.
fn ortho_ratio(
    extent: Coord,
    axis: FovAxis,
    vp: &Viewport,
) -> Result<[(u128, u128); 2], CameraError> {
    if extent.to_bits() <= 0 {
        return Err(CameraError::BadExtent);
    }
    let r = half_extent_q16(axis, vp)? as u128;
    let e = extent.to_bits() as u128;
    Ok([
        (2 * r, e * vp.pixel_width as u128),
        (2 * r, e * vp.pixel_height as u128),
    ])
}

/// The world → observer transform of an observer at `position` looking along `view_dir` with
/// approximate up `up` (course §3.5): the orthonormal basis `(W, V, U)` (right, up, forward)
/// to rounding, then the translation `−R·Ω`.
fn view_transform(position: Vec3, view_dir: Vec3, up: Vec3) -> Result<Affine3, CameraError> {
    let wide = |v: Vec3| {
        let b = v.bits();
        [b[0] as i64, b[1] as i64, b[2] as i64]
    };
    let u = unit_bits(wide(view_dir), LINEAR_FRAC).ok_or(CameraError::ZeroViewDirection)?;
    let vp = unit_bits(wide(up), LINEAR_FRAC).ok_or(CameraError::UpParallelToView)?;
    let (u64v, vp64) = (u.map(|c| c as i64), vp.map(|c| c as i64));
    // U·V' in Q48, then V' − (U·V')U in Q48.
    let d: i64 = (0..3).map(|i| u64v[i] * vp64[i]).sum();
    let d24 = d >> LINEAR_FRAC;
    let vw: [i64; 3] = core::array::from_fn(|i| (vp64[i] << LINEAR_FRAC) - d24 * u64v[i]);
    // Reject |V' − (U·V')U| < 2^-10 (V' within ~0.06° of ±U).
    let len2: u64 = vw.iter().map(|c| ((c.unsigned_abs()) >> 24).pow(2)).sum();
    if len2 < 1 << 28 {
        return Err(CameraError::UpParallelToView);
    }
    let v0 = unit_bits(vw, LINEAR_FRAC).ok_or(CameraError::UpParallelToView)?;
    // W = U × V (Q48), then V = W × U again: W is orthogonal to U and to the first V, and
    // the second V is orthogonal to both, so the basis is orthonormal to rounding (2^-24)
    // even when V' is nearly parallel to U.
    let cross = |a: [i64; 3], b: [i64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let w = unit_bits(cross(u64v, v0.map(|c| c as i64)), LINEAR_FRAC)
        .ok_or(CameraError::UpParallelToView)?;
    let v = unit_bits(cross(w.map(|c| c as i64), u64v), LINEAR_FRAC)
        .ok_or(CameraError::UpParallelToView)?;
    let rot = Affine3::from_bits([w, v, u], Vec3::ZERO).map_err(|_| CameraError::OutOfRange)?;
    let t = rot.transform_vector(position);
    // The translation is −R·Ω; refuse positions whose observer-frame image saturated.
    if t.bits().iter().any(|&c| c == i32::MAX || c == i32::MIN) {
        return Err(CameraError::OutOfRange);
    }
    Affine3::translation(t.neg())
        .mul(&rot)
        .map_err(|_| CameraError::OutOfRange)
}

/// The focal lengths `(f_x, f_y)` in Q16 pixels of `lens` on `viewport`, once its depth range,
/// field of view and pixel sizes are checked.
fn focal_lengths(lens: &Lens, viewport: &Viewport) -> Result<(i32, i32), CameraError> {
    if lens.near.to_bits() <= 0 || lens.far <= lens.near {
        return Err(CameraError::BadDepthRange);
    }
    if lens.fov.0 == 0 || lens.fov.0 >= 1 << 31 {
        return Err(CameraError::FovOutOfRange);
    }
    if viewport.pixel_width == 0 || viewport.pixel_height == 0 {
        return Err(CameraError::BadViewport);
    }
    let r = half_extent_q16(lens.axis, viewport)?;
    let (s, c) = sin_cos_bits(lens.fov.half());
    if s <= 0 {
        return Err(CameraError::FocalTooLong);
    }
    // d = ⌊(r·cos + sin/2) / sin⌋ in Q16 physical units (r < 2^37, 0 ≤ cos ≤ 2^30,
    // 0 < sin ≤ 2^30), in u64 divisions: with r = sin·q + t, d = q·cos + ⌊(t·cos + sin/2) /
    // sin⌋, where t·cos < 2^60. Only d ≥ 2^64 overflows, and then f ≥ 2^48 pixels.
    let (s, c) = (s as u64, c.max(0) as u64);
    let d = (r / s)
        .checked_mul(c)
        .and_then(|whole| whole.checked_add(((r % s) * c + s / 2) / s))
        .ok_or(CameraError::FocalTooLong)?;
    // ⌊(d + p/2) / p⌋ without the sum: one more when d mod p ≥ p − ⌊p/2⌋.
    let round_div = |p: u16| {
        let p = p as u64;
        d / p + (d % p >= p - p / 2) as u64
    };
    let (fx, fy) = (
        round_div(viewport.pixel_width),
        round_div(viewport.pixel_height),
    );
    if fx > i32::MAX as u64 || fy > i32::MAX as u64 {
        return Err(CameraError::FocalTooLong);
    }
    if fx == 0 || fy == 0 {
        return Err(CameraError::FovOutOfRange);
    }
    Ok((fx as i32, fy as i32))
}

impl Camera {
    /// The observer at `position` looking along `view_dir` with approximate up `up`
    /// (course §3.5), with the given lens and screen.
    pub fn new(
        position: Vec3,
        view_dir: Vec3,
        up: Vec3,
        lens: Lens,
        viewport: Viewport,
    ) -> Result<Camera, CameraError> {
        let view = view_transform(position, view_dir, up)?;
        let (focal_x, focal_y) = focal_lengths(&lens, &viewport)?;
        Ok(Camera {
            position,
            view,
            focal_x,
            focal_y,
            viewport,
            lens,
            projection: Projection::Perspective,
        })
    }

    /// The parallel projection (course ch. 1 §3.2) of an observer at `position` looking along
    /// `view_dir` with approximate up `up`: the view `view.extent` world units across along
    /// `view.axis`. Its [`lens`](Camera::lens) has a zero field of view and `view`'s axis,
    /// near and far.
    pub fn orthographic(
        position: Vec3,
        view_dir: Vec3,
        up: Vec3,
        view: OrthoView,
        viewport: Viewport,
    ) -> Result<Camera, CameraError> {
        let lens = Lens {
            fov: BinaryAngle(0),
            axis: view.axis,
            near: view.near,
            far: view.far,
        };
        if lens.near.to_bits() <= 0 || lens.far <= lens.near {
            return Err(CameraError::BadDepthRange);
        }
        if viewport.pixel_width == 0 || viewport.pixel_height == 0 {
            return Err(CameraError::BadViewport);
        }
        let projection = Projection::Orthographic {
            extent: view.extent,
        };
        let ratio = ortho_ratio(view.extent, view.axis, &viewport)?;
        // Q16 pixels per world unit, rounded; in [1, 2^31) raw.
        let q16 = |(num, den): (u128, u128)| {
            let s = ((num << 16) + den / 2) / den;
            if s == 0 || s >= 1 << 31 {
                Err(CameraError::BadExtent)
            } else {
                Ok(s as i32)
            }
        };
        let (focal_x, focal_y) = (q16(ratio[0])?, q16(ratio[1])?);
        Ok(Camera {
            position,
            view: view_transform(position, view_dir, up)?,
            focal_x,
            focal_y,
            viewport,
            lens,
            projection,
        })
    }

    /// [`Camera::orthographic`] looking from `position` at `target`.
    pub fn look_at_orthographic(
        position: Vec3,
        target: Vec3,
        up: Vec3,
        view: OrthoView,
        viewport: Viewport,
    ) -> Result<Camera, CameraError> {
        let dir = look_direction(position, target)?;
        Camera::orthographic(position, dir, up, view, viewport)
    }

    /// How this camera projects.
    pub fn projection(&self) -> Projection {
        self.projection
    }

    /// True for a parallel projection ([`Camera::orthographic`]).
    pub fn is_orthographic(&self) -> bool {
        matches!(self.projection, Projection::Orthographic { .. })
    }

    /// An orthographic camera's exact scales, pixels per world unit along `x` and `y`, as
    /// ratios `(numerator, denominator)` (numerators below 2^38, denominators below 2^47);
    /// `None` for a perspective camera.
    pub(crate) fn ortho_scales(&self) -> Option<[(u128, u128); 2]> {
        match self.projection {
            Projection::Orthographic { extent } => {
                ortho_ratio(extent, self.lens.axis, &self.viewport).ok()
            }
            Projection::Perspective => None,
        }
    }

    /// The unit tests' camera: at the origin looking along `+z` (`y` up), 60° vertical field
    /// of view, near 0.5, far 10, 320 × 240 pixels.
    #[cfg(test)]
    pub(crate) fn test_standard() -> Camera {
        let lens = Lens {
            fov: BinaryAngle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: Coord::from_num(0.5),
            far: Coord::from_num(10),
        };
        let axis = |x, y, z| Vec3::from_int(x, y, z);
        let (position, forward, up) = (Vec3::ZERO, axis(0, 0, 1), axis(0, 1, 0));
        Camera::new(position, forward, up, lens, Viewport::new(320, 240)).unwrap()
    }

    /// The observer at `position` looking at `target`, with approximate up `up`.
    pub fn look_at(
        position: Vec3,
        target: Vec3,
        up: Vec3,
        lens: Lens,
        viewport: Viewport,
    ) -> Result<Camera, CameraError> {
        let dir = look_direction(position, target)?;
        Camera::new(position, dir, up, lens, viewport)
    }

    /// Course exercise 5: the observer looking along `view_dir` at a bounding sphere
    /// (`centre`, `radius`), placed at the smallest distance where the whole sphere is inside
    /// the picture: its silhouette touches the screen edge nearest to the principal point.
    /// Returns the camera and that distance.
    pub fn framing_sphere(
        centre: Vec3,
        radius: Coord,
        view_dir: Vec3,
        up: Vec3,
        lens: Lens,
        viewport: Viewport,
    ) -> Result<(Camera, Coord), CameraError> {
        // A provisional camera gives the focal lengths and validates everything else.
        let probe = Camera::new(centre, view_dir, up, lens, viewport)?;
        let r = radius.to_bits();
        if r < 0 {
            return Err(CameraError::OutOfRange);
        }
        let half = 1i64 << 15;
        let px = viewport.principal_x.to_bits() as i64;
        let py = viewport.principal_y.to_bits() as i64;
        // Screen covers [-0.5, W - 0.5] around lattice pixels.
        let ex = (px + half).min(((viewport.width as i64) << 16) - half - px);
        let ey = (py + half).min(((viewport.height as i64) << 16) - half - py);
        if ex <= 0 || ey <= 0 {
            return Err(CameraError::BadViewport);
        }
        // D = R·√(e² + f²)/e for each axis (sin α = e/√(e² + f²)); keep the larger.
        let dist = |e: i64, f: i32| -> u64 {
            let e = e.min(i32::MAX as i64) as u64;
            let hyp = isqrt_u64(e * e + (f as u64) * (f as u64)) as u64; // Q16, < 2^32
            (r as u64 * hyp + e / 2) / e // < 2^63
        };
        let d = dist(ex, probe.focal_x).max(dist(ey, probe.focal_y));
        let d = i32::try_from(d).map_err(|_| CameraError::OutOfRange)?;
        let u = probe.forward();
        let back = u.scale(Coord::from_bits(d));
        let eye = [0, 1, 2].map(|i| centre.bits()[i] as i64 - back.bits()[i] as i64);
        let eye = eye.map(i32::try_from);
        let eye = match eye {
            [Ok(x), Ok(y), Ok(z)] => Vec3::from_bits(x, y, z),
            _ => return Err(CameraError::OutOfRange),
        };
        Ok((
            Camera::new(eye, view_dir, up, lens, viewport)?,
            Coord::from_bits(d),
        ))
    }

    /// The world → observer transform (rows `W`, `V`, `U`; translation `−R·Ω`).
    pub fn view_transform(&self) -> &Affine3 {
        &self.view
    }

    /// A world point in observer coordinates (see [`Affine3::transform_point`] for rounding).
    pub fn to_observer(&self, p: Vec3) -> Vec3 {
        self.view.transform_point(p)
    }

    /// `Ω`, the observer's position.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    fn row(&self, i: usize) -> Vec3 {
        let r = self.view.linear_bits()[i];
        let f = |c: i32| super::fixed::shr_round(c as i64, LINEAR_FRAC - 16) as i32;
        Vec3::from_bits(f(r[0]), f(r[1]), f(r[2]))
    }

    /// `W`, the unit vector to the viewer's right (I16F16).
    pub fn right(&self) -> Vec3 {
        self.row(0)
    }

    /// `V`, the unit up vector (I16F16).
    pub fn up(&self) -> Vec3 {
        self.row(1)
    }

    /// `U`, the unit view direction (I16F16).
    pub fn forward(&self) -> Vec3 {
        self.row(2)
    }

    /// Horizontal focal length `f_x = d / r_x` in pixels.
    pub fn focal_x(&self) -> Coord {
        Coord::from_bits(self.focal_x)
    }

    /// Vertical focal length `f_y = d / r_y` in pixels.
    pub fn focal_y(&self) -> Coord {
        Coord::from_bits(self.focal_y)
    }

    /// The screen.
    pub fn viewport(&self) -> &Viewport {
        &self.viewport
    }

    /// The lens.
    pub fn lens(&self) -> &Lens {
        &self.lens
    }
}

/// `f32` set-up helpers (`float-setup` feature): conversions happen once, here; the camera
/// itself stays integer.
#[cfg(feature = "float-setup")]
impl Lens {
    /// A lens from a field of view in degrees and near/far distances (saturating to I16F16;
    /// NaN becomes 0, which [`Camera::new`] then rejects).
    pub fn from_f32(fov_degrees: f32, axis: FovAxis, near: f32, far: f32) -> Lens {
        let c = |v: f32| Coord::saturating_from_num(if v.is_nan() { 0.0 } else { v });
        Lens {
            fov: BinaryAngle::from_degrees_f32(fov_degrees),
            axis,
            near: c(near),
            far: c(far),
        }
    }
}

#[cfg(feature = "float-setup")]
impl Camera {
    /// [`Camera::look_at`] from `f32` coordinates (set-up only).
    pub fn look_at_f32(
        eye: [f32; 3],
        target: [f32; 3],
        up: [f32; 3],
        lens: Lens,
        viewport: Viewport,
    ) -> Result<Camera, CameraError> {
        let v = |a: [f32; 3]| Vec3::from_f32(a[0], a[1], a[2]);
        Camera::look_at(v(eye), v(target), v(up), lens, viewport)
    }
}

/// Course exercise 5 with a circular field of view: the distance `D = R / sin(φ/2)` at which a
/// sphere of radius `R` just fills a view cone of opening `fov`, and the eye position
/// `centre − D·U` looking along `view_dir`. Errors for a zero direction, a field of view not
/// strictly between 0 and half a turn, or a distance beyond I16F16.
pub fn frame_sphere(
    centre: Vec3,
    radius: Coord,
    view_dir: Vec3,
    fov: BinaryAngle,
) -> Result<(Vec3, Coord), CameraError> {
    if fov.0 == 0 || fov.0 >= 1 << 31 {
        return Err(CameraError::FovOutOfRange);
    }
    if radius.to_bits() < 0 {
        return Err(CameraError::OutOfRange);
    }
    let (s, _) = sin_cos_bits(fov.half());
    if s <= 0 {
        return Err(CameraError::FovOutOfRange);
    }
    let d = ((radius.to_bits() as i64) << 30) / s as i64;
    let d = i32::try_from(d).map_err(|_| CameraError::OutOfRange)?;
    let u = view_dir.normalize().ok_or(CameraError::ZeroViewDirection)?;
    let back = u.scale(Coord::from_bits(d));
    let e: [i64; 3] = core::array::from_fn(|i| centre.bits()[i] as i64 - back.bits()[i] as i64);
    match e.map(i32::try_from) {
        [Ok(x), Ok(y), Ok(z)] => Ok((Vec3::from_bits(x, y, z), Coord::from_bits(d))),
        _ => Err(CameraError::OutOfRange),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
    }

    fn lens() -> Lens {
        Lens {
            fov: BinaryAngle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: Coord::from_num(0.5),
            far: Coord::from_num(10),
        }
    }

    #[test]
    fn lens_new_is_the_literal() {
        const L: Lens = Lens::new(
            BinaryAngle::from_degrees(60),
            Coord::lit("0.5"),
            Coord::lit("10"),
        );
        assert_eq!(L, lens());
        let d = L.with_axis(FovAxis::Diagonal);
        assert_eq!(
            d,
            Lens {
                axis: FovAxis::Diagonal,
                ..lens()
            }
        );
    }

    /// The focal lengths equal the former u128 formula, `⌊(r·cos + sin/2)/sin⌋` then rounded
    /// per pixel size, on every field of view from the narrowest to the widest, each axis,
    /// extreme viewports and pixel sizes (and give `FocalTooLong` exactly where it did).
    #[test]
    fn focal_lengths_match_the_u128_formula() {
        let mut rng = crate::test_rng::XorShift(0x9E37_79B9_7F4A_7C15u64);
        let mut rnd = |m: u64| rng.next_u64() % m;
        let fovs = [
            1u32,
            2,
            7,
            1 << 10,
            1 << 20,
            0x2AAA_AAAB,
            0x7FFF_FFFE,
            0x7FFF_FFFF,
        ];
        let sizes = [
            (1u16, 1u16, 1u16, 1u16),
            (65535, 16, 16, 1),
            (320, 240, 3, 5),
        ];
        let mut checked = [0usize; 2];
        for i in 0..6000 {
            let fov = if i < fovs.len() * 24 {
                fovs[i % fovs.len()]
            } else {
                1 + rnd(0x7FFF_FFFF) as u32
            };
            let (w, h, pw, ph) = if i % 4 < 3 {
                sizes[i % 3]
            } else {
                let mut side = || 1 + rnd(4096) as u16;
                (side(), side(), side(), side())
            };
            let axis = [FovAxis::Vertical, FovAxis::Horizontal, FovAxis::Diagonal][i % 3];
            let mut viewport = Viewport::new(w, h);
            (viewport.pixel_width, viewport.pixel_height) = (pw, ph);
            let lens = Lens {
                fov: BinaryAngle(fov),
                axis,
                ..lens()
            };
            let got = Camera::new(
                Vec3::ZERO,
                v(0.0, 0.0, 1.0),
                v(0.0, 1.0, 0.0),
                lens,
                viewport,
            );
            let Ok(r) = half_extent_q16(axis, &viewport) else {
                assert_eq!(got.err(), Some(CameraError::BadViewport));
                continue;
            };
            let (s, c) = sin_cos_bits(lens.fov.half());
            if s <= 0 {
                assert_eq!(got.err(), Some(CameraError::FocalTooLong));
                checked[1] += 1;
                continue;
            }
            let d = (r as u128 * c as u128 + s as u128 / 2) / s as u128;
            let fx = (d + pw as u128 / 2) / pw as u128;
            let fy = (d + ph as u128 / 2) / ph as u128;
            match got {
                Ok(cam) => {
                    assert_eq!(
                        (
                            cam.focal_x().to_bits() as u128,
                            cam.focal_y().to_bits() as u128
                        ),
                        (fx, fy),
                        "fov {fov} {axis:?} {viewport:?}"
                    );
                    checked[0] += 1;
                }
                Err(CameraError::FovOutOfRange) => assert!(fx == 0 || fy == 0, "fov {fov}"),
                Err(e) => {
                    assert_eq!(e, CameraError::FocalTooLong, "fov {fov}");
                    assert!(fx > i32::MAX as u128 || fy > i32::MAX as u128, "fov {fov}");
                    checked[1] += 1;
                }
            }
        }
        // Both outcomes occur: the narrowest fields of view are too long.
        assert!(checked[0] > 1000 && checked[1] > 10, "{checked:?}");
    }

    #[test]
    fn viewport_extremes() {
        assert_eq!(Viewport::new(65535, 0).principal_x, Coord::from_num(32767));
        assert_eq!(Viewport::new(65535, 0).principal_y, Coord::from_num(-0.5));
    }

    #[test]
    fn scenes_camera() {
        let cam = Camera::look_at(
            v(0.0, 0.0, 3.0),
            Vec3::ZERO,
            v(0.0, 1.0, 0.0),
            lens(),
            Viewport::new(320, 240),
        )
        .unwrap();
        assert_eq!(cam.right(), v(1.0, 0.0, 0.0));
        assert_eq!(cam.up(), v(0.0, 1.0, 0.0));
        assert_eq!(cam.forward(), v(0.0, 0.0, -1.0));
        assert_eq!(cam.to_observer(Vec3::ZERO), v(0.0, 0.0, 3.0));
        let f = 120.0 / (30.0f64.to_radians().tan());
        assert!((cam.focal_y().to_num::<f64>() - f).abs() < 2.0 / 65536.0);
        assert_eq!(cam.focal_x(), cam.focal_y());
        assert_eq!(cam.viewport().principal_x, Coord::from_num(159.5));
    }

    #[cfg(feature = "float-setup")]
    #[test]
    fn float_setup_builders() {
        let lens = Lens::from_f32(60.0, FovAxis::Vertical, 0.5, 10.0);
        assert_eq!(lens, super::tests::lens());
        let cam = Camera::look_at_f32(
            [0.0, 0.0, 3.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            lens,
            Viewport::new(320, 240),
        )
        .unwrap();
        assert_eq!(cam.forward(), v(0.0, 0.0, -1.0));
    }

    #[test]
    fn errors() {
        let vp = Viewport::new(320, 240);
        let o = Vec3::ZERO;
        let up = v(0.0, 1.0, 0.0);
        assert_eq!(
            Camera::new(o, o, up, lens(), vp),
            Err(CameraError::ZeroViewDirection)
        );
        assert_eq!(
            Camera::new(o, v(0.0, 2.0, 0.0), up, lens(), vp),
            Err(CameraError::UpParallelToView)
        );
        assert_eq!(
            Camera::new(o, v(0.0, 0.0, 1.0), o, lens(), vp),
            Err(CameraError::UpParallelToView)
        );
        let mut l = lens();
        l.fov = BinaryAngle::HALF_TURN;
        assert_eq!(
            Camera::new(o, v(0.0, 0.0, 1.0), up, l, vp),
            Err(CameraError::FovOutOfRange)
        );
        l.fov = BinaryAngle(3);
        assert_eq!(
            Camera::new(o, v(0.0, 0.0, 1.0), up, l, vp),
            Err(CameraError::FocalTooLong)
        );
        let mut l = lens();
        l.near = l.far;
        assert_eq!(
            Camera::new(o, v(0.0, 0.0, 1.0), up, l, vp),
            Err(CameraError::BadDepthRange)
        );
        assert_eq!(
            Camera::new(o, v(0.0, 0.0, 1.0), up, lens(), Viewport::new(0, 10)),
            Err(CameraError::BadViewport)
        );
        let far = Vec3::from_bits(i32::MAX, i32::MIN, i32::MAX);
        assert!(Camera::look_at(far, far.neg(), up, lens(), vp).is_err());
    }
}
