//! An independent `f64` reference renderer for [`Scene`]s: the picture the integer pipeline
//! approximates. It shares nothing with the zscan core.
//!
//! Per triangle, in order of the scene's list:
//! 1. **Back-face culling** in world space: the triangle is drawn only when the eye lies strictly
//!    on the front side of its plane, `((b − a) × (c − a)) · (eye − a) > 0` (front faces are
//!    counter-clockwise seen from outside). Edge-on triangles are culled.
//! 2. **Clipping in 3D** (Sutherland–Hodgman) against the near plane `d ≥ near` and the far plane
//!    `d ≤ far`, `d` the depth along the view direction. Clip points carry their intensity,
//!    interpolated linearly along the clipped edge.
//! 3. **Projection** of the (clipped) polygon with [`Camera::project_view`]: unsnapped `f64`
//!    screen coordinates, lattice-point pixels, `y` down.
//! 4. **Coverage** ([`cover_polygon`]): pixel `(x, y)` (a lattice point) is covered when it is
//!    inside; on a left edge in, on a right edge out; each edge covers the rows
//!    `y_low ≤ y < y_high` (the top-left rule, zscan's fill rule), nonzero winding. Every
//!    decision is an **exact predicate** on the `f64` screen coordinates: the row test is an exact
//!    comparison, and "pixel on or right of an edge" is the sign of an orientation determinant,
//!    evaluated with a floating-point filter and, near zero, exactly with floating-point
//!    expansions (Shewchuk's two-sum/two-product). So the coverage is that of the polygon whose
//!    vertices are exactly the `f64` values; only the projection itself rounds.
//! 5. **Depth** per pixel from the plane (TIPE's back-projection): the point of the triangle's
//!    plane seen through the pixel, `P = t·r` with `r = ((x − cx)/f, −(y − cy)/f, 1)` in view
//!    coordinates; the depth is `t`, the view-space distance along the view direction. A fragment
//!    is written when its depth is strictly less than the stored one (ties keep the first).
//! 6. **Luminance** from the per-corner intensities, two ways, both stored:
//!    - *perspective-correct*: the barycentric coordinates of `P` in the 3D triangle;
//!    - *screen-affine*: the barycentric coordinates of the pixel in the projected triangle (for
//!      a clipped polygon, in the fan triangle `(0, i, i+1)` of the clipped polygon that holds
//!      the pixel, with the clip points' interpolated intensities).
//!
//! The pictures written by the tests (`target/zscan-out/float-<scene>.png`) use the
//! perspective-correct luminance.
use crate::scenes::{cross, dot, sub, Camera, Scene, Vec3};

/// Which interpolation of the corner intensities to read from a [`Fragment`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interpolation {
    /// Barycentric coordinates of the visible 3D point (what the eye sees on the surface).
    PerspectiveCorrect,
    /// Barycentric coordinates in screen space (what incremental span interpolation computes).
    ScreenAffine,
}

/// What a covered pixel holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fragment {
    /// Index of the scene triangle visible at the pixel.
    pub triangle: usize,
    /// View-space depth (distance along the view direction) of the visible point.
    pub depth: f64,
    /// Luminance 0..=255, perspective-correct interpolation.
    pub luminance_perspective: f64,
    /// Luminance 0..=255, screen-affine interpolation.
    pub luminance_affine: f64,
}

impl Fragment {
    /// The luminance by the chosen interpolation.
    pub fn luminance(&self, mode: Interpolation) -> f64 {
        match mode {
            Interpolation::PerspectiveCorrect => self.luminance_perspective,
            Interpolation::ScreenAffine => self.luminance_affine,
        }
    }
}

/// Counts gathered while rendering.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RenderStats {
    /// Pixels covered in the final frame.
    pub covered_pixels: usize,
    /// Fragments that passed the depth test and were written (≥ covered pixels).
    pub fragments_written: usize,
    /// Triangles that survived culling and clipping and were rasterised.
    pub triangles_drawn: usize,
    /// Triangles removed by back-face culling.
    pub triangles_culled: usize,
    /// Front-facing triangles removed entirely by the near/far planes.
    pub triangles_clipped_away: usize,
    /// Front-facing triangles cut by the near or far plane (and drawn).
    pub triangles_clipped: usize,
}

/// A rendered frame: one optional [`Fragment`] per pixel, row-major from the top left.
#[derive(Debug, Clone, PartialEq)]
pub struct FloatFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `pixels[y * width + x]`.
    pub pixels: Vec<Option<Fragment>>,
    /// Counts.
    pub stats: RenderStats,
}

impl FloatFrame {
    /// The fragment at pixel `(x, y)`, `None` when uncovered or outside.
    pub fn at(&self, x: u32, y: u32) -> Option<&Fragment> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.pixels[(y * self.width + x) as usize].as_ref()
    }

    /// An 8-bit grey image of the luminance (`round`, uncovered pixels 0), row-major.
    pub fn luminance_image(&self, mode: Interpolation) -> Vec<u8> {
        self.pixels
            .iter()
            .map(|p| p.map_or(0, |f| f.luminance(mode).round().clamp(0.0, 255.0) as u8))
            .collect()
    }
}

/// Renders `scene` (see the module doc for the exact model).
pub fn render(scene: &Scene) -> Result<FloatFrame, String> {
    scene.validate()?;
    let cam: &Camera = &scene.camera;
    let (w, h) = (cam.width, cam.height);
    let focal = cam.focal();
    let (cx, cy) = cam.principal;
    let view: Vec<Vec3> = scene.vertices.iter().map(|&p| cam.to_view(p)).collect();
    let mut frame = FloatFrame {
        width: w,
        height: h,
        pixels: vec![None; w as usize * h as usize],
        stats: RenderStats::default(),
    };
    for (t, tri) in scene.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|i| scene.vertices[i]);
        if dot(cross(sub(b, a), sub(c, a)), sub(cam.eye, a)) <= 0.0 {
            frame.stats.triangles_culled += 1;
            continue;
        }
        let corners = tri.map(|i| view[i]);
        let levels = scene.intensities[t].map(f64::from);
        let poly: Vec<(Vec3, f64)> = (0..3).map(|k| (corners[k], levels[k])).collect();
        let needs_clip = poly.iter().any(|(v, _)| v[2] < cam.near || v[2] > cam.far);
        let poly = if needs_clip {
            frame.stats.triangles_clipped += 1;
            let p = clip(&poly, |v| v[2] - cam.near);
            clip(&p, |v| cam.far - v[2])
        } else {
            poly
        };
        if poly.len() < 3 {
            if needs_clip {
                frame.stats.triangles_clipped -= 1;
            }
            frame.stats.triangles_clipped_away += 1;
            continue;
        }
        frame.stats.triangles_drawn += 1;
        let screen: Vec<(f64, f64)> = poly.iter().map(|(v, _)| cam.project_view(*v)).collect();
        let n = cross(sub(corners[1], corners[0]), sub(corners[2], corners[0]));
        let n_dot_a = dot(n, corners[0]);
        let nn = dot(n, n);
        cover_polygon(&screen, w, h, |x, y| {
            let ray = [(x as f64 - cx) / focal, -(y as f64 - cy) / focal, 1.0];
            let denom = dot(n, ray);
            if denom == 0.0 {
                return;
            }
            let depth = n_dot_a / denom;
            let slot = &mut frame.pixels[(y * w + x) as usize];
            if slot.is_some_and(|f| f.depth <= depth) {
                return;
            }
            let p = [ray[0] * depth, ray[1] * depth, depth];
            let mut lum_p = 0.0;
            for k in 0..3 {
                let (u, v) = (corners[(k + 1) % 3], corners[(k + 2) % 3]);
                let lambda = dot(n, cross(sub(u, p), sub(v, p))) / nn;
                lum_p += lambda * levels[k];
            }
            let lum_a = affine_luminance(&screen, &poly, (x as f64, y as f64));
            *slot = Some(Fragment {
                triangle: t,
                depth,
                luminance_perspective: lum_p,
                luminance_affine: lum_a,
            });
            frame.stats.fragments_written += 1;
        });
    }
    frame.stats.covered_pixels = frame.pixels.iter().filter(|p| p.is_some()).count();
    Ok(frame)
}

/// Sutherland–Hodgman against the half-space `dist(v) ≥ 0`; points on the plane are kept.
fn clip(poly: &[(Vec3, f64)], dist: impl Fn(Vec3) -> f64) -> Vec<(Vec3, f64)> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (dp, dq) = (dist(p.0), dist(q.0));
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            let s = dp / (dp - dq);
            let v = [0, 1, 2].map(|k| p.0[k] + s * (q.0[k] - p.0[k]));
            out.push((v, p.1 + s * (q.1 - p.1)));
        }
    }
    out
}

/// Screen-affine luminance at `pixel` inside the projected polygon: barycentric interpolation
/// in the fan triangle `(0, i, i+1)` that holds the pixel (the one whose smallest barycentric
/// coordinate is largest, robust to pixels on the fan's inner edges).
fn affine_luminance(screen: &[(f64, f64)], poly: &[(Vec3, f64)], pixel: (f64, f64)) -> f64 {
    let mut best = (f64::NEG_INFINITY, 0.0);
    for i in 1..screen.len() - 1 {
        let (a, b, c) = (screen[0], screen[i], screen[i + 1]);
        let area = orient_approx(a, b, c);
        if area == 0.0 {
            continue;
        }
        let l0 = orient_approx(pixel, b, c) / area;
        let l1 = orient_approx(a, pixel, c) / area;
        let l2 = 1.0 - l0 - l1;
        let m = l0.min(l1).min(l2);
        if m > best.0 {
            best = (m, l0 * poly[0].1 + l1 * poly[i].1 + l2 * poly[i + 1].1);
        }
    }
    best.1
}

/// `(b − a) × (c − a)` in plain `f64`.
fn orient_approx(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> f64 {
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
}

/// The exact coverage of a polygon with `f64` screen vertices on the `width × height` screen:
/// calls `pixel(x, y)` for every covered lattice point, row by row from the top, each row left
/// to right. The rule is zscan's (top-left, nonzero winding; see the module doc); every decision
/// is exact on the given coordinates. Returns the number of pixels reported.
pub fn cover_polygon(
    poly: &[(f64, f64)],
    width: u32,
    height: u32,
    mut pixel: impl FnMut(u32, u32),
) -> usize {
    if poly.len() < 3 || poly.iter().any(|p| !p.0.is_finite() || !p.1.is_finite()) {
        return 0;
    }
    let ymin = poly.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let ymax = poly.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
    let first = ymin.ceil().max(0.0) as i64;
    let end = ymax.ceil().min(height as f64) as i64;
    let mut count = 0;
    let mut events: Vec<(i64, i32)> = Vec::new();
    for y in first..end {
        let yf = y as f64;
        events.clear();
        for i in 0..poly.len() {
            let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
            let (top, bottom, dir) = if p.1 < q.1 {
                (p, q, 1)
            } else if p.1 > q.1 {
                (q, p, -1)
            } else {
                continue;
            };
            if !(top.1 <= yf && yf < bottom.1) {
                continue;
            }
            events.push((first_pixel_right_of(top, bottom, yf, width), dir));
        }
        events.sort_unstable();
        let mut winding = 0;
        let mut k = 0;
        let mut x = 0i64;
        while k < events.len() {
            let at = events[k].0;
            let was_in = winding != 0;
            while k < events.len() && events[k].0 == at {
                winding += events[k].1;
                k += 1;
            }
            if was_in {
                for px in x.max(0)..at.min(width as i64) {
                    pixel(px as u32, y as u32);
                    count += 1;
                }
            }
            x = at;
        }
    }
    count
}

/// The smallest integer `x` whose lattice point `(x, y)` is on or to the right of the edge
/// `top → bottom` (`top.1 ≤ y < bottom.1`), i.e. `⌈x_e⌉` for the exact crossing `x_e`; clamped
/// to `[-1, width + 1]` (equivalent for coverage on the screen).
fn first_pixel_right_of(top: (f64, f64), bottom: (f64, f64), y: f64, width: u32) -> i64 {
    let xe = top.0 + (y - top.1) * (bottom.0 - top.0) / (bottom.1 - top.1);
    let hi = width as f64 + 1.0;
    // Far outside the screen: the rounding of `xe` (relative 1e-15) cannot matter.
    if xe < -2.0 {
        return -1;
    }
    if xe > hi + 1.0 {
        return hi as i64;
    }
    let mut c = xe.ceil();
    while on_or_right(c - 1.0, y, top, bottom) {
        c -= 1.0;
    }
    while !on_or_right(c, y, top, bottom) {
        c += 1.0;
    }
    (c as i64).clamp(-1, hi as i64)
}

/// Exactly: is the point `(x, y)` on or to the right (`+x`) of the line `top → bottom`
/// (`top.1 < bottom.1`)? The sign of `(x − tx)(by − ty) − (y − ty)(bx − tx)`.
fn on_or_right(x: f64, y: f64, top: (f64, f64), bottom: (f64, f64)) -> bool {
    orient_sign((x, y), bottom, top) >= 0
}

/// The exact sign of `(a.x − c.x)(b.y − c.y) − (a.y − c.y)(b.x − c.x)` (Shewchuk's `orient2d`):
/// a floating-point filter with his error bound, and exact expansion arithmetic near zero.
pub fn orient_sign(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> i32 {
    let left = (a.0 - c.0) * (b.1 - c.1);
    let right = (a.1 - c.1) * (b.0 - c.0);
    let det = left - right;
    const EPS: f64 = f64::EPSILON / 2.0;
    let bound = (3.0 + 16.0 * EPS) * EPS * (left.abs() + right.abs());
    if det > bound {
        return 1;
    }
    if -det > bound {
        return -1;
    }
    let l = exp_mul(&exp_diff(a.0, c.0), &exp_diff(b.1, c.1));
    let r = exp_mul(&exp_diff(a.1, c.1), &exp_diff(b.0, c.0));
    let mut d = l;
    for &x in &r {
        d = exp_grow(&d, -x);
    }
    d.iter()
        .rev()
        .find(|&&x| x != 0.0)
        .map_or(0, |&x| if x > 0.0 { 1 } else { -1 })
}

/// `a + b = s + e` exactly (Knuth's two-sum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// `a · b = p + e` exactly (fused multiply-add).
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `a − b` as a nonoverlapping expansion (increasing magnitude).
fn exp_diff(a: f64, b: f64) -> Vec<f64> {
    let (s, e) = two_sum(a, -b);
    vec![e, s]
}

/// Shewchuk's Grow-Expansion: `e + b` exactly, nonoverlapping when `e` is.
fn exp_grow(e: &[f64], b: f64) -> Vec<f64> {
    let mut q = b;
    let mut h = Vec::with_capacity(e.len() + 1);
    for &x in e {
        let (s, err) = two_sum(q, x);
        h.push(err);
        q = s;
    }
    h.push(q);
    h
}

/// The exact product of two expansions, as a nonoverlapping expansion.
fn exp_mul(e: &[f64], f: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for &x in e {
        for &y in f {
            let (p, err) = two_product(x, y);
            out = exp_grow(&out, err);
            out = exp_grow(&out, p);
        }
    }
    out
}

/// Writes an 8-bit greyscale PNG (`grey.len() == width · height`, row-major), creating the
/// parent directories.
pub fn write_grey_png(
    path: &std::path::Path,
    width: u32,
    height: u32,
    grey: &[u8],
) -> Result<(), String> {
    if grey.len() != width as usize * height as usize {
        return Err(format!(
            "image data has {} bytes for {width} × {height}",
            grey.len()
        ));
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let file = std::fs::File::create(path)
        .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc
        .write_header()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    writer
        .write_image_data(grey)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    writer
        .finish()
        .map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact orientation on a 2^-30 grid with i128 integers (independent of the expansions).
    fn orient_i128(a: (i64, i64), b: (i64, i64), c: (i64, i64)) -> i32 {
        let d =
            (a.0 - c.0) as i128 * (b.1 - c.1) as i128 - (a.1 - c.1) as i128 * (b.0 - c.0) as i128;
        d.signum() as i32
    }

    #[test]
    fn orient_sign_is_exact_on_nearly_collinear_points() {
        let unit = (-30f64).exp2();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |range: i64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % (2 * range as u64 + 1)) as i64 - range
        };
        let (mut zeros, mut naive_wrong) = (0, 0);
        for _ in 0..20_000 {
            let c = (next(1 << 38), next(1 << 38));
            let d = (next(1 << 30), next(1 << 30));
            let k = next(1 << 10);
            let b = (c.0 + d.0, c.1 + d.1);
            let a = (c.0 + k * d.0 + next(1), c.1 + k * d.1 + next(1));
            let f = |p: (i64, i64)| (p.0 as f64 * unit, p.1 as f64 * unit);
            let want = orient_i128(a, b, c);
            assert_eq!(orient_sign(f(a), f(b), f(c)), want, "{a:?} {b:?} {c:?}");
            zeros += (want == 0) as usize;
            let (fa, fb, fc) = (f(a), f(b), f(c));
            let naive = (fa.0 - fc.0) * (fb.1 - fc.1) - (fa.1 - fc.1) * (fb.0 - fc.0);
            naive_wrong += (naive.partial_cmp(&0.0).unwrap() as i32 != want) as usize;
        }
        // The cases are hard: many exactly collinear, and plain f64 gets some wrong.
        assert!(zeros > 1000, "{zeros}");
        assert!(naive_wrong > 0, "{naive_wrong}");
    }

    #[test]
    fn top_left_rule_on_a_lattice_triangle() {
        // zscan's documented example: triangle (1,0) (5,0) (1,4).
        let tri = [(1.0, 0.0), (5.0, 0.0), (1.0, 4.0)];
        let mut grid = [[b'.'; 7]; 5];
        let n = cover_polygon(&tri, 7, 5, |x, y| grid[y as usize][x as usize] = b'#');
        assert_eq!(n, 10);
        let rows: Vec<String> = grid
            .iter()
            .map(|g| String::from_utf8(g.to_vec()).unwrap())
            .collect();
        assert_eq!(
            rows,
            [".####..", ".###...", ".##....", ".#.....", "......."]
        );
    }
}
