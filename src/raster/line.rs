//! Bresenham (midpoint) lines between lattice points, with exact clipping to a [`Window`].
//!
//! Role in the pipeline: the raster stage's wireframe primitive. Projected edges (whole
//! pixels) become a [`Bresenham`] iterator of pixels, clipped to the drawing window, then
//! [`draw_line`] writes a palette index into the [`Framebuffer`].
//!
//! ## Which pixels a line covers (the definition the code implements)
//! A line from `p0 = (x0, y0)` to `p1 = (x1, y1)` has deltas `dx = x1 − x0`, `dy = y1 − y0`.
//! Its **major axis** is `x` when `|dx| ≥ |dy|` (diagonals included), else `y`; with
//! `n = |major delta|` and `a = |minor delta|` (so `a ≤ n`), the line has exactly `n + 1`
//! pixels, one per major coordinate between the ends. At major step `t = 0..=n` the minor
//! coordinate is the exact value `minor0 + t·(minor delta)/n` **rounded to the nearest
//! integer, ties toward the smaller coordinate** (towards the top for an x-major line, since
//! `y` grows downward; towards the left for a y-major line).
//!
//! Because the tie rule depends on absolute coordinates, not on the direction of travel, and
//! the choice of the major axis is symmetric too, **drawing `p1 → p0` covers the same pixels
//! as `p0 → p1`, visited in reverse order** (tested exhaustively).
//!
//! ```text
//!                     −y (up)
//!             \   5   |   6   /        x-major (|dx| ≥ |dy|): octants 0, 3, 4, 7
//!               \     |     /          y-major (|dy| > |dx|): octants 1, 2, 5, 6
//!           4     \   |   /     7      ties round the minor coordinate toward
//!                   \ | /              the smaller value: up for x-major,
//!     −x ────────────p0──────────── +x left for y-major, in every octant
//!                   / | \
//!           3     /   |   \     0      octant 0: dx > 0, dy ≥ 0, |dx| ≥ |dy|
//!               /     |     \          octant 1: dy > 0, dx ≥ 0, |dy| > |dx|
//!             /   2   |   1   \        ... clockwise on screen
//!                     +y (down)
//! ```
//!
//! ## End points
//! [`Ends::Closed`] (the default of [`Bresenham::new`] and [`draw_line`]) yields both end
//! points: `n + 1` pixels. [`Ends::HalfOpen`] yields the same pixels without the last one
//! (`p1`): `n` pixels, none for a zero-length line. Chaining half-open segments of a polyline
//! draws each joint once (useful with XOR or blending); add the final point separately.
//!
//! ## The midpoint iteration
//! With `c = n − 1` when the minor coordinate increases along the line and `c = n` when it
//! decreases, the minor offset after `t` major steps is `o(t) = ⌊(2ta + c) / 2n⌋` (this is the
//! rounding above, expressed in the direction of travel). The [`Bresenham`] state keeps the
//! remainder of that division shifted down by `2n` as its `error ∈ [−2n, 0)`: each major move
//! adds `2a`; when the error becomes non-negative a minor move is taken and `2n` subtracted.
//! Only additions and one comparison per pixel; no division after set-up.
//!
//! ## Clipping
//! [`Bresenham::clipped`] classifies the ends with Cohen–Sutherland `Outcode`s (trivial
//! accept/reject), and otherwise computes directly, with a few `u64`/`i64` divisions, the
//! first and last steps `t` whose pixel is inside the window, and the exact midpoint state at
//! the first one. So a clipped line draws **exactly the pixels of the unclipped line that lie
//! inside the window, in the same order** — clipping never moves a pixel — and its set-up
//! costs O(1) whatever the line's length; a line far outside costs O(1) in total.
//!
//! ## Numeric contract
//! - [`Bresenham::new`] accepts **any** `i32` end points: `n, a ≤ 2^32 − 1` are held as
//!   `u32`, the error and its steps (`|error| ≤ 2n < 2^33`) as `i64`, and every pixel lies
//!   between the end points so positions never overflow `i32` (the state never moves past the
//!   last pixel).
//! - [`Bresenham::clipped`] and the `draw_*` functions need `|x|, |y| ≤ `[`MAX_COORD`]` = 2^30`
//!   for both ends, and return [`LineError::CoordinateOutOfRange`] otherwise (nothing drawn).
//!   Then `n, a ≤ 2^31`, and the largest set-up product, `2·n·k` with `k ≤ a`, is at most
//!   `2^63`, which fits `u64`; `2ta + c ≤ 2^63 + 2^31` as well. Window bounds may be any `i32`
//!   (they enter only through `i64` differences).
//!
//! ## Sub-pixel end points (the 3D lines' pixels)
//! [`SubpixelLine::new`] draws the exact segment between end points given in units of `2^-S`
//! pixel (`U = 2^S` units to a pixel), as the 3D pipeline projects them. The definition is the
//! one above with the end points no longer on the lattice: the major axis is `x` when
//! `|dx| ≥ |dy|` (sub-pixel deltas); the line has **one pixel per integer major coordinate `m`
//! whose pixel centre `m·U` lies on the closed segment's major extent**, and its minor
//! coordinate is the exact minor value of the segment at `m·U`, divided by `U`, **rounded to
//! nearest, ties toward the smaller coordinate**. On the lattice (`S = 0`, or end points
//! that are multiples of `U`) these are exactly the pixels of [`Bresenham::new`] (tested). The
//! definition does not depend on the direction of travel, so a shared edge drawn from either
//! end covers the same pixels. A segment whose major extent holds no pixel centre draws
//! nothing; a segment of zero length draws its point's pixel when it is a pixel centre along
//! the major axis (`x`), else nothing.
//!
//! The walk is the same midpoint iteration: with `n = |major delta|` and `a = |minor delta|`
//! in sub-pixel units, the minor pixel at step `t` is `⌊(N₀ + 2Ua·t) / 2Un⌋` (or its
//! negation) for an `N₀` fixed at set-up; the remainder of that division is constant modulo
//! `2U` (every step adds a multiple of `2U`), so its quotient by `2U` decides the minor moves
//! alone: the [`Bresenham`] state with error steps `a` and `n` (error in `[−n, 0)`). Clipping
//! to the window is exact and O(1), as for lattice lines: the first and last steps inside come
//! from a few `i128` divisions at set-up. Range: `|x|, |y| ≤ `[`MAX_COORD`] sub-pixel units
//! for both ends (then `n, a ≤ 2^31`; the set-up products stay below `2^100` in `i128`).
//! Those divisions take the 64-bit routine whenever both operands fit `i64`, as they do for
//! any segment within a few thousand pixels of the window (`arith::euclid::div_floor_i128`).

use super::outcode::Outcode;
use crate::arith::euclid::div_floor_i128;
use crate::output::Framebuffer;
use crate::raster::SubpixelPoint;
use crate::raster::Window;
use embedded_graphics_core::geometry::Point;

/// The largest end-point coordinate magnitude accepted by clipping and drawing: `2^30`.
pub const MAX_COORD: i32 = 1 << 30;

/// Whether the last end point of a line is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Ends {
    /// Both end points are drawn: `n + 1` pixels.
    #[default]
    Closed,
    /// The last end point is left out: `n` pixels (polyline segments without double joints).
    HalfOpen,
}

/// Why a line could not be clipped or drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LineError {
    /// An end point has a coordinate beyond `±`[`MAX_COORD`].
    CoordinateOutOfRange {
        /// The offending end point.
        point: Point,
    },
}

impl core::fmt::Display for LineError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LineError::CoordinateOutOfRange { point } => write!(
                f,
                "line end point ({}, {}) is beyond ±{} and cannot be clipped",
                point.x, point.y, MAX_COORD
            ),
        }
    }
}

impl core::error::Error for LineError {}

/// The set-up shared by plain and clipped iteration: axes, directions and deltas.
#[derive(Debug, Clone, Copy)]
struct Setup {
    /// Unit move along the major axis.
    major_step: Point,
    /// Unit move along the minor axis.
    minor_step: Point,
    /// True when the minor coordinate increases along the line.
    minor_increases: bool,
    /// `|major delta|`.
    n: u32,
    /// `|minor delta|` (`a ≤ n`).
    a: u32,
}

impl Setup {
    fn new(p0: Point, p1: Point) -> Setup {
        let dx = p1.x as i64 - p0.x as i64;
        let dy = p1.y as i64 - p0.y as i64;
        // |dx|, |dy| ≤ 2^32 − 1: they fit u32.
        let (adx, ady) = (dx.unsigned_abs() as u32, dy.unsigned_abs() as u32);
        let sx = if dx < 0 { -1 } else { 1 };
        let sy = if dy < 0 { -1 } else { 1 };
        if adx >= ady {
            Setup {
                major_step: Point::new(sx, 0),
                minor_step: Point::new(0, sy),
                minor_increases: dy > 0,
                n: adx,
                a: ady,
            }
        } else {
            Setup {
                major_step: Point::new(0, sy),
                minor_step: Point::new(sx, 0),
                minor_increases: dx > 0,
                n: ady,
                a: adx,
            }
        }
    }

    /// The rounding bias `c` of `o(t) = ⌊(2ta + c) / 2n⌋`: ties go to the smaller absolute
    /// coordinate, i.e. down in offset when the minor coordinate increases, up otherwise.
    fn bias(&self) -> u64 {
        if self.minor_increases {
            (self.n as u64).saturating_sub(1)
        } else {
            self.n as u64
        }
    }
}

/// A Bresenham line as an allocation-free iterator of pixels ([`Point`]s), in order from the
/// first end point to the last.
///
/// See the [module documentation](self) for the pixels covered, the tie rule and the ranges.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Bresenham {
    /// The next pixel to yield.
    point: Point,
    /// Unit move along the major axis (`(±1, 0)` or `(0, ±1)`), taken at every step.
    major_step: Point,
    /// Unit move along the minor axis, taken when the error becomes non-negative.
    minor_step: Point,
    /// The midpoint decision variable, in `[−2n, 0)`: the remainder of `(2ta + c) / 2n`
    /// minus `2n`.
    error: i64,
    /// Added to the error at every major move: `2a`.
    error_step_major: i64,
    /// Subtracted from the error at every minor move: `2n`.
    error_step_minor: i64,
    /// Moves left after `point` (so `steps_left + 1` pixels remain unless `done`).
    steps_left: u32,
    /// True when every pixel has been yielded.
    done: bool,
    /// The last pixel the iterator yields (fixed at construction; meaningless when `done`).
    last: Point,
}

impl Bresenham {
    /// The closed line from `p0` to `p1`: both end points included. Any `i32` end points.
    pub fn new(p0: Point, p1: Point) -> Bresenham {
        Bresenham::with_ends(p0, p1, Ends::Closed)
    }

    /// The half-open line from `p0` to `p1`: `p1` excluded (empty when `p0 == p1`).
    pub fn half_open(p0: Point, p1: Point) -> Bresenham {
        Bresenham::with_ends(p0, p1, Ends::HalfOpen)
    }

    /// The line from `p0` to `p1` with the given treatment of `p1`. Any `i32` end points.
    pub fn with_ends(p0: Point, p1: Point, ends: Ends) -> Bresenham {
        let s = Setup::new(p0, p1);
        let (steps_left, done, last) = match ends {
            Ends::Closed => (s.n, false, p1),
            Ends::HalfOpen if s.n == 0 => (0, true, p0),
            // The pixel before p1 (step n − 1, on the segment: no overflow). The last move
            // is a minor one when o(n − 1) = a − 1: o(n) = a + ⌊c / 2n⌋ = a (c < 2n), and
            // o(n − 1) = a + ⌊(c − 2a) / 2n⌋ is a − 1 exactly when c < 2a.
            Ends::HalfOpen => {
                let mut q = p1 - s.major_step;
                if s.bias() < 2 * s.a as u64 {
                    q -= s.minor_step;
                }
                (s.n - 1, false, q)
            }
        };
        Bresenham {
            point: p0,
            major_step: s.major_step,
            minor_step: s.minor_step,
            // r(0) = c, so error = c − 2n.
            error: s.bias() as i64 - 2 * s.n as i64,
            error_step_major: 2 * s.a as i64,
            error_step_minor: 2 * s.n as i64,
            steps_left,
            done,
            last,
        }
    }

    /// An iterator that yields nothing.
    pub fn empty() -> Bresenham {
        Bresenham {
            point: Point::zero(),
            major_step: Point::new(1, 0),
            minor_step: Point::new(0, 1),
            error: -1,
            error_step_major: 0,
            error_step_minor: 0,
            steps_left: 0,
            done: true,
            last: Point::zero(),
        }
    }

    /// The part of the line from `p0` to `p1` inside `window`: exactly the pixels of
    /// [`Bresenham::with_ends`]`(p0, p1, ends)` that `window` contains, in the same order.
    ///
    /// O(1) set-up (outcodes, then at most four `u64` divisions and one remainder).
    /// Errors when a coordinate of `p0` or `p1` is beyond `±`[`MAX_COORD`].
    pub fn clipped(
        p0: Point,
        p1: Point,
        ends: Ends,
        window: &Window,
    ) -> Result<Bresenham, LineError> {
        for p in [p0, p1] {
            if p.x.unsigned_abs() > MAX_COORD as u32 || p.y.unsigned_abs() > MAX_COORD as u32 {
                return Err(LineError::CoordinateOutOfRange { point: p });
            }
        }
        if window.is_empty() {
            return Ok(Bresenham::empty());
        }
        let c0 = Outcode::of(p0.x, p0.y, window);
        let c1 = Outcode::of(p1.x, p1.y, window);
        if Outcode::trivially_inside(c0, c1) {
            return Ok(Bresenham::with_ends(p0, p1, ends));
        }
        if Outcode::trivially_outside(c0, c1) {
            return Ok(Bresenham::empty());
        }
        Ok(Bresenham::clip_exact(p0, p1, ends, window).unwrap_or_else(Bresenham::empty))
    }

    /// The exact clipping of a partially visible line; `None` when no pixel is inside.
    /// Preconditions (checked by the caller): coordinates within `±MAX_COORD`, window not empty.
    fn clip_exact(p0: Point, p1: Point, ends: Ends, window: &Window) -> Option<Bresenham> {
        let s = Setup::new(p0, p1);
        let (n, a) = (s.n as u64, s.a as u64);
        // Last step index drawn (as i64; −1 for an empty half-open line).
        let last: i64 = match ends {
            Ends::Closed => n as i64,
            Ends::HalfOpen => n as i64 - 1,
        };
        // Window bounds, closed, along the major and minor axes.
        let xs = (window.x0 as i64, window.x1 as i64 - 1);
        let ys = (window.y0 as i64, window.y1 as i64 - 1);
        let (major0, minor0, major_win, minor_win, major_sign, minor_sign) = if s.major_step.x != 0
        {
            (p0.x, p0.y, xs, ys, s.major_step.x, s.minor_step.y)
        } else {
            (p0.y, p0.x, ys, xs, s.major_step.y, s.minor_step.x)
        };
        // Steps t whose major coordinate major0 + sign·t is inside the window.
        let (tm_lo, tm_hi) = signed_range(major0 as i64, major_win, major_sign);
        // Minor offsets o whose minor coordinate minor0 + sign·o is inside the window.
        let (k_lo, k_hi) = signed_range(minor0 as i64, minor_win, minor_sign);
        if k_hi < 0 || k_lo > a as i64 {
            return None; // o(t) ∈ [0, a] never reaches the window's rows/columns
        }
        let c = s.bias();
        // T(k): the first step with o(t) ≥ k, for 1 ≤ k ≤ a (then a ≥ 1, n ≥ 1):
        // ⌊(2ta + c) / 2n⌋ ≥ k  ⇔  2ta ≥ 2nk − c  ⇔  t ≥ ⌈(2nk − c) / 2a⌉.
        // 2nk ≤ 2·2^31·2^31 = 2^63 and 2nk − c ≥ 2n − n ≥ 0: no overflow in u64.
        let first_step_reaching = |k: u64| -> i64 {
            let num = 2 * n * k - c;
            num.div_ceil(2 * a) as i64
        };
        let tk_lo = if k_lo <= 0 {
            0
        } else {
            first_step_reaching(k_lo as u64)
        };
        let tk_hi = if k_hi >= a as i64 {
            n as i64
        } else {
            first_step_reaching(k_hi as u64 + 1) - 1
        };
        let t_first = tm_lo.max(tk_lo).max(0);
        let t_last = tm_hi.min(tk_hi).min(last);
        if t_first > t_last {
            return None;
        }
        // The pixel at step t and its midpoint remainder: 2ta + c ≤ 2^63 + 2^31 < 2^64, and
        // o(t) ≤ a ≤ 2^31. The pixel is on the segment, so both coordinates fit i32.
        let two_n = 2 * n; // n ≥ 1 here: p0 ≠ p1, or the outcodes would have decided
        let at = |t: i64| {
            let num = 2 * t as u64 * a + c;
            let major = (major0 as i64 + major_sign as i64 * t) as i32;
            let minor = (minor0 as i64 + minor_sign as i64 * (num / two_n) as i64) as i32;
            let p = if s.major_step.x != 0 {
                Point::new(major, minor)
            } else {
                Point::new(minor, major)
            };
            (p, num % two_n)
        };
        let ((point, r), (last, _)) = (at(t_first), at(t_last));
        Some(Bresenham {
            point,
            major_step: s.major_step,
            minor_step: s.minor_step,
            error: r as i64 - two_n as i64,
            error_step_major: 2 * a as i64,
            error_step_minor: two_n as i64,
            // t_last − t_first ≤ n ≤ 2^31.
            steps_left: (t_last - t_first) as u32,
            done: false,
            last,
        })
    }

    /// The last pixel the iterator will yield (the current one when a single pixel remains),
    /// kept from construction: `p1` for a closed line, the pixel before it for a half-open
    /// one, the last inside pixel for a clipped one. Meaningless once `done`.
    fn last_point(&self) -> Point {
        self.last
    }

    /// Pixels not yet yielded (up to `2^32` for a closed line across the whole `i32` range).
    pub fn remaining(&self) -> u64 {
        if self.done {
            0
        } else {
            self.steps_left as u64 + 1
        }
    }
}

/// A line between sub-pixel end points, clipped to a window: its pixels as a [`Bresenham`]
/// state, and where they fall along the segment (for the depth walker of 3D lines). See the
/// [module documentation](self), "Sub-pixel end points".
#[derive(Debug, Clone)]
pub struct SubpixelLine {
    /// The pixels inside the window, in order from the first end point.
    pub(crate) pixels: Bresenham,
    /// The same pixels walked from the last one back to the first (the two-ended walk).
    pub(crate) back: Bresenham,
    /// Major distance from the first end point to the first pixel's centre, sub-pixel units.
    pub(crate) travel: u64,
    /// Major distance from the first end point to the last pixel's centre, sub-pixel units.
    pub(crate) travel_last: u64,
    /// `|major delta|` in sub-pixel units (0 for a point).
    pub(crate) length: u64,
    /// Sub-pixel units per pixel (`2^S`).
    pub(crate) unit: u64,
}

impl SubpixelLine {
    /// The pixels of the exact segment `p0`–`p1` (both ends included where they are pixel
    /// centres along the major axis) that `window` holds, or `None` when it holds none.
    ///
    /// Errors when a coordinate of `p0` or `p1` is beyond `±`[`MAX_COORD`] sub-pixel units.
    pub fn new<const S: u32>(
        p0: SubpixelPoint<S>,
        p1: SubpixelPoint<S>,
        window: &Window,
    ) -> Result<Option<SubpixelLine>, LineError> {
        for p in [p0, p1] {
            if p.x.unsigned_abs() > MAX_COORD as u32 || p.y.unsigned_abs() > MAX_COORD as u32 {
                return Err(LineError::CoordinateOutOfRange {
                    point: Point::new(p.x, p.y),
                });
            }
        }
        if window.is_empty() {
            return Ok(None);
        }
        Ok(Self::clipped(p0, p1, window))
    }

    /// The set-up (module doc); coordinates checked by the caller.
    fn clipped<const S: u32>(
        p0: SubpixelPoint<S>,
        p1: SubpixelPoint<S>,
        window: &Window,
    ) -> Option<SubpixelLine> {
        let unit = 1i128 << S;
        let (dx, dy) = (p1.x as i64 - p0.x as i64, p1.y as i64 - p0.y as i64);
        let x_major = dx.unsigned_abs() >= dy.unsigned_abs();
        let (m0, m1, mu0, mu1) = if x_major {
            (p0.x as i128, p1.x as i128, p0.y as i128, p1.y as i128)
        } else {
            (p0.y as i128, p1.y as i128, p0.x as i128, p1.x as i128)
        };
        let sigma: i128 = if m1 >= m0 { 1 } else { -1 };
        // A point (n = 0) takes the increasing form: its minor value rounded at set-up.
        let tau: i128 = if mu1 > mu0 || m1 == m0 { 1 } else { -1 };
        let (n, a) = ((m1 - m0).abs(), (mu1 - mu0).abs());
        // The pixel centres on the major extent, in the direction of travel.
        let (first, last) = if sigma > 0 {
            (-((-m0) >> S), m1 >> S)
        } else {
            (m0 >> S, -((-m1) >> S))
        }; // floors and ceilings of m / U, U = 2^S
        let count = sigma * (last - first) + 1;
        if count <= 0 {
            return None;
        }
        let travel = sigma * (first * unit - m0); // in [0, U)
        let (xs, ys) = (
            (window.x0 as i64, window.x1 as i64 - 1),
            (window.y0 as i64, window.y1 as i64 - 1),
        );
        let (major_win, minor_win) = if x_major { (xs, ys) } else { (ys, xs) };
        let (tm_lo, tm_hi) = signed_range(first as i64, major_win, sigma as i32);
        // The minor pixel at step t is ±q(t), q(t) = ⌊(N₀ + t·B) / C⌋ (module doc).
        let (c, b) = (2 * unit * n.max(1), 2 * unit * a);
        let n0 = if n == 0 {
            // A point: ⌈(2μ₀ − U) / 2U⌉, its minor coordinate rounded, ties toward the smaller.
            2 * mu0 + unit - 1
        } else if tau > 0 {
            2 * mu0 * n + 2 * travel * a + unit * n - 1
        } else {
            2 * travel * a - 2 * mu0 * n + unit * n
        };
        let (q_lo, q_hi) = if tau > 0 {
            (minor_win.0 as i128, minor_win.1 as i128)
        } else {
            (-(minor_win.1 as i128), -(minor_win.0 as i128))
        };
        let (tk_lo, tk_hi) = if b == 0 {
            let q = div_floor_i128(n0, c).0;
            if q < q_lo || q > q_hi {
                return None;
            }
            (0, count - 1)
        } else {
            (
                ceil_div(q_lo * c - n0, b),
                ceil_div((q_hi + 1) * c - n0, b) - 1,
            )
        };
        let t_first = (tm_lo as i128).max(tk_lo).max(0);
        let t_last = (tm_hi as i128).min(tk_hi).min(count - 1);
        if t_first > t_last {
            return None;
        }
        let axis = |major: i128, minor: i128| {
            if x_major {
                Point::new(major as i32, minor as i32)
            } else {
                Point::new(minor as i32, major as i32)
            }
        };
        let (major_step, minor_step) = (axis(sigma, 0), axis(0, tau));
        // The pixel at step t and its error r_hi − n (r_hi = remainder / 2U).
        let at = |t: i128| {
            let num = n0 + t * b;
            let (q, r) = div_floor_i128(num, c);
            let point = axis(first + sigma * t, tau * q);
            (point, ((r >> (S + 1)) - n) as i64) // r ≥ 0: the quotient by 2U
        };
        let ((p_first, e_first), (p_last, e_last)) = (at(t_first), at(t_last));
        let steps_left = (t_last - t_first) as u32; // ≤ 2^31
        let (a, n) = (a as i64, n as i64);
        let pixels = Bresenham {
            point: p_first,
            major_step,
            minor_step,
            error: e_first,
            error_step_major: a,
            error_step_minor: n,
            steps_left,
            done: false,
            last: p_last,
        };
        // Walked backwards the error becomes g = −n − 1 − e: the same iteration (module doc
        // of the depth walker, `raster::depth_line`).
        let back = Bresenham {
            point: p_last,
            major_step: Point::zero() - major_step,
            minor_step: Point::zero() - minor_step,
            error: -n - 1 - e_last,
            error_step_major: a,
            error_step_minor: n,
            steps_left,
            done: false,
            last: p_first,
        };
        Some(SubpixelLine {
            pixels,
            back,
            travel: (travel + t_first * unit) as u64,
            travel_last: (travel + t_last * unit) as u64,
            length: n as u64,
            unit: unit as u64,
        })
    }

    /// The pixels, in order from the first end point.
    pub fn pixels(&self) -> Bresenham {
        self.pixels.clone()
    }
}

/// `⌈p / q⌉` for `q > 0`.
fn ceil_div(p: i128, q: i128) -> i128 {
    -div_floor_i128(-p, q).0
}

/// The steps `t` with `lo ≤ origin + sign·t ≤ hi`, as a closed `i64` range (possibly empty or
/// negative: the caller intersects it with the line's own steps). All terms are below `2^33`.
fn signed_range(origin: i64, (lo, hi): (i64, i64), sign: i32) -> (i64, i64) {
    if sign > 0 {
        (lo - origin, hi - origin)
    } else {
        (origin - hi, origin - lo)
    }
}

impl Iterator for Bresenham {
    type Item = Point;

    #[inline]
    fn next(&mut self) -> Option<Point> {
        if self.done {
            return None;
        }
        let p = self.point;
        if self.steps_left == 0 {
            self.done = true;
        } else {
            self.steps_left -= 1;
            self.point += self.major_step;
            self.error += self.error_step_major;
            if self.error >= 0 {
                self.error -= self.error_step_minor;
                self.point += self.minor_step;
            }
        }
        Some(p)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        match usize::try_from(self.remaining()) {
            Ok(n) => (n, Some(n)),
            Err(_) => (usize::MAX, None),
        }
    }
}

impl core::iter::FusedIterator for Bresenham {}

/// Draws the closed line `p0`–`p1` (both ends included) into `fb` with palette `index`,
/// clipped to the buffer's window (bands included): exactly the pixels of
/// [`Bresenham::new`]`(p0, p1)` that the buffer holds.
///
/// Errors (nothing drawn) when a coordinate is beyond `±`[`MAX_COORD`].
pub fn draw_line(
    fb: &mut Framebuffer<'_>,
    p0: Point,
    p1: Point,
    index: u8,
) -> Result<(), LineError> {
    draw_line_with_ends(fb, p0, p1, Ends::Closed, index)
}

/// Draws the half-open line `p0`–`p1` (`p1` excluded), clipped like [`draw_line`].
pub fn draw_line_half_open(
    fb: &mut Framebuffer<'_>,
    p0: Point,
    p1: Point,
    index: u8,
) -> Result<(), LineError> {
    draw_line_with_ends(fb, p0, p1, Ends::HalfOpen, index)
}

/// Draws the line `p0`–`p1` with the given end treatment, clipped like [`draw_line`].
pub fn draw_line_with_ends(
    fb: &mut Framebuffer<'_>,
    p0: Point,
    p1: Point,
    ends: Ends,
    index: u8,
) -> Result<(), LineError> {
    let line = Bresenham::clipped(p0, p1, ends, &fb.window())?;
    line.draw(fb, index);
    Ok(())
}

impl Bresenham {
    /// Writes every remaining pixel into `fb` with one tight loop: the pixel's offset in the
    /// buffer moves by a precomputed major (and, on error overflow, minor) stride, so a pixel
    /// costs a store, two adds, a compare and the loop test.
    ///
    /// Writes exactly the remaining pixels of the line that `fb` holds (its window, bands
    /// included); pixels outside it are skipped, never written elsewhere (not into another
    /// row, nor into the padding of a buffer whose stride exceeds its width). The tight loop
    /// runs when the line's first and last remaining pixels are both in the window — then
    /// every pixel between them is, since both coordinates move monotonically — which is
    /// always true for [`Bresenham::clipped`] against `fb.window()`. Otherwise, and for lines
    /// whose error terms exceed `i32` (end points farther apart than 2^30), each pixel goes
    /// through the checked [`Framebuffer::set_pixel`].
    pub fn draw(self, fb: &mut Framebuffer<'_>, index: u8) {
        if self.done {
            return;
        }
        let fits = |v: i64| v.unsigned_abs() < 1 << 30;
        let window = fb.window();
        let inside = |p: Point| window.contains(p.x, p.y);
        let fast = fits(self.error)
            && fits(self.error_step_major)
            && fits(self.error_step_minor)
            && inside(self.point)
            && inside(self.last_point());
        if !fast {
            for p in self {
                fb.set_pixel(p.x, p.y, index);
            }
            return;
        }
        let (stride, top) = (fb.stride() as isize, fb.top());
        let (x, y) = (self.point.x, self.point.y - top);
        let offset = |p: Point| (p.x as isize + p.y as isize * stride) as usize;
        let start = (y as isize * stride + x as isize) as usize;
        let steps = BresenhamSteps {
            major: offset(self.major_step),
            minor: offset(self.minor_step),
            error_step_major: self.error_step_major as i32,
            error_step_minor: self.error_step_minor as i32,
        };
        steps.run(
            fb.pixels_mut(),
            start,
            self.error as i32,
            self.steps_left,
            index,
        );
    }
}

/// The inner loop of [`Bresenham::draw`], kept apart with few live values so that everything
/// stays in registers: offsets in the buffer (negative strides as wrapping `usize`), `i32`
/// error terms.
#[derive(Clone, Copy)]
struct BresenhamSteps {
    major: usize,
    minor: usize,
    error_step_major: i32,
    error_step_minor: i32,
}

impl BresenhamSteps {
    #[inline(never)]
    fn run(self, pixels: &mut [u8], mut at: usize, error: i32, mut left: u32, index: u8) {
        let mut error = error as u32; // two's complement: see the step below
        loop {
            // An offset that left the buffer (negative ones wrap to huge values) ends the line.
            let Some(p) = pixels.get_mut(at) else { return };
            *p = index;
            if left == 0 {
                return;
            }
            left -= 1;
            at = at.wrapping_add(self.major);
            // The error lives in [−2n, 0); as a u32 it is in [2^32 − 2n, 2^32), so adding 2a
            // (≤ 2n) carries out of 32 bits exactly when the error becomes ≥ 0: the carry
            // flag is the minor-step decision (`adds` + a conditional pair on Cortex-M).
            let (e, carry) = error.overflowing_add(self.error_step_major as u32);
            error = e;
            if carry {
                error = error.wrapping_sub(self.error_step_minor as u32);
                at = at.wrapping_add(self.minor);
            }
        }
    }
}

/// Draws the polyline through `points` (each joint once: half-open segments, then the last
/// point), clipped like [`draw_line`]. One point draws that pixel; none draws nothing.
///
/// Errors (stopping at the offending segment) when a coordinate is beyond `±`[`MAX_COORD`].
pub fn draw_polyline(
    fb: &mut Framebuffer<'_>,
    points: &[Point],
    index: u8,
) -> Result<(), LineError> {
    for pair in points.windows(2) {
        if let [a, b] = *pair {
            draw_line_half_open(fb, a, b, index)?;
        }
    }
    if let Some(&last) = points.last() {
        draw_line(fb, last, last, index)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(it: Bresenham) -> heapless::Vec<(i32, i32), 64> {
        it.map(|p| (p.x, p.y)).collect()
    }

    #[test]
    fn octant_zero_with_a_tie() {
        // (0,0)→(4,1): y = t/4 → 0, 0, 0.5→0 (tie up), 1, 1.
        assert_eq!(
            &pts(Bresenham::new(Point::new(0, 0), Point::new(4, 1)))[..],
            &[(0, 0), (1, 0), (2, 0), (3, 1), (4, 1)]
        );
        // Reversed: same pixels, reverse order (tie still goes to the smaller y).
        assert_eq!(
            &pts(Bresenham::new(Point::new(4, 1), Point::new(0, 0)))[..],
            &[(4, 1), (3, 1), (2, 0), (1, 0), (0, 0)]
        );
    }

    #[test]
    fn steep_line_ties_go_left() {
        // (0,0)→(1,2): x = y/2 → 0, 0.5→0, 1.
        assert_eq!(
            &pts(Bresenham::new(Point::new(0, 0), Point::new(1, 2)))[..],
            &[(0, 0), (0, 1), (1, 2)]
        );
        assert_eq!(
            &pts(Bresenham::new(Point::new(1, 2), Point::new(0, 0)))[..],
            &[(1, 2), (0, 1), (0, 0)]
        );
    }

    #[test]
    fn axis_lines_and_single_points() {
        assert_eq!(
            &pts(Bresenham::new(Point::new(2, 5), Point::new(2, 2)))[..],
            &[(2, 5), (2, 4), (2, 3), (2, 2)]
        );
        assert_eq!(
            &pts(Bresenham::new(Point::new(7, 7), Point::new(7, 7)))[..],
            &[(7, 7)]
        );
        assert_eq!(
            Bresenham::half_open(Point::new(7, 7), Point::new(7, 7)).count(),
            0
        );
        assert_eq!(
            &pts(Bresenham::half_open(Point::new(0, 0), Point::new(-2, -2)))[..],
            &[(0, 0), (-1, -1)]
        );
    }

    #[test]
    fn extreme_coordinates_do_not_overflow() {
        let mut it = Bresenham::new(
            Point::new(i32::MIN, i32::MAX),
            Point::new(i32::MAX, i32::MIN),
        );
        assert_eq!(it.remaining(), 1 << 32);
        assert_eq!(it.next(), Some(Point::new(i32::MIN, i32::MAX)));
        let p = Point::new(i32::MAX, i32::MAX);
        let mut single = Bresenham::new(p, p);
        assert_eq!(single.next(), Some(p));
        assert_eq!(single.next(), None);
        // Clipping rejects what it cannot compute exactly, without panicking.
        let w = Window::new(0, 0, 10, 10);
        assert!(
            Bresenham::clipped(Point::new(i32::MIN, 0), Point::new(5, 5), Ends::Closed, &w)
                .is_err()
        );
        assert!(Bresenham::clipped(
            Point::new(-MAX_COORD, MAX_COORD),
            Point::new(MAX_COORD, -MAX_COORD),
            Ends::Closed,
            &w
        )
        .is_ok());
    }

    #[test]
    fn clipping_keeps_pixels_in_place() {
        let w = Window::new(2, 1, 7, 4);
        for (p0, p1) in [
            ((-3, -2), (11, 6)),
            ((12, 0), (-5, 5)),
            ((3, -9), (5, 20)),
            ((0, 5), (9, 0)),
        ] {
            let (p0, p1) = (Point::new(p0.0, p0.1), Point::new(p1.0, p1.1));
            let expect: heapless::Vec<(i32, i32), 64> = Bresenham::new(p0, p1)
                .filter(|p| w.contains(p.x, p.y))
                .map(|p| (p.x, p.y))
                .collect();
            let got = pts(Bresenham::clipped(p0, p1, Ends::Closed, &w).unwrap());
            assert_eq!(got, expect, "{p0:?} {p1:?}");
        }
    }

    #[test]
    fn clipping_at_the_ends_of_the_longest_lines() {
        // n = 2^31 and a close to n: the set-up products reach 2^63 (debug builds check
        // overflow). The pixels near p1 are computed independently by walking the reversed
        // line from p1 (same pixels by symmetry) for a few steps.
        let m = MAX_COORD;
        let lines = [
            ((-m, -m), (m, m)),
            ((-m, m), (m, -m)),
            ((-m, -m), (m, m - 1)),
            ((m, m - 1), (-m, -m)),
            ((-m, m), (m - 1, -m)),
            ((m, -m + 1), (-m, m)),
            ((-m, 0), (m, 1)),
        ];
        for ((x0, y0), (x1, y1)) in lines {
            let (p0, p1) = (Point::new(x0, y0), Point::new(x1, y1));
            for ends in [Ends::Closed, Ends::HalfOpen] {
                // A 5×5 window around p1, one around p0, and each end alone.
                for (c, far, r) in [(p1, p0, 2), (p0, p1, 2), (p1, p0, 0), (p0, p1, 0)] {
                    // r = 0: the single pixel at the end, where 2·n·k reaches 2^63 exactly.
                    let w = Window::new(c.x - r, c.y - r, c.x + r + 1, c.y + r + 1);
                    let mut want: heapless::Vec<(i32, i32), 64> = if c == p1 {
                        let mut v: heapless::Vec<(i32, i32), 64> = Bresenham::new(p1, p0)
                            .take(8)
                            .filter(|p| w.contains(p.x, p.y))
                            .map(|p| (p.x, p.y))
                            .collect();
                        v.reverse();
                        v
                    } else {
                        Bresenham::new(p0, p1)
                            .take(8)
                            .filter(|p| w.contains(p.x, p.y))
                            .map(|p| (p.x, p.y))
                            .collect()
                    };
                    if ends == Ends::HalfOpen && want.last() == Some(&(p1.x, p1.y)) {
                        want.pop();
                    }
                    let got = pts(Bresenham::clipped(p0, p1, ends, &w).unwrap());
                    assert_eq!(got, want, "{p0:?}→{p1:?} {ends:?} near {c:?} (far {far:?})");
                    assert!(!got.is_empty() || ends == Ends::HalfOpen);
                }
            }
        }
    }

    #[test]
    fn far_lines_cost_nothing() {
        let w = Window::new(0, 0, 320, 240);
        let it = Bresenham::clipped(
            Point::new(-MAX_COORD, -MAX_COORD),
            Point::new(MAX_COORD, -MAX_COORD + 3),
            Ends::Closed,
            &w,
        )
        .unwrap();
        assert_eq!(it.remaining(), 0);
        // A huge line crossing the window: only the visible part is left to walk.
        let it = Bresenham::clipped(
            Point::new(-MAX_COORD, 100),
            Point::new(MAX_COORD, 140),
            Ends::Closed,
            &w,
        )
        .unwrap();
        assert!(it.remaining() <= 320);
        assert!(it.remaining() > 0);
    }

    #[test]
    fn draw_line_into_a_band() {
        let mut buf = [0u8; 8 * 3];
        let mut fb = Framebuffer::band(&mut buf, 8, 3, 2).unwrap(); // rows 2..5
        draw_line(&mut fb, Point::new(-4, -4), Point::new(12, 12), 9).unwrap();
        for y in 2..5 {
            for x in 0..8 {
                let want = if x == y { 9 } else { 0 };
                assert_eq!(fb.pixel(x, y), Some(want), "({x}, {y})");
            }
        }
        assert!(draw_line(&mut fb, Point::new(0, 0), Point::new(MAX_COORD + 1, 0), 1).is_err());
    }

    /// Issue "hostile inputs" #4: an unclipped line partly outside the frame writes only its
    /// own pixels that the frame holds: not row 0 for (1,1)→(−6,1) on a 4×3 frame, nothing in
    /// the padding of a buffer whose stride exceeds its width.
    #[test]
    fn unclipped_draw_writes_only_the_lines_pixels_in_the_frame() {
        let mut buf = [0u8; 12];
        let mut fb = Framebuffer::new(&mut buf, 4, 3).unwrap();
        Bresenham::new(Point::new(1, 1), Point::new(-6, 1)).draw(&mut fb, 7);
        assert_eq!(buf, [0, 0, 0, 0, 7, 7, 0, 0, 0, 0, 0, 0]);

        let mut rng = crate::test_rng::XorShift(0xB2E5_3A17_0D1C_44F1);
        let (w, h) = (5usize, 4usize);
        for i in 0..20000 {
            // Even cases: stride 8 > width 5, rows 0..4; odd ones: a band of rows 3..7.
            let (stride, top) = if i % 2 == 0 { (8usize, 0i32) } else { (w, 3) };
            let mut r = |m: u64| (rng.next_u64() % m) as i32;
            let span = [12, 40, 1 << 12][i % 3];
            let p0 = Point::new(r(span as u64) - span / 2, r(span as u64) - span / 2 + top);
            let p1 = Point::new(r(span as u64) - span / 2, r(span as u64) - span / 2 + top);
            let ends = if i % 4 < 2 {
                Ends::Closed
            } else {
                Ends::HalfOpen
            };
            let mut line = Bresenham::with_ends(p0, p1, ends);
            // Sometimes start part-way along the line.
            for _ in 0..r(3) {
                line.next();
            }
            let mut want = [0u8; 8 * 4];
            for p in line.clone() {
                let (x, y) = (p.x, p.y - top);
                if (0..w as i32).contains(&x) && (0..h as i32).contains(&y) {
                    want[y as usize * stride + x as usize] = 1;
                }
            }
            let mut got = [0u8; 8 * 4];
            let mut fb = if top == 0 {
                Framebuffer::with_stride(&mut got, w as u16, h as u16, stride).unwrap()
            } else {
                Framebuffer::band(&mut got[..w * h], w as u16, h as u16, top as u16).unwrap()
            };
            line.draw(&mut fb, 1);
            assert_eq!(got, want, "{p0:?} -> {p1:?} {ends:?}");
        }
    }

    #[test]
    fn last_point_is_the_last_pixel_yielded() {
        let mut rng = crate::test_rng::XorShift(0x1A57_9017_7000_0001);
        for i in 0..6000 {
            let shift = [1, 20, 25][i % 3];
            let ends = if i % 6 < 3 {
                Ends::Closed
            } else {
                Ends::HalfOpen
            };
            let mut r = || (rng.next_u64() as i32) >> shift;
            let (p0, p1) = (Point::new(r(), r()), Point::new(r(), r()));
            let mut line = if shift == 1 {
                // Long lines (up to 2^31 pixels): clipped to a small window around p1, so the
                // state starts mid-line and few pixels remain.
                let (p0, p1) = (p0 / 2, p1 / 2); // within ±2^29: clipping's range
                let w = Window::new(p1.x - 20, p1.y - 20, p1.x + 20, p1.y + 20);
                assert_eq!(Bresenham::new(p0, p1).last_point(), p1);
                Bresenham::clipped(p0, p1, ends, &w).unwrap()
            } else {
                Bresenham::with_ends(p0, p1, ends)
            };
            // The last pixel does not move as the iterator advances.
            for _ in 0..i % 3 {
                if line.remaining() > 1 {
                    line.next();
                }
            }
            if line.remaining() > 0 {
                assert_eq!(
                    Some(line.last_point()),
                    line.clone().last(),
                    "{p0:?} {p1:?} {ends:?}"
                );
            }
        }
        // Short lines in every direction, both end treatments, clipped to windows that cut
        // them anywhere.
        for dx in -6..=6 {
            for dy in -6..=6 {
                let (p0, p1) = (Point::new(3, 2), Point::new(3 + dx, 2 + dy));
                for ends in [Ends::Closed, Ends::HalfOpen] {
                    let w = Window::new(0, 0, 7, 6);
                    for line in [
                        Bresenham::with_ends(p0, p1, ends),
                        Bresenham::clipped(p0, p1, ends, &w).unwrap(),
                    ] {
                        if line.remaining() > 0 {
                            assert_eq!(Some(line.last_point()), line.clone().last());
                        }
                    }
                }
            }
        }
        let far = Bresenham::new(Point::new(i32::MIN, i32::MIN), Point::new(i32::MAX, 5));
        assert_eq!(far.last_point(), Point::new(i32::MAX, 5));
        // Half open across the whole range: the pixel before p1, found independently as the
        // second pixel of the reversed line (same pixels by symmetry).
        let (p0, p1) = (Point::new(i32::MAX, i32::MIN), Point::new(i32::MIN, 5));
        let far = Bresenham::half_open(p0, p1);
        assert_eq!(Some(far.last_point()), Bresenham::new(p1, p0).nth(1));
        assert_eq!(far.last_point(), Point::new(i32::MIN + 1, 4));
    }
}
