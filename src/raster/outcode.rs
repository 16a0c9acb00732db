//! Cohen–Sutherland outcodes: where a point lies relative to a half-open [`Window`].
//!
//! Role in the pipeline: the raster stage classifies the two ends of a 2D line against the
//! drawing window before walking it ([`crate::raster::line`]). Two codes decide the easy
//! cases in O(1): both zero → the segment is entirely inside (*trivial accept*); a common bit
//! → both ends are beyond the same side, so is every point between them (*trivial reject*,
//! the window being convex). Anything else needs the exact clipping of the line module.
//!
//! Numeric contract: only comparisons of `i32` values, nothing can overflow. The window is
//! half-open like every [`Window`]: a point is [`LEFT`](Outcode::LEFT) when `x < x0`,
//! [`RIGHT`](Outcode::RIGHT) when `x ≥ x1`, [`TOP`](Outcode::TOP) when `y < y0` (y grows
//! downward, so "top" is the small-`y` side) and [`BOTTOM`](Outcode::BOTTOM) when `y ≥ y1`.
//! For an empty window every point gets at least one bit; a point may then be both `LEFT` and
//! `RIGHT` (when `x1 ≤ x < x0`), which is harmless: no point is ever reported inside.

use super::Window;

/// The Cohen–Sutherland code of a point: a set of the four sides of a window it lies beyond.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Outcode(u8);

impl Outcode {
    /// Inside the window: no bit set.
    #[cfg(test)]
    pub const INSIDE: Outcode = Outcode(0);
    /// Left of the window: `x < x0`.
    pub const LEFT: Outcode = Outcode(1);
    /// Right of the window: `x ≥ x1`.
    pub const RIGHT: Outcode = Outcode(2);
    /// Above the window (small `y`): `y < y0`.
    pub const TOP: Outcode = Outcode(4);
    /// Below the window (large `y`): `y ≥ y1`.
    pub const BOTTOM: Outcode = Outcode(8);

    /// The code of point `(x, y)` against `window`.
    #[inline]
    pub const fn of(x: i32, y: i32, window: &Window) -> Outcode {
        let mut bits = 0;
        if x < window.x0 {
            bits |= Self::LEFT.0;
        }
        if x >= window.x1 {
            bits |= Self::RIGHT.0;
        }
        if y < window.y0 {
            bits |= Self::TOP.0;
        }
        if y >= window.y1 {
            bits |= Self::BOTTOM.0;
        }
        Outcode(bits)
    }

    /// The raw bits (`LEFT = 1`, `RIGHT = 2`, `TOP = 4`, `BOTTOM = 8`).
    #[inline]
    #[cfg(test)]
    pub const fn bits(self) -> u8 {
        self.0
    }

    /// True when the point is inside the window (no bit set).
    #[inline]
    #[cfg(test)]
    pub const fn is_inside(self) -> bool {
        self.0 == 0
    }

    /// True when every side in `other` is also in `self`.
    #[inline]
    #[cfg(test)]
    pub const fn contains(self, other: Outcode) -> bool {
        self.0 & other.0 == other.0
    }

    /// The sides in either code.
    #[inline]
    #[cfg(test)]
    pub const fn or(self, other: Outcode) -> Outcode {
        Outcode(self.0 | other.0)
    }

    /// Trivial accept of segment `a`–`b`: both ends inside, hence the whole segment.
    #[inline]
    pub const fn trivially_inside(a: Outcode, b: Outcode) -> bool {
        a.0 | b.0 == 0
    }

    /// Trivial reject of segment `a`–`b`: both ends beyond one same side, hence the whole
    /// segment is outside.
    #[inline]
    pub const fn trivially_outside(a: Outcode, b: Outcode) -> bool {
        a.0 & b.0 != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_of_a_half_open_window() {
        let w = Window::new(2, 3, 6, 5); // x in 2..6, y in 3..5
        assert_eq!(Outcode::of(2, 3, &w), Outcode::INSIDE);
        assert_eq!(Outcode::of(5, 4, &w), Outcode::INSIDE);
        assert_eq!(Outcode::of(1, 3, &w), Outcode::LEFT);
        assert_eq!(Outcode::of(6, 3, &w), Outcode::RIGHT);
        assert_eq!(Outcode::of(2, 2, &w), Outcode::TOP);
        assert_eq!(Outcode::of(2, 5, &w), Outcode::BOTTOM);
        assert_eq!(Outcode::of(-9, 99, &w), Outcode::LEFT.or(Outcode::BOTTOM));
        assert_eq!(Outcode::of(i32::MAX, i32::MIN, &w).bits(), 2 | 4);
    }

    #[test]
    fn inside_matches_window_contains() {
        let w = Window::new(-2, -1, 3, 2);
        for y in -5..6 {
            for x in -5..6 {
                assert_eq!(Outcode::of(x, y, &w).is_inside(), w.contains(x, y));
            }
        }
    }

    #[test]
    fn trivial_cases() {
        let w = Window::new(0, 0, 10, 10);
        let a = Outcode::of(-1, 5, &w);
        let b = Outcode::of(-3, 50, &w);
        assert!(Outcode::trivially_outside(a, b));
        assert!(!Outcode::trivially_inside(a, b));
        let c = Outcode::of(20, 5, &w);
        assert!(!Outcode::trivially_outside(a, c)); // crosses the window
        assert!(Outcode::trivially_inside(
            Outcode::of(0, 0, &w),
            Outcode::of(9, 9, &w)
        ));
        assert!(b.contains(Outcode::LEFT) && b.contains(Outcode::BOTTOM));
        assert!(!b.contains(Outcode::TOP));
    }

    #[test]
    fn empty_window_has_no_inside() {
        let w = Window::new(4, 4, 4, 9);
        for x in 0..8 {
            assert!(!Outcode::of(x, 5, &w).is_inside());
        }
    }
}
