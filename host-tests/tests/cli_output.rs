//! Every `zscan` subcommand on a standard output it cannot write: a full device (`/dev/full`)
//! and a pipe whose reading end is closed (`zscan … | head -1` once `head` has exited). Each
//! must answer in words on standard error with a non-zero exit, never panic (exit 101,
//! "failed printing to stdout"); a full standard error must not make it panic either.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cli-output-{}", std::process::id()))
        .join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Where standard output goes.
#[derive(Debug, Clone, Copy)]
enum Sink {
    /// `/dev/full`: every write fails with "No space left on device".
    Full,
    /// A pipe whose reading end was closed before the command started: every write fails
    /// with "Broken pipe" (Rust programs ignore SIGPIPE).
    ClosedPipe,
}

impl Sink {
    fn stdio(self) -> Stdio {
        match self {
            Sink::Full => std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .expect("/dev/full")
                .into(),
            Sink::ClosedPipe => {
                // The writing end of a pipe whose only reader, `true`, has exited.
                let mut reader = Command::new("true")
                    .stdin(Stdio::piped())
                    .spawn()
                    .expect("run true");
                let writer = reader.stdin.take().expect("the pipe's writing end");
                assert!(reader.wait().expect("wait for true").success());
                writer.into()
            }
        }
    }

    fn words(self) -> &'static str {
        match self {
            Sink::Full => "No space left on device",
            Sink::ClosedPipe => "Broken pipe",
        }
    }
}

/// Runs `zscan ARGS` with standard output to `sink`, `stdin` on standard input.
fn run(args: &[&str], sink: Sink, stdin: &str) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(sink.stdio())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run zscan");
    let mut input = child.stdin.take().expect("stdin");
    // The command may exit before reading its input; a failed write here is not the test.
    let _ = input.write_all(stdin.as_bytes());
    drop(input);
    child.wait_with_output().expect("wait for zscan")
}

/// `zscan ARGS` on each sink: exit 1 and the one message naming standard output and the
/// failure, no panic.
fn refuses_in_words(args: &[&str], stdin: &str) {
    for sink in [Sink::Full, Sink::ClosedPipe] {
        let out = run(args, sink, stdin);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?} on {sink:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?} on {sink:?}: {err}");
        assert!(
            err.contains("zscan: cannot write standard output: ") && err.contains(sink.words()),
            "{args:?} on {sink:?}: {err}"
        );
    }
}

fn s(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 path")
}

#[test]
fn render_on_failed_stdout() {
    let scene = root().join("host-tests/scenes/standard_cube.toml");
    let png = out_dir("render").join("cube.png");
    refuses_in_words(&["render", s(&scene), "-o", s(&png)], "");
    // The plan's lines come first with --visibility auto.
    refuses_in_words(
        &["render", s(&scene), "-o", s(&png), "--visibility", "auto"],
        "",
    );
}

#[test]
fn chart_on_failed_stdout() {
    let svg = out_dir("chart").join("plan.svg");
    let data = root().join("docs/plan_chart.csv");
    refuses_in_words(&["chart", "--plan-data", s(&data), "--out", s(&svg)], "");
    refuses_in_words(&["chart", "--no-measure"], "");
}

#[test]
fn failures_on_failed_stdout() {
    let dir = out_dir("failures");
    refuses_in_words(&["failures", "--out-dir", s(&dir)], "");
}

#[test]
fn export_scenes_on_failed_stdout() {
    let dir = out_dir("export");
    refuses_in_words(&["export-scenes", s(&dir)], "");
}

#[test]
fn spans_on_failed_stdout() {
    refuses_in_words(&["spans"], "0 0\n4 0\n0 4\n");
}

#[test]
fn bench_checksums_on_failed_stdout() {
    refuses_in_words(&["bench", "--checksums"], "");
}

#[test]
fn help_and_version_on_failed_stdout() {
    refuses_in_words(&["--help"], "");
    refuses_in_words(&["render", "--help"], "");
    refuses_in_words(&["--version"], "");
}

/// A full standard error (progress notes, warnings, the final message) is no panic either:
/// the exit code still tells.
#[test]
fn full_stderr_is_no_panic() {
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full")
    };
    let png = out_dir("lines").join("lines.png");
    // `zscan lines` reports on standard error only.
    let ok = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(["lines", "-o", s(&png)])
        .stderr(full())
        .status()
        .expect("run zscan");
    assert_eq!(ok.code(), Some(0));
    // An error whose message cannot be written: exit 1, not 101.
    let bad = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(["render", "no-such-scene.toml", "-o", s(&png)])
        .stdout(full())
        .stderr(full())
        .status()
        .expect("run zscan");
    assert_eq!(bad.code(), Some(1));
}

/// The same commands on a working standard output still print and exit 0 (the refusals above
/// are about the output, not the commands).
#[test]
fn the_same_commands_succeed_on_a_working_stdout() {
    let scene = root().join("host-tests/scenes/standard_cube.toml");
    let png = out_dir("ok").join("cube.png");
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(["render", s(&scene), "-o", s(&png)])
        .output()
        .expect("run zscan");
    assert!(out.status.success(), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("wrote "));
}
