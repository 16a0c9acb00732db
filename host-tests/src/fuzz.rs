//! Seeded property campaigns ("fuzzing" on the stable toolchain): random, often hostile,
//! inputs to the scene parser and renderer behind `zscan render`, the OBJ reader, `zscan
//! spans`' parser and fill, and the core's buffers, bands, lines, circles, polygon fill and
//! flush. Every case is checked for: no panic (`catch_unwind`), no write outside the buffers
//! it was given (guard bytes around them and the padding between rows stay untouched), and
//! deterministic output (the case run twice gives the same result).
//!
//! The generator is the workspace's test PRNG ([`XorShift`](crate::test_rng::XorShift)); a
//! case is fully described by its target and its input text ([`Case`]), which is what
//! the campaign prints and what the corpus (`host-tests/fuzz-corpus/*.case`) stores:
//! the first line names the target, the rest is the input. `tests/fuzz.rs` runs a bounded
//! campaign and replays the corpus; `scripts/fuzz.sh COUNT [SEED]` runs a long one.

use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use zscan::output::{flush, Framebuffer, Lut};
use zscan::raster::line::{Bresenham, Ends};
use zscan::raster::polygon::{fill_polygon, FillRule};
use zscan::raster::{circle, line, SubpixelPoint};

use crate::test_rng::XorShift as Rng;

/// What a case exercises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A scene file's text through `load_scene_str` and `LoadedScene::render`.
    Scene,
    /// OBJ text through `parse_obj` and `ObjMesh::to_zscan`.
    Obj,
    /// `zscan spans` input through `write_spans`, under both fill rules.
    Spans,
    /// Core API operations generated from a seed (the input is the seed in decimal).
    Core,
}

impl Target {
    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            Target::Scene => "scene",
            Target::Obj => "obj",
            Target::Spans => "spans",
            Target::Core => "core",
        }
    }

    /// The target of a name.
    pub fn from_name(s: &str) -> Option<Target> {
        [Target::Scene, Target::Obj, Target::Spans, Target::Core]
            .into_iter()
            .find(|t| t.name() == s)
    }
}

/// One input: the target and its text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Case {
    /// What it exercises.
    pub target: Target,
    /// The input.
    pub input: String,
}

impl Case {
    /// The case file text: the target's name, a newline, the input.
    pub fn to_file(&self) -> String {
        format!("{}\n{}", self.target.name(), self.input)
    }

    /// Parses a case file.
    pub fn from_file(text: &str) -> Option<Case> {
        let (name, input) = text.split_once('\n').unwrap_or((text, ""));
        Some(Case {
            target: Target::from_name(name.trim())?,
            input: input.to_string(),
        })
    }
}

/// What running a case gave, compared between two runs for determinism.
type Outcome = Result<Vec<u64>, String>;

/// Runs a case twice and checks it; `Err` describes the violated property.
pub fn check(case: &Case) -> Result<(), String> {
    let run = || catch_unwind(AssertUnwindSafe(|| run_case(case)));
    let first = run().map_err(|p| format!("panic: {}", panic_text(&p)))?;
    let second = run().map_err(|p| format!("panic (second run): {}", panic_text(&p)))?;
    let a = first?;
    let b = second?;
    if a != b {
        return Err("not deterministic: two runs differ".into());
    }
    Ok(())
}

fn panic_text(p: &Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(non-string panic)".into())
}

/// One run: `Ok(fingerprint)` (errors of the input are part of the fingerprint), or `Err`
/// for a violated property (a write outside a buffer).
fn run_case(case: &Case) -> Result<Outcome, String> {
    match case.target {
        Target::Scene => Ok(run_scene(&case.input)),
        Target::Obj => Ok(run_obj(&case.input)),
        Target::Spans => Ok(run_spans(&case.input)),
        Target::Core => {
            let seed = case
                .input
                .trim()
                .parse::<u64>()
                .map_err(|e| e.to_string())?;
            run_core(seed).map(Ok)
        }
    }
}

fn hash(bytes: impl IntoIterator<Item = u64>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in bytes {
        h = (h ^ b).wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn run_scene(text: &str) -> Outcome {
    let scene = crate::cli::render::load_scene_str(text, Path::new("fuzz.toml"))?;
    let bands = (text.len() % 3 == 0).then_some(1 + (text.len() % 7) as u16);
    let (pixels, depth, stats) = if scene.depth_bits == 16 {
        let f = scene.render::<u16>(bands)?;
        (
            f.pixels,
            f.depth.iter().map(|&d| d as u64).collect::<Vec<_>>(),
            f.stats,
        )
    } else {
        let f = scene.render::<u32>(bands)?;
        (
            f.pixels,
            f.depth.iter().map(|&d| d as u64).collect::<Vec<_>>(),
            f.stats,
        )
    };
    Ok(vec![
        hash(pixels.iter().map(|&p| p as u64)),
        hash(depth),
        stats.pixels_covered as u64,
        stats.triangles_drawn as u64,
    ])
}

fn run_obj(text: &str) -> Outcome {
    let m = crate::obj::parse_obj(text).map_err(|e| e.to_string())?;
    let tables = m.to_zscan(|v| v);
    Ok(vec![
        m.vertices.len() as u64,
        m.polygons.len() as u64,
        tables.map_or(0, |(v, i, s)| {
            hash(
                v.iter()
                    .flat_map(|p| p.bits().map(|b| b as u32 as u64))
                    .chain(i.iter().map(|&x| x as u64))
                    .chain(s.iter().map(|&x| x as u64)),
            )
        }),
    ])
}

fn run_spans(text: &str) -> Outcome {
    let (bits, body) = text.split_once('\n').unwrap_or(("4", text));
    let bits: u32 = bits.trim().parse().unwrap_or(4);
    let mut out = Vec::new();
    for rule in [FillRule::NonZero, FillRule::EvenOdd] {
        crate::cli::spans::write_spans(body, bits, rule, &mut out).map_err(|e| e.to_string())?;
    }
    Ok(vec![hash(out.iter().map(|&b| b as u64)), out.len() as u64])
}

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
fn run_core(seed: u64) -> Result<Vec<u64>, String> {
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

/// A random number as TOML text, from a pool of ordinary and hostile values.
fn number(rng: &mut Rng, lo: f64, hi: f64) -> String {
    match rng.range(0, 15) {
        0 => [
            "nan", "inf", "-inf", "1e9", "-1e9", "32768", "-32769", "1e-6", "0", "-0.0",
        ][rng.range(0, 9) as usize]
            .into(),
        1 => format!("{}", rng.range(i64::MIN / 2, i64::MAX / 2)),
        _ => format!("{:.3}", rng.uniform(lo, hi)),
    }
}

fn integer(rng: &mut Rng, lo: i64, hi: i64) -> String {
    match rng.range(0, 12) {
        0 => [
            "-1",
            "256",
            "65535",
            "65536",
            "70000",
            "4097",
            "0",
            "9223372036854775807",
        ][rng.range(0, 7) as usize]
            .into(),
        _ => rng.range(lo, hi).to_string(),
    }
}

fn vec3(rng: &mut Rng, lo: f64, hi: f64) -> String {
    format!(
        "[{}, {}, {}]",
        number(rng, lo, hi),
        number(rng, lo, hi),
        number(rng, lo, hi)
    )
}

/// A random scene file, mostly well-formed, with hostile values.
pub fn random_scene(rng: &mut Rng) -> String {
    let mut s = String::new();
    if rng.range(0, 1) == 0 {
        let _ = writeln!(s, "[camera]");
        if rng.range(0, 1) == 0 {
            let _ = writeln!(s, "eye = {}", vec3(rng, -6.0, 6.0));
        }
        if rng.range(0, 3) == 0 {
            let _ = writeln!(s, "target = {}", vec3(rng, -1.0, 1.0));
        }
        if rng.range(0, 4) == 0 {
            let _ = writeln!(s, "up = {}", vec3(rng, -1.0, 1.0));
        }
        if rng.range(0, 3) == 0 {
            let _ = writeln!(s, "fov_deg = {}", number(rng, 1.0, 179.0));
        }
        if rng.range(0, 3) == 0 {
            let _ = writeln!(s, "near = {}", number(rng, 0.001, 2.0));
        }
        if rng.range(0, 3) == 0 {
            let _ = writeln!(s, "far = {}", number(rng, 2.0, 100.0));
        }
    }
    let _ = writeln!(s, "[viewport]");
    // Mostly small pictures; some up to the tool's 4096-pixel side (strips, so that a case
    // stays fast) and, rarely, the whole 4096 × 4096: every size must render (issue 16 #1).
    let (w, h) = match rng.range(0, 19) {
        0 => (integer(rng, 1, 4096), integer(rng, 1, 24)),
        1 => (integer(rng, 1, 24), integer(rng, 1, 4096)),
        2 if rng.range(0, 3999) == 0 => ("4096".into(), "4096".into()),
        2 => (integer(rng, 256, 1024), integer(rng, 64, 192)),
        _ => (integer(rng, 1, 48), integer(rng, 1, 40)),
    };
    let _ = writeln!(s, "width = {w}\nheight = {h}");
    if rng.range(0, 3) == 0 {
        // Near the picture, at its corners and edges, or anywhere in the I16F16 range.
        let side = |rng: &mut Rng, n: &str| {
            let n = n.parse::<f64>().unwrap_or(48.0).min(4096.0);
            match rng.range(0, 5) {
                0 => ["0", "-0.5", "-32767", "32767"][rng.range(0, 3) as usize].to_string(),
                1 => format!("{}", n - 1.0),
                2 => format!("{:.3}", rng.uniform(-32767.0, 32767.0)),
                _ => number(rng, -10.0, n + 10.0),
            }
        };
        let (px, py) = (side(rng, &w), side(rng, &h));
        let _ = writeln!(s, "principal = [{px}, {py}]");
    }
    if rng.range(0, 6) == 0 {
        let _ = writeln!(
            s,
            "pixel_aspect = [{}, {}]",
            integer(rng, 1, 3),
            integer(rng, 1, 3)
        );
    }
    let _ = writeln!(s, "[render]");
    let _ = writeln!(
        s,
        "depth_bits = {}",
        ["16", "32", "16", "24"][rng.range(0, 3) as usize]
    );
    let shades = ["\"flat\"", "\"gouraud\"", "\"gouraud-fast\"", "\"phong\""];
    let _ = writeln!(s, "shade = {}", shades[rng.range(0, 3) as usize]);
    let _ = writeln!(s, "cull = {}", rng.range(0, 1) == 0);
    let _ = writeln!(s, "dither = {}", rng.range(0, 3) == 0);
    let lit = rng.range(0, 1) == 0;
    if lit {
        let _ = writeln!(s, "[lighting]\nambient = {}", integer(rng, 0, 255));
        for _ in 0..rng.range(0, 5) {
            let kind = if rng.range(0, 1) == 0 {
                "point"
            } else {
                "toward"
            };
            let _ = writeln!(
                s,
                "[[lighting.light]]\n{kind} = {}\nintensity = {}",
                vec3(rng, -5.0, 5.0),
                integer(rng, 0, 255)
            );
        }
    }
    for _ in 0..rng.range(0, 3) {
        let _ = writeln!(s, "[[object]]");
        match rng.range(0, 6) {
            0 => {
                let _ = writeln!(
                    s,
                    "generator = \"sphere\"\nsegments = {}\nrings = {}",
                    integer(rng, 3, 24),
                    integer(rng, 2, 12)
                );
            }
            1 => {
                let _ = writeln!(
                    s,
                    "generator = \"torus\"\nrings = {}\nsides = {}\nmajor = {}\nminor = {}",
                    integer(rng, 3, 24),
                    integer(rng, 3, 12),
                    number(rng, 0.5, 2.0),
                    number(rng, 0.05, 0.6)
                );
            }
            2 => {
                let _ = writeln!(
                    s,
                    "generator = \"prism\"\nsides = {}\ninner = {}",
                    integer(rng, 3, 12),
                    number(rng, 0.1, 1.2)
                );
            }
            3 => {
                let _ = writeln!(
                    s,
                    "generator = \"quad\"\nsize = [{}, {}]",
                    number(rng, 0.1, 40.0),
                    number(rng, 0.1, 40.0)
                );
            }
            4 => {
                let _ = writeln!(s, "generator = \"blob\"");
            }
            _ => {
                let _ = writeln!(s, "generator = \"cube\"\ncenter = {}", rng.range(0, 1) == 0);
            }
        }
        if rng.range(0, 2) == 0 {
            let _ = writeln!(s, "scale = {}", number(rng, 0.1, 3.0));
        }
        if rng.range(0, 1) == 0 {
            let _ = writeln!(s, "rotate_deg = {}", vec3(rng, -180.0, 180.0));
        }
        if rng.range(0, 2) == 0 {
            let _ = writeln!(s, "translate = {}", vec3(rng, -3.0, 3.0));
        }
        if lit && rng.range(0, 1) == 0 {
            let _ = writeln!(
                s,
                "material = {{ ka = {}, kd = {}, n = {} }}",
                number(rng, 0.0, 1.0),
                number(rng, 0.0, 1.5),
                integer(rng, 1, 200)
            );
        } else if rng.range(0, 3) == 0 {
            let _ = writeln!(s, "material = {}", integer(rng, 0, 3));
        }
    }
    s
}

/// Random OBJ text with hostile numbers and indices.
pub fn random_obj(rng: &mut Rng) -> String {
    let mut s = String::new();
    let mut defined = 0i64;
    for _ in 0..rng.range(0, 40) {
        match rng.range(0, 9) {
            0..=3 => {
                let _ = writeln!(
                    s,
                    "v {} {} {}",
                    number(rng, -2.0, 2.0),
                    number(rng, -2.0, 2.0),
                    number(rng, -2.0, 2.0)
                );
                defined += 1;
            }
            4..=7 => {
                let _ = write!(s, "f");
                for _ in 0..rng.range(0, 6) {
                    let i = match rng.range(0, 7) {
                        0 => [i64::MIN, i64::MAX, 0, -1, i64::MIN + 1][rng.range(0, 4) as usize],
                        1 => -rng.range(1, defined.max(1) + 2),
                        _ => rng.range(1, defined.max(1) + 1),
                    };
                    let form = ["", "/1", "//2", "/3/4"][rng.range(0, 3) as usize];
                    let _ = write!(s, " {i}{form}");
                }
                let _ = writeln!(s);
            }
            8 => {
                let _ = writeln!(s, "# comment\nvn 0 0 1\ng group");
            }
            _ => {
                let _ = writeln!(s, "v 1 2");
            }
        }
    }
    s
}

/// Random `zscan spans` input: first line the sub-pixel bits, then polygons.
pub fn random_spans(rng: &mut Rng) -> String {
    let bits = [0, 1, 4, 4, 4, 8, 16, 17][rng.range(0, 7) as usize];
    let mut s = format!("{bits}\n");
    for _ in 0..rng.range(0, 3) {
        for _ in 0..rng.range(0, 9) {
            let c = |rng: &mut Rng| match rng.range(0, 20) {
                // Out-of-range or malformed (in-range extremes such as −16777215.9375 are
                // valid but make polygons 2^24 rows tall: seconds per case).
                0 => [
                    "16777216",
                    "-16777216.0625",
                    "1e3",
                    "0.1",
                    "x",
                    "99999999999999999999",
                    ".",
                ][rng.range(0, 6) as usize]
                    .to_string(),
                1 => format!("{}", rng.range(-5000, 5000)),
                _ => format!(
                    "{}",
                    rng.range(-64, 64) as f64 + [0.0, 0.5, 0.25, 0.0625][rng.range(0, 3) as usize]
                ),
            };
            let _ = writeln!(s, "{} {}", c(rng), c(rng));
        }
        let _ = writeln!(
            s,
            "{}",
            ["", "# gap", "", "1 2 3"][rng.range(0, 3) as usize]
        );
    }
    s
}

/// The `k`-th case of the campaign seeded with `seed` (targets in turn).
pub fn generate(seed: u64, k: u64) -> Case {
    let mut rng = Rng::new(seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    for _ in 0..4 {
        rng.next_u64();
    }
    let target = [Target::Scene, Target::Obj, Target::Spans, Target::Core][(k % 4) as usize];
    let input = match target {
        Target::Scene => random_scene(&mut rng),
        Target::Obj => random_obj(&mut rng),
        Target::Spans => random_spans(&mut rng),
        Target::Core => rng.next_u64().to_string(),
    };
    Case { target, input }
}

/// The result of a campaign.
#[derive(Debug, Default)]
pub struct Report {
    /// Cases run.
    pub cases: u64,
    /// Cases per target (scene, obj, spans, core) whose input was accepted (no error).
    pub accepted: [u64; 4],
    /// Time spent per target (scene, obj, spans, core).
    pub time: [std::time::Duration; 4],
    /// The slowest case and its time.
    pub slowest: Option<(Case, std::time::Duration)>,
    /// Cases that violated a property, with the violation.
    pub failures: Vec<(Case, String)>,
}

/// What a campaign writes to its log while it runs.
pub enum Log<'w> {
    /// Nothing.
    None,
    /// One line per case: its index, target and input, escaped to one line.
    Inputs(&'w mut dyn std::io::Write),
    /// One line every `n` cases: the cases run so far, accepted per target, the time (a case
    /// is regenerated from the seed and its index, [`generate`]).
    Progress(&'w mut dyn std::io::Write, u64),
}

/// Runs `cases` cases of the campaign `seed`; `log` gets one line per case (its target and
/// input, escaped to one line) when given.
pub fn campaign(seed: u64, cases: u64, log: Option<&mut dyn std::io::Write>) -> Report {
    campaign_from(seed, 0..cases, log.map_or(Log::None, Log::Inputs))
}

/// [`campaign`] over the case indices `range` (so that several processes can share a
/// campaign), logging as `log` says.
pub fn campaign_from(seed: u64, range: std::ops::Range<u64>, mut log: Log<'_>) -> Report {
    let mut report = Report::default();
    let started = std::time::Instant::now();
    // Panics are expected to be caught and reported; keep the default hook's noise out.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for k in range {
        let case = generate(seed, k);
        match &mut log {
            Log::Inputs(w) => {
                let _ = writeln!(w, "case {k} {}: {:?}", case.target.name(), case.input);
            }
            Log::Progress(w, n) if report.cases > 0 && report.cases % *n == 0 => {
                let _ = writeln!(
                    w,
                    "progress: {} cases (up to index {k}) in {:.1?}, accepted (scene, obj, \
                     spans, core) = {:?}, {} failures",
                    report.cases,
                    started.elapsed(),
                    report.accepted,
                    report.failures.len()
                );
                let _ = w.flush();
            }
            _ => {}
        }
        report.cases += 1;
        let start = std::time::Instant::now();
        let checked = check(&case);
        let took = start.elapsed();
        report.time[(k % 4) as usize] += took;
        if report.slowest.as_ref().is_none_or(|(_, t)| took > *t) {
            report.slowest = Some((case.clone(), took));
        }
        match checked {
            Ok(()) => {
                let ok = catch_unwind(AssertUnwindSafe(|| run_case(&case)))
                    .map(|r| matches!(r, Ok(Ok(_))))
                    .unwrap_or(false);
                report.accepted[(k % 4) as usize] += ok as u64;
            }
            Err(e) => report.failures.push((case, e)),
        }
    }
    std::panic::set_hook(hook);
    report
}
