//! `zscan render` end to end: the built binary on the scenes of `host-tests/scenes`, outputs
//! written under `target/` (`CARGO_TARGET_TMPDIR`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use zscan_host::image::read_png_rgb;

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("render-cli-{}", std::process::id()))
        .join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn zscan(args: &[&Path]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_zscan"));
    c.arg("render");
    for a in args {
        c.arg(a);
    }
    c.output().expect("run zscan")
}

/// Renders `scene` into `dir` with image, depth image and stats; returns them.
fn render(scene: &Path, dir: &Path, extra: &[&str]) -> (PathBuf, PathBuf, serde_json::Value) {
    let (png, depth, stats) = (
        dir.join("out.png"),
        dir.join("depth.png"),
        dir.join("stats.json"),
    );
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .arg("render")
        .arg(scene)
        .arg("-o")
        .arg(&png)
        .arg("--depth-out")
        .arg(&depth)
        .arg("--stats")
        .arg(&stats)
        .args(extra)
        .output()
        .expect("run zscan");
    assert!(
        out.status.success(),
        "{}: {}",
        scene.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let json = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    (png, depth, json)
}

fn n(v: &serde_json::Value, key: &str) -> i64 {
    v[key]
        .as_i64()
        .unwrap_or_else(|| panic!("stats key {key} missing: {v}"))
}

/// Pixels that are not black (the standard scenes' background; lit pixels are ≥ 26).
fn lit_pixels(png: &Path) -> usize {
    let img = read_png_rgb(png).unwrap();
    img.data.chunks_exact(3).filter(|p| p != &[0, 0, 0]).count()
}

#[test]
fn example_and_demo_render_with_sane_stats() {
    for name in ["example", "demo"] {
        let dir = out_dir(name);
        let (png, depth, s) = render(&scenes().join(format!("{name}.toml")), &dir, &[]);
        let img = read_png_rgb(&png).unwrap();
        assert_eq!((img.width, img.height), (320, 240), "{name}");
        let d = read_png_rgb(&depth).unwrap();
        assert_eq!((d.width, d.height), (320, 240), "{name}");
        assert!(
            d.data.contains(&255) && d.data.contains(&0),
            "{name}: depth range"
        );
        assert_eq!(
            (n(&s, "width"), n(&s, "height"), n(&s, "bands")),
            (320, 240, 1)
        );
        assert_eq!(
            n(&s, "depth_bits"),
            if name == "demo" { 16 } else { 32 },
            "{name}"
        );
        let drawn = n(&s, "triangles_drawn");
        assert!(drawn > 100 && drawn <= n(&s, "triangles_in"), "{name}: {s}");
        assert!(n(&s, "culled") > 0 && n(&s, "culled") < n(&s, "polygons_in"));
        let (cov, wr) = (n(&s, "pixels_covered"), n(&s, "pixels_written"));
        assert!(wr <= cov && cov > 10_000 && wr > 10_000, "{name}: {s}");
        // Objects: several distinct colours on screen.
        let mut colours: Vec<&[u8]> = img.data.chunks_exact(3).collect();
        colours.sort();
        colours.dedup();
        assert!(colours.len() > 50, "{name}: {} colours", colours.len());
    }
}

#[test]
fn standard_scenes_match_scenes_md() {
    // SCENES.md: coverage with exact arithmetic (zscan snaps to 1/16 pixel: within ±20).
    for (name, pixels, drawn) in [
        ("quad", 76_800, Some(2)),
        ("cube", 16_014, Some(6)),
        ("sphere", 22_000, None),
        ("bunny", 11_462, None),
    ] {
        let dir = out_dir(&format!("standard_{name}"));
        let scene = scenes().join(format!("standard_{name}.toml"));
        let (png, _, s) = render(&scene, &dir, &[]);
        let lit = lit_pixels(&png) as i64;
        assert!((lit - pixels).abs() <= 20, "{name}: {lit} pixels drawn");
        if name != "bunny" {
            // Convex: covered pixels are the silhouette, each written once.
            let cov = n(&s, "pixels_covered");
            assert!((cov - pixels).abs() <= 20, "{name}: {s}");
            assert_eq!(n(&s, "pixels_written"), cov, "{name}");
        }
        if let Some(t) = drawn {
            assert_eq!(n(&s, "triangles_drawn"), t, "{name}");
        }
        assert_eq!(n(&s, "clipped") + n(&s, "rejected"), 0, "{name}");
    }
}

#[test]
fn bands_give_the_same_pictures_as_one_pass() {
    let scene = scenes().join("demo.toml");
    let (png1, depth1, s1) = render(&scene, &out_dir("bands-1"), &[]);
    for rows in ["1", "7", "64", "1000"] {
        let (png, depth, s) = render(
            &scene,
            &out_dir(&format!("bands-{rows}")),
            &["--bands", rows],
        );
        assert_eq!(
            std::fs::read(&png).unwrap(),
            std::fs::read(&png1).unwrap(),
            "{rows}"
        );
        assert_eq!(
            std::fs::read(&depth).unwrap(),
            std::fs::read(&depth1).unwrap(),
            "{rows}"
        );
        assert_eq!(n(&s, "pixels_written"), n(&s1, "pixels_written"), "{rows}");
        assert_eq!(n(&s, "pixels_covered"), n(&s1, "pixels_covered"), "{rows}");
        let bands = (240 + n(&s, "band_rows") - 1) / n(&s, "band_rows");
        assert_eq!(n(&s, "bands"), bands, "{rows}");
    }
}

/// Runs `zscan render` on `text` written to a scene file; expects failure, returns stderr.
fn fails(name: &str, text: &str) -> String {
    let dir = out_dir("errors");
    let scene = dir.join(name);
    std::fs::write(&scene, text).unwrap();
    let out = zscan(&[&scene, Path::new("-o"), &dir.join(format!("{name}.png"))]);
    assert!(!out.status.success(), "{name} should fail");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{name}: {err}");
    assert!(
        err.contains(name),
        "{name}: message should name the file: {err}"
    );
    err
}

#[test]
fn bad_scenes_fail_with_messages_naming_the_problem() {
    let err = fails("syntax.toml", "[camera]\neye = [0, 0,\n");
    assert!(err.contains("line"), "{err}");

    let err = fails(
        "generator.toml",
        "[camera]\nfov_deg = 50.0\n\n[[object]]\ngenerator = \"blob\"\n",
    );
    assert!(err.contains("unknown generator \"blob\""), "{err}");
    assert!(err.contains("line 5"), "{err}");

    let err = fails("key.toml", "[render]\ndepht_bits = 16\n");
    assert!(err.contains("depht_bits"), "{err}");

    let err = fails("depth.toml", "[render]\ndepth_bits = 24\n");
    assert!(err.contains("depth_bits"), "{err}");

    let err = fails("axis.toml", "[camera]\nfov_axis = \"sideways\"\n");
    assert!(err.contains("sideways"), "{err}");

    let err = fails("obj.toml", "[[object]]\nobj = \"no-such-mesh.obj\"\n");
    assert!(err.contains("no-such-mesh.obj"), "{err}");

    let err = fails(
        "param.toml",
        "[[object]]\ngenerator = \"cube\"\nradius = 2.0\n",
    );
    assert!(err.contains("radius"), "{err}");

    let err = fails(
        "material.toml",
        "[lut]\nkind = \"shaded\"\ncolours = [[255, 0, 0]]\n[[object]]\ngenerator = \"cube\"\nmaterial = 3\n",
    );
    assert!(err.contains("material 3"), "{err}");

    // The core's lighting: materials, lights, Phong.
    let lit = "[[object]]\ngenerator = \"cube\"\nmaterial = { ka = 0.2, kd = 0.7 }\n";
    let err = fails("no-lighting.toml", lit);
    assert!(err.contains("[lighting]"), "{err}");
    let err = fails(
        "phong-unlit.toml",
        "[[object]]\ngenerator = \"cube\"\nshade = \"phong\"\n",
    );
    assert!(err.contains("phong") && err.contains("line 1"), "{err}");
    let err = fails(
        "coefficient.toml",
        &format!("[lighting]\n{}", lit.replace("0.7", "2.5")),
    );
    assert!(err.contains("`kd` must be in [0, 2)"), "{err}");
    let err = fails(
        "shininess.toml",
        "[lighting]\n[[object]]\ngenerator = \"cube\"\nmaterial = { n = 0 }\n",
    );
    assert!(err.contains("`n` must be in 1..=200"), "{err}");
    let err = fails(
        "two-kinds.toml",
        "[lighting]\n[[lighting.light]]\npoint = [1, 2, 3]\ntoward = [0, 1, 0]\nintensity = 9\n",
    );
    assert!(
        err.contains("exactly one of `point`, `toward` or `spot`"),
        "{err}"
    );
    let light = "[[lighting.light]]\ntoward = [0, 1, 0]\nintensity = 9\n";
    let err = fails(
        "five-lights.toml",
        &format!("[lighting]\n{}", light.repeat(5)),
    );
    assert!(err.contains("5 lights (at most 4)"), "{err}");
    let err = fails(
        "zero-toward.toml",
        "[lighting]\n[[lighting.light]]\ntoward = [0, 0, 0]\nintensity = 9\n",
    );
    assert!(err.contains("must not be zero"), "{err}");

    // Spots and attenuation: keys that belong together, ranges in words.
    let spot = |keys: &str| {
        format!(
            "[lighting]\n[[lighting.light]]\nspot = [0, 3, 0]\nintensity = 200\n{keys}\n\
             [[object]]\ngenerator = \"cube\"\nmaterial = {{ kd = 0.7 }}\n"
        )
    };
    let err = fails("spot-no-axis.toml", &spot("cone = [10, 20]"));
    assert!(err.contains("needs `axis"), "{err}");
    let err = fails(
        "spot-cone.toml",
        &spot("axis = [0, -1, 0]\ncone = [20, 20.5]"),
    );
    assert!(
        err.contains("light 0") && err.contains("cone out of range"),
        "{err}"
    );
    let err = fails(
        "spot-cone-degrees.toml",
        &spot("axis = [0, -1, 0]\ncone = [10, 120]"),
    );
    assert!(err.contains("within [0, 90]"), "{err}");
    let err = fails(
        "spot-zero-axis.toml",
        &spot("axis = [0, 0, 0]\ncone = [10, 20]"),
    );
    assert!(err.contains("`axis` must not be zero"), "{err}");
    let err = fails(
        "attenuation.toml",
        &spot("axis = [0, -1, 0]\ncone = [10, 20]\nattenuation = [0.5, 0, 0]"),
    );
    assert!(err.contains("constant in [1, 256]"), "{err}");
    let err = fails(
        "attenuation-toward.toml",
        "[lighting]\n[[lighting.light]]\ntoward = [0, 1, 0]\nattenuation = [1, 0, 0]\nintensity = 9\n",
    );
    assert!(err.contains("no `attenuation`"), "{err}");
    let err = fails(
        "axis-on-point.toml",
        "[lighting]\n[[lighting.light]]\npoint = [0, 1, 0]\naxis = [1, 0, 0]\nintensity = 9\n",
    );
    assert!(err.contains("belong to a `spot`"), "{err}");

    // A scene file that does not exist.
    let dir = out_dir("errors");
    let missing = dir.join("missing-scene.toml");
    let out = zscan(&[&missing, Path::new("-o"), &dir.join("missing.png")]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("missing-scene.toml") && err.contains("cannot read"),
        "{err}"
    );
}

/// `--visibility`: the scan-line draws the bunny's z-buffer picture, back faces alone the
/// convex standard sphere's; the stats name the method; methods without a depth buffer refuse
/// `--depth-out`; an unknown method is named with the choices.
#[test]
fn visibility_methods_from_the_command_line() {
    let dir = out_dir("visibility");
    for (scene, method) in [
        ("standard_bunny.toml", "scanline"),
        ("standard_sphere.toml", "backface"),
        ("standard_bunny.toml", "warnock"),
    ] {
        let path = scenes().join(scene);
        let (z_png, _, _) = render(&path, &dir.join("z"), &[]);
        let png = dir.join(format!("{method}.png"));
        let stats = dir.join(format!("{method}.json"));
        let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
            .args([
                "render",
                path.to_str().unwrap(),
                "-o",
                png.to_str().unwrap(),
            ])
            .args(["--stats", stats.to_str().unwrap(), "--visibility", method])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(
            read_png_rgb(&png).unwrap(),
            read_png_rgb(&z_png).unwrap(),
            "{scene} {method}"
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
        assert_eq!(json["visibility"], method);
        // Every method reports its caller memory: at least the 320 × 240 frame or band.
        assert!(json["ram_bytes"].as_u64().unwrap() > 320, "{json}");
        if method == "warnock" {
            let windows = &json["method"];
            let parts: u64 = ["empty", "one", "front", "pixel", "split"]
                .iter()
                .map(|v| windows[format!("windows_{v}")].as_u64().unwrap())
                .sum();
            assert!(
                parts > 0 && parts == windows["windows"].as_u64().unwrap(),
                "{json}"
            );
        }
    }
    let path = scenes().join("standard_sphere.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args([
            "render",
            path.to_str().unwrap(),
            "-o",
            dir.join("p.png").to_str().unwrap(),
        ])
        .args([
            "--depth-out",
            dir.join("d.png").to_str().unwrap(),
            "--visibility",
            "painter",
        ])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("keeps no depth buffer"));
    // The stored-triangle methods keep levels, not normals: the demo's Phong object is named.
    let demo = scenes().join("demo.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args([
            "render",
            demo.to_str().unwrap(),
            "-o",
            dir.join("p.png").to_str().unwrap(),
        ])
        .args(["--visibility", "scanline"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("a Phong object cannot be stored"));
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args([
            "render",
            path.to_str().unwrap(),
            "-o",
            dir.join("p.png").to_str().unwrap(),
        ])
        .args(["--visibility", "newell"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains("one of auto, backface, reverse-painter, painter, scanline, warnock, zbuffer"));
}

/// Runs `zscan render SCENE -o OUT --stats JSON --visibility auto EXTRA…`.
fn auto(scene: &str, dir: &Path, extra: &[&str]) -> (Output, PathBuf, PathBuf) {
    let (png, stats) = (
        dir.join(format!("{scene}.png")),
        dir.join(format!("{scene}.json")),
    );
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(["render", scenes().join(scene).to_str().unwrap()])
        .args([
            "-o",
            png.to_str().unwrap(),
            "--stats",
            stats.to_str().unwrap(),
        ])
        .args(["--visibility", "auto"])
        .args(extra)
        .output()
        .unwrap();
    (out, png, stats)
}

/// The smallest plan of the standard bunny: compact bands of one row of 16-bit depth, 8 bytes
/// per vertex and a byte per polygon (its levels are given per vertex: no level bytes).
const BUNNY_COMPACT_ONE_ROW: usize = 8 * 1839 + 3674 + 3 * 320;

/// `--visibility auto [--ram-budget BYTES]`: the plan and its reasons printed, the stats with
/// the method, the plan and every buffer's bytes, the z-buffer's picture; a budget too small
/// is refused with the bytes needed.
#[test]
fn auto_plans_within_a_ram_budget() {
    let dir = out_dir("auto");
    for (scene, method, budget) in [
        ("standard_quad.toml", "backface", None),
        // The scene file's cube is the core's quad mesh, its rounded quads not planar: the
        // per-view check decides on the fans drawn (`visibility/facts.rs`).
        ("standard_cube.toml", "backface", None),
        ("standard_sphere.toml", "backface", Some("100K")),
        ("standard_bunny.toml", "zbuffer", None),
        ("standard_bunny.toml", "zbuffer", Some("100000")),
        // Compact bands: 8 bytes per vertex and a byte per polygon (`render/compact.rs`).
        ("standard_bunny.toml", "zbuffer", Some("32K")),
    ] {
        let (z_png, _, _) = render(&scenes().join(scene), &dir.join("z"), &[]);
        let extra: Vec<&str> = budget.map_or(vec![], |b| vec!["--ram-budget", b]);
        let (out, png, stats) = auto(scene, &dir, &extra);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            stdout.contains(&format!("plan: method {method} (")),
            "{stdout}"
        );
        assert!(stdout.contains("plan: bytes: frame "), "{stdout}");
        assert_eq!(
            read_png_rgb(&png).unwrap(),
            read_png_rgb(&z_png).unwrap(),
            "{scene}"
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
        assert_eq!(json["visibility"], method, "{scene}");
        let plan = &json["plan"];
        let b = &plan["buffers"];
        let sum: u64 = ["frame", "depth", "vertices", "polygons", "tables"]
            .iter()
            .map(|k| b[k].as_u64().unwrap())
            .sum();
        assert_eq!(b["total"].as_u64(), Some(sum));
        assert!(plan["method_reason"]
            .as_str()
            .is_some_and(|r| !r.is_empty()));
        if let Some(limit) = budget {
            let limit = zscan_host::cli::render::parse_bytes(limit).unwrap() as u64;
            assert!(sum <= limit, "{scene}: {sum} bytes over {limit}");
        }
        if method == "backface" {
            assert_eq!(b["depth"], 0, "{scene}");
        }
    }
    // The bunny at 100,000 bytes: bands of the 32-bit z-buffer.
    let (_, _, stats) = auto("standard_bunny.toml", &dir, &["--ram-budget", "100000"]);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert!(json["plan"]["band_rows"].as_u64().unwrap() < 240);
    // 32K is too little for the bunny's full vertex scratch (51,492 bytes) but not for compact
    // bands, which the plan names and sizes.
    let (out, _, stats) = auto("standard_bunny.toml", &dir, &["--ram-budget", "32K"]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("compact bands"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(json["plan"]["buffers"]["polygons"], 3674);
    assert!(json["plan"]["buffers"]["vertices"].as_u64().unwrap() >= 8 * 1839);
    // 16K is too little even for compact bands of one row: refused, with the bytes needed.
    let (out, _, _) = auto("standard_bunny.toml", &dir, &["--ram-budget", "16K"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains(&format!("{} bytes", BUNNY_COMPACT_ONE_ROW)) && err.contains("16384 bytes"),
        "{err}"
    );
    // A malformed budget, and a budget without auto, are named.
    let (out, _, _) = auto("standard_cube.toml", &dir, &["--ram-budget", "12Q"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a byte count"));
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args([
            "render",
            scenes().join("standard_cube.toml").to_str().unwrap(),
        ])
        .args([
            "-o",
            dir.join("x.png").to_str().unwrap(),
            "--ram-budget",
            "32K",
        ])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stderr).contains("only --visibility auto"));
}

/// `[camera] projection = "orthographic"`: the orthographic bunny renders; the scan-line and
/// Warnock methods and bands draw the z-buffer's picture; the planner and perspective-only
/// keys are refused in words.
#[test]
fn orthographic_camera_from_the_command_line() {
    let dir = out_dir("orthographic");
    let path = scenes().join("orthographic_bunny.toml");
    let (z_png, _, stats) = render(&path, &dir.join("z"), &[]);
    assert!(lit_pixels(&z_png) > 5000, "{stats}");
    for extra in [
        &["--visibility", "scanline"][..],
        &["--visibility", "warnock"][..],
        &["--bands", "16"][..],
    ] {
        let png = dir.join(format!("{}.png", extra[1]));
        let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
            .args([
                "render",
                path.to_str().unwrap(),
                "-o",
                png.to_str().unwrap(),
            ])
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(
            read_png_rgb(&png).unwrap(),
            read_png_rgb(&z_png).unwrap(),
            "{extra:?}"
        );
    }
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args([
            "render",
            path.to_str().unwrap(),
            "-o",
            dir.join("a.png").to_str().unwrap(),
        ])
        .args(["--visibility", "auto"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the planner needs a perspective camera"),
        "{err}"
    );
    // Width and height together, or a width on a perspective camera, are refused.
    let text = std::fs::read_to_string(&path).unwrap();
    for (bad, words) in [
        (
            text.replace("height = 3.2", "height = 3.2\nwidth = 3.0"),
            "exactly one of `width` or",
        ),
        (
            text.replace("projection = \"orthographic\"\n", ""),
            "are for projection = \"orthographic\"",
        ),
        (
            text.replace("height = 3.2", "height = 0.0"),
            "[camera] height",
        ),
    ] {
        let scene = dir.join("bad.toml");
        std::fs::write(&scene, bad).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
            .args([
                "render",
                scene.to_str().unwrap(),
                "-o",
                dir.join("b.png").to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(words), "{words}: {err}");
    }
}

/// `spot.toml` renders, and its spot only takes light away: the same scene with the spot
/// replaced by a point light at the same place (same attenuation) is at least as bright at
/// every pixel, brighter at many (outside the cone and across its ramp) and equal at many
/// (inside the inner cone).
#[test]
fn a_spot_lights_a_cone_of_what_a_point_lights() {
    let scene = scenes().join("spot.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let dir = out_dir("spot");
    let point_scene = dir.join("spot-as-point.toml");
    let as_point = text
        .replace("spot = [", "point = [")
        .replace("axis = [1.7, -4.0, -1.3]", "")
        .replace("cone = [14.0, 24.0]", "");
    assert_ne!(as_point, text);
    std::fs::write(&point_scene, as_point).unwrap();
    let (spot_png, _, _) = render(&scene, &dir, &[]);
    let spot = read_png_rgb(&spot_png).unwrap();
    let (point_png, _, _) = render(&point_scene, &out_dir("spot-as-point"), &[]);
    let point = read_png_rgb(&point_png).unwrap();
    let sums = |img: &zscan_host::image::RgbImage| -> Vec<u32> {
        img.data
            .chunks_exact(3)
            .map(|p| p.iter().map(|&c| c as u32).sum())
            .collect()
    };
    let (s, p) = (sums(&spot), sums(&point));
    let darker = s.iter().zip(&p).filter(|(a, b)| a < b).count();
    let brighter = s.iter().zip(&p).filter(|(a, b)| a > b).count();
    let lit_equal = s
        .iter()
        .zip(&p)
        .filter(|(a, b)| a == b && **a > 200)
        .count();
    assert_eq!(brighter, 0);
    assert!(darker > 10_000, "{darker}");
    assert!(lit_equal > 1_000, "{lit_equal}");
}

/// The wireframe scenes: each mode's picture is the one in `docs/images` (looked at), the
/// hidden-line picture lies inside the front edges', which lies inside every edge's; bands and
/// other visibility methods are refused in words.
#[test]
fn wireframe_scenes_render_their_modes() {
    let dir = out_dir("wireframe");
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/images");
    let mut lit = Vec::new();
    for mode in ["all", "front", "hidden"] {
        let scene = scenes().join(format!("wireframe_{mode}.toml"));
        let png = dir.join(format!("{mode}.png"));
        let out = zscan(&[&scene, Path::new("-o"), &png]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let img = read_png_rgb(&png).unwrap();
        let golden = read_png_rgb(&docs.join(format!("wireframe_{mode}.png"))).unwrap();
        assert!(img.data == golden.data, "{mode}: differs from docs/images");
        let set: Vec<bool> = img.data.chunks_exact(3).map(|p| p != [0, 0, 0]).collect();
        lit.push(set);
    }
    let inside = |a: &[bool], b: &[bool]| a.iter().zip(b).all(|(&x, &y)| !x || y);
    let count = |a: &[bool]| a.iter().filter(|&&x| x).count();
    assert!(inside(&lit[2], &lit[1]) && inside(&lit[1], &lit[0]));
    assert!(count(&lit[2]) < count(&lit[1]) && count(&lit[1]) < count(&lit[0]));
    let scene = scenes().join("wireframe_hidden.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .arg("render")
        .arg(&scene)
        .args([
            "-o",
            dir.join("bands.png").to_str().unwrap(),
            "--bands",
            "8",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("whole-frame z-buffer"),
        "{err}"
    );
}

/// The transparency scene: drawn by the z-buffer (whole and in bands, the same picture) and
/// refused in words by the painter (its blended sphere); out-of-range `opacity` and `blend`
/// keys, or both on one object, named.
#[test]
fn transparency_keys_from_the_command_line() {
    let dir = out_dir("transparency");
    let path = scenes().join("transparency.toml");
    let (png, _, s) = render(&path, &dir, &[]);
    let (png8, _, _) = render(&path, &dir.join("bands"), &["--bands", "8"]);
    assert!(n(&s, "pixels_covered") > 30_000, "{s}");
    assert_eq!(read_png_rgb(&png).unwrap(), read_png_rgb(&png8).unwrap());
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(["render", path.to_str().unwrap(), "-o"])
        .arg(dir.join("painter.png"))
        .args(["--visibility", "painter"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("object 4 is blended, which the painter cannot draw"),
        "{err}"
    );

    let object = "[[object]]\ngenerator = \"cube\"\n";
    let err = fails("opacity.toml", &format!("{object}opacity = 17\n"));
    assert!(
        err.contains("opacity 17 is past the screen door's 16 levels"),
        "{err}"
    );
    let err = fails("blend.toml", &format!("{object}blend = 1.5\n"));
    assert!(err.contains("blend = 1.5: an opacity from 0 to 1"), "{err}");
    let err = fails("both.toml", &format!("{object}blend = 0.5\nopacity = 3\n"));
    assert!(err.contains("not both"), "{err}");
}
