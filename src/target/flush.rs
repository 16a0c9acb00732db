//! Sending a frame to a display: palette indices → colours through the [`Lut`], then
//! `DrawTarget::fill_contiguous` row block by row block.
//!
//! `fill_contiguous` is the call display drivers (mipidsi, ssd1306, the simulator) implement as
//! one address-window set-up followed by a stream of pixels, so a flush costs one window per
//! call, not one per pixel. An optional dirty rectangle limits the transfer to changed pixels.

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
    let full = Rectangle::new(
        Point::new(w.x0, w.y0),
        Size::new((w.x1 - w.x0) as u32, (w.y1 - w.y0) as u32),
    );
    let area = match dirty {
        Some(d) => d.intersection(&full),
        None => full,
    };
    let Some(br) = area.bottom_right() else {
        return Ok(());
    };
    let (x0, x1) = (area.top_left.x as usize, br.x as usize + 1);
    let colours = (area.top_left.y..=br.y)
        .filter_map(|y| frame.row(y))
        .flat_map(|row| row[x0..x1].iter().map(|&i| lut.get(i)));
    display.fill_contiguous(&area, colours)
}
