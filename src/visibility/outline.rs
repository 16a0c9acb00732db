//! A painter's piece judged by its own polygon: the outline of a stored triangle cut by the
//! planes of others (Newell's test 6), for tests 1–4 of `painter.rs`.
//!
//! A piece may carry any number of cuts (as many as the store holds pieces); its outline is
//! clipped by the latest [`OUTLINE_CUTS`] of them. Dropping a cut only enlarges the polygon, so
//! the outline is still a superset of the piece, which is all the tests need (below).
//!
//! A piece of triangle `P` is the part of `P` on one side of each of its cut planes, its
//! samples sorted by the z-buffer's rounded depths (`painter.rs`'s `draw_piece`): within one
//! depth unit of the plane a sample may go either way. In `P`'s plane a cut plane `Q` is a
//! line, and the side of `Q` is an affine function of the point that takes, at `P`'s corners,
//! the exact `i128` values `q_k` (its oriented side there, `Plane::oriented`), `u` per depth
//! unit (`Plane::unit`). With barycentric weights `λ ≥ 0` over `P`'s corners the piece lies in
//! `{λ : Σ λ_k c_k ≥ 0 for each cut}`, `c = q + u` for the piece behind `Q` and `c = u − q` in
//! front (the cut moved one depth unit outward).
//!
//! **Superset, never smaller.** The outline relaxes each cut to small coefficients,
//! `c'_k = ⌊c_k / 2^m⌋ + 1` when `m > 0` (else `c'_k = c_k`): since `Σ λ_k = 1`,
//! `Σ λ_k c'_k > Σ λ_k c_k / 2^m ≥ 0` wherever the exact cut holds, so the relaxed polygon
//! contains the piece. Its vertices are exact homogeneous barycentric points (integers
//! `μ_k ≥ 0`, `Σ μ_k > 0`), clipped one relaxed cut after another (Sutherland–Hodgman: the
//! crossing of edge `u → w` is `|a(w)|·u + |a(u)|·w`, `a` the relaxed cut's value). Every test
//! evaluates an affine function at these vertices, where a convex polygon takes its extremes,
//! and rounds outward: depths and screen positions by floor and ceiling divisions, plane sides
//! by `⌊·/2^s⌋` (lower bound) or `⌈·/2^s⌉` (upper bound) of the corner values. So a test that
//! passes on the outline holds on the piece (what holds for a set holds for its subsets); an
//! outline that is empty means the piece has no sample at all. The relaxation moves a cut line
//! by at most `2^-10` of the corner values' range (`2^-24` with one or two cuts): outlines are
//! a sliver larger than their pieces, which costs nothing but, rarely, a test that would have
//! passed on the exact piece.
//!
//! Numeric contract: corner sides `|c_k| < 2^93 + 2^59 < 2^94` (`painter.rs`, `u < 2^59`). Relaxed coefficients
//! `|c'| ≤ C = 2^b + 1` (`b` = [`CUT_BITS_TWO`] for pieces of one or two cuts,
//! [`CUT_BITS_THREE`] for three). Vertex weights: `U_0 = 1`, and a clip makes
//! `U_{i+1} ≤ 6·C·U_i²`: two cuts at `b = 24` give `U_2 ≤ 216·C³ < 2^80`, three at `b = 10`
//! give `U_3 ≤ 6·216²·C^7 < 2^89`. Evaluations: depths (`< 2^32`) and positions
//! (`< 2^28`) times three weights stay below `2^89·2^32·3 < 2^123`; plane sides are shifted so
//! that `|f'|·max μ·3 < 2^126`. All `i128`.

use super::plane::{Plane, Store};
use super::store::{cuts, StoredTriangle, CUT_FRONT};

/// Bits of a relaxed cut's coefficients on a piece of one or two cuts.
const CUT_BITS_TWO: u32 = 24;
/// Bits of a relaxed cut's coefficients on a piece of three cuts.
const CUT_BITS_THREE: u32 = 10;

/// The cuts an outline is clipped by (a piece's latest; module doc): the bound of the vertex
/// weights below holds for three.
const OUTLINE_CUTS: usize = 3;

/// Vertices an outline may have: a triangle clipped by [`OUTLINE_CUTS`] lines, each clip
/// adding at most one vertex (so `clip` never drops one).
const MAX_VERTICES: usize = 3 + OUTLINE_CUTS;

/// A piece's outline (module doc): homogeneous barycentric vertices over its base triangle.
#[derive(Debug, Clone, Copy)]
pub(super) struct Outline {
    v: [[i128; 3]; MAX_VERTICES],
    n: usize,
}

/// Bits of `|x|` (0 for 0).
fn bits(x: i128) -> u32 {
    128 - x.unsigned_abs().leading_zeros()
}

impl Outline {
    /// The outline of stored triangle `t` (the whole triangle when it has no cut), clipped by
    /// its latest [`OUTLINE_CUTS`] cuts.
    pub(super) fn of<const S: u32>(all: Store<'_, S>, t: &StoredTriangle<S>) -> Outline {
        let mut o = Outline {
            v: [[0; 3]; MAX_VERTICES],
            n: 3,
        };
        o.v[0] = [1, 0, 0];
        o.v[1] = [0, 1, 0];
        o.v[2] = [0, 0, 1];
        let cuts = cuts(all.0, t).take(OUTLINE_CUTS);
        let b = if cuts.clone().count() <= 2 {
            CUT_BITS_TWO
        } else {
            CUT_BITS_THREE
        };
        for cut in cuts {
            let plane = Plane::stored(all, cut & !CUT_FRONT);
            let (q, unit) = (plane.oriented(t), plane.unit());
            let c = if cut & CUT_FRONT == 0 {
                q.map(|x| x + unit)
            } else {
                q.map(|x| unit - x)
            };
            o.clip(relaxed(c, b));
            if o.n == 0 {
                break;
            }
        }
        o
    }

    /// True when the piece has no point (so no sample).
    pub(super) fn is_empty(&self) -> bool {
        self.n == 0
    }

    fn vertices(&self) -> &[[i128; 3]] {
        &self.v[..self.n]
    }

    /// Keeps the part where `Σ λ_k c_k ≥ 0` (module doc).
    fn clip(&mut self, c: [i128; 3]) {
        let a = |u: &[i128; 3]| (0..3).map(|k| c[k] * u[k]).sum::<i128>();
        let mut out = [[0i128; 3]; MAX_VERTICES];
        let mut n = 0;
        for i in 0..self.n {
            let (u, w) = (self.v[i], self.v[(i + 1) % self.n]);
            let (au, aw) = (a(&u), a(&w));
            if au >= 0 && n < MAX_VERTICES {
                out[n] = u;
                n += 1;
            }
            if (au > 0 && aw < 0) || (au < 0 && aw > 0) {
                let (su, sw) = (aw.abs(), au.abs());
                if n < MAX_VERTICES {
                    out[n] = [0, 1, 2].map(|k| su * u[k] + sw * w[k]);
                    n += 1;
                }
            }
        }
        self.v = out;
        self.n = n;
    }

    /// `(⌊min⌋, ⌈max⌉)` over the outline of the affine function worth `f[k]` at corner `k`
    /// (`|f| < 2^33`).
    pub(super) fn range(&self, f: [i64; 3]) -> (i64, i64) {
        let (mut lo, mut hi) = (i64::MAX, i64::MIN);
        for u in self.vertices() {
            let num: i128 = (0..3).map(|k| u[k] * f[k] as i128).sum();
            let den: i128 = u.iter().sum();
            let (q, r) = (num.div_euclid(den), num.rem_euclid(den));
            lo = lo.min(q as i64);
            hi = hi.max(q as i64 + (r != 0) as i64);
        }
        (lo, hi)
    }

    /// Signs bounding the affine function worth `f[k]` at corner `k` (`|f| < 2^127`) over the
    /// outline: `(lo, hi)` with `lo ≥ 0` only if it is `≥ 0` everywhere and `hi ≤ 0` only if it
    /// is `≤ 0` everywhere (module doc).
    pub(super) fn side_bounds(&self, f: [i128; 3]) -> (i128, i128) {
        let weight = self
            .vertices()
            .iter()
            .flat_map(|u| u.iter())
            .map(|&x| bits(x))
            .max()
            .unwrap_or(0);
        let size = f.iter().map(|&x| bits(x)).max().unwrap_or(0);
        let s = (size + weight + 2).saturating_sub(126);
        let floor = f.map(|x| x >> s);
        let ceil = f.map(|x| -((-x) >> s));
        let (mut lo, mut hi) = (i128::MAX, i128::MIN);
        for u in self.vertices() {
            lo = lo.min((0..3).map(|k| u[k] * floor[k]).sum());
            hi = hi.max((0..3).map(|k| u[k] * ceil[k]).sum());
        }
        (lo, hi)
    }
}

/// The relaxed cut of the module doc, at most `b` bits (plus one).
fn relaxed(c: [i128; 3], b: u32) -> [i128; 3] {
    let m = c
        .iter()
        .map(|&x| bits(x))
        .max()
        .unwrap_or(0)
        .saturating_sub(b);
    if m == 0 {
        c
    } else {
        c.map(|x| (x >> m) + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::SubpixelPoint;
    use crate::test_rng::XorShift;
    use crate::visibility::plane::Normal;

    fn triangle(rng: &mut XorShift, base: u32) -> StoredTriangle<4> {
        let mut t = StoredTriangle::<4>::DEFAULT;
        t.v =
            [0; 3].map(|_| SubpixelPoint::new(rng.range(0, 640) as i32, rng.range(0, 480) as i32));
        t.depth = [0; 3].map(|_| rng.range(1 << 30, 3 << 30) as u32);
        t.base = base;
        t
    }

    /// Every sample a piece draws (the painter's exact per-sample side of each cut) lies in its
    /// outline's screen box, at a depth within its depth bounds, and on the side of every
    /// other plane the outline's side bounds claim; an empty outline has no such sample. The
    /// pieces take one to five cuts (the outline clips by the latest three).
    #[test]
    fn outlines_contain_their_pieces_samples() {
        let mut rng = XorShift::new(0x0017_0011);
        let mut checked = 0;
        for _ in 0..400 {
            let mut ts = [StoredTriangle::<4>::DEFAULT; 4 + 5];
            for (b, t) in ts.iter_mut().take(4).enumerate() {
                *t = triangle(&mut rng, b as u32);
            }
            if ts[..4].iter().any(|t| t.twice_area() == 0) {
                continue;
            }
            let mut normals = [Normal::DEFAULT; 4 + 5];
            for (n, t) in normals.iter_mut().zip(&ts[..4]) {
                *n = Plane::of(t).normal();
            }
            // The piece of triangle 0 cut `n` times (stored at 4.., each cut from the last),
            // by the planes of triangles 1 and 2 in turn (a plane may cut it more than once).
            let n = 1 + rng.below(5) as usize;
            let mut parent = 0;
            for k in 0..n {
                let mut piece = ts[0];
                piece.cut = (1 + (k % 2) as u32) | if rng.chance(50) { CUT_FRONT } else { 0 };
                piece.parent = parent;
                ts[4 + k] = piece;
                parent = (4 + k) as u32;
            }
            let piece = ts[parent as usize];
            let all = (&ts[..], &normals[..]);
            let outline = Outline::of(all, &piece);
            let own = Plane::stored(all, 0);
            let other = Plane::stored(all, 3);
            let sides = outline.side_bounds(other.oriented(&piece));
            let depths = piece.depth.map(|d| d as i64);
            let (d_lo, d_hi) = outline.range(depths);
            let (x_lo, x_hi) = outline.range(piece.v.map(|p| p.x as i64));
            let (y_lo, y_hi) = outline.range(piece.v.map(|p| p.y as i64));
            for y in (0..480).step_by(16) {
                for x in (0..640).step_by(16) {
                    // Inside the base triangle (closed), on each cut's kept side.
                    let e = |k: usize| {
                        let (p, q) = (piece.v[k], piece.v[(k + 1) % 3]);
                        (q.x as i64 - p.x as i64) * (y - p.y as i64)
                            - (q.y as i64 - p.y as i64) * (x - p.x as i64)
                    };
                    let orient = piece.twice_area().signum();
                    if (0..3).any(|k| e(k) * orient < 0) {
                        continue;
                    }
                    let kept = cuts(all.0, &piece).all(|c| {
                        let plane = Plane::stored(all, c & !CUT_FRONT);
                        plane.sample_behind(&own, x, y) == (c & CUT_FRONT == 0)
                    });
                    if !kept {
                        continue;
                    }
                    checked += 1;
                    assert!(!outline.is_empty());
                    assert!(x_lo <= x && x <= x_hi && y_lo <= y && y <= y_hi);
                    // The depth of P's plane at the sample, rounded to an integer: within
                    // the bounds.
                    let c = |k: usize| {
                        let p = piece.v[k];
                        [p.x as i128, p.y as i128, piece.depth[k] as i128]
                    };
                    let (o, b, q) = (c(0), c(1), c(2));
                    let (e1, e2) = (
                        [0, 1, 2].map(|i| b[i] - o[i]),
                        [0, 1, 2].map(|i| q[i] - o[i]),
                    );
                    let n = [
                        e1[1] * e2[2] - e1[2] * e2[1],
                        e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0],
                    ];
                    let num = -(n[0] * (x as i128 - o[0]) + n[1] * (y as i128 - o[1]));
                    let d = o[2] + num.div_euclid(n[2]);
                    assert!(
                        d_lo as i128 <= d && d <= d_hi as i128,
                        "{d} in {d_lo}..{d_hi}"
                    );
                    // The side of plane 3 at the sample agrees with the bounds' claims.
                    let behind = other.sample_behind(&own, x, y);
                    assert!(sides.0 <= 0 || behind, "{sides:?}");
                    assert!(sides.1 >= 0 || !behind, "{sides:?}");
                }
            }
        }
        assert!(checked > 1000, "{checked} samples checked");
    }
}
