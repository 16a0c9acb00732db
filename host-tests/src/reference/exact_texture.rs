//! An exact rational reference for the texel a textured pixel shows, independent of the
//! production raster's planes.
//!
//! The production writer (`zscan::raster::triangle`, its textured span kind) steps three
//! integer planes along each span and follows the floor of their ratio with remainders. This
//! module evaluates the definition directly at each pixel, in barycentric form: with the
//! pixel's lattice point `p = (x·F, y·F)` (`F = 2^S`) and the signed sub-triangle areas
//! `e_0 = (P1 − p) × (P2 − p)`, `e_1 = (P2 − p) × (P0 − p)`, `e_2 = (P0 − p) × (P1 − p)`
//! (exact `i128`), the perspective-correct coordinate is
//! `u = Σ e_i q_i u_i / Σ e_i q_i` (`u_i` in Q8.8) and the texel column
//! `⌊W · Σ e_i q_i u_i / (256 · Σ e_i q_i)⌋`, taken as a Euclidean quotient after making the
//! denominator positive. The weights are the definition's: `q_i = max(1, w_i >> s)` with `s`
//! the shift that brings the largest below `2^16`, or 1 for the affine mode.

/// The weights of the definition (module doc) from raw weights `w` (any scale).
pub fn weights(w: [u64; 3]) -> [i128; 3] {
    let m = *w.iter().max().unwrap();
    let bits = 64 - m.leading_zeros();
    let s = bits.saturating_sub(16);
    w.map(|x| ((x >> s).max(1)) as i128)
}

/// The texel `(column, row)`, before wrapping or clamping, at pixel `(x, y)` of the triangle
/// `v` (sub-pixel units, `s` bits) with Q8.8 coordinates `uv`, weights `q` (from
/// [`weights`]) and a texture of `w × h` texels. `None` where the weights' sum vanishes
/// (never at a covered pixel).
pub fn texel_at(
    v: [(i64, i64); 3],
    s: u32,
    uv: [[i16; 2]; 3],
    q: [i128; 3],
    (w, h): (u16, u16),
    (x, y): (i64, i64),
) -> Option<(i64, i64)> {
    let p = ((x as i128) << s, (y as i128) << s);
    let cross = |a: (i64, i64), b: (i64, i64)| {
        let (ax, ay) = (a.0 as i128 - p.0, a.1 as i128 - p.1);
        let (bx, by) = (b.0 as i128 - p.0, b.1 as i128 - p.1);
        ax * by - ay * bx
    };
    let e = [cross(v[1], v[2]), cross(v[2], v[0]), cross(v[0], v[1])];
    let den: i128 = (0..3).map(|i| e[i] * q[i]).sum();
    if den == 0 {
        return None;
    }
    let floor = |k: usize, side: u16| {
        let num: i128 = (0..3).map(|i| e[i] * q[i] * uv[i][k] as i128).sum();
        let (n, d) = (num * side as i128, den * 256);
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        n.div_euclid(d) as i64
    };
    Some((floor(0, w), floor(1, h)))
}

/// Texel index `i` on a side of `n`: wrapped for a power of two, else clamped.
pub fn fold(i: i64, n: u16) -> i64 {
    if n.is_power_of_two() {
        i.rem_euclid(n as i64)
    } else {
        i.clamp(0, n as i64 - 1)
    }
}
