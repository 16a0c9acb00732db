//! Where interpolated shading is exact, where it is fast, and where the methods themselves
//! fail (course chapter 4, §2.4) — each measured, printed and bounded.
//!
//! 1. Exact Gouraud equals the `f64` affine interpolant rounded (half up) at every pixel of
//!    random triangles: 0 mismatches (pixels within 1e-9 of a rounding tie are counted apart,
//!    since `f64` cannot decide them). The fast (16.16 DDA) variant's max and mean error.
//! 2. A quad at several screen rotations: per-triangle affine interpolation is invariant under
//!    rotation (an affine map), so the shading at fixed points of the quad changes only by the
//!    pixel sampling; but the split diagonal (which vertex the fan starts from) changes the
//!    centre by `|I0 + I2 − I1 − I3| / 2` — the course's orientation problem (Fig. 4.12c).
//! 3. Affine against perspective-correct interpolation on a steeply receding plane
//!    (`reference::float_render` computes both): the affine error in levels, and the core
//!    within ±1 of the affine value.
use zscan::output::{DepthBuffer, Framebuffer};
use zscan::raster::triangle::{draw_triangle, LuminanceRamp, ShadeMode};
use zscan::raster::SubpixelPoint;
use zscan_host::reference::float_render::{self, Interpolation};
use zscan_host::scenes::{Camera, Scene};

use zscan_host::test_rng::XorShift as Rng;

const W: usize = 96;
const H: usize = 96;

/// Draws one triangle on a cleared 96×96 frame, background 0 drawn as index 0 too, so the
/// coverage is read from the depth buffer.
fn draw(v: [SubpixelPoint<4>; 3], lum: [u32; 3], mode: ShadeMode) -> (Vec<u8>, Vec<u16>) {
    let mut px = vec![0u8; W * H];
    let mut zs = vec![0u16; W * H];
    {
        let mut fb = Framebuffer::new(&mut px, W as u16, H as u16).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, W as u16, H as u16).unwrap();
        zb.clear();
        let vals = [0, 1, 2].map(|k| [1u32 << 20, lum[k]]);
        draw_triangle(&mut fb, &mut zb, v, vals, LuminanceRamp::GREY, mode).unwrap();
    }
    (px, zs)
}

/// `f64` screen-affine interpolant at pixel `(x, y)` of the triangle `v` (sub-pixel units).
fn affine(v: [SubpixelPoint<4>; 3], lum: [u32; 3], x: usize, y: usize) -> f64 {
    let p = |k: usize| (v[k].x as f64 / 16.0, v[k].y as f64 / 16.0);
    let ((x0, y0), (x1, y1), (x2, y2)) = (p(0), p(1), p(2));
    let (px, py) = (x as f64, y as f64);
    let d = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
    let w1 = ((px - x0) * (y2 - y0) - (py - y0) * (x2 - x0)) / d;
    let w2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) / d;
    (1.0 - w1 - w2) * lum[0] as f64 + w1 * lum[1] as f64 + w2 * lum[2] as f64
}

#[test]
fn exact_gouraud_is_correctly_rounded_and_fast_is_bounded() {
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    let (mut pixels, mut mismatches, mut ties) = (0u64, 0u64, 0u64);
    let (mut fast_max, mut fast_sum) = (0i32, 0u64);
    for _ in 0..300 {
        let v = [0; 3].map(|_| {
            SubpixelPoint::<4>::new(
                rng.below(W as u64 * 16) as i32,
                rng.below(H as u64 * 16) as i32,
            )
        });
        let lum = [0; 3].map(|_| rng.below(256) as u32);
        let (exact, zs) = draw(v, lum, ShadeMode::GouraudExact);
        let (fast, _) = draw(v, lum, ShadeMode::GouraudFast);
        for y in 0..H {
            for x in 0..W {
                if zs[y * W + x] == u16::MAX {
                    continue;
                }
                pixels += 1;
                let a = affine(v, lum, x, y);
                let frac = a + 0.5 - (a + 0.5).floor();
                if !(1e-9..=1.0 - 1e-9).contains(&frac) {
                    ties += 1;
                    continue;
                }
                let want = (a + 0.5).floor().clamp(0.0, 255.0) as i32;
                let got = exact[y * W + x] as i32;
                if got != want {
                    mismatches += 1;
                }
                let e = (fast[y * W + x] as i32 - want).abs();
                fast_max = fast_max.max(e);
                fast_sum += e as u64;
            }
        }
    }
    let fast_mean = fast_sum as f64 / pixels as f64;
    eprintln!(
        "exact Gouraud: {pixels} pixels, {mismatches} mismatches, {ties} ties skipped; \
         fast: max error {fast_max}, mean {fast_mean:.4} levels"
    );
    assert!(pixels > 200_000, "{pixels}");
    assert_eq!(mismatches, 0);
    assert!(ties * 100 < pixels);
    assert!(fast_max <= 1);
    assert!(fast_mean < 0.05);
}

#[test]
fn quad_rotations_and_the_split_diagonal() {
    let lum = [40u32, 200, 80, 160];
    let (cx, cy, r) = (48.0f64, 48.0f64, 30.0f64);
    // Corner k of the square at angle θ + k·90°; (u, v) ∈ [0,1]² maps to
    // c0 + u·(c1 − c0) + v·(c3 − c0).
    let corners = |theta: f64| {
        [0, 1, 2, 3].map(|k| {
            let a = theta + (k as f64 - 0.5) * std::f64::consts::FRAC_PI_2;
            (cx + r * a.cos(), cy + r * a.sin())
        })
    };
    let sub = |p: (f64, f64)| {
        SubpixelPoint::<4>::new((p.0 * 16.0).round() as i32, (p.1 * 16.0).round() as i32)
    };
    let render = |theta: f64, first: usize| {
        let c = corners(theta);
        let idx = |k: usize| (first + k) % 4;
        let mut px = vec![0u8; W * H];
        let mut zs = vec![0u16; W * H];
        {
            let mut fb = Framebuffer::new(&mut px, W as u16, H as u16).unwrap();
            let mut zb = DepthBuffer::new(&mut zs, W as u16, H as u16).unwrap();
            zb.clear();
            for t in [[0, 1, 2], [0, 2, 3]] {
                let v = t.map(|k| sub(c[idx(k)]));
                let vals = t.map(|k| [1u32 << 20, lum[idx(k)]]);
                draw_triangle(
                    &mut fb,
                    &mut zb,
                    v,
                    vals,
                    LuminanceRamp::GREY,
                    ShadeMode::GouraudExact,
                )
                .unwrap();
            }
        }
        (px, c)
    };
    // Samples at fixed (u, v) points of the quad, nearest pixel, for 12 rotations.
    let grid: Vec<(f64, f64)> = (1..10)
        .flat_map(|i| (1..10).map(move |j| (i as f64 / 10.0, j as f64 / 10.0)))
        .collect();
    let mut per_point: Vec<Vec<f64>> = vec![Vec::new(); grid.len()];
    let mut worst_vs_model = 0.0f64;
    for step in 0..12 {
        let theta = step as f64 * std::f64::consts::PI / 24.0; // 0° .. 82.5°
        let (px, c) = render(theta, 0);
        for (i, &(u, v)) in grid.iter().enumerate() {
            let p = (
                c[0].0 + u * (c[1].0 - c[0].0) + v * (c[3].0 - c[0].0),
                c[0].1 + u * (c[1].1 - c[0].1) + v * (c[3].1 - c[0].1),
            );
            let (x, y) = (p.0.round() as usize, p.1.round() as usize);
            let got = px[y * W + x] as f64;
            per_point[i].push(got);
            // The model at (u, v): triangle (0,1,2) below the diagonal u ≥ v, else (0,2,3).
            let model = if u >= v {
                lum[0] as f64
                    + u * (lum[1] as f64 - lum[0] as f64)
                    + v * (lum[2] as f64 - lum[1] as f64)
            } else {
                lum[0] as f64
                    + v * (lum[3] as f64 - lum[0] as f64)
                    + u * (lum[2] as f64 - lum[3] as f64)
            };
            worst_vs_model = worst_vs_model.max((got - model).abs());
        }
    }
    let spread = per_point
        .iter()
        .map(|s| {
            s.iter().cloned().fold(f64::MIN, f64::max) - s.iter().cloned().fold(f64::MAX, f64::min)
        })
        .fold(0.0, f64::max);
    // Centre with the other diagonal (fan from vertex 1).
    let (a, _) = render(0.3, 0);
    let (b, _) = render(0.3, 1);
    let (ca, cb) = (a[48 * W + 48] as i32, b[48 * W + 48] as i32);
    eprintln!(
        "quad: over 12 rotations the value at 81 fixed points of the quad varies by at most \
         {spread} levels (sampling); worst |picture − model| {worst_vs_model:.2}; centre with \
         diagonal 0–2: {ca}, with diagonal 1–3: {cb} (bilinear centre 120)"
    );
    // Gradient ≤ 160 levels over 42 px ≈ 3.8 levels/px; nearest-pixel sampling moves the
    // point by ≤ 0.71 px: ≤ 2.7 levels plus rounding.
    assert!(worst_vs_model <= 3.5, "{worst_vs_model}");
    assert!(spread <= 6.0, "{spread}");
    assert!((ca - 60).abs() <= 2 && (cb - 180).abs() <= 2, "{ca} {cb}");
}

#[test]
fn affine_vs_perspective_on_a_receding_plane() {
    // A floor strip from z = −2 to z = −30 (inside the frustum: no clipping) seen from just
    // above: luminance 0 at the near edge, 255
    // at the far edge.
    let camera = Camera {
        eye: [0.0, 1.0, 0.0],
        target: [0.0, 0.0, -10.0],
        up: [0.0, 1.0, 0.0],
        fov_y: 60f64.to_radians(),
        near: 0.5,
        far: 100.0,
        width: W as u32,
        height: H as u32,
        principal: ((W as f64 - 1.0) / 2.0, (H as f64 - 1.0) / 2.0),
    };
    let (near, far) = (-2.0, -30.0);
    let p = [
        [-3.0, 0.0, near],
        [3.0, 0.0, near],
        [3.0, 0.0, far],
        [-3.0, 0.0, far],
    ];
    let l = [0u8, 0, 255, 255];
    let scene = Scene::from_triangles(
        "floor",
        camera,
        &[[p[0], p[1], p[2]], [p[0], p[2], p[3]]],
        &[[l[0], l[1], l[2]], [l[0], l[2], l[3]]],
    )
    .unwrap();
    let frame = float_render::render(&scene).unwrap();
    let (mut max, mut sum, mut n) = (0.0f64, 0.0f64, 0usize);
    for f in frame.pixels.iter().flatten() {
        let d = (f.luminance(Interpolation::ScreenAffine)
            - f.luminance(Interpolation::PerspectiveCorrect))
        .abs();
        max = max.max(d);
        sum += d;
        n += 1;
    }
    // The core on the same scene (its exact Gouraud is screen-affine).
    let core = zscan_host::core_render::to_core(&scene).unwrap();
    let cf = core.render::<u32>(ShadeMode::GouraudExact, None).unwrap();
    let (mut core_max, mut compared, mut beyond) = (0.0f64, 0usize, 0usize);
    for y in 0..H as u32 {
        for x in 0..W as u32 {
            let i = (y * W as u32 + x) as usize;
            let Some(f) = frame.at(x, y) else { continue };
            if cf.depth[i] == u32::MAX {
                continue;
            }
            let got = cf.pixels[i] as f64;
            let a = f.luminance(Interpolation::ScreenAffine);
            // The vertices move by ≤ 1/16 pixel when snapped: allow the affine gradient
            // (central difference over the neighbours) times that, plus rounding.
            let grad = |dx: u32, dy: u32| match (
                frame.at(x + dx, y + dy),
                frame.at(x - dx.min(x), y - dy.min(y)),
            ) {
                (Some(p), Some(q)) => {
                    (p.luminance(Interpolation::ScreenAffine)
                        - q.luminance(Interpolation::ScreenAffine))
                    .abs()
                        / 2.0
                }
                _ => 255.0,
            };
            let bound = 0.5 + 0.5 + (grad(1, 0) + grad(0, 1)) * (1.0 / 16.0);
            let e = (got - a).abs();
            core_max = core_max.max(e);
            if e > bound {
                beyond += 1;
            }
            compared += 1;
        }
    }
    eprintln!(
        "receding plane: {n} pixels, affine − perspective luminance: max {max:.1}, mean {:.1} \
         levels; core vs f64 affine: max {core_max:.2} over {compared} pixels, {beyond} beyond \
         1 + |∇L|·δ",
        sum / n as f64
    );
    assert!(n > 1000);
    assert!(
        max > 50.0,
        "the affine error is large on a receding plane: {max}"
    );
    assert!(compared > 1000);
    assert_eq!(beyond, 0);
}
