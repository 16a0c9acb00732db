//! The `zscan` command-line tool. See `zscan --help`.
//!
//! Output goes through `zscan_host::cli::out` (never `println!`): a closed or full standard
//! output is an error in words and a non-zero exit, not a panic.
#![deny(clippy::print_stdout, clippy::print_stderr)]
use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "zscan",
    version,
    about = "zscan host tool: render, inspect and benchmark"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Draw a test pattern of lines and circles to an image.
    Lines(zscan_host::cli::lines::LinesArgs),
    /// Print the covered spans of polygons read as text.
    Spans(zscan_host::cli::spans::SpansArgs),
    /// Count instructions of the benchmark cases on the host and Cortex-M (docs/BENCHMARKS.md).
    Bench(zscan_host::cli::bench::BenchArgs),
    /// Write the standard benchmark scenes as Rust sources (`DIR/<name>.rs`) to `include!`.
    ExportScenes(zscan_host::cli::export::ExportScenesArgs),
    /// Write a mesh file (OBJ, STL, PLY) as a Rust module of static tables and planner facts.
    Mesh(zscan_host::cli::mesh::MeshArgs),
    /// Render a scene described in TOML (see host-tests/scenes/example.toml) to an image.
    Render(zscan_host::cli::render::RenderArgs),
    /// Write the speed-versus-accuracy chart of the shading modes (SVG) and print its table.
    Chart(zscan_host::cli::chart::ChartArgs),
    /// Draw where the hidden-surface methods fail (wrong pixels marked) and print the counts.
    Failures(zscan_host::cli::failures::FailuresArgs),
}

fn main() -> std::process::ExitCode {
    use std::process::ExitCode;
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // `--help` and `--version` are written through `cli::out` like any output (clap's own
        // printing ignores a failure); a usage error goes to standard error with clap's code.
        Err(e) if !e.use_stderr() => {
            let text = e.render().to_string();
            let written = zscan_host::outln!("{}", text.trim_end())
                .and_then(|()| zscan_host::cli::out::flush());
            return match written {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    zscan_host::note!("zscan: {e}");
                    ExitCode::FAILURE
                }
            };
        }
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(e.exit_code().clamp(1, 255) as u8);
        }
    };
    let result = match cli.command {
        Command::Lines(a) => zscan_host::cli::lines::run(a),
        Command::Spans(a) => zscan_host::cli::spans::run(a),
        Command::Bench(a) => zscan_host::cli::bench::run(a),
        Command::ExportScenes(a) => zscan_host::cli::export::run(a),
        Command::Mesh(a) => zscan_host::cli::mesh::run(a),
        Command::Render(a) => zscan_host::cli::render::run(a),
        Command::Chart(a) => zscan_host::cli::chart::run(a),
        Command::Failures(a) => zscan_host::cli::failures::run(a),
    };
    // What is still buffered is written now, so that its failure is reported too.
    let result = result.and_then(|()| Ok(zscan_host::cli::out::flush()?));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            zscan_host::note!("zscan: {e}");
            ExitCode::FAILURE
        }
    }
}
