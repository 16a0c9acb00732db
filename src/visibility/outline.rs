//! A painter's piece judged by its own polygon: the outline of a stored triangle cut by the
//! planes of others (Newell's test 6), for tests 1–4 of `painter.rs`.
//!
//! A piece of triangle `P` is the part of `P` on one side of each of its cut planes. In `P`'s
//! plane a cut plane `Q` is a line, and the side of `Q` is an affine function of the point
//! that takes, at `P`'s corners, the exact `i128` values `q_k` (its oriented side there,
//! `Plane::oriented`). With barycentric weights `λ ≥ 0` over `P`'s corners the piece is
//! `{λ : Σ λ_k c_k ≥ 0 for each cut}`, `c = q` for the piece behind `Q` and `c = −q` in front.
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
//! Numeric contract: corner sides `|c_k| < 2^93` (`painter.rs`). Relaxed coefficients
//! `|c'| ≤ C = 2^b + 1` (`b` = [`CUT_BITS_TWO`] for pieces of one or two cuts,
//! [`CUT_BITS_THREE`] for three). Vertex weights: `U_0 = 1`, and a clip makes
//! `U_{i+1} ≤ 6·C·U_i²`: two cuts at `b = 24` give `U_2 ≤ 216·C³ < 2^80`, three at `b = 10`
//! give `U_3 ≤ 6·216²·C^7 < 2^89`. Evaluations: depths (`< 2^32`) and positions
//! (`< 2^28`) times three weights stay below `2^89·2^32·3 < 2^123`; plane sides are shifted so
//! that `|f'|·max μ·3 < 2^126`. All `i128`.

use super::painter::{Plane, Store};
use super::store::{StoredTriangle, CUT_FRONT, NO_CUT};

/// Bits of a relaxed cut's coefficients on a piece of one or two cuts.
const CUT_BITS_TWO: u32 = 24;
/// Bits of a relaxed cut's coefficients on a piece of three cuts.
const CUT_BITS_THREE: u32 = 10;

/// Vertices an outline may have: a triangle clipped by three lines.
const MAX_VERTICES: usize = 6;

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
    /// The outline of stored triangle `t` (the whole triangle when it has no cut).
    pub(super) fn of<const S: u32>(all: Store<'_, S>, t: &StoredTriangle<S>) -> Outline {
        let mut o = Outline {
            v: [[0; 3]; MAX_VERTICES],
            n: 3,
        };
        o.v[0] = [1, 0, 0];
        o.v[1] = [0, 1, 0];
        o.v[2] = [0, 0, 1];
        let cuts = t.cuts.iter().filter(|&&c| c != NO_CUT);
        let b = if cuts.clone().count() <= 2 {
            CUT_BITS_TWO
        } else {
            CUT_BITS_THREE
        };
        for &cut in cuts {
            let q = Plane::stored(all, cut & !CUT_FRONT).oriented(t);
            let c = if cut & CUT_FRONT == 0 {
                q
            } else {
                q.map(|x| -x)
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
