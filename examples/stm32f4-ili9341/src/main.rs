//! zscan on an STM32F411 "black pill" (Cortex-M4F at 100 MHz, 128 KB of RAM) driving a
//! 320 × 240 ILI9341 display over SPI with mipidsi: a lit torus turning around a lit sphere,
//! drawn by `render_in_bands` in bands of 16 rows (5 KB of frame, 10 KB of depth), each band
//! getting the text overlay (drawn into the band's palette indices) and then flushed to the
//! display.
//!
//! Wiring (SPI1): SCK PA5, MISO PA6, MOSI PA7, CS PA4, DC PA3, RST PA2, backlight PA1.
//!
//! ```text
//! cargo build --release --target thumbv7em-none-eabihf
//! ```
#![no_std]
#![no_main]

use core::convert::Infallible;
use core::fmt::Write as _;
use cortex_m_rt::entry;
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::{DrawTarget, Point, RgbColor};
use embedded_graphics::text::Text;
use embedded_graphics::Drawable;
use embedded_hal_bus::spi::ExclusiveDevice;
use hal::pac;
use hal::prelude::*;
use hal::spi::{Mode, Phase, Polarity, Spi};
use mipidsi::interface::SpiInterface;
use mipidsi::models::ILI9341Rgb565;
use mipidsi::options::{ColorOrder, Orientation, Rotation};
use mipidsi::Builder;
use panic_halt as _;
use stm32f4xx_hal as hal;
use zscan::prelude::*;
use zscan::target::PaletteIndex;

const W: u16 = 320;
const H: u16 = 240;
/// Rows per band: the frame and depth buffers hold this many rows.
const BAND: u16 = 16;
const BAND_LEN: usize = W as usize * BAND as usize;
const TORUS: (usize, usize) = torus_sizes(24, 12);
const SPHERE: (usize, usize) = uv_sphere_sizes(16, 8);
/// Polygons of both meshes (quads of the torus, triangles of the sphere).
const POLYGONS: usize = TORUS.1 / 4 + SPHERE.1 / 3;
/// Shades per material in the palette.
const LEVELS: u8 = 64;

/// Everything the renderer works in, in one static (so the linker's `.bss` counts it): the
/// meshes' tables, the band buffers and the per-frame scratch.
struct Memory {
    torus: ([Vec3; TORUS.0], [u16; TORUS.1], [Vec3; TORUS.0]),
    sphere: ([Vec3; SPHERE.0], [u16; SPHERE.1], [Vec3; SPHERE.0]),
    pixels: [u8; BAND_LEN],
    depths: [u16; BAND_LEN],
    vertices: [PreparedVertex<4>; TORUS.0 + SPHERE.0],
    polygons: [PolygonRows; POLYGONS],
}

impl Memory {
    fn new() -> Memory {
        Memory {
            torus: ([Vec3::ZERO; TORUS.0], [0; TORUS.1], [Vec3::ZERO; TORUS.0]),
            sphere: (
                [Vec3::ZERO; SPHERE.0],
                [0; SPHERE.1],
                [Vec3::ZERO; SPHERE.0],
            ),
            pixels: [0; BAND_LEN],
            depths: [0; BAND_LEN],
            vertices: [PreparedVertex::default(); TORUS.0 + SPHERE.0],
            polygons: [PolygonRows::default(); POLYGONS],
        }
    }
}

#[entry]
fn main() -> ! {
    let dp = pac::Peripherals::take().unwrap();
    let cp = cortex_m::Peripherals::take().unwrap();
    // The black pill's 25 MHz crystal, the core at 100 MHz.
    let clocks = dp
        .RCC
        .constrain()
        .cfgr
        .use_hse(25.MHz())
        .sysclk(100.MHz())
        .freeze();
    let mut delay = cp.SYST.delay(&clocks);

    let gpioa = dp.GPIOA.split();
    let mode = Mode {
        polarity: Polarity::IdleLow,
        phase: Phase::CaptureOnFirstTransition,
    };
    let (sck, miso, mosi) = (gpioa.pa5, gpioa.pa6, gpioa.pa7);
    let spi = Spi::new(dp.SPI1, (sck, miso, mosi), mode, 25.MHz(), &clocks);
    let cs = gpioa.pa4.into_push_pull_output();
    let dc = gpioa.pa3.into_push_pull_output();
    let rst = gpioa.pa2.into_push_pull_output();
    let mut backlight = gpioa.pa1.into_push_pull_output();
    backlight.set_high();

    let spi = ExclusiveDevice::new_no_delay(spi, cs).unwrap();
    let mut buffer = [0u8; 512];
    let interface = SpiInterface::new(spi, dc, &mut buffer);
    let mut display = Builder::new(ILI9341Rgb565, interface)
        .color_order(ColorOrder::Bgr)
        .orientation(Orientation::new().rotate(Rotation::Deg90).flip_horizontal())
        .reset_pin(rst)
        .init(&mut delay)
        .unwrap();

    let memory = cortex_m::singleton!(: Memory = Memory::new()).unwrap();
    // Returns only on an error: show it as a red screen.
    let _ = run(memory, &mut display);
    let _ = display.clear(Rgb565::RED);
    loop {
        cortex_m::asm::wfi();
    }
}

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

/// Renders frames forever; returns the first error.
fn run<D: DrawTarget<Color = Rgb565>>(
    memory: &mut Memory,
    display: &mut D,
) -> Result<Infallible, zscan::Error> {
    let Memory {
        torus: (tv, ti, tn),
        sphere: (sv, si, sn),
        pixels,
        depths,
        vertices,
        polygons,
    } = memory;
    // Meshes and their normals, generated once into the tables.
    let torus = torus(24, 12, Coord::lit("1.25"), Coord::lit("0.35"), tv, ti)?;
    torus.vertex_normals(tn)?;
    let sphere = uv_sphere(16, 8, Coord::lit("0.6"), sv, si)?;
    sphere.vertex_normals(sn)?;

    let mut ring = Object::new(torus);
    ring.intensities = Intensities::Lit {
        material: Material::from_thousandths(150, 650, 500, 30),
        normals: tn,
    };
    ring.shade = ShadeMode::GouraudExact;
    ring.ramp = ramp(0);
    let mut ball = Object::new(sphere);
    ball.intensities = Intensities::Lit {
        material: Material::from_thousandths(150, 700, 300, 12),
        normals: sn,
    };
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
    let lens = Lens::new(Angle::from_degrees(45), Coord::lit("0.5"), Coord::lit("20"));
    let (eye, up) = (Vec3::from_int(0, 1, 5), Vec3::from_int(0, 1, 0));
    let camera = Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(W, H))?;
    let base = Scene {
        camera,
        objects: &[],
        background: 0,
        ambient: 35,
        lights: &lights,
    };
    // Camera and lights do not change: the renderer is set up once.
    let renderer = Renderer::for_scene(&base)?;

    let lut = palette()?;
    let mut text = heapless::String::<48>::new();
    let mut last = RenderStats::default();
    for frame in 0u32.. {
        ring.transform = Affine3::builder()
            .rotate_y(Angle::from_turns(frame as i64, 120))
            .rotate_x(Angle::from_degrees(65))
            .build()?;
        let objects = [ring, ball];
        // This frame's objects under the renderer's camera and lights (no new set-up).
        let frame_renderer = renderer.with_objects(&objects);
        // The overlay shows the previous frame's counts: this frame's are being summed.
        text.clear();
        let _ = write!(
            text,
            "zscan frame {frame}: {} tris, {} px",
            last.triangles_drawn, last.pixels_covered
        );
        let mut stats = RenderStats::default();
        render_in_bands(
            &frame_renderer,
            (&mut pixels[..], &mut depths[..]),
            (W, H, BAND),
            // Vertex scratch and polygon table for all objects: the vertex stage runs once
            // per frame and each band visits only the polygons that reach it.
            BandScratch {
                vertices: &mut vertices[..],
                polygons: &mut polygons[..],
            },
            &mut stats,
            |band, _depth| {
                // The overlay goes into the band, then the band to the display.
                overlay(band, &text)?;
                flush(band, &lut, display, None).map_err(|_| zscan::Error::Display)
            },
        )?;
        last = stats;
    }
    unreachable!("the frame counter does not end")
}
