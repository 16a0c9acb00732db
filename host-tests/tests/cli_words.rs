//! `zscan render` and `zscan chart` on what a newcomer or a careless user gives them: options a
//! method cannot honour, scenes whose keys are out of range or of the wrong form, pictures
//! that come out empty, a scene of many objects, a malformed chart data file. Each answer is
//! checked in words (the key, the line, the range or the cause it names), from a minimal
//! scene written here.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cli-words-{}", std::process::id()))
        .join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 path")
}

/// Runs `zscan ARGS`.
fn zscan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(args)
        .output()
        .expect("run zscan")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Writes `text` as `dir/name.toml` and returns the path.
fn scene_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(format!("{name}.toml"));
    std::fs::write(&p, text).unwrap();
    p
}

/// A centred unit cube in front of the default camera: a small scene every method draws.
const CUBE: &str = "[viewport]\nwidth = 64\nheight = 48\n\n[[object]]\ngenerator = \"cube\"\ncenter = true\nrotate_deg = [20, 30, 0]\n";

/// `zscan render SCENE -o DIR/out.png EXTRA…`.
fn render(scene: &Path, dir: &Path, extra: &[&str]) -> Output {
    let png = dir.join("out.png");
    let mut args = vec!["render", s(scene), "-o", s(&png)];
    args.extend_from_slice(extra);
    zscan(&args)
}

fn read_json(p: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

const METHODS: [&str; 6] = [
    "auto", "backface", "painter", "scanline", "warnock", "zbuffer",
];

/// `--depth-out` is written by the z-buffer alone; every other method refuses it in words,
/// named, before anything is drawn (the all-black depth picture the scan-line wrote is gone).
#[test]
fn depth_out_only_where_a_depth_buffer_is_kept() {
    let dir = out_dir("depth_out");
    let scene = scene_file(&dir, "cube", CUBE);
    for method in METHODS {
        let depth = dir.join(format!("depth-{method}.png"));
        let out = render(
            &scene,
            &dir,
            &["--visibility", method, "--depth-out", s(&depth)],
        );
        let err = stderr(&out);
        if method == "zbuffer" {
            assert!(out.status.success(), "{err}");
            let grey = zscan_host::image::read_png_rgb(&depth).unwrap();
            assert!(grey.data.contains(&255), "the nearest depth is white");
            continue;
        }
        assert_eq!(out.status.code(), Some(1), "{method}: {err}");
        assert!(
            err.contains(&format!("--depth-out: --visibility {method} keeps no "))
                && err.contains("only --visibility zbuffer writes one"),
            "{method}: {err}"
        );
        assert!(!depth.exists(), "{method}: a depth picture was written");
    }
}

/// `--bands` applies to the methods that draw in bands (z-buffer, scan-line: their stats
/// report the bands drawn); the others refuse it instead of ignoring it under a false
/// `band_rows`.
#[test]
fn bands_only_where_the_method_draws_in_bands() {
    let dir = out_dir("bands");
    let scene = scene_file(&dir, "cube", CUBE);
    for method in METHODS {
        let stats = dir.join(format!("{method}.json"));
        let out = render(
            &scene,
            &dir,
            &["--visibility", method, "--bands", "8", "--stats", s(&stats)],
        );
        let err = stderr(&out);
        match method {
            "zbuffer" | "scanline" => {
                assert!(out.status.success(), "{method}: {err}");
                let json = read_json(&stats);
                assert_eq!(json["band_rows"], 8, "{method}: {json}");
                assert_eq!(json["bands"], 6, "{method}: 48 rows in bands of 8: {json}");
            }
            "auto" => {
                assert_eq!(out.status.code(), Some(1), "{err}");
                assert!(err.contains("--bands: --visibility auto picks"), "{err}");
            }
            _ => {
                assert_eq!(out.status.code(), Some(1), "{method}: {err}");
                assert!(
                    err.contains(&format!(
                        "--bands: --visibility {method} draws the whole frame at once"
                    )),
                    "{method}: {err}"
                );
            }
        }
    }
}

/// `--stats` has the same keys for every method, `auto` included: `ram_bytes` (for `auto`,
/// the plan's total) and `method` beside the frame's counts.
#[test]
fn stats_have_the_same_keys_for_every_method() {
    let dir = out_dir("stats_keys");
    let scene = scene_file(&dir, "cube", CUBE);
    let mut keys: Option<Vec<String>> = None;
    for method in METHODS {
        let stats = dir.join(format!("{method}.json"));
        let out = render(
            &scene,
            &dir,
            &["--visibility", method, "--stats", s(&stats)],
        );
        assert!(out.status.success(), "{method}: {}", stderr(&out));
        let json = read_json(&stats);
        let obj = json.as_object().unwrap();
        let mut these: Vec<String> = obj.keys().filter(|k| *k != "plan").cloned().collect();
        these.sort();
        assert!(
            json["ram_bytes"].as_u64().is_some_and(|b| b >= 64 * 48 / 8),
            "{method}: {json}"
        );
        assert!(json["method"].is_object(), "{method}: {json}");
        if method == "auto" {
            assert_eq!(
                json["ram_bytes"], json["plan"]["buffers"]["total"],
                "{json}"
            );
        }
        match &keys {
            None => keys = Some(these),
            Some(k) => assert_eq!(k, &these, "{method}"),
        }
    }
}

/// `n` small quads in a row; `phong(k)` says which are lit per pixel by the core.
fn quads(n: usize, phong: impl Fn(usize) -> bool) -> String {
    let mut t = String::from(
        "[viewport]\nwidth = 64\nheight = 48\n\n[lighting]\nambient = 50\n\
         [[lighting.light]]\ntoward = [0, 0, 1]\nintensity = 200\n",
    );
    for k in 0..n {
        let x = (k % 16) as f64 / 8.0 - 1.0;
        let y = (k / 16) as f64 / 8.0 - 1.0;
        t += &format!(
            "\n[[object]]\ngenerator = \"quad\"\nsize = [0.1, 0.1]\ntranslate = [{x}, {y}, 0]\n"
        );
        if phong(k) {
            t += "shade = \"phong\"\nmaterial = { ramp = 0 }\n";
        }
    }
    t
}

/// A frame's error is put against an object only when that object alone fails with the same
/// error: 258 Phong objects exceed the stored triangles' 256 objects, which no one of them
/// does alone (each alone fails otherwise: Phong); one Phong object among others is named.
#[test]
fn a_frame_error_names_the_object_that_causes_it() {
    let dir = out_dir("attribution");
    let many = scene_file(&dir, "many", &quads(258, |_| true));
    for method in ["painter", "scanline", "warnock"] {
        let out = render(&many, &dir, &["--visibility", method]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(!err.contains("object 1"), "{method}: {err}");
        assert!(
            err.contains("more than 256 objects in the scene (the scene has 258;"),
            "{method}: {err}"
        );
    }
    let one = scene_file(&dir, "one", &quads(3, |k| k == 2));
    let out = render(&one, &dir, &["--visibility", "painter"]);
    let err = stderr(&out);
    assert!(
        err.contains("render: object 3 of 3: a Phong object cannot be stored"),
        "{err}"
    );
    // The z-buffer draws both.
    for scene in [&many, &one] {
        let out = render(scene, &dir, &["--visibility", "zbuffer"]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
}

/// A scene of `n` one-quad objects, each 4 lines long, the first at line 1; object `bad`
/// (1-based) has an unknown generator. Returns the text and the line of that object's
/// `generator` key.
fn many_quads(n: usize, bad: Option<usize>) -> (String, usize) {
    let mut t = String::new();
    let mut bad_line = 0;
    for k in 1..=n {
        let x = (k % 100) as f64 / 50.0 - 1.0;
        let y = (k / 100) as f64 / 100.0 - 1.0;
        let generator = if Some(k) == bad { "cone" } else { "quad" };
        if Some(k) == bad {
            bad_line = 4 * (k - 1) + 2;
        }
        t += &format!(
            "[[object]]\ngenerator = \"{generator}\"\nsize = [0.01, 0.01]\ntranslate = [{x}, {y}, 0]\n"
        );
    }
    (t, bad_line)
}

/// Loading is linear in the objects (line numbers from an index of the line breaks, not
/// counted from the top for every object): 20,000 objects load, every one of them, and an
/// error in the last names its object and the right lines. (The time is measured by hand:
/// see the commit; no time is asserted here.)
#[test]
fn a_scene_of_many_objects_loads_with_the_right_lines() {
    use zscan_host::cli::render::load_scene_str;
    let n = 20_000;
    let (text, _) = many_quads(n, None);
    let scene = load_scene_str(&text, Path::new("many.toml")).unwrap();
    assert_eq!(scene.objects.len(), n);
    assert_eq!(scene.triangles_in, 2 * n as u64);
    for bad in [1, 2, n / 2 + 1, n] {
        let (text, line) = many_quads(n, Some(bad));
        let err = load_scene_str(&text, Path::new("many.toml")).unwrap_err();
        let object_line = line - 1;
        assert!(
            err.starts_with(&format!(
                "many.toml: object {bad} (line {object_line}): `generator` (line {line}): \
                 unknown generator \"cone\""
            )),
            "{err}"
        );
    }
}

/// A minimal plan-chart data file: one point per scene with both counts, after a comment.
const PLAN_DATA: &str = "# scene,method,ram,m4,m0,kind\n\
quad,backface,76912,130199,180339,zscan\n\
cube,zbuffer,230624,334416,574387,zscan\n\
sphere,scanline16,44728,1626698,3729663,zscan\n\
bunny,zbuffer_compact,28946,3453944,9149850,zscan\n";

/// `zscan chart --plan-data` on `text`: the output and whether the SVG was written.
fn plan_chart(dir: &Path, name: &str, text: &str) -> (Output, bool) {
    let data = dir.join(format!("{name}.csv"));
    let svg = dir.join(format!("{name}.svg"));
    std::fs::write(&data, text).unwrap();
    let out = zscan(&["chart", "--plan-data", s(&data), "--out", s(&svg)]);
    (out, svg.exists())
}

/// The plan chart's data: a valid file draws; NaN, infinities, 0, negative and fractional
/// numbers, unknown scenes, methods and kinds, a wrong number of fields, a duplicate row, a
/// row without a count and an empty file are each refused with the line, the field and what
/// is accepted, and no chart is written.
#[test]
fn plan_chart_data_is_checked_field_by_field() {
    let dir = out_dir("plan_data");
    let (out, written) = plan_chart(&dir, "valid", PLAN_DATA);
    assert!(out.status.success() && written, "{}", stderr(&out));
    // A peer without a Cortex-M0 count, and a point far beyond the usual axis, still draw.
    let more = format!(
        "{PLAN_DATA}quad,TinyGL,460800,2362867,-,peer\ncube,painter,3000000000,1,-,zscan\n"
    );
    let (out, written) = plan_chart(&dir, "peer", &more);
    assert!(out.status.success() && written, "{}", stderr(&out));
    let ram = "field 3 `ram`";
    let ram_range = "is not a whole number of bytes in 1..=4294967296";
    let m4 = "field 4 `m4`";
    let m4_range =
        "is not a whole number of instructions in 1..=1000000000000 (or - where not measured)";
    // (what replaces line 3's `cube,zbuffer,230624,334416,574387,zscan`, words expected)
    let cases: Vec<(&str, Vec<String>)> = vec![
        (
            "cube,zbuffer,NaN,334416,574387,zscan",
            vec![format!("{ram} = \"NaN\" {ram_range}")],
        ),
        (
            "cube,zbuffer,inf,334416,574387,zscan",
            vec![format!("{ram} = \"inf\" {ram_range}")],
        ),
        (
            "cube,zbuffer,230624,-inf,574387,zscan",
            vec![format!("{m4} = \"-inf\" {m4_range}")],
        ),
        (
            "cube,zbuffer,230624,NaN,574387,zscan",
            vec![format!("{m4} = \"NaN\" {m4_range}")],
        ),
        (
            "cube,zbuffer,0,334416,574387,zscan",
            vec![format!("{ram} = \"0\" {ram_range}")],
        ),
        (
            "cube,zbuffer,230624,0,574387,zscan",
            vec![format!("{m4} = \"0\" {m4_range}")],
        ),
        (
            "cube,zbuffer,-230624,334416,574387,zscan",
            vec![format!("{ram} = \"-230624\"")],
        ),
        (
            "cube,zbuffer,230624,334416,-5,zscan",
            vec!["field 5 `m0` = \"-5\"".into()],
        ),
        (
            "cube,zbuffer,230624.5,334416,574387,zscan",
            vec![format!("{ram} = \"230624.5\"")],
        ),
        (
            "cube,zbuffer,8589934592,334416,574387,zscan",
            vec![format!("{ram} = \"8589934592\" {ram_range}")],
        ),
        (
            "cub,zbuffer,230624,334416,574387,zscan",
            vec!["field 1 `scene` = \"cub\" is not one of quad, cube, sphere, bunny".into()],
        ),
        (
            "cube,zbufer,230624,334416,574387,zscan",
            vec![
                "field 2 `method` = \"zbufer\" is not a zscan method: one of backface, painter, \
                 scanline, warnock, zbuffer"
                    .into(),
            ],
        ),
        (
            "cube,zbuffer,230624,334416,574387,zscn",
            vec!["field 6 `kind` = \"zscn\" is not zscan or peer".into()],
        ),
        (
            "cube,tiny gl,230624,334416,574387,peer",
            vec!["field 2 `method` = \"tiny gl\": a peer's name".into()],
        ),
        (
            "cube,zbuffer,230624,334416,574387",
            vec!["5 fields, expected 6".into()],
        ),
        (
            "cube,zbuffer,230624,334416,574387,zscan,x",
            vec!["7 fields, expected 6".into()],
        ),
        (
            "cube,zbuffer,230624,-,-,zscan",
            vec!["both - : a row needs at least one count".into()],
        ),
        (
            "quad,backface,76912,130199,180339,zscan",
            vec!["quad,backface,zscan appears twice (first on line 2)".into()],
        ),
    ];
    for (k, (row, words)) in cases.iter().enumerate() {
        let text = PLAN_DATA.replace("cube,zbuffer,230624,334416,574387,zscan", row);
        let name = format!("bad{k}");
        let (out, written) = plan_chart(&dir, &name, &text);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{row}: {err}");
        assert!(!written, "{row}: a chart was written");
        assert!(err.contains(&format!("{name}.csv:3: ")), "{row}: {err}");
        for w in words {
            assert!(err.contains(w.as_str()), "{row}: {err}\nwanted: {w}");
        }
    }
    // Files without a point, and a scene without a count on one core.
    for (name, text, words) in [
        (
            "empty",
            "",
            "no data rows (expected lines scene,method,ram,m4,m0,kind)",
        ),
        ("comments", "# only\n\n", "no data rows"),
        (
            "no_m0",
            &PLAN_DATA.replace("9149850", "-"),
            "scene bunny has no `m0` count",
        ),
    ] {
        let (out, written) = plan_chart(&dir, name, text);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{name}: {err}");
        assert!(!written && err.contains(words), "{name}: {err}");
    }
}

/// Keys out of range or of the wrong form are named with what is accepted: `scale` of two
/// numbers (serde's "did not match any variant of untagged enum ScaleKey"), a specular
/// exponent past a byte ("expected u8"), a viewport past 16 bits ("expected u16"), and every
/// other integer key (background, ambient, a light's intensity, generator counts, pixel
/// aspect, depth bits, the LUT's levels, colours and entries) past its type's range.
#[test]
fn scene_keys_are_named_with_their_range() {
    let dir = out_dir("keys");
    let cube = "[[object]]\ngenerator = \"cube\"\n";
    for (name, text, words) in [
        (
            "scale",
            format!("{cube}scale = [0.12, 0.12]\n"),
            "`scale` must be a number (uniform, `scale = 2`) or an array of three numbers \
             (per axis, `scale = [sx, sy, sz]`), got [0.12, 0.12]",
        ),
        (
            "scale_text",
            format!("{cube}scale = \"big\"\n"),
            "`scale` must be a number",
        ),
        (
            "shininess",
            format!("[lighting]\nambient = 10\n\n{cube}material = {{ n = 300 }}\n"),
            "material `n` must be in 1..=200 (the specular exponent), got 300",
        ),
        (
            "shininess_zero",
            format!("[lighting]\nambient = 10\n\n{cube}material = {{ n = 0 }}\n"),
            "must be in 1..=200 (the specular exponent), got 0",
        ),
        (
            "width",
            format!("[viewport]\nwidth = 100000\n\n{cube}"),
            "[viewport] width = 100000 is outside the supported sizes 1..=4096 pixels",
        ),
        (
            "height",
            format!("[viewport]\nheight = -1\n\n{cube}"),
            "[viewport] height = -1 is outside the supported sizes 1..=4096 pixels",
        ),
        (
            "background",
            format!("[render]\nbackground = 300\n\n{cube}"),
            "300 is outside the range 0..=255",
        ),
        (
            "depth_bits",
            format!("[render]\ndepth_bits = -16\n\n{cube}"),
            "-16 is outside the range 0..=4294967295",
        ),
        (
            "ambient",
            format!("[lighting]\nambient = 256\n\n{cube}"),
            "256 is outside the range 0..=255",
        ),
        (
            "intensity",
            format!("[[lighting.light]]\ntoward = [0, 0, 1]\nintensity = -1\n\n{cube}"),
            "-1 is outside the range 0..=255",
        ),
        (
            "segments",
            "[[object]]\ngenerator = \"sphere\"\nsegments = 70000\n".to_string(),
            "70000 is outside the range 0..=65535",
        ),
        (
            "pixel_aspect",
            format!("[viewport]\npixel_aspect = [1, 65536]\n\n{cube}"),
            "65536 is outside the range 0..=65535",
        ),
        (
            "lut_levels",
            format!("[lut]\nlevels = 256\n\n{cube}"),
            "256 is outside the range 0..=255",
        ),
        (
            "lut_entries",
            format!("[lut]\nentries = [[0, 1, 2, 999]]\n\n{cube}"),
            "999 is outside the range 0..=255",
        ),
        (
            "lut_colours",
            format!("[lut]\ncolours = [[1, 2]]\n\n{cube}"),
            "expected 3 integers, got 2",
        ),
    ] {
        let scene = scene_file(&dir, name, &text);
        let out = render(&scene, &dir, &[]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{name}: {err}");
        assert!(err.contains(words), "{name}: {err}");
        assert!(
            !err.contains("expected u") && !err.contains("variant"),
            "{name}: {err}"
        );
    }
    // The accepted forms still load.
    for scale in ["2", "0.5", "[1, 2, 0.5]"] {
        let scene = scene_file(&dir, "scale_ok", &format!("{cube}scale = {scale}\n"));
        let out = render(&scene, &dir, &[]);
        assert!(out.status.success(), "{scale}: {}", stderr(&out));
    }
}

/// An empty picture is drawn (exit 0) with a warning on standard error naming its cause:
/// every object beyond `far`, the camera inside a culled object, no object at all. A picture
/// with something in it has no warning.
#[test]
fn an_empty_picture_says_why() {
    let dir = out_dir("empty");
    let cube = "[[object]]\ngenerator = \"cube\"\ncenter = true\n";
    for (name, text, words) in [
        (
            "far",
            format!("[camera]\neye = [0, 0, 30]\n\n{cube}"),
            "the picture is empty: every object lies beyond [camera] far = 10 (the nearest at \
             depth 29.500)",
        ),
        (
            "inside",
            format!("[camera]\neye = [0, 0, 0.1]\ntarget = [0, 0, -1]\nnear = 0.05\n\n{cube}"),
            "the picture is empty: the camera is inside object 1 (its faces are seen from \
             behind and culled; cull = false draws them)",
        ),
        (
            "nothing",
            "[viewport]\nwidth = 32\nheight = 32\n".to_string(),
            "the picture is empty: the scene has no objects",
        ),
    ] {
        let scene = scene_file(&dir, name, &text);
        for method in ["zbuffer", "auto"] {
            let out = render(&scene, &dir, &["--visibility", method]);
            let err = stderr(&out);
            assert!(out.status.success(), "{name} {method}: {err}");
            assert!(
                err.contains(&format!("zscan render: warning: {words}")),
                "{name} {method}: {err}"
            );
        }
    }
    let scene = scene_file(&dir, "cube", CUBE);
    let out = render(&scene, &dir, &[]);
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "{}",
        stderr(&out)
    );
}
