//! The lower half of `zscan chart`: speed against accuracy of the hidden-surface methods and
//! depth widths, one panel per scene that traps one of them ([`Trap`]).
//!
//! ## What is measured
//! - **y, accuracy**: wrong pixels, those whose palette index differs from the 32-bit
//!   z-buffer's picture of the same scene ([`against_z32`]: the frames and the count of
//!   `zscan failures`, whose five cases `tests/visibility.rs` asserts). A different measure
//!   from the shading panels' error in LUT levels, hence its own panels. Linear, from 0.
//! - **x, speed**: host x86-64 instructions of one frame, counted by valgrind callgrind only
//!   inside `zscan_chart_region` ([`crate::core_render::measured`]): the core's frame call
//!   with its clears and the copy of each finished band into the picture; the renderer's
//!   set-up and the buffers the harness allocates are outside. Log scale, shared by the
//!   panels. These scenes are not bench cases, so there is no Cortex-M count here; the
//!   standard scenes' Cortex-M4 and M0 counts of the methods are in `docs/plan_chart.svg`.
//!
//! Every method ([`Method::ALL`]) runs on every trap; the markers are red where pixels are
//! wrong, blue where the picture is the reference's, and the reference itself is a black
//! square. Each mark carries its method's name (and its count when not 0), placed where it
//! overlaps no other.

use super::CliError;
use crate::failures::{against_z32, Method, Trap};

/// One point: a method on a trap.
#[derive(Debug, Clone, Copy)]
pub struct Point {
    trap: Trap,
    method: Method,
    wrong: usize,
    instructions: Option<u64>,
}

impl Point {
    /// The `--run-visibility` argument of this point.
    fn tag(trap: Trap, method: Method) -> String {
        format!("{}:{}", trap.name(), method.name())
    }
}

/// Host instructions of `zscan chart FLAG TAG`'s measured region (callgrind).
pub type Counter<'a> = &'a dyn Fn(&str, &str) -> Result<u64, CliError>;

/// Every point, its wrong pixels computed here and, when `count` is given, its host
/// instructions counted by it (`zscan chart --run-visibility TAG`).
pub fn points(count: Option<Counter<'_>>) -> Result<Vec<Point>, CliError> {
    let mut out = Vec::new();
    for trap in Trap::ALL {
        for method in Method::ALL {
            let (picture, reference) =
                against_z32(trap, method).map_err(|e| super::render::visibility_error_words(&e))?;
            let wrong = picture
                .iter()
                .zip(&reference)
                .filter(|(a, b)| a != b)
                .count();
            let tag = Point::tag(trap, method);
            let instructions = match count {
                Some(count) => Some(count("--run-visibility", &tag)?),
                None => None,
            };
            out.push(Point {
                trap,
                method,
                wrong,
                instructions,
            });
        }
    }
    Ok(out)
}

/// Prints the table of the points.
pub fn print(points: &[Point]) -> Result<(), super::out::OutputError> {
    crate::outln!(
        "\n{:<18} {:<34} {:>12} {:>12}",
        "scene",
        "method",
        "wrong px",
        "host instr"
    )?;
    for p in points {
        crate::outln!(
            "{:<18} {:<34} {:>12} {:>12}",
            p.trap.name(),
            p.method.label(),
            p.wrong,
            p.instructions.map_or("-".into(), |i| i.to_string())
        )?;
    }
    Ok(())
}

/// What callgrind runs: the frame of `tag` (`trap:method`), its core call in the measured
/// region.
pub fn run_one(tag: &str) -> Result<(), CliError> {
    let found = Trap::ALL.into_iter().find_map(|trap| {
        let method = Method::ALL
            .into_iter()
            .find(|&m| Point::tag(trap, m) == tag)?;
        Some((trap, method))
    });
    let (trap, method) = found.ok_or_else(|| format!("no scene and method {tag:?}"))?;
    let picture = trap
        .with(|r| method.draw(std::hint::black_box(r)))
        .map_err(|e| super::render::visibility_error_words(&e))?;
    crate::outln!("{tag}: {} pixels", picture.len())?;
    Ok(())
}

/// Height of one panel, pixels.
pub const PANEL_HEIGHT: u32 = 210;
/// Height of the section's heading above the panels, pixels.
pub const HEADING: u32 = 80;

/// Draws the section into `area` (heading, then one panel per trap), its texts collected in
/// `texts`; `top` is the area's top in the whole SVG (where the heading's text goes).
pub fn draw<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    points: &[Point],
    (width, top): (i32, i32),
    texts: &mut Vec<String>,
) -> Result<(), CliError> {
    let counts = points.iter().filter_map(|p| p.instructions);
    let (lo, hi) = counts.fold((f64::MAX, 0f64), |(lo, hi), n| {
        (lo.min(n as f64), hi.max(n as f64))
    });
    if hi <= 0.0 {
        return Ok(());
    }
    // Room on the right of the costliest mark for its name.
    let xs = (lo / 1.6, hi * 4.0);
    let heading = [
        (16, "zscan visibility methods and depth widths: speed vs wrong pixels"),
        (12, "one panel per scene that traps a method; y: pixels that differ from the 32-bit z-buffer's picture"),
        (12, "(red: some; blue: none; black square: that reference); x: host instructions of one frame, log scale"),
    ];
    for (i, (size, line)) in heading.into_iter().enumerate() {
        let weight = if i == 0 { r#" font-weight="bold""# } else { "" };
        texts.push(format!(
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="{size}"{weight}>{line}</text>"#,
            width / 2,
            top + 22 + 18 * i as i32
        ));
    }
    let body = area.margin(HEADING, 0, 0, 0);
    let panels = body.split_evenly((Trap::ALL.len(), 1));
    for (i, (panel_area, trap)) in panels.iter().zip(Trap::ALL).enumerate() {
        let mine: Vec<&Point> = points.iter().filter(|p| p.trap == trap).collect();
        let last = i + 1 == Trap::ALL.len();
        panel(panel_area, trap, &mine, xs, last, texts)?;
    }
    Ok(())
}

/// A label's box in SVG pixels: left, top, right, bottom.
type LabelBox = (i32, i32, i32, i32);

fn overlaps(a: LabelBox, b: LabelBox) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Where the label `text` of a mark at `(px, py)` goes: the first place right of the mark, then
/// higher and higher, then the same on its left, whose box stays inside `bounds` and overlaps
/// no box in `taken` (the marks and the labels placed so far); the box is added to `taken`.
/// Returns the text's anchor point and SVG `text-anchor`, and whether the label was lifted off
/// its mark (then a leader line joins them).
fn place_label(
    text: &str,
    (px, py): (i32, i32),
    bounds: LabelBox,
    taken: &mut Vec<LabelBox>,
) -> ((i32, i32, &'static str), bool) {
    // About 6 pixels per character at font size 11.
    let w = 6 * text.chars().count() as i32;
    let lanes = |dx, anchor| (0..8).map(move |k| (dx, 4 - 13 * k, anchor));
    let candidates = lanes(8, "start").chain(lanes(-8, "end"));
    let boxed = |(dx, dy, anchor): (i32, i32, &'static str)| {
        let (x, y) = (px + dx, py + dy);
        let left = if anchor == "start" { x } else { x - w };
        ((x, y, anchor), (left, y - 10, left + w, y + 2))
    };
    let fits =
        |b: &LabelBox| b.0 >= bounds.0 && b.2 <= bounds.2 && b.1 >= bounds.1 && b.3 <= bounds.3;
    let (at, b) = candidates
        .map(boxed)
        .find(|(_, b)| fits(b) && !taken.iter().any(|t| overlaps(*t, *b)))
        .unwrap_or_else(|| boxed((8, 4, "start")));
    taken.push(b);
    (at, at.1 < py)
}

/// Grid values of a log axis from `lo` to `hi`: 1, 2 and 5 times the powers of ten.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut decade = 10f64.powf(lo.log10().floor());
    while decade <= hi {
        out.extend(
            [1.0, 2.0, 5.0]
                .map(|m| m * decade)
                .iter()
                .filter(|&&v| v >= lo && v <= hi),
        );
        decade *= 10.0;
    }
    out
}

/// `n` instructions as a tick label: `500 k`, `2 M`.
fn count_label(n: f64) -> String {
    if n >= 1e6 {
        format!("{} M", n / 1e6)
    } else {
        format!("{} k", n / 1e3)
    }
}

/// One trap's panel: axes, grid, the marks and their labels.
fn panel<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    trap: Trap,
    points: &[&Point],
    (x0, x1): (f64, f64),
    last: bool,
    texts: &mut Vec<String>,
) -> Result<(), CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    let most = points.iter().map(|p| p.wrong).max().unwrap_or(0).max(1) as f64;
    // Room above the highest mark for the labels stacked over it.
    let y1 = most * 1.35;
    let mut chart = ChartBuilder::on(area)
        .margin_left(super::chart::MARGINS.0)
        .margin_top(26)
        .margin_right(20)
        .margin_bottom(if last { 44 } else { 22 })
        .build_cartesian_2d((x0..x1).log_scale(), 0f64..y1)
        .map_err(|x| e(&x))?;
    let grey = RGBColor(225, 225, 225);
    for x in log_ticks(x0, x1) {
        chart
            .draw_series(LineSeries::new([(x, 0.0), (x, y1)], grey))
            .map_err(|q| e(&q))?;
        let (px, py) = chart.backend_coord(&(x, 0.0));
        texts.push(format!(
            r#"<text x="{px}" y="{}" text-anchor="middle" font-size="11">{}</text>"#,
            py + 14,
            count_label(x)
        ));
    }
    let step = super::chart::nice_step(most);
    let label = |y: f64| format!("{y:.0}");
    super::chart::y_grid(&mut chart, (x0, x1), (y1, step), (grey, 11), &label, texts)?;
    chart
        .draw_series(LineSeries::new([(x0, y1), (x0, 0.0), (x1, 0.0)], BLACK))
        .map_err(|q| e(&q))?;
    let (left, top) = chart.backend_coord(&(x0, y1));
    let (right, bottom) = chart.backend_coord(&(x1, 0.0));
    texts.push(format!(
        r#"<text x="{left}" y="{}" font-size="13" font-weight="bold">{}</text>"#,
        top - 8,
        trap.caption()
    ));
    let mid = (top + bottom) / 2;
    texts.push(format!(
        r#"<text x="{0}" y="{mid}" text-anchor="middle" font-size="11" transform="rotate(-90 {0} {mid})">wrong pixels</text>"#,
        left - 44
    ));
    if last {
        texts.push(format!(
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="13">host x86-64 instructions per frame (valgrind callgrind: the core's frame call, clears included; log scale)</text>"#,
            (left + right) / 2,
            bottom + 34
        ));
    }
    marks(&mut chart, points, (left, top, right, bottom), texts)
}

/// The marks of `points` on `chart` and their labels, kept inside `bounds`.
fn marks<DB: plotters::prelude::DrawingBackend>(
    chart: &mut plotters::prelude::ChartContext<
        '_,
        DB,
        plotters::prelude::Cartesian2d<
            plotters::coord::combinators::LogCoord<f64>,
            plotters::coord::types::RangedCoordf64,
        >,
    >,
    points: &[&Point],
    bounds: LabelBox,
    texts: &mut Vec<String>,
) -> Result<(), CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    let mut measured: Vec<(&Point, f64)> = points
        .iter()
        .filter_map(|p| Some((*p, p.instructions? as f64)))
        .collect();
    // Right to left: each label goes right of its mark, above the labels of the marks further
    // right when it must, so that no leader line crosses a label.
    measured.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut taken: Vec<LabelBox> = measured
        .iter()
        .map(|(p, x)| {
            let (px, py) = chart.backend_coord(&(*x, p.wrong as f64));
            (px - 6, py - 6, px + 6, py + 6)
        })
        .collect();
    for (p, x) in &measured {
        let at = (*x, p.wrong as f64);
        if p.method == Method::ZBuffer32 {
            let (px, py) = chart.backend_coord(&at);
            texts.push(format!(
                r#"<rect x="{}" y="{}" width="10" height="10" fill="none" stroke="black" stroke-width="2"/>"#,
                px - 5,
                py - 5
            ));
        } else {
            let colour = if p.wrong > 0 {
                RGBColor(210, 30, 30)
            } else {
                RGBColor(30, 90, 200)
            };
            chart
                .draw_series(std::iter::once(Circle::new(at, 5, colour.filled())))
                .map_err(|q| e(&q))?;
        }
        let text = if p.wrong > 0 {
            format!("{}: {} wrong", p.method.label(), p.wrong)
        } else {
            p.method.label().to_string()
        };
        let (px, py) = chart.backend_coord(&at);
        let ((lx, ly, anchor), lifted) = place_label(&text, (px, py), bounds, &mut taken);
        if lifted {
            let end = if anchor == "start" { lx - 2 } else { lx + 2 };
            texts.push(format!(
                r#"<line x1="{px}" y1="{py}" x2="{end}" y2="{}" stroke="rgb(150,150,150)" stroke-width="1"/>"#,
                ly - 4
            ));
        }
        texts.push(format!(
            r#"<text x="{lx}" y="{ly}" text-anchor="{anchor}" font-size="11">{text}</text>"#
        ));
    }
    Ok(())
}
