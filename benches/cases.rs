//! Benchmark cases shared by the Cortex-M example (`examples/cortex_m_bench.rs`) and the host
//! runner (`zscan bench`, `host-tests/src/cli/bench.rs`). Both include this one file with
//! `#[path = ".../benches/cases.rs"] mod cases;`, so every platform measures the same code
//! drawing the same pixels, and the framebuffer checksums must agree across platforms.
//!
//! Rules for this file: `no_std`-compatible (no allocation, no `std`, no floats), only absolute
//! `zscan::` paths, no `unsafe`.
//!
//! # Adding a case
//! 1. Write `fn my_case(fb: &mut Framebuffer<'_>) -> u32` that draws into the cleared
//!    [`WIDTH`] × [`HEIGHT`] framebuffer and returns the number of pixels it wrote (a pixel
//!    written twice counts twice; keep the count a constant or cheap to compute, since it is
//!    inside the measured region).
//! 2. Add one line `Case { name: "my_case", run: my_case },` to [`CASES`].
//!
//! Names are single words (`[a-z0-9_]`), unique. [`CASES`]`[0]` is the empty calibration case;
//! keep it first. The host test `host-tests/tests/bench_cases.rs` checks names and pixel counts.
//!
//! The harness clears the framebuffer to index 0 before each call, calls the case once to warm
//! up, clears again, then measures one call between the region markers.
use zscan::target::Framebuffer;

/// Framebuffer width of every case.
pub const WIDTH: u16 = 320;
/// Framebuffer height of every case.
pub const HEIGHT: u16 = 240;
/// Bytes of the framebuffer.
pub const FB_LEN: usize = WIDTH as usize * HEIGHT as usize;

/// One benchmark case: a name and a drawing function returning the pixels it wrote.
#[derive(Clone, Copy)]
pub struct Case {
    /// Unique single-word name.
    pub name: &'static str,
    /// Draws into a cleared `WIDTH × HEIGHT` framebuffer; returns the pixels written.
    pub run: fn(&mut Framebuffer<'_>) -> u32,
}

/// All cases, in the order they run. `CASES[0]` is the empty calibration case.
pub const CASES: &[Case] = &[
    Case {
        name: "empty",
        run: empty,
    },
    Case {
        name: "line_shallow",
        run: line_shallow,
    },
    Case {
        name: "line_diagonal",
        run: line_diagonal,
    },
    Case {
        name: "line_steep",
        run: line_steep,
    },
    Case {
        name: "line_star64",
        run: line_star64,
    },
    Case {
        name: "line_short",
        run: line_short,
    },
    Case {
        name: "line_clipped",
        run: line_clipped,
    },
];

/// FNV-1a (32-bit) of a byte slice: the framebuffer checksum every platform prints.
pub fn fnv1a(bytes: &[u8]) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for &b in bytes {
        h ^= b as u32;
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}

/// Draws the segment `(x0, y0)–(x1, y1)` (both ends included) with `index`, clipped to the
/// framebuffer: the one place the cases call the line API (`zscan::raster::line::draw_line`).
#[inline(always)]
fn line(fb: &mut Framebuffer<'_>, x0: i32, y0: i32, x1: i32, y1: i32, index: u8) {
    // Coordinates here are far inside the accepted range, so the result is always `Ok`.
    let _ = zscan::raster::line::draw_line(fb, (x0, y0).into(), (x1, y1).into(), index);
}

/// Calibration: draws nothing. Its count is the harness overhead subtracted from every case.
fn empty(_fb: &mut Framebuffer<'_>) -> u32 {
    0
}

/// 8 long x-major lines across the whole width (320 pixels each, slope 37/319).
fn line_shallow(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        let y = 10 + 25 * i;
        line(fb, 0, y, 319, y + 37, 1 + i as u8);
    }
    8 * 320
}

/// 8 diagonal lines at 45° (240 pixels each).
fn line_diagonal(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        let x = 10 * i;
        line(fb, x, 0, x + 239, 239, 1 + i as u8);
    }
    8 * 240
}

/// 8 long y-major lines down the whole height (240 pixels each, slope 50/239).
fn line_steep(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        let x = 20 + 30 * i;
        line(fb, x, 0, x + 50, 239, 1 + i as u8);
    }
    8 * 240
}

/// A star of 64 lines from the centre to points spread over the perimeter of a 200×200
/// square (16 per side), every octant and direction: 101 pixels each.
fn line_star64(fb: &mut Framebuffer<'_>) -> u32 {
    let (cx, cy, r) = (160, 120, 100);
    for k in 0..16 {
        let t = -r + (25 * k) / 2; // -100, -88, ..., 87: 16 points per side
        line(fb, cx, cy, cx + t, cy - r, 1 + k as u8);
        line(fb, cx, cy, cx + r, cy + t, 17 + k as u8);
        line(fb, cx, cy, cx - t, cy + r, 33 + k as u8);
        line(fb, cx, cy, cx - r, cy - t, 49 + k as u8);
    }
    64 * 101
}

/// 256 short lines of 9 pixels in 8 directions: the per-line set-up cost.
fn line_short(fb: &mut Framebuffer<'_>) -> u32 {
    const DIRS: [(i32, i32); 8] = [
        (8, 3),
        (3, 8),
        (-3, 8),
        (-8, 3),
        (-8, -3),
        (-3, -8),
        (3, -8),
        (8, -3),
    ];
    for i in 0..256 {
        let (dx, dy) = DIRS[i & 7];
        let x = 10 + 19 * ((i >> 3) & 15) as i32;
        let y = 12 + 20 * ((i >> 7) * 5 + (i >> 3) % 5) as i32;
        line(fb, x, y, x + dx, y + dy, 1 + (i % 255) as u8);
    }
    256 * 9
}

/// Lines that leave the framebuffer: 8 x-major lines entering at the left edge and leaving at
/// the right (320 visible pixels each), 8 y-major lines crossing from top to bottom (240
/// visible each), and 8 lines entirely outside (0 visible; trivially rejected by a clipper).
fn line_clipped(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        // y = 40 + 20 i + (x + 500) * 60 / 1320 - 22: inside rows 18..220 for 0 <= x < 320.
        let y = 18 + 20 * i;
        line(fb, -500, y, 820, y + 60, 1 + i as u8);
        // x inside columns 30..300 for 0 <= y < 240.
        let x = 30 + 30 * i;
        line(fb, x, -400, x + 40, 640, 9 + i as u8);
        line(fb, -900 + 10 * i, -50, 1200, -10 - i, 17 + i as u8);
    }
    8 * 320 + 8 * 240
}
