//! The board examples' animation, written once: the standard bunny compiled into flash by
//! `zscan mesh` (`examples/flash-mesh`) turns about its vertical axis under a directional
//! light, drawn by [`DoubleBands`] in bands of [`BAND`] rows with a frame counter drawn into
//! each band, and sent by the board's [`BandSink`] (a DMA-driven SPI display on the
//! RP2040 and STM32F4 examples, the window and GIF writer of the simulator).
//!
//! A board supplies only what differs between boards: the display's initialisation, a sink
//! (its `start` opens the display's address window with [`open_window`] and starts the DMA
//! channel on the band's bytes, its `wait` waits for the channel) and a microsecond clock.
//! [`run`] does the rest.
//!
//! Scene: SCENES.md's camera (eye at `(0, 0, 3)`, 60° vertical field of view, near 0.5, far
//! 10) and bunny (1,839 vertices, 3,674 triangles, fit to 0.70), exact Gouraud shading, so that
//! the frame costs what `zscan bench` counts for `frame_bunny_bands16` plus the per-vertex
//! lighting from the flash normals, the LUT conversion and the text.
//!
//! Pixel format: the send buffers hold Rgb565 words in the bus's byte order (big-endian, the
//! order MIPI DCS displays such as the ST7789 and ILI9341 take them), converted through the
//! [`Lut`] line by line by [`DoubleBands`]; [`as_bytes`] views a band as the bytes an 8-bit
//! SPI DMA channel sends.
//!
//! Memory: one [`Memory`] (static on a board, where a DMA channel may read the send buffers
//! for as long as a transfer runs): for a `W`-pixel-wide display, `W·16` bytes of palette
//! indices, `W·16·2` of depth, `2·W·16·2` of send buffers, then the bunny's vertex scratch
//! (1,839 × 28 = 51,492 bytes) and polygon table (3,674 × 4 = 14,696 bytes). The bunny's
//! tables (vertices, indices, normals: 66 KB) stay in flash.
//!
//! The one-bit boards' animation (the same bunny and turn as a hidden-line wireframe on a
//! 128 × 64 monochrome display, packed into the SSD1306's pages) is the `wireframe` module's
//! `Wire`, with the feature `wireframe`.
#![no_std]

#[cfg(feature = "wireframe")]
pub mod wireframe;
#[cfg(feature = "wireframe")]
pub use wireframe::{wire_bunny, wire_camera, Wire, WireMemory, MONO_H, MONO_W, PAGES};

use core::fmt::Write as _;
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565, Rgb888};
use embedded_graphics::prelude::{Point, RgbColor};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::text::Text;
use embedded_graphics::Drawable;
use zscan::output::PaletteIndex;
use zscan::prelude::*;
use zscan::render::DoubleBandError;
use zscan_example_flash_mesh::{bunny, lit_bunny};

/// Rows per band.
pub const BAND: u16 = 16;
/// The bunny's vertices (one prepared vertex each per frame).
pub const VERTICES: usize = bunny::VERTICES.len();
/// Polygon-table entries: the bunny's triangles (for another mesh `zscan mesh` writes, at
/// least its polygons, each having three indices or more).
pub const POLYGONS: usize = bunny::INDICES.len() / 3;
/// Shades of the bunny's material in the palette (indices 1 to 64).
const LEVELS: u8 = 64;
/// Palette index of the overlay's text.
const TEXT: u8 = 255;

/// Everything the animation works in, for a display `BAND_PIXELS / BAND` pixels wide. A board
/// keeps it in a `static mut` of its `#[entry]` function (which cortex-m-rt hands over as a
/// `&'static mut`): the send buffers stay where they are while a DMA channel reads them, and
/// the zeroed static ([`Memory::new`] is a `const fn`) is built in place in `.bss`, not on
/// the stack (a `cortex_m::singleton!` would build its 100 KB there first).
pub struct Memory<const BAND_PIXELS: usize> {
    pixels: [u8; BAND_PIXELS],
    depths: [u16; BAND_PIXELS],
    send: [[u16; BAND_PIXELS]; 2],
    vertices: [PreparedVertex<4>; VERTICES],
    polygons: [PolygonRows; POLYGONS],
}

impl<const BAND_PIXELS: usize> Memory<BAND_PIXELS> {
    /// Zeroed buffers.
    pub const fn new() -> Self {
        Memory {
            pixels: [0; BAND_PIXELS],
            depths: [0; BAND_PIXELS],
            send: [[0; BAND_PIXELS]; 2],
            vertices: [PreparedVertex::ZERO; VERTICES],
            polygons: [PolygonRows::ZERO; POLYGONS],
        }
    }
}

impl<const BAND_PIXELS: usize> Default for Memory<BAND_PIXELS> {
    fn default() -> Self {
        Self::new()
    }
}

/// The display and the animation's pace.
#[derive(Debug, Clone, Copy)]
pub struct Spin {
    /// Display width in pixels (`BAND_PIXELS / BAND`).
    pub width: u16,
    /// Display height in pixels, a multiple of [`BAND`] (every band is then a full one and
    /// the send buffers are exactly a band: what a DMA channel sends whole).
    pub height: u16,
    /// Frames per turn of the bunny.
    pub frames_per_turn: u32,
}

/// What stopped [`run`].
#[derive(Debug)]
pub enum Stop<E> {
    /// Building the camera, palette or turn failed.
    Setup(zscan::Error),
    /// The display does not fit the memory: `width × BAND` must be the memory's band and
    /// `height` a multiple of [`BAND`].
    Layout {
        /// The display's size.
        width: u16,
        /// See `width`.
        height: u16,
        /// The memory's band, in pixels.
        band_pixels: usize,
    },
    /// Drawing or sending a frame failed.
    Frame(DoubleBandError<E>),
}

impl<E> From<zscan::Error> for Stop<E> {
    fn from(e: zscan::Error) -> Self {
        Stop::Setup(e)
    }
}

impl<E: core::fmt::Display> core::fmt::Display for Stop<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Stop::Setup(e) => write!(f, "set-up failed: {e}"),
            Stop::Layout {
                width,
                height,
                band_pixels,
            } => write!(
                f,
                "a {width} x {height} display needs bands of {width} x {BAND} pixels and a \
                 height that is a multiple of {BAND}; the memory's band holds {band_pixels} pixels"
            ),
            Stop::Frame(e) => write!(f, "frame failed: {e}"),
        }
    }
}

/// A sink's error: its bus's, or a band that is not its whole buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SinkError<E> {
    /// The SPI bus or a control pin failed.
    Bus(E),
    /// `start` was called while a transfer ran (a caller other than [`DoubleBands`]).
    Busy,
    /// The band has `band` pixels but its buffer `buffer`: a DMA channel sends whole buffers
    /// ([`run`] checks the layout that makes them equal).
    Length {
        /// Pixels in the band.
        band: usize,
        /// Pixels in the buffer.
        buffer: usize,
    },
}

impl<E: core::fmt::Debug> core::fmt::Display for SinkError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SinkError::Bus(e) => write!(f, "the display bus failed: {e:?}"),
            SinkError::Busy => write!(f, "a band was started while the previous one was sent"),
            SinkError::Length { band, buffer } => write!(
                f,
                "a band of {band} pixels in a send buffer of {buffer}: DMA sends whole buffers"
            ),
        }
    }
}

/// Opens `area` of a MIPI DCS display (ST7789, ILI9341) for a pixel stream: column address
/// set (0x2A), row address set (0x2B), memory write (0x2C). `command(code, parameters)` sends
/// one command (data/command pin low for the code, high for the parameters); the pixels
/// follow with the pin high.
pub fn open_window<E>(
    area: &Rectangle,
    mut command: impl FnMut(u8, &[u8]) -> Result<(), E>,
) -> Result<(), E> {
    let (x0, y0) = (area.top_left.x as u16, area.top_left.y as u16);
    let x1 = x0.saturating_add(area.size.width as u16).saturating_sub(1);
    let y1 = y0.saturating_add(area.size.height as u16).saturating_sub(1);
    let [a, b] = x0.to_be_bytes();
    let [c, d] = x1.to_be_bytes();
    command(0x2A, &[a, b, c, d])?;
    let [a, b] = y0.to_be_bytes();
    let [c, d] = y1.to_be_bytes();
    command(0x2B, &[a, b, c, d])?;
    command(0x2C, &[])
}

/// A band of big-endian Rgb565 words as the bytes an 8-bit SPI sends, in order.
pub fn as_bytes(words: &'static mut [u16]) -> &'static mut [u8] {
    bytemuck::cast_slice_mut(words)
}

/// The words of [`as_bytes`] back (an odd or misaligned slice, which `as_bytes` never
/// gives, comes back empty: the next band then refuses it as too small).
pub fn as_words(bytes: &'static mut [u8]) -> &'static mut [u16] {
    bytemuck::try_cast_slice_mut(bytes).unwrap_or_default()
}

/// The palette: index 0 the background, 1 to 64 the bunny's shades, 255 the text; each entry
/// an Rgb565 word in the bus's byte order.
pub fn palette() -> Result<Lut<u16>, zscan::Error> {
    let mut rgb = Lut::<Rgb565>::shaded(&[Rgb888::new(235, 205, 160)], LEVELS, 1)?;
    rgb.set(0, Rgb565::new(2, 5, 8));
    rgb.set(TEXT, Rgb565::WHITE);
    Ok(Lut::from_entries(core::array::from_fn(|i| {
        rgb.get(i as u8).into_storage().to_be()
    })))
}

/// The light: directional, from the upper right and in front of the bunny.
pub static LIGHTS: [Light; 1] = [Light::Directional {
    toward: Vec3::from_int(1, 2, 3),
    intensity: 215,
}];
/// The ambient level.
pub const AMBIENT: u8 = 40;

/// SCENES.md's camera for a `width × height` display: eye at `(0, 0, 3)` looking at the
/// origin, 60° vertical field of view, near 0.5, far 10.
pub fn camera(width: u16, height: u16) -> Result<Camera, zscan::Error> {
    const LENS: Lens = lens(60);
    looking_at_origin(LENS, width, height)
}

/// A vertical field of view of `degrees`, near 0.5, far 10: a `const fn`, for constants
/// (`Coord::lit` evaluated at run time would link the decimal parser, 9 KB on a Cortex-M0+).
pub(crate) const fn lens(degrees: i32) -> Lens {
    Lens {
        fov: BinaryAngle::from_degrees(degrees),
        axis: FovAxis::Vertical,
        near: Coord::lit("0.5"),
        far: Coord::lit("10"),
    }
}

/// The eye at `(0, 0, 3)`, up `+y`, looking at the origin through `lens` on a
/// `width × height` display.
pub(crate) fn looking_at_origin(
    lens: Lens,
    width: u16,
    height: u16,
) -> Result<Camera, zscan::Error> {
    let (eye, up) = (Vec3::from_int(0, 0, 3), Vec3::from_int(0, 1, 0));
    Ok(Camera::look_at(
        eye,
        Vec3::ZERO,
        up,
        lens,
        Viewport::new(width, height),
    )?)
}

/// The bunny of frame `frame`: lit from its flash normals, exact Gouraud, the palette's ramp,
/// turned `frame / frames_per_turn` of a turn about its vertical axis (`frames_per_turn` 0 is
/// taken as 1).
pub fn bunny(frame: u32, frames_per_turn: u32) -> Result<Object<'static>, zscan::Error> {
    let mut bunny = lit_bunny(Material::from_thousandths(150, 750, 300, 16));
    bunny.shade = ShadeMode::GouraudExact;
    bunny.ramp = LuminanceRamp {
        first: 1,
        levels: LEVELS as u16,
    };
    bunny.transform = Affine3::builder()
        .rotate_y(turn(frame, frames_per_turn))
        .build()?;
    Ok(bunny)
}

/// The bunny's angle about its vertical axis in frame `frame`: `frame / frames_per_turn` of a
/// turn (`frames_per_turn` 0 is taken as 1); [`bunny`] and the wireframe's `wire_bunny` turn
/// alike.
pub fn turn(frame: u32, frames_per_turn: u32) -> BinaryAngle {
    let turn = frames_per_turn.max(1);
    BinaryAngle::from_turns((frame % turn) as i64, turn)
}

/// The animation's scene: `objects` seen by `camera` under [`LIGHTS`] and [`AMBIENT`], on
/// palette index 0.
pub fn scene<'a>(camera: Camera, objects: &'a [Object<'a>]) -> Scene<'a> {
    Scene {
        camera,
        objects,
        background: 0,
        ambient: AMBIENT,
        lights: &LIGHTS,
    }
}

/// Draws frames into `sink` until `frame_done(frame, sink)` returns `false` (a board's never
/// does) or a frame fails. `clock_us` is a free-running microsecond counter (wrapping): the
/// overlay shows the previous frame's period and rate, measured, beside the frame number.
pub fn run<K, const BAND_PIXELS: usize>(
    memory: &'static mut Memory<BAND_PIXELS>,
    spin: Spin,
    sink: K,
    mut clock_us: impl FnMut() -> u32,
    mut frame_done: impl FnMut(u32, &mut K) -> bool,
) -> Result<(), Stop<K::Error>>
where
    K: BandSink<'static, u16>,
{
    let Spin {
        width,
        height,
        frames_per_turn,
    } = spin;
    if width as usize * BAND as usize != BAND_PIXELS || height % BAND != 0 {
        return Err(Stop::Layout {
            width,
            height,
            band_pixels: BAND_PIXELS,
        });
    }
    let Memory {
        pixels,
        depths,
        send: [send_a, send_b],
        vertices,
        polygons,
    } = memory;

    // Camera and lights do not change: the renderer is set up once.
    let base = scene(camera(width, height)?, &[]);
    let renderer = Renderer::for_scene(&base).map_err(zscan::Error::from)?;

    let lut = palette()?;
    let mut bands = DoubleBands::new(&lut, [send_a, send_b], sink);
    let style = MonoTextStyle::new(&FONT_6X10, PaletteIndex(TEXT));
    let mut text = heapless::String::<48>::new();
    let mut last = clock_us();
    let mut frame = 0u32;
    loop {
        let objects = [bunny(frame, frames_per_turn)?];
        let mut stats = RenderStats::default();
        bands
            .render(
                &renderer.with_objects(&objects),
                (&mut pixels[..], &mut depths[..]),
                (width, height, BAND),
                BandScratch {
                    vertices: &mut vertices[..],
                    polygons: &mut polygons[..],
                },
                &mut stats,
                // The counter goes into each band (those without its rows keep nothing).
                |band| {
                    let _ = Text::new(&text, Point::new(6, 14), style).draw(band);
                },
            )
            .map_err(Stop::Frame)?;
        let now = clock_us();
        let period = now.wrapping_sub(last).max(1);
        last = now;
        text.clear();
        // Whole and tenth milliseconds and frames per second, in integers.
        let tenths_fps = 10_000_000 / period;
        let _ = write!(
            text,
            "frame {} {}.{} ms {}.{} fps",
            frame.wrapping_add(1),
            period / 1000,
            period / 100 % 10,
            tenths_fps / 10,
            tenths_fps % 10
        );
        if !frame_done(frame, bands.sink_mut()) {
            return Ok(());
        }
        frame = frame.wrapping_add(1);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::boxed::Box;
    use std::vec;
    use std::vec::Vec;

    /// A sink that records every band into a whole frame and checks the double-buffer
    /// discipline: `start` and `wait` alternate, and a band is never handed out again before
    /// its transfer was waited for.
    struct Recorder {
        width: usize,
        frame: Vec<u16>,
        sending: Option<&'static mut [u16]>,
        areas: Vec<Rectangle>,
    }

    impl BandSink<'static, u16> for Recorder {
        type Error = core::convert::Infallible;

        fn start(
            &mut self,
            pixels: &'static mut [u16],
            area: Rectangle,
        ) -> Result<(), Self::Error> {
            assert!(self.sending.is_none(), "start while a band is being sent");
            let first = area.top_left.y as usize * self.width;
            let n = area.size.width as usize * area.size.height as usize;
            self.frame[first..first + n].copy_from_slice(&pixels[..n]);
            self.areas.push(area);
            self.sending = Some(pixels);
            Ok(())
        }

        fn wait(&mut self) -> (&'static mut [u16], Result<(), Self::Error>) {
            let pixels = self.sending.take().expect("wait without a transfer");
            (pixels, Ok(()))
        }
    }

    const W: u16 = 320;
    const H: u16 = 240;
    const N: usize = W as usize * BAND as usize;

    fn memory<const P: usize>() -> &'static mut Memory<P> {
        Box::leak(Box::new(Memory::new()))
    }

    fn recorder() -> Recorder {
        Recorder {
            width: W as usize,
            frame: vec![0xDEAD; W as usize * H as usize],
            sending: None,
            areas: Vec::new(),
        }
    }

    /// Frame 0 (its counter text still empty) is, word for word, the one-pass z-buffer
    /// picture of the same scene through the palette, sent as 15 bands of 16 rows in order.
    #[test]
    fn first_frame_is_the_one_pass_picture_through_the_palette() {
        let spin = Spin {
            width: W,
            height: H,
            frames_per_turn: 120,
        };
        let mut sent = None;
        let done = run(
            memory::<N>(),
            spin,
            recorder(),
            || 0,
            |frame, r| {
                assert_eq!(frame, 0);
                assert!(
                    r.sending.is_none(),
                    "the frame ended with a transfer running"
                );
                sent = Some((core::mem::take(&mut r.frame), core::mem::take(&mut r.areas)));
                false
            },
        );
        assert!(done.is_ok());
        let (sent, areas) = sent.expect("one frame");
        let rows: Vec<i32> = areas.iter().map(|a| a.top_left.y).collect();
        assert_eq!(rows, (0..15).map(|b| b * 16).collect::<Vec<i32>>());
        assert!(areas
            .iter()
            .all(|a| a.size.width == 320 && a.size.height == 16));

        let objects = [bunny(0, 120).unwrap()];
        let scene = scene(camera(W, H).unwrap(), &objects);
        let renderer = Renderer::for_scene(&scene).unwrap();
        let size = W as usize * H as usize;
        let (mut pixels, mut depths) = (vec![0u8; size], vec![0u16; size]);
        let mut frame = Framebuffer::new(&mut pixels, W, H).unwrap();
        let mut depth = DepthBuffer::new(&mut depths, W, H).unwrap();
        let mut scratch = vec![PreparedVertex::default(); VERTICES];
        let mut stats = RenderStats::default();
        render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats).unwrap();
        let lut = palette().unwrap();
        let expected: Vec<u16> = pixels.iter().map(|&i| lut.get(i)).collect();
        assert!(stats.pixels_covered > 5_000, "{stats:?}");
        assert_eq!(sent, expected);
    }

    /// Frame 1 carries frame 0's counter: its first band differs from a text-free picture
    /// in the text's pixels only, which are the palette's white.
    #[test]
    fn second_frame_carries_the_counter() {
        let spin = Spin {
            width: W,
            height: H,
            frames_per_turn: 120,
        };
        let mut frames = Vec::new();
        let mut clock = 0;
        let done = run(
            memory::<N>(),
            spin,
            recorder(),
            || {
                clock += 40_000; // 40 ms a frame: "25.0 fps"
                clock
            },
            |frame, r| {
                frames.push(r.frame.clone());
                frame < 1
            },
        );
        assert!(done.is_ok());
        assert_eq!(frames.len(), 2);
        let white = palette().unwrap().get(TEXT);
        let text_pixels =
            |f: &Vec<u16>| f[..W as usize * 16].iter().filter(|&&p| p == white).count();
        assert_eq!(text_pixels(&frames[0]), 0);
        // "frame 1 40.0 ms 25.0 fps": 24 characters of FONT_6X10, a few pixels each.
        assert!(
            text_pixels(&frames[1]) > 24 * 5,
            "{}",
            text_pixels(&frames[1])
        );
    }

    /// A display whose band is not the memory's, or whose height is not a multiple of the
    /// band, is refused before anything is drawn.
    #[test]
    fn wrong_layout_is_refused() {
        for (width, height) in [(240, 240), (320, 200)] {
            let spin = Spin {
                width,
                height,
                frames_per_turn: 1,
            };
            let mut r = recorder();
            r.frame.clear();
            let result = run(memory::<N>(), spin, r, || 0, |_, _| false);
            match result {
                Err(Stop::Layout { band_pixels, .. }) => assert_eq!(band_pixels, N),
                other => panic!("{width}x{height}: {other:?}"),
            }
        }
    }

    /// The address window of the band at rows 16..32 of a 320-pixel-wide display.
    #[test]
    fn window_commands_are_caset_raset_ramwr() {
        let mut sent: Vec<(u8, Vec<u8>)> = Vec::new();
        let size = embedded_graphics::prelude::Size::new(320, 16);
        open_window::<()>(
            &Rectangle::new(Point::new(0, 16), size),
            |code, parameters| {
                sent.push((code, parameters.to_vec()));
                Ok(())
            },
        )
        .unwrap();
        assert_eq!(
            sent,
            [
                (0x2A, vec![0, 0, 0x01, 0x3F]),
                (0x2B, vec![0, 16, 0, 31]),
                (0x2C, vec![]),
            ]
        );
    }

    /// A band's words go out high byte first (red is 0xF800), and come back unchanged.
    #[test]
    fn bytes_are_big_endian_and_round_trip() {
        let words: &'static mut [u16] = Box::leak(Box::new([0xF800u16.to_be(), 0x001Fu16.to_be()]));
        let bytes = as_bytes(words);
        assert_eq!(bytes, [0xF8, 0x00, 0x00, 0x1F]);
        let back = as_words(bytes);
        assert_eq!(back, [0xF800u16.to_be(), 0x001Fu16.to_be()]);
        assert_eq!(u16::from_be(palette().unwrap().get(TEXT)), 0xFFFF);
    }
}
