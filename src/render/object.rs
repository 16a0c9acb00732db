//! One object's polygon pass: which attributes its corners carry (a level given, lit per
//! vertex or per polygon, or a normal for Phong) and which consumer draws its triangles.
//!
//! Role in the pipeline: between the vertex stage and the polygon stage (`polygon_stage.rs`),
//! for every frame that draws an object's triangles: one pass, bands, the visibility methods
//! that collect triangles and compact bands (`compact.rs`), which hand their own vertex source
//! and band table to the same [`Renderer::run_levels`]. Numeric contract: levels are
//! `0..=255` (`i32` attributes), texture coordinates and normals as `consumer.rs` states.

use core::cell::Cell;

use super::consumer::{LevelWriter, PhongWriter, TextureWriter, TriangleConsumer};
use super::polygon_stage::{BandTable, PolygonStage, VertexSource};
use super::transparency;
use super::{
    IntensityTable, PolygonRows, PreparedVertex, RenderError, RenderStats, Renderer, StatsSink,
};
use crate::geometry::vector::Vec3;
use crate::lighting::light_polygon;
use crate::output::{DepthBuffer, DepthValue, Framebuffer, PaintedMask};
use crate::raster::triangle::PhongContext;
use crate::raster::triangle::{RasterTarget, ShadeMode, SpanTarget};
use crate::scene::{Intensities, Object};

impl<const S: u32> Renderer<S> {
    /// The polygon stage and raster for `object`, whose vertices `prepare` put in `scratch`.
    ///
    /// Lit objects ([`Intensities::Lit`]) get their levels here: flat ones per polygon
    /// (`light_polygon`), Gouraud ones from the vertex stage; Phong ones carry their
    /// observer-frame normals through clipping as three attributes and are lit per pixel
    /// ([`draw_triangle_phong`](crate::raster::triangle::draw_triangle_phong)).
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
            return Err(RenderError::PolygonTableTooSmall {
                given: rows.len(),
                needed: object.mesh.polygon_count(),
            });
        }
        self.rasterize_with(object, scratch, Some(rows), frame, depth, stats)
    }

    /// The polygon stage of `object` with its corner attributes and its consumer: Phong
    /// objects carry their normals to a [`PhongWriter`], every other object a level to a
    /// [`LevelWriter`] ([`Self::run_levels`]).
    fn rasterize_with<D: DepthValue, T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        table: Option<&[PolygonRows]>,
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        self.check_targets(frame, depth)?;
        let rows = (frame.top().max(depth.top()), {
            let f = frame.top() + frame.height() as i32;
            f.min(depth.top() + depth.height() as i32)
        });
        // The buffers prepared once for the object.
        let target = RasterTarget::with_count(frame, depth, T::Count::default());
        self.rasterize_on(object, scratch, table, rows, target, stats)
    }

    /// [`rasterize`](Self::rasterize) through the reverse painter's mask instead of a depth
    /// buffer (`visibility/reverse.rs`): a pixel is written by the first triangle that reaches
    /// it, and never again. `mask` holds `frame`'s rows (`PaintedMask::for_frame`).
    pub(crate) fn rasterize_masked<T: StatsSink>(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        frame: &mut Framebuffer<'_>,
        mask: &mut PaintedMask<'_>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        self.check_frame(frame)?;
        let rows = (frame.top().max(mask.top()), {
            let f = frame.top() + frame.height() as i32;
            f.min(mask.top() + mask.height() as i32)
        });
        let target = RasterTarget::masked(frame, mask, T::Count::default());
        self.rasterize_on(object, scratch, None, rows, target, stats)
    }

    /// The polygon stage of `object` over `rows`, its triangles drawn into `target` (a depth
    /// buffer's or a mask's).
    fn rasterize_on<D: DepthValue, T: StatsSink, G: SpanTarget<Depth = D>>(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        table: Option<&[PolygonRows]>,
        rows: (i32, i32),
        mut target: RasterTarget<'_, D, T::Count, G>,
        stats: &mut T,
    ) -> Result<(), RenderError> {
        let stats = stats.counts();
        let prepared = checked_scratch(object, scratch)?;
        let stage = self.stage(object, prepared, rows, table);
        if let Some(texturing) = object.texture {
            // Textured triangles: the level and the corner's texture coordinates, read from
            // the table parallel to the indices (a corner's position in it is the polygon's
            // slice offset plus its rank, as the triangle loops find it).
            let uvs = textured_uvs(object)?;
            let indices = object.mesh.indices().as_ptr() as usize;
            let uv = |poly: &[u16], k: usize| {
                let at = (poly.as_ptr() as usize - indices) / core::mem::size_of::<u16>() + k;
                uvs.get(at).copied().unwrap_or([0, 0]).map(i32::from)
            };
            let writer = TextureWriter {
                target: &mut target,
                texturing,
                origin: self.projector.weight_origin(),
            };
            return self.run_levels(&stage, stats, writer, |l, poly, k| {
                let [u, v] = uv(poly, k);
                [l, u, v]
            });
        }
        if let (Intensities::Lit { material, normals }, ShadeMode::Phong) =
            (object.intensities, object.shade)
        {
            if let Some(kind) = transparency::kind(object) {
                return Err(RenderError::TransparencyRefused {
                    object: None,
                    kind,
                    method: "Phong shading",
                });
            }
            let model_view = self.model_view(object)?;
            let context = PhongContext {
                illumination: &self.illumination,
                material,
                ramp: object.ramp,
                dither: object.dither,
            };
            let normal = |i: u16| {
                let n = normals.get(i as usize).copied().unwrap_or(Vec3::ZERO);
                model_view.transform_vector(n).bits()
            };
            let writer = PhongWriter {
                target: &mut target,
                context,
            };
            return stage.run(stats, |_, poly, k, _| normal(poly[k]), writer);
        }
        if let (Some(kind), false) = (transparency::kind(object), cfg!(feature = "transparency")) {
            return Err(RenderError::TransparencyRefused {
                object: None,
                kind,
                method: transparency::WITHOUT_FEATURE,
            });
        }
        // Luminance triangles.
        let writer = LevelWriter {
            target: &mut target,
            object,
        };
        self.run_levels(&stage, stats, writer, |l, _, _| [l])
    }

    /// The polygon stage of `object` handing every triangle, with a level per corner, to
    /// `consumer` (the visibility methods that store triangles before drawing them). Phong
    /// objects carry normals, not levels: [`RenderError::PhongUnsupported`].
    pub(crate) fn collect_levels(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        stats: &mut RenderStats,
        consumer: impl TriangleConsumer<S, 1>,
    ) -> Result<(), RenderError> {
        if object.shade == ShadeMode::Phong && matches!(object.intensities, Intensities::Lit { .. })
        {
            return Err(RenderError::PhongUnsupported);
        }
        let prepared = checked_scratch(object, scratch)?;
        let rows = (0, self.camera.viewport().height as i32);
        let stage = self.stage(object, prepared, rows, None);
        self.run_levels(&stage, stats, consumer, |l, _, _| [l])
    }

    /// The polygon stage of `object` over the rows `rows.0 .. rows.1` (with its band table,
    /// if any).
    pub(super) fn stage<'r, 'o>(
        &'r self,
        object: &'r Object<'o>,
        prepared: &'r [PreparedVertex<S>],
        rows: (i32, i32),
        table: Option<&'r [PolygonRows]>,
    ) -> PolygonStage<'r, 'o, S> {
        PolygonStage {
            renderer: self,
            object,
            prepared,
            rows,
            banded: rows.0 > 0 || rows.1 < self.camera.viewport().height as i32,
            table,
        }
    }

    /// Runs `stage` with a level per corner: lit per polygon for flat lit objects, read from
    /// the prepared vertex for Gouraud-lit or given per-vertex levels, else given per polygon
    /// or uniform; `with(level, polygon, corner k)` makes the corner's attributes of it (the
    /// level alone, or with the texture coordinates).
    pub(super) fn run_levels<V, T, const N: usize>(
        &self,
        stage: &PolygonStage<'_, '_, S, V, T>,
        stats: &mut RenderStats,
        consumer: impl TriangleConsumer<S, N>,
        with: impl Fn(i32, &[u16], usize) -> [i32; N],
    ) -> Result<(), RenderError>
    where
        V: ?Sized + VertexSource<S>,
        T: ?Sized + BandTable,
    {
        let object = stage.object;
        let mesh = &object.mesh;
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
                stage.run(
                    stats,
                    |pi, poly, k, _| with(level(pi, poly) as i32, poly, k),
                    consumer,
                )
            }
            Intensities::Lit { .. } | Intensities::PerVertex(_) => {
                // Gouraud-lit or given per vertex: the level the vertex stage stored beside the
                // vertex (in the prepared vertex, read with it; in compact bands' level bytes).
                let source = stage.prepared;
                let level = |i: u16, p: Option<&V::Vertex>| p.map_or(0, |p| source.level(i, p));
                stage.run(
                    stats,
                    |_, poly, k, p| with(level(poly[k], p) as i32, poly, k),
                    consumer,
                )
            }
            _ => stage.run(
                stats,
                |pi, poly, k, _| with(object.intensity(pi, poly[k]) as i32, poly, k),
                consumer,
            ),
        }
    }
}

/// The texture coordinates of a textured `object`: one per index, and not Phong-lit (its
/// corners carry a level and the coordinates, no normals), transparent or dithered (the
/// textured writer stores its texels as they are: refused rather than drawn opaque).
fn textured_uvs<'a>(
    object: &Object<'a>,
) -> Result<&'a [crate::geometry::mesh::TexCoord], RenderError> {
    if !cfg!(feature = "textures") {
        // Known at compile time: without the feature, the textured writer below is never
        // reached and is left out of the firmware (about 100 KB of i128 planes on a
        // Cortex-M0+).
        return Err(RenderError::TextureNotDrawable {
            reason: "zscan was built without its `textures` feature (on by default)",
        });
    }
    let uvs = object.mesh.uvs();
    if uvs.len() != object.mesh.indices().len() {
        return Err(RenderError::TextureNotDrawable {
            reason: "its mesh has no texture coordinates (Mesh::with_uvs)",
        });
    }
    if transparency::kind(object).is_some() {
        return Err(RenderError::TextureNotDrawable {
            reason: "a texture does not combine with transparency (its texels are written as \
                     they are)",
        });
    }
    if object.dither {
        return Err(RenderError::TextureNotDrawable {
            reason: "a texture does not combine with dithering (its texels are written as they \
                     are)",
        });
    }
    if object.shade == ShadeMode::Phong && matches!(object.intensities, Intensities::Lit { .. }) {
        return Err(RenderError::TextureNotDrawable {
            reason: "Phong shading does not combine with a texture (light it per vertex or \
                     per face)",
        });
    }
    Ok(uvs)
}

/// The prepared vertices of `object` in `scratch`, once its tables are checked long enough.
pub(super) fn checked_scratch<'s, const S: u32>(
    object: &Object<'_>,
    scratch: &'s [PreparedVertex<S>],
) -> Result<&'s [PreparedVertex<S>], RenderError> {
    let mesh = &object.mesh;
    let prepared = scratch
        .get(..mesh.vertices().len())
        .ok_or(RenderError::ScratchTooSmall {
            given: scratch.len(),
            needed: mesh.vertices().len(),
        })?;
    let short = |table, given, needed| {
        Err(RenderError::IntensitiesTooShort {
            table,
            given,
            needed,
        })
    };
    match object.intensities {
        Intensities::PerVertex(t) if t.len() < prepared.len() => {
            short(IntensityTable::PerVertex, t.len(), prepared.len())
        }
        Intensities::PerPolygon(t) if t.len() < mesh.polygon_count() => {
            short(IntensityTable::PerPolygon, t.len(), mesh.polygon_count())
        }
        Intensities::Lit { normals, .. }
            if object.shade != ShadeMode::Flat && normals.len() < prepared.len() =>
        {
            short(IntensityTable::Normals, normals.len(), prepared.len())
        }
        _ => Ok(prepared),
    }
}
