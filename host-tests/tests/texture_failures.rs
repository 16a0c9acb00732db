//! `zscan failures --textures` and the accuracy of the texture modes on SCENES.md's textured
//! scenes (`zscan_host::texture_failures`):
//! - the counts the tool prints are the pixels whose texel differs between the core's frames of
//!   the two modes, counted here from frames read back with other numbered textures than the
//!   tool's, and its pictures mark exactly those pixels over the bench case's frame;
//! - the exact mode shows, on the cube and the sphere, the texel of the exact rational
//!   reference (`reference::exact_texture`) at every covered pixel, from the renderer's own
//!   projected corners: 0 differences (the random triangles and views of `tests/textures.rs`
//!   are the other half of that claim);
//! - against the `f64` definition of SCENES.md the exact mode shows another texel at fewer
//!   than 2 % of the pixels (sub-pixel vertices, I16F16 coordinates and 16-bit weights round
//!   where a pixel centre lies near a texel edge), the affine mode at most of them on the
//!   floor and the cube.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use zscan::internals::Projector;
use zscan::output::Framebuffer;
use zscan::raster::triangle::twice_area;
use zscan::texture::{Texture, TextureMode, Texturing};
use zscan_host::cli::bench::cases;
use zscan_host::image::read_png_rgb;
use zscan_host::reference::exact_fill;
use zscan_host::reference::exact_texture::{fold, texel_at, weights};
use zscan_host::texture_failures::{reference, TexScene};

const W: usize = cases::WIDTH as usize;
const H: usize = cases::HEIGHT as usize;
const S: u32 = 4;

/// What the `encode`-numbered texture (64 × 64, `encode(i, j)`) shows at every pixel of
/// `scene` in `mode` (0: uncovered), and the storage after the frame (its vertex scratch).
fn numbered_frame(
    scene: TexScene,
    mode: TextureMode,
    encode: impl Fn(usize, usize) -> u8,
) -> (Vec<u8>, Box<cases::Storage>) {
    let texels: Vec<u8> = (0..64 * 64).map(|k| encode(k % 64, k / 64)).collect();
    let texturing = Texturing {
        texture: Texture::new(&texels, 64, 64).unwrap(),
        mode,
        shades: None,
    };
    let mut st = storage();
    let mut px = vec![0u8; W * H];
    let mut fb = Framebuffer::new(&mut px, W as u16, H as u16).unwrap();
    cases::scene::textured::frame_with(&mut fb, &mut st, scene.tables(), texturing);
    (px, st)
}

/// The bench cases' storage on the heap. `Storage::new` builds it by value (the firmware's
/// way, without an allocator), more than a test thread's 2 MiB stack holds with its copy in an
/// optimised build: it is built on a thread of its own with room for it.
fn storage() -> Box<cases::Storage> {
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| Box::new(cases::Storage::new()))
        .unwrap()
        .join()
        .unwrap()
}

/// The texel each pixel shows, as one number `64·j + i` (`None`: uncovered), read through two
/// textures holding the low and the high three bits of `i` and `j`.
fn texel_ids(scene: TexScene, mode: TextureMode) -> Vec<Option<u16>> {
    let (low, _) = numbered_frame(scene, mode, |i, j| 1 + (i & 7 | (j & 7) << 3) as u8);
    let (high, _) = numbered_frame(scene, mode, |i, j| 1 + (i >> 3 | (j >> 3) << 3) as u8);
    low.iter()
        .zip(&high)
        .map(|(&l, &h)| {
            assert_eq!(l == 0, h == 0, "coverage differs between the two frames");
            (l > 0).then(|| {
                let (l, h) = ((l - 1) as u16, (h - 1) as u16);
                (l & 7 | (h & 7) << 3) + 64 * (l >> 3 | (h >> 3) << 3)
            })
        })
        .collect()
}

/// The bench case's frame (grey levels).
fn case_frame(name: &str) -> Vec<u8> {
    let case = cases::CASES.iter().find(|c| c.name == name).unwrap();
    let mut st = storage();
    let mut px = vec![0u8; W * H];
    let mut fb = Framebuffer::new(&mut px, W as u16, H as u16).unwrap();
    (case.run)(&mut fb, &mut st);
    px
}

/// The standard output of `zscan ARGS PATH`, which must succeed.
fn zscan(args: &[&str], path: &Path) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .args(args)
        .arg(path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn out_dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("texture-failures-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn the_tool_counts_and_marks_the_texels_the_modes_disagree_on() {
    let dir = out_dir();
    let text = zscan(
        &["failures", "--textures", "--scale", "1", "--out-dir"],
        &dir,
    );
    // `| `name.png` | caption | count |`
    let counts: HashMap<String, usize> = text
        .lines()
        .filter_map(|l| {
            let f: Vec<&str> = l.split('|').map(str::trim).collect();
            let name = f.get(1)?.strip_prefix('`')?.strip_suffix(".png`")?;
            Some((name.to_string(), f.get(3)?.parse().ok()?))
        })
        .collect();
    let modes = [
        ("sub16", TextureMode::Subdivided16),
        ("affine", TextureMode::Affine),
    ];
    let mut checked = 0;
    for scene in TexScene::ALL {
        let short = scene.name().trim_start_matches("tex_");
        let exact = texel_ids(scene, TextureMode::Exact);
        assert_eq!(counts.get(&format!("tex_{short}")), Some(&0), "{text}");
        for (word, mode) in modes {
            let name = format!("tex_{short}_{word}");
            let Some(&count) = counts.get(&name) else {
                continue;
            };
            let fast = texel_ids(scene, mode);
            let differs: Vec<bool> = fast
                .iter()
                .zip(&exact)
                .map(|(f, e)| {
                    assert_eq!(f.is_some(), e.is_some(), "coverage differs, {name}");
                    f != e
                })
                .collect();
            let want = differs.iter().filter(|&&d| d).count();
            assert_eq!(count, want, "{name}");
            // The picture: the case's frame in grey, the differing pixels red.
            let png = read_png_rgb(&dir.join(format!("{name}.png"))).unwrap();
            assert_eq!((png.width as usize, png.height as usize), (W, H));
            let frame = case_frame(&scene.case_name(mode));
            for (k, rgb) in png.data.chunks_exact(3).enumerate() {
                let grey = rgb[0] == rgb[1] && rgb[1] == rgb[2];
                assert_eq!(!grey, differs[k], "{name}, pixel {k}: {rgb:?}");
                if grey {
                    assert_eq!(rgb[0], frame[k], "{name}, pixel {k}");
                } else {
                    assert!(rgb[0] >= 128 && rgb[1] < 64, "{name}: {rgb:?}");
                }
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 5, "{text}");
    // The counts the docs quote: the affine floor and cube differ almost everywhere, the
    // subdivided cube at thousands of pixels, the sphere (small triangles) at few.
    assert!(counts["tex_floor_affine"] > 29_000, "{text}");
    assert!(counts["tex_cube_affine"] > 10_000, "{text}");
    assert!(counts["tex_cube_sub16"] > 1_000, "{text}");
    assert!(
        counts["tex_sphere_sub16"] < counts["tex_sphere_affine"],
        "{text}"
    );
}

#[test]
fn exact_mode_shows_the_rational_reference_texel_on_the_cube_and_sphere() {
    let camera = cases::scene::camera().unwrap();
    let origin = Projector::<4>::new(&camera)
        .unwrap()
        .weight_origin()
        .unwrap();
    for scene in [TexScene::Cube, TexScene::Sphere] {
        let ids = texel_ids(scene, TextureMode::Exact);
        let (_, st) = numbered_frame(scene, TextureMode::Exact, |i, _| i as u8);
        let mesh = scene.tables().mesh();
        let scratch = &st.vertices[..mesh.vertices().len()];
        assert!(scratch.iter().all(|p| p.outcode == 0), "{}", scene.name());
        let mut front = Vec::new();
        for (t, tri) in mesh.indices().chunks_exact(3).enumerate() {
            let p = [0, 1, 2].map(|k| scratch[tri[k] as usize]);
            if twice_area(p[0].screen, p[1].screen, p[2].screen) < 0 {
                let v = p.map(|p| (p.screen.x as i64, p.screen.y as i64));
                let uv = [0, 1, 2].map(|k| mesh.uvs()[3 * t + k]);
                let q = weights(p.map(|p| origin - p.depth as u64));
                front.push((v, uv, q));
            }
        }
        let mut compared = 0;
        for y in 0..H as i64 {
            for x in 0..W as i64 {
                let first = exact_fill::sole_cover(&front, |t| &t.0, S, (x, y)).unwrap();
                let shown = ids[y as usize * W + x as usize];
                assert_eq!(first.is_some(), shown.is_some(), "coverage at ({x},{y})");
                let Some(&(v, uv, q)) = first else { continue };
                let (i, j) = texel_at(v, S, uv, q, (64, 64), (x, y)).unwrap();
                let want = (fold(j, 64) * 64 + fold(i, 64)) as u16;
                assert_eq!(shown, Some(want), "{} at ({x},{y})", scene.name());
                compared += 1;
            }
        }
        assert!(compared > 15_000, "{}: {compared}", scene.name());
    }
}

/// Pixels both cover and, of those, pixels whose texel is not the `f64` definition's.
fn against_f64(scene: TexScene, mode: TextureMode) -> (usize, usize) {
    let ids = texel_ids(scene, mode);
    let reference = reference(scene).unwrap();
    let (mut both, mut other) = (0, 0);
    for (id, r) in ids.iter().zip(&reference) {
        if let (Some(id), Some(r)) = (id, r) {
            both += 1;
            other += usize::from(*id != r.texel.1 as u16 * 64 + r.texel.0 as u16);
        }
    }
    (both, other)
}

#[test]
fn exact_mode_follows_the_f64_definition_on_the_cube_and_sphere() {
    for scene in [TexScene::Cube, TexScene::Sphere] {
        let (both, other) = against_f64(scene, TextureMode::Exact);
        assert!(both > 15_000, "{}: {both}", scene.name());
        assert!(other * 50 < both, "{}: {other} of {both}", scene.name());
        let (_, affine) = against_f64(scene, TextureMode::Affine);
        assert!(
            affine > 2 * other,
            "{}: {affine} against {other}",
            scene.name()
        );
    }
    let (both, affine) = against_f64(TexScene::Cube, TextureMode::Affine);
    assert!(affine * 2 > both, "{affine} of {both}");
}

/// The floor is clipped: its clipped corners' texture coordinates must be those of the clip
/// point in the scene (coordinates are affine in 3D), not the screen interpolant's value there
/// (right for a Gouraud level, wrong for a texture: with it, 30,060 of 30,064 pixels showed
/// another texel, off by up to half the grid). Now every pixel shows the definition's texel or
/// its neighbour, and about one in ten the neighbour (3,140 of 30,064): a clipped corner carries
/// its coordinates rounded to Q8.8, a quarter of a texel of this 64-texel grid, which the
/// cube's and the sphere's unclipped corners do not.
#[test]
fn exact_mode_follows_the_f64_definition_on_the_clipped_floor() {
    let ids = texel_ids(TexScene::Floor, TextureMode::Exact);
    let reference = reference(TexScene::Floor).unwrap();
    let wrapped = |a: u16, b: u16| {
        let d = (i32::from(a) - i32::from(b)).rem_euclid(64);
        d.min(64 - d)
    };
    let (mut both, mut other) = (0, 0);
    for (id, r) in ids.iter().zip(&reference) {
        if let (Some(id), Some(r)) = (id, r) {
            both += 1;
            let (u, v) = (u16::from(r.texel.0), u16::from(r.texel.1));
            let far = wrapped(id % 64, u).max(wrapped(id / 64, v));
            assert!(far <= 1, "texel {id} where the definition has ({u}, {v})");
            other += usize::from(far != 0);
        }
    }
    assert!(both > 30_000, "{both}");
    assert!(other * 8 < both, "{other} of {both}");
}

/// `zscan chart --textures --no-measure`: one row per scene and mode whose count of texels
/// differing from the exact mode is the one counted here (0 for the exact mode itself), and
/// the Cortex-M4 column is read from a saved `zscan bench --no-host` table.
#[test]
fn the_texture_chart_table_states_the_counts() {
    let dir = out_dir();
    let table = dir.join("m4.txt");
    std::fs::write(
        &table,
        "case              pixels | Cortex-M4 instr  /px ~cycles | checksum\n\
         frame_tex_cube     16019 |   3524987   220.0   5000000 | 01234567\n\
         frame_tex_cube_sub8 16019 |  12035232   751.3  15000000 | 01234567\n",
    )
    .unwrap();
    let text = zscan(&["chart", "--textures", "--no-measure", "--m4"], &table);
    let modes = [
        ("exact", TextureMode::Exact),
        ("sub16", TextureMode::Subdivided16),
        ("sub8", TextureMode::Subdivided8),
        ("affine", TextureMode::Affine),
    ];
    let mut rows = 0;
    for scene in TexScene::ALL {
        let exact = texel_ids(scene, TextureMode::Exact);
        for (word, mode) in modes {
            let row: Vec<&str> = text
                .lines()
                .map(|l| l.split('|').map(str::trim).collect::<Vec<_>>())
                .find(|f| f.get(1) == Some(&scene.name()) && f.get(2) == Some(&word))
                .unwrap_or_else(|| panic!("no row {} {word}:\n{text}", scene.name()));
            let ids = texel_ids(scene, mode);
            let want = ids.iter().zip(&exact).filter(|(a, b)| a != b).count();
            let shown: usize = row[6].split_whitespace().next().unwrap().parse().unwrap();
            assert_eq!(shown, want, "{} {word}", scene.name());
            if mode == TextureMode::Exact {
                assert_eq!(shown, 0);
            }
            let m4 = match (scene, mode) {
                (TexScene::Cube, TextureMode::Exact) => "3524987",
                (TexScene::Cube, TextureMode::Subdivided8) => "12035232",
                _ => "-",
            };
            assert_eq!(row[5], m4, "{} {word}", scene.name());
            rows += 1;
        }
    }
    assert_eq!(rows, 12);
}
