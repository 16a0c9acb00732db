//! Double-buffered bands: band `n + 1` is drawn while band `n` is sent to the display, through
//! a [`BandSink`] that starts a transfer and later waits for it (a DMA-driven SPI display), or
//! sends at once ([`DisplaySink`], any embedded-graphics `DrawTarget`).
//!
//! Role: the output end of [`render_in_bands`], whose band loop draws every band
//! (one mechanism: this module adds no band loop of its own, only what `band_done` does with
//! each finished band). For each band, after `render_in_bands` has drawn it into the caller's
//! index band:
//!
//! 1. the caller's overlay draws into it (text, a frame counter: a [`Framebuffer`] is a
//!    `DrawTarget`);
//! 2. each line is converted through the [`Lut`] (the course's "table de couleurs") into a
//!    free *send buffer*: caller memory holding the band in the display's pixel format `C`
//!    (`Rgb565`, or raw `u16` words in the byte order the bus sends);
//! 3. the transfer of the previous band is waited for, which gives its send buffer back;
//! 4. the transfer of this band starts, and the next band is drawn while it runs.
//!
//! There are two send buffers: the one being sent belongs to the sink (the [`BandSink`] takes
//! it by `&mut` and gives it back from [`BandSink::wait`]), so no code here can write a band
//! while the sink sends it: the borrow checker forbids it. The index band and depth band are
//! the renderer's only (they are never sent).
//!
//! Memory: `width·band_rows·(1 + size_of::<D>())` bytes for the band being drawn (as for
//! [`render_in_bands`]) plus `2·width·band_rows·size_of::<C>()` for the send buffers; a
//! 320-pixel-wide display in bands of 16 rows with 16-bit depth and `Rgb565` takes
//! `15,360 + 20,480` bytes besides the vertex scratch.
//!
//! The pixels sent are exactly `lut(render_in_bands' pixels)` (tested on the standard scenes),
//! in band order, one transfer at a time; the last band's transfer is waited for before
//! [`DoubleBands::render`] returns.

use super::{render_in_bands, BandScratch, RenderError, SceneRenderer, StatsSink};
use crate::output::{DepthValue, Framebuffer, Lut};
use embedded_graphics_core::{
    draw_target::DrawTarget,
    geometry::{Point, Size},
    primitives::Rectangle,
};

/// Where finished bands go: a transfer is started with a band's pixels, then waited for.
///
/// The sink owns `pixels` from [`start`](Self::start) until [`wait`](Self::wait) returns it:
/// a DMA engine may read it all that time. [`DoubleBands`] starts one transfer at a time and
/// always waits for it before the next `start`; after `start` has returned (`Ok` or `Err`) the
/// next `wait` must return that same buffer (an implementation that has none to return may
/// return an empty slice, which the next band then refuses as too small).
///
/// A blocking display is a sink whose `start` sends everything ([`DisplaySink`]); a DMA
/// driver's `start` sets the display's address window and starts the channel, and its `wait`
/// spins (or sleeps with `WFI`) until the channel is done: no executor, no allocator.
pub trait BandSink<'buf, C> {
    /// The sink's error (a bus error, a display's).
    type Error;

    /// Starts sending `pixels[..area.size.width × area.size.height]`, row by row, to `area`
    /// of the display (absolute picture coordinates: `x` from 0, `y` from the band's top).
    fn start(&mut self, pixels: &'buf mut [C], area: Rectangle) -> Result<(), Self::Error>;

    /// Waits until the transfer started last has finished; returns its buffer, and the
    /// transfer's result.
    fn wait(&mut self) -> (&'buf mut [C], Result<(), Self::Error>);
}

/// A sink borrowed: [`DoubleBands`] may hold `&mut sink` and leave the sink with its owner.
impl<'buf, C, K: BandSink<'buf, C> + ?Sized> BandSink<'buf, C> for &mut K {
    type Error = K::Error;

    fn start(&mut self, pixels: &'buf mut [C], area: Rectangle) -> Result<(), K::Error> {
        (**self).start(pixels, area)
    }

    fn wait(&mut self) -> (&'buf mut [C], Result<(), K::Error>) {
        (**self).wait()
    }
}

/// The blocking form of a [`BandSink`]: any embedded-graphics `DrawTarget` (mipidsi, the
/// simulator), sent during `start` with one `fill_contiguous` call per band (one address
/// window, then the pixel stream).
#[derive(Debug)]
pub struct DisplaySink<'buf, 'd, D: DrawTarget> {
    display: &'d mut D,
    held: Option<&'buf mut [D::Color]>,
}

impl<'d, D: DrawTarget> DisplaySink<'_, 'd, D> {
    /// A sink sending to `display`.
    pub fn new(display: &'d mut D) -> Self {
        DisplaySink {
            display,
            held: None,
        }
    }
}

impl<'buf, D: DrawTarget> BandSink<'buf, D::Color> for DisplaySink<'buf, '_, D> {
    type Error = D::Error;

    fn start(&mut self, pixels: &'buf mut [D::Color], area: Rectangle) -> Result<(), D::Error> {
        let n = area.size.width as usize * area.size.height as usize;
        let sent = pixels.get(..n).unwrap_or(&[]).iter().copied();
        let result = self.display.fill_contiguous(&area, sent);
        self.held = Some(pixels);
        result
    }

    fn wait(&mut self) -> (&'buf mut [D::Color], Result<(), D::Error>) {
        (self.held.take().unwrap_or_default(), Ok(()))
    }
}

/// What stopped a [`DoubleBands`] frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DoubleBandError<E> {
    /// Drawing failed (or `band_rows` is 0: [`RenderError::BadBandRows`]).
    Render(RenderError),
    /// The sink's `start` or `wait` failed; both send buffers are back in the
    /// [`DoubleBands`] and the next frame may be drawn.
    Sink(E),
    /// Send buffer `buffer` (0 or 1) holds `given` pixels; a band of this frame needs
    /// `needed` (`width × band_rows`). Checked before anything is drawn.
    SendBufferTooSmall {
        /// Which buffer: 0 or 1, in the order given to [`DoubleBands::new`].
        buffer: usize,
        /// Its length, in pixels.
        given: usize,
        /// A band's pixels.
        needed: usize,
    },
}

impl<E> From<RenderError> for DoubleBandError<E> {
    fn from(e: RenderError) -> Self {
        DoubleBandError::Render(e)
    }
}

impl<E: core::fmt::Display> core::fmt::Display for DoubleBandError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            DoubleBandError::Render(e) => write!(f, "{e}"),
            DoubleBandError::Sink(e) => write!(f, "the band sink failed: {e}"),
            DoubleBandError::SendBufferTooSmall {
                buffer,
                given,
                needed,
            } => write!(
                f,
                "send buffer {buffer} holds {given} pixels; a band needs {needed} (width × band rows)"
            ),
        }
    }
}

impl<E: core::fmt::Debug + core::fmt::Display> core::error::Error for DoubleBandError<E> {}

/// Double-buffered banded frames: the [`Lut`], the two send buffers and the sink, kept from
/// frame to frame (the send buffers are back here between frames). See the module doc.
///
/// ```
/// use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565};
/// use embedded_graphics_core::primitives::Rectangle;
/// use zscan::prelude::*;
/// use zscan::render::{BandSink, DoubleBands};
///
/// /// A DMA-driven SPI display: `start` programs the transfer and returns at once, `wait`
/// /// spins until the channel is done. (Here the "channel" copies at `wait`, as late as a
/// /// real one may read.)
/// struct DmaSpi<'buf> {
///     in_flight: Option<(&'buf mut [u16], Rectangle)>,
///     screen: [u16; 64 * 48],
/// }
///
/// impl<'buf> BandSink<'buf, u16> for DmaSpi<'buf> {
///     type Error = core::convert::Infallible;
///
///     fn start(&mut self, pixels: &'buf mut [u16], area: Rectangle) -> Result<(), Self::Error> {
///         // On a device: send the address-window commands for `area`, then start the DMA
///         // channel from `pixels` to the SPI data register.
///         self.in_flight = Some((pixels, area));
///         Ok(())
///     }
///
///     fn wait(&mut self) -> (&'buf mut [u16], Result<(), Self::Error>) {
///         // On a device: `while !channel.is_done() {}` (or WFI until its interrupt).
///         let Some((pixels, area)) = self.in_flight.take() else {
///             return (&mut [], Ok(()));
///         };
///         let (x, y, w) = (area.top_left.x as usize, area.top_left.y as usize, 64);
///         let n = area.size.width as usize * area.size.height as usize;
///         for (i, &p) in pixels[..n].iter().enumerate() {
///             self.screen[(y + i / w) * w + x + i % w] = p;
///         }
///         (pixels, Ok(()))
///     }
/// }
///
/// // The scene: a cube, 64 × 48.
/// let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
/// let camera = Camera::look_at(
///     Vec3::from_int(2, 2, 3),
///     Vec3::ZERO,
///     Vec3::from_int(0, 1, 0),
///     lens,
///     Viewport::new(64, 48),
/// )?;
/// let objects = [Object::new(unit_cube())];
/// let scene = Scene { camera, objects: &objects, background: 0, ambient: 0, lights: &[] };
/// let renderer = Renderer::for_scene(&scene)?;
///
/// // Rgb565 words in the bus's byte order (big-endian on most SPI displays).
/// let grey = Lut::<Rgb565>::grey_ramp();
/// let lut = Lut::from_entries(core::array::from_fn(|i| grey.get(i as u8).into_storage().to_be()));
///
/// // One band of 8 rows being drawn, two being sent.
/// let (mut band, mut depths) = ([0u8; 64 * 8], [0u16; 64 * 8]);
/// let (mut send_a, mut send_b) = ([0u16; 64 * 8], [0u16; 64 * 8]);
/// let mut dma = DmaSpi { in_flight: None, screen: [0; 64 * 48] };
/// let mut stats = RenderStats::default();
/// {
///     let mut bands = DoubleBands::new(&lut, [&mut send_a, &mut send_b], &mut dma);
///     let scratch = BandScratch { vertices: &mut [PreparedVertex::default(); 8], polygons: &mut [] };
///     bands.render(&renderer, (&mut band, &mut depths), (64, 48, 8), scratch, &mut stats, |_frame| {
///         // Draw an overlay into the band here (a `Framebuffer` is a `DrawTarget`).
///     })?;
/// }
/// assert!(stats.pixels_covered > 0);
/// assert!(dma.screen.iter().any(|&p| p != lut.get(0)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct DoubleBands<'buf, 'l, C, K> {
    lut: &'l Lut<C>,
    buffers: [&'buf mut [C]; 2],
    sink: K,
}

impl<'buf, 'l, C: Copy, K: BandSink<'buf, C>> DoubleBands<'buf, 'l, C, K> {
    /// Frames converted through `lut` into `buffers` (each at least `width × band_rows`
    /// pixels) and sent by `sink`.
    pub fn new(lut: &'l Lut<C>, buffers: [&'buf mut [C]; 2], sink: K) -> Self {
        DoubleBands { lut, buffers, sink }
    }

    /// The sink (e.g. to reach the display between frames).
    pub fn sink_mut(&mut self) -> &mut K {
        &mut self.sink
    }

    /// The send buffers and the sink back.
    pub fn into_parts(self) -> ([&'buf mut [C]; 2], K) {
        (self.buffers, self.sink)
    }

    /// Draws a `width × height` picture of the renderer's scene band by band with
    /// [`render_in_bands`] (same arguments, same pixels and statistics), calls `overlay` on
    /// each finished band, then converts it through the LUT into a free send buffer and
    /// starts its transfer, waiting first for the previous band's. Returns when the last
    /// band's transfer is done.
    ///
    /// Errors: a send buffer shorter than a band ([`DoubleBandError::SendBufferTooSmall`],
    /// before anything is drawn or sent), a drawing error, or the sink's (the frame stops
    /// there; a transfer already started is waited for, so both buffers are back).
    pub fn render<D: DepthValue, const S: u32>(
        &mut self,
        scene_renderer: &SceneRenderer<'_, S>,
        (pixels, depths): (&mut [u8], &mut [D]),
        (width, height, band_rows): (u16, u16, u16),
        scratch: BandScratch<'_, S>,
        stats: &mut impl StatsSink,
        mut overlay: impl FnMut(&mut Framebuffer<'_>),
    ) -> Result<(), DoubleBandError<K::Error>> {
        let rows = super::band_height(scene_renderer.renderer(), (width, height, band_rows))?;
        let needed = width as usize * rows as usize;
        for (buffer, b) in self.buffers.iter().enumerate() {
            if b.len() < needed {
                return Err(DoubleBandError::SendBufferTooSmall {
                    buffer,
                    given: b.len(),
                    needed,
                });
            }
        }
        let (lut, sink) = (self.lut, &mut self.sink);
        // The buffer being sent is the sink's; its slot here holds an empty slice meanwhile.
        let mut free = core::mem::take(&mut self.buffers);
        let mut sending = false;
        let drawn = render_in_bands(
            scene_renderer,
            (pixels, depths),
            (width, height, band_rows),
            scratch,
            stats,
            |frame, _| {
                overlay(frame);
                let n = frame.width() as usize * frame.height() as usize;
                // A free buffer holding the band (the other one may be away): both were
                // checked above, so only a sink returning another buffer than it was given
                // can make this fail.
                let Some(slot) = free.iter().position(|b| b.len() >= n && !b.is_empty()) else {
                    let given = free.iter().map(|b| b.len()).max().unwrap_or(0);
                    let (buffer, needed) = (0, n);
                    return Err(DoubleBandError::SendBufferTooSmall {
                        buffer,
                        given,
                        needed,
                    });
                };
                let buffer = convert(frame, lut, core::mem::take(&mut free[slot]));
                if sending {
                    sending = false;
                    let (back, result) = sink.wait();
                    put_back(&mut free, back);
                    if let Err(e) = result {
                        put_back(&mut free, buffer);
                        return Err(DoubleBandError::Sink(e));
                    }
                }
                let area = Rectangle::new(
                    Point::new(0, frame.top()),
                    Size::new(frame.width() as u32, frame.height() as u32),
                );
                sending = true;
                sink.start(buffer, area).map_err(DoubleBandError::Sink)
            },
        );
        // The last transfer (or the one a failed `start` left with the sink).
        let waited = if sending {
            let (back, result) = sink.wait();
            put_back(&mut free, back);
            result.map_err(DoubleBandError::Sink)
        } else {
            Ok(())
        };
        self.buffers = free;
        drawn.and(waited)
    }
}

/// Converts `frame` through `lut`, line by line, into the front of `buffer` (which
/// [`DoubleBands::render`] has checked holds the band); returns the buffer.
fn convert<'buf, C: Copy>(
    frame: &Framebuffer<'_>,
    lut: &Lut<C>,
    buffer: &'buf mut [C],
) -> &'buf mut [C] {
    let width = frame.width() as usize;
    for ((_, line), out) in frame.rows().zip(buffer.chunks_exact_mut(width.max(1))) {
        for (o, &index) in out.iter_mut().zip(line) {
            *o = lut.get(index);
        }
    }
    buffer
}

/// Puts a buffer (given back by the sink, or not sent) into an empty slot.
fn put_back<'buf, C>(free: &mut [&'buf mut [C]; 2], back: &'buf mut [C]) {
    if let Some(slot) = free.iter_mut().find(|s| s.is_empty()) {
        *slot = back;
    }
}
