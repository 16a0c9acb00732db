//! The one-bit animation: the coarse bunny (`zscan_example_flash_mesh::coarse`, 117 vertices
//! and 243 triangles clustered from the standard one, whose front edges at this size would be
//! about a pixel apart), turned as in [`run`](crate::run), drawn as a
//! wireframe with hidden lines removed (`Wireframe::Hidden`: the faces into the depth buffer,
//! then the front faces' edges depth-tested against them) on a 128 × 64 monochrome display,
//! and packed into the SSD1306's pages (`pack_pages`) for the board to send as they are.
//!
//! Memory: one [`WireMemory`], 29 KB: the whole 128 × 64 frame's palette indices (8,192
//! bytes) and 16-bit depths (16,384), the coarse bunny's vertex scratch (117 × 28 = 3,276
//! bytes) and the 1,024 bytes of pages sent to the display.
//!
//! Camera: SCENES.md's eye at `(0, 0, 3)` looking at the origin, near 0.5 and far 10, with a
//! 48° vertical field of view (60° on the colour boards), so that the bunny fills most of the
//! display's 64 rows.

use crate::turn;
use embedded_graphics::pixelcolor::BinaryColor;
use zscan::prelude::*;
use zscan_example_flash_mesh::coarse;

/// The coarse bunny's vertex count.
const VERTICES: usize = coarse::VERTICES.len();

/// The display's width in pixels.
pub const MONO_W: u16 = 128;
/// The display's height in pixels (8 pages of 8 rows).
pub const MONO_H: u16 = 64;
/// Pixels in the frame.
const PIXELS: usize = MONO_W as usize * MONO_H as usize;
/// Bytes of the frame in pages.
pub const PAGES: usize = page_bytes(MONO_W, MONO_H);
/// The lines' palette index (the background is 0).
const LINE: u8 = 255;
/// Indices 1 to 255 on: the lines; 0, the background, off.
static ON_OFF: Lut<BinaryColor> = Lut::<BinaryColor>::threshold(1);

/// Everything the wireframe animation works in (module doc). A board keeps it in a
/// `static mut` of its `#[entry]` function: [`WireMemory::new`] is a `const fn`, so it is
/// zeroed `.bss` built in place.
pub struct WireMemory {
    pixels: [u8; PIXELS],
    depths: [u16; PIXELS],
    vertices: [PreparedVertex<4>; VERTICES],
    pages: [u8; PAGES],
}

impl WireMemory {
    /// Zeroed buffers.
    pub const fn new() -> Self {
        WireMemory {
            pixels: [0; PIXELS],
            depths: [0; PIXELS],
            vertices: [PreparedVertex::ZERO; VERTICES],
            pages: [0; PAGES],
        }
    }
}

impl Default for WireMemory {
    fn default() -> Self {
        Self::new()
    }
}

/// The camera of the one-bit display (module doc).
pub fn wire_camera() -> Result<Camera, zscan::Error> {
    const LENS: Lens = crate::lens(48);
    crate::looking_at_origin(LENS, MONO_W, MONO_H)
}

/// The coarse bunny of frame `frame` as [`bunny`](crate::bunny) turns the standard one, unlit (lines take their
/// palette index from their style).
pub fn wire_bunny(frame: u32, frames_per_turn: u32) -> Result<Object<'static>, zscan::Error> {
    let mut object = Object::new(coarse::MESH);
    object.transform = Affine3::builder()
        .rotate_y(turn(frame, frames_per_turn))
        .build()?;
    Ok(object)
}

/// The wireframe animation: its renderer (set up once) and memory.
pub struct Wire {
    renderer: Renderer<4>,
    memory: &'static mut WireMemory,
    frames_per_turn: u32,
}

impl Wire {
    /// The animation in `memory`, one turn in `frames_per_turn` frames.
    pub fn new(
        memory: &'static mut WireMemory,
        frames_per_turn: u32,
    ) -> Result<Self, zscan::Error> {
        let renderer = Renderer::<4>::new(&wire_camera()?)?;
        Ok(Wire {
            renderer,
            memory,
            frames_per_turn,
        })
    }

    /// Draws frame `frame` and returns its pages: byte `page · 128 + x` holds column `x` of
    /// rows `8·page` to `8·page + 7`, the top row in bit 0 (what the SSD1306 takes in its
    /// horizontal addressing mode, the whole display's window open).
    pub fn frame(&mut self, frame: u32) -> Result<&[u8], zscan::Error> {
        let WireMemory {
            pixels,
            depths,
            vertices,
            pages,
        } = &mut *self.memory;
        let mut target = Framebuffer::new(pixels, MONO_W, MONO_H)?;
        let mut depth = DepthBuffer::new(depths, MONO_W, MONO_H)?;
        target.clear(0);
        depth.clear();
        let object = wire_bunny(frame, self.frames_per_turn)?;
        let style = LineStyle::new(LINE);
        self.renderer.draw_wireframe(
            &object,
            &[],
            Wireframe::Hidden,
            vertices,
            &style,
            &mut target,
            &mut depth,
        )?;
        let n = pack_pages(&target, &ON_OFF, pages)?;
        Ok(&pages[..n])
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::boxed::Box;
    use std::vec;

    /// Frame 1 drawn after frame 0 in the same memory is, bit for bit, the hidden-line
    /// wireframe of frame 1 drawn alone into fresh buffers: a pixel's bit (by the page
    /// layout's definition) is set exactly where that picture has the line's index.
    #[test]
    fn pages_are_the_hidden_line_picture() {
        let memory = Box::leak(Box::new(WireMemory::new()));
        let mut wire = Wire::new(memory, 48).unwrap();
        wire.frame(0).unwrap();
        let pages = wire.frame(1).unwrap().to_vec();
        assert_eq!(pages.len(), 1024);

        let renderer = Renderer::<4>::new(&wire_camera().unwrap()).unwrap();
        let (mut pixels, mut depths) = (vec![0u8; PIXELS], vec![0u16; PIXELS]);
        let mut frame = Framebuffer::new(&mut pixels, MONO_W, MONO_H).unwrap();
        let mut depth = DepthBuffer::new(&mut depths, MONO_W, MONO_H).unwrap();
        depth.clear();
        let mut scratch = vec![PreparedVertex::default(); VERTICES];
        let drawn = renderer
            .draw_wireframe(
                &wire_bunny(1, 48).unwrap(),
                &[],
                Wireframe::Hidden,
                &mut scratch,
                &LineStyle::new(LINE),
                &mut frame,
                &mut depth,
            )
            .unwrap();
        let mut on = 0;
        for y in 0..MONO_H as usize {
            for x in 0..MONO_W as usize {
                let bit = pages[y / 8 * MONO_W as usize + x] >> (y % 8) & 1 == 1;
                assert_eq!(bit, pixels[y * MONO_W as usize + x] == LINE, "({x}, {y})");
                on += bit as usize;
            }
        }
        // Not a blank or filled display, and lines rather than a filled silhouette (the
        // standard bunny's front edges, about a pixel apart at this size, lit about 2,000).
        assert!(drawn > 0 && on > 300 && on < 1_500, "{on} pixels on");
    }
}
