//! The core's buffers: from a seed, a framebuffer of random size, stride and band top inside a
//! guarded allocation, and up to 12 operations (clipped and unclipped lines, circles, polygon
//! fill, `flush`, clears). A run fails when a write lands outside the buffer (the guard bytes
//! or the padding between rows change), a span leaves its window, or `flush` streams another
//! area than it announces.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use zscan::output::{flush, Framebuffer, Lut};
use zscan::raster::line::{Bresenham, Ends};
use zscan::raster::polygon::fill_polygon;
use zscan::raster::{circle, line, SubpixelPoint};

use super::{hash, Rng};

/// A display that records what `flush` sends and checks that the area matches the colours.
struct Recorder {
    size: Size,
    sent: Vec<(Rectangle, usize)>,
    mismatch: bool,
}

impl OriginDimensions for Recorder {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Recorder {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        p: I,
    ) -> Result<(), Self::Error> {
        self.sent.push((Rectangle::zero(), p.into_iter().count()));
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        let n = colors.into_iter().count();
        if area.size.width as u64 * area.size.height as u64 != n as u64 {
            self.mismatch = true;
        }
        self.sent.push((*area, n));
        Ok(())
    }
}

const GUARD: usize = 64;
const GUARD_BYTE: u8 = 0xA5;
const PAD_BYTE: u8 = 0x5A;

/// A coordinate: mostly near the buffer, sometimes far or extreme.
fn coord(rng: &mut Rng, extent: i64) -> i32 {
    match rng.range(0, 9) {
        0 => [i32::MIN, i32::MAX, -(1 << 30), 1 << 30, (1 << 30) + 1, 0][rng.range(0, 5) as usize],
        1 => rng.range(-(1 << 20), 1 << 20) as i32,
        _ => rng.range(-8, extent + 8) as i32,
    }
}

/// Random core operations on a guarded buffer; returns the buffer's fingerprint.
pub(super) fn run_core(seed: u64) -> Result<Vec<u64>, String> {
    let mut rng = Rng::new(seed);
    let w = rng.range(1, 48) as u16;
    let h = rng.range(1, 32) as u16;
    let stride = w as usize + rng.range(0, 3) as usize * rng.range(0, 5) as usize;
    let top = if rng.range(0, 2) == 0 {
        rng.range(0, 200) as u16
    } else {
        0
    };
    let len = (h as usize - 1) * stride + w as usize;
    let mut store = vec![GUARD_BYTE; GUARD + len + GUARD];
    {
        let inner = &mut store[GUARD..GUARD + len];
        for (k, b) in inner.iter_mut().enumerate() {
            *b = if k % stride < w as usize { 0 } else { PAD_BYTE };
        }
    }
    let mut log = Vec::new();
    {
        let pixels = &mut store[GUARD..GUARD + len];
        let mut fb = if top > 0 && stride == w as usize {
            Framebuffer::band(pixels, w, h, top).map_err(|e| e.to_string())?
        } else {
            Framebuffer::with_stride(pixels, w, h, stride).map_err(|e| e.to_string())?
        };
        let (ext_x, ext_y) = (w as i64, h as i64 + top as i64);
        for _ in 0..rng.range(1, 12) {
            let index = rng.range(1, 255) as u8;
            match rng.range(0, 5) {
                0 => {
                    let p0 = Point::new(coord(&mut rng, ext_x), coord(&mut rng, ext_y));
                    let p1 = Point::new(coord(&mut rng, ext_x), coord(&mut rng, ext_y));
                    let r = line::draw_line(&mut fb, p0, p1, index);
                    log.push(r.is_ok() as u64);
                }
                1 => {
                    // Unclipped lines straight into the buffer (short ones: ±64 px).
                    let p0 = Point::new(
                        rng.range(-64, 64) as i32,
                        rng.range(-64, 64) as i32 + top as i32,
                    );
                    let p1 = Point::new(
                        rng.range(-64, 64) as i32,
                        rng.range(-64, 64) as i32 + top as i32,
                    );
                    let ends = if rng.range(0, 1) == 0 {
                        Ends::Closed
                    } else {
                        Ends::HalfOpen
                    };
                    Bresenham::with_ends(p0, p1, ends).draw(&mut fb, index);
                }
                2 => {
                    let c = Point::new(coord(&mut rng, ext_x), coord(&mut rng, ext_y));
                    let r = match rng.range(0, 3) {
                        0 => rng.next_u64() as u32,
                        _ => rng.range(0, 80) as u32,
                    };
                    let res = circle::draw_circle(&mut fb, c, r, index);
                    log.push(res.is_ok() as u64);
                }
                3 => {
                    let n = rng.range(0, 12) as usize;
                    let pts: Vec<SubpixelPoint<4>> = (0..n)
                        .map(|_| {
                            let x = coord(&mut rng, ext_x * 16);
                            let y = coord(&mut rng, ext_y * 16);
                            // Keep most polygons small enough to fill fast.
                            if rng.range(0, 3) == 0 {
                                SubpixelPoint::new(x, y)
                            } else {
                                SubpixelPoint::new(x.clamp(-4096, 4096), y.clamp(-4096, 4096))
                            }
                        })
                        .collect();
                    let window = fb.window();
                    let mut spans = Vec::new();
                    let r = fill_polygon::<4, 16>(&pts, &window, |s| spans.push(s));
                    log.push(r.is_ok() as u64);
                    for s in spans {
                        if let Some(row) = fb.span_mut(s.y, s.x0 as usize, s.x1 as usize) {
                            row.fill(index);
                        } else {
                            return Err(format!("fill emitted a span outside its window: {s:?}"));
                        }
                    }
                }
                4 => {
                    let mut display = Recorder {
                        size: Size::new(w as u32, (h + top) as u32),
                        sent: Vec::new(),
                        mismatch: false,
                    };
                    let dirty = (rng.range(0, 4) != 0).then(|| {
                        let size = |rng: &mut Rng| match rng.range(0, 2) {
                            0 => rng.next_u64() as u32,
                            _ => rng.range(0, 60) as u32,
                        };
                        let p = Point::new(coord(&mut rng, ext_x), coord(&mut rng, ext_y));
                        Rectangle::new(p, Size::new(size(&mut rng), size(&mut rng)))
                    });
                    let lut = Lut::grey_ramp();
                    let _ = flush(&fb, &lut, &mut display, dirty);
                    if display.mismatch {
                        return Err(format!("flush of {dirty:?}: area and colours differ"));
                    }
                    for (area, n) in &display.sent {
                        log.extend([area.top_left.x as u64, area.size.width as u64, *n as u64]);
                    }
                }
                _ => fb.clear(index),
            }
        }
    }
    if store[..GUARD]
        .iter()
        .chain(&store[GUARD + len..])
        .any(|&b| b != GUARD_BYTE)
    {
        return Err("a write landed outside the buffer (guard bytes changed)".into());
    }
    for (k, &b) in store[GUARD..GUARD + len].iter().enumerate() {
        if k % stride >= w as usize && b != PAD_BYTE {
            return Err(format!("a write landed in the row padding at offset {k}"));
        }
    }
    log.push(hash(store.iter().map(|&b| b as u64)));
    Ok(log)
}
