//! Where the fast texture modes depart from the exact one, as counts and pictures: what
//! `zscan failures --textures` draws into `docs/images/` and `zscan chart --textures` plots
//! against the frames' instructions.
//!
//! The scenes are SCENES.md's textured ones (`tex_floor`, `tex_cube`, `tex_sphere`: the 64 × 64
//! grid, nearest texel, wrapping), drawn by the benchmark cases `frame_tex_*`
//! (`benches/cases.rs`, `scene::textured`) in each [`TextureMode`]: the very frames the
//! instruction counts measure. Course ch. 4 §2.4: what is linear in the scene is not linear on
//! screen, so the affine mode warps a face seen at a slant and the subdivided modes bend the
//! texture between their exact points (every 16 or 8 pixels along a span): the wobble.
//!
//! Which texel a pixel shows is read back from the core itself: the same frame drawn twice
//! more with unlit numbered textures, texel `(i, j)` holding `1 + i` in one and `1 + j` in the
//! other (0 is the cleared background). Against two references:
//! - **the exact mode** of the core: a pixel *differs* when its texel is not the exact mode's
//!   (the red pixels of the pictures);
//! - **the `f64` definition** of SCENES.md ([`reference()`]): the visible triangle and the
//!   Gouraud intensity from `reference::float_render`, the texture coordinate the barycentric
//!   combination at the visible 3D point (perspective-correct by construction, course ch. 4
//!   §2.4), the texel `(⌊64u⌋ mod 64, ⌊64v⌋ mod 64)` and the level `t · I / 255`. Its coverage
//!   is that of unsnapped vertices, so a few edge pixels are covered by one frame only; they are
//!   counted apart, and the texel and level comparisons run over pixels both cover.
//!
//! Everything here is host set-up and `f64` measurement; the frames are the core's.

use zscan::output::Framebuffer;
use zscan::texture::{Texture, TextureMode, Texturing};

use crate::cli::bench::cases;
use crate::reference::float_render;
use crate::scenes::{self, Scene, Vec3};

/// Texture side of the textured scenes, texels.
pub const SIDE: usize = 64;

/// The texture modes, exact first, with their short names (the bench cases' suffixes and
/// `zscan render`'s `texture_mode` values).
pub const MODES: [(TextureMode, &str); 4] = [
    (TextureMode::Exact, "exact"),
    (TextureMode::Subdivided16, "sub16"),
    (TextureMode::Subdivided8, "sub8"),
    (TextureMode::Affine, "affine"),
];

/// The short name of `mode` ([`MODES`]).
pub fn mode_name(mode: TextureMode) -> &'static str {
    MODES
        .iter()
        .find(|(m, _)| *m == mode)
        .map_or("exact", |(_, n)| n)
}

/// A triangle's corner coordinates `(u, v)` in `f64` (1.0 = the whole texture).
pub type CornerUvs = [[f64; 2]; 3];

/// SCENES.md's textured scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexScene {
    /// `tex_floor`: the plane `y = −1` receding to the horizon, 4 × 8 repeats.
    Floor,
    /// `tex_cube`: the standard cube, the texture once per face.
    Cube,
    /// `tex_sphere`: the standard UV sphere, `u` around, `v` from pole to pole.
    Sphere,
}

impl TexScene {
    /// Every textured scene, in SCENES.md's order.
    pub const ALL: [TexScene; 3] = [TexScene::Floor, TexScene::Cube, TexScene::Sphere];

    /// SCENES.md's name (`tex_floor`, …).
    pub const fn name(self) -> &'static str {
        match self {
            TexScene::Floor => "tex_floor",
            TexScene::Cube => "tex_cube",
            TexScene::Sphere => "tex_sphere",
        }
    }

    /// The bench case drawing this scene in `mode` (`frame_tex_floor`, `…_sub16`, …).
    pub fn case_name(self, mode: TextureMode) -> String {
        match mode {
            TextureMode::Exact => format!("frame_{}", self.name()),
            m => format!("frame_{}_{}", self.name(), mode_name(m)),
        }
    }

    /// The bench tables of the scene.
    pub fn tables(self) -> &'static cases::scene::StandardScene {
        match self {
            TexScene::Floor => &cases::scene::textured::FLOOR,
            TexScene::Cube => &cases::scene::textured::CUBE,
            TexScene::Sphere => &cases::scene::textured::SPHERE,
        }
    }

    /// The scene in `f64` (SCENES.md's definition, independent of the bench tables) with
    /// each triangle's corner coordinates `(u, v)` (1.0 = the whole texture).
    pub fn float_scene(self) -> Result<(Scene, Vec<CornerUvs>), String> {
        match self {
            TexScene::Floor => {
                let c = |x: f64, z: f64| [x, -1.0, z];
                let vertices = vec![c(-4.0, 2.4), c(4.0, 2.4), c(4.0, -6.5), c(-4.0, -6.5)];
                let scene = Scene {
                    name: self.name().into(),
                    camera: scenes::Camera::standard(),
                    vertices,
                    triangles: vec![[0, 1, 2], [0, 2, 3]],
                    // N = (0, 1, 0): I = round(255 · (0.1 + 0.9 / √3)) = 158.
                    intensities: vec![[scenes::intensity([0.0, 1.0, 0.0]); 3]; 2],
                    scale: 1.0,
                };
                let uv = [[0.0, 0.0], [4.0, 0.0], [4.0, 8.0], [0.0, 8.0]];
                Ok((scene, vec![[uv[0], uv[1], uv[2]], [uv[0], uv[2], uv[3]]]))
            }
            TexScene::Cube => {
                let scene = scenes::cube();
                let uvs = scene
                    .triangles
                    .iter()
                    .enumerate()
                    .map(|(t, tri)| tri.map(|i| cube_uv(t / 2, i)))
                    .collect();
                Ok((scene, uvs))
            }
            TexScene::Sphere => {
                let scene = scenes::sphere();
                let uvs = scene.triangles.iter().map(|&t| sphere_uvs(t)).collect();
                Ok((scene, uvs))
            }
        }
    }
}

/// `(u, v)` of cube corner `i` (bit 0: `x`, bit 1: `y`, bit 2: `z`, set = +0.5) on face `f`
/// of `scenes::cube` (−x, +x, −y, +y, −z, +z). Side faces: `(0, 0)` at the lower-left corner
/// seen from outside, `u` to the right, `v` up. SCENES.md fixes only the winding of the top
/// and bottom faces (counter-clockwise from outside); `u` runs along `+x` on both, as the
/// bench tables have it.
fn cube_uv(face: usize, i: usize) -> [f64; 2] {
    let bit = |k: usize| (i >> k & 1) as f64;
    let (x, y, z) = (bit(0), bit(1), bit(2));
    match face {
        0 => [z, y],
        1 => [1.0 - z, y],
        2 => [x, z],
        3 => [x, 1.0 - z],
        4 => [1.0 - x, y],
        _ => [x, y],
    }
}

/// The corners' `(u, v)` of a sphere triangle: segment `j` takes `u = j/32` (the corners that
/// close the ring, `j = 0` beside `j = 31`, take 1), ring `k` takes `v = k/16`, a pole the mean
/// `u` of the triangle's two other corners.
fn sphere_uvs(t: [usize; 3]) -> CornerUvs {
    let (seg, rings) = (scenes::SPHERE_SEGMENTS, scenes::SPHERE_RINGS);
    let south = 1 + (rings - 1) * seg;
    let pole = |i: usize| i == 0 || i == south;
    let closes = t.iter().any(|&i| !pole(i) && (i - 1) % seg == seg - 1);
    let mut uv = t.map(|i| {
        if i == 0 {
            [f64::NAN, 0.0]
        } else if i == south {
            [f64::NAN, 1.0]
        } else {
            let (k, j) = ((i - 1) / seg + 1, (i - 1) % seg);
            let j = if closes && j == 0 { seg } else { j };
            [j as f64 / seg as f64, k as f64 / rings as f64]
        }
    });
    if let Some(p) = t.iter().position(|&i| pole(i)) {
        uv[p][0] = (uv[(p + 1) % 3][0] + uv[(p + 2) % 3][0]) / 2.0;
    }
    uv
}

/// What the `f64` definition shows at a covered pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefPixel {
    /// Texel `(column, row)`, wrapped.
    pub texel: (u8, u8),
    /// The level `t · I / 255` (not rounded).
    pub level: f64,
}

/// SCENES.md's grid: texel `(i, j)`.
pub fn grid(i: usize, j: usize) -> u8 {
    if i % 8 == 0 || j % 8 == 0 {
        0
    } else if ((i >> 3) + (j >> 3)) % 2 == 0 {
        255
    } else {
        96
    }
}

/// The `f64` reference of `scene` (module doc), row-major, `None` where uncovered.
pub fn reference(scene: TexScene) -> Result<Vec<Option<RefPixel>>, String> {
    let (s, uvs) = scene.float_scene()?;
    let frame = float_render::render(&s)?;
    let cam = &s.camera;
    let (f, (cx, cy)) = (cam.focal(), cam.principal);
    let mut out = vec![None; frame.pixels.len()];
    for y in 0..frame.height {
        for x in 0..frame.width {
            let Some(frag) = frame.at(x, y) else { continue };
            let tri = s.triangles[frag.triangle];
            let [a, b, c] = tri.map(|i| cam.to_view(s.vertices[i]));
            let ray: Vec3 = [(x as f64 - cx) / f, -(y as f64 - cy) / f, 1.0];
            let p = scenes::scale(ray, frag.depth);
            // The visible point's barycentric weights in the 3D triangle.
            let n = scenes::cross(scenes::sub(b, a), scenes::sub(c, a));
            let nn = scenes::dot(n, n);
            let wb = scenes::dot(scenes::cross(scenes::sub(p, a), scenes::sub(c, a)), n) / nn;
            let wc = scenes::dot(scenes::cross(scenes::sub(b, a), scenes::sub(p, a)), n) / nn;
            let w = [1.0 - wb - wc, wb, wc];
            let uv = uvs[frag.triangle];
            let at = |k: usize| {
                let t: f64 = (0..3).map(|c| w[c] * uv[c][k]).sum();
                ((t * SIDE as f64).floor() as i64).rem_euclid(SIDE as i64) as u8
            };
            let texel = (at(0), at(1));
            let t = grid(texel.0 as usize, texel.1 as usize) as f64;
            let level = t * frag.luminance_affine / 255.0;
            out[(y * frame.width + x) as usize] = Some(RefPixel { texel, level });
        }
    }
    Ok(out)
}

/// One frame of a textured scene in one mode, as the core draws it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TexFrame {
    /// The bench case's frame (grey levels, 0 the background), row-major.
    pub pixels: Vec<u8>,
    /// The texel `(column, row)` each pixel shows, `None` where uncovered.
    pub texels: Vec<Option<(u8, u8)>>,
    /// Pixels covered, as the case returns them.
    pub covered: u32,
}

/// A numbered texture: texel `(i, j)` holds `1 + i` (`column`) or `1 + j`.
fn numbered(column: bool) -> Vec<u8> {
    (0..SIDE * SIDE)
        .map(|k| 1 + if column { k % SIDE } else { k / SIDE } as u8)
        .collect()
}

/// `scene` in `mode`: the bench case's frame and the texels read back (module doc).
pub fn draw(scene: TexScene, mode: TextureMode) -> Result<TexFrame, String> {
    let name = scene.case_name(mode);
    let case = cases::CASES
        .iter()
        .find(|c| c.name == name)
        .ok_or_else(|| format!("no bench case {name}"))?;
    let mut storage = Box::new(cases::Storage::new());
    let mut frame = |draw: &mut dyn FnMut(&mut Framebuffer<'_>, &mut cases::Storage) -> u32| {
        let mut pixels = vec![0u8; cases::FB_LEN];
        let mut fb = Framebuffer::new(&mut pixels, cases::WIDTH, cases::HEIGHT)
            .map_err(|e| e.to_string())?;
        let covered = draw(&mut fb, &mut storage);
        Ok::<_, String>((pixels, covered))
    };
    let (pixels, covered) = frame(&mut |fb, st| (case.run)(fb, st))?;
    let mut read = |column: bool| {
        let texels = numbered(column);
        let texturing = Texturing {
            texture: Texture::new(&texels, SIDE as u16, SIDE as u16).map_err(|e| e.to_string())?,
            mode,
            shades: None,
        };
        let (index, n) = frame(&mut |fb, st| {
            cases::scene::textured::frame_with(fb, st, scene.tables(), texturing)
        })?;
        if n != covered {
            return Err(format!(
                "{name}: {n} pixels covered with a numbered texture, {covered} with the grid"
            ));
        }
        Ok(index)
    };
    let (columns, rows) = (read(true)?, read(false)?);
    let texels = columns
        .iter()
        .zip(&rows)
        .map(|(&i, &j)| (i > 0 && j > 0).then(|| (i - 1, j - 1)))
        .collect();
    Ok(TexFrame {
        pixels,
        texels,
        covered,
    })
}

/// How far one mode's frame is from the exact mode's and from the `f64` reference.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Accuracy {
    /// Pixels covered.
    pub covered: u32,
    /// Covered pixels whose texel is not the exact mode's.
    pub texels_vs_exact: usize,
    /// Pixels whose level is not the exact mode's frame's.
    pub pixels_vs_exact: usize,
    /// Pixels covered by the frame and the reference both.
    pub compared: usize,
    /// Of those, pixels showing another texel than the reference's.
    pub texels_vs_reference: usize,
    /// Mean `|level − reference level|` over them.
    pub mean_error: f64,
    /// Largest `|level − reference level|` over them.
    pub max_error: f64,
    /// Pixels covered by the frame or the reference only.
    pub coverage_vs_reference: usize,
}

impl Accuracy {
    /// `frame` against the exact mode's frame `exact` and the reference.
    pub fn of(frame: &TexFrame, exact: &TexFrame, reference: &[Option<RefPixel>]) -> Accuracy {
        let mut a = Accuracy {
            covered: frame.covered,
            ..Accuracy::default()
        };
        let mut sum = 0.0;
        for (k, r) in reference.iter().enumerate() {
            let t = frame.texels[k];
            a.texels_vs_exact += usize::from(t.is_some() && t != exact.texels[k]);
            a.pixels_vs_exact += usize::from(frame.pixels[k] != exact.pixels[k]);
            match (t, r) {
                (Some(t), Some(r)) => {
                    a.compared += 1;
                    a.texels_vs_reference += usize::from(t != r.texel);
                    let d = (frame.pixels[k] as f64 - r.level).abs();
                    sum += d;
                    a.max_error = a.max_error.max(d);
                }
                (None, None) => {}
                _ => a.coverage_vs_reference += 1,
            }
        }
        a.mean_error = sum / a.compared.max(1) as f64;
        a
    }
}

/// Every scene in every mode: `(scene, mode, accuracy)`, the modes in [`MODES`]' order.
pub fn accuracy_table() -> Result<Vec<(TexScene, TextureMode, Accuracy)>, String> {
    let mut rows = Vec::new();
    for scene in TexScene::ALL {
        let reference = reference(scene)?;
        let exact = draw(scene, TextureMode::Exact)?;
        for (mode, _) in MODES {
            let frame = if mode == TextureMode::Exact {
                exact.clone()
            } else {
                draw(scene, mode)?
            };
            rows.push((scene, mode, Accuracy::of(&frame, &exact, &reference)));
        }
    }
    Ok(rows)
}

/// A picture of where a fast mode's texels differ from the exact mode's.
#[derive(Debug, Clone)]
pub struct TexFailure {
    /// File stem (`docs/images/<name>.png`).
    pub name: String,
    /// What is drawn, in words.
    pub caption: String,
    /// The mode's frame.
    pub frame: TexFrame,
    /// Per pixel: its texel differs from the exact mode's (always false for the exact mode's
    /// own picture).
    pub differs: Vec<bool>,
}

/// The colour of a differing texel of grey level `g` in [`TexFailure::marked`]: red, dark for
/// a dark texel and light for a light one, so that the mode's texture still shows under it.
pub const fn differing_colour(g: u8) -> [u8; 3] {
    [128 + g / 2, g / 4, g / 4]
}

impl TexFailure {
    /// `mode`'s frame of `scene` with the pixels whose texel is not the exact mode's marked.
    pub fn new(scene: TexScene, mode: TextureMode) -> Result<TexFailure, String> {
        let exact = draw(scene, TextureMode::Exact)?;
        let frame = if mode == TextureMode::Exact {
            exact.clone()
        } else {
            draw(scene, mode)?
        };
        let differs = frame
            .texels
            .iter()
            .zip(&exact.texels)
            .map(|(t, e)| t.is_some() && t != e)
            .collect();
        let short = scene.name().trim_start_matches("tex_");
        let (name, caption) = match mode {
            TextureMode::Exact => (
                format!("tex_{short}"),
                format!("{}, exact mode", scene.name()),
            ),
            m => (
                format!("tex_{short}_{}", mode_name(m)),
                format!(
                    "{}, {} mode, texels that differ from the exact mode in red",
                    scene.name(),
                    mode_name(m)
                ),
            ),
        };
        Ok(TexFailure {
            name,
            caption,
            frame,
            differs,
        })
    }

    /// Pixels marked.
    pub fn count(&self) -> usize {
        self.differs.iter().filter(|&&d| d).count()
    }

    /// The picture, `scale` times the frame's size: each pixel's grey level, or
    /// [`differing_colour`] of it where its texel differs. RGB, row-major.
    pub fn marked(&self, scale: usize) -> Vec<u8> {
        let (w, h) = (cases::WIDTH as usize, cases::HEIGHT as usize);
        let mut out = Vec::with_capacity(w * h * scale * scale * 3);
        for y in 0..h * scale {
            for x in 0..w * scale {
                let at = (y / scale) * w + x / scale;
                let g = self.frame.pixels[at];
                let rgb = if self.differs[at] {
                    differing_colour(g)
                } else {
                    [g; 3]
                };
                out.extend_from_slice(&rgb);
            }
        }
        out
    }
}

/// The pictures the docs show, in their order: each scene in the exact mode, then the floor
/// affine (its warping), the cube and the sphere subdivided every 16 pixels (their wobble) and
/// affine. The floor has no subdivided picture: its spans run at one depth each (a horizontal
/// plane seen by a level camera), so there the subdivided modes are exact.
pub fn texture_failures() -> Result<Vec<TexFailure>, String> {
    use TextureMode::{Affine, Exact, Subdivided16};
    let list = [
        (TexScene::Floor, Exact),
        (TexScene::Cube, Exact),
        (TexScene::Sphere, Exact),
        (TexScene::Floor, Affine),
        (TexScene::Cube, Subdivided16),
        (TexScene::Cube, Affine),
        (TexScene::Sphere, Subdivided16),
        (TexScene::Sphere, Affine),
    ];
    list.into_iter()
        .map(|(s, m)| TexFailure::new(s, m))
        .collect()
}
