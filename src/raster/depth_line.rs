//! The depth line walker: a [`SubpixelLine`]'s pixels with an exactly rounded depth at each,
//! tested against and written into the depth buffer (the 3D lines of `render::lines`).
//!
//! Role in the pipeline: the raster stage of a 3D segment, after the 3D clip and the
//! projection of its end points (sub-pixel positions and 32-bit depths `D₀`, `D₁`).
//!
//! ## Depth at a pixel (the definition the code implements)
//! The projection's depth is affine in screen space (`project.rs`), so along the projected
//! segment it is affine in the major coordinate. A pixel whose centre is `δ` sub-pixel units
//! along the major axis from the first end point (`0 ≤ δ ≤ n`, `n` the major extent) takes
//! the depth of the exact segment there, **rounded to nearest, ties up**:
//! `D(δ) = ⌊(2·D₀·n + 2·δ·(D₁ − D₀) + n) / 2n⌋`, between `D₀` and `D₁` (so it fits `u32`),
//! the same from either end. A segment of zero length takes the nearer end's depth.
//!
//! The walk is incremental and exact: each major step adds `U·(D₁ − D₀)/n` (`U = 2^S`) as a
//! quotient and a remainder; the remainder of the numerator above is constant modulo 2, so
//! its half, kept as an error in `[−n, 0)` like the line's own, decides the carries. No
//! division after set-up; the `i64` error holds `n ≤ 2^31`. The set-up's numerator
//! (`2·D₀·n + 2·δ·(D₁ − D₀) + n < 2^66`) is an `i128`; its two divisions take the 64-bit
//! routine when the operands fit `i64` (`n < 2^29` with 32-bit depths, every segment of a
//! frame in practice: `arith::euclid::div_floor_i128`).
//!
//! ## The depth test and its offset
//! A line pixel at depth `d` is **pulled toward the eye by `offset`** (32-bit depth units,
//! saturating at 0) and then takes the z-buffer's own strict test: it is drawn, and its pulled
//! depth stored, where `from_depth32(d − offset)` is nearer than the stored sample. The offset
//! lets the edges of a surface show on that surface: the surface stores its plane's depth at
//! the pixel centre, up to half a pixel off the edge, so the edge's own depth may lie behind
//! it by half a pixel of the surface's depth slope. See `render::lines` for the default.
//!
//! ## Two ends (course ch. 2, exercise 10)
//! [`Walk::TwoEnded`] walks the same pixels from both ends at once, the first half forward
//! and the second backward, one loop iteration per pair of pixels: the backward state is the
//! forward one mirrored (`g = −n − 1 − e` for both the line's and the depth's errors, steps
//! negated), so the pixels and their depths are those of the one-ended walk (tested).

use super::line::{Bresenham, SubpixelLine};
use crate::arith::euclid::div_floor_i128;
use crate::output::DepthValue;
use embedded_graphics_core::geometry::Point;

/// Which way a line's pixels are walked: the same pixels and depths either way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Walk {
    /// From the first end point to the last (the course's Bresenham).
    #[default]
    OneEnded,
    /// From both ends toward the middle (the course's chapter 2, exercise 10).
    TwoEnded,
}

/// The exact incremental depth along a line (module doc): depth, error in `[−n, 0)`, and the
/// per-step quotient and remainder.
#[derive(Debug, Clone, Copy)]
struct DepthStep {
    depth: u32,
    error: i64,
    quotient: u32,
    remainder: i64,
    n: i64,
    carry: u32,
}

impl DepthStep {
    /// The depth at `travel` (sub-pixel units from the first end), stepping `unit` per pixel
    /// forward, or backward when `back`.
    fn at(line: &SubpixelLine, d0: u32, d1: u32, travel: u64, back: bool) -> DepthStep {
        let n = line.length as i128;
        if n == 0 {
            return DepthStep {
                depth: d0.min(d1),
                error: -1,
                quotient: 0,
                remainder: 0,
                n: 1,
                carry: 0,
            };
        }
        let delta = d1 as i128 - d0 as i128;
        let num = 2 * d0 as i128 * n + 2 * travel as i128 * delta + n;
        let (depth, rem) = div_floor_i128(num, 2 * n);
        let depth = depth as u32; // between d0 and d1
        let error = (rem / 2 - n) as i64;
        let step = line.unit as i128 * delta;
        let (q, r) = div_floor_i128(step, n);
        let r = r as i64;
        if back {
            DepthStep {
                depth,
                error: -(n as i64) - 1 - error,
                quotient: (q as u32).wrapping_neg(),
                remainder: r,
                n: n as i64,
                carry: u32::MAX,
            }
        } else {
            DepthStep {
                depth,
                error,
                quotient: q as u32,
                remainder: r,
                n: n as i64,
                carry: 1,
            }
        }
    }

    /// Moves one pixel along.
    #[inline(always)]
    fn step(&mut self) {
        self.depth = self.depth.wrapping_add(self.quotient);
        self.error += self.remainder;
        if self.error >= 0 {
            self.error -= self.n;
            self.depth = self.depth.wrapping_add(self.carry);
        }
    }
}

/// The buffers a depth line writes: a frame's indices and its depth samples, each with its
/// stride and first row; every pixel handed to it lies in both (the line was clipped to the
/// window they share), and each access is still checked.
pub(crate) struct LineTarget<'a, D> {
    pub(crate) pixels: &'a mut [u8],
    pub(crate) stride: usize,
    pub(crate) top: i32,
    pub(crate) depths: &'a mut [D],
    pub(crate) depth_stride: usize,
    pub(crate) depth_top: i32,
}

impl<D: DepthValue> LineTarget<'_, D> {
    /// The depth test of one pixel (module doc); true when it was drawn.
    #[inline(always)]
    pub(crate) fn plot(&mut self, p: Point, depth: u32, offset: u32, index: u8) -> bool {
        let (x, y) = (p.x as usize, p.y.wrapping_sub(self.top) as usize);
        let dy = p.y.wrapping_sub(self.depth_top) as usize;
        let at = y.wrapping_mul(self.stride).wrapping_add(x);
        let dat = dy.wrapping_mul(self.depth_stride).wrapping_add(x);
        let pulled = D::from_depth32(depth.saturating_sub(offset).min(D::MAX_DEPTH32));
        match (self.depths.get_mut(dat), self.pixels.get_mut(at)) {
            (Some(stored), Some(pixel)) if pulled.nearer(*stored) => {
                *stored = pulled;
                *pixel = index;
                true
            }
            _ => false,
        }
    }
}

/// Draws `line` (end depths `d0`, `d1`) into `target` with the depth test pulled by `offset`
/// (module doc), walked as `walk` says. Returns the pixels drawn.
pub(crate) fn draw_depth_line<D: DepthValue>(
    target: &mut LineTarget<'_, D>,
    line: &SubpixelLine,
    (d0, d1): (u32, u32),
    offset: u32,
    index: u8,
    walk: Walk,
) -> u32 {
    let mut front = line.pixels.clone();
    let mut depth = DepthStep::at(line, d0, d1, line.travel, false);
    let total = front.remaining();
    let mut drawn = 0;
    let mut one = |p: Option<Point>, d: &mut DepthStep, target: &mut LineTarget<'_, D>| {
        if let Some(p) = p {
            drawn += target.plot(p, d.depth, offset, index) as u32;
            d.step();
        }
    };
    match walk {
        Walk::OneEnded => {
            for _ in 0..total {
                one(front.next(), &mut depth, target);
            }
        }
        Walk::TwoEnded => {
            let mut back: Bresenham = line.back.clone();
            let mut back_depth = DepthStep::at(line, d0, d1, line.travel_last, true);
            for _ in 0..total / 2 {
                one(front.next(), &mut depth, target);
                one(back.next(), &mut back_depth, target);
            }
            if total % 2 == 1 {
                one(front.next(), &mut depth, target);
            }
        }
    }
    drawn
}

/// The pixels of `line` with their depths (the one-ended walk, or the two-ended one in the
/// order it visits them), for the tests that compare both walks and the float reference.
#[cfg(test)]
pub(crate) fn depth_pixels(
    line: &SubpixelLine,
    d0: u32,
    d1: u32,
    walk: Walk,
    out: &mut heapless::Vec<(Point, u32), 512>,
) {
    let mut front = line.pixels.clone();
    let mut depth = DepthStep::at(line, d0, d1, line.travel, false);
    let total = front.remaining();
    let mut back = line.back.clone();
    let mut back_depth = DepthStep::at(line, d0, d1, line.travel_last, true);
    let mut take = |it: &mut Bresenham, d: &mut DepthStep| {
        if let Some(p) = it.next() {
            let _ = out.push((p, d.depth));
            d.step();
        }
    };
    match walk {
        Walk::OneEnded => (0..total).for_each(|_| take(&mut front, &mut depth)),
        Walk::TwoEnded => {
            for _ in 0..total / 2 {
                take(&mut front, &mut depth);
                take(&mut back, &mut back_depth);
            }
            if total % 2 == 1 {
                take(&mut front, &mut depth);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::{SubpixelPoint, Window};

    /// The definition, evaluated directly per pixel centre in `i128` (no walking): the pixels
    /// and depths of the exact segment, in order, inside `w`.
    fn by_definition<const S: u32>(
        p0: SubpixelPoint<S>,
        p1: SubpixelPoint<S>,
        d0: u32,
        d1: u32,
        w: &Window,
    ) -> heapless::Vec<(Point, u32), 512> {
        let u = 1i128 << S;
        let (dx, dy) = (p1.x as i128 - p0.x as i128, p1.y as i128 - p0.y as i128);
        let xm = dx.abs() >= dy.abs();
        let (m0, m1, v0, v1) = if xm {
            (p0.x as i128, p1.x as i128, p0.y as i128, p1.y as i128)
        } else {
            (p0.y as i128, p1.y as i128, p0.x as i128, p1.x as i128)
        };
        let n = (m1 - m0).abs();
        let s = if m1 >= m0 { 1 } else { -1 };
        let mut out = heapless::Vec::new();
        let (lo, hi) = (m0.min(m1), m0.max(m1));
        let mut ms: heapless::Vec<i128, 512> = heapless::Vec::new();
        let mut m = -((-lo).div_euclid(u));
        while m * u <= hi {
            let _ = ms.push(m);
            m += 1;
        }
        if s < 0 {
            ms.reverse();
        }
        for m in ms {
            let delta = (m * u - m0).abs();
            // minor value ·n = v0·n + (m·u − m0)·(v1 − v0)·s… as an exact rational over n·u.
            let (num, den) = if n == 0 {
                (v0, u)
            } else {
                (v0 * n + delta * (v1 - v0), n * u)
            };
            // Round num/den to nearest, ties toward the smaller: ⌈(2num − den) / 2den⌉.
            let minor = -((den - 2 * num).div_euclid(2 * den));
            let d = if n == 0 {
                d0.min(d1) as i128
            } else {
                (2 * d0 as i128 * n + 2 * delta * (d1 as i128 - d0 as i128) + n).div_euclid(2 * n)
            };
            let p = if xm {
                Point::new(m as i32, minor as i32)
            } else {
                Point::new(minor as i32, m as i32)
            };
            if w.contains(p.x, p.y) {
                let _ = out.push((p, d as u32));
            }
        }
        out
    }

    #[test]
    fn walks_match_the_definition() {
        let mut rng = crate::test_rng::XorShift(0x11E5_0DE7_4000_0003);
        let w = Window::new(-3, -2, 40, 30);
        for i in 0..20000 {
            let r = |rng: &mut crate::test_rng::XorShift, m: u64| (rng.next_u64() % m) as i32;
            let span = [8 * 16, 50 * 16, 400 * 16][i % 3];
            let mut c = || r(&mut rng, span as u64 * 2) - span + 16 * 16;
            let (p0, p1) = (
                SubpixelPoint::<4>::new(c(), c()),
                SubpixelPoint::new(c(), c()),
            );
            let d0 = rng.next_u64() as u32;
            let d1 = if i % 5 == 0 {
                d0
            } else {
                rng.next_u64() as u32
            };
            let want = by_definition(p0, p1, d0, d1, &w);
            let got = SubpixelLine::new(p0, p1, &w).unwrap();
            let Some(line) = got else {
                assert!(want.is_empty(), "{p0:?} {p1:?}");
                continue;
            };
            for walk in [Walk::OneEnded, Walk::TwoEnded] {
                let mut out = heapless::Vec::new();
                depth_pixels(&line, d0, d1, walk, &mut out);
                if walk == Walk::TwoEnded {
                    out.sort_by_key(|&(p, _)| {
                        want.iter().position(|&(q, _)| q == p).unwrap_or(usize::MAX)
                    });
                }
                assert_eq!(out, want, "{p0:?} {p1:?} {d0} {d1} {walk:?}");
            }
        }
    }

    #[test]
    fn lattice_end_points_give_the_lattice_line() {
        let w = Window::new(-20, -20, 20, 20);
        for (x0, y0, x1, y1) in [(0, 0, 7, 3), (5, -4, -6, 9), (2, 2, 2, -8), (-9, 1, 9, 2)] {
            let (p0, p1) = (Point::new(x0, y0), Point::new(x1, y1));
            let sp = |p: Point| SubpixelPoint::<4>::new(p.x * 16, p.y * 16);
            let line = SubpixelLine::new(sp(p0), sp(p1), &w).unwrap().unwrap();
            assert!(line.pixels().eq(Bresenham::new(p0, p1)), "{p0:?} {p1:?}");
        }
    }
}
