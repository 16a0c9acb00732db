//! `zscan bench`: instruction counts of the shared benchmark cases (`benches/cases.rs`) on the
//! host (valgrind's callgrind) and on a Cortex-M4 (QEMU `mps2-an386` with the `qemu-icount`
//! plugin of `tools/qemu-icount`), optionally a Cortex-M0 (QEMU `microbit`, RAM enlarged),
//! printed side by side. Figures are *instructions*; beside each Cortex-M count stands a
//! *cycle estimate* (the plugin's timing-table model, `tools/qemu-icount/src/cycles.rs`:
//! Cortex-M4 for the M4 column, Cortex-M0+ for the M0 column, whose ARMv6-M code is the
//! same), and for `frame_bunny` (one pass and in bands of 16 rows) the frames per second it
//! implies at the clocks of two boards:
//! an STM32F411 (Cortex-M4, 100 MHz) and an RP2040 (Cortex-M0+, 133 MHz). The estimate assumes
//! zero-wait-state memory and no cache effects, a taken branch costing the pipeline refill
//! (Cortex-M4: `1 + P`, `P` = 2), the M0+'s 1-cycle multiplier and 12 cycles per M4 division
//! (the TRM's worst case; the line also gives the figure at 2 cycles, the best case). See
//! docs/BENCHMARKS.md.
//!
//! Every count is the measured call minus the `empty` case (the harness overhead), so it is
//! the case function's own work. Framebuffer checksums must agree across platforms; a
//! mismatch is an error.
//!
//! Run it from a release build: `cargo run --release -p zscan-host --bin zscan -- bench`
//! (or `scripts/bench.sh`). It builds the firmware and the plugin with cargo unless
//! `--no-build` is given.
use super::CliError;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use zscan::output::Framebuffer;

// The benchmark cases, the same source file the Cortex-M example includes (its own inner
// docs describe it; an outer doc here would make rustdoc resolve their links from this module).
#[path = "../../../benches/cases.rs"]
pub mod cases;

/// Arguments of `zscan bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Only print each case's pixel count and framebuffer checksum (no measurement), in the
    /// firmware's line format without the SysTick field.
    #[arg(long)]
    pub checksums: bool,
    /// Skip the host (callgrind) column.
    #[arg(long)]
    pub no_host: bool,
    /// Skip the Cortex-M4 (QEMU mps2-an386) column.
    #[arg(long)]
    pub no_m4: bool,
    /// Add a Cortex-M0 column (QEMU microbit with 4 MB of RAM, which no real nRF51 has).
    #[arg(long)]
    pub m0: bool,
    /// Use the existing firmware and plugin builds instead of running cargo.
    #[arg(long)]
    pub no_build: bool,
    /// Internal: run one case between the host markers (what callgrind measures).
    #[arg(long, hide = true)]
    pub run_case: Option<String>,
}

/// The host's measured region: callgrind collects exactly the calls of this function
/// (`--toggle-collect=zscan_bench_host_region`). Kept out of line and unmangled so its symbol
/// is stable.
#[no_mangle]
#[inline(never)]
pub fn zscan_bench_host_region(
    run: fn(&mut Framebuffer<'_>, &mut cases::Storage) -> u32,
    fb: &mut Framebuffer<'_>,
    storage: &mut cases::Storage,
) -> u32 {
    run(fb, storage)
}

/// Draws `case` on a cleared frame the way the firmware does (warm-up call, clear, measured
/// call); returns the pixels reported and the framebuffer checksum.
pub fn run_case(case: &cases::Case) -> (u32, u32) {
    let mut pixels = vec![0u8; cases::FB_LEN];
    let mut storage = Box::new(cases::Storage::new()); // declared once, like the firmware's
    let px = {
        let mut fb = Framebuffer::new(&mut pixels, cases::WIDTH, cases::HEIGHT)
            .expect("the buffer has the cases' size");
        fb.clear(0);
        std::hint::black_box((case.run)(
            std::hint::black_box(&mut fb),
            std::hint::black_box(&mut storage),
        ));
        fb.clear(0);
        let run = std::hint::black_box(case.run);
        zscan_bench_host_region(
            run,
            std::hint::black_box(&mut fb),
            std::hint::black_box(&mut storage),
        )
    };
    (px, cases::fnv1a(&pixels))
}

/// One platform's figures: raw instruction count per case index (harness overhead included),
/// and on Cortex-M the raw cycle estimate and divisions per case.
#[derive(Debug, Default, Clone)]
struct Column {
    raw: Vec<u64>,
    checksums: Vec<Option<u32>>,
    cycles: Vec<u64>,
    divisions: Vec<u64>,
}

impl Column {
    fn net(&self, i: usize) -> Option<u64> {
        Some(self.raw.get(i)?.saturating_sub(*self.raw.first()?))
    }

    /// The estimated cycles of case `i`, the empty case's subtracted.
    fn net_cycles(&self, i: usize) -> Option<u64> {
        Some(self.cycles.get(i)?.saturating_sub(*self.cycles.first()?))
    }

    fn net_divisions(&self, i: usize) -> Option<u64> {
        Some(
            self.divisions
                .get(i)?
                .saturating_sub(*self.divisions.first()?),
        )
    }
}

/// Runs `zscan bench`.
pub fn run(args: BenchArgs) -> Result<(), CliError> {
    if let Some(name) = &args.run_case {
        let case = find_case(name)?;
        let (px, sum) = run_case(case);
        crate::outln!(
            "zscan-bench case {} pixels={px} checksum={sum:08x}",
            case.name
        )?;
        return Ok(());
    }
    let host_sums: Vec<(u32, u32)> = cases::CASES.iter().map(run_case).collect();
    if args.checksums {
        for (case, (px, sum)) in cases::CASES.iter().zip(&host_sums) {
            crate::outln!(
                "zscan-bench case {} pixels={px} checksum={sum:08x}",
                case.name
            )?;
        }
        return Ok(());
    }
    if cfg!(debug_assertions) {
        crate::note!(
            "zscan bench: warning: a debug build; run with --release for meaningful host figures"
        );
    }
    let root = workspace_root();
    let host = if args.no_host {
        None
    } else {
        Some(host_column()?)
    };
    let mut arm = Vec::new();
    if !args.no_build && (!args.no_m4 || args.m0) {
        build_plugin(&root)?;
    }
    if !args.no_m4 {
        arm.push((
            "Cortex-M4",
            qemu_column(&root, Board::Mps2An386, !args.no_build)?,
        ));
    }
    if args.m0 {
        arm.push((
            "Cortex-M0",
            qemu_column(&root, Board::Microbit, !args.no_build)?,
        ));
    }

    // Checksums: every platform must draw the same pixels.
    let mut mismatches = Vec::new();
    for (label, col) in &arm {
        for (i, case) in cases::CASES.iter().enumerate() {
            if col.checksums.get(i).copied().flatten() != Some(host_sums[i].1) {
                mismatches.push(format!("{} on {label}", case.name));
            }
        }
    }

    print_table(&host_sums, host.as_ref(), &arm)?;
    if !mismatches.is_empty() {
        return Err(format!(
            "framebuffer checksums differ from the host's: {}",
            mismatches.join(", ")
        )
        .into());
    }
    Ok(())
}

fn find_case(name: &str) -> Result<&'static cases::Case, CliError> {
    cases::CASES.iter().find(|c| c.name == name).ok_or_else(|| {
        let names: Vec<_> = cases::CASES.iter().map(|c| c.name).collect();
        format!("no case {name:?}; cases: {}", names.join(", ")).into()
    })
}

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("host-tests has a parent")
        .to_path_buf()
}

fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"))
}

fn run_checked(cmd: &mut Command) -> Result<std::process::Output, CliError> {
    let out = cmd
        .output()
        .map_err(|e| format!("cannot run {cmd:?}: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "{cmd:?} failed ({}):\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        )
        .into());
    }
    Ok(out)
}

/// Host figures: one callgrind run per case, collecting only inside the host region.
fn host_column() -> Result<Column, CliError> {
    let dir = std::env::temp_dir().join(format!("zscan-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let mut col = Column::default();
    for case in cases::CASES {
        let (total, stdout) = callgrind_case(&dir, case.name)?;
        col.raw.push(total);
        col.checksums
            .push(parse_case_line(&stdout, case.name).map(|(_, s, _)| s));
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(col)
}

/// Host instructions of case `name` (harness overhead included: subtract the `empty` case's),
/// one callgrind run of this tool's `bench --run-case` collecting only inside the host region
/// (its output file in `dir`), with the run's standard output.
pub fn callgrind_case(dir: &Path, name: &str) -> Result<(u64, String), CliError> {
    let exe = std::env::current_exe()?;
    let out_file = dir.join(format!("callgrind.{name}"));
    let out = run_checked(
        Command::new("valgrind")
            .arg("--tool=callgrind")
            .arg("--collect-atstart=no")
            .arg("--toggle-collect=zscan_bench_host_region")
            .arg(format!("--callgrind-out-file={}", out_file.display()))
            .arg(&exe)
            .args(["bench", "--run-case", name]),
    )
    .map_err(|e| format!("valgrind (is it installed?): {e}"))?;
    let text = std::fs::read_to_string(&out_file)?;
    let total = text
        .lines()
        .find_map(|l| {
            l.strip_prefix("totals:")
                .or_else(|| l.strip_prefix("summary:"))
        })
        .and_then(|v| v.split_whitespace().next()?.parse::<u64>().ok())
        .ok_or_else(|| format!("no totals in {}", out_file.display()))?;
    let _ = std::fs::remove_file(&out_file);
    Ok((total, String::from_utf8_lossy(&out.stdout).into_owned()))
}

/// Parses `zscan-bench case <name> pixels=<p> checksum=<hex> [systick_instructions=<n>]`.
fn parse_case_line(text: &str, name: &str) -> Option<(u32, u32, Option<u64>)> {
    text.lines().find_map(|l| {
        let mut w = l.split_whitespace();
        if w.next()? != "zscan-bench" || w.next()? != "case" || w.next()? != name {
            return None;
        }
        let kv: BTreeMap<&str, &str> = w.filter_map(|f| f.split_once('=')).collect();
        Some((
            kv.get("pixels")?.parse().ok()?,
            u32::from_str_radix(kv.get("checksum")?, 16).ok()?,
            kv.get("systick_instructions").and_then(|v| v.parse().ok()),
        ))
    })
}

#[derive(Clone, Copy)]
enum Board {
    Mps2An386,
    Microbit,
}

impl Board {
    fn target(self) -> &'static str {
        match self {
            Board::Mps2An386 => "thumbv7em-none-eabihf",
            Board::Microbit => "thumbv6m-none-eabi",
        }
    }
    /// The plugin's cycle model (`cpu=`): the Cortex-M0 column's ARMv6-M code is costed as
    /// on a Cortex-M0+ (same instructions, the M0+'s timings).
    fn cycle_model(self) -> &'static str {
        match self {
            Board::Mps2An386 => "m4",
            Board::Microbit => "m0plus",
        }
    }

    /// The estimated cycles of one more iteration of the firmware's spin loop (`subs` and a
    /// taken `bne`): 1 + (1 + P) with P = 2 on the Cortex-M4, 1 + 2 on the Cortex-M0+.
    fn spin_cycles(self) -> u64 {
        match self {
            Board::Mps2An386 => 4,
            Board::Microbit => 3,
        }
    }

    fn qemu_args(self) -> &'static [&'static str] {
        match self {
            Board::Mps2An386 => &["-machine", "mps2-an386", "-cpu", "cortex-m4"],
            Board::Microbit => &[
                "-machine",
                "microbit",
                "-global",
                "nrf51-soc.sram-size=0x400000",
                "-global",
                "nrf51-soc.flash-size=0x400000",
            ],
        }
    }
}

fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())
}

fn plugin_path(root: &Path) -> PathBuf {
    target_dir(root).join("qemu-icount/release/libqemu_icount.so")
}

fn build_plugin(root: &Path) -> Result<(), CliError> {
    crate::note!("zscan bench: building the qemu-icount plugin");
    run_checked(
        Command::new(cargo())
            .current_dir(root)
            .args([
                "build",
                "--release",
                "--quiet",
                "--manifest-path",
                "tools/qemu-icount/Cargo.toml",
            ])
            .arg("--target-dir")
            .arg(target_dir(root).join("qemu-icount")),
    )?;
    Ok(())
}

/// The `llvm-nm` of the rustup component `llvm-tools`.
fn llvm_tool(tool: &str) -> Result<PathBuf, CliError> {
    let sysroot = run_checked(Command::new("rustc").args(["--print", "sysroot"]))?;
    let vv = run_checked(Command::new("rustc").arg("-vV"))?;
    let host = String::from_utf8_lossy(&vv.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_owned))
        .ok_or("rustc -vV printed no host")?;
    let p = PathBuf::from(String::from_utf8_lossy(&sysroot.stdout).trim())
        .join("lib/rustlib")
        .join(host)
        .join("bin")
        .join(tool);
    if !p.exists() {
        return Err(format!("{} not found: rustup component add llvm-tools", p.display()).into());
    }
    Ok(p)
}

fn symbol(nm_out: &str, name: &str) -> Result<u64, CliError> {
    nm_out
        .lines()
        .find_map(|l| {
            let f: Vec<_> = l.split_whitespace().collect();
            (f.len() == 3 && f[2] == name)
                .then(|| u64::from_str_radix(f[0], 16).ok())
                .flatten()
        })
        .ok_or_else(|| format!("symbol {name} not in the firmware").into())
}

/// Cortex-M figures: one QEMU run of the firmware with the plugin.
fn qemu_column(root: &Path, board: Board, build: bool) -> Result<Column, CliError> {
    let target = board.target();
    if build {
        crate::note!("zscan bench: building the firmware for {target}");
        run_checked(Command::new(cargo()).current_dir(root).args([
            "build",
            "--release",
            "--quiet",
            "--example",
            "cortex_m_bench",
            "--features",
            "cortex-m-example",
            "--target",
            target,
        ]))?;
    }
    let elf = target_dir(root)
        .join(target)
        .join("release/examples/cortex_m_bench");
    let nm = run_checked(Command::new(llvm_tool("llvm-nm")?).arg(&elf))?;
    let nm = String::from_utf8_lossy(&nm.stdout);
    let begin = symbol(&nm, "zscan_bench_begin")? & !1;
    let end = symbol(&nm, "zscan_bench_end")? & !1;
    let plugin = plugin_path(root);
    crate::note!("zscan bench: running {} under QEMU", elf.display());
    let out = run_checked(
        Command::new("timeout")
            .args(["300", "qemu-system-arm"])
            .args(board.qemu_args())
            .args([
                "-nographic",
                "-semihosting-config",
                "enable=on,target=native",
                "-icount",
                "shift=0",
            ])
            .arg("-kernel")
            .arg(&elf)
            .arg("-plugin")
            .arg(format!(
                "{},begin={begin:#x},end={end:#x},cpu={}",
                plugin.display(),
                board.cycle_model()
            )),
    )?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let (mut regions, mut cycles, mut divisions) = (Vec::new(), Vec::new(), Vec::new());
    for l in stderr.lines() {
        let f: Vec<_> = l.split_whitespace().collect();
        if f.len() == 4 && f[0] == "qemu-icount:" && f[1] == "region" {
            regions.push(f[3].parse::<u64>()?);
        }
        // qemu-icount: cycles <k> <cycles> taken=<n> divisions=<n> model=<m>
        if f.len() == 7 && f[0] == "qemu-icount:" && f[1] == "cycles" {
            cycles.push(f[3].parse::<u64>()?);
            let d = f[5]
                .strip_prefix("divisions=")
                .ok_or("no divisions= field")?;
            divisions.push(d.parse::<u64>()?);
        }
        if f.len() == 5 && f[1] == "regions" && f[4] != "0" {
            return Err(format!("qemu-icount reported protocol errors: {l}").into());
        }
    }
    let n = cases::CASES.len();
    if regions.len() != n + 2 || cycles.len() != n + 2 {
        return Err(format!(
            "expected {} regions and cycle lines from qemu-icount, got {} and {}:\n{stderr}",
            n + 2,
            regions.len(),
            cycles.len()
        )
        .into());
    }
    // The cycle model's self-test: 1000 more taken iterations of `subs; bne`.
    let spin = cycles[n + 1].checked_sub(cycles[n]);
    if spin != Some(1000 * board.spin_cycles()) {
        return Err(format!(
            "cycle model self-test failed: spin regions estimated {} and {} cycles (expected a difference of {})",
            cycles[n],
            cycles[n + 1],
            1000 * board.spin_cycles()
        )
        .into());
    }
    // Self-test: the two spin loops differ by exactly 2 x 1000 instructions.
    if regions[n + 1] - regions[n] != 2000 {
        return Err(format!(
            "counter self-test failed: spin regions {} and {}",
            regions[n],
            regions[n + 1]
        )
        .into());
    }
    let mut col = Column {
        raw: regions[..n].to_vec(),
        checksums: Vec::new(),
        cycles: cycles[..n].to_vec(),
        divisions: divisions[..n].to_vec(),
    };
    for case in cases::CASES {
        col.checksums
            .push(parse_case_line(&stdout, case.name).map(|(_, s, _)| s));
    }
    Ok(col)
}

/// The boards whose frame rate `zscan bench` states: the column's label, the board, the core
/// whose timings are applied and the clock in Hz.
const BOARDS: [(&str, &str, &str, u64); 2] = [
    ("Cortex-M4", "STM32F411", "Cortex-M4", 100_000_000),
    ("Cortex-M0", "RP2040", "Cortex-M0+", 133_000_000),
];

/// The cases whose frame rate is stated: SCENES.md's bunny frame in one pass (a full
/// 320 × 240 frame and 16-bit depth buffer, 230 KB: an RP2040 holds it, an STM32F411's 128 KB
/// do not) and in bands of 16 rows with the polygon table, each band copied out where a device
/// converts and sends it (what a board draws with `render_in_bands` or `DoubleBands`).
const RATED: [&str; 2] = ["frame_bunny", "frame_bunny_bands16"];

/// Frames per second of the [`RATED`] cases (clears and set-up included; the display transfer
/// not, which double-buffered bands overlap with drawing) at each board's clock from the cycle
/// estimate. On the Cortex-M4 the figure is given with every division at 12 cycles and at 2
/// (the TRM's range).
fn print_frame_rates(arm: &[(&str, Column)]) -> Result<(), super::out::OutputError> {
    for name in RATED {
        let Some(i) = cases::CASES.iter().position(|c| c.name == name) else {
            continue;
        };
        for (label, col) in arm {
            let Some(&(_, board, core, hz)) = BOARDS.iter().find(|b| b.0 == *label) else {
                continue;
            };
            let (Some(cycles), Some(instructions)) = (col.net_cycles(i), col.net(i)) else {
                continue;
            };
            let fps = |c: u64| hz as f64 / c.max(1) as f64;
            let mut line = format!(
                "{name} on {board} ({core} at {} MHz): {instructions} instructions, ~{cycles} cycles = {:.1} frames/s",
                hz / 1_000_000,
                fps(cycles)
            );
            let divisions = col.net_divisions(i).unwrap_or(0);
            if core == "Cortex-M4" && divisions > 0 {
                let best = cycles.saturating_sub(10 * divisions);
                line += &format!(
                    " (divisions at 12 cycles; {divisions} of them, at 2 cycles: ~{best} cycles = {:.1} frames/s)",
                    fps(best)
                );
            }
            crate::outln!("{line}")?;
        }
    }
    Ok(())
}

fn per_px(net: Option<u64>, px: u32) -> String {
    match net {
        Some(n) if px > 0 => format!("{:.2}", n as f64 / px as f64),
        _ => "-".into(),
    }
}

fn cell(net: Option<u64>) -> String {
    net.map_or_else(|| "-".into(), |n| n.to_string())
}

fn print_table(
    sums: &[(u32, u32)],
    host: Option<&Column>,
    arm: &[(&str, Column)],
) -> Result<(), super::out::OutputError> {
    let mut cols: Vec<(&str, &Column)> = Vec::new();
    if let Some(h) = host {
        cols.push(("host x86-64", h));
    }
    for (l, c) in arm {
        cols.push((l, c));
    }
    crate::outln!("instructions per call (harness overhead subtracted), pixels written, instructions per pixel;")?;
    crate::outln!("on Cortex-M also the estimated cycles (timing-table model: zero wait states, no cache, see tools/qemu-icount/src/cycles.rs;")?;
    crate::outln!("the Cortex-M0 column's ARMv6-M code costed with the Cortex-M0+'s timings)")?;
    let mut head = format!("{:<16} {:>7}", "case", "pixels");
    for (l, c) in &cols {
        head += &format!(" | {:>22}", format!("{l} instr  /px"));
        if !c.cycles.is_empty() {
            head += &format!(" {:>11}", "~cycles");
        }
    }
    crate::outln!("{head} | checksum")?;
    crate::outln!("{}", "-".repeat(head.len() + 11))?;
    for (i, case) in cases::CASES.iter().enumerate() {
        let px = sums[i].0;
        let mut row = format!("{:<16} {:>7}", case.name, px);
        for (_, c) in &cols {
            row += &format!(" | {:>13} {:>8}", cell(c.net(i)), per_px(c.net(i), px));
            if !c.cycles.is_empty() {
                row += &format!(" {:>11}", cell(c.net_cycles(i)));
            }
        }
        crate::outln!("{row} | {:08x}", sums[i].1)?;
    }
    print_frame_rates(arm)?;
    // A line model fitted on the two all-octant cases: per-line set-up + per-pixel cost.
    let idx = |n: &str| cases::CASES.iter().position(|c| c.name == n);
    if let (Some(a), Some(b)) = (idx("line_short"), idx("line_star64")) {
        let (la, pa) = (256.0, sums[a].0 as f64);
        let (lb, pb) = (64.0, sums[b].0 as f64);
        for (l, c) in &cols {
            if let (Some(na), Some(nb)) = (c.net(a), c.net(b)) {
                // na = la*S + pa*P, nb = lb*S + pb*P.
                let det = la * pb - lb * pa;
                let s = (na as f64 * pb - nb as f64 * pa) / det;
                let p = (la * nb as f64 - lb * na as f64) / det;
                crate::outln!("line model on {l}: {s:.1} instructions per line + {p:.2} per pixel (fit of line_short and line_star64)")?;
            }
        }
    }
    Ok(())
}
