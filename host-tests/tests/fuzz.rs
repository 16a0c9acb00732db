//! The fuzz campaigns of `zscan_host::fuzz` (docs/RELIABILITY.md): a bounded campaign on
//! every test run, the corpus replayed, and the long campaign `scripts/fuzz.sh` runs.

use std::path::PathBuf;

use zscan_host::fuzz::{campaign, check, Case};

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

/// A bounded campaign: 20,000 cases (5,000 per target) of a fixed seed.
#[test]
fn bounded_campaign() {
    let start = std::time::Instant::now();
    let report = campaign(0x5EED_2026_1201, 20_000, None);
    eprintln!(
        "fuzz: {} cases in {:?}, accepted (scene, obj, spans, core) = {:?}, time {:?}, slowest {:?}",
        report.cases,
        start.elapsed(),
        report.accepted,
        report.time,
        report.slowest
    );
    report_failures(&report);
    // The generators reach past the input checks: a fair share of each target is accepted.
    assert!(
        report.accepted.iter().all(|&a| a >= 100),
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
/// printing every input tried. Run by `scripts/fuzz.sh COUNT [SEED]`.
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
    let start = std::time::Instant::now();
    let mut out = std::io::stdout();
    let report = campaign(seed, cases, Some(&mut out));
    println!(
        "fuzz: seed {seed}: {} cases in {:?}, accepted (scene, obj, spans, core) = {:?}, {} failures",
        report.cases,
        start.elapsed(),
        report.accepted,
        report.failures.len()
    );
    report_failures(&report);
}
