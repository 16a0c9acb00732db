//! Issue 16 #1 at the largest sizes: triangles of any size within the raster's range, and
//! scenes at the largest viewports the core holds, drawn with the exact fill and the exactly
//! rounded depth and luminance (the wide attribute plane, `raster::triangle::wide_plane::WidePlane`).
//!
//! The references here are independent of the core's arithmetic: the exact rational fill of
//! `reference::exact_fill` (winding numbers in `i128`), the correctly rounded interpolant
//! computed from barycentric weights in `i128`, and for whole scenes the `f64` geometry of a
//! quad facing the camera (its level is affine in the screen there, its depth constant).
//! The common sizes (512×512 to 1024×768, principal points in the corners) are compared
//! with the `f64` renderer in `tests/render_accuracy.rs::large_viewports_match_the_reference`.

use zscan::geometry::camera::{Camera, FovAxis, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::output::{DepthBuffer, DepthValue, Framebuffer};
use zscan::raster::triangle::{draw_triangle, LuminanceRamp, ShadeMode};
use zscan::raster::SubpixelPoint;
use zscan::render::{
    render_in_bands, render_scene, BandScratch, PreparedVertex, RenderError, RenderStats, Renderer,
};
use zscan::visibility::Visibility;
use zscan_host::core_render::{
    render_compact_picture, render_visible, scene_of, CoreFrame, CoreMesh,
};
use zscan_host::reference::compare::Rng;
use zscan_host::reference::exact_fill::covered;

/// The correctly rounded (half up) screen-affine interpolant of `a` over `v` at pixel
/// `(x, y)`, from barycentric weights in `i128`.
fn exact_value(v: &[(i64, i64); 3], a: [u32; 3], x: i64, y: i64) -> u32 {
    let p = |q: (i64, i64)| (q.0 as i128, q.1 as i128);
    let ((x0, y0), (x1, y1), (x2, y2)) = (p(v[0]), p(v[1]), p(v[2]));
    let (px, py) = ((x as i128) << 4, (y as i128) << 4);
    let d = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
    let w1 = (px - x0) * (y2 - y0) - (py - y0) * (x2 - x0);
    let w2 = (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0);
    let num = (d - w1 - w2) * a[0] as i128 + w1 * a[1] as i128 + w2 * a[2] as i128;
    let (num, d) = if d < 0 { (-num, -d) } else { (num, d) };
    (2 * num + d).div_euclid(2 * d) as u32
}

/// Triangles of every size up to the raster's whole range (`±(2^28 − 1)` sub-pixel units, far
/// past the 2^30 limit of the 32-bit stepping plane), drawn by the public `draw_triangle` into
/// bands of a 65 535-pixel-wide frame: every pixel of the band is covered exactly as the
/// rational fill says, with the exactly rounded depth (full 32-bit range) and luminance.
#[test]
fn huge_triangles_have_exact_coverage_depth_and_luminance() {
    const W: u16 = 65535;
    const ROWS: u16 = 2;
    let mut rng = Rng::new(0x16_0001);
    let mut px = vec![0u8; W as usize * ROWS as usize];
    let mut zs = vec![0u32; W as usize * ROWS as usize];
    let (mut covered_total, mut huge) = (0u64, 0);
    for i in 0..24 {
        // Boxes from 2^20 sub-pixel units (2^16 px) to the whole range, around the frame.
        let m = [1i64 << 20, 1 << 24, 1 << 27, (1 << 28) - 1][i % 4];
        let c = |rng: &mut Rng| rng.range(-m, m).clamp(-(1 << 28) + 1, (1 << 28) - 1);
        let v = [0; 3].map(|_| (c(&mut rng) + (32768 << 4), c(&mut rng)));
        let v = v.map(|(x, y)| (x.clamp(-(1 << 28) + 1, (1 << 28) - 1), y));
        let depth = [0; 3].map(|_| rng.range(0, u32::MAX as i64 - 1) as u32);
        let lum = [0; 3].map(|_| rng.range(0, 255) as u32);
        let d2 = ((v[1].0 - v[0].0) as i128 * (v[2].1 - v[0].1) as i128
            - (v[1].1 - v[0].1) as i128 * (v[2].0 - v[0].0) as i128)
            .abs();
        huge += (d2 >= 1 << 30) as u32;
        // A band through the triangle's middle rows.
        let top = (((v[0].1 + v[1].1 + v[2].1) / 3) >> 4) as u16;
        let top = top.min(u16::MAX - ROWS);
        px.fill(7);
        let mut fb = Framebuffer::band(&mut px, W, ROWS, top).unwrap();
        let mut zb = DepthBuffer::band(&mut zs, W, ROWS, top).unwrap();
        zb.clear();
        let sv = v.map(|(x, y)| SubpixelPoint::<4>::new(x as i32, y as i32));
        let values = [0, 1, 2].map(|k| [depth[k], lum[k]]);
        let mode = ShadeMode::GouraudExact;
        let (n, _) = draw_triangle(&mut fb, &mut zb, sv, values, LuminanceRamp::GREY, mode)
            .unwrap_or_else(|e| panic!("{v:?}: {e}"));
        let mut count = 0u64;
        for r in 0..ROWS as usize {
            let y = top as i64 + r as i64;
            for x in 0..W as i64 {
                let k = r * W as usize + x as usize;
                if !covered(&v, 4, x, y) {
                    assert_eq!((px[k], zs[k]), (7, u32::FAR), "({x}, {y}) of {v:?}");
                    continue;
                }
                count += 1;
                let want_z = exact_value(&v, depth, x, y);
                let want_l = exact_value(&v, lum, x, y);
                assert_eq!(
                    (zs[k], px[k] as u32),
                    (want_z, want_l),
                    "({x}, {y}) of {v:?}"
                );
            }
        }
        assert_eq!(count, n as u64, "{v:?}");
        covered_total += count;
    }
    assert!(
        huge >= 18 && covered_total > 400_000,
        "{huge} {covered_total}"
    );
}

/// The big quad of issue 16 #1 (40 × 40 units facing the eye 3 units away, a level per
/// corner) on a camera of `w × h` pixels, field of view `fov_y` degrees, principal point `p`.
fn quad_at(w: u16, h: u16, fov_y: i32, p: (f64, f64)) -> CoreMesh {
    let c = |v: f64| Coord::from_num(v);
    let mut vp = Viewport::new(w, h);
    (vp.principal_x, vp.principal_y) = (c(p.0), c(p.1));
    let lens =
        Lens::new(BinaryAngle::from_degrees(fov_y), c(0.5), c(10.0)).with_axis(FovAxis::Vertical);
    let camera = Camera::look_at(
        Vec3::from_int(0, 0, 3),
        Vec3::ZERO,
        Vec3::from_int(0, 1, 0),
        lens,
        vp,
    )
    .unwrap();
    let v = |x: i32, y: i32| Vec3::from_int(x, y, 0);
    CoreMesh {
        vertices: vec![v(-20, -20), v(20, -20), v(20, 20), v(-20, 20)],
        indices: vec![0, 1, 2, 0, 2, 3],
        intensities: vec![20, 200, 120, 240],
        per_vertex: true,
        camera,
    }
}

/// The quad's level at pixel `(x, y)` and its `D(z)`, in `f64`: the pixel's point on the
/// plane `z = 0` (3 units from the eye), the level affine over each triangle `(a, b, c)`,
/// `(a, c, d)` of the quad, `D(3)` of the projection's formula.
fn quad_reference(mesh: &CoreMesh, x: f64, y: f64) -> (f64, f64) {
    let vp = mesh.camera.viewport();
    let (cx, cy) = (
        vp.principal_x.to_num::<f64>(),
        vp.principal_y.to_num::<f64>(),
    );
    let f = mesh.camera.focal_y().to_num::<f64>();
    let (wx, wy) = ((x - cx) * 3.0 / f, -(y - cy) * 3.0 / f);
    // Levels 20, 200, 120, 240 at (−20, −20), (20, −20), (20, 20), (−20, 20).
    let (s, t) = ((wx + 20.0) / 40.0, (wy + 20.0) / 40.0);
    let level = if s >= t {
        20.0 + s * 180.0 + t * (120.0 - 200.0)
    } else {
        20.0 + t * 220.0 + s * (120.0 - 240.0)
    };
    let (near, far, z) = (0.5, 10.0, 3.0);
    let d = (u32::MAX as f64) * far * (z - near) / (z * (far - near));
    (level, d)
}

/// The quad at the largest viewports: the command-line tool's 4096 × 4096 and the core's
/// 65 535 × 65 535 (a field of view of 90°: the focal length stays below its 32 768-pixel
/// limit), principal point centred, in a corner, or at the far end of its I16F16 range (left of
/// the picture), drawn in bands of 2 rows at the top, the
/// middle and the bottom. Every pixel is drawn; its level is within 1 of the `f64` one
/// (exact rounding, plus the clip points' levels rounded to integers); every depth is the
/// same (the quad's depth plane is constant) and within the projection's 8 units of `D(3)`.
#[test]
fn maximum_viewports_render_the_quad() {
    const ROWS: u16 = 2;
    let sizes = [
        (4096, 4096, 60, (2047.5, 2047.5)),
        (65535, 65535, 90, (32767.0, 32767.0)),
        (65535, 65535, 90, (0.0, 0.0)),
        (65535, 65535, 90, (-32767.0, 32767.0)),
    ];
    for (w, h, fov, p) in sizes {
        let mesh = quad_at(w, h, fov, p);
        let objects = [mesh.object(ShadeMode::GouraudExact).unwrap()];
        let scene = scene_of(&objects, mesh.camera);
        let renderer = Renderer::for_scene(&scene).unwrap();
        let mut scratch = vec![PreparedVertex::<4>::default(); 4];
        let n = w as usize * ROWS as usize;
        let (mut px, mut zs) = (vec![0u8; n], vec![0u32; n]);
        let mut depths = Vec::new();
        for top in [0, h / 2, h - ROWS] {
            let mut fb = Framebuffer::band(&mut px, w, ROWS, top).unwrap();
            let mut zb = DepthBuffer::band(&mut zs, w, ROWS, top).unwrap();
            let mut stats = RenderStats::default();
            render_scene(&renderer, &mut fb, &mut zb, &mut scratch, &mut stats)
                .unwrap_or_else(|e| panic!("{w}×{h} at {p:?}: {e}"));
            for (k, (&l, &z)) in px.iter().zip(&zs).enumerate() {
                let (x, y) = (
                    (k % w as usize) as f64,
                    (top as usize + k / w as usize) as f64,
                );
                let (level, d) = quad_reference(&mesh, x, y);
                assert!(z != u32::FAR, "({x}, {y}) not drawn at {w}×{h}, {p:?}");
                assert!(
                    (l as f64 - level).abs() <= 1.0,
                    "({x}, {y}): {l} vs {level}"
                );
                assert!((z as f64 - d).abs() <= 8.0, "({x}, {y}): {z} vs {d}");
            }
            depths.extend_from_slice(&zs);
        }
        assert!(depths.iter().all(|&z| z == depths[0]), "{w}×{h} at {p:?}");
    }
}

/// Issue 16, `render_in_bands`: bands of 0 rows are an error naming the value (they were
/// silently made 1); a band taller than the picture is the whole picture in one band.
#[test]
fn zero_band_rows_are_an_error() {
    let mesh = quad_at(32, 24, 60, (15.5, 11.5));
    let objects = [mesh.object(ShadeMode::GouraudExact).unwrap()];
    let scene = scene_of(&objects, mesh.camera);
    let renderer = Renderer::for_scene(&scene).unwrap();
    let (mut px, mut zs) = (vec![0u8; 32 * 24], vec![0u16; 32 * 24]);
    let mut bands = 0;
    for rows in [0u16, 24, 100, u16::MAX] {
        let mut scratch = [PreparedVertex::<4>::default(); 4];
        let band = BandScratch {
            vertices: &mut scratch,
            polygons: &mut [],
        };
        let r = render_in_bands(
            &renderer,
            (&mut px, &mut zs),
            (32, 24, rows),
            band,
            &mut RenderStats::default(),
            |f, _| -> Result<(), RenderError> {
                assert_eq!((f.top(), f.height()), (0, 24));
                bands += 1;
                Ok(())
            },
        );
        if rows == 0 {
            let e = r.unwrap_err();
            assert_eq!(e, RenderError::BadBandRows { band_rows: 0 });
            assert!(e.to_string().contains("bands of 0 rows"), "{e}");
        } else {
            r.unwrap();
        }
    }
    assert_eq!(bands, 3);
}

/// Issue 16's slow input: a tall picture in bands of one row re-clipped every clipped polygon
/// in every band (4,096 bands × the clipped polygons). With the polygon table a clipped
/// polygon is clipped once per frame to find its rows, and only the bands it reaches clip it
/// again: here a thin triangle above the eye that runs under the camera (crossing the near
/// plane) reaches the top 20 or so rows of 4,096. The picture is one pass's.
#[test]
fn tall_pictures_in_thin_bands_clip_only_where_the_clipped_polygons_reach() {
    let c = |v: f64| Coord::from_num(v);
    let lens =
        Lens::new(BinaryAngle::from_degrees(60), c(0.5), c(10.0)).with_axis(FovAxis::Vertical);
    let camera = Camera::look_at(
        Vec3::from_int(0, 0, 3),
        Vec3::ZERO,
        Vec3::from_int(0, 1, 0),
        lens,
        Viewport::new(16, 4096),
    )
    .unwrap();
    let v = |x: f64, y: f64, z: f64| Vec3::new(c(x), c(y), c(z));
    let mesh = CoreMesh {
        vertices: vec![v(-0.02, 3.4, -3.0), v(0.02, 3.4, -3.0), v(0.0, 3.4, 2.9)],
        // Both windings: one is culled, whichever faces the eye is clipped and drawn.
        indices: vec![0, 1, 2, 0, 2, 1],
        intensities: vec![60, 120, 240],
        per_vertex: true,
        camera,
    };
    let shade = ShadeMode::GouraudExact;
    let one: CoreFrame<u32> = mesh.render(shade, None).unwrap();
    assert_eq!(one.stats.clipped, 1, "one triangle crosses the near plane");
    let first_empty = (0..4096)
        .find(|&y| one.pixels[y * 16..(y + 1) * 16].iter().all(|&p| p == 0))
        .unwrap();
    assert!(
        (5..40).contains(&first_empty),
        "drawn rows 0..{first_empty}"
    );
    let every: CoreFrame<u32> = mesh.render(shade, Some(1)).unwrap();
    let table: CoreFrame<u32> = mesh.render_with(shade, Some(1), true).unwrap();
    for b in [&every, &table] {
        assert!(b.pixels == one.pixels && b.depth == one.depth);
    }
    // Without the table every band clips it; with it, about the rows it reaches (rounded).
    println!(
        "rows 0..{first_empty}: clipper runs {} without the table, {} with it",
        every.stats.clipped, table.stats.clipped
    );
    assert_eq!(every.stats.clipped, 4096);
    assert!(
        (first_empty as u32..=first_empty as u32 + 2).contains(&table.stats.clipped),
        "{} clipper runs for {first_empty} rows",
        table.stats.clipped
    );
}

/// Issue 16, every banded entry refuses bands of 0 rows with `BadBandRows` (the host harness
/// and the scan-line used to make them 1 silently).
#[test]
fn zero_band_rows_are_an_error_in_every_banded_entry() {
    let mesh = quad_at(32, 24, 60, (15.5, 11.5));
    let e = mesh
        .render::<u16>(ShadeMode::GouraudExact, Some(0))
        .unwrap_err();
    assert!(e.contains("bands of 0 rows"), "{e}");
    let objects = [mesh.object(ShadeMode::GouraudExact).unwrap()];
    let scene = scene_of(&objects, mesh.camera);
    let renderer = Renderer::for_scene(&scene).unwrap();
    let scan = render_visible(&renderer, (32, 24), Visibility::ScanLine, None, 0);
    assert_eq!(
        scan.unwrap_err(),
        RenderError::BadBandRows { band_rows: 0 }.into()
    );
    let compact = render_compact_picture::<u16, 4>(&renderer, (32, 24), 0);
    assert_eq!(
        compact.unwrap_err(),
        RenderError::BadBandRows { band_rows: 0 }
    );
}
