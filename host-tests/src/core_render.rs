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
use zscan::geometry::trig::Angle;
use zscan::geometry::vector::Vec3;
use zscan::render::{
    render_in_bands, BandScratch, PolygonRows, PreparedVertex, RenderError, RenderStats,
    SceneRenderer,
};
use zscan::scene::{Intensities, Object, Scene as CoreScene};
use zscan::shade::span_writer::{LuminanceRamp, ShadeMode};
use zscan::target::{DepthValue, Framebuffer};
use zscan::visibility::{
    render_back_faces, render_painter, render_scan_lines, PainterMemory, ScanLineMemory,
    SplitPolicy, StoredTriangle, Visibility,
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
        fov: Angle::from_turns((turns * (1u64 << 31) as f64).round() as i64, 1 << 31),
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
        let scene = CoreScene {
            camera: self.camera,
            objects: &objects,
            background: 0,
            ambient: 0,
            lights: &[],
        };
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
    let band = band_rows.unwrap_or(h).clamp(1, h.max(1));
    let n = w as usize * band as usize;
    let (mut band_pixels, mut band_depths) = (vec![0u8; n], vec![D::FAR; n]);
    let total = w as usize * h as usize;
    let (mut pixels, mut depth) = (vec![scene.background; total], vec![D::FAR; total]);
    let mut stats = RenderStats::default();
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
    )?;
    Ok((pixels, depth, stats))
}

/// Renders `scene` into a whole `w × h` picture by the hidden-surface method `visibility`
/// ([`zscan::visibility`]), with caller memory sized for the scene on the host: the painter
/// with a split budget of `splits` (`None`: no test 6), the scan-line and z-buffer in bands of
/// `band_rows` rows (the z-buffer 32-bit, the reference the other methods are compared with).
pub fn render_visible<const SB: u32>(
    renderer: &SceneRenderer<'_, SB>,
    (w, h): (u16, u16),
    visibility: Visibility,
    splits: Option<usize>,
    band_rows: u16,
) -> Result<(Vec<u8>, RenderStats), RenderError> {
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
            let mut frame =
                Framebuffer::new(&mut pixels, w, h).map_err(|_| RenderError::BufferTooSmall)?;
            render_back_faces(renderer, &mut frame, &mut scratch, &mut stats)?;
            Ok((pixels, stats))
        }
        Visibility::Painter => {
            let mut pixels = vec![0u8; total];
            let mut frame =
                Framebuffer::new(&mut pixels, w, h).map_err(|_| RenderError::BufferTooSmall)?;
            let mut triangles = vec![StoredTriangle::default(); capacity];
            let mut order = vec![0u32; capacity];
            let memory = PainterMemory {
                triangles: &mut triangles,
                order: &mut order,
            };
            let policy = splits.map_or(SplitPolicy::Never, SplitPolicy::Budget);
            render_painter(
                renderer,
                &mut frame,
                &mut scratch,
                memory,
                policy,
                &mut stats,
            )?;
            Ok((pixels, stats))
        }
        Visibility::ScanLine => {
            let band = band_rows.clamp(1, h.max(1));
            let n = w as usize * band as usize;
            let (mut band_pixels, mut band_depths) = (vec![0u8; n], vec![0u32; n]);
            let mut triangles = vec![StoredTriangle::default(); capacity];
            let (mut order, mut active) = (vec![0u32; capacity], vec![0u32; capacity]);
            let memory = ScanLineMemory {
                triangles: &mut triangles,
                order: &mut order,
                active: &mut active,
                pixels: &mut band_pixels,
                depths: &mut band_depths,
            };
            let mut pixels = vec![scene.background; total];
            render_scan_lines(
                renderer,
                (w, h, band),
                &mut scratch,
                memory,
                &mut stats,
                |frame, _| {
                    for (y, row) in frame.rows() {
                        let at = y as usize * w as usize;
                        pixels[at..at + w as usize].copy_from_slice(row);
                    }
                    Ok::<(), RenderError>(())
                },
            )?;
            Ok((pixels, stats))
        }
        Visibility::ZBuffer => {
            let mut table = vec![PolygonRows::default(); polygons];
            let band_scratch = BandScratch {
                vertices: &mut scratch,
                polygons: &mut table,
            };
            let (pixels, _, stats) =
                render_picture::<u32, SB>(renderer, (w, h), Some(band_rows), band_scratch)?;
            Ok((pixels, stats))
        }
    }
}
