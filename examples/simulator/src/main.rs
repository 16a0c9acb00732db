//! zscan on the embedded-graphics simulator: a lit torus around a lit sphere, 320 × 240,
//! rendered band by band (16 rows: 5 KB of frame and 10 KB of depth) through a shaded
//! palette; the text overlay is drawn into each band (palette indices) before its flush.
//!
//! ```text
//! cargo run --release -- out/simulator.png            # writes the PNG (no SDL needed)
//! cargo run --release --features window               # also opens an SDL2 window
//! ```
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::{Point, RgbColor, Size};
use embedded_graphics::text::Text;
use embedded_graphics::Drawable;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use std::fmt::Write as _;
use zscan::prelude::*;
use zscan::target::PaletteIndex;

const W: u16 = 320;
const H: u16 = 240;
/// Rows per band: the frame and depth buffers hold this many rows.
const BAND: u16 = 16;
const BAND_LEN: usize = W as usize * BAND as usize;
const TORUS: (usize, usize) = torus_sizes(32, 16);
const SPHERE: (usize, usize) = uv_sphere_sizes(20, 10);
/// Shades per material in the palette.
const LEVELS: u8 = 64;

/// The palette: index 0 the background, then 64 shades of each material.
fn palette() -> Result<Lut<Rgb565>, zscan::Error> {
    let bases = [Rgb888::new(255, 150, 40), Rgb888::new(60, 170, 255)];
    let mut lut = Lut::shaded(&bases, LEVELS, 1)?;
    lut.set(0, Rgb565::new(2, 5, 6));
    lut.set(TEXT, Rgb565::WHITE);
    Ok(lut)
}

/// The material `m` of the palette as a luminance ramp.
fn ramp(m: u8) -> LuminanceRamp {
    LuminanceRamp {
        first: 1 + m * LEVELS,
        levels: LEVELS as u16,
    }
}

/// Palette index of the overlay's text.
const TEXT: u8 = 255;

/// Draws `text` into the band (a `DrawTarget` of palette indices; it keeps the rows it holds).
fn overlay(band: &mut Framebuffer<'_>, text: &str) -> Result<(), zscan::Error> {
    let style = MonoTextStyle::new(&FONT_6X10, PaletteIndex(TEXT));
    Text::new(text, Point::new(6, 14), style).draw(band)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "out/simulator.png".into());

    // Meshes and their normals, generated once into our tables.
    let (mut tv, mut ti, mut tn) = (
        vec![Vec3::ZERO; TORUS.0],
        vec![0; TORUS.1],
        vec![Vec3::ZERO; TORUS.0],
    );
    let torus = torus(
        32,
        16,
        Coord::lit("1.25"),
        Coord::lit("0.35"),
        &mut tv,
        &mut ti,
    )?;
    torus.vertex_normals(&mut tn)?;
    let (mut sv, mut si, mut sn) = (
        vec![Vec3::ZERO; SPHERE.0],
        vec![0; SPHERE.1],
        vec![Vec3::ZERO; SPHERE.0],
    );
    let sphere = uv_sphere(20, 10, Coord::lit("0.6"), &mut sv, &mut si)?;
    sphere.vertex_normals(&mut sn)?;

    let mut ring = Object::new(torus);
    ring.transform = Affine3::builder()
        .rotate_x(Angle::from_degrees(70))
        .rotate_z(Angle::from_degrees(-20))
        .build()?;
    ring.intensities = Intensities::Lit {
        material: Material::from_thousandths(150, 650, 500, 30),
        normals: &tn,
    };
    ring.shade = ShadeMode::Phong;
    ring.ramp = ramp(0);
    let mut ball = Object::new(sphere);
    ball.intensities = Intensities::Lit {
        material: Material::from_thousandths(150, 700, 300, 12),
        normals: &sn,
    };
    ball.shade = ShadeMode::GouraudExact;
    ball.ramp = ramp(1);

    let lights = [
        Light::Point {
            position: Vec3::from_int(-4, 5, 6),
            intensity: 220,
        },
        Light::Directional {
            toward: Vec3::from_int(2, -1, 1),
            intensity: 50,
        },
    ];
    let lens = Lens::new(Angle::from_degrees(40), Coord::lit("0.5"), Coord::lit("20"));
    let (eye, up) = (Vec3::from_int(0, 1, 5), Vec3::from_int(0, 1, 0));
    let camera = Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(W, H))?;
    let objects = [ring, ball];
    let scene = Scene {
        camera,
        objects: &objects,
        background: 0,
        ambient: 35,
        lights: &lights,
    };
    let renderer = Renderer::for_scene(&scene)?;

    // Band-sized buffers; vertex scratch and polygon table for all objects (the vertex stage
    // runs once per frame, each band visits only the polygons that reach it).
    let (mut pixels, mut depths) = (vec![0u8; BAND_LEN], vec![0u16; BAND_LEN]);
    let mut vertices = vec![PreparedVertex::default(); TORUS.0 + SPHERE.0];
    let polygons = objects.iter().map(|o| o.mesh.polygon_count()).sum();
    let mut table = vec![PolygonRows::default(); polygons];
    let scratch = BandScratch {
        vertices: &mut vertices,
        polygons: &mut table,
    };

    let lut = palette()?;
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(W as u32, H as u32));
    let mut text = String::new();
    write!(text, "zscan {W}x{H}, bands of {BAND} rows")?;
    let mut stats = RenderStats::default();
    render_in_bands(
        &renderer,
        (&mut pixels, &mut depths),
        (W, H, BAND),
        scratch,
        &mut stats,
        |band, _depth| {
            // The overlay goes into the band, then the band to the display.
            overlay(band, &text)?;
            flush(band, &lut, &mut display, None).map_err(|_| zscan::Error::Display)
        },
    )?;

    let settings = OutputSettingsBuilder::new().scale(2).build();
    if let Some(dir) = std::path::Path::new(&path).parent() {
        std::fs::create_dir_all(dir)?;
    }
    display.to_rgb_output_image(&settings).save_png(&path)?;
    println!("wrote {path}: {stats:?}");

    #[cfg(feature = "window")]
    embedded_graphics_simulator::Window::new("zscan", &settings).show_static(&display);
    Ok(())
}
