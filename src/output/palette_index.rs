//! [`PaletteIndex`]: the colour type of the indexed framebuffer, so embedded-graphics text and
//! shapes can be drawn over a 3D frame with `Framebuffer` as their `DrawTarget`.

use super::Framebuffer;
use embedded_graphics_core::{
    draw_target::DrawTarget,
    geometry::{Dimensions, Point, Size},
    pixelcolor::{raw::RawU8, PixelColor},
    primitives::Rectangle,
    Pixel,
};

/// A palette index (0..=255), resolved to a display colour by a [`Lut`](super::Lut).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct PaletteIndex(pub u8);

impl PixelColor for PaletteIndex {
    type Raw = RawU8;
}

impl From<RawU8> for PaletteIndex {
    fn from(raw: RawU8) -> Self {
        use embedded_graphics_core::pixelcolor::raw::RawData;
        PaletteIndex(raw.into_inner())
    }
}

impl Dimensions for Framebuffer<'_> {
    /// The rows held, in absolute picture coordinates: for a band drawn at `top`, the box
    /// starts at `(0, top)`, so the same drawing code serves every band.
    fn bounding_box(&self) -> Rectangle {
        Rectangle::new(
            Point::new(0, self.top()),
            Size::new(self.width() as u32, self.height() as u32),
        )
    }
}

impl DrawTarget for Framebuffer<'_> {
    type Color = PaletteIndex;
    type Error = core::convert::Infallible;

    /// Pixels outside the buffer are skipped, as embedded-graphics expects of targets.
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(Point { x, y }, PaletteIndex(i)) in pixels {
            self.set_pixel(x, y, i);
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        let area = area.intersection(&self.bounding_box());
        let Some(br) = area.bottom_right() else {
            return Ok(());
        };
        let (x0, x1) = (area.top_left.x as usize, br.x as usize + 1);
        for y in area.top_left.y..=br.y {
            if let Some(row) = self.row_mut(y) {
                row[x0..x1].fill(color.0);
            }
        }
        Ok(())
    }
}
