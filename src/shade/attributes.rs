//! Exact incremental interpolation of per-vertex integer attributes over a triangle.
//!
//! Role in the pipeline: between the triangle fill and the span writers. Depth, Gouraud
//! luminance and any other per-vertex quantity go through this one mechanism: an
//! [`AttributePlane<N>`] holds `N` attributes; at the start of each span it gives a
//! [`AttributeCursor<N>`] that steps one pixel right with integer adds only.
//!
//! ## What is computed
//! With vertices `P0, P1, P2` (sub-pixel units, `F = 2^S`) and values `A0, A1, A2`, the affine
//! interpolant at pixel `(x, y)` (the point `p = (x·F, y·F)`) is `A(p) = A0 + M(p) / D` with
//!
//! ```text
//! D    = (P1 − P0) × (P2 − P0)                   (twice the signed area; made positive)
//! M(p) = gx·(p.x − X0) + gy·(p.y − Y0)
//! gx   = (A1−A0)·(Y2−Y0) − (A2−A0)·(Y1−Y0)
//! gy   = (A2−A0)·(X1−X0) − (A1−A0)·(X2−X0)
//! ```
//!
//! and every pixel receives the **correctly rounded** value `A0 + ⌊(2M + D) / 2D⌋`
//! (round half up). The cursor keeps that quotient and its remainder `0 ≤ rem < 2D`: a step adds
//! a precomputed quotient and remainder and carries once, so there is no drift on any span
//! length (the exact variant of course exercise 18).
//!
//! ## Numeric contract
//! - Attribute values are `u32` (depth uses the full range). Values are added with wrapping
//!   arithmetic: at a covered pixel the true value is a convex combination of the vertex values,
//!   so it lies in `0..2^32` and the wrapped result equals it exactly.
//! - `0 < D < 2^30` (at `S = 4`, triangles up to 2 M square pixels): the remainder and `2D` fit
//!   `u32` with room for one addition. Larger triangles are rejected with
//!   [`PlaneError::TooLarge`]; the 3D pipeline's guard band keeps screen triangles far below.
//! - `|A1 − A0|, |A2 − A0| ≤ 2^32` and coordinate differences `< 2^29` give `|gx|, |gy| < 2^62`.
//!   `M` at a covered pixel is bounded by `D·2^32 < 2^62`; it is evaluated with wrapping
//!   products, exact because the true result is in range.

use crate::raster::SubpixelPoint;

/// Why an attribute plane could not be set up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlaneError {
    /// The triangle has zero area: it covers no pixel, nothing to interpolate.
    Degenerate,
    /// Twice the area is `2^30` sub-pixel units squared or more.
    TooLarge,
}

/// The per-pixel step of `N` attributes: add `q`, add `r` to the remainder, carry at `two_d`.
#[derive(Debug, Clone, Copy)]
pub struct AttributeStep<const N: usize> {
    q: [u32; N],
    r: [u32; N],
    two_d: u32,
}

/// `N` attribute values at one pixel, with the remainders that keep them exact.
#[derive(Debug, Clone, Copy)]
pub struct AttributeCursor<const N: usize> {
    /// The correctly rounded values at the current pixel.
    pub values: [u32; N],
    rem: [u32; N],
}

impl<const N: usize> AttributeCursor<N> {
    /// Moves one pixel to the right.
    #[inline(always)]
    pub fn step(&mut self, s: &AttributeStep<N>) {
        for i in 0..N {
            let t = self.rem[i] + s.r[i]; // both < 2^30·2: no overflow
            let carry = (t >= s.two_d) as u32;
            self.rem[i] = t - carry * s.two_d;
            self.values[i] = self.values[i].wrapping_add(s.q[i]).wrapping_add(carry);
        }
    }
}

/// The exact affine interpolant of `N` attributes over one triangle.
#[derive(Debug, Clone, Copy)]
pub struct AttributePlane<const N: usize, const S: u32> {
    origin: SubpixelPoint<S>,
    base: [u32; N],
    gx: [i64; N],
    gy: [i64; N],
    d: i64,
    step_x: AttributeStep<N>,
}

impl<const N: usize, const S: u32> AttributePlane<N, S> {
    /// Sets up the plane of `values[i]` at vertex `v[i]`.
    pub fn new(v: [SubpixelPoint<S>; 3], values: [[u32; N]; 3]) -> Result<Self, PlaneError> {
        let (x0, y0) = (v[0].x as i64, v[0].y as i64);
        let (dx1, dy1) = (v[1].x as i64 - x0, v[1].y as i64 - y0);
        let (dx2, dy2) = (v[2].x as i64 - x0, v[2].y as i64 - y0);
        let mut d = dx1 * dy2 - dy1 * dx2;
        if d == 0 {
            return Err(PlaneError::Degenerate);
        }
        let sign = d.signum();
        d = d.abs();
        if d >= 1 << 30 {
            return Err(PlaneError::TooLarge);
        }
        let mut gx = [0i64; N];
        let mut gy = [0i64; N];
        let mut q = [0u32; N];
        let mut r = [0u32; N];
        let f = 1i64 << S;
        for i in 0..N {
            let a1 = values[1][i] as i64 - values[0][i] as i64;
            let a2 = values[2][i] as i64 - values[0][i] as i64;
            gx[i] = sign * (a1 * dy2 - a2 * dy1);
            gy[i] = sign * (a2 * dx1 - a1 * dx2);
            // One pixel right adds 2·gx·F to 2M + D: quotient ⌊gx·F / D⌋ (mod 2^32), remainder
            // 2·(gx·F mod D). Split gx = D·g1 + g0 so no product exceeds 2^46.
            let (g1, g0) = (gx[i].div_euclid(d), gx[i].rem_euclid(d));
            let g0f = g0 << S;
            q[i] = (g1.wrapping_mul(f) + g0f / d) as u32;
            r[i] = (2 * (g0f % d)) as u32;
        }
        Ok(AttributePlane {
            origin: v[0],
            base: values[0],
            gx,
            gy,
            d,
            step_x: AttributeStep {
                q,
                r,
                two_d: (2 * d) as u32,
            },
        })
    }

    /// The values at pixel `(x, y)`, which must be covered by the triangle (see the module's
    /// numeric contract), ready to step right.
    #[inline]
    pub fn at(&self, x: i32, y: i32) -> AttributeCursor<N> {
        let px = ((x as i64) << S) - self.origin.x as i64;
        let py = ((y as i64) << S) - self.origin.y as i64;
        let two_d = 2 * self.d;
        let mut values = [0u32; N];
        let mut rem = [0u32; N];
        for i in 0..N {
            let m = self.gx[i]
                .wrapping_mul(px)
                .wrapping_add(self.gy[i].wrapping_mul(py));
            let t = 2 * m + self.d;
            values[i] = self.base[i].wrapping_add(t.div_euclid(two_d) as u32);
            rem[i] = t.rem_euclid(two_d) as u32;
        }
        AttributeCursor { values, rem }
    }

    /// The per-pixel step to the right.
    #[inline(always)]
    pub fn step_x(&self) -> &AttributeStep<N> {
        &self.step_x
    }

    /// The attribute values at vertex 0 (the values everywhere for a constant attribute).
    pub fn vertex0_values(&self) -> [u32; N] {
        self.base
    }

    /// True when attribute `i` is the same at every pixel (its plane is flat).
    pub fn is_constant(&self, i: usize) -> bool {
        self.gx.get(i) == Some(&0) && self.gy.get(i) == Some(&0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Correctly rounded interpolant, straight from barycentric coordinates in i128.
    fn exact(v: [SubpixelPoint<4>; 3], a: [u32; 3], x: i32, y: i32) -> u32 {
        let p = |q: SubpixelPoint<4>| (q.x as i128, q.y as i128);
        let ((x0, y0), (x1, y1), (x2, y2)) = (p(v[0]), p(v[1]), p(v[2]));
        let (px, py) = ((x as i128) << 4, (y as i128) << 4);
        let d = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
        let w1 = (px - x0) * (y2 - y0) - (py - y0) * (x2 - x0);
        let w2 = (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0);
        let w0 = d - w1 - w2;
        let num = w0 * a[0] as i128 + w1 * a[1] as i128 + w2 * a[2] as i128;
        let (num, d) = if d < 0 { (-num, -d) } else { (num, d) };
        (2 * num + d).div_euclid(2 * d) as u32
    }

    #[test]
    fn every_pixel_is_correctly_rounded() {
        let mut seed = 0xDEAD_BEEF_1234_5678u64;
        let mut rnd = |m: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed % m
        };
        let window = crate::raster::Window::new(0, 0, 64, 64);
        let mut checked = 0;
        for _ in 0..400 {
            let v = [0; 3].map(|_| SubpixelPoint::<4>::new(rnd(1024) as i32, rnd(1024) as i32));
            let a = [0; 3].map(|_| [rnd(1 << 32) as u32, rnd(256) as u32]);
            let Ok(plane) = AttributePlane::<2, 4>::new(v, a) else {
                continue;
            };
            crate::raster::triangle::fill_triangle(v, &window, |s| {
                let mut c = plane.at(s.x0, s.y);
                for x in s.x0..s.x1 {
                    for (i, &got) in c.values.iter().enumerate() {
                        let want = exact(v, [a[0][i], a[1][i], a[2][i]], x, s.y);
                        assert_eq!(got, want, "attr {i} at ({x},{}) of {v:?}", s.y);
                    }
                    checked += 1;
                    c.step(plane.step_x());
                }
            })
            .unwrap();
        }
        assert!(checked > 100_000, "{checked}");
    }

    #[test]
    fn rejects_degenerate_and_huge() {
        let p = SubpixelPoint::<4>::new;
        assert_eq!(
            AttributePlane::<1, 4>::new([p(0, 0), p(5, 5), p(10, 10)], [[0]; 3]).err(),
            Some(PlaneError::Degenerate)
        );
        assert_eq!(
            AttributePlane::<1, 4>::new([p(0, 0), p(1 << 16, 0), p(0, 1 << 15)], [[0]; 3]).err(),
            Some(PlaneError::TooLarge)
        );
    }
}
