//! The frame: geometry → clipping → projection → raster → shading → target, for whole scenes.
//!
//! Role in the pipeline: the glue that runs every stage in order. A [`Renderer`] holds what is
//! fixed for a frame (projector, frustum, view transform, lights). For each [`Object`]:
//!
//! 1. **Vertex stage** ([`Renderer::prepare`]), once per vertex: model → observer frame with one
//!    combined [`Affine3`], the vertex's [`Frustum`] outcode, and, when it is inside the
//!    frustum (near, far and the guard band), its projection: sub-pixel screen position and
//!    normalised depth; for lit Gouraud objects, the vertex's lit level, and for levels given per
//!    vertex, a copy of the vertex's level. Results go to a caller-provided scratch slice (no heap), one
//!    [`PreparedVertex`] per mesh vertex.
//! 2. **Polygon stage** ([`Renderer::rasterize`]), once per polygon (`PolygonStage`, generic
//!    over corner attributes and triangle writer; triangle meshes have their own loop, which
//!    reads each vertex once and, for an object drawn in one pass with culling, tests no
//!    per-object flag per triangle): outcodes all outside one
//!    plane → rejected; all inside → back-face test on the projected polygon's signed area
//!    (exact integers) and drawn from the prepared vertices; otherwise → back-face test in the
//!    observer frame (exact, `i128`), Sutherland–Hodgman against the planes it crosses
//!    (course exercise 12), projection of the clipped vertices. Polygons are drawn as fans of
//!    triangles — exact for convex polygons, whose fan triangles tile them with the fill rule.
//! 3. **Raster** ([`draw_triangle_on`] into a [`RasterTarget`] prepared once per object, or
//!    [`draw_triangle_phong`] for lit Phong objects): the exact triangle fill with depth test
//!    and shading.
//!
//! ## Bands
//! Frame and depth buffer may be a band of rows ([`Framebuffer::band`]): the raster stage
//! writes only the rows the buffers hold, so drawing a picture band by band, flushing each band
//! to the display before the next, gives the same pixels as one pass (tested).
//! [`render_in_bands`] runs the vertex stage once per frame when its scratch holds every
//! object's vertices, and with a polygon table ([`PolygonRows`], [`Renderer::polygon_rows`])
//! decides rejection, culling and each polygon's rows once, so that each band visits only the
//! polygons that reach it (the costs are reported with the benchmarks).
//!
//! ## Numeric contract
//! Mesh coordinates `|c| ≤ 1024` ([`MAX_MESH_COORD_BITS`](crate::geometry::mesh::MAX_MESH_COORD_BITS));
//! observer-frame positions saturate to the I16F16 range. Once per object, the vertex stage
//! bounds them from the mesh's largest coordinate ([`Affine3::point_bounds`]); when that bound
//! is below `2^30` (and the frustum's side products fit 32 bits, [`Frustum::narrow_fits`]) it
//! runs a loop without saturation and with a 32-bit outcode, equal within the bound (tested
//! against the general loop). The frustum's guard band keeps
//! projected vertices within `±4` screen extents, so triangles stay far below the attribute
//! interpolation's size limit (`2·area < 2^30` sub-pixel units²). Intensities are `0..=255`.
//! Culling in the observer frame uses `i128` (edge vectors up to 2^32 raw, cross products up
//! to 2^65).

use core::cell::Cell;

use heapless::Vec;

use crate::clip::frustum::{ClipError, ClipVertex, Frustum};
use crate::geometry::camera::Camera;
use crate::geometry::fixed::mul_wide;
use crate::geometry::matrix::{Affine3, MatrixError};
use crate::geometry::mesh::PolygonSizes;
use crate::geometry::vector::Vec3;
use crate::project::{ProjectError, Projector};
use crate::raster::edge_walker::ceil_shift;
use crate::raster::SubpixelPoint;
use crate::scene::{Intensities, Object, Scene};
use crate::shade::dither::Bayer4;
use crate::shade::lighting::{light_polygon, Illumination, Light, LightingError};
use crate::shade::phong::{draw_triangle_phong, PhongContext, PhongVertex};
use crate::shade::span_writer::{
    draw_triangle_on, CountWritten, DrawError, RasterTarget, ShadeMode, SkipWritten, WrittenCount,
};
use crate::target::{DepthBuffer, DepthValue, Framebuffer};

/// Largest polygon (vertex count) the clipping path accepts; each of the 6 planes may add one.
pub const MAX_POLYGON_VERTICES: usize = 24;
const CLIP_CAPACITY: usize = MAX_POLYGON_VERTICES + 6;

/// Outcode bit marking a vertex that could not be projected (forces the clipping path).
const UNPROJECTED: u8 = 0x80;
/// What [`PolygonStage::outcodes`] returns for a polygon wholly outside one plane (no real
/// union of outcodes has every bit set: bit 6 is unused).
const REJECTED: u8 = 0xFF;

/// Why a frame or object could not be rendered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RenderError {
    /// The scratch slice is shorter than the mesh's vertex table.
    ScratchTooSmall {
        /// Vertices in the mesh.
        needed: usize,
    },
    /// An intensity table is shorter than the vertex or polygon table it describes.
    IntensitiesTooShort,
    /// A polygon has more than [`MAX_POLYGON_VERTICES`] vertices.
    PolygonTooLarge,
    /// Composing the object and view transforms overflowed.
    Transform(MatrixError),
    /// The camera cannot be used for projection (sub-pixel bits, ranges).
    Projection(ProjectError),
    /// Clipping failed (capacity, plane range).
    Clip(ClipError),
    /// A triangle was rejected by the raster stage (range or size limits).
    Draw(DrawError),
    /// The band buffers hold fewer than `width × band_rows` elements (or the size is zero).
    BufferTooSmall,
    /// The lights could not be set up (too many, a zero direction).
    Lighting(LightingError),
}

impl core::fmt::Display for RenderError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::ScratchTooSmall { needed } => {
                write!(f, "scratch holds fewer than the mesh's {needed} vertices")
            }
            RenderError::IntensitiesTooShort => {
                write!(f, "intensity table shorter than its mesh table")
            }
            RenderError::PolygonTooLarge => {
                write!(f, "polygon with more than {MAX_POLYGON_VERTICES} vertices")
            }
            RenderError::Transform(e) => write!(f, "transform: {e:?}"),
            RenderError::Projection(e) => write!(f, "projection: {e:?}"),
            RenderError::Clip(e) => write!(f, "clipping: {e:?}"),
            RenderError::Draw(e) => write!(f, "raster: {e:?}"),
            RenderError::BufferTooSmall => write!(f, "band buffers smaller than width × rows"),
            RenderError::Lighting(e) => write!(f, "lighting: {e:?}"),
        }
    }
}

/// What a frame did, for reports and tests.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Polygons read from the meshes.
    pub polygons_in: u32,
    /// Polygons skipped as back faces.
    pub culled: u32,
    /// Polygons wholly outside one frustum plane.
    pub rejected: u32,
    /// Polygons that went through the 3D clipper.
    pub clipped: u32,
    /// Triangles handed to the raster stage with non-zero area.
    pub triangles_drawn: u32,
    /// Pixels covered by drawn triangles inside the buffers (depth test passed or not).
    pub pixels_covered: u32,
    /// Pixels that passed the depth test and were written (not counted, 0, when drawn for a
    /// [`StatsWithoutWritten`]).
    pub pixels_written: u32,
}

/// Where the renderer adds its counts, and whether its span loops count written pixels:
/// [`RenderStats`] counts everything; [`StatsWithoutWritten`] everything but the written
/// pixels, whose per-pixel add the span loops then leave out
/// ([`WrittenCount`]).
pub trait StatsSink {
    /// [`CountWritten`] or [`SkipWritten`].
    type Count: WrittenCount;
    /// The counts added to.
    fn counts(&mut self) -> &mut RenderStats;
}

impl StatsSink for RenderStats {
    type Count = CountWritten;
    fn counts(&mut self) -> &mut RenderStats {
        self
    }
}

/// [`RenderStats`] whose `pixels_written` stays 0: the span loops drawn for it have no
/// written-pixel counter (the Cortex-M4 frames of the standard cube, sphere and bunny take
/// 6.4 %, 9.8 % and 6.5 % fewer instructions). Every other count is kept. Pass one to
/// [`render_scene`] or [`render_in_bands`] when nothing reads the written count.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StatsWithoutWritten(pub RenderStats);

impl StatsSink for StatsWithoutWritten {
    type Count = SkipWritten;
    fn counts(&mut self) -> &mut RenderStats {
        &mut self.0
    }
}

impl core::ops::AddAssign for RenderStats {
    /// Sums two frames' (or bands') counts.
    fn add_assign(&mut self, o: RenderStats) {
        self.polygons_in += o.polygons_in;
        self.culled += o.culled;
        self.rejected += o.rejected;
        self.clipped += o.clipped;
        self.triangles_drawn += o.triangles_drawn;
        self.pixels_covered += o.pixels_covered;
        self.pixels_written += o.pixels_written;
    }
}

/// One mesh vertex after the vertex stage: 28 bytes (the scratch a mesh needs is 28 bytes per
/// vertex; the bunny's 1,839 vertices take 51 KB).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PreparedVertex<const S: u32> {
    /// Observer-frame position.
    pub view: Vec3,
    /// Screen position (valid when `outcode == 0`).
    pub screen: SubpixelPoint<S>,
    /// Normalised depth (valid when `outcode == 0`).
    pub depth: u32,
    /// Frustum outcode: bit `i` set when outside plane `i`; 0 when projected.
    pub outcode: u8,
    /// Level `0..=255` of the vertex: lit, for a Gouraud-shaded lit object, or given
    /// ([`Intensities::PerVertex`], 0 past the end of a short table), where the polygon stage
    /// reads it with the vertex; 0 otherwise. It fits in the structure's padding.
    pub level: u8,
}

impl<const S: u32> Default for PreparedVertex<S> {
    fn default() -> Self {
        PreparedVertex {
            view: Vec3::ZERO,
            screen: SubpixelPoint::new(0, 0),
            depth: 0,
            outcode: 0,
            level: 0,
        }
    }
}

/// What the polygon stage does with one polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Path {
    /// Rejected, culled, or outside the band.
    Skip,
    /// Every vertex projected: drawn from the prepared vertices.
    Projected,
    /// Crosses a frustum plane: clipped, projected, drawn.
    Clip,
}

/// A polygon's fate in a frame drawn in bands, decided once by [`Renderer::polygon_rows`]:
/// the rows `top..bottom` its projection can touch (clamped to `0..=65535`), never drawn
/// (rejected or culled), or needing the clipper in every band it reaches. 4 bytes: one word,
/// `top | bottom << 16`, so that a band's scan tests `bottom` with one comparison.
#[derive(Clone, Copy, PartialEq, Eq, Default)]
pub struct PolygonRows {
    packed: u32,
}

impl core::fmt::Debug for PolygonRows {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PolygonRows")
            .field("top", &self.top())
            .field("bottom", &self.bottom())
            .finish()
    }
}

impl PolygonRows {
    /// Rejected or culled: no band draws it.
    pub const NEVER: PolygonRows = PolygonRows::pack(u16::MAX, 0);
    /// Crosses a frustum plane: every band runs the clipper (and the raster's own band limit).
    pub const CLIP: PolygonRows = PolygonRows::pack(u16::MAX, u16::MAX);

    const fn pack(top: u16, bottom: u16) -> PolygonRows {
        PolygonRows {
            packed: top as u32 | (bottom as u32) << 16,
        }
    }

    #[inline(always)]
    const fn top(self) -> u16 {
        self.packed as u16
    }

    #[inline(always)]
    const fn bottom(self) -> u16 {
        (self.packed >> 16) as u16
    }

    /// Rows `top..bottom` (half-open, any `i32`), clamped to `0..=65535` (band rows are
    /// within that range, so the overlap test is unchanged). A clamped `(65535, 65535)` is
    /// [`CLIP`](Self::CLIP), which draws the same pixels by the slower path.
    pub fn rows(top: i32, bottom: i32) -> PolygonRows {
        let c = |r: i32| r.clamp(0, u16::MAX as i32) as u16;
        PolygonRows::pack(c(top), c(bottom))
    }

    /// True when the polygon may touch rows `band.0..band.1`.
    #[inline(always)]
    fn meets(self, band: (i32, i32)) -> bool {
        (self.bottom() as i32) > band.0 && (self.top() as i32) < band.1
    }
}

/// Everything fixed for a frame: the camera's projector, frustum and view transform, and the
/// lights in the observer frame.
#[derive(Debug, Clone, Copy)]
pub struct Renderer<const S: u32 = 4> {
    camera: Camera,
    projector: Projector<S>,
    frustum: Frustum,
    view: Affine3,
    illumination: Illumination,
}

impl<const S: u32> Renderer<S> {
    /// The renderer of `camera` at `S` sub-pixel bits, with the default guard band. Its
    /// lighting is ambient only, at full intensity (`I_a = 255`, no lights): lit objects show
    /// `k_a·255` until [`with_lights`](Self::with_lights) sets the scene's lights.
    pub fn new(camera: &Camera) -> Result<Self, RenderError> {
        Ok(Renderer {
            camera: *camera,
            projector: Projector::new(camera).map_err(RenderError::Projection)?,
            frustum: Frustum::new::<S>(camera, Frustum::DEFAULT_GUARD)
                .map_err(RenderError::Clip)?,
            view: *camera.view_transform(),
            illumination: Illumination::observer(255, &[]).map_err(RenderError::Lighting)?,
        })
    }

    /// This renderer with ambient intensity `ambient` and `lights` (world frame, at most
    /// [`MAX_LIGHTS`](crate::shade::lighting::MAX_LIGHTS)) for lit objects.
    pub fn with_lights(mut self, ambient: u8, lights: &[Light]) -> Result<Self, RenderError> {
        self.illumination =
            Illumination::new(&self.camera, ambient, lights).map_err(RenderError::Lighting)?;
        Ok(self)
    }

    /// The renderer of a scene: its camera, ambient intensity and lights.
    pub fn for_scene(scene: &Scene<'_>) -> Result<Self, RenderError> {
        Renderer::new(&scene.camera)?.with_lights(scene.ambient, scene.lights)
    }

    /// The lights in the observer frame.
    pub fn illumination(&self) -> &Illumination {
        &self.illumination
    }

    /// The camera this renderer projects for.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The vertex stage for `object`: fills `scratch[..vertex count]`.
    pub fn prepare(
        &self,
        object: &Object<'_>,
        scratch: &mut [PreparedVertex<S>],
    ) -> Result<(), RenderError> {
        let vertices = object.mesh.vertices();
        let scratch = scratch
            .get_mut(..vertices.len())
            .ok_or(RenderError::ScratchTooSmall {
                needed: vertices.len(),
            })?;
        let m = self.model_view(object)?;
        // Lit Gouraud objects are lit here, once per vertex, in the observer frame.
        let lit = match object.intensities {
            Intensities::Lit { material, normals }
                if !matches!(object.shade, ShadeMode::Flat | ShadeMode::Phong) =>
            {
                if normals.len() < vertices.len() {
                    return Err(RenderError::IntensitiesTooShort);
                }
                Some((material, normals))
            }
            _ => None,
        };
        // Levels given per vertex are copied beside the vertex, where the polygon stage reads
        // them with it.
        let given = match object.intensities {
            Intensities::PerVertex(t) => t,
            _ => &[],
        };
        // Once per object: when no vertex of the mesh (all within ±max_coord_bits) can leave
        // the i32 range, nor make the frustum's side products leave 32 bits, the loop without
        // saturation and with the 32-bit outcode runs; both give the same values there.
        let narrow = self
            .frustum
            .narrow_fits(m.point_bounds(object.mesh.max_coord_bits()));
        // One loop per level source, so that the given-levels loop carries nothing of lighting.
        match lit {
            Some((material, normals)) => {
                let level = |i: usize, view: Vec3| {
                    let n = normals
                        .get(i)
                        .map_or([0; 3], |n| m.transform_vector(*n).bits());
                    let n = [n[0] as i64, n[1] as i64, n[2] as i64];
                    self.illumination.intensity(&material, view, n)
                };
                self.prepare_vertices(narrow, &m, vertices, scratch, &level);
            }
            None => {
                let level = |i: usize, _: Vec3| given.get(i).copied().unwrap_or(0);
                self.prepare_vertices(narrow, &m, vertices, scratch, &level);
            }
        }
        Ok(())
    }

    /// [`prepare_loop`](Self::prepare_loop) without saturation and with the 32-bit outcode
    /// when `narrow` (the object's bound passed [`Frustum::narrow_fits`]), else the general one.
    #[inline(always)]
    fn prepare_vertices(
        &self,
        narrow: bool,
        m: &Affine3,
        vertices: &[Vec3],
        scratch: &mut [PreparedVertex<S>],
        level: &impl Fn(usize, Vec3) -> u8,
    ) {
        if narrow {
            self.prepare_loop::<true>(m, vertices, scratch, level);
        } else {
            self.prepare_loop::<false>(m, vertices, scratch, level);
        }
    }

    /// The per-vertex loop of [`prepare`](Self::prepare): `NARROW` when the object's bound
    /// passed [`Frustum::narrow_fits`] ([`Affine3::transform_point_wrapping`] and
    /// [`Frustum::outcode_narrow`], equal to the saturating transform and the 64-bit outcode
    /// within that bound), else the general transform and outcode.
    /// `level(i, view)` gives vertex `i`'s level.
    #[inline(always)]
    fn prepare_loop<const NARROW: bool>(
        &self,
        m: &Affine3,
        vertices: &[Vec3],
        scratch: &mut [PreparedVertex<S>],
        level: &impl Fn(usize, Vec3) -> u8,
    ) {
        for (i, (out, v)) in scratch.iter_mut().zip(vertices).enumerate() {
            let (view, mut outcode);
            if NARROW {
                view = m.transform_point_wrapping(*v);
                outcode = self.frustum.outcode_narrow(view);
            } else {
                view = m.transform_point(*v);
                outcode = self.frustum.outcode(view);
            }
            let (mut screen, mut depth) = (SubpixelPoint::new(0, 0), 0);
            if outcode == 0 {
                match self.projector.project_point(view) {
                    Ok((p, d)) => (screen, depth) = (p, d),
                    Err(_) => outcode = UNPROJECTED,
                }
            }
            *out = PreparedVertex {
                view,
                screen,
                depth,
                outcode,
                level: level(i, view),
            };
        }
    }

    /// The polygon stage and raster for `object`, whose vertices `prepare` put in `scratch`.
    ///
    /// Lit objects ([`Intensities::Lit`]) get their levels here: flat ones per polygon
    /// ([`light_polygon`]), Gouraud ones from the vertex stage; Phong ones carry their
    /// observer-frame normals through clipping as three attributes and are lit per pixel
    /// ([`draw_triangle_phong`]).
    pub fn rasterize<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        self.rasterize_with(object, scratch, None, frame, depth, stats)
    }

    /// [`rasterize`](Self::rasterize) for one band, with the object's polygon table from
    /// [`polygon_rows`](Self::polygon_rows) (as long as its polygon table): a polygon is
    /// visited only when its rows meet the band, and rejection and culling are not repeated.
    /// `polygons_in`, `rejected` and `culled` were counted by `polygon_rows`.
    pub fn rasterize_rows<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        rows: &[PolygonRows],
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        if rows.len() < object.mesh.polygon_count() {
            return Err(RenderError::ScratchTooSmall {
                needed: object.mesh.polygon_count(),
            });
        }
        self.rasterize_with(object, scratch, Some(rows), frame, depth, stats)
    }

    /// The band pre-pass of an object whose vertices `prepare` put in `scratch`: for each
    /// polygon, [`PolygonRows::NEVER`] when it is rejected (wholly outside one plane) or culled,
    /// [`PolygonRows::CLIP`] when it crosses a plane, else the rows its projection touches.
    /// Counts `polygons_in`, `rejected` and `culled` into `stats`.
    pub fn polygon_rows(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        out: &mut [PolygonRows],
        stats: &mut impl StatsSink,
    ) -> Result<(), RenderError> {
        let stats = stats.counts();
        let mesh = &object.mesh;
        let needed = mesh.vertices().len();
        let prepared = scratch
            .get(..needed)
            .ok_or(RenderError::ScratchTooSmall { needed })?;
        let out = out
            .get_mut(..mesh.polygon_count())
            .ok_or(RenderError::ScratchTooSmall {
                needed: mesh.polygon_count(),
            })?;
        let stage = PolygonStage {
            renderer: self,
            object,
            prepared,
            rows: (0, 0),
            banded: false,
            table: None,
        };
        if let PolygonSizes::Uniform(3) = mesh.sizes() {
            stage.classify_triangles(out, stats)?;
        } else {
            for (o, poly) in out.iter_mut().zip(mesh.polygons()) {
                stats.polygons_in += 1;
                *o = stage.classify(poly, stats)?;
            }
        }
        Ok(())
    }

    fn rasterize_with<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        table: Option<&[PolygonRows]>,
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        let stats = stats.counts();
        let mesh = &object.mesh;
        let prepared =
            scratch
                .get(..mesh.vertices().len())
                .ok_or(RenderError::ScratchTooSmall {
                    needed: mesh.vertices().len(),
                })?;
        match object.intensities {
            Intensities::PerVertex(t) if t.len() < prepared.len() => {
                return Err(RenderError::IntensitiesTooShort)
            }
            Intensities::PerPolygon(t) if t.len() < mesh.polygon_count() => {
                return Err(RenderError::IntensitiesTooShort)
            }
            Intensities::Lit { normals, .. }
                if object.shade != ShadeMode::Flat && normals.len() < prepared.len() =>
            {
                return Err(RenderError::IntensitiesTooShort)
            }
            _ => {}
        }
        let rows = (frame.top().max(depth.top()), {
            let f = frame.top() + frame.height() as i32;
            f.min(depth.top() + depth.height() as i32)
        });
        let stage = PolygonStage {
            renderer: self,
            object,
            prepared,
            rows,
            banded: rows.0 > 0 || rows.1 < self.camera.viewport().height as i32,
            table,
        };
        if let (Intensities::Lit { material, normals }, ShadeMode::Phong) =
            (object.intensities, object.shade)
        {
            let model_view = self.model_view(object)?;
            let ctx = PhongContext {
                illumination: &self.illumination,
                material,
                ramp: object.ramp,
                dither: object.dither,
            };
            let normal = |i: u16| {
                let n = normals.get(i as usize).copied().unwrap_or(Vec3::ZERO);
                model_view.transform_vector(n).bits()
            };
            return stage.run(
                stats,
                |_, poly, k, _| normal(poly[k]),
                |c| {
                    let corner = |c: &Corner<S, 3>| PhongVertex {
                        screen: c.screen,
                        depth: c.depth,
                        position: c.view,
                        normal: Vec3::from_bits(c.attrs[0], c.attrs[1], c.attrs[2]),
                    };
                    let (covered, written) =
                        draw_triangle_phong(frame, depth, [0, 1, 2].map(|k| corner(&c[k])), &ctx)?;
                    Ok((covered, if T::Count::COUNTS { written } else { 0 }))
                },
            );
        }
        // Luminance triangles: the buffers prepared once for the object.
        let mut target = RasterTarget::with_count(frame, depth, T::Count::default());
        match object.intensities {
            Intensities::Lit { material, .. } if object.shade == ShadeMode::Flat => {
                // One level per polygon, computed for its first corner and reused.
                let model_view = self.model_view(object)?;
                let last = Cell::new((usize::MAX, 0u8));
                let level = |pi: usize, poly: &[u16]| {
                    if last.get().0 != pi {
                        let l =
                            light_polygon(mesh, poly, &model_view, &self.illumination, &material);
                        last.set((pi, l));
                    }
                    last.get().1
                };
                return stage.run(
                    stats,
                    |pi, poly, _, _| [level(pi, poly) as i32],
                    |c| draw_levels(&mut target, object, c),
                );
            }
            Intensities::Lit { .. } | Intensities::PerVertex(_) => {
                // Gouraud-lit or given per vertex: the level the vertex stage stored in the
                // prepared vertex, read with it.
                return stage.run(
                    stats,
                    |_, _, _, p| [p.map_or(0, |p| p.level as i32)],
                    |c| draw_levels(&mut target, object, c),
                );
            }
            _ => {}
        }
        stage.run(
            stats,
            |pi, poly, k, _| [object.intensity(pi, poly[k]) as i32],
            |c| draw_levels(&mut target, object, c),
        )
    }

    /// The object's model → observer transform.
    fn model_view(&self, object: &Object<'_>) -> Result<Affine3, RenderError> {
        object
            .transform
            .then(&self.view)
            .map_err(RenderError::Transform)
    }

    /// Both stages for one object.
    pub fn draw_object<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &mut [PreparedVertex<S>],
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        self.prepare(object, scratch)?;
        self.rasterize(object, scratch, frame, depth, stats)
    }
}

/// One triangle corner handed to a writer: screen position, depth, observer-frame position
/// and `N` attributes (a level, or a normal), from the vertex stage or the clipper.
#[derive(Debug, Clone, Copy)]
struct Corner<const S: u32, const N: usize> {
    screen: SubpixelPoint<S>,
    depth: u32,
    view: Vec3,
    attrs: [i32; N],
}

impl<const S: u32, const N: usize> Corner<S, N> {
    /// The corner of a prepared (projected) vertex with attributes `attrs`.
    #[inline(always)]
    fn prepared(p: &PreparedVertex<S>, attrs: [i32; N]) -> Self {
        Corner {
            screen: p.screen,
            depth: p.depth,
            view: p.view,
            attrs,
        }
    }
}

/// A luminance triangle (flat or Gouraud, plain or dithered) from corners whose one attribute
/// is a level (clamped to `0..=255`: clipped corners are interpolated).
#[inline(always)]
fn draw_levels<D: DepthValue, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    object: &Object<'_>,
    c: [Corner<S, 1>; 3],
) -> Result<(u32, u32), DrawError> {
    let v = c.map(|c| c.screen);
    let values = c.map(|c| [c.depth, c.attrs[0].clamp(0, 255) as u32]);
    let ramp = object.ramp;
    if object.dither {
        draw_triangle_on(target, v, values, object.shade, |x, y| {
            Bayer4::at(ramp, x, y)
        })
    } else {
        draw_triangle_on(target, v, values, object.shade, |_, _| ramp)
    }
}

/// The polygon stage of one object: rejection, culling, clipping, projection and fans, for
/// any per-corner attributes and triangle writer.
struct PolygonStage<'r, 'o, const S: u32> {
    renderer: &'r Renderer<S>,
    object: &'r Object<'o>,
    prepared: &'r [PreparedVertex<S>],
    /// Rows the buffers hold, `rows.0 .. rows.1`.
    rows: (i32, i32),
    /// The buffers hold only part of the viewport's rows.
    banded: bool,
    /// The object's band pre-pass ([`Renderer::polygon_rows`]), if any.
    table: Option<&'r [PolygonRows]>,
}

impl<const S: u32> PolygonStage<'_, '_, S> {
    /// Runs every polygon: `attrs(polygon index, polygon, corner k)` gives a corner's
    /// attributes, `draw` writes one triangle and returns `(covered, written)`.
    #[inline(always)]
    fn run<const N: usize>(
        &self,
        stats: &mut RenderStats,
        attrs: impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        mut draw: impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        // Two loops in separate functions, so that each keeps its drawing paths inline.
        match self.table {
            Some(table) => self.run_table(table, stats, &attrs, &mut draw),
            None => self.run_all(stats, &attrs, &mut draw),
        }
    }

    /// Every polygon, deciding rejection, band and culling for each.
    #[inline(never)]
    fn run_all<const N: usize>(
        &self,
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        // Triangle meshes (the common case) have their own loops, which read each vertex
        // once; other meshes go through `decide` and `follow`.
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            // The frame's common case, a culled object drawn in one pass, has its own loop.
            if !self.banded && self.object.cull_back_faces {
                self.triangles::<true, N>(stats, attrs, draw)?;
            } else {
                self.triangles::<false, N>(stats, attrs, draw)?;
            }
        } else {
            for (pi, poly) in self.object.mesh.polygons().enumerate() {
                stats.polygons_in += 1;
                self.polygon(pi, poly, stats, attrs, draw)?;
            }
        }
        Ok(())
    }

    /// Every triangle of a triangle mesh; `UNBANDED_CULLED` when the buffers hold every row
    /// and the object culls back faces (the flags are then not read per triangle).
    #[inline(always)]
    fn triangles<const UNBANDED_CULLED: bool, const N: usize>(
        &self,
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        // Every triangle is counted in, once (on an error, those up to the failing one); the
        // polygon index is derived from the iterator, so that the loop carries it only for
        // attributes that read it.
        let mut triangles = self.object.mesh.indices().chunks_exact(3);
        let n = triangles.len();
        while let Some(poly) = triangles.next() {
            let pi = n - 1 - triangles.len();
            let r = self.triangle::<UNBANDED_CULLED, N>(pi, poly, stats, attrs, draw);
            if r.is_err() {
                stats.polygons_in += pi as u32 + 1;
                return r;
            }
        }
        stats.polygons_in += n as u32;
        Ok(())
    }

    /// One triangle of a triangle mesh (`poly`, 3 indices) without a table, not counted in
    /// `polygons_in`: three vertices in range and projected (the common case) go straight to
    /// [`projected_triangle`](Self::projected_triangle), others through
    /// [`decide`](Self::decide).
    #[inline(always)]
    fn triangle<const UNBANDED_CULLED: bool, const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        match self.prepared_triangle(poly) {
            Some(v) if v[0].outcode | v[1].outcode | v[2].outcode == 0 => {
                self.projected_triangle::<UNBANDED_CULLED, N>(pi, poly, v, stats, attrs, draw)
            }
            _ => self.polygon(pi, poly, stats, attrs, draw),
        }
    }

    /// One polygon by [`decide`](Self::decide) and [`follow`](Self::follow), not counted in
    /// `polygons_in` (out of line: the triangle loops reach it rarely).
    #[inline(never)]
    fn polygon<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        let path = self.decide(poly, stats)?;
        self.follow(path, pi, poly, stats, attrs, draw)
    }

    /// The polygons the band table sends to this band (rejection and culling were decided
    /// once for all bands).
    #[inline(never)]
    fn run_table<const N: usize>(
        &self,
        table: &[PolygonRows],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        let path = |r: PolygonRows| match r {
            PolygonRows::CLIP => Path::Clip,
            r if r.meets(self.rows) => Path::Projected,
            _ => Path::Skip,
        };
        if let PolygonSizes::Uniform(3) = self.object.mesh.sizes() {
            let indices = self.object.mesh.indices();
            let table = table.get(..indices.len() / 3).unwrap_or(table);
            // The scan finds the entries that `path` may draw with one or two tests for most:
            // rows below the band's end (clamped so that the clipping entry and rows up to
            // 65535 pass) and above its start; `path` then decides exactly.
            let (b0, b1) = self.rows;
            let (c0, c1) = (
                b0.clamp(-1, u16::MAX as i32 - 1),
                b1.min(u16::MAX as i32 + 1),
            );
            // `bottom > c0` on the packed word: `c0 + 1` is in `0..=65535`.
            let below = ((c0 + 1) as u32) << 16;
            let maybe = |r: &PolygonRows| {
                r.packed >= below && ((r.top() as i32) < c1 || *r == PolygonRows::CLIP)
            };
            let mut one = |pi: usize, r: PolygonRows| {
                let Some(poly) = indices.get(3 * pi..3 * pi + 3) else {
                    return Ok(());
                };
                match path(r) {
                    Path::Skip => Ok(()),
                    Path::Projected => self.table_triangle(pi, poly, stats, attrs, draw),
                    Path::Clip => self.clipped(pi, poly, stats, attrs, draw),
                }
            };
            // Two entries per step: most pairs are passed over with two tests.
            let pairs = table.chunks_exact(2);
            let odd = pairs.remainder();
            for (j, pair) in pairs.enumerate() {
                if let [r0, r1] = *pair {
                    if maybe(&r0) || maybe(&r1) {
                        if maybe(&r0) {
                            one(2 * j, r0)?;
                        }
                        if maybe(&r1) {
                            one(2 * j + 1, r1)?;
                        }
                    }
                }
            }
            if let [r] = *odd {
                if maybe(&r) {
                    one(table.len() - 1, r)?;
                }
            }
        } else {
            for ((pi, poly), r) in self.object.mesh.polygons().enumerate().zip(table) {
                self.follow(path(*r), pi, poly, stats, attrs, draw)?;
            }
        }
        Ok(())
    }

    /// A triangle of a table that found it projected and in the band: drawn from its prepared
    /// vertices as [`projected`](Self::projected) does.
    #[inline(always)]
    fn table_triangle<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        match self.prepared_triangle(poly) {
            Some(v) => self.draw_projected(pi, poly, v, stats, attrs, draw),
            None => self.projected(pi, poly, stats, attrs, draw),
        }
    }

    /// A triangle whose three vertices projected (`v`, the prepared vertices of `tri`): the
    /// band's rows, culling and drawing, as [`decide`](Self::decide) and
    /// [`projected`](Self::projected) do for it.
    #[inline(always)]
    fn projected_triangle<const UNBANDED_CULLED: bool, const N: usize>(
        &self,
        pi: usize,
        tri: &[u16],
        v: [&PreparedVertex<S>; 3],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        if !UNBANDED_CULLED && self.banded && !triangle_rows(v).meets(self.rows) {
            return Ok(());
        }
        let cull = UNBANDED_CULLED || self.object.cull_back_faces;
        if cull && !front_triangle(v[0].screen, v[1].screen, v[2].screen) {
            stats.culled += 1;
            return Ok(());
        }
        self.draw_projected(pi, tri, v, stats, attrs, draw)
    }

    /// Draws a triangle from its three prepared vertices `v` (those of `tri`).
    #[inline(always)]
    fn draw_projected<const N: usize>(
        &self,
        pi: usize,
        tri: &[u16],
        v: [&PreparedVertex<S>; 3],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        let corner = |k: usize| Corner::prepared(v[k], attrs(pi, tri, k, Some(v[k])));
        draw_counted([corner(0), corner(1), corner(2)], draw, stats)
    }

    /// Draws one polygon by the path decided for it.
    #[inline(always)]
    fn follow<const N: usize>(
        &self,
        path: Path,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        match path {
            Path::Skip => Ok(()),
            Path::Projected => self.projected(pi, poly, stats, attrs, draw),
            Path::Clip => self.clipped(pi, poly, stats, attrs, draw),
        }
    }

    /// Without a table: rejection, the band's rows (before any other work for projected
    /// polygons in a band), culling. The caller counts the polygon in `polygons_in`.
    #[inline(always)]
    fn decide(&self, poly: &[u16], stats: &mut RenderStats) -> Result<Path, RenderError> {
        let any = self.outcodes(poly, stats)?;
        if any == REJECTED {
            return Ok(Path::Skip);
        }
        let vertex = |k: usize| &self.prepared[poly[k] as usize];
        if any == 0 {
            if self.banded && !self.projected_rows(poly).meets(self.rows) {
                return Ok(Path::Skip);
            }
            if self.object.cull_back_faces && screen_area(poly.len(), |k| vertex(k).screen) >= 0 {
                stats.culled += 1;
                return Ok(Path::Skip);
            }
            return Ok(Path::Projected);
        }
        if self.object.cull_back_faces && !faces_eye_observer(poly.len(), |k| vertex(k).view) {
            stats.culled += 1;
            return Ok(Path::Skip);
        }
        Ok(Path::Clip)
    }

    /// The band pre-pass of one polygon (see [`Renderer::polygon_rows`]); the same decisions
    /// as [`decide`](Self::decide). The caller counts the polygon in `polygons_in`.
    #[inline(always)]
    fn classify(&self, poly: &[u16], stats: &mut RenderStats) -> Result<PolygonRows, RenderError> {
        let any = self.outcodes(poly, stats)?;
        if any == REJECTED {
            return Ok(PolygonRows::NEVER);
        }
        let vertex = |k: usize| &self.prepared[poly[k] as usize];
        let culled = if any == 0 {
            self.object.cull_back_faces && screen_area(poly.len(), |k| vertex(k).screen) >= 0
        } else {
            self.object.cull_back_faces && !faces_eye_observer(poly.len(), |k| vertex(k).view)
        };
        if culled {
            stats.culled += 1;
            return Ok(PolygonRows::NEVER);
        }
        Ok(if any == 0 {
            self.projected_rows(poly)
        } else {
            PolygonRows::CLIP
        })
    }

    /// The band pre-pass of a triangle mesh (see [`Renderer::polygon_rows`]), into `out` (out
    /// of line, so that its loop does not depend on the caller's code).
    #[inline(never)]
    fn classify_triangles(
        &self,
        out: &mut [PolygonRows],
        stats: &mut RenderStats,
    ) -> Result<(), RenderError> {
        if self.object.cull_back_faces {
            self.classify_each::<true>(out, stats)
        } else {
            self.classify_each::<false>(out, stats)
        }
    }

    /// [`classify_triangles`](Self::classify_triangles) with the object's culling flag
    /// `CULL`; every triangle is counted in once (on an error, those up to the failing one).
    #[inline(always)]
    fn classify_each<const CULL: bool>(
        &self,
        out: &mut [PolygonRows],
        stats: &mut RenderStats,
    ) -> Result<(), RenderError> {
        let triangles = self.object.mesh.indices().chunks_exact(3);
        let n = out.len().min(triangles.len());
        for (pi, (o, poly)) in out.iter_mut().zip(triangles).enumerate() {
            match self.classify_triangle::<CULL>(poly, stats) {
                Ok(r) => *o = r,
                Err(e) => {
                    stats.polygons_in += pi as u32 + 1;
                    return Err(e);
                }
            }
        }
        stats.polygons_in += n as u32;
        Ok(())
    }

    /// [`classify`](Self::classify) for a triangle (`poly`, 3 indices) of an object whose
    /// culling flag is `CULL`, not counted in `polygons_in`: three vertices in range and
    /// projected (the common case) are classified from one read of each.
    #[inline(always)]
    fn classify_triangle<const CULL: bool>(
        &self,
        poly: &[u16],
        stats: &mut RenderStats,
    ) -> Result<PolygonRows, RenderError> {
        match self.prepared_triangle(poly) {
            Some(v) if v[0].outcode | v[1].outcode | v[2].outcode == 0 => {
                if CULL && !front_triangle(v[0].screen, v[1].screen, v[2].screen) {
                    stats.culled += 1;
                    return Ok(PolygonRows::NEVER);
                }
                Ok(triangle_rows(v))
            }
            _ => self.classify(poly, stats),
        }
    }

    /// The union of the polygon's vertex outcodes, or [`REJECTED`] (counted) when all are
    /// outside one plane.
    #[inline(always)]
    fn outcodes(&self, poly: &[u16], stats: &mut RenderStats) -> Result<u8, RenderError> {
        if poly.len() > MAX_POLYGON_VERTICES {
            return Err(RenderError::PolygonTooLarge);
        }
        let (mut any, mut all) = (0u8, 0xFFu8);
        for &i in poly {
            let c = self
                .prepared
                .get(i as usize)
                .map_or(UNPROJECTED, |p| p.outcode);
            any |= c;
            all &= c;
        }
        if all & !UNPROJECTED != 0 {
            stats.rejected += 1;
            return Ok(REJECTED);
        }
        Ok(any)
    }

    /// The prepared vertices of `poly` when it is a triangle whose indices are all in range.
    #[inline(always)]
    fn prepared_triangle(&self, poly: &[u16]) -> Option<[&PreparedVertex<S>; 3]> {
        let p = self.prepared;
        match *poly {
            [i0, i1, i2] => Some([
                p.get(i0 as usize)?,
                p.get(i1 as usize)?,
                p.get(i2 as usize)?,
            ]),
            _ => None,
        }
    }

    /// The rows of a polygon whose vertices all projected: `⌈y_min⌉ .. ⌈y_max⌉`.
    #[inline(always)]
    fn projected_rows(&self, poly: &[u16]) -> PolygonRows {
        let (mut y_lo, mut y_hi) = (i32::MAX, i32::MIN);
        for &i in poly {
            let y = self.prepared[i as usize].screen.y;
            (y_lo, y_hi) = (y_lo.min(y), y_hi.max(y));
        }
        PolygonRows::rows(ceil_shift(y_lo, S), ceil_shift(y_hi, S))
    }

    /// Draws a polygon whose vertices all projected, as a fan.
    #[inline(always)]
    fn projected<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        let corner = |k: usize| {
            let p = &self.prepared[poly[k] as usize];
            Corner::prepared(p, attrs(pi, poly, k, Some(p)))
        };
        fan(poly.len(), corner, draw, stats)
    }

    /// Clips a polygon crossing the frustum (Sutherland–Hodgman), projects and draws it.
    fn clipped<const N: usize>(
        &self,
        pi: usize,
        poly: &[u16],
        stats: &mut RenderStats,
        attrs: &impl Fn(usize, &[u16], usize, Option<&PreparedVertex<S>>) -> [i32; N],
        draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    ) -> Result<(), RenderError> {
        stats.clipped += 1;
        let mut input: Vec<ClipVertex<N>, CLIP_CAPACITY> = Vec::new();
        for (k, &i) in poly.iter().enumerate() {
            let p = self.prepared.get(i as usize);
            let view = p.map_or(Vec3::ZERO, |p| p.view);
            // Capacity holds: poly.len() ≤ MAX_POLYGON_VERTICES < CLIP_CAPACITY.
            let _ = input.push(ClipVertex::new(view, attrs(pi, poly, k, p)));
        }
        let clipped = self
            .renderer
            .frustum
            .clip::<N, CLIP_CAPACITY>(&input)
            .map_err(RenderError::Clip)?;
        let mut corners: Vec<Corner<S, N>, CLIP_CAPACITY> = Vec::new();
        for c in clipped.iter() {
            let (screen, depth) = self
                .renderer
                .projector
                .project_point(c.pos)
                .map_err(RenderError::Projection)?;
            let _ = corners.push(Corner {
                screen,
                depth,
                view: c.pos,
                attrs: c.attrs,
            });
        }
        fan(corners.len(), |k| corners[k], draw, stats)
    }
}

/// Draws polygon corners `0..n` as a fan of triangles from corner 0 (exact for convex
/// polygons, whose fan triangles tile them under the fill rule), counting into `stats`.
#[inline(always)]
fn fan<const S: u32, const N: usize>(
    n: usize,
    corner: impl Fn(usize) -> Corner<S, N>,
    draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    stats: &mut RenderStats,
) -> Result<(), RenderError> {
    // The clipper returns no vertices for a polygon that only touches the volume.
    if n < 3 {
        return Ok(());
    }
    let c0 = corner(0);
    for k in 1..n - 1 {
        draw_counted([c0, corner(k), corner(k + 1)], draw, stats)?;
    }
    Ok(())
}

/// Draws one triangle, counting it into `stats` when it covered or wrote pixels.
#[inline(always)]
fn draw_counted<const S: u32, const N: usize>(
    tri: [Corner<S, N>; 3],
    draw: &mut impl FnMut([Corner<S, N>; 3]) -> Result<(u32, u32), DrawError>,
    stats: &mut RenderStats,
) -> Result<(), RenderError> {
    let (covered, written) = draw(tri).map_err(RenderError::Draw)?;
    if covered > 0 || written > 0 {
        stats.triangles_drawn += 1;
    }
    stats.pixels_covered += covered;
    stats.pixels_written += written;
    Ok(())
}

/// Twice the signed area of a projected polygon (fan sum). Projected coordinates are within
/// `±MAX_COORD = ±(2^28 − 1)` (the projector rejects others), so coordinate differences fit
/// `i32` (`< 2^29`) and each product `i32 × i32` is exact in `i64` (one `smull` on a
/// Cortex-M), each triangle's term below `2^59`. The sum wraps modulo `2^64`, so it is exact
/// whenever the true value fits `i64`: always for simple polygons, whose twice-area is at most
/// twice their bounding box's, `2·(2^29)² = 2^59`. Front faces (counter-clockwise seen from outside, with `y` up) are clockwise on a
/// `y`-down screen: negative area.
#[inline(always)]
fn screen_area<const S: u32>(n: usize, p: impl Fn(usize) -> SubpixelPoint<S>) -> i64 {
    let o = p(0);
    let mut sum = 0i64;
    for k in 1..n - 1 {
        let (b, c) = (p(k), p(k + 1));
        let (bx, by) = (b.x.wrapping_sub(o.x), b.y.wrapping_sub(o.y));
        let (cx, cy) = (c.x.wrapping_sub(o.x), c.y.wrapping_sub(o.y));
        sum = sum.wrapping_add(bx as i64 * cy as i64 - by as i64 * cx as i64);
    }
    sum
}

/// The rows of a triangle whose vertices all projected: `⌈y_min⌉ .. ⌈y_max⌉`, as
/// [`PolygonStage::projected_rows`] gives for any polygon.
#[inline(always)]
fn triangle_rows<const S: u32>(v: [&PreparedVertex<S>; 3]) -> PolygonRows {
    let (y0, y1, y2) = (v[0].screen.y, v[1].screen.y, v[2].screen.y);
    let (lo, hi) = (y0.min(y1).min(y2), y0.max(y1).max(y2));
    PolygonRows::rows(ceil_shift(lo, S), ceil_shift(hi, S))
}

/// True when a projected triangle is a front face, [`screen_area`]`(3, …) < 0`, computed as
/// `bx·cy + by·(−cx)` (one multiply and one multiply-accumulate). Projected coordinates are
/// within `±MAX_COORD`, so the differences and their negations are below `2^29` in magnitude
/// and each product below `2^58`: the sum is exact in `i64`, equal to `screen_area`'s.
#[inline(always)]
fn front_triangle<const S: u32>(
    a: SubpixelPoint<S>,
    b: SubpixelPoint<S>,
    c: SubpixelPoint<S>,
) -> bool {
    let (bx, by) = (b.x.wrapping_sub(a.x), b.y.wrapping_sub(a.y));
    let (cx, cy) = (c.x.wrapping_sub(a.x), c.y.wrapping_sub(a.y));
    mul_wide(bx, cy).wrapping_add(mul_wide(by, cx.wrapping_neg())) < 0
}

/// Back-face test in the observer frame (eye at the origin): the face is front-facing when
/// `(0 − P0)·N > 0` with `N` the outward normal. The observer frame is left-handed (x right,
/// y up, z forward), so the winding cross product there is `−N`: front ⇔ `P0·Σ cross > 0`.
fn faces_eye_observer(n: usize, p: impl Fn(usize) -> Vec3) -> bool {
    let w = |v: Vec3| v.bits().map(|c| c as i128);
    let o = w(p(0));
    let mut nrm = [0i128; 3];
    for k in 1..n - 1 {
        let (a, b) = (w(p(k)), w(p(k + 1)));
        let e1 = [a[0] - o[0], a[1] - o[1], a[2] - o[2]];
        let e2 = [b[0] - o[0], b[1] - o[1], b[2] - o[2]];
        nrm[0] += e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] += e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] += e1[0] * e2[1] - e1[1] * e2[0];
    }
    // |o| < 2^31, |nrm| < 2^66·n: the dot stays below 2^102.
    o[0] * nrm[0] + o[1] * nrm[1] + o[2] * nrm[2] > 0
}

/// Clears `frame` to the scene's background and `depth` to far, then draws every object,
/// adding the frame's counts to `stats`: a [`RenderStats`] counts everything, a
/// [`StatsWithoutWritten`] everything but the written pixels, whose per-pixel add the span
/// loops then leave out (the faster choice when the count is not read; see its doc).
/// `scratch` must hold at least as many vertices as the largest mesh.
pub fn render_scene<D: DepthValue, const S: u32>(
    renderer: &Renderer<S>,
    scene: &Scene<'_>,
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    scratch: &mut [PreparedVertex<S>],
    stats: &mut impl StatsSink,
) -> Result<(), RenderError> {
    frame.clear(scene.background);
    depth.clear();
    for object in scene.objects {
        renderer.draw_object(object, scratch, frame, depth, stats)?;
    }
    Ok(())
}

/// Caller memory of [`render_in_bands`]; each part is a documented memory/time switch.
#[derive(Debug)]
pub struct BandScratch<'a, const S: u32> {
    /// Prepared vertices (28 bytes each). Holding the vertices of **all** objects together,
    /// the vertex stage runs once per frame; holding only the largest object's, it runs again
    /// for every band.
    pub vertices: &'a mut [PreparedVertex<S>],
    /// Polygon table (4 bytes per polygon), used when `vertices` holds all objects and this
    /// holds all objects' polygons: rejection, culling and each polygon's rows are decided
    /// once per frame ([`Renderer::polygon_rows`]) and a band visits only the polygons that
    /// reach it. Otherwise (e.g. `&mut []`) every band tests every polygon.
    pub polygons: &'a mut [PolygonRows],
}

/// Draws a `width × height` picture band by band through one band-sized pair of buffers:
/// for each band of `band_rows` rows (the last may be shorter) it clears and draws the band,
/// then calls `band_done` with the finished band — flush it to the display there (e.g.
/// [`flush`](crate::target::flush)). The picture is the same as one pass (the raster stage
/// writes exactly the rows a buffer holds), whatever the scratch ([`BandScratch`]).
///
/// The band's buffers `(pixels, depths)` need `width × band_rows` elements each. Statistics
/// are added to `stats` (a [`StatsSink`], as for [`render_scene`]) summed over bands: pixel
/// counts add up to the picture's and `clipped` counts each band's clipper runs. With
/// the polygon table, `polygons_in`, `rejected` and `culled` are counted once per frame;
/// without it, once per band pass (`culled` then counts, per band, the back faces that reach
/// the band's rows: a band skips projected polygons above or below it first).
pub fn render_in_bands<D: DepthValue, const S: u32>(
    renderer: &Renderer<S>,
    scene: &Scene<'_>,
    (pixels, depths): (&mut [u8], &mut [D]),
    (width, height, band_rows): (u16, u16, u16),
    scratch: BandScratch<'_, S>,
    stats: &mut impl StatsSink,
    mut band_done: impl FnMut(&Framebuffer<'_>, &DepthBuffer<'_, D>),
) -> Result<(), RenderError> {
    let BandScratch { vertices, polygons } = scratch;
    let band_rows = band_rows.clamp(1, height.max(1));
    let total: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let total_polygons: usize = scene.objects.iter().map(|o| o.mesh.polygon_count()).sum();
    let prepare_once = vertices.len() >= total;
    let table = prepare_once && polygons.len() >= total_polygons;
    if prepare_once {
        let (mut at, mut pat) = (0, 0);
        for object in scene.objects {
            let (n, np) = (object.mesh.vertices().len(), object.mesh.polygon_count());
            renderer.prepare(object, &mut vertices[at..at + n])?;
            if table {
                let out = &mut polygons[pat..pat + np];
                renderer.polygon_rows(object, &vertices[at..at + n], out, stats)?;
            }
            (at, pat) = (at + n, pat + np);
        }
    }
    let mut top = 0u16;
    while top < height {
        let rows = band_rows.min(height - top);
        let n = width as usize * rows as usize;
        let too_small = RenderError::BufferTooSmall;
        let mut frame = Framebuffer::band(pixels.get_mut(..n).ok_or(too_small)?, width, rows, top)
            .map_err(|_| too_small)?;
        let mut depth = DepthBuffer::band(depths.get_mut(..n).ok_or(too_small)?, width, rows, top)
            .map_err(|_| too_small)?;
        if prepare_once {
            frame.clear(scene.background);
            depth.clear();
            let (mut at, mut pat) = (0, 0);
            for object in scene.objects {
                let (n, np) = (object.mesh.vertices().len(), object.mesh.polygon_count());
                let prepared = &vertices[at..at + n];
                let (f, z, st) = (&mut frame, &mut depth, &mut *stats);
                if table {
                    let t = &polygons[pat..pat + np];
                    renderer.rasterize_rows(object, prepared, t, f, z, st)?;
                } else {
                    renderer.rasterize(object, prepared, f, z, st)?;
                }
                (at, pat) = (at + n, pat + np);
            }
        } else {
            render_scene(renderer, scene, &mut frame, &mut depth, vertices, stats)?;
        }
        band_done(&frame, &depth);
        top += rows;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lit level lives in the padding: a prepared vertex stays 28 bytes (7 words), as its
    /// doc says.
    #[test]
    fn prepared_vertex_is_seven_words() {
        assert_eq!(core::mem::size_of::<PreparedVertex<4>>(), 28);
    }

    /// The vertex loop without saturation and with the 32-bit outcode gives the same prepared
    /// vertices as the general one, for objects whose bound lets `prepare` choose it.
    #[test]
    fn narrow_vertex_loop_equals_general_loop() {
        use crate::geometry::camera::{FovAxis, Lens, Viewport};
        use crate::geometry::fixed::Coord;
        use crate::geometry::mesh::{Mesh, MAX_MESH_COORD_BITS};
        use crate::geometry::trig::Angle;
        let c = |x: f64| Coord::from_num(x);
        let lens = Lens {
            fov: Angle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: c(0.5),
            far: c(10.0),
        };
        let cam = Camera::new(
            Vec3::new(c(0.3), c(1.0), c(-4.0)),
            Vec3::new(c(0.0), c(-0.2), c(1.0)),
            Vec3::new(c(0.0), c(1.0), c(0.0)),
            lens,
            Viewport::new(320, 240),
        )
        .unwrap();
        let r = Renderer::<4>::new(&cam).unwrap();
        let mut rng = crate::test_rng::XorShift(0xC0FF_EE12_3456_789Bu64);
        let mut rnd = || rng.next_u64();
        let (mut narrow_runs, mut codes) = (0, [0u32; 2]);
        for n in 0..60 {
            let span = [1u64 << 10, 1 << 17, 1 << 22, MAX_MESH_COORD_BITS as u64][n % 4];
            let mut coord = || ((rnd() % (2 * span + 1)) as i64 - span as i64) as i32;
            let mut vs = [Vec3::ZERO; 64];
            for v in vs.iter_mut() {
                *v = Vec3::from_bits(coord(), coord(), coord());
            }
            vs[0] = Vec3::from_bits(span as i32, -(span as i32), span as i32);
            let levels: [u8; 40] = core::array::from_fn(|i| (i * 7) as u8);
            let mesh = Mesh::triangles(&vs, &[]).unwrap();
            let mut obj = Object::new(mesh);
            obj.intensities = Intensities::PerVertex(&levels);
            let s = [0.01, 0.3, 1.0, 4.0, 60.0][n % 5];
            let rot = Affine3::rotation_axis(
                Vec3::new(c(1.0), c(2.0), c(-0.5)),
                Angle::from_degrees(n as i32 * 37),
            )
            .unwrap();
            let t = Affine3::translation(Vec3::new(c(0.5), c(-0.25), c((n % 7) as f64)));
            obj.transform = Affine3::scale(c(s))
                .unwrap()
                .then(&rot)
                .unwrap()
                .then(&t)
                .unwrap();
            let m = r.model_view(&obj).unwrap();
            let narrow = r.frustum.narrow_fits(m.point_bounds(mesh.max_coord_bits()));
            narrow_runs += narrow as u32;
            let mut a = [PreparedVertex::<4>::default(); 64];
            let mut b = [PreparedVertex::<4>::default(); 64];
            r.prepare(&obj, &mut a).unwrap();
            let level = |i: usize, _: Vec3| levels.get(i).copied().unwrap_or(0);
            r.prepare_loop::<false>(&m, &vs, &mut b, &level);
            assert_eq!(a, b, "n={n} narrow={narrow}");
            if narrow {
                r.prepare_loop::<true>(&m, &vs, &mut a, &level);
                assert_eq!(a, b, "n={n}");
                for v in &a {
                    codes[(v.outcode != 0) as usize] += 1;
                }
            }
        }
        // Both paths ran, and the narrow one saw projected and outside vertices.
        assert!((10..60).contains(&narrow_runs), "{narrow_runs}");
        assert!(codes[0] > 50 && codes[1] > 50, "{codes:?}");
    }
}
