//! `zscan spans` end to end: the built binary on standard input and on files. Expectations are
//! worked out by hand (in the comments) or given by the independent reference
//! (`zscan_host::reference::exact_fill`).

use std::io::Write;
use std::process::{Command, Output, Stdio};
use zscan_host::reference::exact_fill as reference;

fn zscan() -> Command {
    Command::new(env!("CARGO_BIN_EXE_zscan"))
}

/// Runs `zscan spans <args>` with `input` on standard input.
fn run_stdin(args: &[&str], input: &str) -> Output {
    let mut child = zscan()
        .arg("spans")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn zscan");
    let written = child.stdin.take().unwrap().write_all(input.as_bytes());
    // A refused argument ends the tool before it reads its input: the write may then find
    // the pipe closed, and the tool's status and message say why.
    if let Err(e) = written {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
    }
    child.wait_with_output().expect("wait zscan")
}

/// Runs `zscan spans <args> FILE` with `input` written to a temporary file.
fn run_file(args: &[&str], input: &str, name: &str) -> Output {
    let dir = std::env::temp_dir().join(format!("zscan-spans-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, input).unwrap();
    let out = zscan()
        .arg("spans")
        .args(args)
        .arg(&path)
        .output()
        .expect("run zscan");
    let _ = std::fs::remove_file(&path);
    out
}

fn ok_stdout(out: &Output) -> String {
    assert!(
        out.status.success(),
        "zscan failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

fn failure_stderr(out: &Output) -> String {
    assert!(!out.status.success(), "zscan should have failed");
    assert!(out.stdout.is_empty(), "no output expected on error");
    String::from_utf8(out.stderr.clone()).unwrap()
}

/// The polygon of TIPE's annex (figure 8), in the text's vertex order.
const ANNEX: &str = "\
17 0
15 2
13 2
11 0
9 4
7 2
5 2
1 0
5 4
1 8
1 12
5 10
8 10
10 6
13 12
16 12
18 14
20 13
20 8
17 8
21 4
";

/// The annex's pixels, from the text's xG/xD tables (row y covers xG[y,k] ..= xD[y,k]):
/// row 0 has only empty pairs (1,0) (11,10) (17,16); row 6's pairs (3,9) (10,18) touch and
/// merge into one run (the text's sorted list "(3, 19)"); row 4 is "(5, 21)"; row 13 "(17, 20)".
const ANNEX_SPANS: &str = "\
polygon 0
1 2 2
1 11 11
1 16 17
2 3 6
2 10 18
3 4 7
3 10 19
4 5 20
5 4 19
6 3 18
7 2 9
7 11 17
8 1 8
8 11 19
9 1 8
9 12 19
10 1 4
10 12 19
11 1 2
11 13 19
12 16 19
13 17 19
";

#[test]
fn tipe_annex_on_stdin_and_file() {
    assert_eq!(
        ok_stdout(&run_stdin(&["--subpixel-bits", "0"], ANNEX)),
        ANNEX_SPANS
    );
    // Integers are multiples of 1/16 too: same output at the default S = 4.
    assert_eq!(ok_stdout(&run_stdin(&[], ANNEX)), ANNEX_SPANS);
    assert_eq!(
        ok_stdout(&run_file(&["--subpixel-bits", "0"], ANNEX, "annex.txt")),
        ANNEX_SPANS
    );
    // Reverse vertex order, decimals with trailing zeros, CRLF line ends: same pixels.
    let rev: String = ANNEX
        .lines()
        .rev()
        .map(|l| {
            let (x, y) = l.split_once(' ').unwrap();
            format!("{x}.000 {y}.0\r\n")
        })
        .collect();
    assert_eq!(
        ok_stdout(&run_file(&[], &rev, "annex-rev.txt")),
        ANNEX_SPANS
    );
}

#[test]
fn subpixel_triangles() {
    // (0.5, 0.5) (8.5, 0.5) (0.5, 4.5): rows 0.5 ≤ y < 4.5 are 1..=4; the left side x = 0.5
    // starts every row at 1; the hypotenuse x = 8.5 − 2(y − 0.5) is 7.5, 5.5, 3.5, 1.5 on
    // rows 1..=4, so the rows end at 7, 5, 3, 1.
    let out = run_stdin(&[], "0.5 0.5\n8.5 0.5\n0.5 4.5\n");
    assert_eq!(ok_stdout(&out), "polygon 0\n1 1 7\n2 1 5\n3 1 3\n4 1 1\n");

    // (0.5, -0.5) (4.5, 3.5) (-1.5, 3.5): rows 0..=3. Right side x = y + 1 goes through the
    // lattice points (1,0) (2,1) (3,2) (4,3), which are out (right edge); left side
    // x = 0.25 − y/2 is 0.25, −0.25, −0.75, −1.25 → first pixels 1, 0, 0, −1.
    // Row 0: 1 ≤ x < 1, empty. Row 1: 0..=1. Row 2: 0..=2. Row 3: −1..=3.
    let want = "polygon 0\n1 0 1\n2 0 2\n3 -1 3\n";
    let tri = "0.5 -0.5\n4.5 3.5\n-1.5 3.5\n";
    assert_eq!(ok_stdout(&run_stdin(&[], tri)), want);
    let rev = "-1.5 3.5\n4.5 3.5\n0.5 -0.5\n";
    assert_eq!(ok_stdout(&run_stdin(&["--subpixel-bits", "1"], rev)), want);

    // (0, 0) (2, 4) (−2, 4) with S = 1: left side x = −y/2 has lattice points at even rows
    // (in), right side x = y/2 too (out). Row 0: 0 ≤ x < 0, empty. Row 1: [−0.5, 0.5) → 0.
    // Row 2: [−1, 1) → −1..=0. Row 3: [−1.5, 1.5) → −1..=1.
    let out = run_stdin(&["--subpixel-bits", "1"], "0 0\n2 4\n-2 4\n");
    assert_eq!(ok_stdout(&out), "polygon 0\n1 0 0\n2 -1 0\n3 -1 1\n");
}

#[test]
fn comments_and_several_polygons() {
    let input = "\
# Three polygons; comments anywhere.

0 0   # the square [0,2]²
2 0
# a comment line inside a polygon does not end it
2 2
0 2



# a polygon of two vertices covers nothing
5 5
6 6
  \t
1.5 0.5 # the square [1.5,3.5] × [0.5,2.5]
3.5 0.5
3.5 2.5
1.5 2.5";
    // Square [0,2]²: rows 0, 1 and columns 0, 1 (right and bottom sides out).
    // Square [1.5,3.5] × [0.5,2.5]: rows 1, 2 and columns 2, 3.
    let want = "polygon 0\n0 0 1\n1 0 1\npolygon 1\npolygon 2\n1 2 3\n2 2 3\n";
    assert_eq!(ok_stdout(&run_stdin(&[], input)), want);
    assert_eq!(ok_stdout(&run_file(&[], input, "three.txt")), want);
    // Empty input: no polygon, no output.
    assert_eq!(ok_stdout(&run_stdin(&[], "")), "");
    assert_eq!(ok_stdout(&run_stdin(&[], "\n# nothing\n\n")), "");
}

#[test]
fn bad_input_names_the_line() {
    let cases: &[(&[&str], &str, &[&str])] = &[
        (&[], "0 0\n1 0.1\n0 1\n", &["line 2", "multiple"]),
        (
            &["--subpixel-bits", "2"],
            "0 0\n1 0\n0.125 1\n",
            &["line 3", "multiple"],
        ),
        (
            &["--subpixel-bits", "0"],
            "# c\n0 0\n1 0\n0 0.5\n",
            &["line 4", "multiple"],
        ),
        (&[], "0 0\nabc 1\n0 1\n", &["line 2", "abc"]),
        (&[], "0 0\n1 1e3\n", &["line 2", "1e3"]),
        (&[], "0 0\n\n\n1 2 3\n", &["line 4"]),
        (&[], "0 0\n7\n", &["line 2"]),
        (&[], "0 0\n1 0\n20000000 1\n", &["line 3", "out of range"]),
        (
            &["--subpixel-bits", "0"],
            "0 0\n1 -268435456\n",
            &["line 2", "out of range"],
        ),
        (&["--subpixel-bits", "17"], "0 0\n", &["subpixel"]),
    ];
    for (args, input, needles) in cases {
        let err = failure_stderr(&run_stdin(args, input));
        for n in *needles {
            assert!(err.contains(n), "{input:?}: stderr {err:?} lacks {n:?}");
        }
    }
    // A valid polygon before the error is not printed either.
    let err = failure_stderr(&run_stdin(&[], "0 0\n4 0\n0 4\n\n0 0\nx y\n"));
    assert!(err.contains("line 6"), "{err}");
    // A missing file is named.
    let out = zscan()
        .args(["spans", "/nonexistent/zscan-polygons.txt"])
        .output()
        .unwrap();
    let err = failure_stderr(&out);
    assert!(err.contains("/nonexistent/zscan-polygons.txt"), "{err}");
    // Over capacity: a zigzag of 1100 non-horizontal edges (more than the CLI's 1024).
    let mut zig = String::new();
    for i in 0..1100 {
        zig.push_str(&format!("{} {}\n", (i % 2) * 10, i));
    }
    let err = failure_stderr(&run_stdin(&["--subpixel-bits", "0"], &zig));
    assert!(err.contains("1024") && err.contains("line 1"), "{err}");
    // The same after a valid polygon: nothing printed, the error names polygon 1 at line 5.
    let input = format!("0 0\n4 0\n0 4\n\n{zig}");
    let err = failure_stderr(&run_stdin(&["--subpixel-bits", "0"], &input));
    assert!(err.contains("polygon 1") && err.contains("line 5"), "{err}");
    // 1024 non-horizontal edges (plus horizontal ones, which do not count) are accepted:
    // a comb of 512 teeth, each tooth one horizontal edge and two vertical ones.
    let mut comb = String::new();
    for i in 0..512 {
        comb.push_str(&format!(
            "{} 0\n{} 0\n{} 3\n{} 3\n",
            4 * i,
            4 * i + 2,
            4 * i + 2,
            4 * i + 4
        ));
    }
    let out = ok_stdout(&run_stdin(&["--subpixel-bits", "0"], &comb));
    let v: Vec<(i64, i64)> = (0..512)
        .flat_map(|i| [(4 * i, 0), (4 * i + 2, 0), (4 * i + 2, 3), (4 * i + 4, 3)])
        .collect();
    let mut want = String::from("polygon 0\n");
    for sp in reference::covered_spans(&v, 0) {
        want.push_str(&format!("{} {} {}\n", sp.y, sp.x0, sp.x1 - 1));
    }
    assert_eq!(out, want);
    // At the largest coordinates, accepted.
    let big = "268435455 268435455\n268435450 268435455\n268435455 268435450\n";
    let out = ok_stdout(&run_stdin(&["--subpixel-bits", "0"], big));
    // Triangle with a right angle at (M, M), legs of 5 towards −x and −y (M = 2^28 − 1):
    // rows M−5 ≤ y < M; the hypotenuse x + y = 2M − 5 is the left side (in), x = M the right
    // side (out): row M−5+k covers M−k ..= M−1 for k = 1..=4, and row M−5 nothing.
    let m = 268435455i64;
    let want: String = std::iter::once("polygon 0\n".to_string())
        .chain((1..=4).map(|k| format!("{} {} {}\n", m - 5 + k, m - k, m - 1)))
        .collect();
    assert_eq!(out, want);
}

/// Exact decimal text of `units / 2^s` (what a user would type).
fn decimal(units: i64, s: u32) -> String {
    let a = units.unsigned_abs();
    let int = a >> s;
    let frac = a & ((1u64 << s) - 1);
    let sign = if units < 0 { "-" } else { "" };
    if frac == 0 {
        format!("{sign}{int}")
    } else {
        // frac / 2^s = frac·5^s / 10^s exactly.
        let digits = format!("{:0width$}", frac * 5u64.pow(s), width = s as usize);
        format!("{sign}{int}.{}", digits.trim_end_matches('0'))
    }
}

/// A pentagram under both rules: the nonzero rule fills its centre, the even-odd rule leaves
/// it empty. Worked by hand: on row 10, the star (10,0) (16,19) (0,7) (20,7) (4,19) has four
/// edges crossing (its horizontal edge at y = 7 counts for nothing), at x = 16·3/12 = 4,
/// 10 − 60/19 ≈ 6.84, 10 + 60/19 ≈ 13.16 and 20 − 16·3/12 = 16. Left in, right out: the
/// even-odd runs are pixels 4..=6 and 14..=15, the nonzero run 4..=15.
#[test]
fn pentagram_under_both_rules() {
    let star = "10 0\n16 19\n0 7\n20 7\n4 19\n";
    let nonzero = ok_stdout(&run_stdin(&["--subpixel-bits", "0"], star));
    let even_odd = ok_stdout(&run_stdin(
        &["--subpixel-bits", "0", "--rule", "even-odd"],
        star,
    ));
    assert!(nonzero.lines().any(|l| l == "10 4 15"), "{nonzero}");
    assert!(even_odd.lines().any(|l| l == "10 4 6"), "{even_odd}");
    assert!(even_odd.lines().any(|l| l == "10 14 15"), "{even_odd}");
    assert_eq!(even_odd.lines().filter(|l| l.starts_with("10 ")).count(), 2);
    let explicit = ok_stdout(&run_stdin(
        &["--subpixel-bits", "0", "--rule", "nonzero"],
        star,
    ));
    assert_eq!(explicit, nonzero);
    let bad = failure_stderr(&run_stdin(&["--rule", "odd"], star));
    assert!(bad.contains("even-odd") && bad.contains("nonzero"), "{bad}");
}

#[test]
fn random_polygons_match_the_reference() {
    let mut seed = 0x0123_4567_89AB_CDEFu64;
    let mut rnd = |lo: i64, hi: i64| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        lo + (seed % ((hi - lo + 1) as u64)) as i64
    };
    for s in [0u32, 3, 4, 8] {
        let mut input = String::new();
        let mut want = String::new();
        let mut want_eo = String::new();
        for k in 0..40 {
            let n = rnd(3, 9);
            let f = 1i64 << s;
            let v: Vec<(i64, i64)> = (0..n)
                .map(|_| (rnd(-12 * f, 12 * f), rnd(-12 * f, 12 * f)))
                .collect();
            for &(x, y) in &v {
                input.push_str(&format!("{} {}\n", decimal(x, s), decimal(y, s)));
            }
            input.push('\n');
            want.push_str(&format!("polygon {k}\n"));
            want_eo.push_str(&format!("polygon {k}\n"));
            for sp in reference::covered_spans(&v, s) {
                want.push_str(&format!("{} {} {}\n", sp.y, sp.x0, sp.x1 - 1));
            }
            for sp in reference::covered_spans_by(&v, s, reference::RefRule::EvenOdd) {
                want_eo.push_str(&format!("{} {} {}\n", sp.y, sp.x0, sp.x1 - 1));
            }
        }
        let bits = s.to_string();
        let out = run_stdin(&["--subpixel-bits", &bits], &input);
        assert_eq!(ok_stdout(&out), want, "S = {s}");
        let out = run_stdin(&["--subpixel-bits", &bits, "--rule", "even-odd"], &input);
        assert_eq!(ok_stdout(&out), want_eo, "S = {s}, even-odd");
        // Random polygons of 5 to 9 vertices self-intersect often: the rules must differ.
        assert_ne!(want, want_eo, "S = {s}: no case tells the rules apart");
    }
}
