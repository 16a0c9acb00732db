//! The course's exercise 13 (ch. 3, "Pratique du z-buffer"): the z-buffer by hand on a 2D
//! figure whose depth axis is vertical and whose projection plane is the horizontal axis, each
//! pixel seeing one column of the figure, the depth grid in steps of 1.
//!
//! The course's figure 3.6 is not in the text that survives, so the figure is stated here in
//! the exercise's terms: eight pixels, pixel `i` seeing the figure at `x = i` (zscan's pixels
//! are lattice points; the fill rule keeps a left edge and leaves a right one), depth in tenths
//! of the grid step (smaller is nearer):
//!
//! ```text
//! polygon 1: x ∈ [1, 7), z = 4 everywhere            → pixels 1..=6 at 40
//! polygon 2: x ∈ [0, 5), z from 1 (x = 0) to 6 (x = 5) → pixels 0..=4 at 10 20 30 40 50
//! polygon 3: x ∈ [3, 8), z from 8 (x = 3) to 3 (x = 8) → pixels 3..=7 at 80 70 60 50 40
//! ```
//!
//! Polygons 1 and 2 meet at pixel 3 at the same depth: there the buffer keeps the polygon
//! drawn first (the strict test), so the two orders of questions 2 and 3 end with the same
//! depths and pictures that differ at that pixel alone.
//!
//! The answers below were worked by hand from that table (question 1: each polygon's own
//! z-buffer; question 2: the buffer after each polygon in the order 1, 2, 3; question 3: the
//! order 3, 2, 1), and the renderer's depth buffer and picture must hold them at every step.
//! Each polygon is a rectangle two triangles wide and taller than the one-row frame, drawn
//! by the public `draw_triangle` into a `u32` depth buffer (whose stored depth is the 32-bit
//! depth itself), flat-shaded with luminance `k` for polygon `k` (grey ramp: index `k`).

use zscan::output::{DepthBuffer, Framebuffer};
use zscan::raster::triangle::{draw_triangle, LuminanceRamp, ShadeMode};
use zscan::raster::SubpixelPoint;

const W: usize = 8;
/// The cleared depth: farther than everything.
const F: u32 = u32::MAX;

/// Polygon `k` (1, 2 or 3): `(x_left, x_right, z_left, z_right)` in grid units, depths in
/// tenths.
const POLYGONS: [(i32, i32, u32, u32); 3] = [(1, 7, 40, 40), (0, 5, 10, 60), (3, 8, 80, 30)];

/// Draws polygon `k` into the frame and the depth buffer.
fn draw(k: usize, frame: &mut Framebuffer<'_>, depth: &mut DepthBuffer<'_, u32>) {
    let (xl, xr, zl, zr) = POLYGONS[k - 1];
    let p = |x: i32, y: i32| SubpixelPoint::<4>::new(x * 16, y * 16);
    let (a, b, c, d) = (p(xl, -1), p(xr, -1), p(xl, 2), p(xr, 2));
    let lum = k as u32;
    for (v, z) in [([a, b, d], [zl, zr, zr]), ([a, d, c], [zl, zr, zl])] {
        let values = [0, 1, 2].map(|i| [z[i], lum]);
        draw_triangle(
            frame,
            depth,
            v,
            values,
            LuminanceRamp::GREY,
            ShadeMode::Flat,
        )
        .unwrap();
    }
}

/// The depth buffer and the picture after the clear and after each polygon of `order`, drawn
/// into cleared buffers.
fn steps(order: &[usize]) -> Vec<([u32; W], [u8; W])> {
    let mut pixels = [0u8; W];
    let mut samples = [0u32; W];
    let mut frame = Framebuffer::new(&mut pixels, W as u16, 1).unwrap();
    let mut depth = DepthBuffer::new(&mut samples, W as u16, 1).unwrap();
    frame.clear(0);
    depth.clear();
    let state = |frame: &Framebuffer<'_>, depth: &DepthBuffer<'_, u32>| {
        let z: [u32; W] = depth.row(0).unwrap().try_into().unwrap();
        let p: [u8; W] = frame.row(0).unwrap().try_into().unwrap();
        (z, p)
    };
    let mut out = vec![state(&frame, &depth)];
    for &k in order {
        draw(k, &mut frame, &mut depth);
        out.push(state(&frame, &depth));
    }
    out
}

/// Checks the polygons drawn in `order`: after the clear and after each polygon, the depth
/// buffer against `depths` and the picture against `owners` (the polygon seen at each pixel,
/// 0 for none).
fn run(order: [usize; 3], depths: [[u32; W]; 4], owners: [[u8; W]; 4]) {
    for (step, (z, p)) in steps(&order).into_iter().enumerate() {
        assert_eq!(z, depths[step], "depths, order {order:?}, step {step}");
        assert_eq!(p, owners[step], "picture, order {order:?}, step {step}");
    }
}

/// Question 1: each polygon alone in a cleared buffer.
#[test]
fn question_1_each_polygon_alone() {
    let alone = [
        [F, 40, 40, 40, 40, 40, 40, F],
        [10, 20, 30, 40, 50, F, F, F],
        [F, F, F, 80, 70, 60, 50, 40],
    ];
    for k in 1..=3 {
        let (z, p) = steps(&[k])[1];
        assert_eq!(z, alone[k - 1], "polygon {k}");
        let seen = alone[k - 1].map(|z| if z == F { 0 } else { k as u8 });
        assert_eq!(p, seen, "polygon {k}");
    }
}

/// Question 2: the order 1, 2, 3.
#[test]
fn question_2_in_the_order_1_2_3() {
    run(
        [1, 2, 3],
        [
            [F; W],
            [F, 40, 40, 40, 40, 40, 40, F],
            [10, 20, 30, 40, 40, 40, 40, F],
            [10, 20, 30, 40, 40, 40, 40, 40],
        ],
        [
            [0; W],
            [0, 1, 1, 1, 1, 1, 1, 0],
            [2, 2, 2, 1, 1, 1, 1, 0],
            [2, 2, 2, 1, 1, 1, 1, 3],
        ],
    );
}

/// Question 3: the order reversed, 3, 2, 1. The steps differ; the final depths are question
/// 2's, and so is the picture but at pixel 3, where polygon 2, drawn before polygon 1 this
/// time, keeps the tie.
#[test]
fn question_3_in_the_order_3_2_1() {
    run(
        [3, 2, 1],
        [
            [F; W],
            [F, F, F, 80, 70, 60, 50, 40],
            [10, 20, 30, 40, 50, 60, 50, 40],
            [10, 20, 30, 40, 40, 40, 40, 40],
        ],
        [
            [0; W],
            [0, 0, 0, 3, 3, 3, 3, 3],
            [2, 2, 2, 2, 2, 3, 3, 3],
            [2, 2, 2, 2, 1, 1, 1, 3],
        ],
    );
}
