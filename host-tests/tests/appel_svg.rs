//! `zscan render` with `wireframe = "appel"` and `--svg`: the SVG read back (one `<line>` per
//! visible piece, coordinates in pixels inside the view) equals the core's pieces
//! (`Renderer::appel_segments`), the raster picture is the one in `docs/images` (looked at),
//! and the refusals are in words naming the object.

use std::path::{Path, PathBuf};
use std::process::Command;

use zscan_host::cli::render::load_scene;
use zscan_host::cli::svg::appel_segments;
use zscan_host::image::read_png_rgb;

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("appel-svg-{}", std::process::id()))
        .join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn zscan(scene: &Path, extra: &[&Path]) -> std::process::Output {
    let png = scene.with_extension("png");
    Command::new(env!("CARGO_BIN_EXE_zscan"))
        .arg("render")
        .arg(scene)
        .arg("-o")
        .arg(&png)
        .args(extra)
        .output()
        .unwrap()
}

/// The value of attribute `key` in one SVG element's text.
fn attribute(element: &str, key: &str) -> f64 {
    let start = element.find(&format!(" {key}=\"")).unwrap() + key.len() + 3;
    let end = start + element[start..].find('"').unwrap();
    element[start..end].parse().unwrap()
}

#[test]
fn svg_holds_the_cores_pieces() {
    let dir = out_dir("svg");
    let scene = scenes().join("wireframe_appel.toml");
    let copy = dir.join("wireframe_appel.toml");
    std::fs::copy(&scene, &copy).unwrap();
    let svg = dir.join("out.svg");
    let out = zscan(&copy, &[Path::new("--svg"), &svg]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg ") && text.trim_end().ends_with("</svg>"));
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("<line ")).collect();
    let loaded = load_scene(&scene).unwrap();
    let pieces = appel_segments(&loaded).unwrap();
    assert!(pieces.len() > 1000, "{}", pieces.len());
    assert_eq!(lines.len(), pieces.len());
    let vp = *loaded.camera.viewport();
    for (l, (index, s)) in lines.iter().zip(&pieces) {
        assert_eq!(*index, 255);
        assert!(l.contains("stroke=\"#ffffff\""), "{l}");
        let got = ["x1", "y1", "x2", "y2"].map(|k| attribute(l, k));
        // Pixel (x, y) covers [x, x + 1): its centre, sub-pixel (16x, 16y), is at x + 0.5.
        let want = [s.from.x, s.from.y, s.to.x, s.to.y].map(|c| c as f64 / 16.0 + 0.5);
        assert_eq!(got, want, "{l}");
        for k in [0, 2] {
            assert!((0.0..=vp.width as f64).contains(&got[k]), "{l}");
            assert!((0.0..=vp.height as f64).contains(&got[k + 1]), "{l}");
        }
    }
    let img = read_png_rgb(&copy.with_extension("png")).unwrap();
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/images");
    let golden = read_png_rgb(&docs.join("wireframe_appel.png")).unwrap();
    assert!(img.data == golden.data, "differs from docs/images");
}

#[test]
fn appel_refusals_name_the_object() {
    let dir = out_dir("errors");
    let scene = dir.join("open.toml");
    let text = std::fs::read_to_string(scenes().join("wireframe_appel.toml"))
        .unwrap()
        .replace("builtin = \"bunny\"", "generator = \"quad\"");
    std::fs::write(&scene, &text).unwrap();
    let out = zscan(&scene, &[]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && !err.contains("panicked"), "{err}");
    assert!(err.contains("object 1 (wireframe \"appel\")"), "{err}");
    assert!(err.contains("held by 1 triangle"), "{err}");
    let none = dir.join("none.toml");
    std::fs::write(&none, text.replace("\"appel\"", "\"hidden\"")).unwrap();
    let out = zscan(&none, &[Path::new("--svg"), &dir.join("none.svg")]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(
        err.contains("wireframe = \"appel\": the scene has none"),
        "{err}"
    );
}
