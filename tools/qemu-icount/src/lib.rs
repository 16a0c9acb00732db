//! `qemu-icount`: a QEMU TCG plugin that counts executed guest instructions inside regions
//! delimited by two marker functions of the guest program.
//!
//! # Protocol
//! The guest (zscan's `examples/cortex_m_bench.rs`) has two `#[no_mangle] #[inline(never)]`
//! functions, `zscan_bench_begin` and `zscan_bench_end`. Their addresses (from `llvm-nm`; the
//! Thumb bit may be set, it is cleared here) are passed as plugin arguments:
//!
//! ```text
//! qemu-system-arm ... -plugin libqemu_icount.so,begin=0x1234,end=0x1240[,out=counts.txt]
//! ```
//!
//! - When the translation block (TB) at `begin` executes, a region opens with a count of 0.
//!   The instructions of that block (the marker's own body) are not counted.
//! - While a region is open, every executed TB adds its instruction count.
//! - When the TB at `end` executes, the region closes (the marker's body is not counted) and
//!   the plugin prints `qemu-icount: region <k> <instructions>` to stderr, `k` = 0, 1, 2, ...
//!   in execution order (and appends the same line to `out` when given).
//! - At exit it prints `qemu-icount: regions <n> errors <e>`; an error is a `begin` inside an
//!   open region or an `end` outside one.
//!
//! Counts are *raw*: they include the few instructions between the markers that are not the
//! measured work (the return from `begin`, the call of `end`, ...). The guest measures an empty
//! region first, and consumers subtract it. Counts are instructions, not cycles; a skipped
//! conditional instruction (IT block) counts as executed, and an interrupt handler running
//! inside a region is counted. QEMU must run with a single vCPU (Cortex-M boards have one).
//!
//! # Cycle estimate
//! With `cpu=m4` or `cpu=m0plus` (options: `div=<2..12>` cycles per Cortex-M4 division, default
//! 12; `mul=<1|32>` cycles per Cortex-M0+ multiply, default 1), each closed region also prints
//! `qemu-icount: cycles <k> <cycles> taken=<branches> divisions=<n>`: every instruction of
//! each executed block weighted by the core's timing table (`cycles.rs`, whose module doc
//! lists the assumptions: zero wait states, no cache, `P` = 2 on the Cortex-M4, …). A block's
//! last instruction is its only possible branch (TCG ends a block at every branch); a
//! conditional one is taken when the next block executed does not start right after it.
//! Instruction bytes are decoded once per translation; the estimate costs nothing when
//! `cpu=` is absent.
//!
//! Counts are exact because TCG calls the execute callback once per execution of a block and a
//! block always runs to its end unless an exception leaves it (none occurs in the measured code);
//! with `-icount`, QEMU retranslates shorter blocks instead of stopping one half-way, and
//! those shorter blocks are announced to this plugin with their own sizes.

mod cycles;

use cycles::{block_cost, BlockCost, Model};
use qemu_plugin::{
    install::{Args, Info},
    plugin::{HasCallbacks, Register},
    register, PluginId, Result, TranslationBlock, VCPUIndex,
};
use std::{
    io::Write,
    sync::{
        atomic::{AtomicBool, AtomicU64, Ordering},
        Mutex,
    },
};

/// Whether a region is open.
static OPEN: AtomicBool = AtomicBool::new(false);
/// Instructions counted in the open region.
static COUNT: AtomicU64 = AtomicU64::new(0);
/// Regions closed so far.
static REGIONS: AtomicU64 = AtomicU64::new(0);
/// Protocol errors (begin inside a region, end outside one).
static ERRORS: AtomicU64 = AtomicU64::new(0);
/// Estimated cycles, taken branches and divisions in the open region (`cpu=` given).
static CYCLES: AtomicU64 = AtomicU64::new(0);
static TAKEN: AtomicU64 = AtomicU64::new(0);
static DIVISIONS: AtomicU64 = AtomicU64::new(0);
/// The block executed last: where it falls through to, and what taking its conditional exit
/// adds (`u64::MAX` fall-through when its exit is not conditional).
static PREVIOUS_FALLTHROUGH: AtomicU64 = AtomicU64::new(u64::MAX);
static PREVIOUS_TAKEN_EXTRA: AtomicU64 = AtomicU64::new(0);
/// Optional output file (`out=` argument).
static OUT: Mutex<Option<std::fs::File>> = Mutex::new(None);
/// Profile of one region (`profile=<file>,profile_region=<k>`): per translation block, its
/// guest address, instruction count and executions inside region `k`, written at exit.
static PROFILE: Mutex<Option<Profile>> = Mutex::new(None);

/// Output path, profiled region, and per block address: (instructions, executions).
type Profile = (String, u64, std::collections::HashMap<u64, (u64, u64)>);

#[derive(Default)]
struct ICount {
    begin: u64,
    end: u64,
    model: Option<Model>,
}

/// Records the block at `at` as executed, with its own exit (`fallthrough`, `taken_extra`;
/// `u64::MAX` when the exit is not conditional); returns the extra cycles of the previous
/// block's conditional exit when it was taken (the block at `at` is not its fall-through).
fn follow(at: u64, fallthrough: u64, taken_extra: u64) -> Option<u64> {
    let previous = PREVIOUS_FALLTHROUGH.swap(fallthrough, Ordering::Relaxed);
    let extra = PREVIOUS_TAKEN_EXTRA.swap(taken_extra, Ordering::Relaxed);
    (previous != u64::MAX && previous != at).then_some(extra)
}

fn parse_addr(s: &str) -> Option<u64> {
    let s = s.trim();
    let v = if let Some(h) = s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        u64::from_str_radix(h, 16).ok()?
    } else {
        s.parse().ok()?
    };
    // Thumb functions have bit 0 set in symbol tables; code addresses never do.
    Some(v & !1)
}

fn emit(line: &str) {
    eprintln!("{line}");
    if let Ok(mut g) = OUT.lock() {
        if let Some(f) = g.as_mut() {
            let _ = writeln!(f, "{line}");
        }
    }
}

fn on_begin(_: VCPUIndex) {
    follow(0, u64::MAX, 0);
    if OPEN.swap(true, Ordering::Relaxed) {
        ERRORS.fetch_add(1, Ordering::Relaxed);
    }
    for counter in [&COUNT, &CYCLES, &TAKEN, &DIVISIONS] {
        counter.store(0, Ordering::Relaxed);
    }
}

fn on_end(model: Option<Model>) {
    follow(0, u64::MAX, 0);
    if OPEN.swap(false, Ordering::Relaxed) {
        let k = REGIONS.fetch_add(1, Ordering::Relaxed);
        let n = COUNT.load(Ordering::Relaxed);
        emit(&format!("qemu-icount: region {k} {n}"));
        if let Some(model) = model {
            emit(&format!(
                "qemu-icount: cycles {k} {} taken={} divisions={} model={}",
                CYCLES.load(Ordering::Relaxed),
                TAKEN.load(Ordering::Relaxed),
                DIVISIONS.load(Ordering::Relaxed),
                model.name(),
            ));
        }
    } else {
        ERRORS.fetch_add(1, Ordering::Relaxed);
    }
}

fn on_exit() {
    if let Ok(g) = PROFILE.lock() {
        if let Some((path, _, blocks)) = g.as_ref() {
            let mut rows: Vec<_> = blocks.iter().collect();
            rows.sort();
            let text: String = rows
                .iter()
                .map(|(a, (n, c))| format!("{a:#x} {n} {c}\n"))
                .collect();
            if let Err(e) = std::fs::write(path, text) {
                eprintln!("qemu-icount: cannot write {path}: {e}");
            }
        }
    }
    emit(&format!(
        "qemu-icount: regions {} errors {}",
        REGIONS.load(Ordering::Relaxed),
        ERRORS.load(Ordering::Relaxed)
    ));
}

impl Register for ICount {
    fn register(&mut self, id: PluginId, args: &Args, _info: &Info) -> Result<()> {
        let mut begin = None;
        let mut end = None;
        let (mut cpu, mut divide, mut multiply) = (None, None, None);
        for raw in &args.raw {
            let (k, v) = raw.split_once('=').unwrap_or((raw.as_str(), ""));
            match k {
                "begin" => begin = parse_addr(v),
                "end" => end = parse_addr(v),
                "profile" => {
                    let mut g = PROFILE.lock().expect("not poisoned");
                    let region = g.as_ref().map_or(0, |p| p.1);
                    *g = Some((v.to_string(), region, Default::default()));
                }
                "profile_region" => {
                    let k = v.parse().unwrap_or(0);
                    let mut g = PROFILE.lock().expect("not poisoned");
                    match g.as_mut() {
                        Some(p) => p.1 = k,
                        None => *g = Some((String::new(), k, Default::default())),
                    }
                }
                "cpu" => cpu = Some(v.to_string()),
                "div" => divide = v.parse::<u32>().ok().filter(|d| (2..=12).contains(d)),
                "mul" => multiply = v.parse::<u32>().ok().filter(|m| *m == 1 || *m == 32),
                "out" => match std::fs::File::create(v) {
                    Ok(f) => *OUT.lock().expect("not poisoned") = Some(f),
                    Err(e) => eprintln!("qemu-icount: cannot create {v}: {e}"),
                },
                _ => {
                    eprintln!("qemu-icount: unknown argument {raw:?} (expected begin=, end=, out=, cpu=, div=, mul=, profile=, profile_region=)")
                }
            }
        }
        self.model = match (cpu.as_deref().map(Model::parse), divide, multiply) {
            (None, None, None) => None,
            (Some(Some(Model::M4 { divide: d })), div, None) => Some(Model::M4 {
                divide: div.unwrap_or(d),
            }),
            (Some(Some(Model::M0Plus { multiply: m })), None, mul) => Some(Model::M0Plus {
                multiply: mul.unwrap_or(m),
            }),
            _ => {
                eprintln!(
                    "qemu-icount: bad cycle model arguments: cpu=m4 [div=2..12] or cpu=m0plus [mul=1|32]"
                );
                std::process::exit(2);
            }
        };
        match (begin, end) {
            (Some(b), Some(e)) if b != e => {
                self.begin = b;
                self.end = e;
            }
            _ => {
                eprintln!("qemu-icount: need distinct begin=<addr> and end=<addr> arguments");
                std::process::exit(2);
            }
        }
        qemu_plugin::qemu_plugin_register_atexit_cb(id, |_| on_exit())?;
        Ok(())
    }
}

impl HasCallbacks for ICount {
    fn on_translation_block_translate(
        &mut self,
        _id: PluginId,
        tb: TranslationBlock,
    ) -> Result<()> {
        let at = tb.vaddr();
        if at == self.begin {
            tb.register_execute_callback(on_begin);
        } else if at == self.end {
            let model = self.model;
            tb.register_execute_callback(move |_| on_end(model));
        } else {
            let n = tb.size() as u64;
            let profiling = PROFILE.lock().map(|g| g.is_some()).unwrap_or(false);
            // The block's bytes, decoded once here: its cycles and its exit.
            let (cost, fallthrough) = match self.model {
                Some(model) => {
                    let bytes: Vec<Vec<u8>> = tb.instructions().map(|i| i.data()).collect();
                    let len: usize = bytes.iter().map(Vec::len).sum();
                    let cost = block_cost(model, bytes.iter().map(Vec::as_slice));
                    let exit = if cost.conditional {
                        at + len as u64
                    } else {
                        u64::MAX
                    };
                    (cost, exit)
                }
                None => (BlockCost::default(), u64::MAX),
            };
            tb.register_execute_callback(move |_| {
                let taken = follow(at, fallthrough, cost.taken_extra);
                if !OPEN.load(Ordering::Relaxed) {
                    return;
                }
                COUNT.fetch_add(n, Ordering::Relaxed);
                let extra = taken.unwrap_or(0);
                CYCLES.fetch_add(cost.cycles + extra, Ordering::Relaxed);
                let branches = cost.always_taken + taken.is_some() as u64;
                TAKEN.fetch_add(branches, Ordering::Relaxed);
                DIVISIONS.fetch_add(cost.divisions, Ordering::Relaxed);
                if profiling {
                    if let Ok(mut g) = PROFILE.lock() {
                        if let Some((_, region, blocks)) = g.as_mut() {
                            if REGIONS.load(Ordering::Relaxed) == *region {
                                blocks.entry(at).or_insert((n, 0)).1 += 1;
                            }
                        }
                    }
                }
            });
        }
        Ok(())
    }
}

register!(ICount::default());
