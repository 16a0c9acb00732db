//! The command line's text inputs: random scene files (`zscan render`), OBJ text and `zscan
//! spans` input, mostly well-formed with hostile values, and their runs through the library
//! functions behind the subcommands (no subprocess). The fingerprint of a run is its pictures'
//! hashes and counts, or the error's text.

use std::fmt::Write as _;
use std::path::Path;

use zscan::raster::polygon::FillRule;

use super::{hash, Outcome, Rng};

pub(super) fn run_scene(text: &str) -> Outcome {
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

pub(super) fn run_obj(text: &str) -> Outcome {
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

pub(super) fn run_spans(text: &str) -> Outcome {
    let (bits, body) = text.split_once('\n').unwrap_or(("4", text));
    let bits: u32 = bits.trim().parse().unwrap_or(4);
    let mut out = Vec::new();
    for rule in [FillRule::NonZero, FillRule::EvenOdd] {
        crate::cli::spans::write_spans(body, bits, rule, &mut out).map_err(|e| e.to_string())?;
    }
    Ok(vec![hash(out.iter().map(|&b| b as u64)), out.len() as u64])
}

/// A random number as TOML text, from a pool of ordinary and hostile values.
pub(super) fn number(rng: &mut Rng, lo: f64, hi: f64) -> String {
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
