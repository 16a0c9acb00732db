//! Rendering a host [`Scene`] with the zscan core.
//!
//! Floats exist only here, in set-up: vertex positions are rounded once to I16F16, the camera
//! is built from the rounded eye/target/up and an angle in 2^32 units per turn, and the
//! per-corner intensities become a per-vertex table (when every corner of a vertex agrees,
//! as on the sphere and bunny), a per-polygon table (flat faces, as on the quad and cube) or,
//! failing both, a triangle soup with its own vertices. Everything per frame runs in the core.

use zscan::geometry::camera::{Camera, FovAxis, Lens, Viewport};
use zscan::geometry::fixed::Coord;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::trig::BinaryAngle;
use zscan::geometry::vector::Vec3;
use zscan::output::{DepthValue, Framebuffer};
use zscan::raster::triangle::{LuminanceRamp, ShadeMode};
use zscan::render::{
    render_in_bands, BandPart, BandScratch, PolygonRows, PreparedVertex, RenderError, RenderStats,
    SceneRenderer,
};
use zscan::scene::{Intensities, Object, Scene as CoreScene};
use zscan::visibility::{
    render_back_faces, render_painter, render_reverse_painter, render_scan_lines, render_warnock,
    Area, Convexity, MeshFacts, Normal, PainterMemory, ScanLineMemory, SplitPolicy, StoredTriangle,
    Visibility, VisibilityError, WarnockMemory,
};

use crate::scenes::Scene;

/// Sub-pixel bits the host renders with (the core's default).
pub const S: u32 = 4;

/// A scene converted to the core's integer tables.
#[derive(Debug, Clone)]
pub struct CoreMesh {
    /// Vertex table (I16F16).
    pub vertices: Vec<Vec3>,
    /// Triangle indices, three per triangle.
    pub indices: Vec<u16>,
    /// Intensity table (per vertex or per polygon, see `per_vertex`).
    pub intensities: Vec<u8>,
    /// True when `intensities` is per vertex, false when per polygon.
    pub per_vertex: bool,
    /// The camera.
    pub camera: Camera,
}

/// A `w × h` frame over `pixels` (allocated `w × h` by the caller): refused only for a zero
/// size, as the pixels the frame needs.
fn whole_frame(pixels: &mut [u8], w: u16, h: u16) -> Result<Framebuffer<'_>, RenderError> {
    let given = pixels.len();
    Framebuffer::new(pixels, w, h).map_err(|_| RenderError::BandMemoryTooSmall {
        part: BandPart::Pixels,
        given,
        needed: w as usize * h as usize,
    })
}

/// I16F16 from `f64`, rounded to nearest, saturating.
pub fn coord(v: f64) -> Coord {
    Coord::saturating_from_num(v)
}

fn vec3(v: [f64; 3]) -> Vec3 {
    Vec3::new(coord(v[0]), coord(v[1]), coord(v[2]))
}

/// The core camera of a host camera.
pub fn core_camera(c: &crate::scenes::Camera) -> Result<Camera, String> {
    let turns = c.fov_y / std::f64::consts::TAU;
    let lens = Lens {
        fov: BinaryAngle::from_turns((turns * (1u64 << 31) as f64).round() as i64, 1 << 31),
        axis: FovAxis::Vertical,
        near: coord(c.near),
        far: coord(c.far),
    };
    let w = u16::try_from(c.width).map_err(|_| "viewport width above 65535".to_string())?;
    let h = u16::try_from(c.height).map_err(|_| "viewport height above 65535".to_string())?;
    let mut vp = Viewport::new(w, h);
    vp.principal_x = coord(c.principal.0);
    vp.principal_y = coord(c.principal.1);
    Camera::look_at(vec3(c.eye), vec3(c.target), vec3(c.up), lens, vp)
        .map_err(|e| format!("camera: {e:?}"))
}

/// Converts a host scene (see the module doc for the intensity tables).
pub fn to_core(scene: &Scene) -> Result<CoreMesh, String> {
    let camera = core_camera(&scene.camera)?;
    let nv = scene.vertices.len();
    // Per-vertex if every corner of each vertex agrees.
    let mut per_vertex: Vec<Option<u8>> = vec![None; nv];
    let mut consistent = true;
    for (t, tri) in scene.triangles.iter().enumerate() {
        for c in 0..3 {
            let l = scene.intensities[t][c];
            match per_vertex[tri[c]] {
                None => per_vertex[tri[c]] = Some(l),
                Some(x) if x != l => consistent = false,
                _ => {}
            }
        }
    }
    let flat = scene
        .intensities
        .iter()
        .all(|i| i[0] == i[1] && i[1] == i[2]);
    let (vertices, indices, intensities, per_vertex): (Vec<[f64; 3]>, Vec<usize>, Vec<u8>, bool) =
        if consistent {
            let table = per_vertex.iter().map(|l| l.unwrap_or(0)).collect();
            (
                scene.vertices.clone(),
                scene.triangles.iter().flatten().copied().collect(),
                table,
                true,
            )
        } else if flat {
            let table = scene.intensities.iter().map(|i| i[0]).collect();
            (
                scene.vertices.clone(),
                scene.triangles.iter().flatten().copied().collect(),
                table,
                false,
            )
        } else {
            let verts = scene
                .triangles
                .iter()
                .flat_map(|t| t.map(|i| scene.vertices[i]))
                .collect();
            let table = scene.intensities.iter().flatten().copied().collect();
            (
                (verts),
                (0..3 * scene.triangles.len()).collect(),
                table,
                true,
            )
        };
    if vertices.len() > u16::MAX as usize + 1 {
        return Err(format!(
            "{} vertices: the core indexes at most 65536",
            vertices.len()
        ));
    }
    Ok(CoreMesh {
        vertices: vertices.into_iter().map(vec3).collect(),
        indices: indices.into_iter().map(|i| i as u16).collect(),
        intensities,
        per_vertex,
        camera,
    })
}

/// The core scene of `objects` seen by `camera`, on background 0, unlit (ambient 0, no
/// light): how the host's tests, `zscan failures` and the charts draw one mesh or a soup.
pub fn scene_of<'a>(objects: &'a [Object<'a>], camera: Camera) -> CoreScene<'a> {
    CoreScene {
        camera,
        objects,
        background: 0,
        ambient: 0,
        lights: &[],
    }
}

/// The measured region of the host's instruction counts: `zscan chart` runs one frame under
/// valgrind callgrind collecting only inside this call (`--toggle-collect=zscan_chart_region`).
/// Never nested (callgrind would toggle collection off inside).
#[no_mangle]
#[inline(never)]
pub fn zscan_chart_region(f: &mut dyn FnMut()) {
    f()
}

/// `f()` inside [`zscan_chart_region`]: the frame functions below wrap exactly the core's
/// frame call in it, so that a count leaves out the buffers this harness allocates (a device
/// has them statically) but keeps the core's clears and the copy of each finished band into
/// the picture (a device's flush).
pub fn measured<R>(f: impl FnOnce() -> R) -> R {
    let (mut f, mut out) = (Some(f), None);
    zscan_chart_region(&mut || out = f.take().map(|f| f()));
    out.expect("zscan_chart_region calls its closure once")
}

/// A frame rendered by the core.
#[derive(Debug, Clone)]
pub struct CoreFrame<D> {
    /// Palette indices (grey ramp: the luminance), row-major.
    pub pixels: Vec<u8>,
    /// Depth samples, row-major (`D::FAR` where nothing was drawn).
    pub depth: Vec<D>,
    /// Frame statistics (summed over bands).
    pub stats: RenderStats,
}

impl CoreMesh {
    /// The core mesh view.
    pub fn mesh(&self) -> Result<Mesh<'_>, String> {
        Mesh::new(&self.vertices, &self.indices, PolygonSizes::Uniform(3))
            .map_err(|e| format!("mesh: {e:?}"))
    }

    /// The object with the grey ramp and the given shading.
    pub fn object(&self, shade: ShadeMode) -> Result<Object<'_>, String> {
        let mut o = Object::new(self.mesh()?);
        o.intensities = if self.per_vertex {
            Intensities::PerVertex(&self.intensities)
        } else {
            Intensities::PerPolygon(&self.intensities)
        };
        o.shade = shade;
        o.ramp = LuminanceRamp::GREY;
        Ok(o)
    }

    /// Renders the frame, in one pass (`band_rows = None`) or band by band, without the
    /// polygon table (every band tests every polygon).
    pub fn render<D: DepthValue>(
        &self,
        shade: ShadeMode,
        band_rows: Option<u16>,
    ) -> Result<CoreFrame<D>, String> {
        self.render_with(shade, band_rows, false)
    }

    /// [`render`](Self::render), with or without `render_in_bands`' polygon table.
    pub fn render_with<D: DepthValue>(
        &self,
        shade: ShadeMode,
        band_rows: Option<u16>,
        polygon_table: bool,
    ) -> Result<CoreFrame<D>, String> {
        let vp = *self.camera.viewport();
        let (w, h) = (vp.width, vp.height);
        let object = self.object(shade)?;
        let objects = [object];
        let scene = scene_of(&objects, self.camera);
        let renderer = SceneRenderer::<S>::new(&scene).map_err(|e| e.to_string())?;
        let mut scratch = vec![PreparedVertex::default(); self.vertices.len()];
        let polygons = if polygon_table {
            objects[0].mesh.polygon_count()
        } else {
            0
        };
        let mut table = vec![PolygonRows::default(); polygons];
        let band_scratch = BandScratch {
            vertices: &mut scratch,
            polygons: &mut table,
        };
        let (pixels, depth, stats) = render_picture(&renderer, (w, h), band_rows, band_scratch)
            .map_err(|e| e.to_string())?;
        Ok(CoreFrame {
            pixels,
            depth,
            stats,
        })
    }
}

/// Renders `scene` into a whole `w × h` picture with the core's [`render_in_bands`], through
/// one band-sized pair of buffers (the embedded way: each finished band is copied out here
/// where a device would flush it). `band_rows = None` is one band of the whole height.
/// Returns the picture's indices and depths, row-major, and the summed statistics.
pub fn render_picture<D: DepthValue, const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    (w, h): (u16, u16),
    band_rows: Option<u16>,
    scratch: BandScratch<'_, SB>,
) -> Result<(Vec<u8>, Vec<D>, RenderStats), zscan::render::RenderError> {
    let scene = renderer.scene();
    // A 0 is passed on for the core to refuse (`BadBandRows`); a band taller than the
    // picture is the picture.
    let band = band_rows.unwrap_or(h);
    let n = w as usize * band.min(h.max(1)) as usize;
    let (mut band_pixels, mut band_depths) = (vec![0u8; n], vec![D::FAR; n]);
    let total = w as usize * h as usize;
    let (mut pixels, mut depth) = (vec![scene.background; total], vec![D::FAR; total]);
    let mut stats = RenderStats::default();
    measured(|| {
        render_in_bands(
            renderer,
            (&mut band_pixels, &mut band_depths),
            (w, h, band),
            scratch,
            &mut stats,
            |frame, zb| {
                for y in frame.top()..frame.top() + frame.height() as i32 {
                    let at = y as usize * w as usize;
                    if let (Some(row), Some(zrow)) = (frame.row(y), zb.row(y)) {
                        pixels[at..at + w as usize].copy_from_slice(row);
                        depth[at..at + w as usize].copy_from_slice(zrow);
                    }
                }
                Ok::<(), RenderError>(())
            },
        )
    })?;
    Ok((pixels, depth, stats))
}

/// Windows on Warnock's stack in [`render_visible`]: `1 + 3 × 16` levels, any frame.
pub const WARNOCK_WINDOWS: usize = 49;

/// The caller memory, in bytes, of a `w × h` frame drawn by `visibility` with `band_rows`-row
/// bands (scan-line, z-buffer) and `depth_bytes` per depth sample, for a scene of `vertices`
/// vertices and `polygons` polygons, as [`render_visible`] and `zscan render` give it (the
/// `ram_bytes` of `--stats`): the frame (the band, for the methods that draw in bands), the
/// depth samples, the vertex scratch, the z-buffer's polygon table, and the triangle store,
/// orders, active table and Warnock's stacks as far as the frame filled them (`stats.method`).
pub fn ram_bytes<const SB: u32>(
    visibility: Visibility,
    (w, h): (u16, u16),
    band_rows: u16,
    (vertices, polygons): (usize, usize),
    depth_bytes: usize,
    stats: &RenderStats,
) -> usize {
    use core::mem::size_of;
    let m = &stats.method;
    let frame = w as usize * h as usize;
    let band = w as usize * band_rows.min(h.max(1)) as usize;
    let scratch = vertices * size_of::<PreparedVertex<SB>>();
    let stored = m.stored as usize * size_of::<StoredTriangle<SB>>();
    let order = 4 * m.stored as usize;
    scratch
        + match visibility {
            Visibility::BackFace => frame,
            Visibility::ReversePainter => frame + 4 * zscan::output::mask_words_needed(w, h),
            Visibility::Painter => {
                let pieces = m.pieces as usize;
                frame
                    + stored
                    + order
                    + pieces * (size_of::<StoredTriangle<SB>>() + 4)
                    + m.stored as usize * size_of::<Normal>()
            }
            Visibility::ScanLine => {
                band * (1 + depth_bytes) + stored + order + 4 * m.active_peak as usize
            }
            Visibility::Warnock => {
                frame
                    + stored
                    + 4 * m.candidates_peak as usize
                    + m.stack_peak as usize * size_of::<Area>()
            }
            Visibility::ZBuffer => band * (1 + depth_bytes) + polygons * size_of::<PolygonRows>(),
        }
}

/// Renders `scene` into a whole `w × h` picture by the hidden-surface method `visibility`
/// ([`zscan::visibility`]), with caller memory sized for the scene on the host: the painter
/// with a split budget of `splits` (`None`: no test 6), the scan-line and z-buffer in bands of
/// `band_rows` rows with 32-bit depth (the z-buffer the reference the other methods are
/// compared with). [`render_visible_at`] takes the depth width.
pub fn render_visible<const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    size: (u16, u16),
    visibility: Visibility,
    splits: Option<usize>,
    band_rows: u16,
) -> Result<(Vec<u8>, RenderStats), VisibilityError> {
    render_visible_at::<u32, SB>(renderer, size, visibility, splits, band_rows)
}

/// [`render_visible`] with depth samples `D` for the methods that keep depth (the scan-line's
/// band, the z-buffer): at a scene's `depth_bits`, the scan-line draws that z-buffer's picture
/// (the same writer quantises depth to `D` and compares it). The painter and Warnock keep no
/// depth: they claim the 32-bit z-buffer's picture whatever `D`.
pub fn render_visible_at<D: DepthValue, const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    (w, h): (u16, u16),
    visibility: Visibility,
    splits: Option<usize>,
    band_rows: u16,
) -> Result<(Vec<u8>, RenderStats), VisibilityError> {
    let scene = renderer.scene();
    let vertices: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let polygons: usize = scene.objects.iter().map(|o| o.mesh.polygon_count()).sum();
    let mut scratch = vec![PreparedVertex::default(); vertices.max(1)];
    let mut stats = RenderStats::default();
    // Front triangles: at most the fans of every polygon (triangles here), plus pieces.
    let capacity = 2 * polygons * 4 + 64;
    let total = w as usize * h as usize;
    match visibility {
        Visibility::BackFace => {
            let mut pixels = vec![0u8; total];
            let mut frame = whole_frame(&mut pixels, w, h)?;
            measured(|| render_back_faces(renderer, &mut frame, &mut scratch, &mut stats))?;
            Ok((pixels, stats))
        }
        // A scene outside the planner's rule 1 is `VisibilityError::ReverseRefused`, in words.
        Visibility::ReversePainter => reverse_picture(renderer, (w, h)),
        Visibility::Painter => {
            let mut pixels = vec![0u8; total];
            let mut frame = whole_frame(&mut pixels, w, h)?;
            let mut triangles = vec![StoredTriangle::default(); capacity];
            let mut order = vec![0u32; capacity];
            let mut normals = vec![Normal::DEFAULT; capacity];
            let memory = PainterMemory {
                triangles: &mut triangles,
                order: &mut order,
                normals: &mut normals,
            };
            let policy = splits.map_or(SplitPolicy::Never, SplitPolicy::Budget);
            measured(|| {
                render_painter(
                    renderer,
                    &mut frame,
                    &mut scratch,
                    memory,
                    policy,
                    &mut stats,
                )
            })?;
            Ok((pixels, stats))
        }
        Visibility::ScanLine => {
            let pixels = scan_line_picture::<D, SB>(
                renderer,
                (w, h),
                band_rows,
                &mut scratch,
                capacity,
                &mut stats,
            )?;
            Ok((pixels, stats))
        }
        Visibility::Warnock => {
            let mut pixels = vec![0u8; total];
            let mut frame = whole_frame(&mut pixels, w, h)?;
            let mut triangles = vec![StoredTriangle::default(); capacity];
            let mut candidates = vec![0u32; 2 * capacity];
            let mut windows = vec![Area::DEFAULT; WARNOCK_WINDOWS];
            let memory = WarnockMemory {
                triangles: &mut triangles,
                candidates: &mut candidates,
                windows: &mut windows,
            };
            measured(|| render_warnock(renderer, &mut frame, &mut scratch, memory, &mut stats))?;
            Ok((pixels, stats))
        }
        Visibility::ZBuffer => {
            let mut table = vec![PolygonRows::default(); polygons];
            let band_scratch = BandScratch {
                vertices: &mut scratch,
                polygons: &mut table,
            };
            let (pixels, _, stats) =
                render_picture::<D, SB>(renderer, (w, h), Some(band_rows), band_scratch)?;
            Ok((pixels, stats))
        }
    }
}

/// The whole `w × h` picture of `scene` by the reverse painter
/// ([`render_reverse_painter`]): each mesh's facts computed here, a mask of
/// `mask_words_needed(w, h)` words. A scene outside the planner's rule 1 is
/// [`VisibilityError::ReverseRefused`], naming why.
pub fn reverse_picture<const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    (w, h): (u16, u16),
) -> Result<(Vec<u8>, RenderStats), VisibilityError> {
    let scene = renderer.scene();
    let largest = scene.objects.iter().map(|o| o.mesh.vertices().len()).max();
    let mut scratch = vec![PreparedVertex::default(); largest.unwrap_or(0).max(1)];
    let mut words: Vec<Vec<u32>> = scene
        .objects
        .iter()
        .map(|o| vec![0u32; MeshFacts::words_needed(&o.mesh)])
        .collect();
    let facts: Vec<MeshFacts<'_>> = scene
        .objects
        .iter()
        .zip(words.iter_mut())
        .map(|(o, w)| {
            MeshFacts::of(&o.mesh, w).unwrap_or(MeshFacts {
                convexity: Convexity::NotConvex,
                bounds: [[i32::MIN; 3], [i32::MAX; 3]],
            })
        })
        .collect();
    let mut order = vec![0u16; scene.objects.len()];
    let mut pixels = vec![0u8; w as usize * h as usize];
    let mut frame = whole_frame(&mut pixels, w, h)?;
    let mut mask = vec![0u32; zscan::output::mask_words_needed(w, h)];
    let mut stats = RenderStats::default();
    measured(|| {
        render_reverse_painter(
            renderer,
            &facts,
            &mut order,
            &mut frame,
            &mut mask,
            &mut scratch,
            &mut stats,
        )
    })?;
    Ok((pixels, stats))
}

/// [`render_visible_at`]'s scan-line: bands of `band_rows` rows (depth samples `D`),
/// `capacity` stored triangles, each finished band copied into the whole picture.
fn scan_line_picture<D: DepthValue, const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    (w, h): (u16, u16),
    band_rows: u16,
    scratch: &mut [PreparedVertex<SB>],
    capacity: usize,
    stats: &mut RenderStats,
) -> Result<Vec<u8>, VisibilityError> {
    // A 0 is passed on for the core to refuse (`BadBandRows`).
    let n = w as usize * band_rows.min(h.max(1)) as usize;
    let (mut band_pixels, mut band_depths) = (vec![0u8; n], vec![D::FAR; n]);
    let mut triangles = vec![StoredTriangle::default(); capacity];
    let (mut order, mut active) = (vec![0u32; capacity], vec![0u32; capacity]);
    let memory = ScanLineMemory {
        triangles: &mut triangles,
        order: &mut order,
        active: &mut active,
        pixels: &mut band_pixels,
        depths: &mut band_depths,
    };
    let mut pixels = vec![renderer.scene().background; w as usize * h as usize];
    measured(|| {
        render_scan_lines(
            renderer,
            (w, h, band_rows),
            scratch,
            memory,
            stats,
            |frame, _| {
                for (y, row) in frame.rows() {
                    let at = y as usize * w as usize;
                    pixels[at..at + w as usize].copy_from_slice(row);
                }
                Ok::<(), VisibilityError>(())
            },
        )
    })?;
    Ok(pixels)
}

/// Renders `scene` into a whole `w × h` picture with the core's
/// [`render_in_compact_bands`](zscan::render::render_in_compact_bands) in bands of
/// `band_rows` rows, with exactly the memory [`CompactSizes::of`](zscan::render::CompactSizes)
/// gives; each finished band is copied out where a device would flush it. Returns the
/// picture's indices and depths, row-major, and the summed statistics.
pub fn render_compact_picture<D: DepthValue, const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    (w, h): (u16, u16),
    band_rows: u16,
) -> Result<(Vec<u8>, Vec<D>, RenderStats), RenderError> {
    let scene = renderer.scene();
    use zscan::render::{
        render_in_compact_bands, CompactBandScratch, CompactSizes, CompactVertex, PolygonTop,
    };
    let sizes = CompactSizes::of(scene);
    let n = w as usize * band_rows.min(h.max(1)) as usize;
    let (mut band_pixels, mut band_depths) = (vec![0u8; n], vec![D::FAR; n]);
    let mut vertices = vec![CompactVertex::default(); sizes.vertices];
    let mut levels = vec![0u8; sizes.levels];
    let mut polygons = vec![PolygonTop::default(); sizes.polygons];
    let total = w as usize * h as usize;
    let (mut pixels, mut depth) = (vec![scene.background; total], vec![D::FAR; total]);
    let mut stats = RenderStats::default();
    measured(|| {
        render_in_compact_bands(
            renderer,
            (&mut band_pixels, &mut band_depths),
            (w, h, band_rows),
            CompactBandScratch {
                vertices: &mut vertices,
                levels: &mut levels,
                polygons: &mut polygons,
            },
            &mut stats,
            |frame, zb| {
                for (y, row) in frame.rows() {
                    let at = y as usize * w as usize;
                    pixels[at..at + w as usize].copy_from_slice(row);
                    if let Some(zrow) = zb.row(y) {
                        depth[at..at + w as usize].copy_from_slice(zrow);
                    }
                }
                Ok::<(), RenderError>(())
            },
        )
    })?;
    Ok((pixels, depth, stats))
}

impl CoreMesh {
    /// The frame in compact bands of `band_rows` rows
    /// ([`render_compact_picture`]).
    pub fn render_compact<D: DepthValue>(
        &self,
        shade: ShadeMode,
        band_rows: u16,
    ) -> Result<CoreFrame<D>, String> {
        let vp = *self.camera.viewport();
        let object = self.object(shade)?;
        let objects = [object];
        let scene = scene_of(&objects, self.camera);
        let renderer = SceneRenderer::<S>::new(&scene).map_err(|e| e.to_string())?;
        let (pixels, depth, stats) =
            render_compact_picture(&renderer, (vp.width, vp.height), band_rows)
                .map_err(|e| e.to_string())?;
        Ok(CoreFrame {
            pixels,
            depth,
            stats,
        })
    }
}

/// Each object's [`MeshFacts`], computed once, with the
/// buffers its edge table borrows (`words[i]` for object `i`, sized by
/// [`MeshFacts::words_needed`](zscan::visibility::MeshFacts::words_needed): memory
/// proportional to the mesh).
pub fn mesh_facts<'p>(
    scene: &CoreScene<'_>,
    words: &'p mut Vec<Vec<u32>>,
) -> Result<Vec<zscan::visibility::MeshFacts<'p>>, String> {
    use zscan::visibility::MeshFacts;
    *words = scene
        .objects
        .iter()
        .map(|o| vec![0; MeshFacts::words_needed(&o.mesh)])
        .collect();
    scene
        .objects
        .iter()
        .zip(words.iter_mut())
        .enumerate()
        .map(|(i, (o, w))| MeshFacts::of(&o.mesh, w).map_err(|e| format!("object {i}: {e}")))
        .collect()
}

/// A frame drawn as its plan says, with the buffers the plan sized (the depth width, bands and
/// vertex scratch of [`Plan`](zscan::visibility::Plan)).
#[derive(Debug, Clone)]
pub struct PlannedFrame {
    /// The plan.
    pub plan: zscan::visibility::Plan,
    /// The drawing order the plan wrote.
    pub order: Vec<u16>,
    /// Palette indices, row-major.
    pub pixels: Vec<u8>,
    /// The frame's counts.
    pub stats: RenderStats,
}

/// Plans the renderer's scene within `budget` bytes and draws it so
/// ([`zscan::visibility::plan_frame`]: a plan of back faces alone draws with the vertices its
/// view check prepared; a z-buffer or reverse painter plan is drawn by [`draw_plan`]).
pub fn render_planned<const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    facts: &[zscan::visibility::MeshFacts<'_>],
    budget: usize,
) -> Result<PlannedFrame, String> {
    use zscan::visibility::{plan_frame, PlannedFrame as Planned};
    let scene = renderer.scene();
    let mut order = vec![0u16; scene.objects.len()];
    let largest = scene.objects.iter().map(|o| o.mesh.vertices().len()).max();
    let mut scratch = vec![PreparedVertex::<SB>::default(); largest.unwrap_or(0).max(1)];
    let planned = plan_frame(renderer, facts, budget, &mut order, &mut scratch)
        .map_err(|e| format!("plan: {e}"))?;
    let plan = *planned.plan();
    let (pixels, stats) = match planned {
        Planned::BackFace(frame) => {
            let vp = *scene.camera.viewport();
            let mut pixels = vec![0u8; vp.width as usize * vp.height as usize];
            let mut stats = RenderStats::default();
            let mut fb =
                Framebuffer::new(&mut pixels, vp.width, vp.height).map_err(|e| e.to_string())?;
            frame.render(&mut fb, &mut stats).map_err(render_words)?;
            (pixels, stats)
        }
        Planned::ZBuffer(plan) | Planned::ReversePainter(plan) => {
            draw_plan(renderer, &plan, &order).map_err(render_words)?
        }
    };
    Ok(PlannedFrame {
        plan,
        order,
        pixels,
        stats,
    })
}

/// A frame's error in words, for [`render_planned`].
fn render_words(e: VisibilityError) -> String {
    format!("render: {e}")
}

/// Draws the renderer's scene as `plan` says (objects in `order`) through the core's one
/// entry, [`zscan::visibility::draw_plan`], with buffers of exactly the plan's sizes
/// ([`PlanSizes`](zscan::visibility::PlanSizes)); returns the whole picture (bands copied out
/// as a display flush would take them) and the frame's counts.
pub fn draw_plan<const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    plan: &zscan::visibility::Plan,
    order: &[u16],
) -> Result<(Vec<u8>, RenderStats), VisibilityError> {
    use zscan::render::{CompactVertex, PolygonTop};
    use zscan::visibility::{PlanMemory, PlanSizes};
    let scene = renderer.scene();
    let vp = *scene.camera.viewport();
    let w = vp.width as usize;
    let n = PlanSizes::of(plan, scene);
    let (mut pixels, mut depth16, mut depth32) =
        (vec![0; n.pixels], vec![0; n.depth16], vec![0; n.depth32]);
    let mut vertices = vec![PreparedVertex::<SB>::default(); n.vertices];
    let mut polygons = vec![PolygonRows::default(); n.polygons];
    let mut compact_vertices = vec![CompactVertex::default(); n.compact_vertices];
    let (mut levels, mut tops) = (vec![0; n.levels], vec![PolygonTop::default(); n.tops]);
    let mut mask = vec![0u32; n.mask];
    let memory = PlanMemory {
        pixels: &mut pixels,
        depth16: &mut depth16,
        depth32: &mut depth32,
        vertices: &mut vertices,
        polygons: &mut polygons,
        compact_vertices: &mut compact_vertices,
        levels: &mut levels,
        tops: &mut tops,
        mask: &mut mask,
    };
    let mut picture = vec![scene.background; w * vp.height as usize];
    let mut stats = RenderStats::default();
    measured(|| {
        zscan::visibility::draw_plan(renderer, plan, order, memory, &mut stats, |band| {
            for (y, row) in band.rows() {
                let at = y as usize * w;
                picture[at..at + w].copy_from_slice(row);
            }
            Ok::<(), VisibilityError>(())
        })
    })?;
    Ok((picture, stats))
}
