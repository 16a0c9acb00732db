//! The output module: framebuffer layout and errors, bands, flushing to a display through the
//! LUT, the `DrawTarget` implementation of `Framebuffer`, and the palette builders.

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Line, PrimitiveStyle, Rectangle};
use embedded_graphics::text::{Baseline, Text};
use zscan::output::{flush, shaded_index, BufferError, Framebuffer, Lut, LutError, PaletteIndex};

#[test]
fn framebuffer_rejects_bad_layouts_without_panicking() {
    let mut buf = vec![0u8; 100];
    assert_eq!(
        Framebuffer::new(&mut buf, 0, 10).unwrap_err(),
        BufferError::ZeroSize
    );
    assert_eq!(
        Framebuffer::new(&mut buf, 10, 0).unwrap_err(),
        BufferError::ZeroSize
    );
    assert_eq!(
        Framebuffer::new(&mut buf, 11, 10).unwrap_err(),
        BufferError::BufferTooSmall {
            needed: 110,
            len: 100
        }
    );
    assert_eq!(
        Framebuffer::with_stride(&mut buf, 10, 10, 9).unwrap_err(),
        BufferError::StrideTooSmall {
            stride: 9,
            width: 10
        }
    );
    // The last row needs only `width` elements: 9 × 11 + 1 = 100 fits.
    assert!(Framebuffer::with_stride(&mut buf, 1, 10, 11).is_ok());
    assert!(Framebuffer::with_stride(&mut buf, 2, 10, 11).is_err());
    // A stride so large that the size computation would wrap is an error, not a panic.
    assert!(Framebuffer::with_stride(&mut buf, 1, 3, usize::MAX).is_err());
    assert_eq!(
        Framebuffer::band(&mut buf, 50, 3, 7).unwrap_err(),
        BufferError::BufferTooSmall {
            needed: 150,
            len: 100
        }
    );
    // A longer buffer is accepted; the rest is untouched.
    let mut fb = Framebuffer::new(&mut buf, 9, 9).unwrap();
    fb.clear(3);
    assert_eq!(buf.iter().filter(|&&p| p == 3).count(), 81);
    assert_eq!(buf[81..], [0; 19]);
}

#[test]
fn band_rows_are_absolute() {
    let mut buf = vec![0u8; 4 * 3];
    let mut fb = Framebuffer::band(&mut buf, 4, 3, 10).unwrap();
    assert_eq!((fb.top(), fb.height(), fb.width()), (10, 3, 4));
    let w = fb.window();
    assert_eq!((w.x0, w.y0, w.x1, w.y1), (0, 10, 4, 13));
    assert!(fb.row(9).is_none() && fb.row(13).is_none() && fb.row(i32::MIN).is_none());
    fb.set_pixel(2, 11, 5);
    fb.set_pixel(2, 9, 6); // outside: ignored
    fb.set_pixel(-1, 11, 6);
    fb.set_pixel(4, 11, 6);
    fb.set_pixel(i32::MAX, i32::MAX, 6);
    fb.row_mut(12).unwrap().fill(8);
    assert_eq!(fb.pixel(2, 11), Some(5));
    assert_eq!(fb.pixel(2, 9), None);
    let rows: Vec<(i32, Vec<u8>)> = fb.rows().map(|(y, r)| (y, r.to_vec())).collect();
    assert_eq!(
        rows,
        vec![
            (10, vec![0, 0, 0, 0]),
            (11, vec![0, 0, 5, 0]),
            (12, vec![8, 8, 8, 8])
        ]
    );
    assert_eq!(buf, [0, 0, 0, 0, 0, 0, 5, 0, 8, 8, 8, 8]);
}

/// A display that records the calls it receives.
struct Recorder {
    size: Size,
    contiguous: Vec<(Rectangle, Vec<Rgb888>)>,
    single_pixels: usize,
}

impl Recorder {
    fn new(w: u32, h: u32) -> Self {
        Recorder {
            size: Size::new(w, h),
            contiguous: Vec::new(),
            single_pixels: 0,
        }
    }
}

impl OriginDimensions for Recorder {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Recorder {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        self.single_pixels += pixels.into_iter().count();
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        self.contiguous.push((*area, colors.into_iter().collect()));
        Ok(())
    }
}

/// A LUT where index `i` is a colour easy to recognise: `(i, 255 − i, i / 2)`.
fn test_lut() -> Lut<Rgb888> {
    let mut lut = Lut::filled(Rgb888::new(1, 2, 3));
    for i in 0..=255u8 {
        lut.set(i, Rgb888::new(i, 255 - i, i / 2));
    }
    lut
}

fn colour(i: u8) -> Rgb888 {
    Rgb888::new(i, 255 - i, i / 2)
}

#[test]
fn flush_sends_one_block_through_the_lut() {
    let (w, h) = (5u16, 4u16);
    let mut buf: Vec<u8> = (0..20).map(|i| i * 3).collect();
    let fb = Framebuffer::new(&mut buf, w, h).unwrap();
    let lut = test_lut();
    let mut display = Recorder::new(64, 64);
    flush(&fb, &lut, &mut display, None).unwrap();
    assert_eq!(display.single_pixels, 0);
    assert_eq!(display.contiguous.len(), 1);
    let (area, colours) = &display.contiguous[0];
    assert_eq!(*area, Rectangle::new(Point::new(0, 0), Size::new(5, 4)));
    let want: Vec<Rgb888> = (0..20u8).map(|i| colour(i * 3)).collect();
    assert_eq!(colours, &want);

    // A dirty rectangle limits the block (and is clipped to the frame).
    let mut display = Recorder::new(64, 64);
    let dirty = Rectangle::new(Point::new(3, 2), Size::new(10, 10));
    flush(&fb, &lut, &mut display, Some(dirty)).unwrap();
    assert_eq!(display.contiguous.len(), 1);
    let (area, colours) = &display.contiguous[0];
    assert_eq!(*area, Rectangle::new(Point::new(3, 2), Size::new(2, 2)));
    // Pixels (3,2), (4,2), (3,3), (4,3): indices 3·(y·5 + x).
    let want: Vec<Rgb888> = [13u8, 14, 18, 19].iter().map(|&k| colour(k * 3)).collect();
    assert_eq!(colours, &want);

    // A dirty rectangle outside the frame sends nothing.
    let mut display = Recorder::new(64, 64);
    let away = Rectangle::new(Point::new(-10, 1), Size::new(5, 5));
    flush(&fb, &lut, &mut display, Some(away)).unwrap();
    assert!(display.contiguous.is_empty());
    assert_eq!(display.single_pixels, 0);
}

/// Issue "hostile inputs" #3: dirty rectangles far larger than the frame (sizes up to
/// `u32::MAX`, corners anywhere) are intersected with the frame without overflow; the area
/// given to the display always matches the colours streamed.
#[test]
fn flush_intersects_huge_dirty_rectangles_without_overflow() {
    let (w, h) = (4u16, 3u16);
    let mut buf: Vec<u8> = (0..12).collect();
    let fb = Framebuffer::new(&mut buf, w, h).unwrap();
    let lut = test_lut();
    let cases = [
        // (dirty, expected area)
        (
            Rectangle::new(Point::zero(), Size::new(u32::MAX, 1)),
            Some(Rectangle::new(Point::zero(), Size::new(4, 1))),
        ),
        (
            Rectangle::new(
                Point::new(i32::MIN, i32::MIN),
                Size::new(u32::MAX, u32::MAX),
            ),
            Some(Rectangle::new(Point::zero(), Size::new(4, 3))),
        ),
        (
            Rectangle::new(Point::new(-100_000, 1), Size::new(92_000_000, 92_000_000)),
            Some(Rectangle::new(Point::new(0, 1), Size::new(4, 2))),
        ),
        (
            Rectangle::new(
                Point::new(i32::MAX, i32::MAX),
                Size::new(u32::MAX, u32::MAX),
            ),
            None,
        ),
        (
            Rectangle::new(Point::new(i32::MIN, 0), Size::new(u32::MAX / 2, 3)),
            None,
        ),
        (Rectangle::new(Point::new(1, 1), Size::new(0, 5)), None),
        (
            Rectangle::new(Point::new(2, -5), Size::new(1, u32::MAX)),
            Some(Rectangle::new(Point::new(2, 0), Size::new(1, 3))),
        ),
    ];
    for (dirty, want) in cases {
        let mut display = Recorder::new(64, 64);
        flush(&fb, &lut, &mut display, Some(dirty)).unwrap();
        match want {
            None => assert!(display.contiguous.is_empty(), "{dirty:?}"),
            Some(area) => {
                assert_eq!(display.contiguous.len(), 1, "{dirty:?}");
                let (got, colours) = &display.contiguous[0];
                assert_eq!(*got, area, "{dirty:?}");
                let n = (area.size.width * area.size.height) as usize;
                assert_eq!(colours.len(), n, "{dirty:?}");
                let x0 = area.top_left.x as u8;
                let y0 = area.top_left.y as u8;
                assert_eq!(colours[0], colour(y0 * 4 + x0), "{dirty:?}");
            }
        }
    }
}

#[test]
fn flushing_a_band_lands_at_its_absolute_rows() {
    let mut buf = vec![7u8, 8, 9, 10, 11, 12];
    let fb = Framebuffer::band(&mut buf, 3, 2, 20).unwrap();
    let lut = test_lut();
    let mut display = Recorder::new(3, 40);
    flush(&fb, &lut, &mut display, None).unwrap();
    assert_eq!(display.contiguous.len(), 1);
    let (area, colours) = &display.contiguous[0];
    assert_eq!(*area, Rectangle::new(Point::new(0, 20), Size::new(3, 2)));
    assert_eq!(colours, &(7..=12u8).map(colour).collect::<Vec<_>>());
    // Dirty rectangle in absolute coordinates, overlapping the band's second row only.
    let mut display = Recorder::new(3, 40);
    let dirty = Rectangle::new(Point::new(1, 21), Size::new(1, 30));
    flush(&fb, &lut, &mut display, Some(dirty)).unwrap();
    assert_eq!(
        display.contiguous,
        vec![(
            Rectangle::new(Point::new(1, 21), Size::new(1, 1)),
            vec![colour(11)]
        )]
    );
}

#[test]
fn framebuffer_is_an_embedded_graphics_draw_target() {
    let (w, h) = (16u16, 12u16);
    let mut buf = vec![0u8; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut buf, w, h).unwrap();
    assert_eq!(
        fb.bounding_box(),
        Rectangle::new(Point::zero(), Size::new(16, 12))
    );
    // A filled rectangle partly outside (fill_solid path).
    Rectangle::new(Point::new(-3, 8), Size::new(6, 10))
        .into_styled(PrimitiveStyle::with_fill(PaletteIndex(4)))
        .draw(&mut fb)
        .unwrap();
    // A horizontal and a diagonal line (draw_iter path), the diagonal leaving the buffer.
    Line::new(Point::new(5, 1), Point::new(9, 1))
        .into_styled(PrimitiveStyle::with_stroke(PaletteIndex(9), 1))
        .draw(&mut fb)
        .unwrap();
    Line::new(Point::new(10, 5), Point::new(30, 25))
        .into_styled(PrimitiveStyle::with_stroke(PaletteIndex(2), 1))
        .draw(&mut fb)
        .unwrap();
    for y in 0..h as i32 {
        for x in 0..w as i32 {
            let want = if (0..3).contains(&x) && y >= 8 {
                4
            } else if y == 1 && (5..=9).contains(&x) {
                9
            } else if x >= 10 && x - 10 == y - 5 {
                2
            } else {
                0
            };
            assert_eq!(fb.pixel(x, y), Some(want), "({x}, {y})");
        }
    }
}

#[test]
fn text_on_a_band_stays_inside_it() {
    let mut buf = vec![0u8; 40 * 6];
    let mut fb = Framebuffer::band(&mut buf, 40, 6, 3).unwrap(); // rows 3..9
    assert_eq!(
        fb.bounding_box(),
        Rectangle::new(Point::new(0, 3), Size::new(40, 6))
    );
    let style = MonoTextStyle::new(&FONT_6X10, PaletteIndex(200));
    Text::with_baseline("HI", Point::new(0, 0), style, Baseline::Top)
        .draw(&mut fb)
        .unwrap();
    // Glyph rows 3..9 of "HI" (12 px wide) fall in the band: some pixels lit, only index 200,
    // and nothing right of the two glyph cells.
    let lit: Vec<(i32, i32)> = fb
        .rows()
        .flat_map(|(y, r)| {
            r.iter()
                .enumerate()
                .filter(|(_, &v)| v != 0)
                .map(move |(x, _)| (x as i32, y))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(lit.len() > 5);
    assert!(lit.iter().all(|&(x, _)| x < 12));
    assert!(buf.iter().all(|&v| v == 0 || v == 200));
}

#[test]
fn grey_ramp_is_the_identity_grey() {
    let lut: Lut<Rgb888> = Lut::grey_ramp();
    for i in 0..=255u8 {
        assert_eq!(lut.get(i), Rgb888::new(i, i, i));
    }
    let lut565: Lut<Rgb565> = Lut::grey_ramp();
    assert_eq!(lut565.get(0), Rgb565::BLACK);
    assert_eq!(lut565.get(255), Rgb565::WHITE);
    assert_eq!(lut565.get(128), Rgb565::from(Rgb888::new(128, 128, 128)));
}

#[test]
fn shaded_palette_values() {
    let bases = [Rgb888::new(200, 101, 7), Rgb888::new(255, 0, 90)];
    let (levels, first) = (5u8, 10u8);
    let lut: Lut<Rgb888> = Lut::shaded(&bases, levels, first).unwrap();
    // Expected by rounding the exact fraction c·(s+1)/levels to nearest (f64 is exact here).
    let scale = |c: u8, s: u8| ((c as f64) * (s as f64 + 1.0) / levels as f64).round() as u8;
    for i in 0..=255u8 {
        let want = if i < first || i >= first + 2 * levels {
            Rgb888::BLACK
        } else {
            let (m, s) = ((i - first) / levels, (i - first) % levels);
            let b = bases[m as usize];
            Rgb888::new(scale(b.r(), s), scale(b.g(), s), scale(b.b(), s))
        };
        assert_eq!(lut.get(i), want, "index {i}");
    }
    // The brightest shade is the base colour; hand-checked values.
    assert_eq!(lut.get(first + levels - 1), bases[0]);
    assert_eq!(lut.get(first), Rgb888::new(40, 20, 1)); // 200/5, 101/5 = 20.2, 7/5 = 1.4
    assert_eq!(lut.get(first + 1), Rgb888::new(80, 40, 3)); // 40.4 → 40, 2.8 → 3
    assert_eq!(shaded_index(first, levels, 1, 2), first + levels + 2);
    assert_eq!(shaded_index(first, levels, 1, 200), first + 2 * levels - 1); // saturates

    // Even level count: exact halves round up (e.g. 1·1/2 = 0.5 → 1).
    let lut: Lut<Rgb888> = Lut::shaded(&[Rgb888::new(1, 3, 255)], 2, 0).unwrap();
    assert_eq!(lut.get(0), Rgb888::new(1, 2, 128));
    assert_eq!(lut.get(1), Rgb888::new(1, 3, 255));
}

#[test]
fn shaded_palette_errors() {
    assert_eq!(
        Lut::<Rgb888>::shaded(&[Rgb888::WHITE], 0, 0).unwrap_err(),
        LutError::ZeroLevels
    );
    let bases = [Rgb888::WHITE; 4];
    assert_eq!(
        Lut::<Rgb888>::shaded(&bases, 64, 1).unwrap_err(),
        LutError::TooManyEntries { needed: 257 }
    );
    // Exactly 256 entries fit.
    let lut = Lut::<Rgb888>::shaded(&bases, 64, 0).unwrap();
    assert_eq!(lut.get(255), Rgb888::WHITE);
    assert_eq!(
        Lut::<Rgb888>::shaded(&[Rgb888::WHITE; 300], 1, 0).unwrap_err(),
        LutError::TooManyEntries { needed: 300 }
    );
    assert!(!LutError::ZeroLevels.to_string().is_empty());
}

/// A framebuffer or depth buffer that does not hold the camera's viewport is refused by every
/// drawing entry, naming both sizes, and nothing is drawn; a band needs only the viewport's
/// width. (Before, each entry drew the part of the picture the buffer held: a silent crop.)
#[test]
fn buffers_smaller_than_the_viewport_are_refused() {
    use zscan::prelude::*;
    use zscan::render::{render_in_compact_bands, CompactBandScratch, RenderError, TargetBuffer};
    use zscan::render::{CompactVertex, PolygonTop};
    use zscan::visibility::{
        render_back_faces, render_painter, render_scan_lines, render_warnock, Area, Normal,
        PainterMemory, ScanLineMemory, SplitPolicy, StoredTriangle, WarnockMemory,
    };

    let (vw, vh) = (32u16, 24u16);
    let lens = Lens::new(
        BinaryAngle::from_degrees(60),
        Coord::lit("0.5"),
        Coord::lit("20"),
    );
    let eye = Vec3::from_int(2, 1, 3);
    let up = Vec3::from_int(0, 1, 0);
    let camera = Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(vw, vh)).unwrap();
    let objects = [Object::new(unit_cube())];
    let scene = Scene {
        camera,
        objects: &objects,
        background: 7,
        ambient: 255,
        lights: &[],
    };
    let renderer = Renderer::for_scene(&scene).unwrap();
    let too_small = |buffer, size: (u16, u16)| {
        Err(RenderError::TargetSmallerThanViewport {
            buffer,
            size,
            viewport: (vw, vh),
        })
    };
    // The visibility methods report the pipeline's error wrapped in their own.
    let method_too_small =
        |buffer, size: (u16, u16)| too_small(buffer, size).map_err(VisibilityError::Render);
    let mut scratch = [PreparedVertex::default(); 8];
    let mut stats = RenderStats::default();
    let message = too_small(TargetBuffer::Frame, (31, 24))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("31 × 24") && message.contains("32 × 24 viewport"),
        "{message}"
    );

    // Whole buffers: narrower, shorter, or a depth buffer smaller than its frame.
    for (fs, ds, buffer, size) in [
        ((31, 24), (32, 24), TargetBuffer::Frame, (31, 24)),
        ((32, 23), (32, 24), TargetBuffer::Frame, (32, 23)),
        ((32, 24), (32, 20), TargetBuffer::Depth, (32, 20)),
    ] {
        let mut pixels = vec![0u8; 32 * 24];
        let mut depths = vec![0u16; 32 * 24];
        let mut frame = Framebuffer::new(&mut pixels, fs.0, fs.1).unwrap();
        let mut depth = DepthBuffer::new(&mut depths, ds.0, ds.1).unwrap();
        let r = render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats);
        assert_eq!(r, too_small(buffer, size), "frame {fs:?}, depth {ds:?}");
        let r = renderer.renderer().draw_object(
            &objects[0],
            &mut scratch,
            &mut frame,
            &mut depth,
            &mut stats,
        );
        assert_eq!(r, too_small(buffer, size), "draw_object: {fs:?}, {ds:?}");
        assert!(
            pixels.iter().all(|&p| p == 0),
            "nothing drawn, not even cleared"
        );
    }
    // A band may hold any rows, but not fewer columns.
    let (mut pixels, mut depths) = (vec![0u8; 32 * 8], vec![0u16; 32 * 8]);
    let mut band = Framebuffer::band(&mut pixels, 32, 8, 8).unwrap();
    let mut depth = DepthBuffer::band(&mut depths, 32, 8, 8).unwrap();
    render_scene(&renderer, &mut band, &mut depth, &mut scratch, &mut stats).unwrap();
    let mut band = Framebuffer::band(&mut pixels, 31, 8, 8).unwrap();
    let mut depth = DepthBuffer::band(&mut depths, 31, 8, 8).unwrap();
    let r = render_scene(&renderer, &mut band, &mut depth, &mut scratch, &mut stats);
    assert_eq!(r, too_small(TargetBuffer::Frame, (31, 8)));

    // The banded entries: the picture size they are given.
    for size in [(31u16, 24u16), (32, 23)] {
        let (mut pixels, mut depths) = (vec![0u8; 32 * 24], vec![0u16; 32 * 24]);
        let mut polygons = [PolygonRows::NEVER; 6];
        let band_scratch = BandScratch {
            vertices: &mut scratch,
            polygons: &mut polygons,
        };
        let r = render_in_bands(
            &renderer,
            (&mut pixels, &mut depths),
            (size.0, size.1, 8),
            band_scratch,
            &mut stats,
            |_, _| Ok::<(), RenderError>(()),
        );
        assert_eq!(r, too_small(TargetBuffer::Frame, size), "render_in_bands");
        let (mut vertices, mut polygons) =
            ([CompactVertex::default(); 8], [PolygonTop::default(); 6]);
        let compact = CompactBandScratch {
            vertices: &mut vertices,
            levels: &mut [],
            polygons: &mut polygons,
        };
        let r = render_in_compact_bands(
            &renderer,
            (&mut pixels, &mut depths),
            (size.0, size.1, 8),
            compact,
            &mut stats,
            |_, _| Ok::<(), RenderError>(()),
        );
        assert_eq!(r, too_small(TargetBuffer::Frame, size), "compact bands");
        let (mut triangles, mut order) = (vec![StoredTriangle::DEFAULT; 16], vec![0u32; 16]);
        let mut active = vec![0u32; 16];
        let memory = ScanLineMemory {
            triangles: &mut triangles,
            order: &mut order,
            active: &mut active,
            pixels: &mut pixels,
            depths: &mut depths,
        };
        let r = render_scan_lines(
            &renderer,
            (size.0, size.1, 8),
            &mut scratch,
            memory,
            &mut stats,
            |_, _| Ok::<(), VisibilityError>(()),
        );
        assert_eq!(r, method_too_small(TargetBuffer::Frame, size), "scan-line");
    }

    // The methods without a depth buffer.
    let mut pixels = vec![0u8; 32 * 24];
    let mut frame = Framebuffer::new(&mut pixels, 32, 23).unwrap();
    let r = render_back_faces(&renderer, &mut frame, &mut scratch, &mut stats);
    assert_eq!(
        r,
        method_too_small(TargetBuffer::Frame, (32, 23)),
        "back faces"
    );
    let (mut triangles, mut order) = (vec![StoredTriangle::DEFAULT; 16], vec![0u32; 16]);
    let mut normals = vec![Normal::DEFAULT; 16];
    let memory = PainterMemory {
        triangles: &mut triangles,
        order: &mut order,
        normals: &mut normals,
    };
    let policy = SplitPolicy::Budget(4);
    let r = render_painter(
        &renderer,
        &mut frame,
        &mut scratch,
        memory,
        policy,
        &mut stats,
    );
    assert_eq!(
        r,
        method_too_small(TargetBuffer::Frame, (32, 23)),
        "painter"
    );
    let (mut candidates, mut windows) = (vec![0u32; 32], vec![Area::DEFAULT; 16]);
    let memory = WarnockMemory {
        triangles: &mut triangles,
        candidates: &mut candidates,
        windows: &mut windows,
    };
    let r = render_warnock(&renderer, &mut frame, &mut scratch, memory, &mut stats);
    assert_eq!(
        r,
        method_too_small(TargetBuffer::Frame, (32, 23)),
        "Warnock"
    );
    assert!(
        pixels.iter().all(|&p| p == 0),
        "nothing drawn, not even cleared"
    );
}
