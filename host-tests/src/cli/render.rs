//! `zscan render`: draws a scene described in TOML with the zscan core.
//!
//! `zscan render SCENE.toml -o out.png [--depth-out depth.png] [--stats stats.json]
//! [--bands ROWS]`. The commented example `host-tests/scenes/example.toml` uses every key but
//! the texture keys, which `host-tests/scenes/textured.toml` shows; in short:
//!
//! | section | keys (defaults) |
//! |---|---|
//! | `[camera]` | `eye` (`[0,0,3]`), `target` (`[0,0,0]`), `up` (`[0,1,0]`), `fov_deg` (60), `fov_axis` = `"vertical"` \| `"horizontal"` \| `"diagonal"`, `near` (0.5), `far` (10), `projection` = `"perspective"` (default) \| `"orthographic"`; orthographic takes `width` or `height`, the view's extent in world units, instead of `fov_deg` |
//! | `[viewport]` | `width` (320), `height` (240), `principal` (`[(w−1)/2, (h−1)/2]`, pixels are lattice points), `pixel_aspect` = `[r_x, r_y]` (`[1,1]`) |
//! | `[render]` | `depth_bits` = 16 \| 32 (16), `subpixel_bits` (4, the only value accepted), `background` palette index (0), `shade` = `"flat"` \| `"gouraud"` \| `"gouraud-fast"` \| `"phong"` (`"gouraud"`), `cull` back faces (true), `dither` (false: 4×4 ordered dithering between ramp levels) |
//! | `[light]` | host lighting (SCENES.md's model) of objects whose `material` is a ramp index: `direction` towards the light (`[1,1,1]`), `ka` (0.1), `kd` (0.9) |
//! | `[lighting]` | the core's lighting of objects whose `material` is a table: `ambient` `I_a` (0); `[[lighting.light]]` entries (at most 4), each `point = [x,y,z]`, `toward = [x,y,z]` or `spot = [x,y,z]` with `axis = [x,y,z]` and `cone = [inner, outer]` (half-angles in degrees), `attenuation = [c, l, q]` for a point or spot, and `intensity` `0..=255` |
//! | `[lut]` | `kind` = `"grey"` \| `"shaded"` (`"grey"`), `colours` = `[[r,g,b], ...]` (shaded: one per material), `levels` per material (32), `first` index of material 0 (shaded: 1, so that index 0 stays free for the background), `entries` = `[[index, r, g, b], ...]` overrides applied last |
//! | `[[object]]` | one of `generator`, `obj` (path relative to the TOML file) or `builtin` = `"bunny"`; generator parameters; `center`, `scale`, `rotate_deg`, `translate`; `material` = ramp index (0) or `{ ramp, ka, kd, ks, n }` (defaults 0, 0.1, 0.7, 0.3, 20; lit by the core); `shade`, `cull`, `dither`; `wireframe` = `"all"` \| `"front"` \| `"hidden"` \| `"appel"` (drawn as lines instead of shaded: every edge, the front faces' edges, hidden lines removed through the depth buffer, or by Appel's quantitative invisibility: the object's own hidden lines, drawn over the picture with no depth test, a closed mesh inside the view volume only), `line_index` the lines' palette index (the ramp's brightest); `opacity` = `0..=16` (screen door: pixels drawn of every 4×4 block) or `blend` = `0..=1` (blended over what lies behind through a table built from `[lut]`; drawn after the opaque objects, far to near, by the z-buffer only); `texture`, `texture_mode`, `texture_lit`, `uv_scale` (section "Textures") |
//! | `[[lines]]` | a 3D line list in world coordinates: `points` = `[[x,y,z], ...]`, `segments` = `[[i, j], ...]` (indices into `points`), `index` palette index (255), `point_size` (0: no points; 1 to 16: each point a square of that side) |
//!
//! Generators (the core's [`zscan::geometry::generators`], buffers allocated here):
//! `"cube"` (the unit cube `[0,1]³`, no parameters; `center = true` makes it `[−½,½]³`),
//! `"sphere"` (`segments` 32, `rings` 16, `radius` 1), `"torus"` (`rings` 24, `sides` 12,
//! `major` 1, `minor` 0.35), `"prism"` (the hollow prism: `sides` 6, `outer` 1, `inner` 0.8,
//! `half_height` 1) and, host-side, `"quad"` (`size = [w, h]`, default `[2, 2]`: the rectangle
//! centred at the origin in the `xy` plane facing `+z`).
//!
//! ## Placement
//! Every vertex `v` of an object becomes `v' = T + Rz·Rx·Ry·(S·(v − c))`: `c` the centre of the
//! bounding box when `center = true` (else 0), `S` the scale (`scale = s` or `[sx, sy, sz]`),
//! then the rotations of `rotate_deg = [ax, ay, az]` in the order **Y, then X, then Z**
//! (degrees, right-hand rule; SCENES.md's cube is `rotate_deg = [20, 30, 0]`), then
//! `translate = T`. The placement is done here in `f64` and the world positions are rounded
//! once to the core's I16F16 (the object's core transform is the identity).
//!
//! ## Textures
//! An object with `texture = "file.png"` (path relative to the TOML file) shows the image over
//! its mesh's per-corner texture coordinates, drawn by the core's textured span kind:
//! - **the image** ([`read_texture`](crate::texture_png::read_texture)): texel `(i, j)` is the
//!   image's column `i`, row `j` as stored (top row first: row 0 lies at `v = 0`); an indexed PNG
//!   gives its palette indices as they are (the scene's `[lut]` colours them); a grey or RGB(A)
//!   PNG is mapped to the `[lut]` by nearest colour, the entry of least squared RGB distance
//!   (grey `g` as `(g, g, g)`, alpha ignored, the lowest index among equals). Sides
//!   `1..=1024` texels (the core's `MAX_TEXTURE_SIDE`); a power-of-two side wraps, another
//!   clamps (the core's rule).
//! - **the coordinates**: the generators' own (the core's `UNIT_CUBE_UVS`, `uv_sphere_uvs`,
//!   `torus_uvs`, `hollow_prism_uvs`; the quad `(0, 0), (1, 0), (1, 1), (0, 1)` from its
//!   lower-left corner, `v` up), or an OBJ file's `vt` (`v/vt` and `v/vt/vn` corners, every
//!   corner of every face; OBJ's `v` runs up the image, so the core's is `1 − v`); the builtin
//!   bunny has none (an error). `uv_scale = s` or `[su, sv]` multiplies them (each factor in
//!   `0 < s ≤ 127`; the products rounded to the core's Q8.8, `1/256`, and each checked within
//!   `−128 ≤ u, v < 128`, else an error naming the value).
//! - **`texture_mode`** = `"exact"` (default) \| `"sub16"` \| `"sub8"` \| `"affine"`: the core's
//!   `TextureMode::Exact`, `Subdivided16`, `Subdivided8`, `Affine`.
//! - **`texture_lit`** (true): the texel and the object's light level (its `material`, host- or
//!   core-lit, flat or Gouraud) go through a shade table of [`TEXTURE_SHADE_LEVELS`] levels built
//!   from the `[lut]` by the core's `shade_table`; `false` writes the texels as they are.
//!
//! A textured object cannot be a wireframe, transparent (`opacity`, `blend`) or dithered, and is
//! not core-lit Phong (the core refuses it in words); `gouraud-fast` draws what `gouraud` draws
//! (the textured span interpolates the level exactly). The z-buffer (whole frames and `--bands`),
//! back faces alone and the reverse painter draw textures; the painter, the scan-line and
//! Warnock's subdivision refuse them in the core's words.
//!
//! ## Wireframes, lines and points
//! Wireframe objects and `[[lines]]` are drawn after the shaded objects, in the file's order,
//! through the same whole-frame z-buffer (the core's `Renderer::draw_wireframe`,
//! `draw_lines`, `draw_points`, at the default depth offset): `--visibility zbuffer` only, not
//! in `--bands`; other methods and bands are refused in words.
//!
//! ## Lighting
//! Two sources, chosen per object by its `material`:
//! - **the core** (`material = { ramp, ka, kd, ks, n }`): the course's model with the
//!   `[lighting]` ambient and lights (point or directional), integer only, evaluated per
//!   polygon (flat), per vertex (Gouraud) or per pixel (`"phong"`); vertex normals are the
//!   core's `Mesh::vertex_normals` of the placed mesh. This is what a device runs.
//! - **the host** (`material` = a ramp index): intensities computed here, in `f64`, with
//!   SCENES.md's model, `round(255·clamp(ka + kd·max(0, N·L), 0, 1))` with `L` the normalised
//!   `[light] direction` — the standard benchmark scenes' definition. Objects shaded `"flat"`
//!   use face normals and a per-polygon table; Gouraud objects use vertex normals
//!   (normalised sums of the un-normalised fan triangle cross products of the polygons around
//!   the vertex) and a per-vertex table. `"phong"` needs the core's lighting (an error here).
//!
//! ## Output
//! The frame (8-bit indices) goes through the LUT to the image (`.png`, `.ppm`, `.pgm` by
//! extension). The depth image (`--depth-out`, the z-buffer only: the other methods keep no
//! whole depth buffer and refuse it) is 8-bit grey: the nearest depth drawn is 255, the
//! farthest drawn 32, linearly in the stored depth, and the background 0. `--bands` applies to
//! the methods that draw in bands (z-buffer, scan-line); the others refuse it, and `auto`
//! picks its own. The stats JSON (the same keys for every method) holds the
//! core's [`RenderStats`] (with `--bands`, summed over the bands: the per-polygon counts then
//! repeat once per band, the pixel counts add up to the frame's), the host's triangle count,
//! frame size, bands and depth bits, the hidden-surface method (`visibility`), `ram_bytes`
//! (every caller buffer the frame used: frame or band, depth samples, vertex scratch, polygon
//! table, triangle store, orders and stacks as far as the frame filled them:
//! [`ram_bytes`](crate::core_render::ram_bytes)), and `method`, the method's own counts
//! (painter: `tests` decided by Newell's tests 1–5, `ambiguities`, `splits`, `pieces`;
//! scan-line: `active_peak`; Warnock: `windows` visited and by verdict, stack peaks;
//! `stored`: front triangles stored). With the stored-triangle methods `triangles_drawn`
//! counts a triangle once per piece, band or window that draws it. A frame that covers no
//! pixel is written (it is the right picture) with a warning on standard error naming the
//! cause ([`LoadedScene::empty_picture_cause`]). With `--visibility auto`,
//! `ram_bytes` is the plan's total and `plan` adds the plan, its reasons and its buffers.
use std::fs;
use std::path::{Path, PathBuf};

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use serde::Deserialize;
use toml::Spanned;
use zscan::geometry::camera::{Camera, FovAxis, Lens, OrthoView, Viewport};
use zscan::geometry::generators;
use zscan::geometry::mesh::{Mesh, PolygonSizes, TexCoord, TEX_ONE};
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::lighting::{
    Attenuation, Cone, Illumination, Light, Material, MAX_LIGHTS, MAX_SHININESS,
};
use zscan::output::{BlendTable, DepthBuffer, DepthValue, Framebuffer, Lut, BLEND_ENTRIES};
use zscan::raster::triangle::{LuminanceRamp, Opacity, ShadeMode};
use zscan::render::{
    AppelCrossing, AppelEdge, AppelScratch, BandScratch, LineStyle, PolygonRows, PreparedVertex,
    RenderStats, Renderer, SceneRenderer, Wireframe,
};
use zscan::scene::{Intensities, Object, Scene, Transparency};
use zscan::texture::{shade_table, ShadeTable, Texture, TextureMode, Texturing};

use super::CliError;
use crate::core_render::coord;
use zscan::visibility::{Visibility, VisibilityError};

/// Arguments of `zscan render`.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// The scene description (TOML; see host-tests/scenes/example.toml).
    pub scene: PathBuf,
    /// Output image (.png, .ppm or .pgm).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the depth buffer as a grey PNG (near bright, background black); only
    /// --visibility zbuffer keeps a whole depth buffer.
    #[arg(long)]
    pub depth_out: Option<PathBuf>,
    /// Write frame statistics as JSON.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Render in bands of ROWS rows (the pixels are the same as one pass); --visibility
    /// zbuffer and scanline only (the other methods draw the whole frame at once).
    #[arg(long, value_name = "ROWS")]
    pub bands: Option<u16>,
    /// Hidden-surface method: auto (zscan::visibility::plan: back faces alone for convex,
    /// separable objects, else the z-buffer in the layout and depth width that fit
    /// --ram-budget; the plan and its reasons are printed), backface, reverse-painter,
    /// painter, scanline, warnock or zbuffer. Back faces alone, the reverse painter (a bit per
    /// pixel; culled convex objects apart in depth where they overlap on screen, else refused
    /// in words), the painter and Warnock's subdivision need no depth buffer and draw the
    /// whole frame at once (no --depth-out, no --bands); the
    /// scan-line draws in bands of --bands rows (default 1) through one band of depth (no
    /// --depth-out).
    #[arg(long, value_name = "METHOD", default_value = "zbuffer", value_parser = parse_visibility)]
    pub visibility: VisibilityArg,
    /// With --visibility auto: the caller memory the plan may use, in bytes (32768 or 32K;
    /// K = 1024, M = 1024²). Default: no limit.
    #[arg(long, value_name = "BYTES", value_parser = parse_bytes)]
    pub ram_budget: Option<usize>,
    /// Also write the visible pieces of every object with `wireframe = "appel"` as an SVG
    /// (one `<line>` per piece, in pixels, the colour of the object's `line_index`).
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

/// `--ram-budget`'s parser: a byte count, optionally followed by `K` (1024) or `M` (1024²).
pub fn parse_bytes(s: &str) -> Result<usize, String> {
    let t = s.trim();
    let (digits, unit) = match t.char_indices().last() {
        Some((i, 'K' | 'k')) => (&t[..i], 1024usize),
        Some((i, 'M' | 'm')) => (&t[..i], 1024 * 1024),
        _ => (t, 1),
    };
    digits
        .parse::<usize>()
        .ok()
        .and_then(|n| n.checked_mul(unit))
        .ok_or_else(|| format!("{s:?} is not a byte count (digits, optionally followed by K or M)"))
}

/// `--visibility`'s value: a method, or `auto` (`None`: the planner's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VisibilityArg(pub Option<Visibility>);

/// `--visibility`'s parser: a method's name ([`Visibility::name`]).
fn parse_visibility(s: &str) -> Result<VisibilityArg, String> {
    if s == "auto" {
        return Ok(VisibilityArg(None));
    }
    Visibility::from_name(s)
        .map(|v| VisibilityArg(Some(v)))
        .ok_or_else(|| {
            let names: Vec<_> = Visibility::ALL.iter().map(|v| v.name()).collect();
            format!("unknown method {s:?}: one of auto, {}", names.join(", "))
        })
}

/// The painter's split budget in `zscan render`.
pub const PAINTER_SPLITS: usize = 4096;

/// The sub-pixel bits `zscan render` uses (the core's default; the only value accepted).
pub const SUBPIXEL_BITS: u32 = 4;

/// A scene file as read from TOML.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// `[camera]`.
    #[serde(default)]
    pub camera: CameraSection,
    /// `[viewport]`.
    #[serde(default)]
    pub viewport: ViewportSection,
    /// `[render]`.
    #[serde(default)]
    pub render: RenderSection,
    /// `[light]`.
    #[serde(default)]
    pub light: LightSection,
    /// `[lighting]`: the core's lighting stage (ambient and lights).
    pub lighting: Option<LightingSection>,
    /// `[lut]`.
    #[serde(default)]
    pub lut: LutSection,
    /// `[[object]]` entries.
    #[serde(default, rename = "object")]
    pub objects: Vec<Spanned<ObjectSection>>,
    /// `[[lines]]` entries.
    #[serde(default, rename = "lines")]
    pub lines: Vec<LinesSection>,
}

/// One `[[lines]]`: a 3D line list (and its points) in world coordinates.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinesSection {
    /// World positions.
    pub points: Vec<[f64; 3]>,
    /// Segments, as pairs of indices into `points`.
    #[serde(default)]
    pub segments: Vec<[u16; 2]>,
    /// Palette index (255).
    #[serde(default = "default_line_index")]
    pub index: u8,
    /// Side of each point's square (0: points not drawn).
    #[serde(default)]
    pub point_size: u8,
}

fn default_line_index() -> u8 {
    255
}

/// `wireframe` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WireKey {
    /// Every edge once.
    All,
    /// The front faces' edges.
    Front,
    /// Hidden lines removed through the depth buffer.
    Hidden,
    /// Hidden lines removed by Appel's quantitative invisibility (no depth buffer).
    Appel,
}

impl WireKey {
    fn mode(self) -> Wireframe {
        match self {
            WireKey::All => Wireframe::All,
            WireKey::Front => Wireframe::Front,
            WireKey::Hidden => Wireframe::Hidden,
            WireKey::Appel => Wireframe::Appel,
        }
    }
}

/// `[camera]`: a look-at camera.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraSection {
    /// Eye position (world).
    pub eye: [f64; 3],
    /// Point looked at.
    pub target: [f64; 3],
    /// Approximate up direction.
    pub up: [f64; 3],
    /// Full field of view in degrees.
    pub fov_deg: f64,
    /// Which extent the field of view spans.
    pub fov_axis: FovAxisKey,
    /// Near plane distance.
    pub near: f64,
    /// Far plane distance.
    pub far: f64,
    /// `"perspective"` (the default) or `"orthographic"` (parallel projection).
    pub projection: ProjectionKey,
    /// Orthographic: the view's width in world units (give this or `height`).
    pub width: Option<f64>,
    /// Orthographic: the view's height in world units (give this or `width`).
    pub height: Option<f64>,
}

/// `projection` values of `[camera]`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ProjectionKey {
    /// Central projection with `fov_deg`.
    #[default]
    Perspective,
    /// Parallel projection with `width` or `height`.
    Orthographic,
}

impl Default for CameraSection {
    fn default() -> Self {
        CameraSection {
            eye: [0.0, 0.0, 3.0],
            target: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            fov_deg: 60.0,
            fov_axis: FovAxisKey::Vertical,
            near: 0.5,
            far: 10.0,
            projection: ProjectionKey::Perspective,
            width: None,
            height: None,
        }
    }
}

/// `fov_axis` values.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FovAxisKey {
    /// Top to bottom.
    Vertical,
    /// Left to right.
    Horizontal,
    /// Corner to corner.
    Diagonal,
}

/// `[viewport]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ViewportSection {
    /// Width in pixels, `1..=`[`MAX_PICTURE_SIDE`](super::MAX_PICTURE_SIDE) (read wide, so
    /// that a value past 16 bits is named with the limit too).
    pub width: i64,
    /// Height in pixels, `1..=`[`MAX_PICTURE_SIDE`](super::MAX_PICTURE_SIDE).
    pub height: i64,
    /// Principal point in pixels (default the picture's centre).
    pub principal: Option<[f64; 2]>,
    /// Physical pixel shape `[r_x, r_y]`.
    #[serde(deserialize_with = "super::ranged::array")]
    pub pixel_aspect: [u16; 2],
}

impl Default for ViewportSection {
    fn default() -> Self {
        ViewportSection {
            width: 320,
            height: 240,
            principal: None,
            pixel_aspect: [1, 1],
        }
    }
}

/// `[render]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSection {
    /// Depth sample width, 16 or 32.
    #[serde(deserialize_with = "super::ranged::int")]
    pub depth_bits: u32,
    /// Sub-pixel bits (only 4 is supported).
    #[serde(deserialize_with = "super::ranged::int")]
    pub subpixel_bits: u32,
    /// Palette index of the background.
    #[serde(deserialize_with = "super::ranged::int")]
    pub background: u8,
    /// Default shading of the objects.
    pub shade: ShadeKey,
    /// Default back-face culling of the objects.
    pub cull: bool,
    /// Default ordered dithering of the objects.
    pub dither: bool,
}

impl Default for RenderSection {
    fn default() -> Self {
        RenderSection {
            depth_bits: 16,
            subpixel_bits: SUBPIXEL_BITS,
            background: 0,
            shade: ShadeKey::Gouraud,
            cull: true,
            dither: false,
        }
    }
}

/// `shade` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShadeKey {
    /// One index per triangle, face normals.
    Flat,
    /// Exact Gouraud, vertex normals.
    Gouraud,
    /// Fast (16.16) Gouraud, vertex normals.
    GouraudFast,
    /// Per-pixel lighting of interpolated normals (objects lit by the core only).
    Phong,
}

impl ShadeKey {
    fn mode(self) -> ShadeMode {
        match self {
            ShadeKey::Flat => ShadeMode::Flat,
            ShadeKey::Gouraud => ShadeMode::GouraudExact,
            ShadeKey::GouraudFast => ShadeMode::GouraudFast,
            ShadeKey::Phong => ShadeMode::Phong,
        }
    }
}

/// `[lighting]`: ambient intensity and lights for objects whose `material` gives reflection
/// coefficients (lit by the core, integer only).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightingSection {
    /// Ambient intensity `I_a`, `0..=255`.
    #[serde(default, deserialize_with = "super::ranged::int")]
    pub ambient: u8,
    /// `[[lighting.light]]` entries (at most 4).
    #[serde(default, rename = "light")]
    pub lights: Vec<LightKey>,
}

/// One `[[lighting.light]]`: exactly one of `point` (a position), `toward` (a direction
/// toward a light at infinity) or `spot` (a position, with `axis` and `cone`), optionally
/// `attenuation` (point and spot), and its intensity `0..=255`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightKey {
    /// Position of a point light (world).
    pub point: Option<[f64; 3]>,
    /// Direction toward a directional light (world, any non-zero length).
    pub toward: Option<[f64; 3]>,
    /// Position of a spot light (world).
    pub spot: Option<[f64; 3]>,
    /// A spot's axis: the direction it points to (world, any non-zero length).
    pub axis: Option<[f64; 3]>,
    /// A spot's inner and outer half-angles in degrees.
    pub cone: Option<[f64; 2]>,
    /// Distance attenuation `[constant, linear, quadratic]` of a point or spot light.
    pub attenuation: Option<[f64; 3]>,
    /// Intensity `I_p`, `0..=255`.
    #[serde(deserialize_with = "super::ranged::int")]
    pub intensity: u8,
}

/// A light's `attenuation = [c, l, q]`: `c` in `[1, 256]`, `l` and `q` in `[0, 256]` (the
/// core's ranges), rounded to Q16.
fn attenuation(k: Option<[f64; 3]>) -> Result<Attenuation, String> {
    let Some(k) = k else {
        return Ok(Attenuation::NONE);
    };
    if !finite(&k)
        || !(1.0..=256.0).contains(&k[0])
        || k[1..].iter().any(|c| !(0.0..=256.0).contains(c))
    {
        return Err(format!(
            "[lighting] a light's `attenuation = [constant, linear, quadratic]` needs constant in \
             [1, 256] and linear, quadratic in [0, 256], got {k:?}"
        ));
    }
    let q16 = |c: f64| (c * 65536.0).round() as u32;
    Ok(Attenuation {
        constant: q16(k[0]),
        linear: q16(k[1]),
        quadratic: q16(k[2]),
    })
}

/// A spot's `cone = [inner, outer]` in degrees, rounded to 1/1000 degree (the core checks
/// `0 ≤ inner < outer ≤ 90` and the gap between their cosines).
fn spot_cone(c: [f64; 2]) -> Result<Cone, String> {
    if c.iter()
        .any(|d| !d.is_finite() || !(0.0..=90.0).contains(d))
    {
        return Err(format!(
            "[lighting] a spot's `cone = [inner, outer]` is in degrees within [0, 90], got {c:?}"
        ));
    }
    let angle = |d: f64| BinaryAngle::from_degrees_ratio((d * 1000.0).round() as i64, 1000);
    Ok(Cone {
        inner: angle(c[0]),
        outer: angle(c[1]),
    })
}

/// An object's `material`: a palette ramp index, or a table with the ramp and the reflection
/// coefficients of the core's lighting model. Read through [`toml::Value`] so that a bad value
/// gets a message with the range (`0..=255`) instead of serde's "did not match any variant".
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(try_from = "toml::Value")]
pub enum MaterialKey {
    /// Index of the material's ramp in a shaded LUT (lit by `[light]`, SCENES.md's model).
    Ramp(u8),
    /// Lit by the core with `[lighting]`: `{ ramp, ka, kd, ks, n }`.
    Lit(LitMaterialKey),
}

impl TryFrom<toml::Value> for MaterialKey {
    type Error = String;

    fn try_from(v: toml::Value) -> Result<Self, String> {
        match v {
            toml::Value::Integer(i) => u8::try_from(i)
                .map(MaterialKey::Ramp)
                .map_err(|_| format!("material = {i} is outside the ramp indices 0..=255")),
            toml::Value::Table(t) => {
                if let Some(r) = t.get("ramp") {
                    if !matches!(r, toml::Value::Integer(i) if (0..=255).contains(i)) {
                        return Err(format!(
                            "material ramp = {r} is outside the ramp indices 0..=255"
                        ));
                    }
                }
                toml::Value::Table(t)
                    .try_into::<LitMaterialKey>()
                    .map(MaterialKey::Lit)
                    .map_err(|e| format!("material table: {}", e.message()))
            }
            other => Err(format!(
                "material must be a ramp index 0..=255 or a table {{ ramp, ka, kd, ks, n }}, \
                 got {other}"
            )),
        }
    }
}

impl Default for MaterialKey {
    fn default() -> Self {
        MaterialKey::Ramp(0)
    }
}

impl MaterialKey {
    fn ramp(&self) -> u8 {
        match self {
            MaterialKey::Ramp(r) => *r,
            MaterialKey::Lit(m) => m.ramp,
        }
    }
}

/// Reflection coefficients (course chapter 4): `ka`, `kd`, `ks` in `[0, 2)`, `n` in `1..=200`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LitMaterialKey {
    /// Ramp index in a shaded LUT (0).
    #[serde(default)]
    pub ramp: u8,
    /// Ambient reflection (0.1).
    #[serde(default = "default_ka")]
    pub ka: f64,
    /// Diffuse reflection (0.7).
    #[serde(default = "default_kd")]
    pub kd: f64,
    /// Specular reflection (0.3).
    #[serde(default = "default_ks")]
    pub ks: f64,
    /// Specular exponent (20), `1..=200` (read wide, so that a value past a byte is named
    /// with its range too).
    #[serde(default = "default_n")]
    pub n: i64,
}

fn default_ka() -> f64 {
    0.1
}
fn default_kd() -> f64 {
    0.7
}
fn default_ks() -> f64 {
    0.3
}
fn default_n() -> i64 {
    20
}

impl LitMaterialKey {
    /// The core material (Q15 coefficients, rounded once).
    fn material(&self) -> Result<Material, String> {
        let q = |name: &str, v: f64| {
            if !(v.is_finite() && (0.0..2.0).contains(&v)) {
                return Err(format!("material `{name}` must be in [0, 2), got {v}"));
            }
            Ok((v * 32768.0).round().min(65535.0) as u16)
        };
        let n = u8::try_from(self.n)
            .ok()
            .filter(|n| (1..=MAX_SHININESS).contains(n))
            .ok_or_else(|| {
                format!(
                    "material `n` must be in 1..={MAX_SHININESS} (the specular exponent), got {}",
                    self.n
                )
            })?;
        Ok(Material {
            ka: q("ka", self.ka)?,
            kd: q("kd", self.kd)?,
            ks: q("ks", self.ks)?,
            n,
        })
    }
}

fn lights(l: &LightingSection) -> Result<Vec<Light>, String> {
    if l.lights.len() > MAX_LIGHTS {
        return Err(format!(
            "[lighting] has {} lights (at most {MAX_LIGHTS})",
            l.lights.len()
        ));
    }
    let p = |a: [f64; 3]| -> Result<Vec3, String> {
        if !finite(&a) || a.iter().any(|c| c.abs() > 1024.0) {
            return Err(format!(
                "[lighting] light coordinates must be finite and within ±1024, got {a:?}"
            ));
        }
        Ok(Vec3::new(coord(a[0]), coord(a[1]), coord(a[2])))
    };
    l.lights
        .iter()
        .map(|k| {
            if k.spot.is_none() && (k.axis.is_some() || k.cone.is_some()) {
                return Err("[lighting] `axis` and `cone` belong to a `spot` light".into());
            }
            match (k.point, k.toward, k.spot) {
                (Some(q), None, None) => match k.attenuation {
                    None => Ok(Light::Point {
                        position: p(q)?,
                        intensity: k.intensity,
                    }),
                    Some(_) => Ok(Light::AttenuatedPoint {
                        position: p(q)?,
                        intensity: k.intensity,
                        attenuation: attenuation(k.attenuation)?,
                    }),
                },
                (None, Some(t), None) => {
                    let toward = p(t)?;
                    if toward == Vec3::ZERO {
                        return Err("[lighting] a light's `toward` must not be zero".into());
                    }
                    if k.attenuation.is_some() {
                        return Err(
                            "[lighting] a directional light (`toward`) has no `attenuation`".into(),
                        );
                    }
                    Ok(Light::Directional {
                        toward,
                        intensity: k.intensity,
                    })
                }
                (None, None, Some(q)) => {
                    let (Some(axis), Some(cone)) = (k.axis, k.cone) else {
                        return Err("[lighting] a `spot` light needs `axis = [x, y, z]` and \
                             `cone = [inner, outer]` (degrees)"
                            .into());
                    };
                    let axis = p(axis)?;
                    if axis == Vec3::ZERO {
                        return Err("[lighting] a spot's `axis` must not be zero".into());
                    }
                    Ok(Light::Spot {
                        position: p(q)?,
                        axis,
                        cone: spot_cone(cone)?,
                        attenuation: attenuation(k.attenuation)?,
                        intensity: k.intensity,
                    })
                }
                _ => Err(
                    "[[lighting.light]] needs exactly one of `point`, `toward` or `spot`".into(),
                ),
            }
        })
        .collect::<Result<Vec<Light>, String>>()
        .and_then(|lights| {
            // The core's own checks (cones, attenuation), which do not depend on the frame.
            Illumination::observer(0, &lights)
                .map(|_| lights)
                .map_err(|e| format!("[lighting] {e}"))
        })
}

/// `[light]`: one directional light, SCENES.md's model.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LightSection {
    /// Direction towards the light (world).
    pub direction: [f64; 3],
    /// Ambient term.
    pub ka: f64,
    /// Diffuse term.
    pub kd: f64,
}

impl Default for LightSection {
    fn default() -> Self {
        LightSection {
            direction: [1.0, 1.0, 1.0],
            ka: 0.1,
            kd: 0.9,
        }
    }
}

/// `[lut]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LutSection {
    /// Grey ramp or shaded palette.
    pub kind: LutKind,
    /// Base colours of the materials (shaded).
    #[serde(deserialize_with = "super::ranged::arrays")]
    pub colours: Vec<[u8; 3]>,
    /// Shade levels per material (shaded).
    #[serde(deserialize_with = "super::ranged::int")]
    pub levels: u8,
    /// Index of material 0's darkest shade (shaded; default 1).
    #[serde(deserialize_with = "super::ranged::option")]
    pub first: Option<u8>,
    /// `[index, r, g, b]` entries set after building the table.
    #[serde(deserialize_with = "super::ranged::arrays")]
    pub entries: Vec<[u8; 4]>,
}

impl Default for LutSection {
    fn default() -> Self {
        LutSection {
            kind: LutKind::Grey,
            colours: Vec::new(),
            levels: 32,
            first: None,
            entries: Vec::new(),
        }
    }
}

/// `kind` of `[lut]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LutKind {
    /// Index = grey level; every material is the grey ramp.
    Grey,
    /// `first + material·levels + shade`.
    Shaded,
}

/// A uniform or per-axis scale. Read through [`toml::Value`] so that a value of another form
/// gets a message with the forms accepted instead of serde's "did not match any variant".
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(try_from = "toml::Value")]
pub enum ScaleKey {
    /// Uniform.
    Uniform(f64),
    /// `[sx, sy, sz]`.
    Axes([f64; 3]),
}

/// A TOML number (float or integer) as `f64`, or `None` for a value of another kind.
fn toml_number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

impl TryFrom<toml::Value> for ScaleKey {
    type Error = String;

    fn try_from(v: toml::Value) -> Result<Self, String> {
        let axes = match &v {
            toml::Value::Array(a) if a.len() == 3 => {
                a.iter().map(toml_number).collect::<Option<Vec<f64>>>()
            }
            _ => None,
        };
        match (toml_number(&v), axes) {
            (Some(s), _) => Ok(ScaleKey::Uniform(s)),
            (None, Some(a)) => Ok(ScaleKey::Axes([a[0], a[1], a[2]])),
            _ => Err(format!(
                "`scale` must be a number (uniform, `scale = 2`) or an array of three numbers \
                 (per axis, `scale = [sx, sy, sz]`), got {v}"
            )),
        }
    }
}

impl Default for ScaleKey {
    fn default() -> Self {
        ScaleKey::Uniform(1.0)
    }
}

/// One `[[object]]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectSection {
    /// `"cube"`, `"sphere"`, `"torus"`, `"prism"` or `"quad"`.
    pub generator: Option<Spanned<String>>,
    /// OBJ file, relative to the scene file.
    pub obj: Option<Spanned<String>>,
    /// A mesh shipped with the repository (`"bunny"`).
    pub builtin: Option<Spanned<String>>,
    /// Sphere segments.
    #[serde(default, deserialize_with = "super::ranged::option")]
    pub segments: Option<u16>,
    /// Sphere rings, or torus rings around the axis.
    #[serde(default, deserialize_with = "super::ranged::option")]
    pub rings: Option<u16>,
    /// Sphere radius.
    pub radius: Option<f64>,
    /// Torus or prism sides.
    #[serde(default, deserialize_with = "super::ranged::option")]
    pub sides: Option<u16>,
    /// Torus major radius.
    pub major: Option<f64>,
    /// Torus minor radius.
    pub minor: Option<f64>,
    /// Prism outer circumradius.
    pub outer: Option<f64>,
    /// Prism inner circumradius.
    pub inner: Option<f64>,
    /// Prism half height.
    pub half_height: Option<f64>,
    /// Quad size `[w, h]`.
    pub size: Option<[f64; 2]>,
    /// Centre the bounding box at the origin first.
    #[serde(default)]
    pub center: bool,
    /// Scale.
    #[serde(default)]
    pub scale: ScaleKey,
    /// Rotations in degrees about x, y, z (applied Y, X, Z).
    #[serde(default)]
    pub rotate_deg: [f64; 3],
    /// Translation.
    #[serde(default)]
    pub translate: [f64; 3],
    /// Palette ramp index, or ramp and reflection coefficients (lit by the core).
    #[serde(default)]
    pub material: MaterialKey,
    /// Shading (default `[render] shade`).
    pub shade: Option<ShadeKey>,
    /// Back-face culling (default `[render] cull`).
    pub cull: Option<bool>,
    /// Ordered dithering (default `[render] dither`).
    pub dither: Option<bool>,
    /// Drawn as a wireframe instead of shaded.
    pub wireframe: Option<WireKey>,
    /// The wireframe's palette index (default: the ramp's brightest).
    pub line_index: Option<u8>,
    /// Screen-door opacity: pixels drawn of every 4×4 block, `0..=16` (16, opaque).
    pub opacity: Option<u8>,
    /// Blended transparency: the object's opacity over what lies behind, `0..=1` (a blend
    /// table over the scene's `[lut]`, at 1/256 steps).
    pub blend: Option<f64>,
    /// A PNG texture, relative to the scene file (module doc, "Textures").
    pub texture: Option<Spanned<String>>,
    /// How exactly the texture follows the perspective (default exact).
    pub texture_mode: Option<TextureModeKey>,
    /// Texels lit through a shade table (default true) or written as they are.
    pub texture_lit: Option<bool>,
    /// Factor on the texture coordinates, uniform or `[su, sv]`.
    pub uv_scale: Option<UvScaleKey>,
}

/// `texture_mode` values: the core's [`TextureMode`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
pub enum TextureModeKey {
    /// [`TextureMode::Exact`].
    #[serde(rename = "exact")]
    Exact,
    /// [`TextureMode::Subdivided16`].
    #[serde(rename = "sub16", alias = "subdivided16")]
    Sub16,
    /// [`TextureMode::Subdivided8`].
    #[serde(rename = "sub8", alias = "subdivided8")]
    Sub8,
    /// [`TextureMode::Affine`].
    #[serde(rename = "affine")]
    Affine,
}

impl TextureModeKey {
    fn mode(self) -> TextureMode {
        match self {
            TextureModeKey::Exact => TextureMode::Exact,
            TextureModeKey::Sub16 => TextureMode::Subdivided16,
            TextureModeKey::Sub8 => TextureMode::Subdivided8,
            TextureModeKey::Affine => TextureMode::Affine,
        }
    }
}

/// `uv_scale`: one factor for `u` and `v`, or one each. Read through [`toml::Value`] so that a
/// value of another form is named with the forms accepted.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(try_from = "toml::Value")]
pub struct UvScaleKey(pub [f64; 2]);

impl TryFrom<toml::Value> for UvScaleKey {
    type Error = String;

    fn try_from(v: toml::Value) -> Result<Self, String> {
        match &v {
            toml::Value::Array(a) if a.len() == 2 => {
                if let (Some(u), Some(w)) = (toml_number(&a[0]), toml_number(&a[1])) {
                    return Ok(UvScaleKey([u, w]));
                }
            }
            other => {
                if let Some(s) = toml_number(other) {
                    return Ok(UvScaleKey([s, s]));
                }
            }
        }
        Err(format!(
            "`uv_scale` must be a number (`uv_scale = 4`) or two (`uv_scale = [su, sv]`), got {v}"
        ))
    }
}

/// Largest `uv_scale` factor: the generators' coordinates lie in `0..=1`, so a factor up to
/// 127 keeps them inside the core's Q8.8 (`−128 ≤ u, v < 128`).
pub const MAX_UV_SCALE: f64 = 127.0;

/// Light levels of a lit texture's shade table (`zscan::texture::shade_table` over the
/// scene's `[lut]`: 32 rows of 256 entries, 8 KiB).
pub const TEXTURE_SHADE_LEVELS: u16 = 32;

/// A mesh in `f64` on the host: positions and polygons (counter-clockwise outward).
#[derive(Debug, Clone, Default)]
pub struct HostMesh {
    /// Positions.
    pub vertices: Vec<[f64; 3]>,
    /// Polygons as vertex indices.
    pub polygons: Vec<Vec<usize>>,
    /// Texture coordinates, one per polygon corner in the polygons' order (the core's
    /// `Mesh::with_uvs` table), or empty: none.
    pub uvs: Vec<TexCoord>,
}

/// A texture ready for the core: its texels, the corners' coordinates, its mode and shades.
#[derive(Debug, Clone)]
pub struct PreparedTexture {
    /// The image as palette indices.
    pub image: crate::texture_png::TextureImage,
    /// Q8.8 coordinates, one per index of the object's mesh.
    pub uvs: Vec<TexCoord>,
    /// Exact, subdivided or affine.
    pub mode: TextureMode,
    /// The shade table (`TEXTURE_SHADE_LEVELS · 256` entries), or `None`: unlit texels.
    pub shades: Option<Vec<u8>>,
}

/// An object ready for the core: rounded tables and its shading.
#[derive(Debug, Clone)]
pub struct PreparedObject {
    /// World positions, I16F16.
    pub vertices: Vec<Vec3>,
    /// Polygon indices, concatenated.
    pub indices: Vec<u16>,
    /// Polygon sizes (all equal: `uniform` is `Some`).
    pub sizes: Vec<u8>,
    /// The common polygon size, if any.
    pub uniform: Option<u8>,
    /// Intensities, per vertex (Gouraud) or per polygon (flat); empty for core-lit objects.
    pub intensities: Vec<u8>,
    /// Reflection coefficients of an object lit by the core.
    pub lit: Option<Material>,
    /// Vertex normals (world frame, the core's `Mesh::vertex_normals`) of a core-lit object.
    pub normals: Vec<Vec3>,
    /// Shading.
    pub shade: ShadeKey,
    /// Palette ramp.
    pub ramp: LuminanceRamp,
    /// Back-face culling.
    pub cull: bool,
    /// Ordered dithering.
    pub dither: bool,
    /// Drawn as a wireframe in this mode instead of shaded.
    pub wireframe: Option<Wireframe>,
    /// The wireframe's palette index.
    pub line_index: u8,
    /// Screen-door opacity (`None`: not a screen door).
    pub opacity: Option<Opacity>,
    /// The blend table's entries of a blended object.
    pub blend: Option<Box<[u8; BLEND_ENTRIES]>>,
    /// The texture of a textured object.
    pub texture: Option<PreparedTexture>,
}

/// A `[[lines]]` list ready for the core.
#[derive(Debug, Clone)]
pub struct PreparedLines {
    /// World positions, I16F16.
    pub points: Vec<Vec3>,
    /// Segments.
    pub segments: Vec<[u16; 2]>,
    /// Palette index.
    pub index: u8,
    /// Side of each point's square (0: none).
    pub point_size: u8,
}

impl PreparedObject {
    fn object(&self) -> Result<Object<'_>, String> {
        let sizes = match self.uniform {
            Some(n) => PolygonSizes::Uniform(n),
            None => PolygonSizes::PerPolygon(&self.sizes),
        };
        let mut mesh = Mesh::new(&self.vertices, &self.indices, sizes)
            .map_err(|e| format!("mesh: {}", mesh_error_words(e)))?;
        if let Some(t) = &self.texture {
            mesh = mesh
                .with_uvs(&t.uvs)
                .map_err(|e| format!("texture coordinates: {e}"))?;
        }
        let mut o = Object::new(mesh);
        if let Some(t) = &self.texture {
            let image = &t.image;
            let shades = t
                .shades
                .as_deref()
                .map(|s| ShadeTable::new(s, TEXTURE_SHADE_LEVELS))
                .transpose()
                .map_err(|e| format!("texture: {e}"))?;
            o.texture = Some(Texturing {
                texture: Texture::new(&image.texels, image.width, image.height)
                    .map_err(|e| format!("texture: {e}"))?,
                mode: t.mode,
                shades,
            });
        }
        o.intensities = match self.lit {
            Some(material) => Intensities::Lit {
                material,
                normals: &self.normals,
            },
            None if self.shade == ShadeKey::Flat => Intensities::PerPolygon(&self.intensities),
            None => Intensities::PerVertex(&self.intensities),
        };
        o.shade = self.shade.mode();
        o.ramp = self.ramp;
        o.cull_back_faces = self.cull;
        o.dither = self.dither;
        if let Some(opacity) = self.opacity {
            o.transparency = Transparency::ScreenDoor(opacity);
        }
        if let Some(entries) = &self.blend {
            o.transparency = Transparency::Blended(BlendTable::from_entries(entries));
        }
        Ok(o)
    }
}

/// A scene loaded and converted: the camera, the objects, the LUT.
#[derive(Debug, Clone)]
pub struct LoadedScene {
    /// The core camera.
    pub camera: Camera,
    /// The objects.
    pub objects: Vec<PreparedObject>,
    /// Colour table.
    pub lut: Lut<Rgb888>,
    /// Background index.
    pub background: u8,
    /// Ambient intensity of `[lighting]`.
    pub ambient: u8,
    /// Lights of `[lighting]` (world frame).
    pub lights: Vec<Light>,
    /// 16 or 32.
    pub depth_bits: u32,
    /// Triangles of the meshes (a polygon of `n` vertices counts `n − 2`).
    pub triangles_in: u64,
    /// `[camera]` as the file gave it (to say why a picture came out empty).
    pub view: CameraSection,
    /// The `[[lines]]` lists.
    pub lines: Vec<PreparedLines>,
}

/// Line numbers of a scene file's text: the byte offsets of its line breaks, found once, so
/// that each look-up is a binary search and loading stays linear in the number of objects
/// (counting the breaks from the top for every object made it quadratic).
struct LineIndex(Vec<usize>);

impl LineIndex {
    fn of(text: &str) -> LineIndex {
        LineIndex(text.match_indices('\n').map(|(i, _)| i).collect())
    }

    /// 1-based line of byte offset `at`.
    fn line(&self, at: usize) -> usize {
        self.0.partition_point(|&b| b < at) + 1
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(v: [f64; 3]) -> Option<[f64; 3]> {
    let l = dot(v, v).sqrt();
    (l > 0.0 && l.is_finite()).then(|| [v[0] / l, v[1] / l, v[2] / l])
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The mesh of a core generator, read back into `f64` (exact: I16F16 values).
fn from_core(mesh: Mesh<'_>) -> HostMesh {
    let f = |v: &Vec3| v.bits().map(|b| b as f64 / 65536.0);
    HostMesh {
        vertices: mesh.vertices().iter().map(f).collect(),
        polygons: mesh
            .polygons()
            .map(|p| p.iter().map(|&i| i as usize).collect())
            .collect(),
        uvs: mesh.uvs().to_vec(),
    }
}

fn positive(name: &str, v: f64) -> Result<zscan::geometry::fixed::Coord, String> {
    if !(v.is_finite() && v > 0.0 && v <= 1024.0) {
        return Err(format!("`{name}` must be in (0, 1024], got {v}"));
    }
    Ok(coord(v))
}

/// Words for the core's mesh errors (the core's enum has no `Display` in this tree).
fn mesh_error_words(e: zscan::geometry::mesh::MeshError) -> String {
    use zscan::geometry::mesh::MeshError as E;
    match e {
        E::BadPolygonSize => "a polygon has fewer than 3 vertices".into(),
        E::IndexCountMismatch => "the polygon sizes do not add up to the index count".into(),
        E::IndexOutOfRange => "a polygon's vertex index is not below the vertex count".into(),
        E::CoordinateOutOfRange => {
            "a coordinate is beyond ±1024 (world coordinates must stay within ±1024)".into()
        }
        E::OutputTooSmall { .. } => e.to_string(),
        E::BadParameters => "invalid generator parameters (too few segments, radii out of \
             order, or more than 65536 vertices)"
            .into(),
        #[allow(unreachable_patterns)]
        other => format!("{other:?}"),
    }
}

/// Builds the generator's mesh (buffers sized by the core's `*_sizes`).
fn generate(name: &str, o: &ObjectSection) -> Result<HostMesh, String> {
    let allowed: &[&str] = match name {
        "cube" => &[],
        "sphere" => &["segments", "rings", "radius"],
        "torus" => &["rings", "sides", "major", "minor"],
        "prism" => &["sides", "outer", "inner", "half_height"],
        "quad" => &["size"],
        other => {
            return Err(format!(
                "unknown generator {other:?} (expected \"cube\", \"sphere\", \"torus\", \"prism\" or \"quad\")"
            ))
        }
    };
    let given = [
        ("segments", o.segments.is_some()),
        ("rings", o.rings.is_some()),
        ("radius", o.radius.is_some()),
        ("sides", o.sides.is_some()),
        ("major", o.major.is_some()),
        ("minor", o.minor.is_some()),
        ("outer", o.outer.is_some()),
        ("inner", o.inner.is_some()),
        ("half_height", o.half_height.is_some()),
        ("size", o.size.is_some()),
    ];
    for (key, set) in given {
        if set && !allowed.contains(&key) {
            return Err(format!("key `{key}` does not apply to generator {name:?}"));
        }
    }
    let bad = |e| format!("generator {name:?}: {}", mesh_error_words(e));
    match name {
        "cube" => Ok(from_core(generators::unit_cube())),
        "sphere" => {
            let (s, r) = (o.segments.unwrap_or(32), o.rings.unwrap_or(16));
            let radius = positive("radius", o.radius.unwrap_or(1.0))?;
            let (nv, ni) = generators::uv_sphere_sizes_checked(s, r).map_err(|_| {
                format!(
                    "sphere needs segments ≥ 3, rings ≥ 2 and 2 + (rings − 1)·segments ≤ {} \
                     vertices, got segments = {s}, rings = {r}",
                    generators::MAX_GENERATED_VERTICES
                )
            })?;
            let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            let mut uvs = vec![[0i16; 2]; ni];
            generators::uv_sphere_uvs(s, r, &mut uvs).map_err(bad)?;
            generators::uv_sphere(s, r, radius, &mut vs, &mut is)
                .and_then(|m| m.with_uvs(&uvs))
                .map(from_core)
                .map_err(bad)
        }
        "torus" => {
            let (r, s) = (o.rings.unwrap_or(24), o.sides.unwrap_or(12));
            let major = positive("major", o.major.unwrap_or(1.0))?;
            let minor = positive("minor", o.minor.unwrap_or(0.35))?;
            let (nv, ni) = generators::torus_sizes_checked(r, s).map_err(|_| {
                format!(
                    "torus needs rings, sides ≥ 3 and rings·sides ≤ {} vertices, \
                     got rings = {r}, sides = {s}",
                    generators::MAX_GENERATED_VERTICES
                )
            })?;
            let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            let mut uvs = vec![[0i16; 2]; ni];
            generators::torus_uvs(r, s, &mut uvs).map_err(bad)?;
            generators::torus(r, s, major, minor, &mut vs, &mut is)
                .and_then(|m| m.with_uvs(&uvs))
                .map(from_core)
                .map_err(bad)
        }
        "prism" => {
            let s = o.sides.unwrap_or(6);
            let outer = positive("outer", o.outer.unwrap_or(1.0))?;
            let inner = positive("inner", o.inner.unwrap_or(0.8))?;
            let hh = positive("half_height", o.half_height.unwrap_or(1.0))?;
            let (nv, ni) = generators::hollow_prism_sizes_checked(s).map_err(|_| {
                format!(
                    "prism needs 3 ≤ sides ≤ {}, got sides = {s}",
                    generators::MAX_GENERATED_VERTICES / 4
                )
            })?;
            let (mut vs, mut is) = (vec![Vec3::ZERO; nv], vec![0u16; ni]);
            let mut uvs = vec![[0i16; 2]; ni];
            generators::hollow_prism_uvs(s, &mut uvs).map_err(bad)?;
            generators::hollow_prism(s, outer, inner, hh, &mut vs, &mut is)
                .and_then(|m| m.with_uvs(&uvs))
                .map(from_core)
                .map_err(bad)
        }
        _ => {
            let [w, h] = o.size.unwrap_or([2.0, 2.0]);
            if !(finite(&[w, h]) && w > 0.0 && h > 0.0) {
                return Err(format!("quad `size` must be positive, got [{w}, {h}]"));
            }
            let (x, y) = (w / 2.0, h / 2.0);
            let one = TEX_ONE as i16;
            Ok(HostMesh {
                vertices: vec![[-x, -y, 0.0], [x, -y, 0.0], [x, y, 0.0], [-x, y, 0.0]],
                polygons: vec![vec![0, 1, 2, 3]],
                uvs: vec![[0, 0], [one, 0], [one, one], [0, one]],
            })
        }
    }
}

fn rot_x(a: f64, v: [f64; 3]) -> [f64; 3] {
    let (s, c) = a.sin_cos();
    [v[0], c * v[1] - s * v[2], s * v[1] + c * v[2]]
}

fn rot_y(a: f64, v: [f64; 3]) -> [f64; 3] {
    let (s, c) = a.sin_cos();
    [c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]]
}

fn rot_z(a: f64, v: [f64; 3]) -> [f64; 3] {
    let (s, c) = a.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
}

/// Applies the placement of the module doc in place.
fn place(mesh: &mut HostMesh, o: &ObjectSection) -> Result<(), String> {
    let s = match o.scale {
        ScaleKey::Uniform(s) => [s; 3],
        ScaleKey::Axes(a) => a,
    };
    if !finite(&s) || s.contains(&0.0) {
        return Err(format!("`scale` must be finite and non-zero, got {s:?}"));
    }
    if !finite(&o.rotate_deg) || !finite(&o.translate) {
        return Err("`rotate_deg` and `translate` must be finite".into());
    }
    let c = if o.center && !mesh.vertices.is_empty() {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &mesh.vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0)
    } else {
        [0.0; 3]
    };
    let [ax, ay, az] = o.rotate_deg.map(f64::to_radians);
    for v in &mut mesh.vertices {
        let p = sub(*v, c);
        let p = [p[0] * s[0], p[1] * s[1], p[2] * s[2]];
        let p = rot_z(az, rot_x(ax, rot_y(ay, p)));
        *v = [0, 1, 2].map(|k| p[k] + o.translate[k]);
    }
    // A mirroring scale turns the winding inside out: restore counter-clockwise outward.
    if s[0] * s[1] * s[2] < 0.0 {
        let mut at = 0;
        for p in &mut mesh.polygons {
            p.reverse();
            if let Some(uvs) = mesh.uvs.get_mut(at..at + p.len()) {
                uvs.reverse();
            }
            at += p.len();
        }
    }
    Ok(())
}

/// The un-normalised normal of a polygon: the sum of its fan triangles' cross products.
fn polygon_cross(vs: &[[f64; 3]], p: &[usize]) -> [f64; 3] {
    let o = vs[p[0]];
    let mut n = [0.0; 3];
    for k in 1..p.len() - 1 {
        let c = cross(sub(vs[p[k]], o), sub(vs[p[k + 1]], o));
        n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
    }
    n
}

/// SCENES.md's intensity of a unit normal (or none: ambient only).
fn intensity(n: Option<[f64; 3]>, light: [f64; 3], ka: f64, kd: f64) -> u8 {
    let d = n.map_or(0.0, |n| dot(n, light).max(0.0));
    ((ka + kd * d).clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Intensity tables of the module doc: per polygon (flat) or per vertex.
fn intensities(mesh: &HostMesh, flat: bool, light: &LightSection) -> Vec<u8> {
    let l = normalize(light.direction).unwrap_or([0.0; 3]);
    let (ka, kd) = (light.ka, light.kd);
    if flat {
        mesh.polygons
            .iter()
            .map(|p| intensity(normalize(polygon_cross(&mesh.vertices, p)), l, ka, kd))
            .collect()
    } else {
        let mut sum = vec![[0.0; 3]; mesh.vertices.len()];
        for p in &mesh.polygons {
            let o = mesh.vertices[p[0]];
            for k in 1..p.len() - 1 {
                let (b, c) = (mesh.vertices[p[k]], mesh.vertices[p[k + 1]]);
                let n = cross(sub(b, o), sub(c, o));
                for &i in &[p[0], p[k], p[k + 1]] {
                    sum[i] = [sum[i][0] + n[0], sum[i][1] + n[1], sum[i][2] + n[2]];
                }
            }
        }
        sum.into_iter()
            .map(|n| intensity(normalize(n), l, ka, kd))
            .collect()
    }
}

/// Loads the mesh source of one object.
fn object_mesh(o: &ObjectSection, dir: &Path, lines: &LineIndex) -> Result<HostMesh, String> {
    let at = |s: &Spanned<String>| lines.line(s.span().start);
    let sources = [&o.generator, &o.obj, &o.builtin]
        .iter()
        .filter(|s| s.is_some())
        .count();
    if sources != 1 {
        return Err(format!(
            "needs exactly one of `generator`, `obj` or `builtin` (found {sources})"
        ));
    }
    if let Some(g) = &o.generator {
        return generate(g.get_ref(), o).map_err(|e| format!("`generator` (line {}): {e}", at(g)));
    }
    let (path, key, mesh) = if let Some(p) = &o.obj {
        let path = dir.join(p.get_ref());
        let mesh = crate::obj::load_obj(&path).map_err(|e| match &e.kind {
            crate::obj::ObjErrorKind::Io(msg) => {
                format!("mesh (line {}): cannot read {msg}", at(p))
            }
            crate::obj::ObjErrorKind::FileTooLarge(_) => format!(
                "mesh (line {}): {}",
                at(p),
                e.to_string().trim_start_matches("line 0: ")
            ),
            _ => format!("mesh (line {}): {}: {e}", at(p), path.display()),
        })?;
        (path, p, mesh)
    } else {
        let b = o.builtin.as_ref().ok_or("no mesh source")?;
        match b.get_ref().as_str() {
            "bunny" => (
                std::path::PathBuf::from("builtin:bunny"),
                b,
                crate::scenes::bunny_mesh().map_err(|e| format!("mesh (line {}): {e}", at(b)))?,
            ),
            other => {
                return Err(format!(
                    "`builtin` (line {}): unknown builtin {other:?} (expected \"bunny\")",
                    at(b)
                ))
            }
        }
    };
    if mesh.polygons.is_empty() {
        return Err(format!(
            "mesh (line {}): {}: no faces",
            at(key),
            path.display()
        ));
    }
    // A textured OBJ needs its `vt`; an untextured one loads whatever they are.
    let uvs = match (&o.obj, &o.texture) {
        (Some(p), Some(_)) => mesh
            .texture_coordinates()
            .map_err(|e| {
                format!(
                    "mesh (line {}): {}: texture coordinates: {e}",
                    at(p),
                    path.display()
                )
            })?
            .to_vec(),
        _ => Vec::new(),
    };
    Ok(HostMesh {
        vertices: mesh.vertices,
        polygons: mesh.polygons,
        uvs,
    })
}

/// The shade table of `lut` for lit textures ([`TEXTURE_SHADE_LEVELS`] levels, the core's
/// `shade_table`).
fn texture_shades(lut: &Lut<Rgb888>) -> Vec<u8> {
    const ENTRIES: usize = TEXTURE_SHADE_LEVELS as usize * 256;
    let palette = lut.entries().map(|c| [c.r(), c.g(), c.b()]);
    shade_table::<ENTRIES>(&palette).to_vec()
}

/// The keys that only a textured object takes.
fn texture_keys(o: &ObjectSection) -> [(&'static str, bool); 3] {
    [
        ("texture_mode", o.texture_mode.is_some()),
        ("texture_lit", o.texture_lit.is_some()),
        ("uv_scale", o.uv_scale.is_some()),
    ]
}

/// The texture of an object whose `texture` is `file` (module doc, "Textures"): the image
/// over `lut`, `mesh`'s coordinates times `uv_scale`, the mode, and `shades` (the scene's
/// table, built at its first use) when lit.
fn prepare_texture(
    o: &ObjectSection,
    file: &Spanned<String>,
    mesh: &HostMesh,
    (lut, dir, lines): (&Lut<Rgb888>, &Path, &LineIndex),
    shades: &mut Option<Vec<u8>>,
) -> Result<PreparedTexture, String> {
    let key = format!("`texture` (line {})", lines.line(file.span().start));
    let corners: usize = mesh.polygons.iter().map(Vec::len).sum();
    if mesh.uvs.len() != corners {
        return Err(format!(
            "{key}: the mesh has no texture coordinates (the generators, the quad and OBJ \
             files with `vt` on every face corner have them)"
        ));
    }
    let [su, sv] = o.uv_scale.map_or([1.0; 2], |k| k.0);
    for f in [su, sv] {
        if !(f.is_finite() && f > 0.0 && f <= MAX_UV_SCALE) {
            return Err(format!(
                "`uv_scale` factor {f} is outside 0 < factor ≤ {MAX_UV_SCALE}"
            ));
        }
    }
    let scaled = |c: i16, f: f64| {
        let x = (c as f64 * f).round();
        if (i16::MIN as f64..=i16::MAX as f64).contains(&x) {
            Ok(x as i16)
        } else {
            Err(format!(
                "`uv_scale`: coordinate {} times {f} is {}, outside the core's Q8.8 range \
                 −128 ≤ u, v < 128",
                c as f64 / 256.0,
                x / 256.0
            ))
        }
    };
    let uvs = mesh
        .uvs
        .iter()
        .map(|&[u, v]| Ok([scaled(u, su)?, scaled(v, sv)?]))
        .collect::<Result<Vec<TexCoord>, String>>()?;
    let image = crate::texture_png::read_texture(&dir.join(file.get_ref()), lut)
        .map_err(|e| format!("{key}: {e}"))?;
    let shades = if o.texture_lit.unwrap_or(true) {
        Some(shades.get_or_insert_with(|| texture_shades(lut)).clone())
    } else {
        None
    };
    Ok(PreparedTexture {
        image,
        uvs,
        mode: o
            .texture_mode
            .map_or(TextureMode::Exact, TextureModeKey::mode),
        shades,
    })
}

/// The blend table of opacity `blend` (`0..=1`, rounded to 1/256) over `lut`.
fn blend_entries(lut: &Lut<Rgb888>, blend: f64) -> Result<Box<[u8; BLEND_ENTRIES]>, String> {
    if !(0.0..=1.0).contains(&blend) {
        return Err(format!("blend = {blend}: an opacity from 0 to 1"));
    }
    let mut entries: Box<[u8; BLEND_ENTRIES]> = vec![0u8; BLEND_ENTRIES]
        .into_boxed_slice()
        .try_into()
        .map_err(|_| "blend table size".to_string())?;
    BlendTable::build(lut, (blend * 256.0).round() as u16, &mut entries)
        .map_err(|e| format!("blend: {e}"))?;
    Ok(entries)
}

/// Rounds a placed, lit mesh into the core's tables.
/// How an object is shaded, as the scene file says.
struct Look {
    intensities: Vec<u8>,
    lit: Option<Material>,
    shade: ShadeKey,
    ramp: LuminanceRamp,
    cull: bool,
    dither: bool,
    wireframe: Option<Wireframe>,
    line_index: u8,
    opacity: Option<Opacity>,
    blend: Option<Box<[u8; BLEND_ENTRIES]>>,
    texture: Option<PreparedTexture>,
}

fn prepare(mesh: &HostMesh, look: Look) -> Result<PreparedObject, String> {
    if mesh.vertices.len() > 65_536 {
        return Err(format!(
            "{} vertices: the core indexes at most 65536",
            mesh.vertices.len()
        ));
    }
    let max = zscan::render::MAX_POLYGON_VERTICES;
    let mut sizes = Vec::with_capacity(mesh.polygons.len());
    let mut indices = Vec::new();
    for p in &mesh.polygons {
        if p.len() > max {
            return Err(format!(
                "a polygon has {} vertices (at most {max})",
                p.len()
            ));
        }
        sizes.push(p.len() as u8);
        indices.extend(p.iter().map(|&i| i as u16));
    }
    let uniform = sizes
        .first()
        .copied()
        .filter(|&n| sizes.iter().all(|&m| m == n));
    let mut vertices = Vec::with_capacity(mesh.vertices.len());
    for v in &mesh.vertices {
        if !finite(v) || v.iter().any(|c| c.abs() > 1024.0) {
            return Err(format!(
                "world position {v:?} outside the core's mesh range (|coordinate| ≤ 1024)"
            ));
        }
        vertices.push(Vec3::new(coord(v[0]), coord(v[1]), coord(v[2])));
    }
    let mut o = PreparedObject {
        normals: Vec::new(),
        vertices,
        indices,
        sizes,
        uniform,
        intensities: look.intensities,
        lit: look.lit,
        shade: look.shade,
        ramp: look.ramp,
        cull: look.cull,
        dither: look.dither,
        wireframe: look.wireframe,
        line_index: look.line_index,
        opacity: look.opacity,
        blend: look.blend,
        texture: look.texture,
    };
    if o.lit.is_some() {
        let mut normals = vec![Vec3::ZERO; o.vertices.len()];
        let sizes = match o.uniform {
            Some(n) => PolygonSizes::Uniform(n),
            None => PolygonSizes::PerPolygon(&o.sizes),
        };
        Mesh::new(&o.vertices, &o.indices, sizes)
            .and_then(|m| m.vertex_normals(&mut normals))
            .map_err(|e| format!("vertex normals: {}", mesh_error_words(e)))?;
        o.normals = normals;
    }
    Ok(o)
}

/// Largest magnitude of a camera or principal-point value: the core's I16F16 holds
/// `−32768 ≤ v < 32768`; values are rounded to 2^-16 once.
pub const MAX_CAMERA_VALUE: f64 = 32767.0;

/// `v` as the core's I16F16, or an error naming `field`, the value and the range
/// `lo..=hi` (both within ±[`MAX_CAMERA_VALUE`]); never a silent clamp.
fn fixed_in(
    field: &str,
    v: f64,
    lo: f64,
    hi: f64,
) -> Result<zscan::geometry::fixed::Coord, String> {
    if !(v.is_finite() && lo <= v && v <= hi) {
        return Err(format!(
            "{field} = {v} is outside the supported range {lo}..={hi}"
        ));
    }
    Ok(coord(v))
}

/// A point or vector of `[camera]`, each coordinate within ±[`MAX_CAMERA_VALUE`].
fn camera_point(field: &str, a: [f64; 3]) -> Result<Vec3, String> {
    let m = MAX_CAMERA_VALUE;
    let mut c = [zscan::geometry::fixed::Coord::ZERO; 3];
    for (k, slot) in c.iter_mut().enumerate() {
        *slot = fixed_in(&format!("[camera] {field}[{k}]"), a[k], -m, m)?;
    }
    Ok(Vec3::new(c[0], c[1], c[2]))
}

/// Words for the core's camera errors (the core's enum has no `Display` in this tree).
fn camera_error_words(e: zscan::geometry::camera::CameraError) -> String {
    use zscan::geometry::camera::CameraError as E;
    match e {
        E::ZeroViewDirection => "eye and target are the same point (no view direction)".into(),
        E::UpParallelToView => "`up` is zero or parallel to the view direction".into(),
        E::FovOutOfRange => "fov_deg is not strictly between 0 and 180 degrees".into(),
        E::FocalTooLong => {
            "the field of view is so narrow that a focal length reaches 32768 pixels".into()
        }
        E::BadViewport => "the viewport's image extent (size × pixel_aspect) exceeds 2^20 \
             physical units, or a size is zero"
            .into(),
        E::BadDepthRange => "near and far do not satisfy 0 < near < far in I16F16".into(),
        E::OutOfRange => "a derived position or distance (eye − target, focal length) leaves \
             the core's range ±32768"
            .into(),
        E::BadExtent => "the orthographic width or height gives a scale outside 2^-16 to 2^15 \
             pixels per world unit"
            .into(),
    }
}

fn build_camera(c: &CameraSection, v: &ViewportSection) -> Result<Camera, String> {
    if !(c.fov_deg.is_finite() && c.fov_deg > 0.0 && c.fov_deg < 180.0) {
        return Err(format!(
            "[camera] fov_deg must be strictly between 0 and 180, got {}",
            c.fov_deg
        ));
    }
    // near ≥ 2^-16 (the smallest positive I16F16), far ≤ 32767, and still near < far after
    // rounding to 2^-16.
    let min_near = 1.0 / 65536.0;
    let near = fixed_in("[camera] near", c.near, min_near, MAX_CAMERA_VALUE)?;
    let far = fixed_in("[camera] far", c.far, min_near, MAX_CAMERA_VALUE)?;
    if far <= near {
        return Err(format!(
            "[camera] needs near < far (after rounding to 1/65536), got near = {}, far = {}",
            c.near, c.far
        ));
    }
    let (eye, target, up) = (
        camera_point("eye", c.eye)?,
        camera_point("target", c.target)?,
        camera_point("up", c.up)?,
    );
    let side = |key: &str, n: i64| {
        let max = super::MAX_PICTURE_SIDE;
        u16::try_from(n)
            .ok()
            .filter(|n| (1..=max).contains(n))
            .ok_or_else(|| {
                format!("[viewport] {key} = {n} is outside the supported sizes 1..={max} pixels")
            })
    };
    let (width, height) = (side("width", v.width)?, side("height", v.height)?);
    if v.pixel_aspect.contains(&0) {
        return Err("[viewport] pixel_aspect entries must be positive".into());
    }
    let lens = Lens {
        fov: BinaryAngle::from_turns(
            (c.fov_deg / 360.0 * (1u64 << 31) as f64).round() as i64,
            1 << 31,
        ),
        axis: match c.fov_axis {
            FovAxisKey::Vertical => FovAxis::Vertical,
            FovAxisKey::Horizontal => FovAxis::Horizontal,
            FovAxisKey::Diagonal => FovAxis::Diagonal,
        },
        near,
        far,
    };
    let mut vp = Viewport::new(width, height);
    if let Some([px, py]) = v.principal {
        let m = MAX_CAMERA_VALUE;
        vp.principal_x = fixed_in("[viewport] principal[0]", px, -m, m)?;
        vp.principal_y = fixed_in("[viewport] principal[1]", py, -m, m)?;
    }
    vp.pixel_width = v.pixel_aspect[0];
    vp.pixel_height = v.pixel_aspect[1];
    let built = match (c.projection, c.width, c.height) {
        (ProjectionKey::Perspective, None, None) => Camera::look_at(eye, target, up, lens, vp),
        (ProjectionKey::Perspective, _, _) => {
            return Err(
                "[camera] width and height are for projection = \"orthographic\"; a \
                 perspective camera takes fov_deg"
                    .into(),
            )
        }
        (ProjectionKey::Orthographic, Some(e), None)
        | (ProjectionKey::Orthographic, None, Some(e)) => {
            let key = if c.width.is_some() { "width" } else { "height" };
            let extent = fixed_in(
                &format!("[camera] {key}"),
                e,
                1.0 / 65536.0,
                MAX_CAMERA_VALUE,
            )?;
            let axis = if c.width.is_some() {
                FovAxis::Horizontal
            } else {
                FovAxis::Vertical
            };
            let view = OrthoView {
                extent,
                axis,
                near,
                far,
            };
            Camera::look_at_orthographic(eye, target, up, view, vp)
        }
        (ProjectionKey::Orthographic, _, _) => {
            return Err(
                "[camera] projection = \"orthographic\" needs exactly one of `width` or \
                 `height` (the view's extent in world units)"
                    .into(),
            )
        }
    };
    built.map_err(|e| {
        format!(
            "[camera]: cannot build the camera: {}",
            camera_error_words(e)
        )
    })
}

fn build_lut(l: &LutSection) -> Result<(Lut<Rgb888>, Vec<LuminanceRamp>), String> {
    let (mut lut, ramps) = match l.kind {
        LutKind::Grey => (Lut::grey_ramp(), vec![LuminanceRamp::GREY]),
        LutKind::Shaded => {
            if l.colours.is_empty() {
                return Err("[lut] kind = \"shaded\" needs `colours = [[r, g, b], ...]`".into());
            }
            let first = l.first.unwrap_or(1);
            let bases: Vec<Rgb888> = l
                .colours
                .iter()
                .map(|c| Rgb888::new(c[0], c[1], c[2]))
                .collect();
            let lut = Lut::shaded(&bases, l.levels, first).map_err(|e| format!("[lut]: {e}"))?;
            let ramps = (0..bases.len())
                .map(|m| LuminanceRamp {
                    first: (first as usize + m * l.levels as usize) as u8,
                    levels: l.levels as u16,
                })
                .collect();
            (lut, ramps)
        }
    };
    for e in &l.entries {
        lut.set(e[0], Rgb888::new(e[1], e[2], e[3]));
    }
    Ok((lut, ramps))
}

/// Parses and converts a scene file's text; `path` names it in messages and anchors `obj`
/// paths.
pub fn load_scene_str(text: &str, path: &Path) -> Result<LoadedScene, String> {
    let name = path.display();
    let file: SceneFile = toml::from_str(text).map_err(|e| format!("{name}: {e}"))?;
    if file.render.subpixel_bits != SUBPIXEL_BITS {
        return Err(format!(
            "{name}: [render] subpixel_bits: only {SUBPIXEL_BITS} is supported, got {}",
            file.render.subpixel_bits
        ));
    }
    if file.render.depth_bits != 16 && file.render.depth_bits != 32 {
        return Err(format!(
            "{name}: [render] depth_bits must be 16 or 32, got {}",
            file.render.depth_bits
        ));
    }
    if !finite(&[file.light.ka, file.light.kd]) || normalize(file.light.direction).is_none() {
        return Err(format!(
            "{name}: [light] needs a finite non-zero direction and finite ka, kd"
        ));
    }
    let camera = build_camera(&file.camera, &file.viewport).map_err(|e| format!("{name}: {e}"))?;
    let (lut, ramps) = build_lut(&file.lut).map_err(|e| format!("{name}: {e}"))?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let lines = LineIndex::of(text);
    let mut objects = Vec::new();
    let mut shades = None;
    let mut triangles_in = 0u64;
    for (k, spanned) in file.objects.iter().enumerate() {
        let o = spanned.get_ref();
        let line = lines.line(spanned.span().start);
        let err = |e: String| format!("{name}: object {} (line {line}): {e}", k + 1);
        let mut mesh = object_mesh(o, dir, &lines).map_err(err)?;
        place(&mut mesh, o).map_err(err)?;
        let ramp = match file.lut.kind {
            LutKind::Grey => LuminanceRamp::GREY,
            LutKind::Shaded => *ramps.get(o.material.ramp() as usize).ok_or_else(|| {
                err(format!(
                    "material {} but [lut] has {} colours",
                    o.material.ramp(),
                    ramps.len()
                ))
            })?,
        };
        let shade = o.shade.unwrap_or(file.render.shade);
        let lit = match o.material {
            MaterialKey::Lit(m) => {
                if file.lighting.is_none() {
                    return Err(err(
                        "a material with reflection coefficients needs a [lighting] section".into(),
                    ));
                }
                Some(m.material().map_err(err)?)
            }
            MaterialKey::Ramp(_) if shade == ShadeKey::Phong => {
                return Err(err(
                    "shade = \"phong\" needs a material with reflection coefficients \
                     (material = { ka, kd, ks, n }) and [lighting]"
                        .into(),
                ))
            }
            MaterialKey::Ramp(_) => None,
        };
        let table = if lit.is_some() {
            Vec::new()
        } else {
            intensities(&mesh, shade == ShadeKey::Flat, &file.light)
        };
        triangles_in += mesh
            .polygons
            .iter()
            .map(|p| p.len().saturating_sub(2) as u64)
            .sum::<u64>();
        let look = Look {
            intensities: table,
            lit,
            shade,
            ramp,
            cull: o.cull.unwrap_or(file.render.cull),
            dither: o.dither.unwrap_or(file.render.dither),
            wireframe: o.wireframe.map(WireKey::mode),
            line_index: o.line_index.unwrap_or(
                (ramp.first as u16 + ramp.levels as u16)
                    .saturating_sub(1)
                    .min(255) as u8,
            ),
            opacity: o
                .opacity
                .map(Opacity::new)
                .transpose()
                .map_err(|e| err(format!("opacity: {e}")))?,
            blend: o
                .blend
                .map(|b| blend_entries(&lut, b))
                .transpose()
                .map_err(err)?,
            texture: None,
        };
        if look.opacity.is_some() && look.blend.is_some() {
            return Err(err(
                "an object is a screen door (opacity) or blended (blend), not both".into(),
            ));
        }
        let mut look = look;
        match &o.texture {
            None => {
                if let Some((key, _)) = texture_keys(o).iter().find(|(_, set)| *set) {
                    return Err(err(format!(
                        "`{key}` applies to a textured object (this one has no `texture`)"
                    )));
                }
            }
            Some(file) => {
                let clash = [
                    ("wireframe", look.wireframe.is_some()),
                    ("opacity", look.opacity.is_some()),
                    ("blend", look.blend.is_some()),
                    ("dither", look.dither),
                ];
                if let Some((key, _)) = clash.iter().find(|(_, set)| *set) {
                    return Err(err(format!(
                        "a textured object takes no `{key}` (the core's textured spans are \
                         opaque, undithered surfaces){}",
                        if *key == "dither" {
                            "; set `dither = false` on it"
                        } else {
                            ""
                        }
                    )));
                }
                look.texture = Some(
                    prepare_texture(o, file, &mesh, (&lut, dir, &lines), &mut shades)
                        .map_err(err)?,
                );
            }
        }
        objects.push(prepare(&mesh, look).map_err(err)?);
    }
    let mut lines = Vec::new();
    for (k, l) in file.lines.iter().enumerate() {
        let err = |e: String| format!("{name}: lines {}: {e}", k + 1);
        let mut points = Vec::with_capacity(l.points.len());
        for v in &l.points {
            if !finite(v) || v.iter().any(|c| c.abs() > 1024.0) {
                return Err(err(format!(
                    "point {v:?} outside the core's mesh range (|coordinate| ≤ 1024)"
                )));
            }
            points.push(Vec3::new(coord(v[0]), coord(v[1]), coord(v[2])));
        }
        if points.len() > 65_536 {
            return Err(err(format!("{} points: at most 65536", points.len())));
        }
        lines.push(PreparedLines {
            points,
            segments: l.segments.clone(),
            index: l.index,
            point_size: l.point_size,
        });
    }
    let (ambient, lights) = match &file.lighting {
        Some(l) => (l.ambient, lights(l).map_err(|e| format!("{name}: {e}"))?),
        None => (0, Vec::new()),
    };
    Ok(LoadedScene {
        camera,
        objects,
        lut,
        ambient,
        lights,
        background: file.render.background,
        depth_bits: file.render.depth_bits,
        view: file.camera.clone(),
        triangles_in,
        lines,
    })
}

/// Reads, parses and converts a scene file.
pub fn load_scene(path: &Path) -> Result<LoadedScene, String> {
    let text = fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read scene: {e}", path.display()))?;
    load_scene_str(&text, path)
}

/// A rendered frame.
#[derive(Debug, Clone)]
pub struct Frame<D> {
    /// Palette indices, row-major.
    pub pixels: Vec<u8>,
    /// Depth samples, row-major (`D::FAR` where nothing was drawn).
    pub depth: Vec<D>,
    /// Core statistics, summed over bands.
    pub stats: RenderStats,
    /// Number of bands drawn.
    pub bands: u32,
}

impl LoadedScene {
    /// Renders the frame with the core, in one pass or in bands of `band_rows` rows.
    ///
    /// Errors are in words ([`render_error_words`]); when the frame fails, each object is
    /// rendered alone to name the first one that fails by itself with the same error
    /// (`object k of n`). An error no object causes alone (more objects than a stored
    /// triangle can name, a store filled by all of them together) names none.
    pub fn render<D: DepthValue>(&self, band_rows: Option<u16>) -> Result<Frame<D>, String> {
        self.render_by::<D>(band_rows, Visibility::ZBuffer)
    }

    /// The frame planned within `budget` bytes and drawn as planned
    /// ([`render_planned`](crate::core_render::render_planned), which runs
    /// [`zscan::visibility::plan_frame`]), each mesh's facts computed here
    /// ([`MeshFacts::of`](zscan::visibility::MeshFacts::of)): the plan, the drawing order it
    /// wrote, the picture (depth samples all far) and its counts.
    pub fn render_planned(
        &self,
        budget: usize,
    ) -> Result<crate::core_render::PlannedFrame, String> {
        if self.objects.iter().any(|o| o.wireframe.is_some()) || !self.lines.is_empty() {
            return Err(
                "wireframes and [[lines]] are drawn through the whole-frame z-buffer, \
                        which the planner does not plan"
                    .into(),
            );
        }
        let objects = self.core_objects(None)?;
        let scene = self.core_scene(&objects);
        let mut pairs = Vec::new();
        let facts = crate::core_render::mesh_facts(&scene, &mut pairs)?;
        let renderer = SceneRenderer::<SUBPIXEL_BITS>::new(&scene)
            .map_err(|e| format!("camera: {}", render_error_words(&e)))?;
        crate::core_render::render_planned(&renderer, &facts, budget)
    }

    /// The core objects of the scene, or object `only` alone.
    pub(crate) fn core_objects(
        &self,
        only: Option<usize>,
    ) -> Result<Vec<zscan::scene::Object<'_>>, String> {
        self.objects
            .iter()
            .enumerate()
            .filter(|(k, _)| only.is_none_or(|o| o == *k))
            .map(|(k, o)| o.object().map_err(|e| format!("object {}: {e}", k + 1)))
            .collect()
    }

    /// The core scene of `objects` with this scene's camera, lights and background.
    fn core_scene<'a>(&'a self, objects: &'a [zscan::scene::Object<'a>]) -> Scene<'a> {
        Scene {
            camera: self.camera,
            objects,
            background: self.background,
            ambient: self.ambient,
            lights: &self.lights,
        }
    }

    /// [`LoadedScene::render`] by the hidden-surface method `visibility` (the depth samples
    /// are all far for the methods without a frame of depth).
    pub fn render_by<D: DepthValue>(
        &self,
        band_rows: Option<u16>,
        visibility: Visibility,
    ) -> Result<Frame<D>, String> {
        let e = match self.render_objects::<D>(band_rows, None, visibility) {
            Ok(frame) => return Ok(frame),
            Err(e) => e,
        };
        let n = self.objects.len();
        let words = e.words();
        if let FrameError::Method(VisibilityError::TooManyObjects { .. }) = e {
            return Err(format!(
                "render: {words} (the scene has {n}; --visibility {visibility} stores \
                 triangles, which name their object in one byte)"
            ));
        }
        // An object is named only when it fails alone with the same error.
        let culprit = (0..n).find(|&k| {
            self.render_objects::<D>(band_rows, Some(k), visibility)
                .is_err_and(|alone| alone.words() == words)
        });
        Err(match culprit {
            Some(k) if n > 1 => format!("render: object {} of {n}: {words}", k + 1),
            Some(_) => format!("render: object 1: {words}"),
            None => format!("render: {words}"),
        })
    }

    /// [`LoadedScene::render`] of every object, or of object `only` alone.
    fn render_objects<D: DepthValue>(
        &self,
        band_rows: Option<u16>,
        only: Option<usize>,
        visibility: Visibility,
    ) -> Result<Frame<D>, FrameError> {
        let vp = *self.camera.viewport();
        let (w, h) = (vp.width, vp.height);
        super::check_picture_size("[viewport] width × height", w, h).map_err(FrameError::Setup)?;
        let lined = self.objects.iter().any(|o| o.wireframe.is_some()) || !self.lines.is_empty();
        if lined && (visibility != Visibility::ZBuffer || band_rows.is_some()) {
            return Err(FrameError::Setup(format!(
                "wireframes and [[lines]] are drawn through the whole-frame z-buffer: \
                 --visibility zbuffer without --bands (asked: --visibility {visibility}{})",
                band_rows.map_or(String::new(), |b| format!(", --bands {b}"))
            )));
        }
        let all = self.core_objects(only).map_err(FrameError::Setup)?;
        let kept: Vec<usize> = (0..self.objects.len())
            .filter(|k| only.is_none_or(|o| o == *k))
            .collect();
        // Shaded objects through the frame's method; wireframes after them, as lines.
        let objects: Vec<_> = all
            .iter()
            .zip(&kept)
            .filter(|(_, &k)| self.objects[k].wireframe.is_none())
            .map(|(o, _)| *o)
            .collect();
        let scene = self.core_scene(&objects);
        let renderer = Renderer::<SUBPIXEL_BITS>::for_scene(&scene)
            .map_err(|e| FrameError::Setup(format!("camera: {}", render_error_words(&e))))?;
        if visibility == Visibility::ReversePainter {
            let (pixels, stats) =
                crate::core_render::reverse_picture(&renderer, (w, h)).map_err(|e| match e {
                    refused @ VisibilityError::ReverseRefused(_) => {
                        FrameError::Setup(refused.to_string())
                    }
                    e => FrameError::from(e),
                })?;
            let depth = vec![D::FAR; w as usize * h as usize];
            return Ok(Frame {
                pixels,
                depth,
                stats,
                bands: 1,
            });
        }
        if visibility != Visibility::ZBuffer {
            let band = band_rows.unwrap_or(1);
            let (pixels, stats) = crate::core_render::render_visible_at::<D, SUBPIXEL_BITS>(
                &renderer,
                (w, h),
                visibility,
                Some(PAINTER_SPLITS),
                band,
            )
            .map_err(FrameError::from)?;
            let bands = if visibility == Visibility::ScanLine {
                band_count(h, band)
            } else {
                1
            };
            let depth = vec![D::FAR; w as usize * h as usize];
            return Ok(Frame {
                pixels,
                depth,
                stats,
                bands,
            });
        }
        // The vertex stage once per frame and the polygon table (render_in_bands' faster
        // switches): scratch for every object's vertices and polygons.
        let vertices: usize = objects.iter().map(|o| o.mesh.vertices().len()).sum();
        let polygons: usize = objects.iter().map(|o| o.mesh.polygon_count()).sum();
        let mut scratch = vec![PreparedVertex::default(); vertices];
        let mut table = vec![PolygonRows::default(); polygons];
        let (pixels, depth, stats) = crate::core_render::render_picture(
            &renderer,
            (w, h),
            band_rows,
            BandScratch {
                vertices: &mut scratch,
                polygons: &mut table,
            },
        )
        .map_err(FrameError::Render)?;
        let (mut pixels, mut depth, mut stats) = (pixels, depth, stats);
        if lined {
            let wires: Vec<_> = all
                .iter()
                .zip(&kept)
                .filter_map(|(o, &k)| self.objects[k].wireframe.map(|m| (o, m, &self.objects[k])))
                .collect();
            let lines = if only.is_none() { &self.lines[..] } else { &[] };
            let drawn = self.draw_lines::<D>(
                renderer.renderer(),
                (w, h),
                &wires,
                lines,
                &mut pixels,
                &mut depth,
            )?;
            stats.pixels_written = stats.pixels_written.saturating_add(drawn);
            stats.pixels_covered = stats.pixels_covered.saturating_add(drawn);
        }
        let bands = band_count(h, band_rows.unwrap_or(h));
        Ok(Frame {
            pixels,
            depth,
            stats,
            bands,
        })
    }
}

/// Runs `f` with Appel's scratch for `object` (`render::appel`): the half-edges, and a
/// crossing per half-edge (no edge crosses more contour edges than the mesh has edges).
pub(crate) fn appel_pieces<T>(
    object: &Object<'_>,
    f: impl FnOnce(
        &mut AppelScratch<'_>,
        &mut [PreparedVertex<SUBPIXEL_BITS>],
    ) -> Result<T, zscan::render::RenderError>,
    scratch: &mut [PreparedVertex<SUBPIXEL_BITS>],
) -> Result<T, zscan::render::RenderError> {
    let n = AppelScratch::edges_needed(&object.mesh);
    let mut edges = vec![AppelEdge::ZERO; n];
    let mut crossings = vec![AppelCrossing::ZERO; n];
    let mut memory = AppelScratch {
        edges: &mut edges,
        crossings: &mut crossings,
    };
    f(&mut memory, scratch)
}

impl LoadedScene {
    /// The wireframes `wires` and the line lists `lines` into the finished picture, through
    /// its depth (module doc, "Wireframes, lines and points"). Returns the pixels drawn.
    fn draw_lines<D: DepthValue>(
        &self,
        renderer: &Renderer<SUBPIXEL_BITS>,
        (w, h): (u16, u16),
        wires: &[(&Object<'_>, Wireframe, &PreparedObject)],
        lines: &[PreparedLines],
        pixels: &mut [u8],
        depth: &mut [D],
    ) -> Result<u32, FrameError> {
        let mut frame = Framebuffer::new(pixels, w, h)
            .map_err(|e| FrameError::Setup(format!("frame: {e:?}")))?;
        let mut depth = DepthBuffer::new(depth, w, h)
            .map_err(|e| FrameError::Setup(format!("depth buffer: {e:?}")))?;
        let mut drawn = 0;
        for (object, mode, prepared) in wires {
            let mesh = object.mesh;
            if *mode == Wireframe::Appel {
                let number = self
                    .objects
                    .iter()
                    .position(|p| std::ptr::eq(p, *prepared))
                    .map_or(0, |k| k + 1);
                let mut scratch = vec![PreparedVertex::default(); mesh.vertices().len()];
                drawn += appel_pieces(
                    object,
                    |memory, scratch| {
                        renderer.draw_appel(
                            object,
                            scratch,
                            memory,
                            prepared.line_index,
                            &mut frame,
                        )
                    },
                    &mut scratch,
                )
                .map_err(|e| {
                    FrameError::Setup(format!(
                        "object {number} (wireframe \"appel\"): {}",
                        render_error_words(&e)
                    ))
                })?;
                continue;
            }
            let mut edges = vec![[0u16; 2]; mesh.indices().len()];
            let k = match mode {
                Wireframe::All => mesh
                    .edges(&mut edges)
                    .map_err(|e| FrameError::Setup(format!("edges: {}", mesh_error_words(e))))?,
                _ => 0,
            };
            let mut scratch = vec![PreparedVertex::default(); mesh.vertices().len()];
            let style = LineStyle::new(prepared.line_index);
            drawn += renderer
                .draw_wireframe(
                    object,
                    &edges[..k],
                    *mode,
                    &mut scratch,
                    &style,
                    &mut frame,
                    &mut depth,
                )
                .map_err(FrameError::Render)?;
        }
        for l in lines {
            let mesh = Mesh::new(&l.points, &[], PolygonSizes::Uniform(3))
                .map_err(|e| FrameError::Setup(format!("lines: {}", mesh_error_words(e))))?;
            let object = Object::new(mesh);
            let mut scratch = vec![PreparedVertex::default(); l.points.len()];
            let style = LineStyle::new(l.index);
            drawn += renderer
                .draw_lines(
                    &object,
                    &l.segments,
                    &mut scratch,
                    &style,
                    &mut frame,
                    &mut depth,
                )
                .map_err(FrameError::Render)?;
            if l.point_size > 0 {
                drawn += renderer
                    .draw_points(
                        &object,
                        &mut scratch,
                        l.point_size,
                        &style,
                        &mut frame,
                        &mut depth,
                    )
                    .map_err(FrameError::Render)?;
            }
        }
        Ok(drawn)
    }
}

/// Why [`LoadedScene::render_objects`] drew no frame: the scene could not be set up (words),
/// or the core refused it.
enum FrameError {
    /// Picture size, meshes, camera: in words.
    Setup(String),
    /// The core's error.
    Render(zscan::render::RenderError),
    /// A hidden-surface method's own refusal (its store, budget or stacks, an object it does
    /// not draw in parts).
    Method(VisibilityError),
}

impl From<VisibilityError> for FrameError {
    /// The pipeline's error a method passed on is [`FrameError::Render`].
    fn from(e: VisibilityError) -> Self {
        match e {
            VisibilityError::Render(e) => FrameError::Render(e),
            e => FrameError::Method(e),
        }
    }
}

impl FrameError {
    fn words(&self) -> String {
        match self {
            FrameError::Setup(s) => s.clone(),
            FrameError::Render(e) => render_error_words(e),
            FrameError::Method(e) => e.to_string(),
        }
    }
}

/// The number of bands of `band_rows` rows a picture `h` rows high is drawn in (the last band
/// may be shorter; a band taller than the picture is the picture). Counted after the core drew,
/// which refuses a `band_rows` of 0 (`BadBandRows`): a 0 here is taken as one row, and a
/// picture of no row has no band.
fn band_count(h: u16, band_rows: u16) -> u32 {
    h.div_ceil(band_rows.clamp(1, h.max(1))) as u32
}

/// Words for a hidden-surface method's [`VisibilityError`]: the pipeline's as
/// [`render_error_words`], the method's own as the core prints them.
pub fn visibility_error_words(e: &VisibilityError) -> String {
    match e {
        VisibilityError::Render(e) => render_error_words(e),
        other => other.to_string(),
    }
}

/// Words for a core [`RenderError`](zscan::render::RenderError), naming the limit that was
/// reached (the core's own `Display` prints some inner errors by their Debug names).
pub fn render_error_words(e: &zscan::render::RenderError) -> String {
    use zscan::geometry::matrix::MatrixError;
    use zscan::lighting::LightingError;
    use zscan::raster::triangle::DrawError;
    use zscan::render::ClipError;
    use zscan::render::ProjectError;
    use zscan::render::{RenderError as R, MAX_POLYGON_VERTICES};
    let matrix = |m: &MatrixError| match m {
        MatrixError::OutOfRange => {
            "a linear entry would exceed ±64 or a translation would leave ±32768".to_string()
        }
        MatrixError::ZeroAxis => "a rotation axis is the zero vector".into(),
        MatrixError::NotRigid => "the view's linear part is not a rotation".into(),
    };
    match e {
        R::Transform(m) => format!("transform: {}", matrix(m)),
        R::Projection(p) => match p {
            ProjectError::BehindNearPlane => {
                "projection: a vertex is nearer than the near plane".into()
            }
            ProjectError::OutOfRange => format!(
                "projection: a vertex projects outside the raster's range of ±{} sub-pixel units",
                zscan::raster::MAX_COORD
            ),
            ProjectError::SubpixelBitsTooLarge => {
                "projection: sub-pixel bits above the raster's limit of 16".into()
            }
            ProjectError::Orthographic(stage) => {
                format!("projection: {stage} needs a perspective camera, not the orthographic one")
            }
        },
        R::Clip(c) => match c {
            ClipError::CapacityExceeded => format!(
                "clipping: a clipped polygon needs more vertices than the clipper holds \
                 ({MAX_POLYGON_VERTICES} + 6; non-convex polygons can exceed it)"
            ),
            ClipError::PlaneOutOfRange => {
                "clipping: a frustum plane coefficient exceeds ±8192".into()
            }
            #[allow(unreachable_patterns)]
            other => format!("clipping: {other:?}"),
        },
        R::Draw(DrawError::Fill(f)) => format!("raster: {f}"),
        R::Lighting(l) => match l {
            LightingError::TooManyLights => {
                format!("lighting: more than {} lights", zscan::lighting::MAX_LIGHTS)
            }
            LightingError::ZeroDirection => {
                "lighting: a directional light has a zero direction".into()
            }
            LightingError::OutputTooSmall { .. }
            | LightingError::ZeroAxis { .. }
            | LightingError::ConeOutOfRange { .. }
            | LightingError::AttenuationOutOfRange { .. } => l.to_string(),
            LightingError::Transform(m) => format!("lighting transform: {}", matrix(m)),
        },
        // Without the core's 0-based index: the caller names the object (`object k of n`).
        R::TextureUnsupported { method, .. } => format!(
            "the object is textured, which {method} does not draw (draw it with the depth \
             buffer: --visibility zbuffer, whole or in --bands)"
        ),
        other => other.to_string(),
    }
}

/// The depth image of the module doc: nearest 255, farthest drawn 32, background 0.
pub fn depth_to_grey<D: DepthValue + Into<u64>>(depth: &[D]) -> Vec<u8> {
    let far: u64 = D::FAR.into();
    let drawn = depth.iter().map(|&d| d.into()).filter(|&d| d != far);
    let (lo, hi) = drawn.fold((u64::MAX, 0), |(lo, hi), d| (lo.min(d), hi.max(d)));
    depth
        .iter()
        .map(|&d| {
            let d: u64 = d.into();
            if d == far {
                0
            } else if hi == lo {
                255
            } else {
                (255 - ((d - lo) as u128 * 223 / (hi - lo) as u128) as u64) as u8
            }
        })
        .collect()
}

fn write_grey_png(path: &Path, w: u16, h: u16, data: &[u8]) -> Result<(), String> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let file =
        fs::File::create(path).map_err(|e| format!("{}: cannot create: {e}", path.display()))?;
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w as u32, h as u32);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Eight);
    let mut wr = enc
        .write_header()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    wr.write_image_data(data)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    wr.finish().map_err(|e| format!("{}: {e}", path.display()))
}

fn finish<D: DepthValue + Into<u64>>(
    args: &RenderArgs,
    scene: &LoadedScene,
) -> Result<(), CliError> {
    let visibility = args.visibility.0.unwrap_or(Visibility::ZBuffer);
    let frame = scene.render_by::<D>(args.bands, visibility)?;
    let vp = *scene.camera.viewport();
    let (w, h) = (vp.width, vp.height);
    let mut pixels = frame.pixels.clone();
    let fb = Framebuffer::new(&mut pixels, w, h).map_err(|e| format!("frame: {e}"))?;
    crate::image::write_image(&args.output, &fb, &scene.lut).map_err(|e| e.0)?;
    if let Some(p) = &args.svg {
        let text = super::svg::appel_svg(scene)?;
        std::fs::write(p, text).map_err(|e| format!("{}: {e}", p.display()))?;
    }
    if let Some(p) = &args.depth_out {
        write_grey_png(p, w, h, &depth_to_grey(&frame.depth))?;
    }
    if let Some(p) = &args.stats {
        let s = frame.stats;
        let band_rows = args
            .bands
            .unwrap_or(if visibility == Visibility::ScanLine {
                1
            } else {
                h
            })
            .clamp(1, h);
        let objects = scene.core_objects(None)?;
        let vertices: usize = objects.iter().map(|o| o.mesh.vertices().len()).sum();
        let polygons: usize = objects.iter().map(|o| o.mesh.polygon_count()).sum();
        // The scan-line's band depth and the z-buffer's are the scene's (render_visible_at).
        let depth_bytes = D::BITS as usize / 8;
        let ram_bytes = crate::core_render::ram_bytes::<SUBPIXEL_BITS>(
            visibility,
            (w, h),
            band_rows,
            (vertices, polygons),
            depth_bytes,
            &s,
        );
        let m = s.method;
        let method = match visibility {
            Visibility::Painter => serde_json::json!({
                "tests": m.painter_tests,
                "ambiguities": m.painter_ambiguities,
                "splits": m.painter_splits,
                "stored": m.stored,
                "pieces": m.pieces,
            }),
            Visibility::ScanLine => serde_json::json!({
                "active_peak": m.active_peak,
                "stored": m.stored,
            }),
            Visibility::Warnock => serde_json::json!({
                "windows": m.windows.total(),
                "windows_empty": m.windows.empty,
                "windows_one": m.windows.one,
                "windows_front": m.windows.front,
                "windows_pixel": m.windows.pixel,
                "windows_split": m.windows.split,
                "candidates_peak": m.candidates_peak,
                "stack_peak": m.stack_peak,
                "stored": m.stored,
            }),
            Visibility::BackFace | Visibility::ReversePainter | Visibility::ZBuffer => {
                serde_json::json!({})
            }
        };
        let json = stats_json(
            scene,
            StatsFrame {
                size: (w, h),
                bands: frame.bands,
                band_rows,
                depth_bits: D::BITS,
                visibility,
                stats: &s,
                ram_bytes,
            },
            method,
        );
        write_stats(p, &json)?;
    }
    warn_if_empty(scene, &frame.stats);
    crate::outln!("{}", summary(&args.output, w, h, &frame.stats))?;
    Ok(())
}

/// `zscan render --visibility auto`: plans within `--ram-budget` (no limit by default),
/// prints the plan and its reasons, draws the frame as planned.
fn finish_auto(args: &RenderArgs, scene: &LoadedScene) -> Result<(), CliError> {
    use zscan::visibility::DepthWidth;
    let budget = args.ram_budget.unwrap_or(usize::MAX);
    let crate::core_render::PlannedFrame {
        plan,
        order,
        pixels,
        stats,
    } = scene.render_planned(budget)?;
    for line in plan.to_string().lines() {
        crate::outln!("plan: {line}")?;
    }
    let vp = *scene.camera.viewport();
    let (w, h) = (vp.width, vp.height);
    let mut pixels = pixels;
    let fb = Framebuffer::new(&mut pixels, w, h).map_err(|e| format!("frame: {e}"))?;
    crate::image::write_image(&args.output, &fb, &scene.lut).map_err(|e| e.0)?;
    if let Some(p) = &args.stats {
        let b = plan.buffers;
        let depth_bits = match plan.depth {
            DepthWidth::None => 0,
            DepthWidth::U16 => 16,
            DepthWidth::U32 => 32,
        };
        let mut json = stats_json(
            scene,
            StatsFrame {
                size: (w, h),
                bands: band_count(h, plan.band_rows),
                band_rows: plan.band_rows,
                depth_bits,
                visibility: plan.visibility,
                stats: &stats,
                ram_bytes: b.total(),
            },
            serde_json::json!({}),
        );
        json["plan"] = serde_json::json!({
                "budget": args.ram_budget,
                "method": plan.visibility.name(),
                "method_reason": plan.method_reason.to_string(),
                "depth_bits": depth_bits,
                "depth_reason": plan.depth_reason.to_string(),
                "band_rows": plan.band_rows,
                "layout_reason": plan.layout_reason.to_string(),
                "vertex_stage_once": plan.vertex_stage_once,
                "order": order,
                "buffers": {
                    "frame": b.frame,
                    "depth": b.depth,
                    "vertices": b.vertices,
                    "polygons": b.polygons,
                    "tables": b.tables,
                    "total": b.total(),
                },
        });
        write_stats(p, &json)?;
    }
    warn_if_empty(scene, &stats);
    crate::outln!("{}", summary(&args.output, w, h, &stats))?;
    Ok(())
}

/// What `--stats` says of a frame, whatever the method (auto included).
struct StatsFrame<'a> {
    /// Width and height, pixels.
    size: (u16, u16),
    /// Bands drawn.
    bands: u32,
    /// Rows of a band (the picture's height when drawn in one).
    band_rows: u16,
    /// Bits of a depth sample (0: no depth).
    depth_bits: u32,
    /// The method that drew the frame.
    visibility: Visibility,
    /// The core's counts.
    stats: &'a RenderStats,
    /// Every caller buffer the frame used, bytes.
    ram_bytes: usize,
}

/// The `--stats` JSON of the module doc (the same keys for every method; `--visibility auto`
/// adds `plan`), `method` the method's own counts.
fn stats_json(
    scene: &LoadedScene,
    f: StatsFrame<'_>,
    method: serde_json::Value,
) -> serde_json::Value {
    let s = f.stats;
    serde_json::json!({
        "width": f.size.0,
        "height": f.size.1,
        "bands": f.bands,
        "band_rows": f.band_rows,
        "depth_bits": f.depth_bits,
        "visibility": f.visibility.name(),
        "subpixel_bits": SUBPIXEL_BITS,
        "objects": scene.objects.len(),
        "triangles_in": scene.triangles_in,
        "polygons_in": s.polygons_in,
        "culled": s.culled,
        "rejected": s.rejected,
        "clipped": s.clipped,
        "triangles_drawn": s.triangles_drawn,
        "pixels_covered": s.pixels_covered,
        "pixels_written": s.pixels_written,
        "ram_bytes": f.ram_bytes,
        "method": method,
    })
}

/// Writes the `--stats` JSON to `path` (its folder created).
fn write_stats(path: &Path, json: &serde_json::Value) -> Result<(), CliError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let text = serde_json::to_string_pretty(json)?;
    fs::write(path, text + "\n").map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(())
}

/// Refuses, in words, the options the chosen method cannot honour (before the scene is
/// read): `--bands` applies to the methods that draw in bands (z-buffer, scan-line),
/// `--depth-out` to the one that keeps a whole depth picture (z-buffer), `--ram-budget` to
/// `auto`.
fn check_options(args: &RenderArgs) -> Result<(), String> {
    if args.bands == Some(0) {
        return Err("--bands 0: a band needs at least 1 row".into());
    }
    let Some(v) = args.visibility.0 else {
        if args.bands.is_some() {
            return Err("--bands: --visibility auto picks the band height itself".into());
        }
        if args.depth_out.is_some() {
            return Err(
                "--depth-out: --visibility auto keeps no whole depth picture \
                 (only --visibility zbuffer writes one)"
                    .into(),
            );
        }
        return Ok(());
    };
    if args.ram_budget.is_some() {
        return Err("--ram-budget: only --visibility auto plans within a budget".into());
    }
    if args.depth_out.is_some() && v != Visibility::ZBuffer {
        let why = if v == Visibility::ScanLine {
            "keeps no whole depth buffer, only the depth of one band of rows at a time"
        } else {
            "keeps no depth buffer"
        };
        return Err(format!(
            "--depth-out: --visibility {v} {why} (only --visibility zbuffer writes one)"
        ));
    }
    if args.bands.is_some() && !matches!(v, Visibility::ZBuffer | Visibility::ScanLine) {
        return Err(format!(
            "--bands: --visibility {v} draws the whole frame at once, not in bands \
             (--bands applies to --visibility zbuffer and scanline)"
        ));
    }
    Ok(())
}

impl LoadedScene {
    /// Why a frame of this scene drew no pixel, in words for a warning: no object, every
    /// object beyond `far` or nearer than `near` (depth along the view direction, from the
    /// scene file's values), the eye inside a culled object's bounds (its faces are seen from
    /// behind), or else outside the field of view or culled.
    pub fn empty_picture_cause(&self) -> String {
        let c = &self.view;
        if self.objects.is_empty() {
            return "the scene has no objects".into();
        }
        let Some(dir) = normalize(sub(c.target, c.eye)) else {
            return "nothing is drawn".into();
        };
        let world = |v: &Vec3| v.bits().map(|b| b as f64 / 65536.0);
        let mut nearest = f64::INFINITY;
        let (mut beyond, mut before) = (0, 0);
        let mut inside = None;
        for (k, o) in self.objects.iter().enumerate() {
            let depths = o.vertices.iter().map(|v| dot(sub(world(v), c.eye), dir));
            let (lo, hi) = depths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            });
            nearest = nearest.min(lo);
            beyond += usize::from(lo > c.far);
            before += usize::from(hi < c.near);
            let within = (0..3).all(|a| {
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for v in &o.vertices {
                    let p = world(v)[a];
                    (lo, hi) = (lo.min(p), hi.max(p));
                }
                lo < c.eye[a] && c.eye[a] < hi
            });
            if within && o.cull && inside.is_none() {
                inside = Some(k);
            }
        }
        let n = self.objects.len();
        if beyond == n {
            return format!(
                "every object lies beyond [camera] far = {} (the nearest at depth {nearest:.3})",
                c.far
            );
        }
        if before == n {
            return format!(
                "every object lies nearer than [camera] near = {} or behind the camera",
                c.near
            );
        }
        if let Some(k) = inside {
            return format!(
                "the camera is inside object {} (its faces are seen from behind and culled; \
                 cull = false draws them)",
                k + 1
            );
        }
        "every object is outside the field of view, beyond far, nearer than near or culled".into()
    }
}

/// On standard error: a warning that the picture is empty, with its cause, when the frame
/// covered no pixel (the picture is right, and the exit stays 0).
fn warn_if_empty(scene: &LoadedScene, stats: &RenderStats) {
    if stats.pixels_covered == 0 {
        crate::note!(
            "zscan render: warning: the picture is empty: {}",
            scene.empty_picture_cause()
        );
    }
}

/// The one-line summary `zscan render` prints on success.
pub fn summary(output: &Path, w: u16, h: u16, stats: &RenderStats) -> String {
    format!(
        "wrote {}: {w}×{h}, {} triangles drawn, {} pixels covered",
        output.display(),
        stats.triangles_drawn,
        stats.pixels_covered
    )
}

/// Runs `zscan render`.
pub fn run(args: RenderArgs) -> Result<(), CliError> {
    check_options(&args)?;
    let scene = load_scene(&args.scene)?;
    let lined = scene.objects.iter().any(|o| o.wireframe.is_some()) || !scene.lines.is_empty();
    if lined && (args.visibility.0 != Some(Visibility::ZBuffer) || args.bands.is_some()) {
        return Err(
            "wireframes and [[lines]] are drawn through the whole-frame z-buffer: \
                    --visibility zbuffer without --bands"
                .into(),
        );
    }
    if args.visibility.0.is_none() {
        return finish_auto(&args, &scene);
    }
    match scene.depth_bits {
        16 => finish::<u16>(&args, &scene),
        _ => finish::<u32>(&args, &scene),
    }
}
