//! Seeded property campaigns ("fuzzing" on the stable toolchain): random, often hostile,
//! inputs to the command line's parsers and renderer, the core's buffers, the scene planner,
//! every hidden-surface method and the polygon fill. Every case is checked for: no panic
//! (`catch_unwind`; with the `checked` profile an arithmetic overflow is one), no write outside
//! the buffers it was given, the reference's picture wherever the code claims it (the 32-bit
//! z-buffer for the methods and the plans, the exact rational fill for the fill), and
//! deterministic output (the case run twice gives the same result). A refusal in words (an
//! error) is an accepted outcome wherever the contract allows one.
//!
//! One file per family of targets ([`Target`]): `files.rs` (scene files, OBJ, `zscan spans`),
//! `buffers.rs` (framebuffers, lines, circles, fill, flush), `plan.rs` (`plan`, `plan_frame`,
//! `draw_plan` with random memory), `methods.rs` (back faces, the painter, the scan-line,
//! Warnock, the z-buffer whole, in bands and in compact bands at 16 and 32 bits, and
//! `DoubleBands`), `fill.rs` (both fill rules and `ConvexWindow`); `world.rs` draws the random
//! 3D scenes the planner's and the methods' targets share, and [`values`] is the one way the
//! new targets draw random values, each with its range.
//!
//! The generator is the workspace's test PRNG ([`XorShift`](crate::test_rng::XorShift)); a
//! case is fully described by its target and its input text ([`Case`]), which is what
//! the campaign prints and what the corpus (`host-tests/fuzz-corpus/*.case`) stores:
//! the first line names the target, the rest is the input (a seed in decimal for the targets
//! generated from one). `tests/fuzz.rs` runs a bounded campaign and replays the corpus;
//! `scripts/fuzz.sh COUNT [SEED]` runs a long one.

use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::test_rng::XorShift as Rng;

mod buffers;
mod files;
mod fill;
mod methods;
mod plan;
pub mod values;
pub mod world;

pub use files::{random_obj, random_scene, random_spans};

/// What a case exercises (one file of this folder per family).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A scene file's text through `load_scene_str` and `LoadedScene::render` (`files.rs`).
    Scene,
    /// OBJ text through `parse_obj` and `ObjMesh::to_zscan` (`files.rs`).
    Obj,
    /// `zscan spans` input through `write_spans`, under both fill rules (`files.rs`).
    Spans,
    /// Core buffer operations generated from a seed (the input is the seed in decimal,
    /// `buffers.rs`).
    Core,
    /// The planner from a seed: `plan`, `plan_frame` and `draw_plan` with random memory on a
    /// random scene of hard meshes (`plan.rs`).
    Plan,
    /// Every hidden-surface method from a seed, against the z-buffer (`methods.rs`).
    Methods,
    /// The polygon fill under both rules and `ConvexWindow` from a seed, against the exact
    /// reference (`fill.rs`).
    Fill,
}

impl Target {
    /// Every target, in the order a campaign takes them in turn.
    pub const ALL: [Target; 7] = [
        Target::Scene,
        Target::Obj,
        Target::Spans,
        Target::Core,
        Target::Plan,
        Target::Methods,
        Target::Fill,
    ];

    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            Target::Scene => "scene",
            Target::Obj => "obj",
            Target::Spans => "spans",
            Target::Core => "core",
            Target::Plan => "plan",
            Target::Methods => "methods",
            Target::Fill => "fill",
        }
    }

    /// The target of a name.
    pub fn from_name(s: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.name() == s)
    }

    /// The target's place in [`Target::ALL`].
    pub fn index(self) -> usize {
        Target::ALL.iter().position(|&t| t == self).unwrap_or(0)
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

/// What running a case gave, compared between two runs for determinism: `Ok` when the input
/// was accepted (the fingerprint of what it drew), `Err` with the error's text when it was
/// refused.
type Outcome = Result<Vec<u64>, String>;

/// Runs a case twice and checks it; `Ok(accepted)` says whether the input was accepted, `Err`
/// describes the violated property.
pub fn check(case: &Case) -> Result<bool, String> {
    let run = || catch_unwind(AssertUnwindSafe(|| run_case(case)));
    let first = run().map_err(|p| format!("panic: {}", panic_text(&p)))?;
    let second = run().map_err(|p| format!("panic (second run): {}", panic_text(&p)))?;
    let a = first?;
    let b = second?;
    if a != b {
        return Err("not deterministic: two runs differ".into());
    }
    Ok(a.is_ok())
}

fn panic_text(p: &Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(non-string panic)".into())
}

/// One run: `Ok(outcome)` (errors of the input are part of the outcome), or `Err` for a
/// violated property (a write outside a buffer, a picture other than the reference's).
fn run_case(case: &Case) -> Result<Outcome, String> {
    let seed = || {
        case.input
            .trim()
            .parse::<u64>()
            .map_err(|e| format!("the input is not a seed: {e}"))
    };
    match case.target {
        Target::Scene => Ok(files::run_scene(&case.input)),
        Target::Obj => Ok(files::run_obj(&case.input)),
        Target::Spans => Ok(files::run_spans(&case.input)),
        Target::Core => buffers::run_core(seed()?).map(Ok),
        Target::Plan => plan::run(seed()?),
        Target::Methods => methods::run(seed()?),
        Target::Fill => fill::run(seed()?),
    }
}

/// FNV-1a over words: the fingerprint of a picture or a list of counts.
fn hash(words: impl IntoIterator<Item = u64>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in words {
        h = (h ^ b).wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The `k`-th case of the campaign seeded with `seed` (the targets of [`Target::ALL`] in
/// turn).
pub fn generate(seed: u64, k: u64) -> Case {
    let mut rng = Rng::new(seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    for _ in 0..4 {
        rng.next_u64();
    }
    let target = Target::ALL[(k % Target::ALL.len() as u64) as usize];
    let input = match target {
        Target::Scene => files::random_scene(&mut rng),
        Target::Obj => files::random_obj(&mut rng),
        Target::Spans => files::random_spans(&mut rng),
        Target::Core | Target::Plan | Target::Methods | Target::Fill => rng.next_u64().to_string(),
    };
    Case { target, input }
}

/// The number of targets.
pub const TARGETS: usize = Target::ALL.len();

/// The result of a campaign.
#[derive(Debug, Default)]
pub struct Report {
    /// Cases run.
    pub cases: u64,
    /// Cases per target ([`Target::ALL`]'s order) whose input was accepted (no error).
    pub accepted: [u64; TARGETS],
    /// Time spent per target ([`Target::ALL`]'s order).
    pub time: [std::time::Duration; TARGETS],
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
                    "progress: {} cases (up to index {k}) in {:.1?}, accepted per target = {:?}, {} failures",
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
        let t = case.target.index();
        report.time[t] += took;
        if report.slowest.as_ref().is_none_or(|(_, t)| took > *t) {
            report.slowest = Some((case.clone(), took));
        }
        match checked {
            Ok(accepted) => report.accepted[t] += accepted as u64,
            Err(e) => report.failures.push((case, e)),
        }
    }
    std::panic::set_hook(hook);
    report
}
