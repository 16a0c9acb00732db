//! The `zscan` command-line tool. See `zscan --help`.
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
    /// Render a scene described in TOML (see host-tests/scenes/example.toml) to an image.
    Render(zscan_host::cli::render::RenderArgs),
    /// Write the speed-versus-accuracy chart of the shading modes (SVG) and print its table.
    Chart(zscan_host::cli::chart::ChartArgs),
    /// Draw where the hidden-surface methods fail (wrong pixels marked) and print the counts.
    Failures(zscan_host::cli::failures::FailuresArgs),
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Lines(a) => zscan_host::cli::lines::run(a),
        Command::Spans(a) => zscan_host::cli::spans::run(a),
        Command::Bench(a) => zscan_host::cli::bench::run(a),
        Command::ExportScenes(a) => zscan_host::cli::export::run(a),
        Command::Render(a) => zscan_host::cli::render::run(a),
        Command::Chart(a) => zscan_host::cli::chart::run(a),
        Command::Failures(a) => zscan_host::cli::failures::run(a),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("zscan: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
