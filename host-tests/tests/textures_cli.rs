//! `zscan render`'s texture keys end to end (the built binary): `scenes/textured.toml` is the
//! frame the core draws of the same objects built here from the core's own tables (the grid's
//! formula, the generators' coordinates, the core's shade table over the grey palette), an
//! OBJ file's `vt` give the generator's picture, indexed and RGB PNGs are read by the stated
//! rules, and bad textures, modes, scales and coordinates are refused in words.

use std::path::{Path, PathBuf};
use std::process::Command;

use zscan::geometry::generators::{uv_sphere_sizes, uv_sphere_uvs, UNIT_CUBE_UVS};
use zscan::geometry::mesh::{Mesh, PolygonSizes, TexCoord};
use zscan::output::{DepthBuffer, Framebuffer};
use zscan::render::{PreparedVertex, RenderStats, Renderer};
use zscan::scene::{Intensities, Object};
use zscan::texture::{shade_table, ShadeTable, Texture, TextureMode, Texturing};
use zscan_host::cli::render::{load_scene, ShadeKey};
use zscan_host::image::read_png_rgb;

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("textures-cli-{}", std::process::id()))
        .join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `zscan render scene -o out.png extra…`; `Ok(palette indices)` (the grey palette's
/// red channel) or `Err(stderr)`.
fn render(scene: &Path, extra: &[&str]) -> Result<Vec<u8>, String> {
    let png = scene.with_extension(format!("{}.png", extra.join("").replace('-', "")));
    let out = Command::new(env!("CARGO_BIN_EXE_zscan"))
        .arg("render")
        .arg(scene)
        .arg("-o")
        .arg(&png)
        .args(extra)
        .output()
        .expect("run zscan");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{err}");
    if !out.status.success() {
        return Err(err);
    }
    let img = read_png_rgb(&png).unwrap();
    Ok(img.data.chunks_exact(3).map(|p| p[0]).collect())
}

/// SCENES.md's grid: texel `(i, j)` of 64 × 64.
fn grid(i: usize, j: usize) -> u8 {
    if i % 8 == 0 || j % 8 == 0 {
        0
    } else if ((i >> 3) + (j >> 3)) % 2 == 0 {
        255
    } else {
        96
    }
}

fn grid_texels() -> Vec<u8> {
    (0..64 * 64).map(|k| grid(k % 64, k / 64)).collect()
}

/// An 8-bit PNG of `w × h` pixels of colour type `colour` (`data` its samples), with
/// `palette` for an indexed one.
fn write_png(path: &Path, w: u32, h: u32, colour: png::ColorType, data: &[u8], palette: &[u8]) {
    let file = std::fs::File::create(path).unwrap();
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    enc.set_color(colour);
    enc.set_depth(png::BitDepth::Eight);
    if !palette.is_empty() {
        enc.set_palette(palette.to_vec());
    }
    enc.write_header().unwrap().write_image_data(data).unwrap();
}

fn differing(a: &[u8], b: &[u8]) -> usize {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).filter(|(x, y)| x != y).count()
}

/// `textured.toml` drawn by the CLI (whole, in bands, by back faces alone) is the frame the
/// core draws of its objects with the texture, coordinates, modes and shade table built here
/// from their definitions (the placed positions and the host lighting are taken from the
/// loaded scene: they are not what this test is about).
#[test]
fn textured_scene_is_the_core_frame_of_the_same_objects() {
    let path = scenes().join("textured.toml");
    let loaded = load_scene(&path).unwrap();
    assert_eq!(loaded.objects.len(), 3);
    let texels = grid_texels();
    let grey: [[u8; 3]; 256] = std::array::from_fn(|i| [i as u8; 3]);
    let shades: Vec<u8> = shade_table::<{ 32 * 256 }>(&grey).to_vec();
    // Floor: the quad's (0,0), (1,0), (1,1), (0,1) times uv_scale = [4, 8].
    let floor: Vec<TexCoord> = vec![[0, 0], [1024, 0], [1024, 2048], [0, 2048]];
    let cube: Vec<TexCoord> = UNIT_CUBE_UVS.to_vec();
    let mut sphere = vec![[0i16; 2]; uv_sphere_sizes(32, 16).1];
    uv_sphere_uvs(32, 16, &mut sphere).unwrap();
    let specs = [
        (floor, TextureMode::Exact, true),
        (cube, TextureMode::Exact, true),
        (sphere, TextureMode::Subdivided16, false),
    ];
    let camera = loaded.camera;
    let (w, h) = (camera.viewport().width, camera.viewport().height);
    let renderer = Renderer::<4>::new(&camera).unwrap();
    let mut px = vec![0u8; w as usize * h as usize];
    let mut zs = vec![0u16; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut px, w, h).unwrap();
    let mut zb = DepthBuffer::new(&mut zs, w, h).unwrap();
    fb.clear(loaded.background);
    zb.clear();
    for (o, (uvs, mode, lit)) in loaded.objects.iter().zip(&specs) {
        let sizes = o.uniform.map_or(PolygonSizes::PerPolygon(&o.sizes), |n| {
            PolygonSizes::Uniform(n)
        });
        let mesh = Mesh::new(&o.vertices, &o.indices, sizes)
            .unwrap()
            .with_uvs(uvs)
            .unwrap();
        let mut object = Object::new(mesh);
        object.intensities = if o.shade == ShadeKey::Flat {
            Intensities::PerPolygon(&o.intensities)
        } else {
            Intensities::PerVertex(&o.intensities)
        };
        object.cull_back_faces = o.cull;
        object.texture = Some(Texturing {
            texture: Texture::new(&texels, 64, 64).unwrap(),
            mode: *mode,
            shades: lit.then(|| ShadeTable::new(&shades, 32).unwrap()),
        });
        let mut scratch = vec![PreparedVertex::<4>::default(); o.vertices.len()];
        renderer
            .draw_object(
                &object,
                &mut scratch,
                &mut fb,
                &mut zb,
                &mut RenderStats::default(),
            )
            .unwrap();
    }
    let covered = zs.iter().filter(|&&z| z != u16::MAX).count();
    assert!(covered > 30_000, "{covered}");
    let dir = out_dir("scene");
    let copy = dir.join("textured.toml");
    std::fs::copy(&path, &copy).unwrap();
    std::fs::copy(scenes().join("grid64.png"), dir.join("grid64.png")).unwrap();
    for extra in [
        &[][..],
        &["--bands", "7"],
        &["--visibility", "backface"],
        &["--visibility", "auto", "--ram-budget", "40000"],
    ] {
        let cli = render(&copy, extra).unwrap();
        assert_eq!(differing(&cli, &px), 0, "{extra:?}");
    }
    // The floor and the cube go through the shade table: their pixels take values the grid
    // does not have.
    let values: std::collections::BTreeSet<u8> = px.iter().copied().collect();
    assert!(values.len() > 10, "{values:?}");
    // The mode is the file's: the floor drawn affinely is another picture.
    let affine = dir.join("affine.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(
        &affine,
        text.replace(
            "uv_scale = [4, 8]",
            "uv_scale = [4, 8]\ntexture_mode = \"affine\"",
        ),
    )
    .unwrap();
    let cli = render(&affine, &[]).unwrap();
    let d = differing(&cli, &px);
    assert!(d > 1000, "{d}");
}

/// The unit cube as an OBJ file whose `vt` are the core's `UNIT_CUBE_UVS` (written with OBJ's
/// `v` up, `1 − v`), in `v/vt/vn` and `v/vt` corners: the picture of the generator's cube.
#[test]
fn obj_texture_coordinates_give_the_generators_picture() {
    use zscan::geometry::generators::{UNIT_CUBE_INDICES, UNIT_CUBE_VERTICES};
    let dir = out_dir("obj");
    std::fs::copy(scenes().join("grid64.png"), dir.join("grid64.png")).unwrap();
    let mut obj = String::new();
    for v in UNIT_CUBE_VERTICES {
        let b = v.bits();
        obj += &format!("v {} {} {}\n", b[0] >> 16, b[1] >> 16, b[2] >> 16);
    }
    for [u, v] in UNIT_CUBE_UVS {
        obj += &format!("vt {} {}\n", u as f64 / 256.0, 1.0 - v as f64 / 256.0);
    }
    obj += "vn 0 0 1\n";
    for (f, face) in UNIT_CUBE_INDICES.chunks(4).enumerate() {
        obj += "f";
        for (k, &i) in face.iter().enumerate() {
            let t = 4 * f + k + 1;
            obj += &if f % 2 == 0 {
                format!(" {}/{t}/1", i + 1)
            } else {
                format!(" {}/{t}", i + 1)
            };
        }
        obj += "\n";
    }
    std::fs::write(dir.join("cube.obj"), obj).unwrap();
    let scene = |source: &str| {
        format!(
            "[render]\nshade = \"flat\"\n[[object]]\n{source}\ncenter = true\nscale = 1.2\n\
             rotate_deg = [25, 35, 0]\ntexture = \"grid64.png\"\nuv_scale = 2\n"
        )
    };
    let (a, b) = (dir.join("generator.toml"), dir.join("obj.toml"));
    std::fs::write(&a, scene("generator = \"cube\"")).unwrap();
    std::fs::write(&b, scene("obj = \"cube.obj\"")).unwrap();
    let (pa, pb) = (render(&a, &[]).unwrap(), render(&b, &[]).unwrap());
    assert!(pa.iter().filter(|&&p| p != 0).count() > 5_000);
    assert_eq!(differing(&pa, &pb), 0);
}

/// A mirroring scale reverses each polygon and its coordinates together: the mirrored cube
/// (scale `[−s, s, s]`, the turn about `y` reversed) is the mirror image of the cube, texels
/// included, up to the pixels whose centres lie on an edge or a texel boundary (the fill rule
/// and the floors are not mirror-symmetric).
#[test]
fn a_mirrored_object_shows_its_texture_mirrored() {
    let dir = out_dir("mirror");
    std::fs::copy(scenes().join("grid64.png"), dir.join("grid64.png")).unwrap();
    let scene = |scale: &str, turn: i32| {
        format!(
            "[render]\nbackground = 7\n[[object]]\ngenerator = \"cube\"\ncenter = true\n\
             scale = {scale}\nrotate_deg = [20, {turn}, 0]\ntexture = \"grid64.png\"\n\
             texture_lit = false\n"
        )
    };
    let (a, b) = (dir.join("plain.toml"), dir.join("mirrored.toml"));
    std::fs::write(&a, scene("1.4", 30)).unwrap();
    std::fs::write(&b, scene("[-1.4, 1.4, 1.4]", -30)).unwrap();
    let (pa, pb) = (render(&a, &[]).unwrap(), render(&b, &[]).unwrap());
    let flipped: Vec<u8> = pb
        .chunks_exact(320)
        .flat_map(|row| row.iter().rev().copied())
        .collect();
    let covered = pa.iter().filter(|&&p| p != 7).count();
    let d = differing(&pa, &flipped);
    assert!(covered > 10_000, "{covered}");
    assert!(d * 100 < covered, "{d} of {covered}");
}

/// An indexed PNG is taken as its indices (its own palette unread); an RGB one is mapped to
/// the nearest palette entry: both give the grey PNG's picture. A 3 × 1 texture (not a power
/// of two) clamps: at `uv_scale = 2` the last texel covers `u ≥ 2/3` of the quad.
#[test]
fn png_kinds_are_read_by_the_stated_rules() {
    let dir = out_dir("kinds");
    let scene = |file: &str, scale: f64| {
        format!(
            "[render]\nbackground = 7\n[[object]]\ngenerator = \"quad\"\nrotate_deg = [0, 0, 10]\n\
             texture = \"{file}\"\ntexture_lit = false\nuv_scale = {scale}\n"
        )
    };
    let texels = grid_texels();
    std::fs::copy(scenes().join("grid64.png"), dir.join("grey.png")).unwrap();
    // Indexed, with a palette of reds that the scene's grey palette overrides.
    let reds: Vec<u8> = (0..256).flat_map(|i| [i as u8, 0, 0]).collect();
    write_png(
        &dir.join("indexed.png"),
        64,
        64,
        png::ColorType::Indexed,
        &texels,
        &reds,
    );
    // RGB off the greys by at most 1 per channel: the nearest grey is the texel.
    let rgb: Vec<u8> = texels
        .iter()
        .flat_map(|&t| [t.saturating_add(1), t, t.saturating_sub(1)])
        .collect();
    write_png(&dir.join("rgb.png"), 64, 64, png::ColorType::Rgb, &rgb, &[]);
    let mut pictures = Vec::new();
    for file in ["grey.png", "indexed.png", "rgb.png"] {
        let path = dir.join(file.replace(".png", ".toml"));
        std::fs::write(&path, scene(file, 3.0)).unwrap();
        pictures.push(render(&path, &[]).unwrap());
    }
    let shown: std::collections::BTreeSet<u8> = pictures[0].iter().copied().collect();
    assert_eq!(shown, [0, 7, 96, 255].into());
    assert_eq!(differing(&pictures[0], &pictures[1]), 0);
    assert_eq!(differing(&pictures[0], &pictures[2]), 0);

    // Indices packed below 8 bits: 2-bit `[3, 0, 2, 1]`, a quarter of the quad each.
    {
        let file = std::fs::File::create(dir.join("packed.png")).unwrap();
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), 4, 1);
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Two);
        enc.set_palette(vec![9; 12]);
        let mut w = enc.write_header().unwrap();
        w.write_image_data(&[0b11_00_10_01]).unwrap();
    }
    let path = dir.join("packed.toml");
    std::fs::write(&path, scene("packed.png", 1.0)).unwrap();
    let p = render(&path, &[]).unwrap();
    let count = |v: u8| p.iter().filter(|&&x| x == v).count() as f64;
    let covered = p.iter().filter(|&&x| x != 7).count() as f64;
    for v in 0..4 {
        let s = count(v) / covered;
        assert!((s - 0.25).abs() < 0.01, "index {v}: {s} of {covered}");
    }
    // Columns left to right are 3, 0, 2, 1: the quad's left edge (u = 0) shows index 3.
    let row = 120 * 320;
    let first = p[row..row + 320].iter().find(|&&x| x != 7);
    assert_eq!(first, Some(&3));

    write_png(
        &dir.join("three.png"),
        3,
        1,
        png::ColorType::Grayscale,
        &[10, 20, 30],
        &[],
    );
    let path = dir.join("three.toml");
    std::fs::write(&path, scene("three.png", 2.0)).unwrap();
    let p = render(&path, &[]).unwrap();
    let count = |v: u8| p.iter().filter(|&&x| x == v).count() as f64;
    let covered = count(10) + count(20) + count(30);
    assert_eq!(covered as usize, p.iter().filter(|&&x| x != 7).count());
    // Texel 0 covers u < 1/3 of [0, 2], texel 1 1/3 ≤ u < 2/3, texel 2 the rest: 1/6, 1/6, 2/3
    // of the quad's area (a square seen head-on, turned 10° on screen).
    for (v, share) in [(10, 1.0 / 6.0), (20, 1.0 / 6.0), (30, 2.0 / 3.0)] {
        let s = count(v) / covered;
        assert!((s - share).abs() < 0.01, "texel {v}: {s} of {covered}");
    }
}

/// Runs `zscan render` on `text` written as `name` beside the grid; expects a failure naming
/// the file and returns its message.
fn fails(name: &str, text: &str) -> String {
    let dir = out_dir("errors");
    std::fs::copy(scenes().join("grid64.png"), dir.join("grid64.png")).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let err = render(&path, &[]).expect_err(name);
    assert!(err.contains(name), "{name}: {err}");
    err
}

#[test]
fn bad_textures_are_refused_in_words() {
    let dir = out_dir("errors");
    let cube = "[[object]]\ngenerator = \"cube\"\n";
    let textured = format!("{cube}texture = \"grid64.png\"\n");

    let err = fails(
        "missing.toml",
        &format!("{cube}texture = \"nowhere.png\"\n"),
    );
    assert!(
        err.contains("object 1 (line 1)")
            && err.contains("`texture` (line 3)")
            && err.contains("nowhere.png: cannot read"),
        "{err}"
    );
    // Too wide: the core's limit, named with the file.
    write_png(
        &dir.join("wide.png"),
        1025,
        1,
        png::ColorType::Grayscale,
        &[0; 1025],
        &[],
    );
    let err = fails("wide.toml", &format!("{cube}texture = \"wide.png\"\n"));
    assert!(
        err.contains("wide.png: 1025 × 1 texels: a texture's sides are 1..=1024 texels"),
        "{err}"
    );
    // Cut short: the file named.
    let grid = std::fs::read(scenes().join("grid64.png")).unwrap();
    std::fs::write(dir.join("short.png"), &grid[..grid.len() - 30]).unwrap();
    let err = fails("short.toml", &format!("{cube}texture = \"short.png\"\n"));
    assert!(err.contains("short.png: bad PNG data"), "{err}");
    std::fs::write(dir.join("text.png"), "not a picture").unwrap();
    let err = fails("text.toml", &format!("{cube}texture = \"text.png\"\n"));
    assert!(err.contains("text.png: not a PNG image"), "{err}");

    let err = fails("mode.toml", &format!("{textured}texture_mode = \"fast\"\n"));
    assert!(
        err.contains("fast") && err.contains("exact") && err.contains("sub16"),
        "{err}"
    );
    for (name, scale, words) in [
        ("scale0.toml", "0", "factor 0 is outside 0 < factor ≤ 127"),
        (
            "scale200.toml",
            "[1, 200]",
            "factor 200 is outside 0 < factor ≤ 127",
        ),
        ("scale-nan.toml", "nan", "factor NaN is outside"),
        ("scale3.toml", "[1, 2, 3]", "`uv_scale` must be a number"),
    ] {
        let err = fails(name, &format!("{textured}uv_scale = {scale}\n"));
        assert!(err.contains(words), "{name}: {err}");
    }
    let err = fails("untextured.toml", &format!("{cube}uv_scale = 2\n"));
    assert!(
        err.contains("`uv_scale` applies to a textured object"),
        "{err}"
    );
    for (key, name) in [
        ("opacity = 8", "opacity.toml"),
        ("blend = 0.5", "blend.toml"),
        ("dither = true", "dither.toml"),
        ("wireframe = \"all\"", "wire.toml"),
    ] {
        let err = fails(name, &format!("{textured}{key}\n"));
        let key = key.split(' ').next().unwrap();
        assert!(
            err.contains(&format!("a textured object takes no `{key}`")),
            "{err}"
        );
    }
    let err = fails(
        "bunny.toml",
        "[[object]]\nbuiltin = \"bunny\"\ntexture = \"grid64.png\"\n",
    );
    assert!(err.contains("the mesh has no texture coordinates"), "{err}");

    // OBJ coordinates past Q8.8, and faces without them: the OBJ line named.
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    std::fs::write(
        dir.join("far.obj"),
        format!("{tri}vt 0 0\nvt 300 0\nf 1/1 2/2 3/1\n"),
    )
    .unwrap();
    std::fs::write(dir.join("bare.obj"), format!("{tri}f 1 2 3\n")).unwrap();
    let obj = |file: &str| format!("[[object]]\nobj = \"{file}\"\ntexture = \"grid64.png\"\n");
    let err = fails("far.toml", &obj("far.obj"));
    assert!(
        err.contains(
            "far.obj: texture coordinates: line 5: texture coordinate u = 300 is \
                      outside the core's Q8.8 range"
        ),
        "{err}"
    );
    // In range as read, out of range once scaled.
    std::fs::write(
        dir.join("big.obj"),
        format!("{tri}vt 0 0\nvt 100 0\nf 1/1 2/2 3/1\n"),
    )
    .unwrap();
    let err = fails("big.toml", &format!("{}uv_scale = 2\n", obj("big.obj")));
    assert!(
        err.contains("coordinate 100 times 2 is 200, outside the core's Q8.8 range"),
        "{err}"
    );
    let err = fails("bare.toml", &obj("bare.obj"));
    assert!(
        err.contains("no face names texture coordinates (vt)"),
        "{err}"
    );
    // Without a texture the same files load.
    let path = dir.join("far-untextured.toml");
    std::fs::write(&path, "[[object]]\nobj = \"far.obj\"\n").unwrap();
    render(&path, &[]).unwrap();
}

/// The methods that do not draw textures refuse them in the core's words, naming the object;
/// so does the core for a core-lit Phong texture.
#[test]
fn methods_refuse_textures_in_the_core_words() {
    let path = scenes().join("textured.toml");
    for method in ["painter", "scanline", "warnock"] {
        let err = render(&path, &["--visibility", method]).expect_err(method);
        assert!(
            err.contains(
                "object 1 of 3: the object is textured, which a visibility method that \
                 stores triangles does not draw"
            ),
            "{method}: {err}"
        );
    }
    let dir = out_dir("errors");
    std::fs::copy(scenes().join("grid64.png"), dir.join("grid64.png")).unwrap();
    let phong = dir.join("phong.toml");
    std::fs::write(
        &phong,
        "[lighting]\nambient = 20\n[[lighting.light]]\ntoward = [1, 1, 1]\nintensity = 200\n\
         [[object]]\ngenerator = \"cube\"\nmaterial = { kd = 0.7 }\nshade = \"phong\"\n\
         texture = \"grid64.png\"\n",
    )
    .unwrap();
    let err = render(&phong, &[]).expect_err("phong");
    assert!(
        err.contains("object 1: a textured object cannot be drawn: Phong shading does not combine"),
        "{err}"
    );
}
