//! Double-buffered bands (`DoubleBands`): the pixels sent are the LUT of `render_in_bands`'
//! pixels on the standard scenes at several band heights, both depth widths; a recording sink
//! shows the order (one transfer at a time, band `n + 1` drawn while band `n` is sent, the
//! two buffers alternating) and that a buffer is never written while it is being sent; the
//! blocking `DisplaySink` draws the same picture; too small send buffers, a zero band height
//! and sink errors are reported, and the buffers come back after an error.

use std::cell::RefCell;
use std::sync::OnceLock;

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::prelude::{DrawTarget, OriginDimensions, Pixel, PointsIter, Size};
use embedded_graphics::primitives::Rectangle;
use zscan::output::{DepthValue, Lut};
use zscan::raster::triangle::ShadeMode;
use zscan::render::{
    BandScratch, BandSink, DisplaySink, DoubleBandError, DoubleBands, PolygonRows, PreparedVertex,
    RenderError, RenderStats, SceneRenderer,
};
use zscan_host::core_render::{render_picture, scene_of, to_core, CoreMesh, S};
use zscan_host::scenes::standard_scenes;

fn standard() -> &'static [(String, CoreMesh)] {
    static M: OnceLock<Vec<(String, CoreMesh)>> = OnceLock::new();
    M.get_or_init(|| {
        let scenes = standard_scenes().expect("standard scenes build");
        let core = |s: &zscan_host::scenes::Scene| to_core(s).expect("standard scene converts");
        scenes.iter().map(|s| (s.name.clone(), core(s))).collect()
    })
}

/// What the recording sink and the overlay saw, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Event {
    /// A band was drawn (the overlay runs once drawing is done): its top row.
    Drawn(i32),
    /// A transfer started: the band's top row and which buffer (by address).
    Start(i32, usize),
    /// A transfer was waited for.
    Wait(i32, usize),
}

/// A DMA-like sink: it keeps the buffer from `start` to `wait`, copies the band to its
/// screen only at `wait` (as late as a DMA engine may read), and checks there that the
/// buffer still holds what it held at `start`. Optionally fails one `start` or `wait`.
struct Recorder<'log, C> {
    log: &'log RefCell<Vec<Event>>,
    width: usize,
    screen: Vec<C>,
    in_flight: Option<(&'log mut [C], Rectangle, Vec<C>)>,
    changed_while_sent: usize,
    fail_start: Option<i32>,
    fail_wait: Option<i32>,
}

impl<'log, C: Copy + PartialEq> Recorder<'log, C> {
    fn new(log: &'log RefCell<Vec<Event>>, (w, h): (u16, u16), fill: C) -> Self {
        Recorder {
            log,
            width: w as usize,
            screen: vec![fill; w as usize * h as usize],
            in_flight: None,
            changed_while_sent: 0,
            fail_start: None,
            fail_wait: None,
        }
    }
}

fn address<C>(b: &[C]) -> usize {
    b.as_ptr() as usize
}

impl<'log, C: Copy + PartialEq> BandSink<'log, C> for Recorder<'log, C> {
    type Error = String;

    fn start(&mut self, pixels: &'log mut [C], area: Rectangle) -> Result<(), String> {
        assert!(
            self.in_flight.is_none(),
            "start while a transfer is in flight"
        );
        let top = area.top_left.y;
        self.log
            .borrow_mut()
            .push(Event::Start(top, address(pixels)));
        let n = area.size.width as usize * area.size.height as usize;
        let snapshot = pixels[..n].to_vec();
        self.in_flight = Some((pixels, area, snapshot));
        if self.fail_start == Some(top) {
            return Err(format!("start of band {top} failed"));
        }
        Ok(())
    }

    fn wait(&mut self) -> (&'log mut [C], Result<(), String>) {
        let (pixels, area, snapshot) = self.in_flight.take().expect("wait after a start");
        let top = area.top_left.y;
        self.log
            .borrow_mut()
            .push(Event::Wait(top, address(pixels)));
        let n = snapshot.len();
        if pixels[..n] != snapshot[..] {
            self.changed_while_sent += 1;
        }
        let at = top as usize * self.width;
        self.screen[at..at + n].copy_from_slice(&pixels[..n]);
        let result = if self.fail_wait == Some(top) {
            Err(format!("transfer of band {top} failed"))
        } else {
            Ok(())
        };
        (pixels, result)
    }
}

/// `render_in_bands`' picture of `mesh` (indices), as the comparison.
fn reference<D: DepthValue>(mesh: &CoreMesh, shade: ShadeMode, rows: u16) -> Vec<u8> {
    let objects = [mesh.object(shade).unwrap()];
    let scene = scene_of(&objects, mesh.camera);
    let renderer = SceneRenderer::<S>::new(&scene).unwrap();
    let mut vertices = vec![PreparedVertex::default(); mesh.vertices.len()];
    let mut polygons = vec![PolygonRows::default(); objects[0].mesh.polygon_count()];
    let scratch = BandScratch {
        vertices: &mut vertices,
        polygons: &mut polygons,
    };
    render_picture::<D, S>(&renderer, viewport(mesh), Some(rows), scratch)
        .unwrap()
        .0
}

fn viewport(mesh: &CoreMesh) -> (u16, u16) {
    let vp = *mesh.camera.viewport();
    (vp.width, vp.height)
}

/// Draws `mesh` through `DoubleBands` into a recording sink; returns the sink's screen, the
/// event log, the number of buffers changed while being sent, the statistics and the result.
#[allow(clippy::type_complexity)]
fn double<D: DepthValue, C: Copy + PartialEq + Default>(
    mesh: &CoreMesh,
    shade: ShadeMode,
    rows: u16,
    lut: &Lut<C>,
    fail: (Option<i32>, Option<i32>),
) -> (
    Vec<C>,
    Vec<Event>,
    usize,
    RenderStats,
    Result<(), DoubleBandError<String>>,
) {
    let (w, h) = viewport(mesh);
    let objects = [mesh.object(shade).unwrap()];
    let scene = scene_of(&objects, mesh.camera);
    let renderer = SceneRenderer::<S>::new(&scene).unwrap();
    let mut vertices = vec![PreparedVertex::default(); mesh.vertices.len()];
    let mut polygons = vec![PolygonRows::default(); objects[0].mesh.polygon_count()];
    let band = w as usize * rows.min(h) as usize;
    let (mut pixels, mut depths) = (vec![0u8; band], vec![D::FAR; band]);
    let log = RefCell::new(Vec::new());
    let (mut a, mut b) = (vec![C::default(); band], vec![C::default(); band]);
    let mut sink = Recorder::new(&log, (w, h), lut.get(0));
    (sink.fail_start, sink.fail_wait) = fail;
    let mut stats = RenderStats::default();
    let result = {
        let mut bands = DoubleBands::new(lut, [&mut a, &mut b], &mut sink);
        bands.render(
            &renderer,
            (&mut pixels, &mut depths),
            (w, h, rows),
            BandScratch {
                vertices: &mut vertices,
                polygons: &mut polygons,
            },
            &mut stats,
            |frame| log.borrow_mut().push(Event::Drawn(frame.top())),
        )
    };
    let changed = sink.changed_while_sent;
    (sink.screen, log.into_inner(), changed, stats, result)
}

/// The identity LUT: what is sent is the indices themselves.
fn identity() -> Lut<u8> {
    Lut::from_entries(core::array::from_fn(|i| i as u8))
}

/// The order of a frame of `bands` bands of `rows` rows: drawn 0, start 0, then for each next
/// band: drawn, wait for the previous, start; finally the last wait. So band `n + 1` is drawn
/// between the start and the wait of band `n`, one transfer at a time, and consecutive
/// transfers use the two buffers in turn.
fn assert_order(events: &[Event], rows: u16, height: u16) {
    let tops: Vec<i32> = (0..height as i32).step_by(rows as usize).collect();
    let mut expected_tops = Vec::new();
    for (k, &top) in tops.iter().enumerate() {
        expected_tops.push(('d', top));
        if k > 0 {
            expected_tops.push(('w', tops[k - 1]));
        }
        expected_tops.push(('s', top));
    }
    expected_tops.push(('w', *tops.last().unwrap()));
    let seen: Vec<(char, i32)> = events
        .iter()
        .map(|e| match *e {
            Event::Drawn(t) => ('d', t),
            Event::Start(t, _) => ('s', t),
            Event::Wait(t, _) => ('w', t),
        })
        .collect();
    assert_eq!(seen, expected_tops, "rows {rows}");
    let starts: Vec<usize> = events
        .iter()
        .filter_map(|e| match *e {
            Event::Start(_, a) => Some(a),
            _ => None,
        })
        .collect();
    for pair in starts.windows(2) {
        assert_ne!(pair[0], pair[1], "consecutive bands share a buffer");
    }
    for pair in starts.windows(3) {
        assert_eq!(pair[0], pair[2], "more than two buffers in use");
    }
    // Each wait returns the buffer its start took.
    for (k, e) in events.iter().enumerate() {
        if let Event::Wait(t, a) = *e {
            assert!(
                events[..k].contains(&Event::Start(t, a)),
                "wait of band {t} returned another buffer"
            );
        }
    }
}

/// Every standard scene, shadings Gouraud and flat, bands of 1 to more than the height, 16-
/// and 32-bit depth: the screen is `render_in_bands`' picture; the order holds; no buffer
/// changed while being sent; the counts equal `render_in_bands`'.
#[test]
fn standard_scenes_send_render_in_bands_pixels() {
    let lut = identity();
    for (name, mesh) in standard() {
        let (_, h) = viewport(mesh);
        for shade in [ShadeMode::GouraudExact, ShadeMode::Flat] {
            for rows in [1u16, 7, 16, 240, 1000] {
                let expected = reference::<u16>(mesh, shade, rows);
                let (screen, events, changed, _, result) =
                    double::<u16, u8>(mesh, shade, rows, &lut, (None, None));
                result.unwrap();
                assert!(
                    screen == expected,
                    "{name} {shade:?} rows {rows}: pixels differ"
                );
                assert_eq!(changed, 0, "{name} rows {rows}");
                assert_order(&events, rows.min(h), h);
            }
            let expected = reference::<u32>(mesh, shade, 16);
            let (screen, _, _, _, result) = double::<u32, u8>(mesh, shade, 16, &lut, (None, None));
            result.unwrap();
            assert!(screen == expected, "{name} {shade:?} u32: pixels differ");
        }
    }
}

/// Through an `Rgb565` ramp the screen is the ramp of `render_in_bands`' indices, and the
/// statistics are `render_in_bands`' (same polygon table, same bands).
#[test]
fn the_lut_converts_each_line() {
    let lut = Lut::<Rgb565>::grey_ramp();
    let (name, mesh) = standard().iter().find(|(n, _)| n == "bunny").unwrap();
    let expected: Vec<Rgb565> = reference::<u16>(mesh, ShadeMode::GouraudExact, 11)
        .iter()
        .map(|&i| lut.get(i))
        .collect();
    let (screen, _, _, stats, result) =
        double::<u16, Rgb565>(mesh, ShadeMode::GouraudExact, 11, &lut, (None, None));
    result.unwrap();
    assert!(screen == expected, "{name}: converted pixels differ");
    assert!(
        screen.iter().any(|&c| c != Rgb565::BLACK),
        "{name}: nothing drawn"
    );
    let (_, _, _, again, _) =
        double::<u16, Rgb565>(mesh, ShadeMode::GouraudExact, 11, &lut, (None, None));
    assert_eq!(stats, again);
    assert!(stats.pixels_covered > 0);
}

/// A minimal `DrawTarget` keeping every pixel.
struct Screen {
    size: Size,
    pixels: Vec<Rgb565>,
    fills: usize,
}

impl OriginDimensions for Screen {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Screen {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            let (x, y) = (p.x as usize, p.y as usize);
            self.pixels[y * self.size.width as usize + x] = c;
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.fills += 1;
        let points = area.points();
        self.draw_iter(points.zip(colors).map(|(p, c)| Pixel(p, c)))
    }
}

/// The blocking sink: one `fill_contiguous` per band, the same picture.
#[test]
fn display_sink_draws_the_same_picture() {
    let lut = Lut::<Rgb565>::grey_ramp();
    let (_, mesh) = standard().iter().find(|(n, _)| n == "sphere").unwrap();
    let (w, h) = viewport(mesh);
    let rows = 13;
    let expected: Vec<Rgb565> = reference::<u16>(mesh, ShadeMode::GouraudExact, rows)
        .iter()
        .map(|&i| lut.get(i))
        .collect();
    let mut screen = Screen {
        size: Size::new(w as u32, h as u32),
        pixels: vec![Rgb565::RED; w as usize * h as usize],
        fills: 0,
    };
    let objects = [mesh.object(ShadeMode::GouraudExact).unwrap()];
    let scene = scene_of(&objects, mesh.camera);
    let renderer = SceneRenderer::<S>::new(&scene).unwrap();
    let mut vertices = vec![PreparedVertex::default(); mesh.vertices.len()];
    let band = w as usize * rows as usize;
    let (mut pixels, mut depths) = (vec![0u8; band], vec![0u16; band]);
    let (mut a, mut b) = (vec![Rgb565::RED; band], vec![Rgb565::RED; band]);
    let mut bands = DoubleBands::new(&lut, [&mut a, &mut b], DisplaySink::new(&mut screen));
    bands
        .render(
            &renderer,
            (&mut pixels, &mut depths),
            (w, h, rows),
            BandScratch {
                vertices: &mut vertices,
                polygons: &mut [],
            },
            &mut RenderStats::default(),
            |_| {},
        )
        .unwrap();
    let _ = bands.into_parts();
    assert!(screen.pixels == expected);
    assert_eq!(screen.fills, (h as usize).div_ceil(rows as usize));
}

/// A send buffer shorter than a band is refused before anything is drawn or sent, naming the
/// buffer and both sizes; a zero band height is `render_in_bands`' error.
#[test]
fn short_buffers_and_zero_rows_are_refused() {
    let (_, mesh) = standard().iter().find(|(n, _)| n == "cube").unwrap();
    let (w, h) = viewport(mesh);
    let objects = [mesh.object(ShadeMode::Flat).unwrap()];
    let scene = scene_of(&objects, mesh.camera);
    let renderer = SceneRenderer::<S>::new(&scene).unwrap();
    let lut = identity();
    let log = RefCell::new(Vec::new());
    let mut vertices = vec![PreparedVertex::default(); mesh.vertices.len()];
    let band = w as usize * 8;
    let (mut pixels, mut depths) = (vec![0u8; band], vec![0u16; band]);
    let (mut a, mut b) = (vec![0u8; band], vec![0u8; band - 1]);
    let mut sink = Recorder::new(&log, (w, h), 0u8);
    let mut bands = DoubleBands::new(&lut, [&mut a, &mut b], &mut sink);
    let mut stats = RenderStats::default();
    let mut render = |rows| {
        let scratch = BandScratch {
            vertices: &mut vertices,
            polygons: &mut [],
        };
        let depths = &mut depths[..];
        bands.render(
            &renderer,
            (&mut pixels, depths),
            (w, h, rows),
            scratch,
            &mut stats,
            |_| {},
        )
    };
    let e = render(8).unwrap_err();
    assert_eq!(
        e,
        DoubleBandError::SendBufferTooSmall {
            buffer: 1,
            given: band - 1,
            needed: band
        }
    );
    assert_eq!(
        e.to_string(),
        format!(
            "send buffer 1 holds {} pixels; a band needs {band} (width × band rows)",
            band - 1
        )
    );
    assert_eq!(
        render(0).unwrap_err(),
        DoubleBandError::Render(RenderError::BadBandRows { band_rows: 0 })
    );
    // Bands of 7 rows fit the shorter buffer.
    render(7).unwrap();
    let _ = bands.into_parts();
    assert!(log.borrow().iter().any(|e| matches!(e, Event::Start(..))));
    assert!(stats.pixels_covered > 0);
}

/// A failed `start` or `wait` stops the frame with the sink's error; the transfer in flight is
/// waited for, both buffers come back, and the next frame draws the full picture.
#[test]
fn sink_errors_stop_the_frame_and_keep_the_buffers() {
    let lut = identity();
    let (_, mesh) = standard().iter().find(|(n, _)| n == "bunny").unwrap();
    let expected = reference::<u16>(mesh, ShadeMode::GouraudExact, 16);
    for fail in [
        (Some(32), None),
        (None, Some(32)),
        (Some(0), None),
        (None, Some(224)),
    ] {
        let (_, events, changed, _, result) =
            double::<u16, u8>(mesh, ShadeMode::GouraudExact, 16, &lut, fail);
        let e = result.unwrap_err();
        assert!(
            matches!(&e, DoubleBandError::Sink(m) if m.contains("band")),
            "{e}"
        );
        assert!(e.to_string().starts_with("the band sink failed: "), "{e}");
        assert_eq!(changed, 0);
        // Every start has its wait: nothing is left with the sink.
        let starts = events
            .iter()
            .filter(|e| matches!(e, Event::Start(..)))
            .count();
        let waits = events
            .iter()
            .filter(|e| matches!(e, Event::Wait(..)))
            .count();
        assert_eq!(starts, waits, "{fail:?}");
        // A failed start of band 32 stops before band 48 is drawn.
        if fail.0 == Some(32) {
            assert!(!events.contains(&Event::Drawn(48)), "{events:?}");
        }
    }
    // The buffers survive an error: the same DoubleBands draws the next frame whole.
    let (w, h) = viewport(mesh);
    let objects = [mesh.object(ShadeMode::GouraudExact).unwrap()];
    let scene = scene_of(&objects, mesh.camera);
    let renderer = SceneRenderer::<S>::new(&scene).unwrap();
    let mut vertices = vec![PreparedVertex::default(); mesh.vertices.len()];
    let band = w as usize * 16;
    let (mut pixels, mut depths) = (vec![0u8; band], vec![0u16; band]);
    let (mut a, mut b) = (vec![0u8; band], vec![0u8; band]);
    let log = RefCell::new(Vec::new());
    let mut sink = Recorder::new(&log, (w, h), 0u8);
    sink.fail_wait = Some(64);
    let mut bands = DoubleBands::new(&lut, [&mut a, &mut b], &mut sink);
    for attempt in 0..2 {
        let result = bands.render(
            &renderer,
            (&mut pixels, &mut depths),
            (w, h, 16),
            BandScratch {
                vertices: &mut vertices,
                polygons: &mut [],
            },
            &mut RenderStats::default(),
            |_| {},
        );
        assert_eq!(result.is_err(), attempt == 0, "{result:?}");
        bands.sink_mut().fail_wait = None;
    }
    let ([a_back, b_back], sink) = bands.into_parts();
    assert_eq!((a_back.len(), b_back.len()), (band, band));
    assert!(sink.screen == expected);
}
