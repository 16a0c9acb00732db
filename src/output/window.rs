//! [`Window`]: a half-open rectangle of pixels, the part of a picture a buffer holds or a
//! drawing may touch.
//!
//! Role in the pipeline: the output buffers say which pixels they hold
//! ([`Framebuffer::window`](super::Framebuffer::window)); the raster stage clips its spans,
//! lines and circles to a window.
//!
//! Numeric contract: `i32` bounds, compared only (nothing can overflow); `x0 ≤ x < x1`,
//! `y0 ≤ y < y1`, empty when `x1 ≤ x0` or `y1 ≤ y0`. Conventions: pixels are lattice points,
//! `y` grows downward (see [`raster`](crate::raster)).

/// A half-open rectangle of pixels: `x0 ≤ x < x1`, `y0 ≤ y < y1`. Empty when `x1 ≤ x0` or `y1 ≤ y0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Window {
    /// First column inside.
    pub x0: i32,
    /// First row inside.
    pub y0: i32,
    /// First column past the right side.
    pub x1: i32,
    /// First row past the bottom.
    pub y1: i32,
}

impl Window {
    /// The window `x0 ≤ x < x1`, `y0 ≤ y < y1`.
    pub const fn new(x0: i32, y0: i32, x1: i32, y1: i32) -> Self {
        Window { x0, y0, x1, y1 }
    }

    /// The window `0 ≤ x < width`, `0 ≤ y < height`.
    pub const fn of_size(width: u16, height: u16) -> Self {
        Window::new(0, 0, width as i32, height as i32)
    }

    /// True when no pixel is inside.
    pub const fn is_empty(&self) -> bool {
        self.x1 <= self.x0 || self.y1 <= self.y0
    }

    /// True when pixel `(x, y)` is inside.
    pub const fn contains(&self, x: i32, y: i32) -> bool {
        x >= self.x0 && x < self.x1 && y >= self.y0 && y < self.y1
    }

    /// The pixels inside both windows.
    pub fn intersect(&self, other: &Window) -> Window {
        Window::new(
            self.x0.max(other.x0),
            self.y0.max(other.y0),
            self.x1.min(other.x1),
            self.y1.min(other.y1),
        )
    }
}
