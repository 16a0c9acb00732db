//! The methods' target: from a seed, a random scene ([`random_world`], perspective or
//! orthographic) drawn by every hidden-surface method with caller memory of random sizes
//! ([`memory`]: exact, longer, or anything shorter) and random band heights (1 row to past the
//! picture), each picture compared with the z-buffer's whole-frame one:
//!
//! | method | compared with |
//! |---|---|
//! | back faces alone | nothing (it claims no picture for a random scene): no panic |
//! | the painter with a random split budget | the 32-bit z-buffer, ties included (where the exact depths differ by less than a unit, a surface the 32-bit z-buffer ties with: the documented exception) |
//! | the painter without test 6 | nothing (it claims no picture): no panic |
//! | the scan-line at 16 and 32 bits | the z-buffer of that width |
//! | Warnock | the 32-bit z-buffer |
//! | the z-buffer in bands (with and without the polygon table), 16 and 32 bits | the whole-frame one of that width |
//! | compact bands, 16 and 32 bits | the whole-frame z-buffer of that width |
//! | `DoubleBands` (an identity LUT, a recording sink) | the 32-bit z-buffer's indices, as sent |
//!
//! A refusal (an error) is accepted: its text is part of the fingerprint. The methods that
//! claim every scene (the scan-line, the z-buffer in bands, `DoubleBands`; Warnock except
//! fast Gouraud objects; compact bands refuse a vertex outside the guard band) must not refuse when their memory is long enough and the whole-frame
//! z-buffer drew the scene.

use embedded_graphics::primitives::Rectangle;
use zscan::output::{DepthValue, Framebuffer, Lut};
use zscan::raster::triangle::ShadeMode;
use zscan::render::{
    BandScratch, BandSink, DoubleBands, PolygonRows, PreparedVertex, RenderStats, Renderer,
    SceneRenderer,
};
use zscan::scene::Object;
use zscan::visibility::{
    render_back_faces, render_painter, render_scan_lines, render_warnock, Area, Normal,
    PainterMemory, ScanLineMemory, SplitPolicy, StoredTriangle, WarnockMemory,
};

use super::values::{bits_size, chance, memory, size};
use super::world::{first_difference, random_world, Shades, World};
use super::{hash, Outcome, Rng};
use crate::core_render::{render_compact_picture, render_picture};

/// What one method gave: its picture, or its refusal in words.
type Drawn = Result<Vec<u8>, String>;

/// One case of the target (module doc).
pub(super) fn run(seed: u64) -> Result<Outcome, String> {
    let mut rng = Rng::new(seed);
    let world = match random_world(&mut rng, true, Shades::All) {
        Ok(w) => w,
        Err(e) => return Ok(Err(e)),
    };
    let objects = world.objects()?;
    let scene = world.scene(&objects);
    let renderer = match Renderer::for_scene(&scene) {
        Ok(r) => r,
        Err(e) => return Ok(Err(e.to_string())),
    };
    let (w, h) = world.size();
    let all_vertices: usize = objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let largest = objects.iter().map(|o| o.mesh.vertices().len()).max();
    let largest = largest.unwrap_or(0);
    let polygons: usize = objects.iter().map(|o| o.mesh.polygon_count()).sum();
    let corners: usize = objects.iter().map(|o| o.mesh.indices().len()).sum();
    // Front triangles: the fans of every polygon as clipped (a convex polygon gains at most a
    // vertex per plane of the frustum, a non-convex one is clipped fan triangle by fan
    // triangle), with room to spare; the painter's pieces on top.
    let front = 8 * corners + 16;
    let fast = objects.iter().any(|o| o.shade == ShadeMode::GouraudFast);

    let whole = |bits16: bool| -> Result<(Vec<u8>, Vec<u32>), String> {
        let mut scratch = vec![PreparedVertex::default(); all_vertices.max(1)];
        let band = BandScratch {
            vertices: &mut scratch,
            polygons: &mut [],
        };
        if bits16 {
            render_picture::<u16, 4>(&renderer, (w, h), None, band)
                .map(|(p, d, _)| (p, d.iter().map(|&d| d as u32).collect()))
        } else {
            render_picture::<u32, 4>(&renderer, (w, h), None, band).map(|(p, d, _)| (p, d))
        }
        .map_err(|e| e.to_string())
    };
    let z32 = whole(false);
    let z16 = whole(true);
    let mut fingerprint = Vec::new();
    let mut note = |what: &str, drawn: &Drawn| {
        fingerprint.push(match drawn {
            Ok(p) => hash(p.iter().map(|&x| x as u64)),
            Err(e) => hash(what.bytes().chain(e.bytes()).map(u64::from)),
        })
    };
    // `claims`: the method must draw when `enough` memory was given and the reference drew.
    let verdict = |what: &str,
                   drawn: &Drawn,
                   reference: &Result<(Vec<u8>, Vec<u32>), String>,
                   enough: bool,
                   claims: bool|
     -> Result<(), String> {
        match (drawn, reference) {
            (Ok(p), Ok((z, _))) => match first_difference(p, z, w) {
                Some(d) => Err(format!("{what}: {d}")),
                None => Ok(()),
            },
            (Ok(_), Err(e)) => Err(format!("{what} drew a scene the z-buffer refuses: {e}")),
            (Err(e), Ok(_)) if enough && claims => {
                Err(format!("{what} refused with enough memory: {e}"))
            }
            (Err(_), _) => Ok(()),
        }
    };

    // Back faces alone: no claim on a random scene; it must not panic.
    {
        let mut pixels = vec![0u8; w as usize * h as usize];
        let n = memory(&mut rng, largest);
        let drawn = frame(&mut pixels, w, h).and_then(|mut fb| {
            let mut scratch = vec![PreparedVertex::default(); n];
            render_back_faces(
                &renderer,
                &mut fb,
                &mut scratch,
                &mut RenderStats::default(),
            )
            .map_err(|e| e.to_string())
        });
        note("back faces", &drawn.map(|()| pixels));
    }

    // The painter, with test 6 (a random split budget) and without.
    for split in [true, false] {
        let (nt, nn) = (memory(&mut rng, 4 * front + 16), memory(&mut rng, front));
        let policy = if split {
            SplitPolicy::Budget(bits_size(&mut rng, 4096))
        } else {
            SplitPolicy::Never
        };
        let mut pixels = vec![0u8; w as usize * h as usize];
        let drawn = frame(&mut pixels, w, h).and_then(|mut fb| {
            let mut scratch = vec![PreparedVertex::default(); memory(&mut rng, largest)];
            let mut triangles = vec![StoredTriangle::default(); nt];
            let mut order = vec![0u32; memory(&mut rng, nt)];
            let mut normals = vec![Normal::DEFAULT; nn];
            let m = PainterMemory {
                triangles: &mut triangles,
                order: &mut order,
                normals: &mut normals,
            };
            render_painter(
                &renderer,
                &mut fb,
                &mut scratch,
                m,
                policy,
                &mut RenderStats::default(),
            )
            .map_err(|e| e.to_string())
        });
        let drawn = drawn.map(|()| pixels);
        if split {
            if let (Ok(p), Ok((z, depth))) = (&drawn, &z32) {
                painter_ties(&world, &objects, p, z, depth)?;
            } else {
                verdict("the painter", &drawn, &z32, false, false)?;
            }
        }
        note("painter", &drawn);
    }

    // The scan-line at both widths, bands of random height.
    for bits16 in [false, true] {
        let rows = size(&mut rng, 1, h as usize + 2) as u16;
        let band = w as usize * rows.min(h) as usize;
        let n = [
            memory(&mut rng, largest),
            memory(&mut rng, front),
            memory(&mut rng, front),
            memory(&mut rng, front),
            memory(&mut rng, band),
            memory(&mut rng, band),
        ];
        let enough =
            n[0] >= largest && n[1..4].iter().all(|&k| k >= front) && n[4] >= band && n[5] >= band;
        let drawn = if bits16 {
            scan_lines::<u16>(&renderer, (w, h, rows), n)
        } else {
            scan_lines::<u32>(&renderer, (w, h, rows), n)
        };
        let reference = if bits16 { &z16 } else { &z32 };
        verdict("the scan-line", &drawn, reference, enough, true)?;
        note("scan-line", &drawn);
    }

    // Warnock.
    {
        let n = [
            memory(&mut rng, largest),
            memory(&mut rng, front),
            memory(&mut rng, 2 * front + 64),
            memory(&mut rng, 64),
        ];
        let enough = n[0] >= largest && n[1] >= front && n[2] >= 2 * front + 64 && n[3] >= 64;
        let mut pixels = vec![0u8; w as usize * h as usize];
        let drawn = frame(&mut pixels, w, h).and_then(|mut fb| {
            let mut scratch = vec![PreparedVertex::default(); n[0]];
            let mut triangles = vec![StoredTriangle::default(); n[1]];
            let mut candidates = vec![0u32; n[2]];
            let mut windows = vec![Area::DEFAULT; n[3]];
            let m = WarnockMemory {
                triangles: &mut triangles,
                candidates: &mut candidates,
                windows: &mut windows,
            };
            render_warnock(
                &renderer,
                &mut fb,
                &mut scratch,
                m,
                &mut RenderStats::default(),
            )
            .map_err(|e| e.to_string())
        });
        let drawn = drawn.map(|()| pixels);
        verdict("Warnock", &drawn, &z32, enough, !fast)?;
        note("Warnock", &drawn);
    }

    // The z-buffer in bands (polygon table or not) and in compact bands, both widths.
    for bits16 in [false, true] {
        let rows = size(&mut rng, 1, h as usize + 2) as u16;
        let table = chance(&mut rng, 50);
        let nv = memory(&mut rng, if table { all_vertices } else { largest });
        let np = if table { memory(&mut rng, polygons) } else { 0 };
        let enough = nv >= if table { all_vertices } else { largest } && (!table || np >= polygons);
        let drawn = {
            let mut scratch = vec![PreparedVertex::default(); nv];
            let mut rows_table = vec![PolygonRows::default(); np];
            let band = BandScratch {
                vertices: &mut scratch,
                polygons: &mut rows_table,
            };
            if bits16 {
                render_picture::<u16, 4>(&renderer, (w, h), Some(rows), band).map(|p| p.0)
            } else {
                render_picture::<u32, 4>(&renderer, (w, h), Some(rows), band).map(|p| p.0)
            }
            .map_err(|e| e.to_string())
        };
        let reference = if bits16 { &z16 } else { &z32 };
        verdict("the z-buffer in bands", &drawn, reference, enough, true)?;
        note("bands", &drawn);
        let rows = size(&mut rng, 1, h as usize + 2) as u16;
        let drawn = if bits16 {
            render_compact_picture::<u16, 4>(&renderer, (w, h), rows).map(|p| p.0)
        } else {
            render_compact_picture::<u32, 4>(&renderer, (w, h), rows).map(|p| p.0)
        }
        .map_err(|e| e.to_string());
        // Compact bands refuse, in words, a vertex outside the guard band (`NotCompact`).
        verdict("compact bands", &drawn, reference, true, false)?;
        note("compact", &drawn);
    }

    // Double-buffered bands through an identity LUT.
    {
        let rows = size(&mut rng, 1, h as usize + 2) as u16;
        let band = w as usize * rows.min(h) as usize;
        let sends = [memory(&mut rng, band), memory(&mut rng, band)];
        let enough = sends.iter().all(|&n| n >= band);
        let drawn = double_bands(&renderer, (w, h, rows), sends, largest);
        verdict("DoubleBands", &drawn, &z32, enough, true)?;
        note("double bands", &drawn);
    }
    Ok(Ok(fingerprint))
}

/// A whole frame over `pixels`, or the refusal in words.
fn frame(pixels: &mut [u8], w: u16, h: u16) -> Result<Framebuffer<'_>, String> {
    Framebuffer::new(pixels, w, h).map_err(|e| e.to_string())
}

/// The scan-line with memory of the sizes `n` (scratch, triangles, order, active, band pixels,
/// band depths), the picture assembled from its bands.
fn scan_lines<D: DepthValue>(
    renderer: &SceneRenderer<'_, 4>,
    (w, h, rows): (u16, u16, u16),
    n: [usize; 6],
) -> Drawn {
    let mut scratch = vec![PreparedVertex::default(); n[0]];
    let mut triangles = vec![StoredTriangle::default(); n[1]];
    let (mut order, mut active) = (vec![0u32; n[2]], vec![0u32; n[3]]);
    let (mut pixels, mut depths) = (vec![0u8; n[4]], vec![D::FAR; n[5]]);
    let memory = ScanLineMemory {
        triangles: &mut triangles,
        order: &mut order,
        active: &mut active,
        pixels: &mut pixels,
        depths: &mut depths,
    };
    let mut picture = vec![renderer.scene().background; w as usize * h as usize];
    let mut outside = false;
    render_scan_lines(
        renderer,
        (w, h, rows),
        &mut scratch,
        memory,
        &mut RenderStats::default(),
        |band, _| {
            for (y, row) in band.rows() {
                let at = y as usize * w as usize;
                match picture.get_mut(at..at + w as usize) {
                    Some(dst) if row.len() == w as usize => dst.copy_from_slice(row),
                    _ => outside = true,
                }
            }
            Ok::<(), zscan::visibility::VisibilityError>(())
        },
    )
    .map_err(|e| e.to_string())?;
    if outside {
        return Err("the scan-line handed a row outside the picture".into());
    }
    Ok(picture)
}

/// A sink that copies each band sent into a whole screen of indices.
struct Screen<'buf> {
    width: usize,
    screen: Vec<u8>,
    away: Option<&'buf mut [u8]>,
    outside: bool,
}

impl<'buf> BandSink<'buf, u8> for Screen<'buf> {
    type Error = String;

    fn start(&mut self, pixels: &'buf mut [u8], area: Rectangle) -> Result<(), String> {
        let (x, y) = (area.top_left.x, area.top_left.y);
        let (bw, bh) = (area.size.width as usize, area.size.height as usize);
        if x != 0 || y < 0 || bw != self.width || pixels.len() < bw * bh {
            self.outside = true;
        } else {
            let at = y as usize * self.width;
            match self.screen.get_mut(at..at + bw * bh) {
                Some(dst) => dst.copy_from_slice(&pixels[..bw * bh]),
                None => self.outside = true,
            }
        }
        self.away = Some(pixels);
        Ok(())
    }

    fn wait(&mut self) -> (&'buf mut [u8], Result<(), String>) {
        (self.away.take().unwrap_or_default(), Ok(()))
    }
}

/// `DoubleBands` with send buffers of `sends` pixels, bands of `rows` rows at 32 bits.
fn double_bands(
    renderer: &SceneRenderer<'_, 4>,
    (w, h, rows): (u16, u16, u16),
    sends: [usize; 2],
    largest: usize,
) -> Drawn {
    let lut = Lut::from_entries(core::array::from_fn(|i| i as u8));
    let band = w as usize * rows.min(h) as usize;
    let (mut pixels, mut depths) = (vec![0u8; band], vec![u32::FAR; band]);
    let mut scratch = vec![PreparedVertex::default(); largest.max(1)];
    let (mut a, mut b) = (vec![0u8; sends[0]], vec![0u8; sends[1]]);
    let mut sink = Screen {
        width: w as usize,
        screen: vec![renderer.scene().background; w as usize * h as usize],
        away: None,
        outside: false,
    };
    {
        let mut bands = DoubleBands::new(&lut, [&mut a, &mut b], &mut sink);
        bands
            .render::<u32, 4>(
                renderer,
                (&mut pixels, &mut depths),
                (w, h, rows),
                BandScratch {
                    vertices: &mut scratch,
                    polygons: &mut [],
                },
                &mut RenderStats::default(),
                |_| {},
            )
            .map_err(|e| e.to_string())?;
    }
    if sink.outside {
        return Err("DoubleBands sent a band outside the picture".into());
    }
    Ok(sink.screen)
}

/// The painter's picture against the 32-bit z-buffer's: every pixel equal, except where the
/// painter shows a surface that the z-buffer's 32-bit depth ties with the one it kept (the
/// painter orders exact planes and paints the exactly nearer of two surfaces less than a depth
/// unit apart, `zscan::visibility`'s module doc). Each polygon is drawn alone by the z-buffer
/// to find the surfaces at a differing pixel; that is done only when a pixel differs.
fn painter_ties(
    world: &World,
    objects: &[Object<'_>],
    painted: &[u8],
    z: &[u8],
    depth: &[u32],
) -> Result<(), String> {
    let (w, h) = world.size();
    let differing: Vec<usize> = (0..z.len()).filter(|&i| painted[i] != z[i]).collect();
    if differing.is_empty() {
        return Ok(());
    }
    // Every polygon alone: (level, depth) at each differing pixel where it draws.
    let mut tied = vec![false; differing.len()];
    for (oi, placed) in world.objects.iter().enumerate() {
        let t = &world.meshes[placed.mesh];
        let k = t.size as usize;
        for p in 0..t.indices.len() / k {
            let indices = &t.indices[p * k..(p + 1) * k];
            let Ok(mesh) = zscan::geometry::mesh::Mesh::new(
                &t.vertices,
                indices,
                zscan::geometry::mesh::PolygonSizes::Uniform(t.size),
            ) else {
                continue;
            };
            let mut o: Object<'_> = objects[oi];
            o.mesh = mesh;
            let level;
            if let zscan::scene::Intensities::PerPolygon(l) = o.intensities {
                level = [l[p]];
                o.intensities = zscan::scene::Intensities::PerPolygon(&level);
            }
            let alone = [o];
            let scene = world.scene(&alone);
            let Ok(r) = Renderer::for_scene(&scene) else {
                continue;
            };
            let mut scratch = vec![PreparedVertex::default(); t.vertices.len()];
            let band = BandScratch {
                vertices: &mut scratch,
                polygons: &mut [],
            };
            let Ok((pix, d, _)) = render_picture::<u32, 4>(&r, (w, h), None, band) else {
                continue;
            };
            for (j, &i) in differing.iter().enumerate() {
                tied[j] |= d[i] == depth[i] && pix[i] == painted[i];
            }
        }
    }
    match tied.iter().position(|&t| !t) {
        None => Ok(()),
        Some(j) => {
            let i = differing[j];
            Err(format!(
                "the painter: {} pixels differ, ({}, {}) is {} against the z-buffer's {} at \
                 depth {}, no surface tying with it shows {}",
                differing.len(),
                i % w as usize,
                i / w as usize,
                painted[i],
                z[i],
                depth[i],
                painted[i]
            ))
        }
    }
}
