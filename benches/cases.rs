//! Benchmark cases shared by the Cortex-M example (`examples/cortex_m_bench.rs`) and the host
//! runner (`zscan bench`, `host-tests/src/cli/bench.rs`). Both include this one file with
//! `#[path = ".../benches/cases.rs"] mod cases;`, so every platform measures the same code
//! drawing the same pixels, and the framebuffer checksums must agree across platforms.
//!
//! Rules for this file: `no_std`-compatible (no allocation, no `std`, no floats), only absolute
//! `zscan::` paths, no `unsafe`.
//!
//! # Adding a case
//! 1. Write `fn my_case(fb: &mut Framebuffer<'_>) -> u32` that draws into the cleared
//!    [`WIDTH`] × [`HEIGHT`] framebuffer and returns the number of pixels it wrote (a pixel
//!    written twice counts twice; keep the count a constant or cheap to compute, since it is
//!    inside the measured region).
//! 2. Add one line `Case { name: "my_case", run: |fb, _| my_case(fb) },` to [`CASES`]. The
//!    second argument is the harness's [`Storage`]: full-frame 16-bit depth samples and
//!    vertex scratch, declared once like an application's buffers, contents unspecified (a
//!    case that uses the depth clears it, as [`scene::frame`] does with `DepthBuffer::clear`;
//!    the vertex stage overwrites the scratch it uses).
//!
//! Names are single words (`[a-z0-9_]`), unique. [`CASES`]`[0]` is the empty calibration case;
//! keep it first. The host test `host-tests/tests/bench_cases.rs` checks names and pixel counts.
//!
//! The harness clears the framebuffer to index 0 before each call, calls the case once to warm
//! up, clears again, then measures one call between the region markers.
use zscan::internals::{DivisionWalker, IncrementalWalker};
use zscan::output::Framebuffer;
use zscan::raster::depth_line::Walk;
use zscan::raster::triangle::ShadeMode;
use zscan::render::{PreparedVertex, Wireframe};
use zscan::texture::TextureMode;

/// Framebuffer width of every case.
pub const WIDTH: u16 = 320;
/// Framebuffer height of every case.
pub const HEIGHT: u16 = 240;
/// Bytes of the framebuffer.
pub const FB_LEN: usize = WIDTH as usize * HEIGHT as usize;

/// The harness's memory besides the framebuffer, declared once like an application's buffers
/// (an application keeps its depth buffer and vertex scratch from frame to frame); contents
/// unspecified when a case starts.
pub struct Storage {
    /// Full-frame 16-bit depth samples ([`FB_LEN`]).
    pub depth: [u16; FB_LEN],
    /// Vertex scratch for the largest standard mesh (28 bytes per vertex).
    pub vertices: [PreparedVertex<4>; scene::MAX_VERTICES],
    /// The visibility methods' triangle store (52 bytes per front triangle or piece).
    pub triangles: [zscan::visibility::StoredTriangle<4>; scene::MAX_STORED],
    /// Their order (painter, scan-line table; Warnock's candidate lists).
    pub order: [u32; scene::MAX_STORED],
    /// The scan-line's active table.
    pub active: [u32; scene::MAX_STORED],
    /// The painter's plane normals (24 bytes per front triangle).
    pub normals: [zscan::visibility::Normal; scene::MAX_STORED],
    /// The compact banded frame's memory (band, compact vertices, polygon table).
    pub compact: scene::CompactMemory,
    /// The planner's facts of the standard meshes, computed once here (an application keeps
    /// them in flash beside the mesh).
    pub facts: scene::KeptFacts,
    /// The edge tables of the cube, sphere and bunny (`Mesh::edges`), computed once here (an
    /// application keeps them in flash beside the mesh).
    pub edges: scene::KeptEdges,
    /// Appel's half-edges (`render::appel`: three per triangle, 8 bytes each).
    pub appel_edges: [zscan::render::AppelEdge; 3 * scene::MAX_POLYGONS],
    /// Appel's crossings of one edge with the contour (24 bytes each).
    pub appel_crossings: [zscan::render::AppelCrossing; scene::MAX_APPEL_CROSSINGS],
    /// The reverse painter's mask of painted pixels, a bit per pixel (2,400 words).
    pub mask: [u32; zscan::output::mask_words_needed(WIDTH, HEIGHT)],
}

impl Storage {
    /// Depth at far, zeroed vertices.
    pub fn new() -> Storage {
        Storage {
            depth: [u16::MAX; FB_LEN],
            vertices: [PreparedVertex::default(); scene::MAX_VERTICES],
            triangles: [zscan::visibility::StoredTriangle::DEFAULT; scene::MAX_STORED],
            order: [0; scene::MAX_STORED],
            active: [0; scene::MAX_STORED],
            normals: [zscan::visibility::Normal::DEFAULT; scene::MAX_STORED],
            compact: scene::CompactMemory::new(),
            facts: scene::KeptFacts::new(),
            edges: scene::KeptEdges::new(),
            appel_edges: [zscan::render::AppelEdge::ZERO; 3 * scene::MAX_POLYGONS],
            appel_crossings: [zscan::render::AppelCrossing::ZERO; scene::MAX_APPEL_CROSSINGS],
            mask: [0; zscan::output::mask_words_needed(WIDTH, HEIGHT)],
        }
    }
}

impl Default for Storage {
    fn default() -> Storage {
        Storage::new()
    }
}

/// One benchmark case: a name and a drawing function returning the pixels it wrote.
#[derive(Clone, Copy)]
pub struct Case {
    /// Unique single-word name.
    pub name: &'static str,
    /// Draws into a cleared `WIDTH × HEIGHT` framebuffer, with the harness's [`Storage`]
    /// (contents unspecified); returns the pixels written.
    pub run: fn(&mut Framebuffer<'_>, &mut Storage) -> u32,
}

/// All cases, in the order they run. `CASES[0]` is the empty calibration case.
pub const CASES: &[Case] = &[
    Case {
        name: "empty",
        run: |fb, _| empty(fb),
    },
    Case {
        name: "clear",
        run: clear,
    },
    Case {
        name: "line_shallow",
        run: |fb, _| line_shallow(fb),
    },
    Case {
        name: "line_diagonal",
        run: |fb, _| line_diagonal(fb),
    },
    Case {
        name: "line_steep",
        run: |fb, _| line_steep(fb),
    },
    Case {
        name: "line_star64",
        run: |fb, _| line_star64(fb),
    },
    Case {
        name: "line_short",
        run: |fb, _| line_short(fb),
    },
    Case {
        name: "line_clipped",
        run: |fb, _| line_clipped(fb),
    },
    Case {
        name: "setup",
        run: |_, _| scene::setup_only(),
    },
    Case {
        name: "vertex_quad",
        run: |fb, st| scene::vertex_only(fb, st, &scene::QUAD),
    },
    Case {
        name: "vertex_cube",
        run: |fb, st| scene::vertex_only(fb, st, &scene::CUBE),
    },
    Case {
        name: "vertex_sphere",
        run: |fb, st| scene::vertex_only(fb, st, &scene::SPHERE),
    },
    Case {
        name: "vertex_bunny",
        run: |fb, st| scene::vertex_only(fb, st, &scene::BUNNY),
    },
    Case {
        name: "fill_quad",
        run: |fb, st| scene::fill_only::<IncrementalWalker>(fb, st, &scene::QUAD),
    },
    Case {
        name: "fill_cube",
        run: |fb, st| scene::fill_only::<IncrementalWalker>(fb, st, &scene::CUBE),
    },
    Case {
        name: "fill_sphere",
        run: |fb, st| scene::fill_only::<IncrementalWalker>(fb, st, &scene::SPHERE),
    },
    Case {
        name: "fill_sphere_division",
        run: |fb, st| scene::fill_only::<DivisionWalker>(fb, st, &scene::SPHERE),
    },
    Case {
        name: "fill_bunny",
        run: |fb, st| scene::fill_only::<IncrementalWalker>(fb, st, &scene::BUNNY),
    },
    Case {
        name: "fill_bunny_division",
        run: |fb, st| scene::fill_only::<DivisionWalker>(fb, st, &scene::BUNNY),
    },
    Case {
        name: "frame_quad",
        run: |fb, st| scene::frame(fb, st, &scene::QUAD, ShadeMode::GouraudExact),
    },
    Case {
        name: "frame_cube",
        run: |fb, st| scene::frame(fb, st, &scene::CUBE, ShadeMode::GouraudExact),
    },
    Case {
        name: "frame_sphere",
        run: |fb, st| scene::frame(fb, st, &scene::SPHERE, ShadeMode::GouraudExact),
    },
    Case {
        name: "frame_sphere_fast",
        run: |fb, st| scene::frame(fb, st, &scene::SPHERE, ShadeMode::GouraudFast),
    },
    Case {
        name: "frame_bunny",
        run: |fb, st| scene::frame(fb, st, &scene::BUNNY, ShadeMode::GouraudExact),
    },
    Case {
        name: "frame_bunny_fast",
        run: |fb, st| scene::frame(fb, st, &scene::BUNNY, ShadeMode::GouraudFast),
    },
    Case {
        name: "frame_bunny_flat",
        run: |fb, st| scene::frame(fb, st, &scene::BUNNY, ShadeMode::Flat),
    },
    Case {
        name: "frame_cube_counted",
        run: |fb, st| scene::frame_counted(fb, st, &scene::CUBE, ShadeMode::GouraudExact),
    },
    Case {
        name: "frame_sphere_counted",
        run: |fb, st| scene::frame_counted(fb, st, &scene::SPHERE, ShadeMode::GouraudExact),
    },
    Case {
        name: "frame_bunny_counted",
        run: |fb, st| scene::frame_counted(fb, st, &scene::BUNNY, ShadeMode::GouraudExact),
    },
    Case {
        name: "frame_bunny_bands16",
        run: |fb, st| scene::frame_in_bands(fb, st, &scene::BUNNY, 16),
    },
    Case {
        name: "frame_bunny_compact",
        run: |fb, st| scene::frame_compact(fb, st, &scene::BUNNY),
    },
    Case {
        name: "frame_quad_backface",
        run: |fb, st| scene::back_faces(fb, st, &scene::QUAD),
    },
    Case {
        name: "frame_cube_backface",
        run: |fb, st| scene::back_faces(fb, st, &scene::CUBE),
    },
    Case {
        name: "frame_sphere_backface",
        run: |fb, st| scene::back_faces(fb, st, &scene::SPHERE),
    },
    Case {
        name: "frame_bunny_backface",
        run: |fb, st| scene::back_faces(fb, st, &scene::BUNNY),
    },
    Case {
        name: "plan_sphere",
        run: scene::plan_only::<{ scene::SPHERE_ID }>,
    },
    Case {
        name: "plan_bunny",
        run: scene::plan_only::<{ scene::BUNNY_ID }>,
    },
    Case {
        name: "frame_quad_planned",
        run: scene::planned::<{ scene::QUAD_ID }>,
    },
    Case {
        name: "frame_cube_planned",
        run: scene::planned::<{ scene::CUBE_ID }>,
    },
    Case {
        name: "frame_sphere_planned",
        run: scene::planned::<{ scene::SPHERE_ID }>,
    },
    Case {
        name: "frame_quad_reverse",
        run: scene::reverse::<{ scene::QUAD_ID }>,
    },
    Case {
        name: "frame_cube_reverse",
        run: scene::reverse::<{ scene::CUBE_ID }>,
    },
    Case {
        name: "frame_sphere_reverse",
        run: scene::reverse::<{ scene::SPHERE_ID }>,
    },
    Case {
        name: "frame_quad_painter",
        run: |fb, st| scene::painter(fb, st, &scene::QUAD),
    },
    Case {
        name: "frame_cube_painter",
        run: |fb, st| scene::painter(fb, st, &scene::CUBE),
    },
    Case {
        name: "frame_sphere_painter",
        run: |fb, st| scene::painter(fb, st, &scene::SPHERE),
    },
    Case {
        name: "frame_bunny_painter",
        run: |fb, st| scene::painter(fb, st, &scene::BUNNY),
    },
    Case {
        name: "frame_sphere_scanline16",
        run: |fb, st| scene::scan_lines(fb, st, &scene::SPHERE, 16),
    },
    Case {
        name: "frame_bunny_scanline1",
        run: |fb, st| scene::scan_lines(fb, st, &scene::BUNNY, 1),
    },
    Case {
        name: "frame_bunny_scanline16",
        run: |fb, st| scene::scan_lines(fb, st, &scene::BUNNY, 16),
    },
    Case {
        name: "frame_quad_warnock",
        run: |fb, st| scene::warnock(fb, st, &scene::QUAD),
    },
    Case {
        name: "frame_cube_warnock",
        run: |fb, st| scene::warnock(fb, st, &scene::CUBE),
    },
    Case {
        name: "frame_sphere_warnock",
        run: |fb, st| scene::warnock(fb, st, &scene::SPHERE),
    },
    Case {
        name: "frame_bunny_warnock",
        run: |fb, st| scene::warnock(fb, st, &scene::BUNNY),
    },
    Case {
        name: "lit_sphere_flat",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::Flat, false),
    },
    Case {
        name: "lit_sphere_flat_dither",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::Flat, true),
    },
    Case {
        name: "lit_sphere_gouraud_fast",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::GouraudFast, false),
    },
    Case {
        name: "lit_sphere_gouraud_fast_dither",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::GouraudFast, true),
    },
    Case {
        name: "lit_sphere_gouraud_exact",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::GouraudExact, false),
    },
    Case {
        name: "lit_sphere_gouraud_exact_dither",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::GouraudExact, true),
    },
    Case {
        name: "lit_sphere_phong",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::Phong, false),
    },
    Case {
        name: "lit_sphere_phong_dither",
        run: |fb, st| scene::lit(fb, st, &scene::SPHERE, ShadeMode::Phong, true),
    },
    Case {
        name: "lit_bunny_flat",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::Flat, false),
    },
    Case {
        name: "lit_bunny_flat_dither",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::Flat, true),
    },
    Case {
        name: "lit_bunny_gouraud_fast",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::GouraudFast, false),
    },
    Case {
        name: "lit_bunny_gouraud_fast_dither",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::GouraudFast, true),
    },
    Case {
        name: "lit_bunny_gouraud_exact",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::GouraudExact, false),
    },
    Case {
        name: "lit_bunny_gouraud_exact_dither",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::GouraudExact, true),
    },
    Case {
        name: "lit_bunny_phong",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::Phong, false),
    },
    Case {
        name: "lit_bunny_phong_dither",
        run: |fb, st| scene::lit(fb, st, &scene::BUNNY, ShadeMode::Phong, true),
    },
    Case {
        name: "frame_tex_floor",
        run: |fb, st| scene::textured::frame(fb, st, &scene::textured::FLOOR, TextureMode::Exact),
    },
    Case {
        name: "frame_tex_floor_sub16",
        run: |fb, st| {
            scene::textured::frame(fb, st, &scene::textured::FLOOR, TextureMode::Subdivided16)
        },
    },
    Case {
        name: "frame_tex_floor_sub8",
        run: |fb, st| {
            scene::textured::frame(fb, st, &scene::textured::FLOOR, TextureMode::Subdivided8)
        },
    },
    Case {
        name: "frame_tex_floor_affine",
        run: |fb, st| scene::textured::frame(fb, st, &scene::textured::FLOOR, TextureMode::Affine),
    },
    Case {
        name: "frame_tex_cube",
        run: |fb, st| scene::textured::frame(fb, st, &scene::textured::CUBE, TextureMode::Exact),
    },
    Case {
        name: "frame_tex_cube_sub16",
        run: |fb, st| {
            scene::textured::frame(fb, st, &scene::textured::CUBE, TextureMode::Subdivided16)
        },
    },
    Case {
        name: "frame_tex_cube_sub8",
        run: |fb, st| {
            scene::textured::frame(fb, st, &scene::textured::CUBE, TextureMode::Subdivided8)
        },
    },
    Case {
        name: "frame_tex_cube_affine",
        run: |fb, st| scene::textured::frame(fb, st, &scene::textured::CUBE, TextureMode::Affine),
    },
    Case {
        name: "frame_tex_sphere",
        run: |fb, st| scene::textured::frame(fb, st, &scene::textured::SPHERE, TextureMode::Exact),
    },
    Case {
        name: "frame_tex_sphere_sub16",
        run: |fb, st| {
            scene::textured::frame(fb, st, &scene::textured::SPHERE, TextureMode::Subdivided16)
        },
    },
    Case {
        name: "frame_tex_sphere_sub8",
        run: |fb, st| {
            scene::textured::frame(fb, st, &scene::textured::SPHERE, TextureMode::Subdivided8)
        },
    },
    Case {
        name: "frame_tex_sphere_affine",
        run: |fb, st| scene::textured::frame(fb, st, &scene::textured::SPHERE, TextureMode::Affine),
    },
    Case {
        name: "shadow_map_cube",
        run: |fb, st| scene::shadow_map(fb, st, &scene::CUBE, false),
    },
    Case {
        name: "shadow_map_sphere_point",
        run: |fb, st| scene::shadow_map(fb, st, &scene::SPHERE, true),
    },
    Case {
        name: "shadow_map_bunny",
        run: |fb, st| scene::shadow_map(fb, st, &scene::BUNNY, false),
    },
    Case {
        name: "shadow_map_bunny_point",
        run: |fb, st| scene::shadow_map(fb, st, &scene::BUNNY, true),
    },
    Case {
        name: "wire_cube_all",
        run: |fb, st| scene::wire(fb, st, scene::CUBE_ID, Wireframe::All, Walk::OneEnded),
    },
    Case {
        name: "wire_cube_front",
        run: |fb, st| scene::wire(fb, st, scene::CUBE_ID, Wireframe::Front, Walk::OneEnded),
    },
    Case {
        name: "wire_cube_hidden",
        run: |fb, st| scene::wire(fb, st, scene::CUBE_ID, Wireframe::Hidden, Walk::OneEnded),
    },
    Case {
        name: "wire_sphere_all",
        run: |fb, st| scene::wire(fb, st, scene::SPHERE_ID, Wireframe::All, Walk::OneEnded),
    },
    Case {
        name: "wire_sphere_front",
        run: |fb, st| scene::wire(fb, st, scene::SPHERE_ID, Wireframe::Front, Walk::OneEnded),
    },
    Case {
        name: "wire_sphere_hidden",
        run: |fb, st| scene::wire(fb, st, scene::SPHERE_ID, Wireframe::Hidden, Walk::OneEnded),
    },
    Case {
        name: "wire_bunny_all",
        run: |fb, st| scene::wire(fb, st, scene::BUNNY_ID, Wireframe::All, Walk::OneEnded),
    },
    Case {
        name: "wire_bunny_front",
        run: |fb, st| scene::wire(fb, st, scene::BUNNY_ID, Wireframe::Front, Walk::OneEnded),
    },
    Case {
        name: "wire_bunny_hidden",
        run: |fb, st| scene::wire(fb, st, scene::BUNNY_ID, Wireframe::Hidden, Walk::OneEnded),
    },
    Case {
        name: "wire_sphere_all_two_ended",
        run: |fb, st| scene::wire(fb, st, scene::SPHERE_ID, Wireframe::All, Walk::TwoEnded),
    },
    Case {
        name: "wire_bunny_all_two_ended",
        run: |fb, st| scene::wire(fb, st, scene::BUNNY_ID, Wireframe::All, Walk::TwoEnded),
    },
    Case {
        name: "wire_cube_appel",
        run: |fb, st| scene::wire_appel(fb, st, scene::CUBE_ID),
    },
    Case {
        name: "wire_sphere_appel",
        run: |fb, st| scene::wire_appel(fb, st, scene::SPHERE_ID),
    },
    Case {
        name: "wire_bunny_appel",
        run: |fb, st| scene::wire_appel(fb, st, scene::BUNNY_ID),
    },
];

/// FNV-1a (32-bit) of a byte slice: the framebuffer checksum every platform prints.
pub fn fnv1a(bytes: &[u8]) -> u32 {
    fnv1a_from(FNV1A_START, bytes)
}

/// FNV-1a's starting value (the hash of no bytes).
pub const FNV1A_START: u32 = 0x811c_9dc5;

/// FNV-1a continued from the hash `h` of the bytes before `bytes`: a picture streamed band by
/// band, `fnv1a_from(fnv1a_from(FNV1A_START, band0), band1)…`, hashes to its [`fnv1a`].
pub fn fnv1a_from(mut h: u32, bytes: &[u8]) -> u32 {
    for &b in bytes {
        h ^= b as u32;
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}

/// Draws the segment `(x0, y0)–(x1, y1)` (both ends included) with `index`, clipped to the
/// framebuffer: the one place the cases call the line API (`zscan::raster::line::draw_line`).
#[inline(always)]
fn line(fb: &mut Framebuffer<'_>, x0: i32, y0: i32, x1: i32, y1: i32, index: u8) {
    // Coordinates here are far inside the accepted range, so the result is always `Ok`.
    let _ = zscan::raster::line::draw_line(fb, (x0, y0).into(), (x1, y1).into(), index);
}

/// Calibration: draws nothing. Its count is the harness overhead subtracted from every case.
fn empty(_fb: &mut Framebuffer<'_>) -> u32 {
    0
}

/// The clears of a frame alone: colour (index 0, one byte per pixel) and 16-bit depth (far),
/// 320 × 240, as [`scene::frame`] does them; returns 0 pixels.
fn clear(fb: &mut Framebuffer<'_>, st: &mut Storage) -> u32 {
    fb.clear(0);
    if let Ok(mut zb) = zscan::output::DepthBuffer::new(&mut st.depth, WIDTH, HEIGHT) {
        zb.clear();
    }
    core::hint::black_box(&st.depth);
    0
}

/// 8 long x-major lines across the whole width (320 pixels each, slope 37/319).
fn line_shallow(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        let y = 10 + 25 * i;
        line(fb, 0, y, 319, y + 37, 1 + i as u8);
    }
    8 * 320
}

/// 8 diagonal lines at 45° (240 pixels each).
fn line_diagonal(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        let x = 10 * i;
        line(fb, x, 0, x + 239, 239, 1 + i as u8);
    }
    8 * 240
}

/// 8 long y-major lines down the whole height (240 pixels each, slope 50/239).
fn line_steep(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        let x = 20 + 30 * i;
        line(fb, x, 0, x + 50, 239, 1 + i as u8);
    }
    8 * 240
}

/// A star of 64 lines from the centre to points spread over the perimeter of a 200×200
/// square (16 per side), every octant and direction: 101 pixels each.
fn line_star64(fb: &mut Framebuffer<'_>) -> u32 {
    let (cx, cy, r) = (160, 120, 100);
    for k in 0..16 {
        let t = -r + (25 * k) / 2; // -100, -88, ..., 87: 16 points per side
        line(fb, cx, cy, cx + t, cy - r, 1 + k as u8);
        line(fb, cx, cy, cx + r, cy + t, 17 + k as u8);
        line(fb, cx, cy, cx - t, cy + r, 33 + k as u8);
        line(fb, cx, cy, cx - r, cy - t, 49 + k as u8);
    }
    64 * 101
}

/// 256 short lines of 9 pixels in 8 directions: the per-line set-up cost.
fn line_short(fb: &mut Framebuffer<'_>) -> u32 {
    const DIRS: [(i32, i32); 8] = [
        (8, 3),
        (3, 8),
        (-3, 8),
        (-8, 3),
        (-8, -3),
        (-3, -8),
        (3, -8),
        (8, -3),
    ];
    for i in 0..256 {
        let (dx, dy) = DIRS[i & 7];
        let x = 10 + 19 * ((i >> 3) & 15) as i32;
        let y = 12 + 20 * ((i >> 7) * 5 + (i >> 3) % 5) as i32;
        line(fb, x, y, x + dx, y + dy, 1 + (i % 255) as u8);
    }
    256 * 9
}

/// Lines that leave the framebuffer: 8 x-major lines entering at the left edge and leaving at
/// the right (320 visible pixels each), 8 y-major lines crossing from top to bottom (240
/// visible each), and 8 lines entirely outside (0 visible; trivially rejected by a clipper).
fn line_clipped(fb: &mut Framebuffer<'_>) -> u32 {
    for i in 0..8 {
        // y = 40 + 20 i + (x + 500) * 60 / 1320 - 22: inside rows 18..220 for 0 <= x < 320.
        let y = 18 + 20 * i;
        line(fb, -500, y, 820, y + 60, 1 + i as u8);
        // x inside columns 30..300 for 0 <= y < 240.
        let x = 30 + 30 * i;
        line(fb, x, -400, x + 40, 640, 9 + i as u8);
        line(fb, -900 + 10 * i, -50, 1200, -10 - i, 17 + i as u8);
    }
    8 * 320 + 8 * 240
}

/// The standard scenes of `docs/SCENES.md` (exported by `zscan export-scenes
/// benches/scenes`, tables in flash, validated at compile time) and the three kinds of scene
/// case: the vertex stage alone, the vertex stage plus the bare fill (no depth, no shading:
/// fill cost = `fill_*` − `vertex_*`), and the whole frame (clear colour, clear depth,
/// transform, cull, clip, project, rasterise, shade: SCENES.md's frame).
///
/// Per-frame set-up inside the measured region: building the camera and
/// [`Renderer`](zscan::render::Renderer) (projector, frustum); `vertex_*` measures it too.
/// The depth samples and the vertex scratch are the harness's [`Storage`].
pub mod scene {
    use super::Storage;
    use zscan::geometry::camera::{Camera, FovAxis, Lens, Viewport};
    use zscan::geometry::fixed::Coord;
    use zscan::geometry::mesh::{triangle_indices, vec3s_from_bits, Mesh, PolygonSizes};
    use zscan::geometry::trig::BinaryAngle;
    use zscan::geometry::vector::Vec3;
    use zscan::internals::EdgeWalker;
    use zscan::output::{DepthBuffer, Framebuffer};
    use zscan::raster::triangle::{fill_triangle_with, twice_area};
    use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
    use zscan::render::{RenderStats, Renderer, StatsSink, StatsWithoutWritten};
    use zscan::scene::{Intensities, Object};

    mod quad {
        include!("scenes/quad.rs");
    }
    mod cube {
        include!("scenes/cube.rs");
    }
    mod sphere {
        include!("scenes/sphere.rs");
    }
    mod bunny {
        include!("scenes/bunny.rs");
    }

    /// Largest vertex table of the scenes (the bunny's).
    pub const MAX_VERTICES: usize = 1839;
    /// Largest polygon table of the scenes (the bunny's).
    pub const MAX_POLYGONS: usize = 3674;
    /// Stored triangles of the visibility methods: every bunny triangle, or the quad's and
    /// cube's clipped fans and the painter's pieces.
    pub const MAX_STORED: usize = 4096;
    /// Crossings of one edge with the contour Appel's method holds (the bunny's most: well
    /// below).
    pub const MAX_APPEL_CROSSINGS: usize = 1024;

    /// The standard frame by back faces alone ([`zscan::visibility::render_back_faces`]: no
    /// depth buffer, right on the convex quad, cube and sphere, wrong where the bunny's front
    /// faces overlap); returns the pixels covered.
    pub fn back_faces(fb: &mut Framebuffer<'_>, st: &mut Storage, s: &StandardScene) -> u32 {
        let Some(camera) = camera() else { return 0 };
        let objects = [object(s, ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return 0;
        };
        let mut stats = StatsWithoutWritten::default();
        match zscan::visibility::render_back_faces(&r, fb, &mut st.vertices, &mut stats) {
            Ok(()) => stats.0.pixels_covered,
            Err(_) => 0,
        }
    }

    /// The edge tables ([`Mesh::edges`]) of the cube, sphere and bunny, computed once (each
    /// buffer holds one entry per corner while the edges are sorted; the edges take the first
    /// `counts[k]`).
    pub struct KeptEdges {
        cube: [[u16; 2]; 36],
        sphere: [[u16; 2]; 2880],
        bunny: [[u16; 2]; 3 * MAX_POLYGONS],
        counts: [usize; 3],
    }

    impl KeptEdges {
        /// The three meshes' edges (run once, outside the measured regions).
        pub fn new() -> KeptEdges {
            let mut k = KeptEdges {
                cube: [[0; 2]; 36],
                sphere: [[0; 2]; 2880],
                bunny: [[0; 2]; 3 * MAX_POLYGONS],
                counts: [0; 3],
            };
            k.counts[0] = CUBE.mesh.edges(&mut k.cube).unwrap_or(0);
            k.counts[1] = SPHERE.mesh.edges(&mut k.sphere).unwrap_or(0);
            k.counts[2] = BUNNY.mesh.edges(&mut k.bunny).unwrap_or(0);
            k
        }

        /// Mesh `which`'s edges ([`CUBE_ID`], [`SPHERE_ID`], [`BUNNY_ID`]; none for others).
        pub fn of(&self, which: usize) -> &[[u16; 2]] {
            match which {
                CUBE_ID => &self.cube[..self.counts[0]],
                SPHERE_ID => &self.sphere[..self.counts[1]],
                BUNNY_ID => &self.bunny[..self.counts[2]],
                _ => &[],
            }
        }
    }

    impl Default for KeptEdges {
        fn default() -> KeptEdges {
            KeptEdges::new()
        }
    }

    /// The standard scene `which` ([`STANDARD`]) as a wireframe in `mode` (palette index 255,
    /// the default depth offset, the lines walked as `walk`), through the cleared 16-bit depth
    /// buffer; returns the pixels drawn.
    pub fn wire(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        which: usize,
        mode: zscan::render::Wireframe,
        walk: zscan::raster::depth_line::Walk,
    ) -> u32 {
        let Ok(mut zb) = DepthBuffer::new(&mut st.depth, super::WIDTH, super::HEIGHT) else {
            return 0;
        };
        zb.clear();
        fb.clear(0);
        let Some(camera) = camera() else { return 0 };
        let Ok(r) = Renderer::<4>::new(&camera) else {
            return 0;
        };
        let mut style = zscan::render::LineStyle::new(255);
        style.walk = walk;
        let object = object(STANDARD[which], ShadeMode::GouraudExact);
        let edges = st.edges.of(which);
        r.draw_wireframe(&object, edges, mode, &mut st.vertices, &style, fb, &mut zb)
            .unwrap_or(0)
    }

    /// The standard scene `which` as a wireframe by Appel's quantitative invisibility
    /// (`render::appel`, palette index 255, no depth buffer); returns the pixels drawn.
    pub fn wire_appel(fb: &mut Framebuffer<'_>, st: &mut Storage, which: usize) -> u32 {
        fb.clear(0);
        let Some(camera) = camera() else { return 0 };
        let Ok(r) = Renderer::<4>::new(&camera) else {
            return 0;
        };
        let object = object(STANDARD[which], ShadeMode::GouraudExact);
        let mut memory = zscan::render::AppelScratch {
            edges: &mut st.appel_edges,
            crossings: &mut st.appel_crossings,
        };
        r.draw_appel(&object, &mut st.vertices, &mut memory, 255, fb)
            .unwrap_or(0)
    }

    /// The planner's facts of the standard meshes (indexed as [`STANDARD`]), computed once by
    /// [`MeshFacts::of`](zscan::visibility::MeshFacts::of) into word buffers of their own
    /// ([`MeshFacts::words_needed`](zscan::visibility::MeshFacts::words_needed): twice the
    /// corners; the edge table is the first half). The bunny's are its bounds alone, kept not
    /// convex without its 88 KB buffer (its facts say so: `host-tests/tests/plan.rs`).
    pub struct KeptFacts {
        quad: [u32; 12],
        cube: [u32; 72],
        sphere: [u32; 5760],
        kept: [Kept; 4],
    }

    /// One mesh's facts without the borrow: convex (the edge table kept), and bounds.
    #[derive(Clone, Copy)]
    struct Kept(bool, [[i32; 3]; 2]);

    impl Kept {
        fn of(f: Result<zscan::visibility::MeshFacts<'_>, zscan::visibility::FactsError>) -> Kept {
            use zscan::visibility::Convexity;
            match f {
                Ok(f) => Kept(matches!(f.convexity, Convexity::Convex { .. }), f.bounds),
                Err(_) => Kept(false, [[0; 3]; 2]),
            }
        }
    }

    impl KeptFacts {
        /// The four meshes' facts (run once, outside the measured regions).
        pub fn new() -> KeptFacts {
            use zscan::visibility::MeshFacts;
            let none = Kept(false, [[0; 3]; 2]);
            let mut k = KeptFacts {
                quad: [0; 12],
                cube: [0; 72],
                sphere: [0; 5760],
                kept: [none; 4],
            };
            k.kept[QUAD_ID] = Kept::of(MeshFacts::of(&QUAD.mesh, &mut k.quad));
            k.kept[CUBE_ID] = Kept::of(MeshFacts::of(&CUBE.mesh, &mut k.cube));
            k.kept[SPHERE_ID] = Kept::of(MeshFacts::of(&SPHERE.mesh, &mut k.sphere));
            let mut bounds = [[i32::MAX; 3], [i32::MIN; 3]];
            for v in BUNNY.mesh.vertices() {
                for (a, &c) in v.bits().iter().enumerate() {
                    bounds[0][a] = bounds[0][a].min(c);
                    bounds[1][a] = bounds[1][a].max(c);
                }
            }
            k.kept[BUNNY_ID] = Kept(false, bounds);
            k
        }

        /// Mesh `which`'s facts.
        pub fn facts(&self, which: usize) -> zscan::visibility::MeshFacts<'_> {
            use zscan::visibility::{Convexity, MeshFacts};
            let Kept(convex, bounds) = self.kept[which % 4];
            let words: &[u32] = match which {
                QUAD_ID => &self.quad,
                CUBE_ID => &self.cube,
                SPHERE_ID => &self.sphere,
                _ => &[],
            };
            let convexity = match convex {
                true => Convexity::Convex {
                    twins: &words[..words.len() / 2],
                },
                false => Convexity::NotConvex,
            };
            MeshFacts { convexity, bounds }
        }
    }

    impl Default for KeptFacts {
        fn default() -> KeptFacts {
            KeptFacts::new()
        }
    }

    /// The planner alone on the standard frame of scene `WHICH` ([`STANDARD`]), no memory limit,
    /// no scratch ([`plan`](zscan::visibility::plan)): for the sphere, the per-view check of its
    /// 960 triangles' silhouette, placing the vertices it looks at itself. Draws nothing;
    /// returns 0 pixels.
    pub fn plan_only<const WHICH: usize>(_fb: &mut Framebuffer<'_>, st: &mut Storage) -> u32 {
        let Some(camera) = camera() else { return 0 };
        let objects = [object(STANDARD[WHICH], ShadeMode::GouraudExact)];
        let facts = [st.facts.facts(WHICH)];
        let mut order = [0u16];
        let scene = core_scene(camera, &objects);
        let plan = zscan::visibility::plan::<4>(&scene, &facts, usize::MAX, &mut order);
        core::hint::black_box(&plan);
        0
    }

    /// The standard frame of scene `WHICH` ([`STANDARD`]) as the planner draws it with no
    /// memory limit ([`plan_frame`](zscan::visibility::plan_frame)): the plan, whose view check
    /// runs the vertex stage into the harness's scratch, then back faces alone in its order,
    /// reusing those vertices (the quad, cube and sphere; the picture and checksum are the
    /// z-buffer's `frame_*`). A plan that is not back faces alone draws nothing (0 pixels).
    pub fn planned<const WHICH: usize>(fb: &mut Framebuffer<'_>, st: &mut Storage) -> u32 {
        use zscan::visibility::{plan_frame, PlannedFrame};
        let Some(camera) = camera() else { return 0 };
        let objects = [object(STANDARD[WHICH], ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return 0;
        };
        let (facts, mut order) = ([st.facts.facts(WHICH)], [0u16]);
        let mut stats = StatsWithoutWritten::default();
        match plan_frame(&r, &facts, usize::MAX, &mut order, &mut st.vertices) {
            Ok(PlannedFrame::BackFace(frame)) => match frame.render(fb, &mut stats) {
                Ok(()) => stats.0.pixels_covered,
                Err(_) => 0,
            },
            _ => 0,
        }
    }

    /// The standard frame of scene `WHICH` ([`STANDARD`]) by the reverse painter
    /// ([`render_reverse_painter`](zscan::visibility::render_reverse_painter): its rule checked
    /// as the planner's, then drawn near to far through the harness's mask of painted pixels;
    /// the picture and checksum are the z-buffer's `frame_*`); returns the pixels covered, 0
    /// when refused.
    pub fn reverse<const WHICH: usize>(fb: &mut Framebuffer<'_>, st: &mut Storage) -> u32 {
        use zscan::visibility::render_reverse_painter;
        let Some(camera) = camera() else { return 0 };
        let objects = [object(STANDARD[WHICH], ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return 0;
        };
        let (facts, mut order) = ([st.facts.facts(WHICH)], [0u16]);
        let mut stats = StatsWithoutWritten::default();
        let (mask, vertices) = (&mut st.mask, &mut st.vertices);
        match render_reverse_painter(&r, &facts, &mut order, fb, mask, vertices, &mut stats) {
            Ok(()) => stats.0.pixels_covered,
            Err(_) => 0,
        }
    }

    /// The standard frame by the depth-sort painter (Newell's tests, splits budget 64, no
    /// depth buffer); returns the pixels covered.
    pub fn painter(fb: &mut Framebuffer<'_>, st: &mut Storage, s: &StandardScene) -> u32 {
        use zscan::visibility::{render_painter, PainterMemory, SplitPolicy};
        let Some(camera) = camera() else { return 0 };
        let objects = [object(s, ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return 0;
        };
        let mut stats = StatsWithoutWritten::default();
        let memory = PainterMemory {
            triangles: &mut st.triangles,
            order: &mut st.order,
            normals: &mut st.normals,
        };
        let policy = SplitPolicy::Budget(64);
        match render_painter(&r, fb, &mut st.vertices, memory, policy, &mut stats) {
            Ok(()) => stats.0.pixels_covered,
            Err(_) => 0,
        }
    }

    /// The standard frame by Warnock's area subdivision (no depth buffer; the order table
    /// holds the candidate lists: 2,585 entries at most on the bunny); returns the pixels
    /// covered.
    pub fn warnock(fb: &mut Framebuffer<'_>, st: &mut Storage, s: &StandardScene) -> u32 {
        use zscan::visibility::{render_warnock, Area, WarnockMemory};
        // 1 + 3 × 9 levels at 320 × 240.
        let mut windows = [Area::DEFAULT; 28];
        let Some(camera) = camera() else { return 0 };
        let objects = [object(s, ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return 0;
        };
        let mut stats = StatsWithoutWritten::default();
        let memory = WarnockMemory {
            triangles: &mut st.triangles,
            candidates: &mut st.order,
            windows: &mut windows,
        };
        match render_warnock(&r, fb, &mut st.vertices, memory, &mut stats) {
            Ok(()) => stats.0.pixels_covered,
            Err(_) => 0,
        }
    }

    /// The standard frame by the scan-line method, bands of `rows` rows (16-bit depth for the
    /// band only), each band copied into `fb` where a device would flush it; returns the
    /// pixels covered.
    pub fn scan_lines(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
        rows: u16,
    ) -> u32 {
        use zscan::visibility::{render_scan_lines, ScanLineMemory};
        const MAX_ROWS: usize = 16;
        let rows = rows.min(MAX_ROWS as u16);
        let mut band = [0u8; super::WIDTH as usize * MAX_ROWS];
        let mut depth = [u16::MAX; super::WIDTH as usize * MAX_ROWS];
        let Some(camera) = camera() else { return 0 };
        let objects = [object(s, ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return 0;
        };
        let mut stats = StatsWithoutWritten::default();
        let memory = ScanLineMemory {
            triangles: &mut st.triangles,
            order: &mut st.order,
            active: &mut st.active,
            pixels: &mut band,
            depths: &mut depth,
        };
        let drawn = render_scan_lines(
            &r,
            (super::WIDTH, super::HEIGHT, rows),
            &mut st.vertices,
            memory,
            &mut stats,
            |frame, _| {
                for (y, row) in frame.rows() {
                    if let Some(out) = fb.row_mut(y) {
                        out.copy_from_slice(row);
                    }
                }
                Ok::<(), zscan::visibility::VisibilityError>(())
            },
        );
        drawn.map_or(0, |()| stats.0.pixels_covered)
    }

    /// The scene of `objects` seen by `camera` (no lights, background 0).
    fn core_scene<'a>(camera: Camera, objects: &'a [Object<'a>]) -> zscan::scene::Scene<'a> {
        zscan::scene::Scene {
            camera,
            objects,
            background: 0,
            ambient: 0,
            lights: &[],
        }
    }

    /// One standard scene as core tables.
    pub struct StandardScene {
        mesh: Mesh<'static>,
        intensities: Intensities<'static>,
    }

    impl StandardScene {
        /// The scene's mesh (the host's accuracy checks read its corners and coordinates).
        pub const fn mesh(&self) -> Mesh<'static> {
            self.mesh
        }
    }

    /// Per-vertex intensities from per-corner ones (the sphere and bunny: corners agree).
    const fn per_vertex<const N: usize>(t: &[[u16; 3]], c: &[[u8; 3]]) -> [u8; N] {
        let mut out = [0u8; N];
        let mut i = 0;
        while i < t.len() {
            let mut k = 0;
            while k < 3 {
                out[t[i][k] as usize] = c[i][k];
                k += 1;
            }
            i += 1;
        }
        out
    }

    /// Per-face intensities (the quad and cube: flat faces).
    const fn per_face<const M: usize>(c: &[[u8; 3]; M]) -> [u8; M] {
        let mut out = [0u8; M];
        let mut i = 0;
        while i < M {
            out[i] = c[i][0];
            i += 1;
        }
        out
    }

    const fn mesh(v: &'static [Vec3], i: &'static [u16]) -> Mesh<'static> {
        match Mesh::new(v, i, PolygonSizes::Uniform(3)) {
            Ok(m) => m,
            Err(_) => panic!("invalid standard mesh"),
        }
    }

    macro_rules! standard {
        ($name:ident, $m:ident, $nv:expr, $nt:expr, $intens:ident) => {
            mod $name {
                use super::*;
                pub static V: [Vec3; $nv] = vec3s_from_bits(&$m::VERTICES);
                pub static I: [u16; 3 * $nt] = triangle_indices(&$m::TRIANGLES);
    pub static L: [u8; standard!(@len $intens, $nv, $nt)] =
        standard!(@table $intens, $m, $nv);
            }
        };
        (@len per_vertex, $nv:expr, $nt:expr) => {
            $nv
        };
        (@len per_face, $nv:expr, $nt:expr) => {
            $nt
        };
        (@table per_vertex, $m:ident, $nv:expr) => {
            per_vertex::<$nv>(&$m::TRIANGLES, &$m::INTENSITIES)
        };
        (@table per_face, $m:ident, $nv:expr) => {
            per_face(&$m::INTENSITIES)
        };
    }
    standard!(quad_t, quad, 4, 2, per_face);
    standard!(cube_t, cube, 8, 12, per_face);
    standard!(sphere_t, sphere, 482, 960, per_vertex);
    standard!(bunny_t, bunny, 1839, 3674, per_vertex);

    /// SCENES.md's quad.
    pub static QUAD: StandardScene = StandardScene {
        mesh: mesh(&quad_t::V, &quad_t::I),
        intensities: Intensities::PerPolygon(&quad_t::L),
    };
    /// SCENES.md's cube.
    pub static CUBE: StandardScene = StandardScene {
        mesh: mesh(&cube_t::V, &cube_t::I),
        intensities: Intensities::PerPolygon(&cube_t::L),
    };
    /// SCENES.md's sphere.
    pub static SPHERE: StandardScene = StandardScene {
        mesh: mesh(&sphere_t::V, &sphere_t::I),
        intensities: Intensities::PerVertex(&sphere_t::L),
    };
    /// SCENES.md's bunny.
    pub static BUNNY: StandardScene = StandardScene {
        mesh: mesh(&bunny_t::V, &bunny_t::I),
        intensities: Intensities::PerVertex(&bunny_t::L),
    };

    /// The standard scenes by index (the planner's cases name a scene by it: its facts are
    /// kept at the same index, [`KeptFacts`]).
    pub static STANDARD: [&StandardScene; 4] = [&QUAD, &CUBE, &SPHERE, &BUNNY];
    /// Indices into [`STANDARD`].
    pub const QUAD_ID: usize = 0;
    /// See [`QUAD_ID`].
    pub const CUBE_ID: usize = 1;
    /// See [`QUAD_ID`].
    pub const SPHERE_ID: usize = 2;
    /// See [`QUAD_ID`].
    pub const BUNNY_ID: usize = 3;

    /// SCENES.md's camera with lattice-point pixels (principal point (159.5, 119.5)). Each case
    /// builds its renderer from it with `Renderer::new` itself: a helper returning the renderer
    /// in an `Option` or a `Result` of another error type costs a copy of its 424 bytes
    /// (measured: 2.6 k Cortex-M4 instructions per frame).
    pub fn camera() -> Option<Camera> {
        let lens = Lens {
            fov: BinaryAngle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: Coord::from_bits(1 << 15),
            far: Coord::from_bits(10 << 16),
        };
        Camera::look_at(
            Vec3::from_bits(0, 0, 3 << 16),
            Vec3::ZERO,
            Vec3::from_bits(0, 1 << 16, 0),
            lens,
            Viewport::new(super::WIDTH, super::HEIGHT),
        )
        .ok()
    }

    fn object(s: &StandardScene, shade: ShadeMode) -> Object<'static> {
        let mut o = Object::new(s.mesh);
        o.intensities = s.intensities;
        o.shade = shade;
        o.ramp = LuminanceRamp::GREY;
        o
    }

    /// The vertex stage alone (plus set-up); returns 0 pixels.
    /// The set-up each scene case does inside its region before its work, alone: the camera
    /// and the renderer (projector, frustum). SCENES.md's frame leaves it out ("each benchmark
    /// renders the frame repeatedly in one process, so set-up is amortised"); these cases
    /// count it (an application whose camera moves pays it every frame), and this case says
    /// how much it is.
    pub fn setup_only() -> u32 {
        let Some(camera) = camera() else { return 0 };
        let Ok(r) = Renderer::<4>::new(&camera) else {
            return 0;
        };
        core::hint::black_box(&r);
        0
    }

    /// The set-up above and the vertex stage (transform, outcodes, projection).
    pub fn vertex_only(_fb: &mut Framebuffer<'_>, st: &mut Storage, s: &StandardScene) -> u32 {
        let Some(camera) = camera() else { return 0 };
        let Ok(r) = Renderer::<4>::new(&camera) else {
            return 0;
        };
        let _ = r.prepare(&object(s, ShadeMode::Flat), &mut st.vertices);
        core::hint::black_box(&st.vertices);
        0
    }

    /// Vertex stage, back-face culling on the projected area, and the bare fill of every
    /// front-facing triangle whose vertices all projected (no depth test, no shading: index
    /// 255 written with `slice::fill`). Returns the pixels written.
    pub fn fill_only<W: EdgeWalker>(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
    ) -> u32 {
        let Some(camera) = camera() else { return 0 };
        let Ok(r) = Renderer::<4>::new(&camera) else {
            return 0;
        };
        let scratch = &mut st.vertices;
        if r.prepare(&object(s, ShadeMode::Flat), scratch).is_err() {
            return 0;
        }
        let window = fb.window();
        let mut written = 0;
        for t in s.mesh.indices().chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| scratch[i as usize]);
            if a.outcode | b.outcode | c.outcode != 0 {
                continue;
            }
            let v = [a.screen, b.screen, c.screen];
            if twice_area(v[0], v[1], v[2]) >= 0 {
                continue; // back face (clockwise on a y-down screen is front)
            }
            let _ = fill_triangle_with::<W, 4>(v, &window, |span| {
                if let Some(row) = fb.span_mut(span.y, span.x0 as usize, span.x1 as usize) {
                    row.fill(255);
                    written += row.len() as u32;
                }
            });
        }
        written
    }

    /// Rows of a compact band ([`frame_compact`]): the tallest band whose memory, with the
    /// bunny's compact scratch, leaves room for the stack in 32 KB of RAM
    /// (`scripts/footprint.sh`).
    pub const COMPACT_ROWS: u16 = 10;
    const COMPACT_BAND: usize = super::WIDTH as usize * COMPACT_ROWS as usize;

    /// The memory of a compact banded frame of any standard scene: one band of pixels and
    /// 16-bit depths, 8 bytes per vertex, 1 per polygon (`CompactSizes::bytes`: 27,986 bytes
    /// for the bunny).
    pub struct CompactMemory {
        /// The band's pixels.
        pub pixels: [u8; COMPACT_BAND],
        /// The band's depth samples.
        pub depths: [u16; COMPACT_BAND],
        /// Compact vertices.
        pub vertices: [zscan::render::CompactVertex; MAX_VERTICES],
        /// The polygon table.
        pub polygons: [zscan::render::PolygonTop; MAX_POLYGONS],
    }

    impl CompactMemory {
        /// Zeroed buffers.
        pub fn new() -> CompactMemory {
            CompactMemory {
                pixels: [0; COMPACT_BAND],
                depths: [0; COMPACT_BAND],
                vertices: [zscan::render::CompactVertex::default(); MAX_VERTICES],
                polygons: [zscan::render::PolygonTop::default(); MAX_POLYGONS],
            }
        }
    }

    impl Default for CompactMemory {
        fn default() -> CompactMemory {
            CompactMemory::new()
        }
    }

    /// SCENES.md's frame of `s` (exact Gouraud, 16-bit depth) drawn in compact bands of
    /// [`COMPACT_ROWS`] rows through `m` ([`zscan::render::render_in_compact_bands`]), each
    /// finished band handed to `band_done` where a device would flush it. Written pixels are
    /// not counted, as in [`frame`]; returns the pixels covered.
    pub fn compact_bands<E: From<zscan::render::RenderError>>(
        s: &StandardScene,
        m: &mut CompactMemory,
        band_done: impl FnMut(&mut Framebuffer<'_>) -> Result<(), E>,
    ) -> Result<u32, E> {
        use zscan::render::{render_in_compact_bands, CompactBandScratch};
        let Some(camera) = camera() else { return Ok(0) };
        let objects = [object(s, ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return Ok(0);
        };
        let mut stats = StatsWithoutWritten::default();
        let mut band_done = band_done;
        render_in_compact_bands(
            &r,
            (&mut m.pixels, &mut m.depths),
            (super::WIDTH, super::HEIGHT, COMPACT_ROWS),
            CompactBandScratch {
                vertices: &mut m.vertices,
                levels: &mut [],
                polygons: &mut m.polygons,
            },
            &mut stats,
            |frame, _| band_done(frame),
        )?;
        Ok(stats.0.pixels_covered)
    }

    /// [`compact_bands`] with the harness's compact memory, each band copied into `fb`;
    /// returns the pixels covered.
    pub fn frame_compact(fb: &mut Framebuffer<'_>, st: &mut Storage, s: &StandardScene) -> u32 {
        let drawn = compact_bands(s, &mut st.compact, |frame| {
            for (y, row) in frame.rows() {
                if let Some(out) = fb.row_mut(y) {
                    out.copy_from_slice(row);
                }
            }
            Ok::<(), zscan::render::RenderError>(())
        });
        drawn.unwrap_or(0)
    }

    /// The same frame drawn through one 320×`rows` band buffer pair with
    /// [`render_in_bands`](zscan::render::render_in_bands), with scratch for every vertex and
    /// polygon (vertex stage, rejection and culling once per frame; each band visits the
    /// polygons that reach it); each finished band is copied into `fb` where a device would
    /// flush it. Written pixels are not counted, as in [`frame`], whose figure it compares
    /// with; returns the pixels covered.
    pub fn frame_in_bands(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
        rows: u16,
    ) -> u32 {
        const MAX_ROWS: usize = 16;
        let rows = rows.min(MAX_ROWS as u16);
        let mut band = [0u8; super::WIDTH as usize * MAX_ROWS];
        let mut depth = [u16::MAX; super::WIDTH as usize * MAX_ROWS];
        let Some(camera) = camera() else { return 0 };
        let mut polygons = [zscan::render::PolygonRows::default(); MAX_POLYGONS];
        let objects = [object(s, ShadeMode::GouraudExact)];
        let Ok(r) = Renderer::for_scene(&core_scene(camera, &objects)) else {
            return 0;
        };
        let mut stats = StatsWithoutWritten::default();
        let drawn = zscan::render::render_in_bands(
            &r,
            (&mut band, &mut depth),
            (super::WIDTH, super::HEIGHT, rows),
            zscan::render::BandScratch {
                vertices: &mut st.vertices,
                polygons: &mut polygons,
            },
            &mut stats,
            |frame, _| {
                for (y, row) in frame.rows() {
                    if let Some(out) = fb.row_mut(y) {
                        out.copy_from_slice(row);
                    }
                }
                Ok::<(), zscan::render::RenderError>(())
            },
        );
        drawn.map_or(0, |()| stats.0.pixels_covered)
    }

    /// SCENES.md's frame: clear colour, clear depth (16-bit, the harness's depth storage
    /// wrapped and cleared as an application would each frame), transform, cull, clip,
    /// project, rasterise with the depth test, Gouraud luminance. Statistics without the
    /// written-pixel count ([`StatsWithoutWritten`]); returns the pixels covered.
    pub fn frame(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
        shade: ShadeMode,
    ) -> u32 {
        let mut stats = StatsWithoutWritten::default();
        match frame_with(fb, st, s, shade, &mut stats) {
            Ok(()) => stats.0.pixels_covered,
            Err(_) => 0,
        }
    }

    /// [`frame`] with every statistic counted, written pixels too ([`RenderStats`]: one add
    /// per written pixel in the span loops); returns the pixels written.
    pub fn frame_counted(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
        shade: ShadeMode,
    ) -> u32 {
        let mut stats = RenderStats::default();
        match frame_with(fb, st, s, shade, &mut stats) {
            Ok(()) => stats.pixels_written,
            Err(_) => 0,
        }
    }

    fn frame_with(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
        shade: ShadeMode,
        stats: &mut impl StatsSink,
    ) -> Result<(), ()> {
        let mut zb =
            DepthBuffer::new(&mut st.depth, super::WIDTH, super::HEIGHT).map_err(|_| ())?;
        zb.clear(); // clear depth
        fb.clear(0); // clear colour
        let r = Renderer::<4>::new(&camera().ok_or(())?).map_err(|_| ())?;
        r.draw_object(&object(s, shade), &mut st.vertices, fb, &mut zb, stats)
            .map_err(|_| ())
    }

    /// `zscan chart`'s lit frames: clear (index 255, depth far), vertex normals of the mesh
    /// (inside the frame, as a mesh without stored normals needs), then the renderer with a
    /// lit object — directional light toward (1, 1, 1) (255), ambient 255, material
    /// (0.15, 0.55, 0.45, 20), 32-level ramp. Returns the pixels covered (the chart's
    /// per-pixel denominator).
    pub fn lit(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
        mode: ShadeMode,
        dither: bool,
    ) -> u32 {
        use zscan::lighting::{Light, Material};
        use zscan::scene::{Intensities, Object};
        let Ok(mut zb) = DepthBuffer::new(&mut st.depth, super::WIDTH, super::HEIGHT) else {
            return 0;
        };
        zb.clear();
        fb.clear(255);
        let Some(camera) = camera() else { return 0 };
        let light = Light::Directional {
            toward: Vec3::from_int(1, 1, 1),
            intensity: 255,
        };
        let Ok(r) = Renderer::<4>::new(&camera).and_then(|r| r.with_lights(255, &[light])) else {
            return 0;
        };
        let mut normals = [Vec3::ZERO; MAX_VERTICES];
        if mode != ShadeMode::Flat && s.mesh.vertex_normals(&mut normals).is_err() {
            return 0;
        }
        let mut object = Object::new(s.mesh);
        object.intensities = Intensities::Lit {
            material: Material::from_thousandths(150, 550, 450, 20),
            normals: &normals,
        };
        object.shade = mode;
        object.ramp = LuminanceRamp {
            first: 0,
            levels: 32,
        };
        object.dither = dither;
        let mut stats = RenderStats::default();
        match r.draw_object(&object, &mut st.vertices, fb, &mut zb, &mut stats) {
            Ok(()) => stats.pixels_covered,
            Err(_) => 0,
        }
    }

    /// Texels across and down of the shadow-map cases: 160 × 240 16-bit samples, whose 76,800
    /// bytes are the framebuffer's.
    const MAP_SIZE: (u16, u16) = (160, 240);

    /// A shadow map's pass 1 ([`ShadowMap::render`](zscan::shadow::ShadowMap::render)):
    /// the map (the harness's depth storage) built and cleared for a directional light toward
    /// (1, 2, 1), or a point light at (2, 3, 2), over the sphere of radius 1.25 at the origin,
    /// then the scene's mesh drawn into it (both faces, depth only). The samples' bytes are
    /// then copied into the framebuffer, so that its checksum is the map's (the copy, about
    /// 2 instructions a byte, is part of the count). Returns the texels.
    pub fn shadow_map(
        fb: &mut Framebuffer<'_>,
        st: &mut Storage,
        s: &StandardScene,
        point: bool,
    ) -> u32 {
        use zscan::geometry::matrix::Affine3;
        use zscan::shadow::ShadowMap;
        let (w, h) = MAP_SIZE;
        let samples = &mut st.depth[..w as usize * h as usize];
        let radius = Coord::from_bits(5 << 14);
        let map = if point {
            ShadowMap::point(samples, w, h, Vec3::from_int(2, 3, 2), Vec3::ZERO, radius)
        } else {
            ShadowMap::new(samples, w, h, Vec3::from_int(1, 2, 1), Vec3::ZERO, radius)
        };
        let Ok(mut map) = map else { return 0 };
        if map.render(&s.mesh, &Affine3::IDENTITY).is_err() {
            return 0;
        }
        let texels = &st.depth[..w as usize * h as usize];
        for (pair, d) in fb.pixels_mut().chunks_exact_mut(2).zip(texels) {
            pair.copy_from_slice(&d.to_le_bytes());
        }
        w as u32 * h as u32
    }

    /// SCENES.md's textured scenes (`tex_floor`, `tex_cube`, `tex_sphere`): the 64 × 64 grid
    /// texture given there as a formula, nearest sampling with wrapping, the standard camera,
    /// and each pixel's luminance `round(t · I / 255)` through a 256-level grey shade table
    /// (texel `t`, corner intensity `I` interpolated as in the untextured scenes).
    pub mod textured {
        use super::*;
        use zscan::geometry::mesh::TexCoord;
        use zscan::texture::{ShadeTable, Texture, TextureMode, Texturing};

        /// SCENES.md's grid: `t = 0` on the lines (`i % 8 == 0` or `j % 8 == 0`), else 255 or
        /// 96 by the parity of `(i >> 3) + (j >> 3)`; row `j` of 64, column `i`.
        const fn grid() -> [u8; 64 * 64] {
            let mut t = [0u8; 64 * 64];
            let mut k = 0;
            while k < 64 * 64 {
                let (i, j) = (k % 64, k / 64);
                t[k] = if i % 8 == 0 || j % 8 == 0 {
                    0
                } else if ((i >> 3) + (j >> 3)) % 2 == 0 {
                    255
                } else {
                    96
                };
                k += 1;
            }
            t
        }
        static GRID: [u8; 64 * 64] = grid();

        /// The grey shade table of 256 levels: row `I`, texel `t` → `round(t · I / 255)`.
        const fn grey_shades() -> [u8; 256 * 256] {
            let mut s = [0u8; 256 * 256];
            let mut k = 0;
            while k < 256 * 256 {
                let (i, t) = ((k / 256) as u32, (k % 256) as u32);
                s[k] = ((2 * t * i + 255) / 510) as u8;
                k += 1;
            }
            s
        }
        static SHADES: [u8; 256 * 256] = grey_shades();

        /// The cube's corners: each face (the vertex bit common to its triangle's three
        /// corners: bit 0 `x`, bit 1 `y`, bit 2 `z`) maps the texture once, counter-clockwise
        /// from outside, from the lower-left corner on the side faces (`v` up).
        const fn cube_uvs<const K: usize>(tris: &[[u16; 3]]) -> [TexCoord; K] {
            let mut out = [[0i16; 2]; K];
            let mut t = 0;
            while t < tris.len() {
                let [a, b, c] = tris[t];
                let (all, none) = (a & b & c, !(a | b | c) & 7);
                let mut k = 0;
                while k < 3 {
                    let v = tris[t][k];
                    let (x, y, z) = ((v & 1) as i16, (v >> 1 & 1) as i16, (v >> 2 & 1) as i16);
                    let (u, w) = if (all | none) & 1 != 0 {
                        (if all & 1 != 0 { 1 - z } else { z }, y) // x faces
                    } else if (all | none) & 4 != 0 {
                        (if all & 4 != 0 { x } else { 1 - x }, y) // z faces
                    } else if all & 2 != 0 {
                        (x, 1 - z) // top
                    } else {
                        (x, z) // bottom
                    };
                    out[3 * t + k] = [u * 256, w * 256];
                    k += 1;
                }
                t += 1;
            }
            out
        }

        /// The sphere's corners: `u = j / 32` (a triangle closing the ring takes 1 at its
        /// `j = 0` corners), `v = k / 16`, a pole corner the mean `u` of the two others.
        const fn sphere_uvs<const K: usize>(tris: &[[u16; 3]]) -> [TexCoord; K] {
            let mut out = [[0i16; 2]; K];
            let mut t = 0;
            while t < tris.len() {
                let mut u = [0i16; 3];
                let mut v = [0i16; 3];
                let mut pole = 3;
                let mut wraps = false;
                let mut k = 0;
                while k < 3 {
                    let i = tris[t][k] as i16;
                    if i == 0 || i == 481 {
                        pole = k;
                        v[k] = if i == 0 { 0 } else { 256 };
                    } else {
                        u[k] = 8 * ((i - 1) % 32);
                        v[k] = 16 * ((i - 1) / 32 + 1);
                        wraps |= u[k] == 8 * 31;
                    }
                    k += 1;
                }
                let mut k = 0;
                while k < 3 {
                    if wraps && k != pole && u[k] == 0 {
                        u[k] = 256;
                    }
                    k += 1;
                }
                if pole < 3 {
                    let (a, b) = ((pole + 1) % 3, (pole + 2) % 3);
                    u[pole] = (u[a] + u[b]) / 2;
                }
                let mut k = 0;
                while k < 3 {
                    out[3 * t + k] = [u[k], v[k]];
                    k += 1;
                }
                t += 1;
            }
            out
        }

        static CUBE_UV: [TexCoord; 36] = cube_uvs(&cube::TRIANGLES);
        static SPHERE_UV: [TexCoord; 2880] = sphere_uvs(&sphere::TRIANGLES);

        /// The floor `y = −1`: corners `(x, z)` = `(−4, 2.4), (4, 2.4), (4, −6.5), (−4, −6.5)`
        /// counter-clockwise seen from above, split along the first and third.
        static FLOOR_V: [Vec3; 4] = vec3s_from_bits(&[
            [-4 << 16, -1 << 16, 157_286],
            [4 << 16, -1 << 16, 157_286],
            [4 << 16, -1 << 16, -425_984],
            [-4 << 16, -1 << 16, -425_984],
        ]);
        static FLOOR_I: [u16; 6] = [0, 1, 2, 0, 2, 3];
        static FLOOR_UV: [TexCoord; 6] = [
            [0, 0],
            [1024, 0],
            [1024, 2048],
            [0, 0],
            [1024, 2048],
            [0, 2048],
        ];

        const fn textured(m: Mesh<'static>, uvs: &'static [TexCoord]) -> Mesh<'static> {
            match m.with_uvs(uvs) {
                Ok(m) => m,
                Err(_) => panic!("invalid texture coordinates"),
            }
        }

        /// SCENES.md's `tex_floor` (no fitting; `I = 158` everywhere).
        pub static FLOOR: StandardScene = StandardScene {
            mesh: textured(mesh(&FLOOR_V, &FLOOR_I), &FLOOR_UV),
            intensities: Intensities::Uniform(158),
        };
        /// SCENES.md's `tex_cube`.
        pub static CUBE: StandardScene = StandardScene {
            mesh: textured(mesh(&cube_t::V, &cube_t::I), &CUBE_UV),
            intensities: Intensities::PerPolygon(&cube_t::L),
        };
        /// SCENES.md's `tex_sphere`.
        pub static SPHERE: StandardScene = StandardScene {
            mesh: textured(mesh(&sphere_t::V, &sphere_t::I), &SPHERE_UV),
            intensities: Intensities::PerVertex(&sphere_t::L),
        };

        /// The textured frame of scene `s` in `mode`: SCENES.md's frame (clears, vertex
        /// stage, cull, clip, project, raster with the 16-bit depth test), the texel through
        /// the grey shade table. Returns the pixels covered.
        pub fn frame(
            fb: &mut Framebuffer<'_>,
            st: &mut Storage,
            s: &StandardScene,
            mode: TextureMode,
        ) -> u32 {
            let (Ok(texture), Ok(shades)) =
                (Texture::new(&GRID, 64, 64), ShadeTable::new(&SHADES, 256))
            else {
                return 0;
            };
            let texturing = Texturing {
                texture,
                mode,
                shades: Some(shades),
            };
            frame_with(fb, st, s, texturing)
        }

        /// [`frame`]'s frame of scene `s` with any `texturing` (the host's accuracy figures
        /// draw the same frames with numbered textures to read back which texel each pixel
        /// shows; the vertex scratch keeps the projected corners). Returns the pixels covered.
        #[inline(always)]
        pub fn frame_with(
            fb: &mut Framebuffer<'_>,
            st: &mut Storage,
            s: &StandardScene,
            texturing: Texturing<'_>,
        ) -> u32 {
            let Ok(mut zb) =
                DepthBuffer::new(&mut st.depth, super::super::WIDTH, super::super::HEIGHT)
            else {
                return 0;
            };
            zb.clear();
            fb.clear(0);
            let Some(camera) = camera() else { return 0 };
            let Ok(r) = Renderer::<4>::new(&camera) else {
                return 0;
            };
            let mut o = object(s, ShadeMode::GouraudExact);
            o.texture = Some(texturing);
            let mut stats = StatsWithoutWritten::default();
            match r.draw_object(&o, &mut st.vertices, fb, &mut zb, &mut stats) {
                Ok(()) => stats.0.pixels_covered,
                Err(_) => 0,
            }
        }
    }
}
