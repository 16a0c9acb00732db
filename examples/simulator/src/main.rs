//! The board examples' animation on the host: `zscan_board_common::run` (the standard bunny
//! compiled into flash by `zscan mesh`, turning, drawn in double-buffered bands of 16 rows with
//! a frame counter) at 320 × 240, with [`Screen`] as its band sink: the boards' DMA SPI sink
//! without the bus, drawing each band into an embedded-graphics `SimulatorDisplay` and
//! keeping the frame's palette indices for an animated GIF.
//!
//! ```text
//! cargo run --release -- out/simulator.gif [FRAMES]   # one turn in FRAMES frames (48), no SDL
//! cargo run --release --features window               # the GIF, then an SDL2 window
//! ```
//!
//! A path ending in `.png` gets the turn's last frame as a PNG instead (scaled × 2).
//!
//! With `--ssd1306` first, the one-bit boards' animation instead ([`mono`]): the bunny as a
//! hidden-line wireframe on a 128 × 64 monochrome display, from the bytes the SSD1306 board
//! sends.
mod mono;

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::DrawTarget;
use embedded_graphics::prelude::{RgbColor, Size};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use std::collections::HashMap;
use std::convert::Infallible;
use std::time::Instant;
use zscan::prelude::BandSink;
use zscan_board_common::{palette, run, Memory, Spin, BAND};

const W: u16 = 320;
const H: u16 = 240;
const BAND_PIXELS: usize = W as usize * BAND as usize;
/// Frames in the GIF's turn when none are given.
const FRAMES: u32 = 48;
/// Hundredths of a second between the GIF's frames.
const DELAY: u16 = 4;

/// The band sink: each band (Rgb565 words in the bus's byte order, as a board's DMA sends
/// them) is drawn into the simulator's display and its palette indices kept for the GIF.
struct Screen {
    display: SimulatorDisplay<Rgb565>,
    /// The palette index of every word the palette holds.
    index_of: HashMap<u16, u8>,
    /// The frame's palette indices, row by row.
    indices: Vec<u8>,
    /// The band being "sent" (at once, here), until `wait` gives it back.
    held: Option<&'static mut [u16]>,
}

impl BandSink<'static, u16> for Screen {
    type Error = Infallible;

    fn start(&mut self, pixels: &'static mut [u16], area: Rectangle) -> Result<(), Infallible> {
        let n = area.size.width as usize * area.size.height as usize;
        let band = &pixels[..n.min(pixels.len())];
        let first = area.top_left.y as usize * W as usize;
        for (out, word) in self.indices[first..].iter_mut().zip(band) {
            // Every word sent is a palette entry (the LUT wrote it).
            *out = self.index_of[word];
        }
        let colours = band
            .iter()
            .map(|&w| Rgb565::from(RawU16::new(u16::from_be(w))));
        self.display.fill_contiguous(&area, colours)?;
        self.held = Some(pixels);
        Ok(())
    }

    fn wait(&mut self) -> (&'static mut [u16], Result<(), Infallible>) {
        (self.held.take().unwrap_or_default(), Ok(()))
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1).peekable();
    let ssd1306 = args.next_if(|a| a == "--ssd1306").is_some();
    let path = args.next().unwrap_or_else(|| {
        if ssd1306 {
            "out/ssd1306.gif".into()
        } else {
            "out/simulator.gif".into()
        }
    });
    let frames: u32 = match args.next() {
        Some(n) => n.parse().map_err(|e| format!("frames {n:?}: {e}"))?,
        None => FRAMES,
    };
    if frames == 0 {
        return Err("frames: at least 1".into());
    }
    if let Some(dir) = std::path::Path::new(&path).parent() {
        std::fs::create_dir_all(dir)?;
    }
    if ssd1306 {
        return mono::main(&path, frames);
    }

    // The palette, as words (the sink's input) and as RGB (the GIF's colour table).
    let lut = palette()?;
    let mut index_of = HashMap::new();
    let mut colours = Vec::with_capacity(3 * 256);
    for i in (0..=255u8).rev() {
        index_of.insert(lut.get(i), i); // the lowest index of a colour wins
    }
    for i in 0..=255u8 {
        let c = Rgb888::from(Rgb565::from(RawU16::new(u16::from_be(lut.get(i)))));
        colours.extend([c.r(), c.g(), c.b()]);
    }
    let screen = || Screen {
        display: SimulatorDisplay::new(Size::new(W as u32, H as u32)),
        index_of: index_of.clone(),
        indices: vec![0; W as usize * H as usize],
        held: None,
    };
    let started = Instant::now();
    let clock_us = move || started.elapsed().as_micros() as u32;
    let spin = Spin {
        width: W,
        height: H,
        frames_per_turn: frames,
    };

    // One turn into the file. The memory is leaked: `run` takes it for the program's life, as
    // a board's static.
    let memory: &'static mut Memory<BAND_PIXELS> = Box::leak(Box::new(Memory::new()));
    let png = path.ends_with(".png");
    let mut gif = if png {
        None
    } else {
        let mut encoder = gif::Encoder::new(std::fs::File::create(&path)?, W, H, &colours)?;
        encoder.set_repeat(gif::Repeat::Infinite)?;
        Some(encoder)
    };
    let mut last = None;
    let mut written = Ok(());
    run(memory, spin, screen(), clock_us, |frame, screen| {
        if let Some(encoder) = gif.as_mut() {
            let f = gif::Frame {
                width: W,
                height: H,
                delay: DELAY,
                buffer: screen.indices.as_slice().into(),
                ..gif::Frame::default()
            };
            written = encoder.write_frame(&f);
        }
        if frame + 1 == frames {
            last = Some(screen.display.clone());
        }
        written.is_ok() && frame + 1 < frames
    })
    .map_err(|e| e.to_string())?;
    written?;
    drop(gif);
    let settings = OutputSettingsBuilder::new().scale(2).build();
    if let (true, Some(display)) = (png, &last) {
        display.to_rgb_output_image(&settings).save_png(&path)?;
    }
    println!("wrote {path}: {frames} frames of {W}x{H}");

    #[cfg(feature = "window")]
    {
        // The same animation in a window, until it is closed.
        use embedded_graphics_simulator::{SimulatorEvent, Window};
        let mut window = Window::new("zscan", &settings);
        let memory: &'static mut Memory<BAND_PIXELS> = Box::leak(Box::new(Memory::new()));
        let spin = Spin {
            frames_per_turn: 120,
            ..spin
        };
        run(memory, spin, screen(), clock_us, |_, screen| {
            window.update(&screen.display);
            !window.events().any(|e| matches!(e, SimulatorEvent::Quit))
        })
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}
