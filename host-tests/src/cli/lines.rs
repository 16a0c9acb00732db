//! `zscan lines`: a test pattern of lines and circles.
//!
//! The pattern ([`pattern`]) is a list of [`Primitive`]s drawn in order by [`draw`]: a star of
//! spokes in every octant around the centre, lines whose end points lie far outside the frame
//! (up to ±2^30) so that only their clipped middle shows, lines crossing the border, concentric
//! and corner circles (clipped), a row of small circles and the arc of a huge circle. The image
//! goes through a shaded palette (or the grey ramp with `--grey`) to a PNG, PPM or PGM file.
//! Host-side code may use floating point to place the spokes; the drawing itself is zscan's.
use super::CliError;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::Point;
use zscan::output::{shaded_index, Framebuffer, Lut};
use zscan::raster::{circle, line};

/// Arguments of `zscan lines`.
#[derive(clap::Args, Debug)]
pub struct LinesArgs {
    /// Output image (.png, .pgm or .ppm).
    #[arg(short, long, default_value = "out/lines.png")]
    pub output: std::path::PathBuf,
    /// Width of the image.
    #[arg(long, default_value_t = 320)]
    pub width: u16,
    /// Height of the image.
    #[arg(long, default_value_t = 240)]
    pub height: u16,
    /// Use the grey ramp (index = grey level) instead of the shaded palette.
    #[arg(long)]
    pub grey: bool,
}

/// One element of the test pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Primitive {
    /// A closed Bresenham line.
    Line {
        /// First end point.
        p0: Point,
        /// Last end point.
        p1: Point,
        /// Palette index.
        index: u8,
    },
    /// A midpoint circle outline.
    Circle {
        /// Centre.
        centre: Point,
        /// Radius.
        radius: u32,
        /// Palette index.
        index: u8,
    },
}

/// First palette index of the shaded palette (index 0 stays black).
pub const FIRST: u8 = 1;
/// Shade levels per material.
pub const LEVELS: u8 = 40;

/// The materials of the shaded palette: spokes, far lines, circles, border lines, small circles.
pub const MATERIALS: [Rgb888; 5] = [
    Rgb888::new(255, 255, 255),
    Rgb888::new(255, 150, 40),
    Rgb888::new(60, 220, 255),
    Rgb888::new(255, 80, 200),
    Rgb888::new(170, 255, 90),
];

/// The shaded palette of the pattern: black at 0, then [`LEVELS`] shades of each material.
pub fn palette() -> Lut<Rgb888> {
    // 1 + 5 × 40 = 201 entries: always fits.
    Lut::shaded(&MATERIALS, LEVELS, FIRST).unwrap_or_else(|_| Lut::grey_ramp())
}

fn shade(material: u8, s: u8) -> u8 {
    shaded_index(FIRST, LEVELS, material, s)
}

/// The test pattern for a `width × height` frame, in drawing order.
pub fn pattern(width: u16, height: u16) -> Vec<Primitive> {
    let (w, h) = (width as i32, height as i32);
    let (cx, cy) = (w / 2, h / 2);
    let m = w.min(h);
    let mut out = Vec::new();
    let line = |x0: i32, y0: i32, x1: i32, y1: i32, index: u8| Primitive::Line {
        p0: Point::new(x0, y0),
        p1: Point::new(x1, y1),
        index,
    };
    let circ = |x: i32, y: i32, radius: u32, index: u8| Primitive::Circle {
        centre: Point::new(x, y),
        radius,
        index,
    };
    // Circles behind everything: concentric around the centre (the outer ones clipped).
    for (i, r) in [m * 2 / 5 + 6, m / 2 + 10, m * 3 / 4]
        .into_iter()
        .enumerate()
    {
        out.push(circ(cx, cy, r.max(0) as u32, shade(2, 39 - 8 * i as u8)));
    }
    // Corner circles: three quarters outside.
    out.push(circ(0, 0, (m / 3).max(0) as u32, shade(3, 39)));
    out.push(circ(w, h, (m * 2 / 5).max(0) as u32, shade(3, 30)));
    // The arc of a huge circle along the bottom.
    out.push(circ(cx, h - 12 + 1_000_000, 1_000_000, shade(2, 20)));
    // A row of small circles, radius 0 to 6.
    for r in 0..7 {
        out.push(circ(
            12 + r * (r + 3) + 2 * r,
            h - 24,
            r as u32,
            shade(4, 39),
        ));
    }
    // The star: 48 spokes (every octant, the axes and the diagonals included).
    let spokes = 48;
    let radius = (m * 2 / 5) as f64;
    for k in 0..spokes {
        let a = k as f64 * std::f64::consts::TAU / spokes as f64;
        let (x, y) = (
            cx + (radius * a.cos()).round() as i32,
            cy + (radius * a.sin()).round() as i32,
        );
        out.push(line(
            cx,
            cy,
            x,
            y,
            shade(0, 14 + (k * 25 / (spokes - 1)) as u8),
        ));
    }
    // Lines through a point of the frame with both ends far outside (up to ±2^30).
    let far = [
        (w / 8, h * 5 / 6, 1_000_003, -777_777),
        (w * 7 / 8, h / 8, (1 << 29) + 12_345, (1 << 28) / 3),
        (w * 4 / 5, h / 2, 1_234, -1_000_000_000),
        (w / 5, h / 6, 1 << 30, 3),
    ];
    for (i, (px, py, dx, dy)) in far.into_iter().enumerate() {
        let (dx, dy) = (
            dx.min((1 << 30) - px.abs()),
            dy.clamp(-(1 << 30) + py.abs(), (1 << 30) - py.abs()),
        );
        out.push(line(
            px - dx,
            py - dy,
            px + dx,
            py + dy,
            shade(1, 39 - 6 * i as u8),
        ));
    }
    // Lines crossing the border: one end inside, or both just outside.
    out.push(line(-40, h / 3, w + 25, h / 3 + 37, shade(3, 35)));
    out.push(line(w / 3, -30, w / 3 - 50, h + 30, shade(3, 35)));
    out.push(line(w - 10, h - 10, w + 500_000, h + 123_456, shade(4, 30)));
    out.push(line(5, h - 5, -700_000, -300_001, shade(4, 30)));
    out
}

/// Draws `prims` in order into `fb`.
pub fn draw(fb: &mut Framebuffer<'_>, prims: &[Primitive]) -> Result<(), CliError> {
    for p in prims {
        match *p {
            Primitive::Line { p0, p1, index } => line::draw_line(fb, p0, p1, index)?,
            Primitive::Circle {
                centre,
                radius,
                index,
            } => circle::draw_circle(fb, centre, radius, index)?,
        }
    }
    Ok(())
}

/// Runs `zscan lines`.
pub fn run(args: LinesArgs) -> Result<(), CliError> {
    let (w, h) = (args.width, args.height);
    super::check_picture_size("--width/--height", w, h)?;
    let mut pixels = vec![0u8; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut pixels, w, h)
        .map_err(|e| format!("cannot make a {w}×{h} frame: {e}"))?;
    draw(&mut fb, &pattern(w, h))?;
    let lut = if args.grey {
        Lut::grey_ramp()
    } else {
        palette()
    };
    crate::image::write_image(&args.output, &fb, &lut)?;
    crate::note!("wrote {}", args.output.display());
    Ok(())
}
