//! A stored triangle's plane in the painter's space `(X, Y, D)` (`painter.rs`'s module doc:
//! sub-pixel screen position and 32-bit depth), shared by the painter's tests and the pieces'
//! outlines (`outline.rs`), so that neither of them imports the other.
//!
//! Numeric contract: corners within `±(2^28 − 1)` sub-pixel units, depths `u32`. A normal
//! `(n_x, n_y, n_d)` has `|n_x|, |n_y| < 2^62` (two products of a `< 2^29` and a `< 2^32`
//! difference) and `n_d` = twice the screen area, `|n_d| < 2^59`: `i64`. A point's side of a
//! plane, `n·(p − p0)`, is below `2^62·2^29·2 + 2^59·2^32 < 2^93`: `i128`. Conventions: a
//! plane is oriented so that "behind" (a larger `D` at the same `(X, Y)`) is positive.

use super::store::StoredTriangle;

/// A front triangle's plane normal in `(X, Y, D)` (the painter's module doc), kept once per triangle by the
/// painter ([`PainterMemory::normals`](super::PainterMemory::normals)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Normal([i64; 3]);

impl Normal {
    /// An unused slot, for declaring a table (`[Normal::DEFAULT; N]`, also in a `static`).
    pub const DEFAULT: Normal = Normal([0; 3]);
}

impl Default for Normal {
    fn default() -> Self {
        Normal::DEFAULT
    }
}

/// A stored triangle's plane in `(X, Y, D)` (the painter's module doc), oriented so that
/// [`behind`](Self::behind) is positive behind it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plane {
    n: [i64; 3],
    origin: [i64; 3],
    /// `sign(n_d)`: +1 or −1 (stored triangles have area).
    facing: i128,
}

/// The stored triangles and their bases' normals.
pub(super) type Store<'a, const S: u32> = (&'a [StoredTriangle<S>], &'a [Normal]);

impl Plane {
    /// The plane of base triangle `base`, from its stored normal.
    pub(super) fn stored<const S: u32>((t, normals): Store<'_, S>, base: u32) -> Plane {
        let (t, n) = (&t[base as usize], normals[base as usize].0);
        Plane {
            n,
            origin: [t.v[0].x as i64, t.v[0].y as i64, t.depth[0] as i64],
            facing: if n[2] < 0 { -1 } else { 1 },
        }
    }

    pub(super) fn normal(&self) -> Normal {
        Normal(self.n)
    }

    pub(super) fn of<const S: u32>(t: &StoredTriangle<S>) -> Plane {
        let p = |k: usize| [t.v[k].x as i64, t.v[k].y as i64, t.depth[k] as i64];
        let (o, b, c) = (p(0), p(1), p(2));
        let e1 = [b[0] - o[0], b[1] - o[1], b[2] - o[2]];
        let e2 = [c[0] - o[0], c[1] - o[1], c[2] - o[2]];
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        Plane {
            n,
            origin: o,
            facing: if n[2] < 0 { -1 } else { 1 },
        }
    }

    /// Positive when corner `k` of `t` is behind the plane, zero on it, negative in front.
    pub(super) fn behind<const S: u32>(&self, t: &StoredTriangle<S>, k: usize) -> i128 {
        self.side(t, k).signum() * self.facing
    }

    /// `n·(p − p0)` at corner `k` of `t` (`|·| < 2^93`, module doc).
    fn side<const S: u32>(&self, t: &StoredTriangle<S>, k: usize) -> i128 {
        let p = [t.v[k].x as i64, t.v[k].y as i64, t.depth[k] as i64];
        (0..3)
            .map(|i| self.n[i] as i128 * (p[i] - self.origin[i]) as i128)
            .sum()
    }

    /// The side at each corner of `t`, positive behind the plane (`|·| < 2^93`).
    pub(super) fn oriented<const S: u32>(&self, t: &StoredTriangle<S>) -> [i128; 3] {
        [0, 1, 2].map(|k| self.side(t, k) * self.facing)
    }

    /// Whether the sample at pixel `(x, y)` of plane `on` lies behind this plane (`> 0`),
    /// exactly: `D_on(X, Y) = q + r/|n_d|` by Euclidean division, the side is
    /// `B + n_d'·r/|n_d|` with `B` an integer, decided by `B` alone when `|B| ≥ |n_d'|` and
    /// otherwise by `B·|n_d| + n_d'·r` (both `< 2^118`). The sample lies within `on`'s
    /// bounding box, where `|q| < 2^35`, so `B < 2^95`.
    #[cfg(test)]
    pub(super) fn sample_behind(&self, on: &Plane, x: i64, y: i64) -> bool {
        self.sample_side(on, x, y) > 0
    }

    /// The side of this plane of the sample at pixel `(x, y)` of plane `on`, exactly (as
    /// [`Self::sample_behind`]): 1 behind, 0 on it (the same depth), −1 in front.
    #[cfg(test)]
    pub(super) fn sample_side(&self, on: &Plane, x: i64, y: i64) -> i128 {
        self.sample_side_moved(on, x, y, 0)
    }

    /// One depth unit in the units of [`Self::oriented`]: `|n_d|` (`< 2^59`), since a point
    /// at depth `D` over `(X, Y)` has the side `|n_d|·(D − D_plane(X, Y))`.
    pub(super) fn unit(&self) -> i128 {
        (self.n[2] as i128).abs()
    }

    /// The depth of the plane at pixel `(x, y)` as the z-buffer stores it: the exact value
    /// rounded half up (`raster::triangle::plane`), `⌊D + 1/2⌋ = q + [2r ≥ |n_d|]` with
    /// `D = q + r/|n_d|` (`|q| < 2^35` within the triangle's bounding box, module doc).
    pub(super) fn rounded_depth(&self, x: i64, y: i64) -> i128 {
        let (q, r, den) = self.depth_at(x, y);
        q + (2 * r >= den) as i128
    }

    /// `(q, r, |n_d|)` with the plane's exact depth at pixel `(x, y)` equal to `q + r/|n_d|`,
    /// `0 ≤ r < |n_d|`.
    fn depth_at(&self, x: i64, y: i64) -> (i128, i128, i128) {
        let [ox, oy, od] = self.origin;
        let (dx, dy) = (x - ox, y - oy);
        // D = od − (n_x dx + n_y dy)/n_d.
        let num = -(self.n[0] as i128 * dx as i128 + self.n[1] as i128 * dy as i128);
        let den = self.n[2] as i128;
        let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
        (num.div_euclid(den) + od as i128, num.rem_euclid(den), den)
    }

    /// The side of this plane of the sample at pixel `(x, y)` of plane `on` moved `shift`
    /// depth units nearer (`|shift| ≤ 1`): the sign of `D_on − shift − D_self` there, exactly
    /// (as [`Self::sample_side`]).
    pub(super) fn sample_side_moved(&self, on: &Plane, x: i64, y: i64, shift: i64) -> i128 {
        let (q, r, den) = on.depth_at(x, y);
        let q = q - shift as i128;
        let [cx, cy, cd] = self.origin;
        let b = self.n[0] as i128 * (x - cx) as i128
            + self.n[1] as i128 * (y - cy) as i128
            + self.n[2] as i128 * (q - cd as i128);
        let nd = self.n[2] as i128;
        let side = if b.abs() >= nd.abs() {
            b.signum()
        } else {
            (b * den + nd * r).signum()
        };
        side * self.facing
    }
}
