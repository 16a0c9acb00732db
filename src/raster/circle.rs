//! Midpoint circles: integer-only, by octant symmetry, with clipping to a window.
//!
//! Role in the pipeline: a raster-stage primitive for overlays and debugging (markers, radar
//! rings). [`MidpointCircle`] iterates the pixels of a circle outline once each;
//! [`draw_circle`] writes them into a [`Framebuffer`], visiting only the part of each octant
//! that can fall inside the buffer's window.
//!
//! ## Which pixels a circle covers
//! For centre `(cx, cy)` and radius `r ≥ 1`, the first octant (`0 ≤ x ≤ y`, measured from the
//! centre, `y` pointing away from the centre) holds, for each column `x ≥ 0` with
//! `x ≤ y(x)`, the pixel `(x, y(x))` where
//!
//! ```text
//! y(x) = max { y : 4x² + (2y − 1)² < 4r² }
//! ```
//!
//! i.e. the midpoint `(x, y − ½)` between two candidate pixels is strictly inside the circle,
//! the one above it outside: the classical midpoint criterion. (`4x² + (2y − 1)² − 4r²` is odd,
//! so it is never zero: there are no ties.) The outline is the union of the eight reflections
//! `(±x, ±y)` and `(±y, ±x)` of those pixels, each pixel yielded once. Radius 0 is the centre
//! pixel alone.
//!
//! ## The iteration
//! The decision variable `D = 4(x + 1)² + (2y − 1)² − 4r²` (four times the classical one, to
//! stay in integers) starts at `5 − 4r`; each column adds `4(2x + 3)`, and `− 8(y − 1)` more
//! when `y` steps down (taken when `D ≥ 0`).
//!
//! ## Numeric contract
//! - [`MidpointCircle`] accepts any centre and any `u32` radius. `0 ≤ x ≤ y ≤ r < 2^32` and
//!   `|D| ≤ 16r + 16 < 2^37` are held in `i64`; absolute pixels are computed in `i64`, and those
//!   that do not fit `i32` are skipped (they lie outside every window).
//! - [`draw_circle`] needs `r ≤ `[`MAX_RADIUS`]` = 2^30` (else [`CircleError::RadiusTooLarge`],
//!   nothing drawn): it jumps into an octant at a given column with an integer square root of
//!   `4(r² − x²) − 1 < 2^62`, and `D` there is `4((x + 1)² − r²) + (2y − 1)²`, two terms below
//!   `2^62` of opposite signs. The cost is O(1) when the circle's bounding box misses the
//!   window and O(window width + height) otherwise, whatever the radius.

use crate::output::Framebuffer;
use crate::raster::Window;
use embedded_graphics_core::geometry::Point;

/// The largest radius [`draw_circle`] accepts: `2^30`.
pub const MAX_RADIUS: u32 = 1 << 30;

/// Why a circle could not be drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CircleError {
    /// The radius exceeds [`MAX_RADIUS`].
    RadiusTooLarge {
        /// The radius given.
        radius: u32,
    },
}

impl core::fmt::Display for CircleError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CircleError::RadiusTooLarge { radius } => {
                write!(f, "circle radius {radius} exceeds {MAX_RADIUS}")
            }
        }
    }
}

impl core::error::Error for CircleError {}

/// The eight reflections of an octant point `(x, y)`: signs of the two offsets and whether
/// `x` and `y` are swapped. Index 0 is the octant itself, `(x, y)` below the centre.
const REFLECTIONS: [(i64, i64, bool); 8] = [
    (1, 1, false),
    (-1, 1, false),
    (1, -1, false),
    (-1, -1, false),
    (1, 1, true),
    (-1, 1, true),
    (1, -1, true),
    (-1, -1, true),
];

/// The offset from the centre of reflection `k` of the octant point `(x, y)`.
#[inline]
fn reflect(k: usize, x: i64, y: i64) -> (i64, i64) {
    let (sx, sy, swap) = REFLECTIONS[k & 7];
    if swap {
        (sx * y, sy * x)
    } else {
        (sx * x, sy * y)
    }
}

/// True when reflection `k` of `(x, y)` is a pixel already produced by an earlier reflection:
/// sign flips of a zero offset (`x = 0`) and the swap when `x = y` give no new pixel.
#[inline]
fn is_duplicate(k: usize, x: i64, y: i64) -> bool {
    let (sx, sy, swap) = REFLECTIONS[k & 7];
    let flips_zero = x == 0 && if swap { sy < 0 } else { sx < 0 };
    let flips_zero_y = y == 0 && if swap { sx < 0 } else { sy < 0 };
    flips_zero || flips_zero_y || (swap && x == y)
}

/// The pixels of a midpoint circle outline, each once, as an allocation-free iterator.
///
/// Order: octant columns `x = 0, 1, …`, and for each the (up to) eight reflections.
/// See the [module documentation](self) for the definition and ranges.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct MidpointCircle {
    /// The centre, widened.
    cx: i64,
    /// The centre row, widened.
    cy: i64,
    /// Octant column of the current pixel (`0 ≤ x ≤ y`).
    x: i64,
    /// Octant row of the current pixel.
    y: i64,
    /// `4(x + 1)² + (2y − 1)² − 4r²`: the sign of the next midpoint.
    decision: i64,
    /// The next reflection of `(x, y)` to yield (`0..8`; 8 means advance to the next column).
    reflection: usize,
    /// True for radius 0 before its single pixel is yielded.
    single: bool,
}

impl MidpointCircle {
    /// The outline of the circle of `radius` around `centre`. Any centre and radius.
    pub fn new(centre: Point, radius: u32) -> MidpointCircle {
        let r = radius as i64;
        MidpointCircle {
            cx: centre.x as i64,
            cy: centre.y as i64,
            x: 0,
            y: r,
            decision: 5 - 4 * r,
            reflection: 0,
            single: radius == 0,
        }
    }
}

impl Iterator for MidpointCircle {
    type Item = Point;

    fn next(&mut self) -> Option<Point> {
        if self.single {
            self.single = false;
            self.x = 1; // ends the iteration below (x > y = 0)
            return to_point(self.cx, self.cy);
        }
        loop {
            if self.x > self.y {
                return None;
            }
            if self.reflection >= 8 {
                let (y, d) = step(self.x, self.y, self.decision);
                self.y = y;
                self.decision = d;
                self.x += 1;
                self.reflection = 0;
                continue;
            }
            let k = self.reflection;
            self.reflection += 1;
            if is_duplicate(k, self.x, self.y) {
                continue;
            }
            let (ox, oy) = reflect(k, self.x, self.y);
            if let Some(p) = to_point(self.cx + ox, self.cy + oy) {
                return Some(p);
            }
        }
    }
}

impl core::iter::FusedIterator for MidpointCircle {}

/// One column of the octant: the row and decision variable after `(x, y)`.
#[inline]
fn step(x: i64, y: i64, d: i64) -> (i64, i64) {
    if d < 0 {
        (y, d + 4 * (2 * x + 3))
    } else {
        (y - 1, d + 4 * (2 * x + 3) - 8 * (y - 1))
    }
}

/// The octant row `y(x)` and decision variable at column `x`, computed directly, or `None`
/// when column `x` has no pixel (`x ≥ r`). Requires `r ≤ MAX_RADIUS` and `0 ≤ x`.
fn octant_state_at(x: i64, r: i64) -> Option<(i64, i64)> {
    if x >= r {
        return None;
    }
    // Q = 4(r² − x²) ≤ 2^62; y(x) is the largest y with (2y − 1)² < Q, i.e. 2y − 1 ≤ isqrt(Q − 1).
    let q = 4 * ((r * r) - (x * x)) as u64;
    let s = (q - 1).isqrt() as i64;
    let y = (s + 1) / 2;
    let d = 4 * ((x + 1) * (x + 1) - r * r) + (2 * y - 1) * (2 * y - 1);
    Some((y, d))
}

/// `(x, y)` as a [`Point`] when both fit `i32`.
#[inline]
fn to_point(x: i64, y: i64) -> Option<Point> {
    Some(Point::new(i32::try_from(x).ok()?, i32::try_from(y).ok()?))
}

/// Draws the outline of the circle of `radius` around `centre` into `fb` with palette
/// `index`: exactly the pixels of [`MidpointCircle::new`]`(centre, radius)` inside the buffer's
/// window (bands included). Any centre; errors (nothing drawn) when `radius > `[`MAX_RADIUS`].
pub fn draw_circle(
    fb: &mut Framebuffer<'_>,
    centre: Point,
    radius: u32,
    index: u8,
) -> Result<(), CircleError> {
    if radius > MAX_RADIUS {
        return Err(CircleError::RadiusTooLarge { radius });
    }
    let window = fb.window();
    let (cx, cy, r) = (centre.x as i64, centre.y as i64, radius as i64);
    let (wx0, wy0, wx1, wy1) = (
        window.x0 as i64,
        window.y0 as i64,
        window.x1 as i64 - 1,
        window.y1 as i64 - 1,
    );
    // Bounding box test: O(1) rejection.
    if window.is_empty() || cx + r < wx0 || cx - r > wx1 || cy + r < wy0 || cy - r > wy1 {
        return Ok(());
    }
    let put = |fb: &mut Framebuffer<'_>, px: i64, py: i64| {
        if px < wx0 || px > wx1 || py < wy0 || py > wy1 {
            return;
        }
        // Inside the window, so both fit i32 and the lookups succeed; still no panic path.
        if let (Ok(y), Ok(x)) = (i32::try_from(py), usize::try_from(px)) {
            if let Some(p) = fb.row_mut(y).and_then(|row| row.get_mut(x)) {
                *p = index;
            }
        }
    };
    if radius == 0 {
        put(fb, cx, cy);
        return Ok(());
    }
    for (k, &(sx, sy, swap)) in REFLECTIONS.iter().enumerate() {
        // The octant column x moves the screen coordinate `along` by `sign · x`.
        let (along, sign, lo, hi) = if swap {
            (cy, sy, wy0, wy1)
        } else {
            (cx, sx, wx0, wx1)
        };
        let (x_lo, x_hi) = if sign > 0 {
            (lo - along, hi - along)
        } else {
            (along - hi, along - lo)
        };
        let mut x = x_lo.max(0);
        let Some((mut y, mut d)) = octant_state_at(x, r) else {
            continue;
        };
        while x <= y && x <= x_hi {
            let (ox, oy) = reflect(k, x, y);
            put(fb, cx + ox, cy + oy);
            (y, d) = step(x, y, d);
            x += 1;
        }
    }
    Ok(())
}

/// The bounding window of a circle's outline, clamped to `i32` (for dirty rectangles).
pub fn bounding_window(centre: Point, radius: u32) -> Window {
    let clamp = |v: i64| v.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
    let (cx, cy, r) = (centre.x as i64, centre.y as i64, radius as i64);
    Window::new(
        clamp(cx - r),
        clamp(cy - r),
        clamp(cx + r + 1),
        clamp(cy + r + 1),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_zero_and_one() {
        let mut c = MidpointCircle::new(Point::new(3, 4), 0);
        assert_eq!(c.next(), Some(Point::new(3, 4)));
        assert_eq!(c.next(), None);
        // r = 1: y(0) = 1, y(1) = 0 (4 + 1 < 4 fails) → the four neighbours.
        let mut v: heapless::Vec<(i32, i32), 16> = MidpointCircle::new(Point::new(0, 0), 1)
            .map(|p| (p.x, p.y))
            .collect();
        v.sort_unstable();
        assert_eq!(&v[..], &[(-1, 0), (0, -1), (0, 1), (1, 0)]);
    }

    #[test]
    fn radius_two_by_hand() {
        // y(0) = 2; x = 1: 4 + (2y−1)² < 16 → y = 2 (9 < 12); x = 2 > y(2) = 1 stops.
        let mut v: heapless::Vec<(i32, i32), 16> = MidpointCircle::new(Point::new(0, 0), 2)
            .map(|p| (p.x, p.y))
            .collect();
        assert_eq!(v.len(), 12);
        v.sort_unstable();
        let mut want = [
            (0, 2),
            (0, -2),
            (2, 0),
            (-2, 0),
            (1, 2),
            (-1, 2),
            (1, -2),
            (-1, -2),
            (2, 1),
            (-2, 1),
            (2, -1),
            (-2, -1),
        ];
        want.sort_unstable();
        assert_eq!(&v[..], &want[..]);
    }

    #[test]
    fn direct_state_matches_incremental() {
        for r in 1..200i64 {
            let (mut x, mut y, mut d) = (0i64, r, 5 - 4 * r);
            while x <= y {
                assert_eq!(octant_state_at(x, r), Some((y, d)), "r {r} x {x}");
                (y, d) = step(x, y, d);
                x += 1;
            }
        }
        // Largest radius: no overflow, sane row.
        let r = MAX_RADIUS as i64;
        let (y, _) = octant_state_at(r / 2, r).unwrap();
        assert!(y > r / 2 && y < r);
    }

    #[test]
    fn huge_radius_far_centre_costs_nothing() {
        let mut buf = [0u8; 16 * 16];
        let mut fb = Framebuffer::new(&mut buf, 16, 16).unwrap();
        draw_circle(&mut fb, Point::new(i32::MAX, i32::MIN), MAX_RADIUS, 1).unwrap();
        assert!(buf.iter().all(|&p| p == 0));
        let mut fb = Framebuffer::new(&mut buf, 16, 16).unwrap();
        assert!(draw_circle(&mut fb, Point::new(0, 0), MAX_RADIUS + 1, 1).is_err());
        // Crossing the window with the largest radius: the arc is nearly a vertical line.
        draw_circle(&mut fb, Point::new(5 - MAX_RADIUS as i32, 8), MAX_RADIUS, 7).unwrap();
        for y in 0..16 {
            assert_eq!(fb.pixel(5, y), Some(7), "row {y}");
        }
    }
}
