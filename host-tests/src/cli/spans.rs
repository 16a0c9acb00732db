//! `zscan spans`: covered spans of polygons read as text.
//!
//! ## Input
//! One vertex per line as `x y`: two decimal numbers in pixel units (`3`, `-2.5`, `10.0625`),
//! `y` growing downward. `#` starts a comment (a whole line, or after the numbers); a line that
//! holds only a comment is ignored. A blank line (only white space) ends a polygon; several
//! blank lines are one separator and the end of the input ends the last polygon.
//!
//! Numbers are parsed exactly (integer and fractional digits as integers, no floating point).
//! A coordinate must be a multiple of `2^-S` pixel (`S` = `--subpixel-bits`, default 4) and lie
//! within the fill's range `|x·2^S| ≤ MAX_COORD`; anything else is an error naming the line.
//!
//! ## Output
//! For each polygon in input order, a line `polygon K` (`K` from 0), then one line `y x0 x1` per
//! maximal horizontal run of covered pixels, `x0 ≤ x1` **inclusive**, sorted by `y` then `x0`.
//! Coverage is the library's fill rule (`zscan::raster::polygon`: top-left rule, and for
//! self-intersecting polygons the nonzero winding rule, or the even-odd rule with
//! `--rule even-odd`); the window is the polygon's whole bounding box. Nothing is printed when the input
//! has an error.
use super::CliError;
use std::io::{Read, Write};
use zscan::raster::polygon::{fill_polygon_with_rule, FillRule, PolygonEdges};
use zscan::raster::{Span, SubpixelPoint, Window};
use zscan::raster::{MAX_COORD, MAX_SUBPIXEL_BITS};

/// The largest number of non-horizontal edges a polygon may have.
pub const MAX_EDGES: usize = 1024;

/// Arguments of `zscan spans`.
#[derive(clap::Args, Debug)]
pub struct SpansArgs {
    /// Fractional bits S of vertex coordinates (0..=16): every coordinate must be a multiple
    /// of 2^-S pixel.
    #[arg(long, default_value_t = 4)]
    pub subpixel_bits: u32,
    /// Which pixels of a self-intersecting polygon are inside: `nonzero` (winding number not
    /// zero) or `even-odd` (an odd number of edges at or left of the pixel on its row).
    #[arg(long, value_enum, default_value_t = RuleArg::Nonzero)]
    pub rule: RuleArg,
    /// Input file: one vertex `x y` per line (pixels, decimals allowed), a blank line between
    /// polygons, `#` comments; standard input when absent.
    pub file: Option<std::path::PathBuf>,
}

/// The `--rule` values: the core's [`FillRule`] by its command-line name.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RuleArg {
    /// Nonzero winding (the default).
    Nonzero,
    /// Even-odd parity (the course's algorithm 2.4).
    EvenOdd,
}

impl From<RuleArg> for FillRule {
    fn from(rule: RuleArg) -> Self {
        match rule {
            RuleArg::Nonzero => FillRule::NonZero,
            RuleArg::EvenOdd => FillRule::EvenOdd,
        }
    }
}

/// A polygon read from the input: its vertices in units of `2^-S` pixel and the line where it
/// starts (1-based).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputPolygon {
    /// Line number of the first vertex.
    pub line: usize,
    /// Vertices `(x, y)` in units of `2^-S` pixel.
    pub vertices: Vec<(i32, i32)>,
}

/// Runs `zscan spans`.
pub fn run(args: SpansArgs) -> Result<(), CliError> {
    let mut text = String::new();
    match &args.file {
        Some(path) => {
            text = std::fs::read_to_string(path)
                .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        }
        None => {
            std::io::stdin()
                .lock()
                .read_to_string(&mut text)
                .map_err(|e| format!("cannot read standard input: {e}"))?;
        }
    }
    let mut out = super::out::Stdout::new();
    write_spans(&text, args.subpixel_bits, args.rule.into(), &mut out)?;
    Ok(out.finish()?)
}

/// Parses `input` and writes the output described in the module doc to `out`. The whole input
/// is parsed and every polygon checked (capacity) before anything is written, so an input
/// error leaves `out` untouched; spans are then streamed to `out` as the fill emits them.
pub fn write_spans(
    input: &str,
    subpixel_bits: u32,
    rule: FillRule,
    out: &mut impl Write,
) -> Result<(), CliError> {
    let polygons = parse_polygons(input, subpixel_bits)?;
    let context = |k: usize, p: &InputPolygon, e: String| {
        format!(
            "polygon {k} (starting at line {}, {} vertices): {e}",
            p.line,
            p.vertices.len()
        )
    };
    for (k, p) in polygons.iter().enumerate() {
        check_polygon(&p.vertices, subpixel_bits).map_err(|e| context(k, p, e))?;
    }
    let werr = super::out::Stdout::error;
    for (k, p) in polygons.iter().enumerate() {
        writeln!(out, "polygon {k}").map_err(werr)?;
        let mut io_error: Option<std::io::Error> = None;
        let mut write = |s: Span| {
            if io_error.is_none() {
                if let Err(e) = writeln!(out, "{} {} {}", s.y, s.x0, s.x1 - 1) {
                    io_error = Some(e);
                }
            }
        };
        // The fill emits maximal spans in row order, left to right; merging touching ones
        // again costs nothing and keeps the output maximal whatever the fill's span split.
        let mut pending: Option<Span> = None;
        for_each_span(
            &p.vertices,
            subpixel_bits,
            rule,
            &mut |s| match pending.as_mut() {
                Some(last) if last.y == s.y && last.x1 == s.x0 => last.x1 = s.x1,
                _ => {
                    if let Some(prev) = pending.replace(s) {
                        write(prev);
                    }
                }
            },
        )
        .map_err(|e| context(k, p, e))?;
        if let Some(prev) = pending {
            write(prev);
        }
        if let Some(e) = io_error {
            return Err(werr(e).into());
        }
    }
    Ok(())
}

/// Splits the input into polygons (see the module doc for the format), converting each
/// coordinate exactly to units of `2^-S` pixel. Errors name the line.
pub fn parse_polygons(input: &str, subpixel_bits: u32) -> Result<Vec<InputPolygon>, String> {
    if subpixel_bits > MAX_SUBPIXEL_BITS {
        return Err(format!(
            "--subpixel-bits {subpixel_bits} is larger than the maximum {MAX_SUBPIXEL_BITS}"
        ));
    }
    let mut polygons = Vec::new();
    let mut current: Option<InputPolygon> = None;
    for (i, raw) in input.lines().enumerate() {
        let line_no = i + 1;
        if raw.trim().is_empty() {
            if let Some(p) = current.take() {
                polygons.push(p);
            }
            continue;
        }
        let content = match raw.find('#') {
            Some(j) => &raw[..j],
            None => raw,
        };
        let fields: Vec<&str> = content.split_whitespace().collect();
        if fields.is_empty() {
            continue; // a comment line
        }
        if fields.len() != 2 {
            return Err(format!(
                "line {line_no}: expected a vertex `x y`, found {} field(s): `{}`",
                fields.len(),
                content.trim()
            ));
        }
        let x = parse_coord(fields[0], subpixel_bits)
            .map_err(|e| format!("line {line_no}: x coordinate {e}"))?;
        let y = parse_coord(fields[1], subpixel_bits)
            .map_err(|e| format!("line {line_no}: y coordinate {e}"))?;
        current
            .get_or_insert_with(|| InputPolygon {
                line: line_no,
                vertices: Vec::new(),
            })
            .vertices
            .push((x, y));
    }
    if let Some(p) = current.take() {
        polygons.push(p);
    }
    Ok(polygons)
}

/// Parses one decimal coordinate in pixel units exactly and returns it in units of `2^-S`
/// pixel. The error text completes "x coordinate …".
pub fn parse_coord(token: &str, subpixel_bits: u32) -> Result<i32, String> {
    let s = subpixel_bits;
    let (negative, body) = match token.as_bytes().first() {
        Some(b'-') => (true, &token[1..]),
        Some(b'+') => (false, &token[1..]),
        _ => (false, token),
    };
    let (int_digits, frac_digits) = match body.find('.') {
        Some(j) => (&body[..j], &body[j + 1..]),
        None => (body, ""),
    };
    let all_digits = |d: &str| d.bytes().all(|c| c.is_ascii_digit());
    if (int_digits.is_empty() && frac_digits.is_empty())
        || !all_digits(int_digits)
        || !all_digits(frac_digits)
    {
        return Err(format!("`{token}` is not a decimal number"));
    }
    let out_of_range = || {
        format!(
            "`{token}` is out of range: |coordinate| must be at most {MAX_COORD} units of 2^-{s} pixel ({} pixels)",
            MAX_COORD >> s
        )
    };
    let int_digits = int_digits.trim_start_matches('0');
    if int_digits.len() > 12 {
        return Err(out_of_range());
    }
    let int_part: i128 = if int_digits.is_empty() {
        0
    } else {
        int_digits.parse().map_err(|_| out_of_range())?
    };
    let frac_digits = frac_digits.trim_end_matches('0');
    let not_multiple = || {
        format!(
            "`{token}` is not a multiple of 2^-{s} pixel (1/{} pixel)",
            1u64 << s
        )
    };
    // A multiple of 2^-S has at most S ≤ 16 decimals once trailing zeros are dropped.
    if frac_digits.len() > MAX_SUBPIXEL_BITS as usize {
        return Err(not_multiple());
    }
    let (frac_num, frac_den): (i128, i128) = if frac_digits.is_empty() {
        (0, 1)
    } else {
        let num = frac_digits.parse().map_err(|_| not_multiple())?;
        (num, 10i128.pow(frac_digits.len() as u32))
    };
    if (frac_num << s) % frac_den != 0 {
        return Err(not_multiple());
    }
    let mut units = (int_part << s) + (frac_num << s) / frac_den;
    if negative {
        units = -units;
    }
    if units.abs() > MAX_COORD as i128 {
        return Err(out_of_range());
    }
    Ok(units as i32)
}

/// Calls `$f::<S>($args)` for the run-time `S` in `0..=MAX_SUBPIXEL_BITS`.
macro_rules! dispatch {
    ($bits:expr, $f:ident $args:tt) => {
        dispatch!(@arms $bits, $f $args; 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
    };
    (@arms $bits:expr, $f:ident $args:tt; $($s:literal)*) => {
        match $bits {
            $($s => $f::<$s> $args,)*
            bits => Err(format!(
                "--subpixel-bits {bits} is larger than the maximum {MAX_SUBPIXEL_BITS}"
            )),
        }
    };
}

/// Checks that a polygon (vertices in units of `2^-S` pixel) can be filled: coordinates in
/// range and at most [`MAX_EDGES`] non-horizontal edges.
pub fn check_polygon(vertices: &[(i32, i32)], subpixel_bits: u32) -> Result<(), String> {
    dispatch!(subpixel_bits, check_at(vertices))
}

/// Calls `emit` with the covered spans of one polygon (vertices in units of `2^-S` pixel)
/// under `rule`, half-open, in row order and left to right, as the library's fill emits them.
pub fn for_each_span(
    vertices: &[(i32, i32)],
    subpixel_bits: u32,
    rule: FillRule,
    emit: &mut dyn FnMut(Span),
) -> Result<(), String> {
    dispatch!(subpixel_bits, fill_at(vertices, rule, emit))
}

/// The covered spans of one polygon (vertices in units of `2^-S` pixel, `S` given at run time)
/// under `rule`, half-open, sorted by row then column, touching runs merged.
pub fn polygon_spans(
    vertices: &[(i32, i32)],
    subpixel_bits: u32,
    rule: FillRule,
) -> Result<Vec<Span>, String> {
    let mut spans: Vec<Span> = Vec::new();
    for_each_span(
        vertices,
        subpixel_bits,
        rule,
        &mut |s| match spans.last_mut() {
            Some(last) if last.y == s.y && last.x1 == s.x0 => last.x1 = s.x1,
            _ => spans.push(s),
        },
    )?;
    spans.sort_unstable_by_key(|s| (s.y, s.x0));
    Ok(spans)
}

fn to_points<const S: u32>(vertices: &[(i32, i32)]) -> Vec<SubpixelPoint<S>> {
    vertices
        .iter()
        .map(|&(x, y)| SubpixelPoint::new(x, y))
        .collect()
}

/// [`check_polygon`] for a compile-time `S`.
fn check_at<const S: u32>(vertices: &[(i32, i32)]) -> Result<(), String> {
    PolygonEdges::<MAX_EDGES>::build(&to_points::<S>(vertices))
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// [`for_each_span`] for a compile-time `S`.
fn fill_at<const S: u32>(
    vertices: &[(i32, i32)],
    rule: FillRule,
    emit: &mut dyn FnMut(Span),
) -> Result<(), String> {
    let points = to_points::<S>(vertices);
    if points.is_empty() {
        return Ok(());
    }
    // The bounding box in pixels (floor of the minimum, one past the floor of the maximum):
    // no covered pixel lies outside it, so the output is the unclipped coverage.
    let min_x = points.iter().map(|p| p.x).min().unwrap_or(0) >> S;
    let max_x = points.iter().map(|p| p.x).max().unwrap_or(0) >> S;
    let min_y = points.iter().map(|p| p.y).min().unwrap_or(0) >> S;
    let max_y = points.iter().map(|p| p.y).max().unwrap_or(0) >> S;
    let window = Window::new(min_x, min_y, max_x + 1, max_y + 1);
    fill_polygon_with_rule::<S, MAX_EDGES>(&points, &window, rule, emit).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_decimal_parsing() {
        assert_eq!(parse_coord("3", 4), Ok(48));
        assert_eq!(parse_coord("-2.5", 4), Ok(-40));
        assert_eq!(parse_coord("10.0625", 4), Ok(161));
        assert_eq!(parse_coord("+0.5000", 1), Ok(1));
        assert_eq!(parse_coord(".25", 2), Ok(1));
        assert_eq!(parse_coord("7.", 0), Ok(7));
        assert_eq!(parse_coord("-0", 0), Ok(0));
        assert_eq!(parse_coord("0.0000152587890625", 16), Ok(1));
        assert!(parse_coord("0.1", 4).unwrap_err().contains("multiple"));
        assert!(parse_coord("0.03125", 4).unwrap_err().contains("multiple"));
        assert!(parse_coord("1e3", 4).unwrap_err().contains("not a decimal"));
        assert!(parse_coord("-", 4).is_err());
        assert!(parse_coord(".", 4).is_err());
        assert!(parse_coord("1.2.3", 4).is_err());
        assert!(parse_coord("99999999999999999999999", 0)
            .unwrap_err()
            .contains("out of range"));
        assert_eq!(parse_coord(&MAX_COORD.to_string(), 0), Ok(MAX_COORD));
        assert!(parse_coord(&(MAX_COORD as i64 + 1).to_string(), 0).is_err());
        assert!(parse_coord("16777216", 4).is_err()); // 2^24 px = 2^28 units > MAX_COORD
        assert_eq!(parse_coord("-16777215.9375", 4), Ok(-MAX_COORD));
    }

    #[test]
    fn polygons_split_on_blank_lines() {
        let p = parse_polygons("# c\n\n0 0\n4 0 # x\n# mid\n0 4\n\n\n \n1 1\n", 0).unwrap();
        assert_eq!(p.len(), 2);
        assert_eq!(p[0].line, 3);
        assert_eq!(p[0].vertices, vec![(0, 0), (4, 0), (0, 4)]);
        assert_eq!(p[1].line, 10);
        assert!(parse_polygons("0 0 0\n", 0)
            .unwrap_err()
            .starts_with("line 1:"));
        assert!(parse_polygons("0 0\nx 0\n", 0)
            .unwrap_err()
            .starts_with("line 2:"));
        assert!(parse_polygons("0 0\n", 17).is_err());
    }
}
