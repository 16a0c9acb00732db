//! The textured span kind: which texel each pixel of a span shows, exactly or fast.
//!
//! Role in the pipeline: one more span kind of the one triangle writer (`kinds`, `spans`),
//! set up once per triangle by [`TexturedKind::new`] and drawn over the depth plane (and the
//! luminance plane when lit) by the same span loop, `depth_span`, whose `Shading` here is a
//! texel: a palette index read from the [`Texture`], through the [`ShadeTable`] when lit.
//!
//! ## What is computed (the `texture` module's definition)
//! With the triangle's given vertices `P_i` (sub-pixel units, `F = 2^S`), `D = (P1 − P0) ×
//! (P2 − P0)` and a per-vertex value `a_i`, the plane `D·a(p) = D·a0 + gx·(p.x − X0) +
//! gy·(p.y − Y0)` (the `plane` module's `gx`, `gy`) is an integer at every pixel point
//! `p = (x·F, y·F)`: no rounding. Three such planes, of the weights `q_i`, of `q_i·u_i` and of
//! `q_i·v_i`, made positive inside the triangle (all negated when `D < 0`), give
//! `Q = 256·D·q(p)`, `N_u = W·D·(qu)(p)`, `N_v = H·D·(qv)(p)`, and the texel column is
//! `t_u = ⌊N_u / Q⌋` (`u` in Q8.8: `W·u/256` texels), the row `t_v = ⌊N_v / Q⌋`, both the
//! floors of the exact perspective-correct coordinate at the pixel.
//!
//! - **Exact** ([`TextureMode::Exact`]): `Q` steps by one add per pixel, and so does the
//!   remainder `r = N − Q·t` of the previous texel `t` (by `dN − dQ·t`, kept beside it); `r` is
//!   tested against `0 ≤ r < Q`; outside, `t` moves by one (one more compare) or, past that
//!   (minified texels, out of line), by one per `Q` taken off `r` (or added) up to eight
//!   texels, and by the Euclidean quotient `⌊r / Q⌋` beyond. Every pixel gets the exact
//!   floor, with no multiply and no division on the common path.
//!
//! The texel is read by masks when both sides are powers of two, else wrapped or clamped per
//! side, and turned into an index through the shade table when lit: each combination has its
//! own span loop, so that a pixel tests neither.
//! - **Subdivided** (8 or 16 pixels) and **affine**: the exact value `⌊2^16·N / Q⌋` (texels
//!   in 16.16) at a segment's ends, a 16.16 step between; affine objects take `q_i = 1`
//!   (the planes of `u` and `v` themselves) and one segment per span.
//!
//! Numeric contract: vertices within the raster's range (`|x|, |y| < 2^28`, `S ≤ 16`, so
//! `|D| < 2^58` and coordinate differences `< 2^29`), weights `1 ≤ q < 2^16`, coordinates
//! Q8.8 (`|u| ≤ 2^15`), sides `≤ 2^10`: every set-up product is below `2^101` (`i128`).
//! The set-up runs in `i64` instead when the given vertices' coordinates and their
//! differences are below `2^14` in size and the plane's values (`256·q_i`, `W·q_i·u_i`,
//! `H·q_i·v_i`) below `2^31`, both checked per plane: then `|D| < 2^29`, the gradients are
//! below `2^47`, and `D·a_0 − gx·X0 − gy·Y0` below `2^60 + 2·2^61 < 2^63`; the shift by `S`
//! and the sign are applied after widening to `i128`.
//! Per pixel the planes run in `i64` when their bound over the triangle leaves room
//! (`|N| + Q·(|t| + 2) < 2^62` at every covered pixel, checked once per triangle), else in
//! `i128`; both with wrapping adds, exact at covered pixels, where the true values are in
//! range (the step past a span's last pixel may leave it, and its value is never read; a
//! non-positive `Q` there moves nothing). The span's start (`N`, `Q` at its first pixel and
//! the floors `⌊N / Q⌋`) is evaluated in the same type: under the `i64` bound the planes'
//! low 64 bits, multiplied and added modulo `2^64`, give the exact values (they lie in
//! range at a covered pixel), and the division is a 64-bit one instead of a 128-bit one.
//! The floors there are first guessed as the previous span's first texels (the same
//! triangle's, so `|t|` within its bound above, and the remainder `N − Q·t` in range):
//! a guess is kept when its remainder lies in `[0, Q)`, moved by one when it lies one `Q`
//! outside, and only otherwise replaced by the division; the floor is the one integer with
//! that remainder, so the guess changes no texel.
//! Likewise a segment end's `⌊2^16·N / Q⌋` runs in `i64` when `2^16·|N| < 2^63` and
//! `Q < 2^62` at every covered pixel (`|N| < 2^47`, checked once per triangle); else, under
//! the exact mode's `i64` bound, as `2^16·t + ⌊2^16·r / Q⌋` with `t = ⌊N / Q⌋` and
//! `r = N − Q·t` (`0 ≤ r < Q < 2^62`: sixteen steps of long division, each doubling `r`
//! below `2^63`); else in `i128`. A segment's step divides by its length with a shift when
//! that is a power of two (the floor either way).

use super::interpolants::{Constant, Interpolant, SpanStarts};
use super::kinds::SpanKind;
use super::setup::TriangleSetup;
use super::span::{depth_span, Shading, SpanTest, WrittenCount};
use crate::texture::{ShadeTable, Texture, TextureMode, Texturing};
use core::cell::Cell;

/// Significant bits of the normalised perspective weights (`q < 2^16`).
pub(crate) const WEIGHT_BITS: u32 = 16;

/// One corner's texture data: Q8.8 coordinates and its raw perspective weight (`K/z` as the
/// depth holds it, `A − D`; any positive scale: [`normalised_weights`] keeps 16 bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TexCorner {
    /// `[u, v]`, Q8.8.
    pub(crate) uv: [i32; 2],
    /// Proportional to `1/z` (0 counts as 1).
    pub(crate) weight: u64,
}

/// The three weights shifted right together until the largest is below `2^16`, each at least
/// 1: `q_i = max(1, w_i >> s)`.
#[inline]
pub(crate) fn normalised_weights(w: [u64; 3]) -> [i64; 3] {
    let m = w[0].max(w[1]).max(w[2]);
    let s = (64 - m.leading_zeros()).saturating_sub(WEIGHT_BITS);
    w.map(|x| (x >> s).max(1) as i64)
}

/// An affine function of the pixel `(x, y)`: `c + gx·x + gy·y` (set-up precision).
#[derive(Debug, Clone, Copy)]
struct Plane {
    c: i128,
    gx: i128,
    gy: i128,
}

/// Below this, the given vertices' coordinates and their differences (sub-pixel units) let a
/// plane of values `|a_i| < 2^31` be set up in `i64` (module doc).
const NARROW_COORDINATE: u32 = 1 << 14;

impl Plane {
    /// `D·a(p)` of the values `a` over the given vertices (module doc), negated with `D`
    /// when `sign` is −1: in `i64` when the triangle and the values are small enough
    /// (`narrow`), else in `i128`.
    fn of<const S: u32>(t: &TriangleSetup<S>, a: [i128; 3], sign: i128) -> Plane {
        let small = a.iter().all(|v| v.unsigned_abs() < 1 << 31);
        let narrow = || Self::narrow(t, a.map(|v| v as i64), sign < 0);
        match small.then(narrow).flatten() {
            Some(p) => p,
            None => Self::wide(t, a, sign),
        }
    }

    /// [`Plane::of`] in `i64` for values `|a_i| < 2^31`, or `None` when a coordinate or a
    /// coordinate difference of the given vertices is not below `2^14` (module doc).
    #[inline(always)]
    fn narrow<const S: u32>(t: &TriangleSetup<S>, a: [i64; 3], negate: bool) -> Option<Plane> {
        let [p0, p1, p2] = t.given;
        let (dx1, dy1) = (p1.x.wrapping_sub(p0.x), p1.y.wrapping_sub(p0.y));
        let (dx2, dy2) = (p2.x.wrapping_sub(p0.x), p2.y.wrapping_sub(p0.y));
        let m = [p0.x, p0.y]
            .into_iter()
            .chain([dx1, dy1, dx2, dy2])
            .map(i32::unsigned_abs)
            .max()
            .unwrap_or(0);
        // Differences of coordinates below 2^28 fit an i32 (below 2^29).
        if m >= NARROW_COORDINATE {
            return None;
        }
        let (x0, y0) = (p0.x as i64, p0.y as i64);
        let (dx1, dy1, dx2, dy2) = (dx1 as i64, dy1 as i64, dx2 as i64, dy2 as i64);
        let (da1, da2) = (a[1] - a[0], a[2] - a[0]);
        let gx = da1 * dy2 - da2 * dy1;
        let gy = da2 * dx1 - da1 * dx2;
        let d = dx1 * dy2 - dx2 * dy1;
        let c = d * a[0] - gx * x0 - gy * y0;
        let sign = |v: i64| if negate { -(v as i128) } else { v as i128 };
        Some(Plane {
            c: sign(c),
            gx: sign(gx) << S,
            gy: sign(gy) << S,
        })
    }

    /// [`Plane::of`] in `i128`.
    fn wide<const S: u32>(t: &TriangleSetup<S>, a: [i128; 3], sign: i128) -> Plane {
        let [p0, p1, p2] = t.given;
        let (x0, y0) = (p0.x as i128, p0.y as i128);
        let (dx1, dy1) = (p1.x as i128 - x0, p1.y as i128 - y0);
        let (dx2, dy2) = (p2.x as i128 - x0, p2.y as i128 - y0);
        let (da1, da2) = (a[1] - a[0], a[2] - a[0]);
        let gx = da1 * dy2 - da2 * dy1;
        let gy = da2 * dx1 - da1 * dx2;
        let d = dx1 * dy2 - dx2 * dy1;
        Plane {
            c: sign * (d * a[0] - gx * x0 - gy * y0),
            gx: sign * (gx << S),
            gy: sign * (gy << S),
        }
    }

    /// The value at pixel `(x, y)`.
    #[inline(always)]
    fn at(&self, x: i32, y: i32) -> i128 {
        self.c + self.gx * x as i128 + self.gy * y as i128
    }

    /// The value at pixel `(x, y)` modulo `2^64` (wrapping `i64` arithmetic on the
    /// coefficients' low words): the value itself wherever it lies in the `i64` range.
    #[inline(always)]
    fn at_i64(&self, x: i32, y: i32) -> i64 {
        let (c, gx, gy) = (self.c as i64, self.gx as i64, self.gy as i64);
        c.wrapping_add(gx.wrapping_mul(x as i64))
            .wrapping_add(gy.wrapping_mul(y as i64))
    }
}

/// The per-triangle set-up of a textured triangle (module doc): its three planes, the texture
/// and how the texel becomes an index.
#[derive(Debug, Clone)]
pub(crate) struct TexturedKind<'a> {
    sampling: Sampling<'a>,
    /// The shade table of a lit texture.
    shades: Option<ShadeTable<'a>>,
    mode: TextureMode,
    /// `Q = 256·D·q(p)`.
    q: Plane,
    /// `N_u = W·D·(qu)(p)`, `N_v = H·D·(qv)(p)`.
    n: [Plane; 2],
    /// The pixel planes need `i128` (the `i64` bound does not hold).
    wide: bool,
    /// How the subdivided and affine modes' segment ends are evaluated.
    segment: SegmentPrecision,
    /// The exact mode's texel at the previous span's first pixel (`[0, 0]` before the first
    /// span): the first guess at the next span's start, accepted only where its remainder
    /// proves it (module doc).
    hint: Cell<[i32; 2]>,
}

impl<'a> TexturedKind<'a> {
    /// The set-up of triangle `t` with `corners` (in the given vertex order), or `None` for a
    /// zero-area triangle (it covers nothing).
    pub(crate) fn new<const S: u32>(
        t: &TriangleSetup<S>,
        corners: [TexCorner; 3],
        texturing: &Texturing<'a>,
    ) -> Option<Self> {
        let d = t.given_twice_area();
        if d == 0 {
            return None;
        }
        let sign = if d < 0 { -1 } else { 1 };
        let q = match texturing.mode {
            TextureMode::Affine => [1; 3],
            _ => normalised_weights(corners.map(|c| c.weight)),
        };
        let texture = texturing.texture;
        let sides = [texture.width() as i128, texture.height() as i128];
        let planes = |k: usize| {
            let a = [0, 1, 2].map(|i| sides[k] * q[i] as i128 * corners[i].uv[k] as i128);
            Plane::of(t, a, sign)
        };
        // The i64 bound: at a covered pixel Q ≤ 256·|D|·max q, |N| ≤ side·|D|·max |q·u|, and
        // the texel |t| ≤ side·max |u| / 256 + 1.
        let ad = d.unsigned_abs() as i128;
        let qmax = 256 * ad * q.iter().max().copied().unwrap_or(1) as i128;
        let nmax = |k: usize| {
            let qu = (0..3).map(|i| (q[i] as i128 * corners[i].uv[k] as i128).abs());
            sides[k] * ad * qu.max().unwrap_or(0)
        };
        let fits = |k: usize| {
            let umax = corners.iter().map(|c| (c.uv[k] as i128).abs()).max();
            let tmax = sides[k] * umax.unwrap_or(0) / 256 + 1;
            nmax(k) + qmax * (tmax + 2) < 1 << 62
        };
        // The segment ends' bound: `2^16·|N| < 2^63` and `Q < 2^63` at a covered pixel.
        let segment_fits = |k: usize| nmax(k) < 1 << 47 && qmax < 1 << 62;
        let wide = !(fits(0) && fits(1));
        let segment = if segment_fits(0) && segment_fits(1) {
            SegmentPrecision::Narrow
        } else if !wide {
            SegmentPrecision::Split
        } else {
            SegmentPrecision::Wide
        };
        Some(TexturedKind {
            sampling: Sampling::new(texture),
            shades: texturing.shades,
            mode: texturing.mode,
            q: Plane::of(t, q.map(|w| 256 * w as i128), sign),
            n: [planes(0), planes(1)],
            wide,
            segment,
            hint: Cell::new([0; 2]),
        })
    }

    /// The span of `colours`/`depths` from pixel `(x, y)` with depth `z` and luminance `lum`,
    /// each texel turned into its index by `tone`: one loop per sampling (wrapped or
    /// clamped) and tone, so that a pixel tests neither.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn span<G: SpanTest, Z: Interpolant, L: Interpolant, C: WrittenCount, Tn: Tone>(
        &self,
        colours: &mut [u8],
        depths: G,
        z: Z,
        lum: L,
        at: (i32, i32),
        count: C,
        tone: Tn,
    ) -> u32 {
        match self.sampling {
            Sampling::Wrapped(s) => self.sampled(colours, depths, z, lum, at, count, s, tone),
            Sampling::Clamped(s) => self.sampled(colours, depths, z, lum, at, count, s, tone),
        }
    }

    /// [`Self::span`] with sampler `sampler`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sampled<G: SpanTest, Z: Interpolant, L: Interpolant, C: WrittenCount, X, Tn>(
        &self,
        colours: &mut [u8],
        depths: G,
        z: Z,
        lum: L,
        (x, y): (i32, i32),
        count: C,
        sampler: X,
        tone: Tn,
    ) -> u32
    where
        X: Sampler,
        Tn: Tone,
    {
        let look = Look { sampler, tone };
        match (self.mode, self.wide) {
            (TextureMode::Exact, false) => {
                let sh = ExactTexels::<i64, L, X, Tn>::start(self, look, lum, x, y);
                depth_span(colours, depths, z, sh, count)
            }
            (TextureMode::Exact, true) => {
                let sh = ExactTexels::<i128, L, X, Tn>::start(self, look, lum, x, y);
                depth_span(colours, depths, z, sh, count)
            }
            (mode, _) => {
                let last = colours.len().saturating_sub(1) as u32;
                let sh = SegmentTexels::start(self, look, lum, x, y, last, mode.segment());
                depth_span(colours, depths, z, sh, count)
            }
        }
    }
}

/// Unlit: depth plane only, the texel written as it is.
impl SpanKind<1> for TexturedKind<'_> {
    #[inline(always)]
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<1>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: G,
        [z]: [I; 1],
        _: &St,
        at: (i32, i32),
        count: C,
    ) -> u32 {
        self.span(colours, depths, z, Constant(0), at, count, Unlit)
    }
}

/// Lit: depth and luminance planes, the texel through the shade table.
impl SpanKind<2> for TexturedKind<'_> {
    #[inline(always)]
    fn write<G: SpanTest, I: Interpolant, St: SpanStarts<2>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: G,
        [z, lum]: [I; 2],
        _: &St,
        at: (i32, i32),
        count: C,
    ) -> u32 {
        // The lit writer is chosen for lit textures only; an unlit one would read the
        // one-level identity table (the texel itself).
        let shades = self.shades.unwrap_or(IDENTITY_SHADES);
        self.span(colours, depths, z, lum, at, count, Lit(shades))
    }
}

/// How a texel `(i, j)` is read from the texture: by masks when both sides are powers of
/// two ([`Wrapped`]), else each side wrapped or clamped by [`Texture::texel`] ([`Clamped`]).
#[derive(Debug, Clone, Copy)]
enum Sampling<'a> {
    Wrapped(Wrapped<'a>),
    Clamped(Clamped<'a>),
}

impl<'a> Sampling<'a> {
    fn new(texture: Texture<'a>) -> Self {
        let (w, h) = (texture.width(), texture.height());
        if w.is_power_of_two() && h.is_power_of_two() {
            Sampling::Wrapped(Wrapped {
                texture,
                masks: [w as i32 - 1, h as i32 - 1],
                shift: w.trailing_zeros(),
            })
        } else {
            Sampling::Clamped(Clamped(texture))
        }
    }
}

/// Texel `(i, j)` → the texel's palette entry.
trait Sampler: Copy {
    fn texel(&self, t: [i32; 2]) -> u8;
}

/// Power-of-two sides: `(j & (H − 1))·W + (i & (W − 1))`.
#[derive(Debug, Clone, Copy)]
struct Wrapped<'a> {
    texture: Texture<'a>,
    /// `[W − 1, H − 1]`.
    masks: [i32; 2],
    /// `log2 W`.
    shift: u32,
}

impl Sampler for Wrapped<'_> {
    #[inline(always)]
    fn texel(&self, t: [i32; 2]) -> u8 {
        let k = ((t[1] & self.masks[1]) << self.shift) | (t[0] & self.masks[0]);
        self.texture.texel_at(k as usize)
    }
}

/// Any sides: [`Texture::texel`].
#[derive(Debug, Clone, Copy)]
struct Clamped<'a>(Texture<'a>);

impl Sampler for Clamped<'_> {
    #[inline(always)]
    fn texel(&self, t: [i32; 2]) -> u8 {
        self.0.texel(t[0], t[1])
    }
}

/// Texel and luminance → the stored palette index.
trait Tone: Copy {
    fn index(&self, texel: u8, lum: u32) -> u8;
}

/// Unlit: the texel as it is.
#[derive(Debug, Clone, Copy)]
struct Unlit;

impl Tone for Unlit {
    #[inline(always)]
    fn index(&self, texel: u8, _: u32) -> u8 {
        texel
    }
}

/// Lit: the texel through the shade table's row of the luminance.
#[derive(Debug, Clone, Copy)]
struct Lit<'a>(ShadeTable<'a>);

impl Tone for Lit<'_> {
    #[inline(always)]
    fn index(&self, texel: u8, lum: u32) -> u8 {
        self.0.shade(self.0.row(lum), texel)
    }
}

/// The one-level shade table whose every entry is its texel.
const IDENTITY_TABLE: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut k = 0;
    while k < 256 {
        t[k] = k as u8;
        k += 1;
    }
    t
};

/// [`IDENTITY_TABLE`] as a shade table (one level, 256 entries: always valid).
const IDENTITY_SHADES: ShadeTable<'static> = match ShadeTable::new(&IDENTITY_TABLE, 1) {
    Ok(s) => s,
    Err(_) => panic!("the identity table has one level of 256 entries"),
};

/// A span's sampler and tone.
#[derive(Debug, Clone, Copy)]
struct Look<X, Tn> {
    sampler: X,
    tone: Tn,
}

/// The per-pixel integer type of the exact planes: `i64` where the triangle's bound allows,
/// else `i128`; wrapping arithmetic (module doc).
trait Wide: Copy + PartialOrd {
    const ZERO: Self;
    fn from_wide(v: i128) -> Self;
    /// The plane's value at pixel `(x, y)` (exact where it lies in the type's range).
    fn at(p: &Plane, x: i32, y: i32) -> Self;
    fn add(self, o: Self) -> Self;
    fn sub(self, o: Self) -> Self;
    fn times(self, t: i32) -> Self;
    /// `⌊self / d⌋` for `d > 0`, as an `i32` (a texel offset).
    fn floor_div(self, d: Self) -> i32;
}

impl Wide for i64 {
    const ZERO: Self = 0;
    #[inline(always)]
    fn from_wide(v: i128) -> Self {
        v as i64
    }
    #[inline(always)]
    fn at(p: &Plane, x: i32, y: i32) -> Self {
        p.at_i64(x, y)
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.wrapping_sub(o)
    }
    #[inline(always)]
    fn times(self, t: i32) -> Self {
        self.wrapping_mul(t as i64)
    }
    #[inline(always)]
    fn floor_div(self, d: Self) -> i32 {
        self.div_euclid(d) as i32
    }
}

impl Wide for i128 {
    const ZERO: Self = 0;
    #[inline(always)]
    fn from_wide(v: i128) -> Self {
        v
    }
    #[inline(always)]
    fn at(p: &Plane, x: i32, y: i32) -> Self {
        p.at(x, y)
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.wrapping_sub(o)
    }
    #[inline(always)]
    fn times(self, t: i32) -> Self {
        self.wrapping_mul(t as i128)
    }
    #[inline(always)]
    fn floor_div(self, d: Self) -> i32 {
        self.div_euclid(d) as i32
    }
}

/// The exact mode's shading: `Q` at the current pixel and its step, and per coordinate the
/// texel floor `t`, its remainder `r = N − Q·t` (`0 ≤ r < Q` at a covered pixel) and the
/// remainder's step `e = dN − dQ·t` (so a pixel costs one add per coordinate, and a move of
/// the texel one add to each of `r` and `e`).
#[derive(Debug, Clone, Copy)]
struct ExactTexels<T, L, X, Tn> {
    q: T,
    dq: T,
    r: [T; 2],
    e: [T; 2],
    t: [i32; 2],
    lum: L,
    look: Look<X, Tn>,
}

impl<T: Wide, L: Interpolant, X: Sampler, Tn: Tone> ExactTexels<T, L, X, Tn> {
    #[inline(always)]
    fn start(k: &TexturedKind<'_>, look: Look<X, Tn>, lum: L, x: i32, y: i32) -> Self {
        let q = T::at(&k.q, x, y);
        let n = k.n.map(|p| T::at(&p, x, y));
        // A covered pixel has Q > 0 (module doc); there the guess is tried first.
        let mut t = [0; 2];
        let mut r = n;
        if q > T::ZERO {
            let guess = k.hint.get();
            for i in 0..2 {
                (t[i], r[i]) = settle(n[i], q, guess[i]);
            }
            k.hint.set(t);
        }
        let dq = T::from_wide(k.q.gx);
        let e = [0, 1].map(|i| T::from_wide(k.n[i].gx).sub(dq.times(t[i])));
        ExactTexels {
            q,
            dq,
            r,
            e,
            t,
            lum,
            look,
        }
    }
}

/// `(t, N − Q·t)` with `t = ⌊N / Q⌋` for `Q > 0`, from a guess `g`: accepted when its
/// remainder `N − Q·g` lies in `[0, Q)`, moved by one when the remainder is one `Q` outside,
/// else the division. Under the `i64` bound (module doc) every value here stays in range when
/// `|g|` is at most the triangle's texel bound, as any covered pixel's floor is.
#[inline(always)]
fn settle<T: Wide>(n: T, q: T, g: i32) -> (i32, T) {
    let r = n.sub(q.times(g));
    if r < T::ZERO {
        let up = r.add(q);
        if up >= T::ZERO {
            return (g - 1, up);
        }
    } else if r < q {
        return (g, r);
    } else {
        let down = r.sub(q);
        if down < q {
            return (g + 1, down);
        }
    }
    let t = n.floor_div(q);
    (t, n.sub(q.times(t)))
}

/// `(m, r − Q·m)` with `m = ⌊r / Q⌋` for `Q > 0`: up to [`JUMP_STEPS`] steps of `Q` taken off
/// `r` (or added), which is the quotient's definition, then the division. The remainders met
/// lie between `r` and the final one, in range where those are (module doc).
#[inline(never)]
fn walk<T: Wide>(mut r: T, q: T) -> (i32, T) {
    let mut m = 0i32;
    if r >= T::ZERO {
        while r >= q && m < JUMP_STEPS {
            r = r.sub(q);
            m += 1;
        }
    } else {
        while r < T::ZERO && m > -JUMP_STEPS {
            r = r.add(q);
            m -= 1;
        }
    }
    if r < T::ZERO || r >= q {
        let rest = r.floor_div(q);
        r = r.sub(q.times(rest));
        m = m.wrapping_add(rest);
    }
    (m, r)
}

impl<T: Wide, L: Interpolant, X: Sampler, Tn: Tone> Shading for ExactTexels<T, L, X, Tn> {
    #[inline(always)]
    fn index(&self) -> u8 {
        let texel = self.look.sampler.texel(self.t);
        self.look.tone.index(texel, self.lum.value())
    }

    #[inline(always)]
    fn step(&mut self) {
        self.lum.step();
        let (q, dq) = (self.q.add(self.dq), self.dq);
        self.q = q;
        for k in 0..2 {
            let r = self.r[k].add(self.e[k]);
            self.r[k] = r;
            if r < T::ZERO {
                let up = r.add(q);
                if up >= T::ZERO {
                    self.t[k] -= 1;
                    self.r[k] = up;
                    self.e[k] = self.e[k].add(dq);
                } else {
                    self.jump(k);
                }
            } else if r >= q {
                let down = r.sub(q);
                if down < q {
                    self.t[k] += 1;
                    self.r[k] = down;
                    self.e[k] = self.e[k].sub(dq);
                } else {
                    self.jump(k);
                }
            }
        }
    }
}

impl<T: Wide, L: Interpolant, X: Sampler, Tn: Tone> ExactTexels<T, L, X, Tn> {
    /// The texel `k` moved by more than one: by the Euclidean quotient `m = ⌊r / Q⌋` (nothing
    /// where `Q ≤ 0`, past a span's end), by [`walk`] (minified textures: a few texels per
    /// pixel).
    #[cold]
    #[inline(never)]
    fn jump(&mut self, k: usize) {
        let q = self.q;
        if q > T::ZERO {
            let (m, r) = walk(self.r[k], q);
            self.t[k] = self.t[k].wrapping_add(m);
            self.r[k] = r;
            self.e[k] = self.e[k].sub(self.dq.times(m));
        }
    }
}

/// The longest texel move [`ExactTexels::jump`] makes by steps before it divides.
const JUMP_STEPS: i32 = 8;

/// `⌊2^16·r / q⌋` for `0 ≤ r < q < 2^63`: sixteen steps of binary long division (each
/// doubles `r < q`, so `2·r < 2^64`); the result is below `2^16`.
#[inline(always)]
fn fraction16(mut r: u64, q: u64) -> i64 {
    let mut f = 0;
    for _ in 0..16 {
        r <<= 1;
        f <<= 1;
        if r >= q {
            r -= q;
            f |= 1;
        }
    }
    f
}

/// How a triangle's segment ends evaluate `⌊2^16·N / Q⌋` (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SegmentPrecision {
    /// `2^16·N` and `Q` in `i64`: one 64-bit division.
    Narrow,
    /// `N` and `Q` in `i64` (the exact mode's bound): the floor `t = ⌊N / Q⌋`, then the
    /// sixteen fraction bits of `(N − Q·t) / Q` by long division.
    Split,
    /// `i128`.
    Wide,
}

/// The subdivided and affine modes' shading: the texel coordinates in 16.16, exact at the
/// ends of each segment of `segment` pixels (and at the span's last pixel), stepped linearly
/// between.
#[derive(Debug, Clone, Copy)]
struct SegmentTexels<'k, L, X, Tn> {
    /// Texels in 16.16 at the current pixel, and the step.
    acc: [i64; 2],
    inc: [i64; 2],
    /// The current pixel's offset in the span, the segment's end and its exact values.
    pos: u32,
    end: u32,
    end_acc: [i64; 2],
    last: u32,
    segment: u32,
    /// The span's first pixel.
    at: (i32, i32),
    /// The triangle's planes (borrowed: a span copies none of them).
    kind: &'k TexturedKind<'k>,
    lum: L,
    look: Look<X, Tn>,
}

impl<'k, L: Interpolant, X: Sampler, Tn: Tone> SegmentTexels<'k, L, X, Tn> {
    #[inline(always)]
    fn start(
        k: &'k TexturedKind<'k>,
        look: Look<X, Tn>,
        lum: L,
        x: i32,
        y: i32,
        last: u32,
        segment: u32,
    ) -> Self {
        let mut s = SegmentTexels {
            acc: [0; 2],
            inc: [0; 2],
            pos: 0,
            end: 0,
            end_acc: [0; 2],
            last,
            segment,
            at: (x, y),
            kind: k,
            lum,
            look,
        };
        s.acc = s.exact(0);
        s.begin_segment();
        s
    }

    /// `⌊2^16·N / Q⌋` at offset `i` of the span (texels in 16.16), in the precision the
    /// triangle's bounds allow (module doc).
    #[inline(never)]
    fn exact(&self, i: u32) -> [i64; 2] {
        let (x, y) = (self.at.0.wrapping_add(i as i32), self.at.1);
        let k = self.kind;
        match k.segment {
            SegmentPrecision::Narrow => {
                let q = k.q.at_i64(x, y);
                k.n.map(|p| {
                    if q > 0 {
                        (p.at_i64(x, y) << 16).div_euclid(q)
                    } else {
                        0
                    }
                })
            }
            SegmentPrecision::Split => {
                let q = k.q.at_i64(x, y);
                k.n.map(|p| {
                    if q > 0 {
                        let n = p.at_i64(x, y);
                        let t = n.div_euclid(q);
                        let r = n.wrapping_sub(q.wrapping_mul(t));
                        (t << 16) | fraction16(r as u64, q as u64)
                    } else {
                        0
                    }
                })
            }
            SegmentPrecision::Wide => {
                let q = k.q.at(x, y);
                k.n.map(|p| {
                    if q > 0 {
                        ((p.at(x, y) << 16).div_euclid(q)) as i64
                    } else {
                        0
                    }
                })
            }
        }
    }

    /// The segment from the current pixel: its end, the exact values there and the step.
    #[inline(always)]
    fn begin_segment(&mut self) {
        self.end = self.pos.saturating_add(self.segment).min(self.last);
        if self.end > self.pos {
            self.end_acc = self.exact(self.end);
            let len = self.end - self.pos;
            for k in 0..2 {
                let d = self.end_acc[k] - self.acc[k];
                self.inc[k] = if len.is_power_of_two() {
                    d >> len.trailing_zeros()
                } else {
                    d.div_euclid(len as i64)
                };
            }
        }
    }
}

impl<L: Interpolant, X: Sampler, Tn: Tone> Shading for SegmentTexels<'_, L, X, Tn> {
    #[inline(always)]
    fn index(&self) -> u8 {
        let texel = self.look.sampler.texel(self.acc.map(|a| (a >> 16) as i32));
        self.look.tone.index(texel, self.lum.value())
    }

    #[inline(always)]
    fn step(&mut self) {
        self.lum.step();
        self.pos += 1;
        if self.pos == self.end {
            self.acc = self.end_acc;
            if self.end < self.last {
                self.begin_segment();
            }
        } else {
            self.acc = [self.acc[0] + self.inc[0], self.acc[1] + self.inc[1]];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::SubpixelPoint;

    fn setup(v: [(i32, i32); 3]) -> TriangleSetup<4> {
        TriangleSetup::in_range(v.map(|(x, y)| SubpixelPoint { x, y }))
    }

    fn same(a: Plane, b: Plane) -> bool {
        (a.c, a.gx, a.gy) == (b.c, b.gx, b.gy)
    }

    /// At the edge of the narrow set-up's bound (coordinates and differences just below
    /// `2^14`, values just below `2^31` in size, both signs; overflow checks on in the test
    /// build) it gives the `i128` planes; one past it, it declines.
    #[test]
    fn narrow_set_up_matches_the_wide_one_up_to_its_bound() {
        let m = NARROW_COORDINATE as i32 - 1;
        let big = (1i64 << 31) - 1;
        let values: [[i64; 3]; 4] = [
            [big, -big, big],
            [-big, big, -big],
            [big, big - 1, -big],
            [0, big, -big],
        ];
        let triangles = [
            [(-m, -m), (0, -m), (-m, 0)],
            [(m, m), (0, m), (m, 0)],
            [(0, 0), (m, 0), (0, m)],
            [(m, -m), (0, 0), (m, 0)],
            [(-m, m), (-1, 0), (0, m)],
        ];
        for v in triangles {
            let t = setup(v);
            for a in values {
                for sign in [1, -1] {
                    let narrow = Plane::narrow(&t, a, sign < 0).expect("within the bound");
                    let wide = Plane::wide(&t, a.map(i128::from), sign);
                    assert!(same(narrow, wide), "{v:?} {a:?} {sign}");
                    assert!(same(Plane::of(&t, a.map(i128::from), sign), wide));
                }
            }
        }
        // One past: a coordinate, a difference.
        let over = NARROW_COORDINATE as i32;
        for v in [
            [(over, 0), (over, 1), (over - 1, 0)],
            [(0, 0), (0, over), (1, 0)],
            [(-over, 0), (-over, 1), (1 - over, 1)],
        ] {
            let t = setup(v);
            assert!(Plane::narrow(&t, [1, 2, 3], false).is_none(), "{v:?}");
            let a = [1i128, 2, 3];
            assert!(same(Plane::of(&t, a, 1), Plane::wide(&t, a, 1)));
        }
    }
}
