//! The one-bit boards' animation (`examples/ssd1306-wireframe`) on the host:
//! `zscan_board_common::Wire` draws the bunny as a hidden-line wireframe at 128 × 64 and packs
//! it into the SSD1306's pages; here those bytes, what the board sends over I²C, are read back
//! bit by bit into a `SimulatorDisplay<BinaryColor>` and into the frames of a two-colour
//! animated GIF (each pixel scaled × [`SCALE`]).
//!
//! ```text
//! cargo run --release -- --ssd1306 out/ssd1306.gif [FRAMES]   # one turn in FRAMES frames (48)
//! cargo run --release -- --ssd1306 out/ssd1306.png [FRAMES]   # the turn's last frame (× 4)
//! ```
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::{DrawTarget, Point, Size};
use embedded_graphics::Pixel;
use embedded_graphics_simulator::{BinaryColorTheme, OutputSettingsBuilder, SimulatorDisplay};
use zscan_board_common::{Wire, WireMemory, MONO_H, MONO_W};

/// Each display pixel is `SCALE × SCALE` pixels of the GIF.
const SCALE: u16 = 2;
/// Hundredths of a second between the GIF's frames.
const DELAY: u16 = 4;
/// The GIF's two colours: off (the OLED's black) and on (its white-blue).
const COLOURS: [u8; 6] = [0, 0, 0, 0xB4, 0xDC, 0xFF];

/// Pixel `(x, y)` of the display from its pages: bit `y mod 8` of byte `⌊y / 8⌋ · 128 + x`.
fn pixel(pages: &[u8], x: u16, y: u16) -> bool {
    pages[(y / 8) as usize * MONO_W as usize + x as usize] >> (y % 8) & 1 == 1
}

/// Writes one turn of `frames` frames to `path` (a GIF, or the last frame as a PNG).
pub fn main(path: &str, frames: u32) -> Result<(), Box<dyn std::error::Error>> {
    let memory: &'static mut WireMemory = Box::leak(Box::new(WireMemory::new()));
    let mut wire = Wire::new(memory, frames)?;
    let (w, h) = (MONO_W * SCALE, MONO_H * SCALE);
    let png = path.ends_with(".png");
    let mut gif = if png {
        None
    } else {
        let mut encoder = gif::Encoder::new(std::fs::File::create(path)?, w, h, &COLOURS)?;
        encoder.set_repeat(gif::Repeat::Infinite)?;
        Some(encoder)
    };
    let mut display = SimulatorDisplay::<BinaryColor>::new(Size::new(MONO_W.into(), MONO_H.into()));
    let mut indices = vec![0u8; w as usize * h as usize];
    for frame in 0..frames {
        let pages = wire.frame(frame)?;
        let bits = (0..MONO_H).flat_map(|y| (0..MONO_W).map(move |x| (x, y)));
        display.draw_iter(bits.map(|(x, y)| {
            let colour = BinaryColor::from(pixel(pages, x, y));
            Pixel(Point::new(x.into(), y.into()), colour)
        }))?;
        if let Some(encoder) = gif.as_mut() {
            for (i, out) in indices.iter_mut().enumerate() {
                let (x, y) = ((i % w as usize) as u16, (i / w as usize) as u16);
                *out = pixel(pages, x / SCALE, y / SCALE) as u8;
            }
            let f = gif::Frame {
                width: w,
                height: h,
                delay: DELAY,
                buffer: indices.as_slice().into(),
                ..gif::Frame::default()
            };
            encoder.write_frame(&f)?;
        }
    }
    drop(gif);
    if png {
        let settings = OutputSettingsBuilder::new()
            .scale(4)
            .theme(BinaryColorTheme::OledWhite)
            .build();
        display.to_rgb_output_image(&settings).save_png(path)?;
    }
    println!("wrote {path}: {frames} frames of the {MONO_W}x{MONO_H} one-bit wireframe");
    Ok(())
}
