//! Sending a frame to a display: palette indices → colours through the [`Lut`], then
//! `DrawTarget::fill_contiguous` row block by row block.
//!
//! `fill_contiguous` is the call display drivers (mipidsi, ssd1306, the simulator) implement as
//! one address-window set-up followed by a stream of pixels, so a flush costs one window per
//! call, not one per pixel. An optional dirty rectangle limits the transfer to changed pixels.
//!
//! ## Dirty rectangles
//! Any `Rectangle` is accepted: its position is any `Point` (`i32`) and its size any `Size`
//! (`u32`), so its far corner may lie past `i32::MAX`. The region sent is the intersection of
//! the rectangle with the frame's window, computed in `i64` (`x0 + width < 2^31 + 2^32`), so
//! no size overflows and the display is never told to fill more pixels than are streamed: the
//! area passed to `fill_contiguous` is exactly the rows × columns whose colours follow. An empty
//! intersection (a rectangle beside the frame, or of zero width or height) sends nothing.

use super::{Framebuffer, Lut};
use embedded_graphics_core::{
    draw_target::DrawTarget,
    geometry::{Point, Size},
    pixelcolor::PixelColor,
    primitives::Rectangle,
};

/// Sends `frame` (or its part inside `dirty`, in absolute picture coordinates) to `display`
/// through `lut`, with one `fill_contiguous` call covering the whole region.
///
/// The region sent is `dirty ∩ frame.window()`; an empty intersection sends nothing. Pixels of
/// a band land at their absolute rows, so flushing each band after drawing it composes the
/// full picture on the display.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565, prelude::*};
/// use zscan::prelude::*;
///
/// let mut pixels = [0u8; 8 * 4];
/// let mut frame = Framebuffer::new(&mut pixels, 8, 4)?;
/// frame.set_pixel(2, 1, 255); // palette index 255: white through the grey palette
/// static LUT: Lut<Rgb565> = Lut::<Rgb565>::GREY; // 256 colours, in flash
/// let mut display = MockDisplay::<Rgb565>::new(); // any DrawTarget<Color = Rgb565>
/// flush(&frame, &LUT, &mut display, None)?; // the whole frame in one fill_contiguous call
/// assert_eq!(display.get_pixel(Point::new(2, 1)), Some(Rgb565::WHITE));
/// assert_eq!(display.get_pixel(Point::new(0, 0)), Some(Rgb565::BLACK));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// The error is the display's (`D::Error`); a driver's error type rarely converts into
/// [`zscan::Error`](crate::Error), so map it: `.map_err(|_| zscan::Error::Display)?`.
pub fn flush<C, D>(
    frame: &Framebuffer<'_>,
    lut: &Lut<C>,
    display: &mut D,
    dirty: Option<Rectangle>,
) -> Result<(), D::Error>
where
    C: PixelColor,
    D: DrawTarget<Color = C>,
{
    let w = frame.window();
    // The frame's window, and `dirty ∩ window` in i64: a `Size` up to u32::MAX added to an
    // i32 corner cannot overflow there (embedded-graphics' own intersection works in i32).
    let (mut x0, mut y0, mut x1, mut y1) = (w.x0 as i64, w.y0 as i64, w.x1 as i64, w.y1 as i64);
    if let Some(d) = dirty {
        let (dx, dy) = (d.top_left.x as i64, d.top_left.y as i64);
        x0 = x0.max(dx);
        y0 = y0.max(dy);
        x1 = x1.min(dx + d.size.width as i64);
        y1 = y1.min(dy + d.size.height as i64);
    }
    if x0 >= x1 || y0 >= y1 {
        return Ok(());
    }
    // Inside the window now: 0 ≤ x0 < x1 ≤ width and top ≤ y0 < y1 ≤ top + height, all i32.
    let area = Rectangle::new(
        Point::new(x0 as i32, y0 as i32),
        Size::new((x1 - x0) as u32, (y1 - y0) as u32),
    );
    let (c0, c1) = (x0 as usize, x1 as usize);
    let colours = (y0 as i32..y1 as i32)
        .filter_map(|y| frame.row(y))
        .flat_map(move |row| row.get(c0..c1).unwrap_or(&[]).iter().map(|&i| lut.get(i)));
    display.fill_contiguous(&area, colours)
}
