//! The fuzz campaigns of `zscan_host::fuzz` (docs/RELIABILITY.md): a bounded campaign on
//! every test run, the corpus replayed, and the long campaign `scripts/fuzz.sh` runs.

use std::path::PathBuf;

use zscan_host::fuzz::{campaign, campaign_from, check, Case, Log, Target, TARGETS};

fn corpus() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fuzz-corpus")
}

/// Writes each failing case to the corpus folder (so that `corpus_replays` keeps it) and
/// fails with their list.
fn report_failures(report: &zscan_host::fuzz::Report) {
    if report.failures.is_empty() {
        return;
    }
    let mut names = Vec::new();
    for (k, (case, why)) in report.failures.iter().enumerate() {
        let name = format!("found-{}-{k}.case", case.target.name());
        let _ = std::fs::write(corpus().join(&name), case.to_file());
        names.push(format!("{name}: {why}"));
    }
    panic!("{} failing cases:\n{}", names.len(), names.join("\n"));
}

/// The targets' names, in [`Target::ALL`]'s order.
fn names() -> [&'static str; TARGETS] {
    Target::ALL.map(Target::name)
}

/// A bounded campaign: 21,000 cases (3,000 per target) of a fixed seed.
#[test]
fn bounded_campaign() {
    let start = std::time::Instant::now();
    let report = campaign(0x5EED_2026_1201, 21_000, None);
    eprintln!(
        "fuzz: {} cases in {:?}, accepted {:?} = {:?}, time {:?}, slowest {:?}",
        report.cases,
        start.elapsed(),
        names(),
        report.accepted,
        report.time,
        report.slowest
    );
    report_failures(&report);
    // The generators reach past the input checks: a share of each target is accepted (the
    // OBJ text, the most hostile, about 4 %).
    assert!(
        report.accepted.iter().all(|&a| a >= 50),
        "{:?}",
        report.accepted
    );
}

/// Every case in `host-tests/fuzz-corpus` still passes.
#[test]
fn corpus_replays() {
    let mut n = 0;
    for entry in std::fs::read_dir(corpus()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "case") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let case = Case::from_file(&text).unwrap_or_else(|| panic!("{}: bad case", path.display()));
        check(&case).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        n += 1;
    }
    assert!(n >= 10, "{n} cases");
}

/// The long campaign: `ZSCAN_FUZZ_CASES` cases (default 100,000) of `ZSCAN_FUZZ_SEED`,
/// starting at case index `ZSCAN_FUZZ_FIRST` (default 0), printing every input tried, or with
/// `ZSCAN_FUZZ_LOG=progress` a progress line every 100,000 cases. Ends with the build (overflow
/// checks on or off), the cases per target, the accepted inputs, the time per target and the
/// failures. Run by `scripts/fuzz.sh`.
#[test]
#[ignore = "long; run by scripts/fuzz.sh"]
fn long_campaign() {
    let env = |k: &str, d: u64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let (cases, seed) = (env("ZSCAN_FUZZ_CASES", 100_000), env("ZSCAN_FUZZ_SEED", 1));
    let first = env("ZSCAN_FUZZ_FIRST", 0);
    let progress = std::env::var("ZSCAN_FUZZ_LOG").is_ok_and(|v| v == "progress");
    // Overflow checks on when adding one to i32::MAX panics in this build (silently).
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let overflow_checks = std::panic::catch_unwind(|| std::hint::black_box(i32::MAX) + 1).is_err();
    std::panic::set_hook(hook);
    let start = std::time::Instant::now();
    let mut out = std::io::stdout();
    let log = if progress {
        Log::Progress(&mut out, 100_000)
    } else {
        Log::Inputs(&mut out)
    };
    let report = campaign_from(seed, first..first + cases, log);
    let per_target = |t: usize| {
        (first..first + cases)
            .filter(|k| k % TARGETS as u64 == t as u64)
            .count()
    };
    println!(
        "fuzz: seed {seed}, cases {first}..{}, overflow checks {}: {} cases in {:?}; per target \
         {:?}: run {:?}, accepted {:?}, time {:?}; slowest {:?}; {} failures",
        first + cases,
        if overflow_checks { "on" } else { "off" },
        report.cases,
        start.elapsed(),
        names(),
        core::array::from_fn::<usize, TARGETS, _>(per_target),
        report.accepted,
        report.time,
        report.slowest.as_ref().map(|(c, t)| (c.target.name(), *t)),
        report.failures.len()
    );
    report_failures(&report);
}
