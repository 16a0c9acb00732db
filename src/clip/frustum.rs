//! Sutherland–Hodgman polygon clipping in 3D (course exercise 12), against any plane
//! `a·x + b·y + c·z + d ≥ 0` of the observer frame, and the view [`Frustum`] built from them.
//!
//! Role in the pipeline: after the world → observer transform and back-face culling, before
//! [`project`](crate::project). One clipper, [`clip_to_plane`], serves every plane:
//! - the **near** plane `z ≥ near`, which makes projection safe (no `z ≤ 0`);
//! - the **far** plane `z ≤ far`;
//! - four **side** planes widened to a *guard band* ([`Frustum::new`]): polygons are only cut
//!   when they reach far outside the screen, which keeps every projected coordinate inside the
//!   2D fill's range (`|x|, |y| ≤ 2^28 − 1` sub-pixel units) while the fill's own window
//!   clipping does the exact cut at the screen edge. Most polygons that cross the screen edge
//!   are therefore not clipped in 3D at all.
//!
//! ## Vertices and attributes
//! A [`ClipVertex<A>`] carries its observer-frame position and `A` integer attributes
//! (intensity, …). At an intersection whose two ends are in front of the eye the attributes
//! take the value of the *screen-affine* interpolant at the new vertex's projection (what the
//! raster interpolates), so a cut by the guard band or the far plane does not change the
//! shading; at the near plane (an end behind the eye) they are interpolated along the 3D edge.
//!
//! ## Numeric contract
//! - Plane coefficients `a, b, c` are [`Coord`] with `|a|, |b|, |c| ≤ 8192` (raw `≤ 2^29`),
//!   `d` any [`Coord`]. A signed distance `a·x + b·y + c·z + d` is computed exactly in Q32
//!   `i64`: three products `≤ 2^29·2^31 = 2^60` plus `d·2^16 < 2^47` stay below 2^63.
//! - An intersection is always computed **from the inside endpoint** `P` toward the outside one
//!   `Q`, so the two polygons sharing an edge get the same point (no cracks). With distances
//!   `d_P ≥ 0 > d_Q`, both are scaled down by the same power of two until their sum is below
//!   2^30, rounding `d_P` down and `|d_Q|` up: the parameter `t' = d_P'/(d_P' + |d_Q|')` never
//!   exceeds the exact `t`. Each coordinate (and attribute) is `P + trunc(Δ·d_P'/den)` with
//!   `|Δ| ≤ 2^32` and `d_P' < 2^30` (product `< 2^62`), truncated toward `P`. Hence a new vertex
//!   lies between `P` and `Q` component-wise, and **for an axis-aligned plane such as the near
//!   plane it is never on the outside**: clipped vertices always satisfy `z ≥ near` exactly.
//!   For oblique planes (the side planes) it may be outside by less than one raw unit per
//!   coordinate, which the guard band's margin absorbs.
//! - **Near-plane precision.** The parameter error is `t − t' < 2^-29` (zero when `k = 0`),
//!   so a clipped vertex is within `ε = |Δ|·2^-29 + 1` raw units (2^-16 world units) of the
//!   exact intersection of the (I16F16) edge with the plane, per coordinate. At `z = near` its
//!   projection `f·x/z` is then within `f·(ε_x + |x/z|·ε_z)/near_raw` pixels of the exact
//!   one (`near_raw` = near in raw units): the error grows as `1/near`. With `near = 0.002`
//!   (131 raw units) and `f = 207.85` px (60° over 240 rows), one raw unit is 1.59 px, and
//!   random edges measured up to **1.54 px** on screen (`|x/z| < 1`; test
//!   `near_plane_clip_points_stay_within_the_documented_bound`), so edges cut by the near
//!   plane may sit that far off the exact near-clip line. For sub-pixel accuracy keep
//!   `near_raw ≫ f`, e.g. `near ≥ f/6554` world units for 0.1 px per raw unit (0.032 at
//!   `f = 208`; SCENES.md's 0.5 gives 0.006 px).
//! - Capacity: the output is a `heapless::Vec<_, N>`; a polygon that would need more than `N`
//!   vertices is [`ClipError::CapacityExceeded`], never truncated. Output with fewer than three
//!   vertices (a polygon that only touches the volume) is returned empty.
//!
//! ## How many vertices clipping can add
//! One plane turns an `n`-gon with `k` vertices inside and `c` edges crossing the plane into
//! `k + c` vertices. A **convex** polygon crosses a plane at most twice (`c ≤ 2`, `k ≤ n − 1`
//! when it crosses), so each plane adds at most one vertex: `n + 6` after the six planes. A
//! **non-convex** polygon can cross a plane on every edge: with `c ≤ min(n, 2k, 2(n − k))`,
//! `k + c ≤ ⌊3n/2⌋`, so one plane can add up to `⌊n/2⌋` vertices (a 24-vertex comb whose teeth
//! reach through the near plane becomes 36), and six planes up to `n·(3/2)^6 ≈ 11.4·n`, which
//! no fixed stack buffer of a microcontroller should hold. [`ClipVolume::clip`] therefore
//! reports [`ClipError::CapacityExceeded`] for such polygons, and [`ClipVolume::clip_fan`] draws
//! them anyway: when the polygon's clip does not fit it clips each fan triangle
//! `(P_0, P_k, P_{k+1})` instead (a triangle is convex: at most 9 vertices), which covers
//! exactly what the renderer's fan from `P_0` covers for a polygon that needs no clipping.

use heapless::Vec;

use crate::arith::wide::mul_wide;
use crate::geometry::camera::Camera;
use crate::geometry::fixed::Coord;
use crate::geometry::vector::Vec3;
use crate::raster::triangle::edge_walker::MAX_COORD;

/// A polygon vertex in the observer frame with `A` integer attributes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ClipVertex<const A: usize> {
    /// Observer-frame position (x right, y up, z forward).
    pub pos: Vec3,
    /// Attributes interpolated at intersections.
    pub attrs: [i32; A],
}

impl<const A: usize> ClipVertex<A> {
    /// A vertex at `pos` with attributes `attrs`.
    pub const fn new(pos: Vec3, attrs: [i32; A]) -> Self {
        ClipVertex { pos, attrs }
    }
}

/// Largest polygon (vertex count) the 3D pipeline clips: the renderer's polygon stage and the
/// shadow map's pass 1 reject larger ones.
pub const MAX_POLYGON_VERTICES: usize = 24;

/// Vertices a clipped polygon of at most [`MAX_POLYGON_VERTICES`] may reach: each of the 6
/// planes adds at most one vertex to a convex polygon.
pub const CLIP_CAPACITY: usize = MAX_POLYGON_VERTICES + 6;

/// What went wrong clipping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClipError {
    /// The input or an intermediate polygon has more vertices than the capacity `N`.
    CapacityExceeded,
    /// A plane coefficient `a`, `b` or `c` exceeds ±8192.
    PlaneOutOfRange,
}

/// Largest raw plane coefficient (8192.0 in I16F16).
pub const MAX_PLANE_COEFF_BITS: i32 = 1 << 29;

/// The half-space `a·x + b·y + c·z + d ≥ 0` (inside) of the observer frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Plane {
    a: i32,
    b: i32,
    pub(crate) c: i32,
    pub(crate) d: i32,
}

impl Plane {
    /// The plane `a·x + b·y + c·z + d ≥ 0`; `|a|, |b|, |c| ≤ 8192`.
    pub fn new(a: Coord, b: Coord, c: Coord, d: Coord) -> Result<Plane, ClipError> {
        let ok = |v: Coord| v.to_bits().unsigned_abs() <= MAX_PLANE_COEFF_BITS as u32;
        if !(ok(a) && ok(b) && ok(c)) {
            return Err(ClipError::PlaneOutOfRange);
        }
        Ok(Plane {
            a: a.to_bits(),
            b: b.to_bits(),
            c: c.to_bits(),
            d: d.to_bits(),
        })
    }

    /// Signed distance (scaled by the normal's length) in Q32: `≥ 0` inside.
    #[inline(always)]
    pub fn distance(&self, p: Vec3) -> i64 {
        let [x, y, z] = p.bits();
        self.a as i64 * x as i64
            + self.b as i64 * y as i64
            + self.c as i64 * z as i64
            + ((self.d as i64) << 16)
    }

    /// True when `p` is inside (distance `≥ 0`).
    pub fn contains(&self, p: Vec3) -> bool {
        self.distance(p) >= 0
    }
}

/// The intersection of edge `p`–`q` with the plane, from the inside endpoint `p`
/// (`dp ≥ 0 > dq`); see the module doc. Bit `i` of `space_linear` set: attribute `i` is linear
/// in the observer frame (a texture coordinate), not in screen space.
fn intersect<const A: usize>(
    p: &ClipVertex<A>,
    q: &ClipVertex<A>,
    dp: i64,
    dq: i64,
    affine: bool,
    space_linear: u8,
) -> ClipVertex<A> {
    let dp = dp.unsigned_abs();
    let dq = dq.unsigned_abs();
    let total = dp + dq; // both < 2^63 / 2, see Plane::distance
    let bits = 64 - total.leading_zeros();
    let k = bits.saturating_sub(30);
    let a = (dp >> k) as i64;
    let b = ((dq + (1u64 << k) - 1) >> k) as i64; // ≥ 1 since dq > 0
    let den = a + b;
    let lerp = |from: i32, to: i32| -> i32 {
        let delta = to as i64 - from as i64;
        (from as i64 + delta * a / den) as i32 // between from and to
    };
    let pp = p.pos.bits();
    let qq = q.pos.bits();
    let pos = Vec3::from_bits(lerp(pp[0], qq[0]), lerp(pp[1], qq[1]), lerp(pp[2], qq[2]));
    // Attributes. When both ends are in front of the eye (side and far planes), the raster
    // interpolates attributes affinely in *screen* space, so the clip point takes the value of
    // that screen-affine interpolant at its projection: screen parameter
    // s = t·z_q / z(t) (z(t) = the new vertex's z), rounded to nearest. Otherwise (the near
    // plane, an end behind the eye) there is no screen interpolant to keep: linear in 3D.
    // Under a parallel projection (`affine`) the screen parameter is `t` itself: linear in 3D.
    // Attributes linear in the observer frame (`space_linear`: texture coordinates, which the
    // raster interpolates perspective-correctly) take the 3D parameter `t` at every plane.
    let z_new = pos.bits()[2] as i128;
    let attrs = if !affine && pp[2] > 0 && qq[2] > 0 && z_new > 0 {
        let (num, den) = (a as i128 * qq[2] as i128, den as i128 * z_new);
        core::array::from_fn(|i| {
            if space_linear >> i & 1 != 0 {
                return lerp(p.attrs[i], q.attrs[i]);
            }
            let delta = q.attrs[i] as i128 - p.attrs[i] as i128;
            // delta < 2^33, num < 2^61: the product < 2^94; round half up.
            let scaled = (2 * delta * num + den).div_euclid(2 * den);
            (p.attrs[i] as i128 + scaled) as i32
        })
    } else {
        core::array::from_fn(|i| lerp(p.attrs[i], q.attrs[i]))
    };
    ClipVertex { pos, attrs }
}

/// Clips the closed polygon `input` to the inside of `plane`, appending the result to `out`
/// (Sutherland–Hodgman, one plane). `out` is cleared first. `affine` is true when the result
/// is projected in parallel (an orthographic camera): the attributes of new vertices then
/// follow that projection's screen interpolant (see `intersect`). Bit `i` of `space_linear`
/// set: attribute `i` is linear in the observer frame (a texture coordinate) and new vertices
/// take its value along the 3D edge at every plane.
pub fn clip_to_plane<const A: usize, const N: usize>(
    plane: &Plane,
    input: &[ClipVertex<A>],
    out: &mut Vec<ClipVertex<A>, N>,
    affine: bool,
    space_linear: u8,
) -> Result<(), ClipError> {
    out.clear();
    let Some(last) = input.last() else {
        return Ok(());
    };
    let mut s = last;
    let mut ds = plane.distance(s.pos);
    for e in input {
        let de = plane.distance(e.pos);
        match (ds >= 0, de >= 0) {
            (true, true) => out.push(*e).map_err(|_| ClipError::CapacityExceeded)?,
            (true, false) => out
                .push(intersect(s, e, ds, de, affine, space_linear))
                .map_err(|_| ClipError::CapacityExceeded)?,
            (false, true) => {
                out.push(intersect(e, s, de, ds, affine, space_linear))
                    .map_err(|_| ClipError::CapacityExceeded)?;
                out.push(*e).map_err(|_| ClipError::CapacityExceeded)?;
            }
            (false, false) => {}
        }
        s = e;
        ds = de;
    }
    Ok(())
}

/// Clips the segment `p`–`q` to the inside of the six `planes` (a 3D line of
/// `render::lines`): `None` when no part of it is inside. Each plane one of its ends is
/// outside of moves that end to the intersection, computed from the inside end by the
/// polygons' own `intersect` (module doc): on the near plane exactly (`z ≥ near` always
/// holds), on an oblique side plane within one raw unit, which the guard band absorbs. `code`
/// gives the outcode of a point against the same planes (bit `i` for plane `i`).
pub(crate) fn clip_segment(
    planes: &[Plane; 6],
    code: impl Fn(Vec3) -> u8,
    p: Vec3,
    q: Vec3,
) -> Option<(Vec3, Vec3)> {
    let (cp, cq) = (code(p), code(q));
    if cp & cq != 0 {
        return None;
    }
    let (mut a, mut b) = (ClipVertex::new(p, []), ClipVertex::new(q, []));
    for (i, plane) in planes.iter().enumerate() {
        if (cp | cq) & (1 << i) == 0 {
            continue;
        }
        let (da, db) = (plane.distance(a.pos), plane.distance(b.pos));
        match (da >= 0, db >= 0) {
            (true, true) => {}
            (false, false) => return None,
            (true, false) => b = intersect::<0>(&a, &b, da, db, false, 0),
            (false, true) => a = intersect::<0>(&b, &a, db, da, false, 0),
        }
    }
    Some((a.pos, b.pos))
}

/// The view volume: near, far and four guard-band side planes (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Frustum {
    planes: [Plane; 6],
    /// The camera is orthographic: the screen is affine in the observer frame.
    affine: bool,
}

/// Index of the near plane in [`Frustum::planes`] (bit 0 of an outcode).
pub const NEAR: usize = 0;
/// Index of the far plane (bit 1).
pub const FAR: usize = 1;

impl Frustum {
    /// The default guard factor: side planes at 4 times the screen's half-extent.
    pub const DEFAULT_GUARD: u16 = 4;

    /// The frustum of `camera`, for a projection at `S` sub-pixel bits, with side planes at
    /// `guard` (≥ 1) times the larger distance from the principal point to a screen edge.
    ///
    /// The guard extent is capped at half of what the raster's range leaves at `S` bits
    /// (`(2^28 − 1)/2^S` pixels minus the principal point), so that projected guard-band
    /// vertices stay inside the range with a wide margin for rounding.
    pub fn new<const S: u32>(camera: &Camera, guard: u16) -> Result<Frustum, ClipError> {
        let lens = camera.lens();
        let vp = camera.viewport();
        let guard = guard.max(1) as i64;
        let one = Coord::from_bits(1 << 16);
        let zero = Coord::ZERO;
        // Extents in Q16 pixels.
        let half = 1i64 << 15;
        // The guard extent `g` in Q16 pixels along one axis.
        let extent = |p: Coord, n: u16| -> i64 {
            let p = p.to_bits() as i64;
            let e = (p + half).max(((n as i64) << 16) - half - p).max(1 << 16);
            let range = ((MAX_COORD as i64) >> S.min(16)) << 16; // Q16 pixels
            let cap = ((range - p.abs()) / 2).max(1 << 16);
            (e * guard).min(cap)
        };
        let (gx, gy) = (
            extent(vp.principal_x, vp.width),
            extent(vp.principal_y, vp.height),
        );
        let p = Plane::new;
        let (near, far) = (
            p(zero, zero, one, -lens.near)?,
            p(zero, zero, -one, lens.far)?,
        );
        let planes = match camera.ortho_scales() {
            None => {
                // c = g / f in Q16, rounded down (a slightly narrower band is always safe).
                let side = |g: i64, f: Coord| -> Coord {
                    let c = (g << 16) / (f.to_bits().max(1) as i64);
                    Coord::from_bits(c.clamp(1, MAX_PLANE_COEFF_BITS as i64) as i32)
                };
                let cx = side(gx, camera.focal_x());
                let cy = side(gy, camera.focal_y());
                [
                    near,
                    far,
                    p(one, zero, cx, zero)?,
                    p(-one, zero, cx, zero)?,
                    p(zero, one, cy, zero)?,
                    p(zero, -one, cy, zero)?,
                ]
            }
            Some([(nx, dx), (ny, dy)]) => {
                // Orthographic: the slab |x| ≤ g / s_x world units, rounded down, below
                // 2^30 raw (so that the narrow outcode's sums stay in `i32`); a point beyond
                // 2^30 raw is never inside the guard band of a scale ≥ 2^-16 px per unit.
                let side = |g: i64, num: u128, den: u128| -> Coord {
                    let d = (g as u128 * den) / num.max(1); // g < 2^45, den < 2^47
                    Coord::from_bits(d.clamp(1, (1 << 30) - 1) as i32)
                };
                let dx = side(gx, nx, dx);
                let dy = side(gy, ny, dy);
                [
                    near,
                    far,
                    p(one, zero, zero, dx)?,
                    p(-one, zero, zero, dx)?,
                    p(zero, one, zero, dy)?,
                    p(zero, -one, zero, dy)?,
                ]
            }
        };
        Ok(Frustum {
            planes,
            affine: camera.is_orthographic(),
        })
    }

    /// The planes: near, far, left, right, bottom, top.
    pub fn planes(&self) -> &[Plane; 6] {
        &self.planes
    }

    /// Bit `i` set when `p` is outside plane `i`.
    ///
    /// The planes have the shapes [`Frustum::new`] gives them (`z − near`, `far − z`,
    /// `±x + cx·z + dx`, `±y + cy·z + dy`, with `d = 0` for a perspective camera and `c = 0`
    /// for an orthographic one), so each distance is formed from its non-zero terms only: the
    /// same `i64` values as `Plane::distance` (tested) with two multiplies instead of
    /// eighteen — this runs once per vertex per frame.
    #[inline]
    pub fn outcode(&self, p: Vec3) -> u8 {
        let [x, y, z] = p.bits();
        let p = &self.planes;
        let (x, y, z) = ((x as i64) << 16, (y as i64) << 16, z as i64);
        let zn = (z << 16) + ((p[NEAR].d as i64) << 16); // z − near
        let zf = ((p[FAR].d as i64) << 16) - (z << 16); // far − z
        let cxz = p[2].c as i64 * z + ((p[2].d as i64) << 16);
        let cyz = p[4].c as i64 * z + ((p[4].d as i64) << 16);
        ((zn < 0) as u8)
            | (((zf < 0) as u8) << 1)
            | (((x + cxz < 0) as u8) << 2)
            | (((cxz - x < 0) as u8) << 3)
            | (((y + cyz < 0) as u8) << 4)
            | (((cyz - y < 0) as u8) << 5)
    }

    /// True when [`Frustum::outcode_narrow`] equals [`Frustum::outcode`] for every point whose
    /// raw coordinates satisfy `|x| ≤ bound[0]`, `|y| ≤ bound[1]`, `|z| ≤ bound[2]`: all three
    /// below `2^30`, `c·bound[2] + |d|·2^16 < 2^46` for both side planes (so
    /// `|⌊c·z / 2^16⌋ + d| ≤ 2^30`) and near and far `|d| ≤ 2^30`; then every sum below stays
    /// within `±2^31`. Once per object.
    pub fn narrow_fits(&self, bound: [u64; 3]) -> bool {
        let p = &self.planes;
        let side = |pl: &Plane| {
            let cz = (pl.c.unsigned_abs() as u64).saturating_mul(bound[2]);
            cz.saturating_add((pl.d.unsigned_abs() as u64) << 16) < 1 << 46
        };
        bound.iter().all(|&b| b < 1 << 30)
            && side(&p[2])
            && side(&p[4])
            && p[NEAR].d.unsigned_abs() <= 1 << 30
            && p[FAR].d.unsigned_abs() <= 1 << 30
    }

    /// [`Frustum::outcode`] in 32-bit arithmetic, for points within a bound that
    /// [`Frustum::narrow_fits`] accepted (outside it the code is unspecified, never a panic).
    ///
    /// Each plane distance is a multiple of `2^16` plus at most the product `c·z`, so its sign
    /// is decided on whole units: with `q = ⌊c·z / 2^16⌋ + d` (remainder `r ∈ [0, 2^16)`; the
    /// side planes' `d` is a whole number of raw units),
    /// `x·2^16 + c·z = (x + q)·2^16 + r < 0 ⟺ x + q < 0` and
    /// `c·z − x·2^16 < 0 ⟺ q − x < 0`; the near plane `(z + d)·2^16 < 0 ⟺ z + d < 0` and
    /// the far plane `(d − z)·2^16 < 0 ⟺ d − z < 0`. Within the bound the six sums do not
    /// overflow `i32`, so a plane's bit is its sum's sign bit, and a point is inside (code 0)
    /// when the OR of the six sums is not negative. Only `q` needs a 64-bit product.
    #[inline]
    pub fn outcode_narrow(&self, p: Vec3) -> u8 {
        let [x, y, z] = p.bits();
        let p = &self.planes;
        let qx = ((mul_wide(p[2].c, z) >> 16) as i32).wrapping_add(p[2].d);
        let qy = ((mul_wide(p[4].c, z) >> 16) as i32).wrapping_add(p[4].d);
        let s = [
            z.wrapping_add(p[NEAR].d),
            p[FAR].d.wrapping_sub(z),
            x.wrapping_add(qx),
            qx.wrapping_sub(x),
            y.wrapping_add(qy),
            qy.wrapping_sub(y),
        ];
        if s[0] | s[1] | s[2] | s[3] | s[4] | s[5] >= 0 {
            return 0;
        }
        let bit = |i: usize| ((s[i] as u32 >> 31) << i) as u8;
        bit(0) | bit(1) | bit(2) | bit(3) | bit(4) | bit(5)
    }

    /// [`Frustum::outcode`] from the six generic plane distances (the reference it is tested
    /// against).
    pub fn outcode_generic(&self, p: Vec3) -> u8 {
        self.planes.outcode(p)
    }
}

/// A convex volume bounded by six planes, bit `i` of an outcode set outside plane `i`: the
/// view [`Frustum`] (with its two-multiply outcode), or any six planes (the shadow map's
/// volume, with the generic plane distances). Clipping needs nothing else.
pub trait ClipVolume {
    /// The six planes.
    fn planes(&self) -> &[Plane; 6];

    /// True when the volume's points are projected in parallel (an orthographic camera's
    /// frustum): new vertices then take attributes linear in 3D at every plane.
    fn screen_affine(&self) -> bool {
        false
    }

    /// Bit `i` set when `p` is outside plane `i` (the generic plane distances).
    fn outcode(&self, p: Vec3) -> u8 {
        let mut code = 0;
        for (i, pl) in self.planes().iter().enumerate() {
            if pl.distance(p) < 0 {
                code |= 1 << i;
            }
        }
        code
    }

    /// Clips a polygon to the volume. Polygons wholly inside are copied, wholly outside one
    /// plane give an empty result; others are clipped against the planes they cross only, in
    /// the planes' order.
    fn clip<const A: usize, const N: usize>(
        &self,
        input: &[ClipVertex<A>],
    ) -> Result<Vec<ClipVertex<A>, N>, ClipError>
    where
        Self: Sized,
    {
        self.clip_attributes(input, 0)
    }

    /// [`clip`](ClipVolume::clip) with attributes `i` whose bit is set in `space_linear`
    /// linear in the observer frame (texture coordinates): new vertices take their value along
    /// the 3D edge, the others the screen interpolant's (module doc).
    fn clip_attributes<const A: usize, const N: usize>(
        &self,
        input: &[ClipVertex<A>],
        space_linear: u8,
    ) -> Result<Vec<ClipVertex<A>, N>, ClipError>
    where
        Self: Sized,
    {
        let mut any = 0u8;
        let mut all = 0xFFu8;
        for v in input {
            let c = self.outcode(v.pos);
            any |= c;
            all &= c;
        }
        let mut a: Vec<ClipVertex<A>, N> = Vec::new();
        if input.len() < 3 || (all != 0) {
            return Ok(a);
        }
        a.extend_from_slice(input)
            .map_err(|_| ClipError::CapacityExceeded)?;
        if any == 0 {
            return Ok(a);
        }
        let mut b: Vec<ClipVertex<A>, N> = Vec::new();
        for (i, pl) in self.planes().iter().enumerate() {
            if any & (1 << i) != 0 {
                clip_to_plane(pl, &a, &mut b, self.screen_affine(), space_linear)?;
                core::mem::swap(&mut a, &mut b);
                if a.len() < 3 {
                    a.clear();
                    return Ok(a);
                }
            }
        }
        Ok(a)
    }

    /// Clips a polygon to the volume and hands the result to `emit`, never failing for lack
    /// of capacity when `N ≥ 9` (module doc, "How many vertices clipping can add").
    ///
    /// Normally `emit` is called once with what [`Frustum::clip`] returns (nothing when that is
    /// empty), so convex polygons, and non-convex ones whose clip fits `N`, are clipped exactly
    /// as before. When the clipped polygon would exceed `N` vertices (only possible for a
    /// non-convex polygon), `emit` is instead called once per non-empty clipped fan triangle
    /// `(input[0], input[k], input[k + 1])`, `k = 1..n − 1`, in order: the same region as the
    /// fan of the unclipped polygon, cut by the frustum (each piece at most 9 vertices).
    ///
    /// Errors: [`ClipError::CapacityExceeded`] only when `input` itself exceeds `N` or `N < 9`
    /// for a fan triangle; `emit`'s own error stops the walk and is returned.
    /// Attributes whose bit is set in `space_linear` are linear in the observer frame
    /// ([`clip_attributes`](ClipVolume::clip_attributes)).
    fn clip_fan<const A: usize, const N: usize, E: From<ClipError>>(
        &self,
        input: &[ClipVertex<A>],
        space_linear: u8,
        mut emit: impl FnMut(&[ClipVertex<A>]) -> Result<(), E>,
    ) -> Result<(), E>
    where
        Self: Sized,
    {
        match self.clip_attributes::<A, N>(input, space_linear) {
            Ok(poly) if poly.is_empty() => Ok(()),
            Ok(poly) => emit(&poly),
            Err(ClipError::CapacityExceeded) if input.len() <= N => {
                for k in 1..input.len().saturating_sub(1) {
                    let tri = [input[0], input[k], input[k + 1]];
                    let piece = self.clip_attributes::<A, N>(&tri, space_linear)?;
                    if !piece.is_empty() {
                        emit(&piece)?;
                    }
                }
                Ok(())
            }
            Err(e) => Err(e.into()),
        }
    }
}

impl ClipVolume for [Plane; 6] {
    fn planes(&self) -> &[Plane; 6] {
        self
    }
}

impl ClipVolume for Frustum {
    fn planes(&self) -> &[Plane; 6] {
        &self.planes
    }

    fn screen_affine(&self) -> bool {
        self.affine
    }

    #[inline]
    fn outcode(&self, p: Vec3) -> u8 {
        Frustum::outcode(self, p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::camera::{FovAxis, Lens, Viewport};
    use crate::geometry::trig::BinaryAngle;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
    }

    fn cv(x: f64, y: f64, z: f64, a: i32) -> ClipVertex<1> {
        ClipVertex::new(v(x, y, z), [a])
    }

    fn camera() -> Camera {
        Camera::test_standard()
    }

    #[test]
    fn fast_outcode_equals_plane_distances() {
        let mut rng = crate::test_rng::XorShift(0x5EED_0123_4567_89ABu64);
        let mut rnd = || rng.next_u64() as i32;
        for guard in [1, 4, 100] {
            let f = Frustum::new::<4>(&camera(), guard).unwrap();
            for i in 0..20000 {
                // Full-range raw coordinates, and small ones near the planes.
                let shift = [0, 8, 14][i % 3];
                let p = Vec3::from_bits(rnd() >> shift, rnd() >> shift, rnd() >> shift);
                assert_eq!(f.outcode(p), f.outcode_generic(p), "{p:?}");
            }
        }
    }

    #[test]
    fn narrow_outcode_equals_outcode_within_its_bound() {
        let mut rng = crate::test_rng::XorShift(0x0123_4567_89AB_CDEFu64);
        let mut rnd = || rng.next_u64();
        for guard in [1, 4, 100] {
            let f = Frustum::new::<4>(&camera(), guard).unwrap();
            // The largest z bound the side planes allow, and a few smaller boxes.
            let c = f.planes[2].c.max(f.planes[4].c) as u64;
            let zmax = ((1u64 << 46) - 1) / c;
            for b in [
                [(1 << 30) - 1, (1 << 30) - 1, zmax.min((1 << 30) - 1)],
                [1 << 16, 1 << 16, 1 << 20],
                [1 << 22, 1 << 18, 1 << 21],
                [100, 100, 100],
            ] {
                assert!(f.narrow_fits(b), "{b:?}");
                let r = |k: u64, b: u64| (k % (2 * b + 1)) as i64 - b as i64;
                let check = |x: i64, y: i64, z: i64| {
                    let p = Vec3::from_bits(x as i32, y as i32, z as i32);
                    assert_eq!(f.outcode_narrow(p), f.outcode(p), "{p:?} in {b:?}");
                };
                for _ in 0..20000 {
                    let (x, y, z) = (r(rnd(), b[0]), r(rnd(), b[1]), r(rnd(), b[2]));
                    check(x, y, z);
                    // On and next to the side planes: x = ±⌊c·z/2^16⌋ + {−1, 0, 1}.
                    let q = (f.planes[2].c as i64 * z) >> 16;
                    for d in -1..=1 {
                        for x in [q + d, -q + d] {
                            if x.unsigned_abs() <= b[0] {
                                check(x, y, z);
                            }
                        }
                    }
                }
                // The corners and the near and far planes.
                for sx in [-1, 0, 1] {
                    for sy in [-1, 0, 1] {
                        for sz in [-1, 0, 1] {
                            check(sx * b[0] as i64, sy * b[1] as i64, sz * b[2] as i64);
                        }
                    }
                }
                for d in [-f.planes[NEAR].d, f.planes[FAR].d] {
                    for e in -1..=1 {
                        check(0, 0, (d + e) as i64);
                    }
                }
            }
            assert!(!f.narrow_fits([1 << 30, 0, 0]));
            assert!(!f.narrow_fits([0, 0, (1 << 46) / c + 1]));
        }
    }

    #[test]
    fn single_plane_halves_a_square_and_interpolates() {
        let pl = Plane::new(Coord::ONE, Coord::ZERO, Coord::ZERO, Coord::ZERO).unwrap(); // x ≥ 0
        let sq = [
            cv(-1.0, -1.0, 1.0, 0),
            cv(1.0, -1.0, 1.0, 100),
            cv(1.0, 1.0, 1.0, 100),
            cv(-1.0, 1.0, 1.0, 0),
        ];
        let mut out: Vec<ClipVertex<1>, 8> = Vec::new();
        clip_to_plane(&pl, &sq, &mut out, false, 0).unwrap();
        assert_eq!(out.len(), 4);
        for p in &out {
            assert!(p.pos.x >= Coord::ZERO);
            if p.pos.x == Coord::ZERO {
                assert_eq!(p.attrs[0], 50);
            }
        }
        let mut small: Vec<ClipVertex<1>, 3> = Vec::new();
        assert_eq!(
            clip_to_plane(&pl, &sq, &mut small, false, 0),
            Err(ClipError::CapacityExceeded)
        );
    }

    /// Issue "hostile inputs" #2: a planar, simple, non-convex 24-vertex polygon (a comb in
    /// the plane `y = 0` whose 11 teeth reach through the near plane) needs 35 vertices after
    /// the near plane alone, more than the renderer's 30: `clip` reports it, `clip_fan` clips
    /// its fan triangles instead, and the pieces cover exactly the polygon's part inside.
    #[test]
    fn non_convex_polygon_beyond_capacity_is_clipped_by_fan() {
        let f = Frustum::new::<4>(&camera(), Frustum::DEFAULT_GUARD).unwrap();
        // Base from x = −0.4 to 0.4 at z = 2, then 22 vertices back along x alternating tips
        // at z = 0.2 (outside near = 0.5) and valleys at z = 1.
        let mut poly: heapless::Vec<ClipVertex<1>, 24> = heapless::Vec::new();
        poly.push(cv(-0.4, 0.0, 2.0, 0)).unwrap();
        poly.push(cv(0.4, 0.0, 2.0, 0)).unwrap();
        for k in 0..22 {
            let x = 0.4 - 0.8 * (k as f64 + 0.5) / 22.0;
            let z = if k % 2 == 0 { 0.2 } else { 1.0 };
            poly.push(cv(x, 0.0, z, k)).unwrap();
        }
        assert_eq!(f.clip::<1, 30>(&poly), Err(ClipError::CapacityExceeded));
        let big: Vec<ClipVertex<1>, 64> = f.clip(&poly).unwrap();
        assert_eq!(big.len(), 35);
        // Signed area in the xz plane (f64 from the raw coordinates).
        let area = |p: &[ClipVertex<1>]| -> f64 {
            let q: heapless::Vec<(f64, f64), 64> = p
                .iter()
                .map(|v| (v.pos.x.to_num::<f64>(), v.pos.z.to_num::<f64>()))
                .collect();
            (0..q.len())
                .map(|i| {
                    let (a, b) = (q[i], q[(i + 1) % q.len()]);
                    a.0 * b.1 - b.0 * a.1
                })
                .sum::<f64>()
                / 2.0
        };
        let mut pieces = 0;
        let mut sum = 0.0;
        f.clip_fan::<1, 30, ClipError>(&poly, 0, |piece| {
            assert!(piece.len() >= 3 && piece.len() <= 9, "{}", piece.len());
            for v in piece {
                assert!(v.pos.z >= Coord::from_num(0.5), "{v:?}");
            }
            pieces += 1;
            sum += area(piece);
            Ok(())
        })
        .unwrap();
        assert_eq!(pieces, 22);
        let want = area(&big);
        assert!((sum - want).abs() < 1e-6, "{sum} vs {want}");
        // A polygon whose clip fits is emitted once, exactly as `clip` returns it.
        let tri = [
            cv(0.0, 0.0, -2.0, 0),
            cv(0.3, 0.0, 3.0, 255),
            cv(-0.3, 0.2, 3.0, 255),
        ];
        let mut calls = 0;
        f.clip_fan::<1, 30, ClipError>(&tri, 0, |piece| {
            assert_eq!(piece, f.clip::<1, 30>(&tri).unwrap().as_slice());
            calls += 1;
            Ok(())
        })
        .unwrap();
        assert_eq!(calls, 1);
        // Capacity below the input's size is still an error.
        assert_eq!(
            f.clip_fan::<1, 20, ClipError>(&poly, 0, |_| Ok(())),
            Err(ClipError::CapacityExceeded)
        );
    }

    /// The near-plane precision bound of the module doc, measured: with `near = 0.002`,
    /// clipped vertices of random edges (ends within ±4 world units, one behind the near
    /// plane) project within the documented distance of the exact intersection of the same
    /// (I16F16) edge with `z = near`.
    #[test]
    fn near_plane_clip_points_stay_within_the_documented_bound() {
        let lens = Lens {
            fov: BinaryAngle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: Coord::from_num(0.002),
            far: Coord::from_num(10),
        };
        let cam = Camera::new(
            Vec3::ZERO,
            v(0.0, 0.0, 1.0),
            v(0.0, 1.0, 0.0),
            lens,
            Viewport::new(320, 240),
        )
        .unwrap();
        let f = Frustum::new::<4>(&cam, Frustum::DEFAULT_GUARD).unwrap();
        let near = f.planes[NEAR];
        let focal = cam.focal_x().to_num::<f64>();
        let near_raw = (-near.d) as f64;
        let mut rng = crate::test_rng::XorShift(0x0EA2_0000_0000_0002);
        let mut worst = 0.0f64;
        for _ in 0..20000 {
            let mut r = |lo: f64, hi: f64| {
                lo + (hi - lo) * (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
            };
            let p = cv(r(-4.0, 4.0), r(-4.0, 4.0), r(0.002, 4.0), 0);
            let q = cv(r(-4.0, 4.0), r(-4.0, 4.0), r(-4.0, 0.0019), 0);
            let (dp, dq) = (near.distance(p.pos), near.distance(q.pos));
            if dp < 0 || dq >= 0 {
                continue;
            }
            let c = intersect(&p, &q, dp, dq, false, 0);
            let raw = |v: &ClipVertex<1>| v.pos.bits().map(|b| b as f64);
            let (pp, qq, cc) = (raw(&p), raw(&q), raw(&c));
            assert!(cc[2] >= near_raw);
            let t = (pp[2] - near_raw) / (pp[2] - qq[2]);
            let exact = [0, 1].map(|i| pp[i] + t * (qq[i] - pp[i]));
            // Screen offsets in pixels: f·x/z.
            for i in 0..2 {
                let err = (focal * cc[i] / cc[2] - focal * exact[i] / near_raw).abs();
                // Module doc: ε = |Δ|·2^-29 + 1 raw units per coordinate.
                let eps = |k: usize| (qq[k] - pp[k]).abs() / (1u64 << 29) as f64 + 1.0;
                let bound = focal * (eps(i) + (exact[i] / near_raw).abs() * eps(2)) / near_raw;
                assert!(err <= bound, "{err} > {bound}: {p:?} {q:?}");
                if (exact[i] / near_raw).abs() < 1.0 {
                    worst = worst.max(err);
                }
            }
        }
        // One raw unit at z = near is focal/131 ≈ 1.59 px; on screen (|x/z| < 1) the measured
        // worst is 1.54 px (module doc).
        assert!(worst < 2.0 * focal / near_raw, "{worst}");
    }

    /// At a side or far plane a screen attribute takes the screen interpolant's value at the new
    /// vertex's projection and a space-linear one (a texture coordinate) the value along the 3D
    /// edge: `t` of the cut, here `1/2` exactly (a far plane halfway in depth).
    #[test]
    fn space_linear_attributes_follow_the_3d_edge() {
        let far = Plane::new(
            Coord::ZERO,
            Coord::ZERO,
            Coord::from_num(-1),
            Coord::from_num(3),
        )
        .unwrap();
        let p = ClipVertex::new(Vec3::from_int(1, 0, 2), [0, 0]);
        let q = ClipVertex::new(Vec3::from_int(1, 0, 4), [1024, 1024]);
        let (dp, dq) = (far.distance(p.pos), far.distance(q.pos));
        let c = intersect(&p, &q, dp, dq, false, 0b10);
        assert_eq!(c.pos, Vec3::from_int(1, 0, 3));
        // Along the edge: half-way. On screen (`x/z` from 1/2 to 1/4, 1/3 at the cut): the
        // screen parameter is (1/2 − 1/3)/(1/2 − 1/4) = 2/3.
        assert_eq!(c.attrs, [683, 512]);
    }
}
