//! `zscan chart --textures`: speed against accuracy of the texture modes, as an SVG (plotters'
//! SVG backend, texts as plain SVG `<text>` like the shading chart) and the table behind it.
//!
//! ## What is measured
//! For each of SCENES.md's textured scenes (`tex_floor`, `tex_cube`, `tex_sphere`) and each
//! [`TextureMode`] (exact, subdivided every 16 or 8 pixels, affine):
//! - **x, host**: instructions per frame of the bench case `frame_tex_<scene>[_<mode>]`
//!   (`benches/cases.rs`), counted by valgrind's callgrind inside the bench harness's region
//!   (`zscan bench --run-case`, the `empty` case subtracted): the figures `zscan bench`
//!   prints. A release build gives the meaningful ones.
//! - **x, Cortex-M4** (second row, with `--m4 FILE`): the same cases' counts from a saved
//!   `zscan bench --no-host` table.
//! - **y**: the share of the pixels covered by the frame and the `f64` definition both that
//!   show another texel than the definition's (filled marks), and the share of covered pixels
//!   whose texel is not the exact mode's (hollow marks): `crate::texture_failures`, from the
//!   very frames the cases draw.
//!
//! The table adds the covered pixels, the mean `|level − t·I/255|` against the definition and
//! the pixels covered by one of the two only.

use std::collections::HashMap;

use super::chart::{linear_grid, read_counts, with_texts, ChartArgs, MARGINS};
use super::CliError;
use crate::texture_failures::{accuracy_table, mode_name, Accuracy, TexScene, MODES};
use zscan::texture::TextureMode;

/// One point: a scene in a mode, its accuracy and its counts.
struct Point {
    scene: TexScene,
    mode: TextureMode,
    accuracy: Accuracy,
    /// Host instructions per frame (harness overhead subtracted).
    host: Option<u64>,
    /// Cortex-M4 instructions per frame, from the saved table.
    m4: Option<u64>,
}

impl Point {
    /// Percent of the compared pixels showing another texel than the definition's.
    fn vs_reference(&self) -> f64 {
        let a = &self.accuracy;
        100.0 * a.texels_vs_reference as f64 / a.compared.max(1) as f64
    }

    /// Percent of the covered pixels whose texel is not the exact mode's.
    fn vs_exact(&self) -> f64 {
        let a = &self.accuracy;
        100.0 * a.texels_vs_exact as f64 / a.covered.max(1) as f64
    }
}

/// Runs `zscan chart --textures`.
pub fn run(args: &ChartArgs) -> Result<(), CliError> {
    let measure = !args.no_measure;
    if cfg!(debug_assertions) && measure {
        crate::note!(
            "zscan chart: warning: a debug build; run with --release for meaningful figures"
        );
    }
    let m4: HashMap<String, u64> = match &args.m4 {
        Some(path) => read_counts(path, "")?,
        None => HashMap::new(),
    };
    let dir = std::env::temp_dir().join(format!("zscan-tex-chart-{}", std::process::id()));
    let empty = if measure {
        std::fs::create_dir_all(&dir)?;
        Some(super::bench::callgrind_case(&dir, "empty")?.0)
    } else {
        None
    };
    let mut points = Vec::new();
    for (scene, mode, accuracy) in accuracy_table()? {
        let case = scene.case_name(mode);
        let host = match empty {
            Some(e) => Some(
                super::bench::callgrind_case(&dir, &case)?
                    .0
                    .saturating_sub(e),
            ),
            None => None,
        };
        points.push(Point {
            scene,
            mode,
            accuracy,
            host,
            m4: m4.get(&case).copied(),
        });
    }
    let _ = std::fs::remove_dir_all(&dir);
    print(&points)?;
    if !measure {
        return Ok(());
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| "docs/texture_chart.svg".into());
    std::fs::write(&out, chart(&points)?).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::note!("zscan chart: wrote {}", out.display());
    Ok(())
}

fn print(points: &[Point]) -> Result<(), super::out::OutputError> {
    crate::outln!(
        "| scene | mode | covered | host instr | Cortex-M4 instr | texels ≠ exact mode | \
         texels ≠ f64 | mean level error vs f64 | covered by one only |"
    )?;
    crate::outln!("|---|---|---:|---:|---:|---:|---:|---:|---:|")?;
    let count = |n: Option<u64>| n.map_or("-".into(), |n| n.to_string());
    for p in points {
        let a = &p.accuracy;
        crate::outln!(
            "| {} | {} | {} | {} | {} | {} ({:.2} %) | {} of {} ({:.2} %) | {:.2} | {} |",
            p.scene.name(),
            mode_name(p.mode),
            a.covered,
            count(p.host),
            count(p.m4),
            a.texels_vs_exact,
            p.vs_exact(),
            a.texels_vs_reference,
            a.compared,
            p.vs_reference(),
            a.mean_error,
            a.coverage_vs_reference
        )?;
    }
    Ok(())
}

/// Colours of the modes, in [`MODES`]' order.
const COLOURS: [(u8, u8, u8); 4] = [(200, 30, 30), (230, 140, 0), (30, 150, 60), (30, 90, 200)];

fn colour(mode: TextureMode) -> plotters::prelude::RGBColor {
    let i = MODES.iter().position(|(m, _)| *m == mode).unwrap_or(0);
    let (r, g, b) = COLOURS[i];
    plotters::prelude::RGBColor(r, g, b)
}

/// The SVG: one panel per scene (columns) and platform (rows: host, then Cortex-M4 when its
/// counts are given); x = instructions per frame, y = percent of pixels.
fn chart(points: &[Point]) -> Result<String, CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    type Count = fn(&Point) -> Option<u64>;
    let mut platforms: Vec<(&str, Count)> = vec![("host x86-64 (callgrind)", |p| p.host)];
    if points.iter().any(|p| p.m4.is_some()) {
        platforms.push(("Cortex-M4 (QEMU, qemu-icount)", |p| p.m4));
    }
    let (width, panel_h) = (1350u32, 420u32);
    let height = 70 + panel_h * platforms.len() as u32;
    let mut svg = String::new();
    let mut texts: Vec<String> = Vec::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let (_, body) = root.split_vertically(70);
        let areas = body.split_evenly((platforms.len(), TexScene::ALL.len()));
        let panels = platforms
            .iter()
            .flat_map(|p| TexScene::ALL.map(|s| (*p, s)));
        for (area, ((platform, count), scene)) in areas.iter().zip(panels) {
            let rows: Vec<(&Point, f64)> = points
                .iter()
                .filter(|p| p.scene == scene)
                .filter_map(|p| Some((p, count(p)? as f64 / 1e6)))
                .collect();
            let title = format!("{}, {platform}", scene.name());
            panel(area, &rows, &title, &mut texts)?;
        }
        root.present().map_err(|x| e(&x))?;
    }
    let w = width as i32;
    texts.push(format!(r#"<text x="{}" y="26" text-anchor="middle" font-size="16" font-weight="bold">zscan textures: instructions per frame against pixels showing another texel (SCENES.md's textured scenes, 320x240, 64x64 grid)</text>"#, w / 2));
    let mut legend = String::new();
    let mut x = w / 2 - 430;
    for (mode, name) in MODES {
        let c = colour(mode);
        legend += &format!(
            r#"<circle cx="{x}" cy="50" r="5" fill="rgb({},{},{})"/><text x="{}" y="54" font-size="12">{name}</text>"#,
            c.0,
            c.1,
            c.2,
            x + 9
        );
        x += 80;
    }
    legend += &format!(
        r#"<text x="{x}" y="54" font-size="12">filled: % of pixels whose texel is not the f64 definition's; hollow: % whose texel is not the exact mode's</text>"#
    );
    texts.push(legend);
    Ok(with_texts(svg, &texts))
}

/// One panel: each point at (millions of instructions, percent), both marks joined by a line.
fn panel<DB: plotters::prelude::DrawingBackend>(
    area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    rows: &[(&Point, f64)],
    title: &str,
    texts: &mut Vec<String>,
) -> Result<(), CliError> {
    use plotters::prelude::*;
    let e = |x: &dyn std::fmt::Display| -> CliError { x.to_string().into() };
    let xmax = rows.iter().map(|r| r.1).fold(0.0, f64::max) * 1.15;
    let top = rows
        .iter()
        .map(|r| r.0.vs_reference().max(r.0.vs_exact()))
        .fold(0.0, f64::max);
    let ymax = (top * 1.12).max(1.0);
    if xmax <= 0.0 {
        return Ok(());
    }
    let mut chart = ChartBuilder::on(area)
        .margin_left(MARGINS.0 - 10)
        .margin_top(MARGINS.1)
        .margin_right(30)
        .margin_bottom(MARGINS.3)
        .build_cartesian_2d(0f64..xmax, 0f64..ymax)
        .map_err(|x| e(&x))?;
    linear_grid(
        &mut chart,
        (xmax, ymax),
        11,
        &trim,
        &|y| format!("{} %", trim(y)),
        texts,
    )?;
    let (tx, ty) = chart.backend_coord(&(0.0, ymax));
    texts.push(format!(
        r#"<text x="{}" y="{}" font-size="13" font-weight="bold">{title}</text>"#,
        tx + 6,
        ty - 8
    ));
    let (bx, by) = chart.backend_coord(&(xmax / 2.0, 0.0));
    texts.push(format!(
        r#"<text x="{bx}" y="{}" text-anchor="middle" font-size="12">millions of instructions per frame</text>"#,
        by + 32
    ));
    for (p, x) in rows {
        let c = colour(p.mode);
        let (f, h) = (p.vs_reference(), p.vs_exact());
        chart
            .draw_series(LineSeries::new([(*x, f), (*x, h)], c.stroke_width(1)))
            .map_err(|q| e(&q))?;
        chart
            .draw_series([
                Circle::new((*x, f), 5, c.filled()),
                Circle::new((*x, h), 5, c.stroke_width(2)),
            ])
            .map_err(|q| e(&q))?;
        // On the floor the exact, subdivided and affine marks stand close: the affine mode's
        // label goes below its mark, the 16-pixel one's to the left.
        let (px, py) = chart.backend_coord(&(*x, f));
        let (dx, dy, anchor) = match p.mode {
            TextureMode::Affine => (8, 18, "start"),
            TextureMode::Subdivided16 => (-8, -6, "end"),
            _ => (8, -6, "start"),
        };
        texts.push(format!(
            r#"<text x="{}" y="{}" text-anchor="{anchor}" font-size="11">{}</text>"#,
            px + dx,
            py + dy,
            mode_name(p.mode)
        ));
    }
    Ok(())
}

/// A tick value without trailing zeros (`0.5`, `2`, `1.25`).
fn trim(v: f64) -> String {
    let s = format!("{v:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
