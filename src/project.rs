//! Projection: observer frame → sub-pixel fixed-point screen coordinates and depth.
//!
//! Role in the pipeline: after [`clip::frustum`](crate::clip::frustum), before the raster.
//! **Callers clip first**: a point with `z < near` is never projected
//! ([`ProjectError::BehindNearPlane`]); the frustum clipper guarantees `z ≥ near` for every
//! vertex it outputs.
//!
//! ## Formulas (TIPE 2010 §1; course ch. 1 §3.2–3.4)
//! For an observer-frame point `(x, y, z)` (x right, y **up**, z forward; [`Coord`] units):
//! - `x_s = i0 + f_x·x/z`, `y_s = j0 − f_y·y/z` in pixels (y grows **down** on screen), stored
//!   in units of 2^-S pixel ([`SubpixelPoint<S>`]) and rounded to nearest (ties up).
//! - depth `D(z) = (2^32 − 1)·far·(z − near) / (z·(far − near))`, i.e. `A − K/z` with
//!   `A = (2^32−1)·far/(far−near)` and `K = A·near`: 0 at `near`, `2^32 − 1` at `far`,
//!   increasing with `z`. It is affine in `1/z`, hence **affine in screen space**: the raster can
//!   interpolate it linearly across a triangle. Smaller is nearer
//!   ([`DepthValue`](crate::output::DepthValue)). Points beyond `far` get `2^32 − 1` (clamped),
//!   which never wins a depth test.
//! - Depth resolution: a buffer of `b` bits (the top `b` bits of `D`) separates surfaces at
//!   distance `z` when they are more than
//!   `Δz ≈ z²·(far − near) / (far·near·2^b)` apart. With SCENES.md's near 0.5, far 10 at
//!   `z = 3`: 16 bits → `Δz ≈ 2.6·10^-4`, 32 bits → `Δz ≈ 4·10^-9` (below the I16F16
//!   resolution of `z` itself, so 32-bit depth is limited by the coordinates, not the buffer).
//!
//! ## Arithmetic (one reciprocal per vertex, no 64-bit division, 32-bit registers)
//! 1. `z` (raw I16F16, `≥ near > 0`) is normalised, `z_n = z·2^n ∈ [2^31, 2^32)`, and its
//!    reciprocal `r ≈ 2^62/z_n ∈ [2^30, 2^31)` is found from one 32-bit division (16 bits)
//!    and two Newton steps, each one unsigned and one signed 32×32→64 multiply
//!    ([`reciprocal`]); `r` is within 2 units below the exact quotient (relative error
//!    < 2^-29).
//! 2. For each axis the focal length (Q16 pixels, `f < 2^31`) is stored normalised,
//!    `f = f_m·2^-e` with `f_m ∈ [2^30, 2^31)`; per vertex `k = (f_m·r) >> 32 ∈ (2^28, 2^30]`
//!    (one 32×32→64 multiply), and the offset is `x·k` (`|x·k| ≤ 2^61`, a second multiply)
//!    shifted right by `t = 46 + e − S − n` with rounding — for `33 ≤ t ≤ 62` (every vertex of
//!    the standard scenes) by taking the product's high word and a 32-bit rounding shift
//!    (exact, see `offset_fast`), the sum with the principal point and the range check in
//!    32 bits too (`|i0| ≤ 2^27`, `|offset| ≤ 2^28`); other `t` take a 64-bit path giving
//!    the same values (`offset_general`). Tested against `f64` for
//!    `S ∈ {0, 4, 8, 16}`: error ≤ `0.5 + |offset|·2^-26` units of 2^-S pixel, i.e. below
//!    0.51 unit for any on-screen or guard-band point at `S = 4`.
//! 3. Depth: `K = K_m·2^e` with a 32-bit mantissa; `K/z = K_m·r·2^(e+n−62)` (`K_m·r < 2^63`),
//!    and `D = A − K/z`, clamped to `[0, 2^32 − 1]`. When the shift `s = 62 − e − n` is in
//!    `32..=62` (again every standard-scene vertex), `K/z < 2^31` comes from the product's
//!    top 32 bits with a 32-bit rounding shift, and since `A ≥ 2^32 − 1` the clamp is one
//!    saturating 32-bit subtraction ([`Projector::project_point`]); otherwise 64-bit shifts
//!    give the same value. Rounding: `A` and `K` are rounded to
//!    nearest at set-up, `K/z` to nearest per vertex from the (slightly low) reciprocal, so `D`
//!    errs a few units high: measured against `f64` over dense sweeps of `z` for near/far =
//!    0.5/10, 0.1/1000 and 1/2, at most 6 units of the 2^32 range (`D(near)` is 1 to 4, not 0;
//!    `D(far) = 2^32 − 1`). That is far below one step of a 16-bit buffer (2^16 units) and
//!    comparable to the 32-bit `Δz` above: surfaces closer than a few `Δz_32` may order either
//!    way.
//!
//! The 32-bit formulation gives bit for bit what the former 64-bit one gave (the tests keep
//! that one as an oracle: exhaustively for the reciprocal, on dense sweeps over cameras and
//! points for [`Projector::project_point`]).
//!
//! Cost, measured on a Cortex-M4 (QEMU `mps2-an386`, `-icount`, release build, SCENES.md's
//! bunny, 1839 vertices): **≈ 84 instructions per vertex** for [`Projector::project_point`]
//! as a call (176 with the former 64-bit Newton steps, offsets and depth shift); it is
//! `#[inline(always)]`, which saves about 9 more per vertex in the vertex stage (no call, no
//! result through memory) for a few hundred bytes of code at its four call sites.
//!
//! ## Parallel projection (course ch. 1 §3.2)
//! For an orthographic camera ([`Camera::orthographic`]) the same `project_point` takes a
//! second path (one branch for perspective cameras):
//! - `x_s = i0 + s_x·x`, `y_s = j0 − s_y·y`, with the camera's exact scales (pixels per world
//!   unit, `2^-16 ≤ s < 2^15`) times `2^S` stored as `m·2^-sh`, `m ∈ [2^30, 2^31)`: one
//!   `i64` product per axis (`|x|·m < 2^62`) and a rounding shift, within
//!   `1/2 + |offset|·2^-30` units of 2^-S pixel of the exact value;
//! - depth **linear in `z`**, `D(z) = (2^32 − 1)·(z − near)/(far − near)` correctly rounded
//!   (ties up): 0 at `near`, `2^32 − 1` at `far`, and `2^32 − 1` beyond. Being affine in `x`, `y`
//!   and `z`, it is affine in screen space, so the raster interpolates it exactly as it does
//!   the perspective `D`. A multiply by the stored ratio estimates it within a few units and
//!   at most a few exact `u64` comparisons correct the estimate (`far − near < 2^32` raw).
//!   A 16-bit buffer separates surfaces `(far − near)/2^16` apart at every depth.
//!
//! Offsets that put a point beyond the raster's range `|x|, |y| ≤ 2^28 − 1`
//! ([`MAX_COORD`]) are [`ProjectError::OutOfRange`]; the frustum's guard band keeps clipped
//! polygons well inside it.

use crate::arith::scale::Scale;
pub(crate) use crate::arith::wide::reciprocal;
use crate::arith::wide::{mul_wide, mul_wide_u};
use crate::clip::frustum::ClipVertex;
use crate::geometry::camera::Camera;
use crate::geometry::fixed::{shr_round, Coord};
use crate::geometry::vector::Vec3;
use crate::raster::triangle::edge_walker::{MAX_COORD, MAX_SUBPIXEL_BITS};
use crate::raster::SubpixelPoint;

/// Why a point could not be projected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProjectError {
    /// `z < near`: the point must be clipped first (it may be behind the eye).
    BehindNearPlane,
    /// The named stage needs a perspective camera and was given an orthographic one.
    Orthographic(&'static str),
    /// The projected point falls outside `|x|, |y| ≤ 2^28 − 1` sub-pixel units.
    OutOfRange,
    /// `S` exceeds the raster's [`MAX_SUBPIXEL_BITS`].
    SubpixelBitsTooLarge,
}

/// A projected vertex: sub-pixel position, depth (smaller is nearer) and the clip attributes
/// carried through unchanged (they are affine in screen space only approximately; Gouraud
/// shading interpolates them linearly, as usual).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ScreenVertex<const S: u32, const A: usize> {
    /// Screen position in units of 2^-S pixel, y down.
    pub point: SubpixelPoint<S>,
    /// Normalised depth `D(z)` (module doc), 0 at near, `2^32 − 1` at far.
    pub depth: u32,
    /// The vertex's attributes.
    pub attrs: [i32; A],
}

/// `Ok` for a perspective camera; [`ProjectError::Orthographic`] naming `stage` for an
/// orthographic one (for the stages whose arithmetic is the perspective's own: the shadow
/// pass's back-projection through `A − K/z`, the shadow map's depth bounds, the planner's
/// rounding guard).
pub(crate) fn require_perspective(
    camera: &Camera,
    stage: &'static str,
) -> Result<(), ProjectError> {
    match camera.is_orthographic() {
        true => Err(ProjectError::Orthographic(stage)),
        false => Ok(()),
    }
}

/// Everything the per-vertex projection needs, precomputed from a [`Camera`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Projector<const S: u32> {
    /// Focal lengths normalised: `f = f_m·2^-e` (Q16 pixels), `f_m ∈ [2^30, 2^31)`.
    fx_m: u32,
    fy_m: u32,
    /// Principal point in sub-pixel units.
    i0: i32,
    j0: i32,
    /// Near and far, raw I16F16.
    near: i32,
    far: i32,
    /// `A` (depth units) and `K = K_m·2^ke` (module doc).
    depth_a: u64,
    depth_km: u32,
    depth_ke: u32,
    /// Fast-path constants (see [`project_point`](Self::project_point)), wrapping `u32`:
    /// `shift − 33` per axis, `30 − ke` for the depth, and `min(A − (2^32 − 1), 2^32 − 1)`.
    fx_b: u32,
    fy_b: u32,
    depth_b: u32,
    depth_ex: u32,
    /// The parallel projection's scales, for an orthographic camera.
    ortho: Option<Ortho>,
}

/// An orthographic camera's projection constants (module doc, "Parallel projection"): raw
/// I16F16 → sub-pixel units per axis, raw `z − near` → depth units, and `far − near` raw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Ortho {
    kx: Scale,
    ky: Scale,
    kd: Scale,
    span: u32,
}

impl<const S: u32> Projector<S> {
    /// The depth's `A` (module doc), from which a vertex's `K/z = A − D` is its perspective
    /// weight for textures; `None` for an orthographic camera (depth linear in `z`: every
    /// weight equal).
    pub fn weight_origin(&self) -> Option<u64> {
        match self.ortho {
            Some(_) => None,
            None => Some(self.depth_a),
        }
    }

    /// The projector of `camera` at `S` sub-pixel bits (`S ≤ 16`).
    pub fn new(camera: &Camera) -> Result<Self, ProjectError> {
        if S > MAX_SUBPIXEL_BITS {
            return Err(ProjectError::SubpixelBitsTooLarge);
        }
        let vp = camera.viewport();
        let to_sub = |p: Coord| shr_round(p.to_bits() as i64, 16 - S);
        let (i0, j0) = (to_sub(vp.principal_x), to_sub(vp.principal_y));
        if i0.abs() > MAX_COORD as i64 / 2 || j0.abs() > MAX_COORD as i64 / 2 {
            return Err(ProjectError::OutOfRange);
        }
        let lens = camera.lens();
        let (near, far) = (lens.near.to_bits(), lens.far.to_bits());
        // Camera guarantees 0 < near < far; A ≤ (2^32 − 1)·2^31, K = A·near < 2^94.
        // A = ⌊(n + span/2) / span⌋ and K = ⌊(n·near + span/2) / span⌋ with n = (2^32 − 1)·far
        // < 2^63, from one u64 division n = span·q + t: A = q + (t ≥ span − ⌊span/2⌋) and
        // K = q·near + ⌊(t·near + span/2) / span⌋, where t·near < 2^62.
        let span = (far - near) as u64;
        let n = u32::MAX as u64 * far as u64;
        let (q, t) = (n / span, n % span);
        let a = (q + (t >= span - span / 2) as u64) as u128;
        let k = q as u128 * near as u128 + ((t * near as u64 + span / 2) / span) as u128;
        let bits = 128 - k.leading_zeros();
        let ke = bits.saturating_sub(32);
        let km = (k + ((1u128 << ke) >> 1)) >> ke; // rounded 32-bit mantissa (≤ 2^32)
        let (km, ke) = if km > u32::MAX as u128 {
            (km >> 1, ke + 1)
        } else {
            (km, ke)
        };
        // Camera guarantees 1 ≤ f < 2^31 (raw Q16 pixels).
        let fx = camera.focal_x().to_bits().max(1) as u32;
        let fy = camera.focal_y().to_bits().max(1) as u32;
        let (ex, ey) = (fx.leading_zeros() - 1, fy.leading_zeros() - 1);
        if a >= 1 << 61 && !camera.is_orthographic() {
            // far/(far − near) ≥ 2^29: near and far practically equal (for the perspective
            // depth `A − K/z`; the parallel projection's linear depth takes any range).
            return Err(ProjectError::OutOfRange);
        }
        let ortho = match camera.ortho_scales() {
            None => None,
            Some([(nx, dx), (ny, dy)]) => {
                // Pixels per world unit n/d, so 2^S·n/(d·2^16) sub-pixel units per raw unit;
                // numerators < 2^38·2^16 ≤ 2^60; multipliers below 2^31 (else out of range).
                let axis = |n: u128, d: u128| Scale::new(n << S, d << 16, 31);
                let full = u32::MAX as u128;
                match (
                    axis(nx, dx),
                    axis(ny, dy),
                    Scale::new(full, span as u128, 32),
                ) {
                    (Some(kx), Some(ky), Some(kd)) => Some(Ortho {
                        kx,
                        ky,
                        kd,
                        span: span as u32,
                    }),
                    _ => return Err(ProjectError::OutOfRange),
                }
            }
        };
        Ok(Projector {
            fx_m: fx << ex,
            fy_m: fy << ey,
            i0: i0 as i32,
            j0: j0 as i32,
            near,
            far,
            depth_a: a as u64,
            depth_km: km as u32,
            depth_ke: ke,
            fx_b: (46 + ex - S).wrapping_sub(33),
            fy_b: (46 + ey - S).wrapping_sub(33),
            depth_b: 30u32.wrapping_sub(ke),
            // A ≥ 2^32 − 1: far/(far − near) > 1.
            depth_ex: (a - u32::MAX as u128).min(u32::MAX as u128) as u32,
            ortho,
        })
    }

    /// True for an orthographic camera's projector.
    pub fn is_orthographic(&self) -> bool {
        self.ortho.is_some()
    }

    /// The parallel projection of `(x, y, z)`, `z ≥ near` (module doc, "Parallel
    /// projection").
    #[inline(never)]
    fn project_parallel(
        &self,
        o: &Ortho,
        x: i32,
        y: i32,
        z: i32,
    ) -> Result<(SubpixelPoint<S>, u32), ProjectError> {
        // |x|, |y| < 2^31 and m < 2^31: the products are below 2^62.
        let sx = self.i0 as i64 + o.kx.signed(x as i64);
        let sy = self.j0 as i64 - o.ky.signed(y as i64);
        let lim = MAX_COORD as i64;
        if sx.abs() > lim || sy.abs() > lim {
            return Err(ProjectError::OutOfRange);
        }
        let v = (z as i64 - self.near as i64) as u64; // 0 ≤ v < 2^32
        let depth = if v >= o.span as u64 {
            u32::MAX
        } else {
            // v < span < 2^31 and m < 2^32: v·m < 2^63. The estimate is within a few units of
            // the quotient; the two loops make it the exact ⌊(v·(2^32 − 1) + ⌊span/2⌋)/span⌋
            // (n < 2^64 − 2^33 + 2^31, q·span and (q + 1)·span ≤ 2^32·(2^32 − 1)).
            let span = o.span as u64;
            let n = v * u32::MAX as u64 + span / 2;
            let mut q = o.kd.unsigned(v).min(u32::MAX as u64);
            while q * span > n {
                q -= 1;
            }
            while (q + 1) * span <= n {
                q += 1;
            }
            q as u32
        };
        Ok((SubpixelPoint::new(sx as i32, sy as i32), depth))
    }

    /// The near plane distance (raw I16F16 checked by [`project_point`](Self::project_point)).
    pub fn near(&self) -> Coord {
        Coord::from_bits(self.near)
    }

    /// The far plane distance.
    pub fn far(&self) -> Coord {
        Coord::from_bits(self.far)
    }

    /// The depth mapping's constants `(A, K_m, K_e)`: [`project_point`](Self::project_point)
    /// computes `D(z) = A − K_m·2^K_e / z` (`z` raw I16F16, `A < 2^61`, `K_m < 2^32`), so a
    /// caller can invert a stored depth with the very constants that produced it
    /// (`z = K_m·2^K_e / (A − D)`; used by the shadow pass's back-projection).
    pub fn depth_constants(&self) -> (u64, u32, u32) {
        (self.depth_a, self.depth_km, self.depth_ke)
    }

    /// The principal point in sub-pixel units.
    pub fn principal(&self) -> SubpixelPoint<S> {
        SubpixelPoint::new(self.i0, self.j0)
    }

    /// `f·c/z` in sub-pixel units: `k = (f_m·r) >> 32 ∈ (2^28, 2^30]` (fits `i32`), `|c·k| ≤ 2^61`,
    /// shifted right by `t = shift − n` with rounding, where `shift = 46 + e − S`.
    ///
    /// For `33 ≤ t ≤ 62` ([`project_point`](Self::project_point)'s fast path, 32-bit) the high
    /// word `h = ⌊c·k/2^32⌋` is enough: `⌊(⌊h/2^(t−33)⌋ + 1)/2⌋` equals the exact rounding
    /// of `c·k/2^t` (`⌊x/2^(t−33)⌋ = ⌊⌊x/2^32⌋/2^(t−33)⌋` for the exact `x = c·k/2^32`, and
    /// `⌊(q + 1)/2⌋` rounds `q/2` to nearest, ties up). Otherwise ([`Self::offset_general`])
    /// the 64-bit shift; `t < 0` (only for focal lengths near 2^15 pixels and `z` near 2^-16)
    /// doubles instead, which the range check then rejects or keeps.
    #[inline(always)]
    fn offset_fast(f_m: u32, b: u32, c: i32, r: u32) -> i32 {
        let k = (mul_wide_u(f_m, r) >> 32) as i32; // ≤ 2^30
        let h = (mul_wide(c, k) >> 32) as i32; // |h| ≤ 2^29
        ((h >> b) + 1) >> 1 // b = t − 33 ∈ 0..30: |result| ≤ 2^28
    }

    /// [`Self::offset_fast`]'s value for any `t` (64-bit): the rounding shift of `c·k` by
    /// `t = shift − n`, `0` for `t > 62`, doubled for `t < 0`.
    #[inline(always)]
    fn offset_general(f_m: u32, shift: u32, c: i32, r: u32, n: u32) -> i64 {
        let k = ((f_m as u64 * r as u64) >> 32) as i32;
        let prod = c as i64 * k as i64;
        let t = shift as i32 - n as i32;
        if t > 62 {
            0
        } else if t >= 0 {
            shr_round(prod, t as u32)
        } else {
            prod * 2 // t = −1 at most (module doc); |prod| ≤ 2^61
        }
    }

    /// Screen position and depth of an observer-frame point with `z ≥ near`.
    ///
    /// Fast path, all in 32-bit registers, taken when both axes' shifts `t` lie in `33..=62`
    /// and the depth shift `s = 62 − ke − n` in `32..=62` (every vertex of the standard
    /// scenes): offsets by `offset_fast` (`|i0| ≤ 2^27` plus `|offset| ≤ 2^28` fits
    /// `i32`, so the range check is 32-bit too); `K/z = ⌊(⌊t/2^31⌋ >> (s − 32)) + 1)/2⌋`
    /// (`t = K_m·r < 2^63 − 2^32`, so `⌊t/2^31⌋ + 1` fits `u32`; the result is below 2^31),
    /// and, as `A ≥ 2^32 − 1 > K/z`, the clamped `A − K/z` is
    /// `(2^32 − 1) − max(K/z − (A − (2^32 − 1)), 0)`, with `A − (2^32 − 1)` stored saturated to
    /// 32 bits (if it saturates, `K/z < 2^31` leaves it far and the result is `2^32 − 1` either
    /// way). Other inputs take `project_general`. Both give exactly what the former
    /// 64-bit code gave (kept as the tests' oracle and compared on dense sweeps).
    #[inline(always)]
    pub fn project_point(&self, p: Vec3) -> Result<(SubpixelPoint<S>, u32), ProjectError> {
        let [x, y, z] = p.bits();
        if z < self.near {
            return Err(ProjectError::BehindNearPlane);
        }
        if let Some(o) = &self.ortho {
            return self.project_parallel(o, x, y, z);
        }
        let (r, n) = reciprocal(z as u32);
        let bx = self.fx_b.wrapping_sub(n); // t − 33, huge when t < 33
        let by = self.fy_b.wrapping_sub(n);
        let bd = self.depth_b.wrapping_sub(n); // s − 32
        if bx >= 30 || by >= 30 || bd > 30 {
            return self.project_general(x, y, r, n);
        }
        let sx = self.i0 + Self::offset_fast(self.fx_m, bx, x, r);
        let sy = self.j0 - Self::offset_fast(self.fy_m, by, y, r);
        // |s| ≤ MAX_COORD as one unsigned compare per axis (|s| < 2^29: the sum cannot wrap).
        let (lim, span) = (MAX_COORD, 2 * MAX_COORD as u32);
        if (sx + lim) as u32 > span || (sy + lim) as u32 > span {
            return Err(ProjectError::OutOfRange);
        }
        let t = mul_wide_u(self.depth_km, r); // < 2^63 − 2^32
        let kz = ((((t >> 31) as u32) >> bd) + 1) >> 1; // K/z < 2^31
        let depth = !kz.saturating_sub(self.depth_ex);
        Ok((SubpixelPoint::new(sx, sy), depth))
    }

    /// [`Self::project_point`] after the reciprocal, for any shifts (64-bit arithmetic).
    #[cold]
    #[inline(never)]
    fn project_general(
        &self,
        x: i32,
        y: i32,
        r: u32,
        n: u32,
    ) -> Result<(SubpixelPoint<S>, u32), ProjectError> {
        let sx =
            self.i0 as i64 + Self::offset_general(self.fx_m, self.fx_b.wrapping_add(33), x, r, n);
        let sy =
            self.j0 as i64 - Self::offset_general(self.fy_m, self.fy_b.wrapping_add(33), y, r, n);
        let lim = MAX_COORD as i64;
        if sx.abs() > lim || sy.abs() > lim {
            return Err(ProjectError::OutOfRange);
        }
        // K/z = K_m·r·2^(ke + n − 62)
        let t = self.depth_km as u64 * r as u64; // < 2^63
        let sh = self.depth_ke as i32 + n as i32 - 62;
        let kz = if sh <= 0 {
            shr_round(t as i64, (-sh) as u32) as u64
        } else {
            t.checked_shl(sh as u32)
                .filter(|v| v >> (64 - sh) == 0)
                .unwrap_or(u64::MAX)
        };
        let depth = self.depth_a.saturating_sub(kz).min(u32::MAX as u64) as u32;
        Ok((SubpixelPoint::new(sx as i32, sy as i32), depth))
    }

    /// Projects a clipped vertex, carrying its attributes.
    #[inline]
    pub fn project<const A: usize>(
        &self,
        v: &ClipVertex<A>,
    ) -> Result<ScreenVertex<S, A>, ProjectError> {
        let (point, depth) = self.project_point(v.pos)?;
        Ok(ScreenVertex {
            point,
            depth,
            attrs: v.attrs,
        })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::clip::frustum::{ClipError, ClipVolume, Frustum};
    use crate::geometry::camera::{FovAxis, Lens, Viewport};
    use crate::geometry::trig::BinaryAngle;
    use crate::test_rng::XorShift;
    use heapless::Vec;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
    }

    /// Orthographic cameras from a tiny view (huge scale) to a huge one (scale near 2^-16):
    /// the three outcodes agree, within and at the slab's planes, and points of the guard band
    /// project inside the raster's range.
    #[test]
    fn orthographic_frustum_outcodes_and_guard_band() {
        use crate::geometry::camera::OrthoView;
        let mut rng = crate::test_rng::XorShift(0x0DD_BA11u64);
        let mut rnd = || rng.next_u64();
        for (extent, w, h) in [
            (4.0, 320, 240),
            (0.01, 64, 32),
            (30000.0, 65535, 7),
            (1.0, 1, 1),
        ] {
            let view = OrthoView::new(
                Coord::from_num(extent),
                Coord::from_num(0.5),
                Coord::from_num(100),
            );
            let cam = Camera::orthographic(
                Vec3::ZERO,
                v(0.0, 0.0, 1.0),
                v(0.0, 1.0, 0.0),
                view,
                Viewport::new(w, h),
            )
            .unwrap();
            let f = Frustum::new::<4>(&cam, Frustum::DEFAULT_GUARD).unwrap();
            assert!(f.screen_affine());
            let proj: Projector<4> = Projector::new(&cam).unwrap();
            let (dx, dy) = (f.planes()[2].d as i64, f.planes()[4].d as i64);
            assert!(f.planes()[2].c == 0 && f.planes()[4].c == 0 && dx > 0 && dy > 0);
            let b = [(1u64 << 30) - 1; 3];
            assert!(f.narrow_fits(b), "{extent}");
            for i in 0..20000 {
                let shift = [0, 8, 14][i % 3];
                let r = |k: u64| (k as i32) >> shift;
                let mut p = Vec3::from_bits(r(rnd()), r(rnd()), r(rnd()));
                if i % 4 == 0 {
                    // On and next to the slab's planes.
                    let e = (rnd() % 3) as i64 - 1;
                    let [_, y, z] = p.bits();
                    p = Vec3::from_bits((dx + e) as i32 * if i % 8 == 0 { 1 } else { -1 }, y, z);
                }
                let code = f.outcode(p);
                assert_eq!(code, f.outcode_generic(p), "{p:?}");
                if p.bits().iter().all(|c| c.unsigned_abs() < 1 << 30) {
                    assert_eq!(f.outcode_narrow(p), code, "{p:?}");
                }
                if code == 0 {
                    assert!(proj.project_point(p).is_ok(), "{extent}: {p:?}");
                }
            }
        }
    }

    fn cv(x: f64, y: f64, z: f64, a: i32) -> ClipVertex<1> {
        ClipVertex::new(v(x, y, z), [a])
    }

    /// The 3D clipper's output projects: polygons crossing the near plane, behind the eye,
    /// spanning the view and beyond (cut to the guard band), and wholly inside.
    #[test]
    fn near_plane_crossing_behind_and_spanning() {
        let cam = camera();
        let f = Frustum::new::<4>(&cam, Frustum::DEFAULT_GUARD).unwrap();
        let proj: Projector<4> = Projector::new(&cam).unwrap();
        // Crosses the near plane (and the eye plane).
        let tri = [
            cv(0.0, 0.0, -2.0, 0),
            cv(0.3, 0.0, 3.0, 255),
            cv(-0.3, 0.2, 3.0, 255),
        ];
        let out: Vec<_, 9> = f.clip(&tri).unwrap();
        assert_eq!(out.len(), 4);
        for p in &out {
            assert!(p.pos.z >= Coord::from_num(0.5), "{p:?}");
            proj.project(p).unwrap();
        }
        // Wholly behind the eye.
        let back = [
            cv(0.0, 0.0, -2.0, 0),
            cv(1.0, 0.0, -3.0, 0),
            cv(0.0, 1.0, -1.0, 0),
        ];
        assert!(f.clip::<1, 9>(&back).unwrap().is_empty());
        // Spanning the whole view and beyond, at z = 5: cut to the guard band, all projectable.
        let big = [
            cv(-1000.0, -1000.0, 5.0, 0),
            cv(1000.0, -1000.0, 5.0, 0),
            cv(1000.0, 1000.0, 5.0, 0),
            cv(-1000.0, 1000.0, 5.0, 0),
        ];
        let out: Vec<_, 10> = f.clip(&big).unwrap();
        assert_eq!(out.len(), 4);
        for p in &out {
            let s = proj.project(p).unwrap();
            assert!(
                s.point.x.abs() < 16 * 160 * 6 && s.point.y.abs() < 16 * 160 * 6,
                "{s:?}"
            );
        }
        // Wholly inside: copied unchanged.
        let inside = [
            cv(0.0, 0.0, 2.0, 1),
            cv(0.1, 0.0, 2.0, 2),
            cv(0.0, 0.1, 2.0, 3),
        ];
        assert_eq!(f.clip::<1, 3>(&inside).unwrap().as_slice(), &inside);
        assert_eq!(f.clip::<1, 2>(&inside), Err(ClipError::CapacityExceeded));
    }

    fn camera() -> Camera {
        Camera::test_standard()
    }

    /// The depth constants equal the former u128 formulas `A = ⌊(n + span/2)/span⌋` and
    /// `K = ⌊(n·near + span/2)/span⌋` (`n = (2^32 − 1)·far`), normalised as before, from the
    /// nearest and farthest planes the range allows to random ones, or fail where they failed.
    #[test]
    fn depth_constants_match_the_u128_formulas() {
        let mut rng = crate::test_rng::XorShift(0x2545_F491_4F6C_DD1Du64);
        let mut rnd = |m: u64| rng.next_u64() % m;
        let edges = [1i32, 2, 3, 0x8000, 0x1_0000, 0x7FFF_FFFE, i32::MAX];
        let mut checked = [0usize; 2];
        for i in 0..20_000 {
            let (near, far) = if i < edges.len() * edges.len() {
                (edges[i % edges.len()], edges[i / edges.len()])
            } else {
                let a = 1 + rnd(i32::MAX as u64) as i32;
                let b = if i % 2 == 0 {
                    a.saturating_add(1 + rnd(1 << (i % 31)) as i32)
                } else {
                    1 + rnd(i32::MAX as u64) as i32
                };
                (a.min(b), a.max(b))
            };
            if near >= far {
                continue;
            }
            let mut cam = camera();
            let lens = Lens {
                near: Coord::from_bits(near),
                far: Coord::from_bits(far),
                ..*cam.lens()
            };
            cam = Camera::new(
                Vec3::ZERO,
                v(0.0, 0.0, 1.0),
                v(0.0, 1.0, 0.0),
                lens,
                *cam.viewport(),
            )
            .unwrap();
            let span = (far - near) as u128;
            let full = u32::MAX as u128;
            let a = (full * far as u128 + span / 2) / span;
            let k = (full * far as u128 * near as u128 + span / 2) / span;
            let bits = 128 - k.leading_zeros();
            let ke = bits.saturating_sub(32);
            let km = (k + ((1u128 << ke) >> 1)) >> ke;
            let (km, ke) = if km > u32::MAX as u128 {
                (km >> 1, ke + 1)
            } else {
                (km, ke)
            };
            match Projector::<4>::new(&cam) {
                Ok(p) => {
                    assert_eq!(
                        p.depth_constants(),
                        (a as u64, km as u32, ke),
                        "{near} {far}"
                    );
                    checked[0] += 1;
                }
                Err(e) => {
                    assert_eq!(e, ProjectError::OutOfRange);
                    assert!(a >= 1 << 61, "{near} {far}");
                    checked[1] += 1;
                }
            }
        }
        assert!(checked[0] > 5000 && checked[1] > 0, "{checked:?}");
    }

    /// The former 64-bit reciprocal, verbatim: the oracle [`reciprocal`] must equal.
    fn reciprocal_oracle(z: u32) -> (u32, u32) {
        if z == 0 {
            return (1 << 31, 32);
        }
        let n = z.leading_zeros();
        let zn = z << n;
        let d16 = (zn >> 16) + 1;
        let mut r = ((u32::MAX / d16) as u64) << 14;
        for _ in 0..2 {
            let prod = zn as u64 * r;
            let err = (1i64 << 62) - prod as i64;
            let e = err >> 30;
            r = (r as i64 + ((r as i64 * e) >> 32)) as u64;
        }
        (r.clamp(1 << 30, 1 << 31) as u32, n)
    }

    /// The former `project_point` (64-bit offsets and depth), verbatim apart from field names:
    /// the oracle the 32-bit fast path must equal bit for bit.
    fn project_oracle<const S: u32>(
        p: &Projector<S>,
        v: Vec3,
    ) -> Result<(SubpixelPoint<S>, u32), ProjectError> {
        fn offset(f_m: u32, shift: u32, c: i32, r: u32, n: u32) -> i64 {
            let k = ((f_m as u64 * r as u64) >> 32) as i32;
            let prod = c as i64 * k as i64;
            let t = shift as i32 - n as i32;
            if (33..=62).contains(&t) {
                let h = (prod >> 32) as i32;
                let b = (t - 32) as u32;
                ((h + (1 << (b - 1))) >> b) as i64
            } else if t > 62 {
                0
            } else if t >= 0 {
                shr_round(prod, t as u32)
            } else {
                prod * 2
            }
        }
        let [x, y, z] = v.bits();
        if z < p.near {
            return Err(ProjectError::BehindNearPlane);
        }
        let (r, n) = reciprocal_oracle(z as u32);
        let (fx_shift, fy_shift) = (p.fx_b.wrapping_add(33), p.fy_b.wrapping_add(33));
        let sx = p.i0 as i64 + offset(p.fx_m, fx_shift, x, r, n);
        let sy = p.j0 as i64 - offset(p.fy_m, fy_shift, y, r, n);
        let lim = MAX_COORD as i64;
        if sx.abs() > lim || sy.abs() > lim {
            return Err(ProjectError::OutOfRange);
        }
        let t = p.depth_km as u64 * r as u64;
        let sh = p.depth_ke as i32 + n as i32 - 62;
        let kz = if sh <= 0 {
            shr_round(t as i64, (-sh) as u32) as u64
        } else {
            t.checked_shl(sh as u32)
                .filter(|v| v >> (64 - sh) == 0)
                .unwrap_or(u64::MAX)
        };
        let depth = p.depth_a.saturating_sub(kz).min(u32::MAX as u64) as u32;
        Ok((SubpixelPoint::new(sx as i32, sy as i32), depth))
    }

    /// A 32-bit draw of the workspace's test generator.
    fn xorshift(s: &mut XorShift) -> u32 {
        s.next_u64() as u32
    }

    /// The reciprocal depends on `z` through `z_n = z·2^n` only: every `z_n` near both ends of
    /// `[2^31, 2^32)` (where the seed's and the clamp's edge cases are), a regular sweep of
    /// the rest, and random `z` of every magnitude.
    #[test]
    fn reciprocal_matches_64_bit_oracle() {
        let check = |z: u32| assert_eq!(reciprocal(z), reciprocal_oracle(z), "z={z}");
        for k in 0..1u32 << 18 {
            check((1 << 31) + k);
            check(u32::MAX - k);
            check((1 << 31) + k * 8191); // spans [2^31, 2^32) in 2^18 steps
        }
        let mut s = XorShift::new(99);
        for _ in 0..200_000 {
            let x = xorshift(&mut s);
            check(x >> (x % 32));
        }
        for z in 0..5000 {
            check(z);
        }
    }

    /// All 2^31 normalised inputs (about 20 s in release): `cargo test --release -p zscan
    /// reciprocal_matches -- --ignored`.
    #[test]
    #[ignore]
    fn reciprocal_matches_64_bit_oracle_everywhere() {
        for zn in 1u32 << 31..=u32::MAX {
            assert_eq!(reciprocal(zn), reciprocal_oracle(zn), "zn={zn}");
        }
    }

    /// `project_point` (32-bit fast path and general path) against the former 64-bit code on
    /// many cameras (fields of view, viewport sizes, pixel shapes, near/far) at every `S`
    /// the raster takes, with `z` over every magnitude from `near` up and `x`, `y` from 0 to
    /// the I16F16 extremes (in range, out of range, and the general path all reached).
    #[test]
    fn project_point_matches_64_bit_oracle() {
        check_oracle::<0>(1);
        check_oracle::<2>(2);
        check_oracle::<4>(3);
        check_oracle::<8>(4);
        check_oracle::<12>(5);
        check_oracle::<16>(6);
    }

    fn check_oracle<const S: u32>(seed: u32) {
        let mut s = XorShift::new(seed as u64);
        let (mut fast, mut general, mut out) = (0u32, 0u32, 0u32);
        let mut cameras = 0;
        while cameras < 60 {
            let fov = 1 + xorshift(&mut s) % 179;
            let (w, h) = (
                1 + (xorshift(&mut s) % 4096) as u16,
                1 + (xorshift(&mut s) % 4096) as u16,
            );
            let near_raw = 1 + (xorshift(&mut s) >> (xorshift(&mut s) % 32)) as i32 % (1 << 22);
            let far_raw = near_raw.saturating_add(
                1 + (xorshift(&mut s) >> (xorshift(&mut s) % 32)) as i32 % i32::MAX,
            );
            let lens = Lens {
                fov: BinaryAngle::from_degrees(fov as i32),
                axis: [FovAxis::Vertical, FovAxis::Horizontal, FovAxis::Diagonal]
                    [cameras as usize % 3],
                near: Coord::from_bits(near_raw),
                far: Coord::from_bits(far_raw),
            };
            let mut vp = Viewport::new(w, h);
            if cameras % 4 == 1 {
                (vp.pixel_width, vp.pixel_height) = (3, 2);
            }
            let Ok(cam) = Camera::new(Vec3::ZERO, v(0.0, 0.0, 1.0), v(0.0, 1.0, 0.0), lens, vp)
            else {
                continue;
            };
            let Ok(p) = Projector::<S>::new(&cam) else {
                continue;
            };
            cameras += 1;
            for i in 0..4000 {
                let z = match i % 4 {
                    0 => near_raw.saturating_add(
                        (xorshift(&mut s) >> (xorshift(&mut s) % 32)) as i32 & i32::MAX,
                    ),
                    1 => (xorshift(&mut s) >> (xorshift(&mut s) % 32)) as i32 & i32::MAX,
                    2 => near_raw.saturating_add((xorshift(&mut s) % 64) as i32),
                    _ => i32::MAX - (xorshift(&mut s) % 64) as i32,
                };
                let mut c = || match xorshift(&mut s) % 8 {
                    0 => 0,
                    1 => i32::MIN,
                    2 => i32::MAX,
                    _ => (xorshift(&mut s) as i32) >> (xorshift(&mut s) % 32),
                };
                let q = Vec3::from_bits(c(), c(), z);
                let got = p.project_point(q);
                assert_eq!(got, project_oracle(&p, q), "S={S} {cam:?} {q:?}");
                if z >= p.near {
                    let (_, n) = reciprocal(z as u32);
                    let t = |b: u32| b.wrapping_sub(n) < 30;
                    if t(p.fx_b) && t(p.fy_b) && p.depth_b.wrapping_sub(n) <= 30 {
                        fast += 1;
                    } else {
                        general += 1;
                    }
                    out += (got == Err(ProjectError::OutOfRange)) as u32;
                }
            }
        }
        assert!(
            fast > 10_000 && general > 1_000 && out > 1_000,
            "{fast} {general} {out}"
        );
    }

    #[test]
    fn reciprocal_is_within_two_units() {
        let mut x: u32 = 12345;
        let check = |z: u32| {
            if z == 0 {
                return;
            }
            let (r, n) = reciprocal(z);
            let exact = (1u128 << 62) / ((z as u128) << n);
            let e = exact as i128 - r as i128;
            assert!(
                (0..=2).contains(&e) || (exact == 1 << 31 && e == 0),
                "z={z} e={e}"
            );
        };
        for z in 1..5000 {
            check(z);
        }
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            check(x | 1);
            check(x >> (x % 31));
        }
        check(u32::MAX);
        check(1 << 31);
        check((1 << 31) + 1);
    }

    #[test]
    fn centre_corners_and_depth_ends() {
        let p: Projector<4> = Projector::new(&camera()).unwrap();
        let (c, d) = p.project_point(v(0.0, 0.0, 0.5)).unwrap();
        assert_eq!(c, SubpixelPoint::new(2552, 1912));
        assert!(d <= 4, "{d}");
        let (_, d) = p.project_point(v(0.0, 0.0, 10.0)).unwrap();
        assert!(d >= u32::MAX - 4, "{d}");
        let (_, d) = p.project_point(v(0.0, 0.0, 100.0)).unwrap();
        assert_eq!(d, u32::MAX);
        // Top edge of the 60° view: y = z·tan 30° projects to j0 − 120 px.
        let t = 30f64.to_radians().tan();
        let (q, _) = p.project_point(v(0.0, 2.0 * t, 2.0)).unwrap();
        assert!((q.y - (1912 - 120 * 16)).abs() <= 1, "{q:?}");
        assert_eq!(
            p.project_point(v(0.0, 0.0, 0.4999)),
            Err(ProjectError::BehindNearPlane)
        );
        assert_eq!(
            p.project_point(v(0.0, 0.0, -3.0)),
            Err(ProjectError::BehindNearPlane)
        );
        assert!(p.project_point(v(30000.0, 0.0, 0.5)).is_ok()); // 199.5 M units: in range
        let p8: Projector<8> = Projector::new(&camera()).unwrap();
        assert_eq!(
            p8.project_point(v(30000.0, 0.0, 0.5)),
            Err(ProjectError::OutOfRange)
        );
        assert_eq!(
            p8.project_point(v(0.0, -30000.0, 0.5)),
            Err(ProjectError::OutOfRange)
        );
        let p16: Projector<16> = Projector::new(&camera()).unwrap();
        let extreme = Vec3::from_bits(i32::MIN, i32::MAX, 32768);
        assert_eq!(p16.project_point(extreme), Err(ProjectError::OutOfRange));
        let (q, _) = p16
            .project_point(Vec3::from_bits(i32::MIN, 0, i32::MAX))
            .unwrap();
        assert_eq!(q.y, 119 * 65536 + 32768);
        assert!(Projector::<17>::new(&camera()).is_err());
    }

    /// The parallel projection against `f64`, on views from tiny to huge, square and
    /// non-square pixels, every sub-pixel precision: positions within
    /// `0.5 + |offset|·2^-30` units of 2^-S pixel, depth **equal** to the correctly rounded
    /// `(2^32 − 1)·(z − near)/(far − near)` (exact integers), clamped beyond far.
    #[test]
    fn orthographic_against_f64() {
        fn check<const S: u32>(seed: u64) {
            use crate::geometry::camera::OrthoView;
            let mut rng = XorShift::new(seed);
            let mut checked = 0;
            for (extent, axis, w, h, pw, ph, near, far) in [
                (
                    4.0,
                    FovAxis::Vertical,
                    320u16,
                    240u16,
                    1u16,
                    1u16,
                    0.5,
                    10.0,
                ),
                (3.0, FovAxis::Horizontal, 128, 64, 1, 1, 0.001, 30000.0),
                (
                    0.02,
                    FovAxis::Diagonal,
                    100,
                    37,
                    3,
                    2,
                    1.0,
                    1.0 + 2f64.powi(-16),
                ),
                (20000.0, FovAxis::Vertical, 4000, 3000, 1, 1, 2.0, 7.0),
            ] {
                let view = OrthoView {
                    extent: Coord::from_num(extent),
                    axis,
                    near: Coord::from_num(near),
                    far: Coord::from_num(far),
                };
                let mut vp = Viewport::new(w, h);
                (vp.pixel_width, vp.pixel_height) = (pw, ph);
                let cam =
                    Camera::orthographic(Vec3::ZERO, v(0.0, 0.0, 1.0), v(0.0, 1.0, 0.0), view, vp)
                        .unwrap();
                let p = Projector::<S>::new(&cam).unwrap();
                assert!(p.is_orthographic());
                // Exact scales in pixels per unit: 2r/(extent·pixel size).
                let (wp, hp) = (w as f64 * pw as f64, h as f64 * ph as f64);
                let r = match axis {
                    FovAxis::Vertical => hp / 2.0,
                    FovAxis::Horizontal => wp / 2.0,
                    // The camera's half-diagonal, rounded down to 2^-11 physical units.
                    FovAxis::Diagonal => {
                        (((wp * wp + hp * hp) * 4194304.0).sqrt().floor()) / 2048.0 / 2.0
                    }
                };
                let extent = view.extent.to_num::<f64>(); // as stored
                let (sx, sy) = (
                    2.0 * r / (extent * pw as f64),
                    2.0 * r / (extent * ph as f64),
                );
                let unit = (1u64 << S) as f64;
                let (near_raw, far_raw) = (view.near.to_bits() as i64, view.far.to_bits() as i64);
                for i in 0..20_000 {
                    let c = |rng: &mut XorShift| (rng.next_u64() as i32) >> (rng.next_u64() % 31);
                    let z = match i % 3 {
                        0 => near_raw + (rng.next_u64() % (far_raw - near_raw + 1) as u64) as i64,
                        1 => near_raw + (rng.next_u64() % 4) as i64,
                        _ => (far_raw - 2 + (rng.next_u64() % 5) as i64).max(near_raw),
                    };
                    let q =
                        Vec3::from_bits(c(&mut rng), c(&mut rng), z.min(i32::MAX as i64) as i32);
                    let [x, y, z] = q.bits();
                    let ex = p.principal().x as f64 + sx * x as f64 / 65536.0 * unit;
                    let ey = p.principal().y as f64 - sy * y as f64 / 65536.0 * unit;
                    match p.project_point(q) {
                        Ok((pt, d)) => {
                            let allow = |o: f64| 0.5 + o.abs() * 2f64.powi(-30) + 1e-6;
                            assert!(
                                (pt.x as f64 - ex).abs() <= allow(ex - p.principal().x as f64),
                                "S={S} {q:?} {pt:?} {ex}"
                            );
                            assert!(
                                (pt.y as f64 - ey).abs() <= allow(ey - p.principal().y as f64),
                                "S={S} {q:?} {pt:?} {ey}"
                            );
                            let (v, span) =
                                ((z as i64 - near_raw) as u128, (far_raw - near_raw) as u128);
                            let want = if v >= span {
                                u32::MAX as u128
                            } else {
                                (v * u32::MAX as u128 + span / 2) / span
                            };
                            assert_eq!(d as u128, want, "S={S} {q:?}");
                            checked += 1;
                        }
                        Err(e) => {
                            assert_eq!(e, ProjectError::OutOfRange);
                            let lim = MAX_COORD as f64;
                            assert!(ex.abs() > lim - 1.0 || ey.abs() > lim - 1.0, "S={S} {q:?}");
                        }
                    }
                }
                assert_eq!(
                    p.project_point(Vec3::from_bits(0, 0, near_raw as i32 - 1)),
                    Err(ProjectError::BehindNearPlane)
                );
            }
            assert!(checked > 20_000, "{checked}");
        }
        check::<0>(1);
        check::<4>(2);
        check::<8>(3);
        check::<16>(4);
    }

    #[test]
    fn against_f64() {
        check_against_f64::<0>();
        check_against_f64::<4>();
        check_against_f64::<8>();
        check_against_f64::<16>();
    }

    /// Random points (z from near to 20.5, |x|, |y| up to 2^5 units) against `f64`: positions
    /// within `0.5 + |offset|·2^-26` units of 2^-S pixel, depth within 64 units of 2^-32.
    fn check_against_f64<const S: u32>() {
        let p: Projector<S> = Projector::new(&camera()).unwrap();
        let (near, far) = (0.5f64, 10.0f64);
        let unit = (1u64 << S) as f64;
        let lim = crate::raster::triangle::edge_walker::MAX_COORD as f64;
        let fx = camera().focal_x().to_num::<f64>();
        let mut s: u32 = 7;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        };
        let (mut worst_xy, mut worst_d) = (0.0f64, 0.0f64);
        for i in 0..100_000 {
            let z_raw = 32768 + (next() % (20 << 16)) as i32;
            let shift = 10 + i % 16;
            let x_raw = (next() as i32) >> shift;
            let y_raw = (next() as i32) >> shift;
            let q = Vec3::from_bits(x_raw, y_raw, z_raw);
            let (x, y, z) = (
                x_raw as f64 / 65536.0,
                y_raw as f64 / 65536.0,
                z_raw as f64 / 65536.0,
            );
            // The principal point as stored (159.5 rounds to 160 at S = 0).
            let sx = p.principal().x as f64 + fx * x / z * unit;
            let sy = p.principal().y as f64 - fx * y / z * unit;
            match p.project_point(q) {
                Ok((pt, d)) => {
                    // Rounding (0.5) plus the relative error of r and k (< 2^-26 of the offset).
                    let allow = |o: f64| 0.5 + o.abs() / (1u64 << 26) as f64;
                    let ex = (pt.x as f64 - sx).abs() - allow(sx - p.principal().x as f64);
                    let ey = (pt.y as f64 - sy).abs() - allow(sy - p.principal().y as f64);
                    worst_xy = worst_xy.max(ex).max(ey);
                    let dd =
                        (4294967295.0 * far * (z - near) / (z * (far - near))).min(4294967295.0);
                    worst_d = worst_d.max((d as f64 - dd).abs());
                }
                Err(e) => {
                    assert_eq!(e, ProjectError::OutOfRange);
                    assert!(sx.abs() > lim - 1.0 || sy.abs() > lim - 1.0, "S={S} {q:?}");
                }
            }
        }
        assert!(
            worst_xy <= 0.51,
            "S={S}: xy error {worst_xy} units of 2^-S pixel"
        );
        assert!(worst_d <= 64.0, "S={S}: depth error {worst_d}");
    }
}
