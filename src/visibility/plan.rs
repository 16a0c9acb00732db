//! The scene planner: "model no more than a scene needs". From a scene, what is known of its
//! meshes ([`MeshFacts`], computed once) and a memory budget in bytes, a [`Plan`]: the
//! hidden-surface method, the depth width, the band height, the size of every caller buffer,
//! and the reason for each choice. No heap: the drawing order goes to a caller slice.
//!
//! ## What is cheap to know, per frame
//! - Each mesh's convexity hint and edge table ([`Convexity`], stored with the mesh), and for a
//!   candidate mesh whether its drawn faces cover each pixel at most once in this view (the
//!   per-view check of `facts.rs`: `O(corners)` exact tests on the screen positions the vertex
//!   stage places; by [`plan_frame`](super::plan_frame), the vertex stage itself, run into the
//!   caller's scratch and reused by the frame).
//! - Each object's bounding box (stored with the mesh), its 8 corners taken to the observer
//!   frame by the object's own model-view transform: the vertex stage rounds every vertex to
//!   nearest, which is monotone, so every vertex the renderer places lies within the box of the
//!   rounded corners, and every clipped corner (on an edge between two vertices) too. From it:
//!   the object's depth range, `D(z)` at its nearest and farthest `z` through the renderer's
//!   projector widened by [`DEPTH_MARGIN`] units on each side (the projector's `D` is within 6
//!   units of the exact one, `project.rs`), and its screen box (the box's corners projected,
//!   widened by [`SCREEN_MARGIN`] sub-pixel units for the projection's rounding).
//! - Vertex and polygon counts, for the buffers' sizes.
//!
//! ## The rules, and why each keeps the picture
//! 1. **Back faces alone** ([`Visibility::BackFace`], no depth buffer) when every object culls
//!    its back faces, its mesh is [`Convexity::Convex`] and passes the per-view check (`facts.rs`:
//!    on the rounded screen positions this frame draws, every polygon inside the frustum and no
//!    sample covered by two of its drawn triangles), and the objects are **separable**: any two whose screen boxes overlap have depth
//!    ranges that do not (Schumacker's clusters). Objects are drawn far to near (`order`).
//!    Within an object no two drawn triangles cover one sample (`facts.rs`), so each pixel an object draws
//!    is the one surface it shows there. Two objects that both draw a pixel overlap on screen,
//!    so their depth ranges are disjoint: the nearer one's stored depth is below the farther
//!    one's (a triangle's depth at a pixel lies between its corners' depths), the z-buffer
//!    keeps it, and drawn last it stays. The frame must be whole (objects draw over each
//!    other in any rows), so this needs the budget for a whole frame.
//!
//!    **Rule 1b, the reverse painter** ([`Visibility::ReversePainter`], `reverse.rs`, course
//!    ch. 3 algorithm 3.2) instead of back faces alone, when rule 1 holds, an object lit per
//!    pixel (Phong) has its screen box overlapping that of a nearer object, and the budget
//!    holds the mask too
//!    (`⌈w·h/32⌉` words, counted in [`Buffers::tables`]). Objects are drawn near to far
//!    (`order`), each pixel painted by the first object that reaches it: the same pixels as
//!    rule 1's, by the same argument read backwards (the nearer object's pixel comes first and
//!    its bit keeps it). Where it pays: back faces alone shade every covered pixel of every
//!    object, the hidden ones included; the reverse painter tests and sets a bit per covered
//!    pixel (and clears a word per 32 pixels per frame) and shades only the pixels it keeps.
//!    Per-pixel lighting costs of the order of a thousand Cortex-M4 instructions a pixel
//!    (`lit_sphere_phong` in `docs/BENCHMARKS.md`), far above a bit's test, so any overlap of
//!    a Phong object by a nearer one pays; for flat and Gouraud objects a hidden pixel costs
//!    about what the mask costs every covered pixel (`frame_*_reverse` against
//!    `frame_*_backface`), so back faces alone stay. The sort is the same for both (rule 1's).
//! 2. Otherwise the **z-buffer**, in the first layout that fits the budget, tried in this
//!    order: the whole frame; bands of `H` rows (`H` as tall as fits) with the vertex stage
//!    run once per frame and the polygon table ([`BandScratch`](crate::render::BandScratch)
//!    holding every object's vertices and polygons); **compact bands**
//!    ([`render_in_compact_bands`](crate::render::render_in_compact_bands): 8 bytes per vertex,
//!    a level byte per vertex of lit Gouraud objects, a byte per polygon), only when every
//!    object's bounding box lies inside the frustum within the 16-bit sub-pixel range (the
//!    renderer's `NotCompact` cannot then occur: every vertex lies in its object's box) and no
//!    object is lit Phong or textured; bands with the vertex stage run again per band (scratch for the
//!    largest mesh only). Every layout gives the same pixels (`render_in_bands`).
//! 3. **Depth width**: `u32` in the first layout that fits with it; `u16` only when no `u32`
//!    layout fits. The picture is then the 16-bit z-buffer's (not always the 32-bit one's: two
//!    surfaces closer than the 16-bit step `Δz ≈ z²·(far − near)/(far·near·2^16)` may swap);
//!    the plan reports that step at the scene's farthest depth.
//! 4. No layout fits: [`PlanError::OverBudget`] with the bytes of the smallest plan.
//!
//! Rule 1's checks run cheapest first, and the reason names the first that fails: each
//! object's culling and convexity hint (in scene order), then the objects' separation, then
//! each mesh's per-view check (the costliest: in reverse drawing order, so
//! that the vertices [`plan_frame`](super::plan_frame) keeps are those of the object drawn
//! first).
//!
//! The painter and the scan-line are never picked: their tables cost more memory than bands of
//! the z-buffer and their frames more instructions (`docs/BENCHMARKS.md`, "Visibility
//! methods").
//!
//! ## Memory beside the budget
//! The budget counts the buffers a plan draws with ([`Buffers`]). The planner's own memory is
//! stated here instead, as it does not change with the plan: each mesh's facts keep 4 bytes
//! per corner (the edge table, beside the mesh, in flash when precomputed; 8 bytes per corner
//! while [`MeshFacts::of`] computes it), the order slice 2 bytes per object, and the per-view
//! check takes under 3 KB of stack ([`plan`]: a 2 KB cache of placed vertices and two
//! polygons' corners; [`plan_frame`](super::plan_frame), when its scratch holds the mesh's
//! vertex table, reads the vertices the frame then uses and needs no cache). Planning time: the facts `O(corners · log corners)`
//! once; per frame `O(objects²)` for the separation and `O(corners)` per candidate mesh.
//!
//! Numeric contract: sizes in bytes as `usize` (products saturating: a size that does not fit
//! a `usize`, as a 65,535 × 65,535 frame's depth on a 32-bit target, is over any budget);
//! observer-frame bounds are I16F16 (saturating, as the vertex stage); depths `u32`; screen
//! boxes in `i64` sub-pixel units.

use super::facts::{apart_in, apart_prepared, Convexity, MeshFacts, Refusal, View};
use super::Visibility;
use crate::clip::frustum::Frustum;
use crate::geometry::fixed::Coord;
use crate::geometry::vector::Vec3;
use crate::output::mask_words_needed;
use crate::project::{require_perspective, Projector};
use crate::raster::triangle::ShadeMode;
use crate::render::compact::{compact_refusal, CompactRefusal};
use crate::render::{CompactSizes, PolygonRows, PreparedVertex, RenderError, Renderer};
use crate::scene::{Intensities, Object, Scene, Transparency};

/// Units of the 2^32 depth range each object's depth range is widened by on each side.
pub const DEPTH_MARGIN: u32 = 16;
/// Sub-pixel units each object's screen box is widened by on each side.
pub const SCREEN_MARGIN: i64 = 8;

/// The depth buffer's sample width.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DepthWidth {
    /// No depth buffer.
    None,
    /// 16-bit samples.
    U16,
    /// 32-bit samples.
    U32,
}

impl DepthWidth {
    /// Bytes per sample.
    pub const fn bytes(self) -> usize {
        match self {
            DepthWidth::None => 0,
            DepthWidth::U16 => 2,
            DepthWidth::U32 => 4,
        }
    }
}

/// The size in bytes of every caller buffer a plan draws with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Buffers {
    /// Frame pixels (whole frame, or one band), one byte each.
    pub frame: usize,
    /// Depth samples (whole frame, or one band).
    pub depth: usize,
    /// Vertex scratch ([`PreparedVertex`], 28 bytes each; for compact bands
    /// [`CompactVertex`](crate::render::CompactVertex)es, 8 bytes each, and a level byte per
    /// vertex of the lit Gouraud objects).
    pub vertices: usize,
    /// Polygon table ([`PolygonRows`], 4 bytes each; for compact bands
    /// [`PolygonTop`](crate::render::PolygonTop)s, 1 byte each).
    pub polygons: usize,
    /// A method's own tables: the reverse painter's mask of painted pixels (a bit per pixel,
    /// [`mask_words_needed`](crate::output::mask_words_needed) words); none for the others.
    pub tables: usize,
}

impl Buffers {
    /// Their sum.
    pub fn total(&self) -> usize {
        [self.depth, self.vertices, self.polygons, self.tables]
            .iter()
            .fold(self.frame, |a, &b| a.saturating_add(b))
    }
}

/// Why the plan took its method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodReason {
    /// No object.
    Empty,
    /// Every object culled, its front faces covering each pixel at most once in this view,
    /// and the objects separable: back faces alone, far to near.
    ConvexAndSeparable,
    /// This object draws its back faces.
    BackFacesDrawn {
        /// Its index.
        object: usize,
    },
    /// This object is blended: the z-buffer draws it after the opaque ones, far to near
    /// (`render::transparency`).
    Blended {
        /// Its index.
        object: usize,
    },
    /// This object's mesh is not convex.
    NotConvex {
        /// Its index.
        object: usize,
    },
    /// Two drawn triangles of this object's mesh may cover one pixel in this view (the
    /// per-view check of `facts.rs` finds its silhouette not star-shaped).
    FrontFacesMayOverlap {
        /// Its index.
        object: usize,
    },
    /// A polygon of this object has a vertex outside the frustum: clipped, it is not checked.
    LeavesFrustum {
        /// Its index.
        object: usize,
    },
    /// These two objects overlap on screen and in depth.
    ObjectsOverlap {
        /// The one.
        a: usize,
        /// The other.
        b: usize,
    },
    /// Rule 1 holds and `object`, lit per pixel (Phong), lies behind `nearer` where their
    /// screen boxes overlap: back faces alone would light the pixels `nearer` then covers, the
    /// reverse painter lights each pixel once (rule 1b).
    HiddenPixelsLitPerPixel {
        /// The object lit per pixel, farther.
        object: usize,
        /// The nearer object whose screen box overlaps its.
        nearer: usize,
    },
    /// Back faces alone would do but need a whole frame: these bytes, over the budget.
    WholeFrameOverBudget {
        /// Bytes back faces alone need.
        needed: usize,
    },
}

/// What rules out compact bands ([`LayoutReason::CompactBands`]) for a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompactBlock {
    /// This object is lit Phong: compact vertices hold no normals.
    LitPhong {
        /// Its index.
        object: usize,
    },
    /// This object is textured: compact vertices hold no texture coordinates.
    Textured {
        /// Its index.
        object: usize,
    },
    /// This object's bounding box leaves the frustum or the 16-bit sub-pixel range.
    OutsideRange {
        /// Its index.
        object: usize,
    },
}

impl core::fmt::Display for CompactBlock {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CompactBlock::LitPhong { object } => write!(
                f,
                "object {object} is lit Phong (compact vertices hold no normals)"
            ),
            CompactBlock::Textured { object } => write!(
                f,
                "object {object} is textured (compact vertices hold no texture coordinates)"
            ),
            CompactBlock::OutsideRange { object } => write!(
                f,
                "object {object}'s bounding box leaves the frustum or the 16-bit sub-pixel range"
            ),
        }
    }
}

/// Why the plan took its depth width.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthReason {
    /// The method needs no depth buffer.
    NoDepthBuffer,
    /// A 32-bit layout fits the budget.
    U32Fits,
    /// No 32-bit layout fits; the 16-bit one resolves depths `resolution` apart at the scene's
    /// farthest point (observer-frame units).
    OnlyU16Fits {
        /// `Δz ≈ z²·(far − near)/(far·near·2^16)` at the scene's largest `z`.
        resolution: Coord,
    },
}

/// Why the plan took its layout (whole frame or bands, and the vertex scratch).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LayoutReason {
    /// The whole frame fits.
    WholeFrame,
    /// The whole frame does not fit; bands of the plan's height do, with the vertex stage run
    /// once per frame and the polygon table.
    BandsVertexStageOnce,
    /// Neither fits; compact bands of the plan's height do
    /// ([`render_in_compact_bands`](crate::render::render_in_compact_bands)): the vertex stage
    /// once per frame into 8 bytes per vertex and a byte per polygon. Planned only when every
    /// object's bounding box lies inside the frustum within the 16-bit sub-pixel range (so no
    /// vertex is [`NotCompact`](RenderError::NotCompact)) and no object is lit Phong.
    CompactBands,
    /// None of these fits; bands of the plan's height do, with the vertex stage run again per
    /// band.
    BandsVertexStagePerBand,
}

/// A plan (the module doc of `visibility/plan.rs` gives the rules).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Plan {
    /// The method.
    pub visibility: Visibility,
    /// The depth buffer's width.
    pub depth: DepthWidth,
    /// Rows per band (the frame's height for a whole frame).
    pub band_rows: u16,
    /// The vertex scratch holds every object's vertices and the polygon table every object's
    /// polygons ([`BandScratch`](crate::render::BandScratch)); else it holds the largest
    /// mesh's vertices and there is no table.
    pub vertex_stage_once: bool,
    /// Every caller buffer's size.
    pub buffers: Buffers,
    /// Why this method.
    pub method_reason: MethodReason,
    /// Why this depth width.
    pub depth_reason: DepthReason,
    /// Why this layout.
    pub layout_reason: LayoutReason,
}

impl Plan {
    /// Every caller buffer, in bytes.
    pub fn ram_bytes(&self) -> usize {
        self.buffers.total()
    }
}

/// Why no plan was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanError {
    /// The smallest plan needs `needed` bytes, over the budget.
    OverBudget {
        /// Bytes of the smallest plan.
        needed: usize,
        /// The budget.
        budget: usize,
        /// What rules out back faces alone (no depth buffer; a whole frame of pixels).
        back_faces: MethodReason,
        /// What rules out compact bands, when something does (`None`: they were tried and
        /// are among the layouts sized).
        compact: Option<CompactBlock>,
    },
    /// The order slice is shorter than the scene's objects (or a fact is missing for one).
    TooFewSlots {
        /// Objects in the scene.
        objects: usize,
    },
    /// The camera cannot be projected for.
    Camera(RenderError),
}

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PlanError::OverBudget {
                needed,
                budget,
                back_faces,
                compact,
            } => {
                write!(
                    f,
                    "the smallest plan needs {needed} bytes of caller memory, over the budget \
                     of {budget} bytes; back faces alone: {back_faces}"
                )?;
                match compact {
                    Some(block) => write!(f, "; compact bands: {block}"),
                    None => write!(f, "; compact bands were sized"),
                }
            }
            PlanError::TooFewSlots { objects } => write!(
                f,
                "the scene has {objects} objects: the order slice and the facts need one entry \
                 each"
            ),
            PlanError::Camera(e) => write!(f, "camera: {e}"),
        }
    }
}

impl core::error::Error for PlanError {}

impl core::fmt::Display for MethodReason {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            MethodReason::Empty => write!(f, "no object"),
            MethodReason::ConvexAndSeparable => write!(
                f,
                "every object is culled and its front faces cover each pixel once in this view, \
                 and objects that overlap on screen are apart in depth"
            ),
            MethodReason::BackFacesDrawn { object } => {
                write!(f, "object {object} draws its back faces")
            }
            MethodReason::Blended { object } => {
                write!(
                    f,
                    "object {object} is blended (drawn after the opaque ones, far to near)"
                )
            }
            MethodReason::NotConvex { object } => {
                write!(f, "object {object}'s mesh is not convex")
            }
            MethodReason::FrontFacesMayOverlap { object } => write!(
                f,
                "two front faces of object {object} may cover one pixel in this view"
            ),
            MethodReason::LeavesFrustum { object } => write!(
                f,
                "object {object} leaves the frustum (its clipped polygons are not checked)"
            ),
            MethodReason::ObjectsOverlap { a, b } => {
                write!(f, "objects {a} and {b} overlap on screen and in depth")
            }
            MethodReason::HiddenPixelsLitPerPixel { object, nearer } => write!(
                f,
                "as back faces alone, and object {object} is lit per pixel (Phong) behind object \
                 {nearer} where they overlap on screen: the reverse painter lights each pixel once"
            ),
            MethodReason::WholeFrameOverBudget { needed } => write!(
                f,
                "back faces alone would do but need a whole frame ({needed} bytes)"
            ),
        }
    }
}

impl core::fmt::Display for DepthReason {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            DepthReason::NoDepthBuffer => write!(f, "no depth buffer"),
            DepthReason::U32Fits => write!(f, "32-bit depth fits the budget"),
            DepthReason::OnlyU16Fits { resolution } => write!(
                f,
                "only 16-bit depth fits; it resolves {resolution} at the scene's far end \
                 (the picture is the 16-bit z-buffer's)"
            ),
        }
    }
}

impl core::fmt::Display for LayoutReason {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            LayoutReason::WholeFrame => "the whole frame fits",
            LayoutReason::BandsVertexStageOnce => {
                "bands, the vertex stage once per frame with the polygon table"
            }
            LayoutReason::CompactBands => {
                "compact bands, the vertex stage once per frame into 8 bytes per vertex and a \
                 byte per polygon"
            }
            LayoutReason::BandsVertexStagePerBand => "bands, the vertex stage again per band",
        })
    }
}

impl core::fmt::Display for Plan {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let b = &self.buffers;
        let depth = match self.depth {
            DepthWidth::None => "none",
            DepthWidth::U16 => "u16",
            DepthWidth::U32 => "u32",
        };
        writeln!(f, "method {} ({})", self.visibility, self.method_reason)?;
        writeln!(f, "depth {depth} ({})", self.depth_reason)?;
        writeln!(f, "band rows {} ({})", self.band_rows, self.layout_reason)?;
        write!(
            f,
            "bytes: frame {}, depth {}, vertices {}, polygons {}, tables {}, total {}",
            b.frame,
            b.depth,
            b.vertices,
            b.polygons,
            b.tables,
            b.total()
        )
    }
}

/// What the planner computes of one object in this view.
struct Placed {
    /// Depth range, widened by [`DEPTH_MARGIN`].
    depth: (u32, u32),
    /// Screen box `[x0, y0, x1, y1]` in sub-pixel units, widened; `None` when a corner does
    /// not project (the object may be anywhere on screen).
    screen: Option<[i64; 4]>,
    /// Largest observer-frame `z` (raw).
    far_z: i32,
}

/// The plan of `scene` at `S` sub-pixel bits within `budget` bytes, given `facts[i]` for
/// object `i`'s mesh; `order[..objects]` receives the drawing order (far to near for back
/// faces alone, near to far for the reverse painter, the scene's order otherwise). It draws
/// nothing and needs no scratch: the per-view check of a mesh places the vertices it looks at
/// itself. To draw the plan,
/// [`plan_frame`](super::plan_frame) makes the same plan and keeps the vertex stage it ran for
/// that check for the frame.
pub fn plan<const S: u32>(
    scene: &Scene<'_>,
    facts: &[MeshFacts<'_>],
    budget: usize,
    order: &mut [u16],
) -> Result<Plan, PlanError> {
    let camera = &scene.camera;
    let projector =
        Projector::<S>::new(camera).map_err(|e| PlanError::Camera(RenderError::Projection(e)))?;
    let frustum = Frustum::new::<S>(camera, Frustum::DEFAULT_GUARD)
        .map_err(|e| PlanError::Camera(RenderError::Clip(e)))?;
    let view = Placing {
        projector: &projector,
        frustum: &frustum,
    };
    plan_with(scene, facts, budget, order, &view, None)
}

/// How the planner places the scene: the renderer's projector and frustum.
pub(super) struct Placing<'p, const S: u32> {
    pub(super) projector: &'p Projector<S>,
    pub(super) frustum: &'p Frustum,
}

/// The vertex scratch [`plan_frame`](super::plan_frame) lends the planner: the per-view check
/// of a mesh runs the renderer's vertex stage there and reads the screen positions it
/// left; `holds` names the object whose vertices the scratch holds (the last one prepared).
pub(super) struct Lent<'s, const S: u32> {
    pub(super) renderer: &'s Renderer<S>,
    pub(super) vertices: &'s mut [PreparedVertex<S>],
    pub(super) holds: Option<usize>,
}

impl<const S: u32> Lent<'_, S> {
    /// Object `i`'s vertices after the vertex stage, or `None` when the scratch is shorter
    /// than its vertex table or the stage refused it (the planner then places the vertices
    /// itself, and the frame's own vertex stage reports the error).
    fn prepare(&mut self, i: usize, object: &Object<'_>) -> Option<&[PreparedVertex<S>]> {
        self.holds = None;
        self.renderer.prepare(object, self.vertices).ok()?;
        self.holds = Some(i);
        self.vertices.get(..object.mesh.vertices().len())
    }
}

/// [`plan`] with the scene placed by `view`, and the vertex scratch `lent` for the per-view
/// check of the meshes (module doc, rule 1), when [`plan_frame`](super::plan_frame) lends
/// one. The plan is the same with or without it.
pub(super) fn plan_with<const S: u32>(
    scene: &Scene<'_>,
    facts: &[MeshFacts<'_>],
    budget: usize,
    order: &mut [u16],
    view: &Placing<'_, S>,
    lent: Option<&mut Lent<'_, S>>,
) -> Result<Plan, PlanError> {
    // The rounding guard bounds the projection's error through the focal length and `z`.
    require_perspective(&scene.camera, "the planner")
        .map_err(|e| PlanError::Camera(RenderError::Projection(e)))?;
    let n = scene.objects.len();
    if order.len() < n || facts.len() < n || n > u16::MAX as usize + 1 {
        return Err(PlanError::TooFewSlots { objects: n });
    }
    let camera = &scene.camera;
    for (i, o) in order[..n].iter_mut().enumerate() {
        *o = i as u16;
    }
    let vp = camera.viewport();
    let (w, h) = (vp.width as usize, vp.height as usize);
    let vertex_bytes = core::mem::size_of::<PreparedVertex<S>>();
    let meshes = scene.objects.iter().map(|o| o.mesh);
    let largest = meshes
        .clone()
        .map(|m| m.vertices().len())
        .max()
        .unwrap_or(0);
    let all = meshes.clone().map(|m| m.vertices().len()).sum::<usize>();
    let polygons = meshes.map(|m| m.polygon_count()).sum::<usize>();
    let reason = match n {
        0 => Ok(MethodReason::Empty),
        _ => back_faces_allowed(scene, facts, view, &mut order[..n], lent),
    };
    let method_reason = match reason {
        Ok(r) => {
            let buffers = Buffers {
                frame: w.saturating_mul(h),
                vertices: largest.saturating_mul(vertex_bytes),
                ..Buffers::default()
            };
            if buffers.total() <= budget {
                let reverse = Buffers {
                    tables: mask_words_needed(vp.width, vp.height).saturating_mul(4),
                    ..buffers
                };
                let hidden = hidden_lit_per_pixel(scene, facts, view.projector, &order[..n]);
                if let (Some(reason), true) = (hidden, reverse.total() <= budget) {
                    order[..n].reverse(); // near to far
                    return Ok(Plan {
                        visibility: Visibility::ReversePainter,
                        depth: DepthWidth::None,
                        band_rows: h as u16,
                        vertex_stage_once: false,
                        buffers: reverse,
                        method_reason: reason,
                        depth_reason: DepthReason::NoDepthBuffer,
                        layout_reason: LayoutReason::WholeFrame,
                    });
                }
                return Ok(Plan {
                    visibility: Visibility::BackFace,
                    depth: DepthWidth::None,
                    band_rows: h as u16,
                    vertex_stage_once: false,
                    buffers,
                    method_reason: r,
                    depth_reason: DepthReason::NoDepthBuffer,
                    layout_reason: LayoutReason::WholeFrame,
                });
            }
            MethodReason::WholeFrameOverBudget {
                needed: buffers.total(),
            }
        }
        Err(r) => r,
    };
    for (o, i) in order[..n].iter_mut().zip(0..) {
        *o = i; // the z-buffer draws in scene order
    }
    // Compact bands' sizes, when the scene can be drawn so (known only for the z-buffer).
    let compact_block = compact_fits(scene, facts, view).err();
    let compact = compact_block.is_none().then(|| {
        let sizes = CompactSizes::of(scene);
        let vertices = sizes.bytes(0, 0, 0).saturating_sub(sizes.polygons);
        (vertices, sizes.polygons)
    });
    let counts = Counts {
        w,
        h,
        largest: largest.saturating_mul(vertex_bytes),
        all: all.saturating_mul(vertex_bytes),
        table: polygons.saturating_mul(core::mem::size_of::<PolygonRows>()),
        compact,
    };
    let far_z = || {
        let placed = scene.objects.iter().zip(facts);
        let far = placed.filter_map(|(o, f)| place(o, f, scene, view.projector).map(|p| p.far_z));
        far.max().unwrap_or(0)
    };
    zbuffer_plan(&counts, camera, far_z, method_reason, budget).map_err(|needed| {
        PlanError::OverBudget {
            needed,
            budget,
            back_faces: method_reason,
            compact: compact_block,
        }
    })
}

/// The z-buffer's plan (rules 2 to 4 of the module doc): the first layout that fits `budget`,
/// `u32` layouts first; else (`Err`) the bytes of the smallest.
fn zbuffer_plan(
    counts: &Counts,
    camera: &crate::geometry::camera::Camera,
    far_z: impl Fn() -> i32,
    method_reason: MethodReason,
    budget: usize,
) -> Result<Plan, usize> {
    let mut smallest = usize::MAX;
    for depth in [DepthWidth::U32, DepthWidth::U16] {
        for (band_rows, buffers, layout_reason) in
            zbuffer_layouts(counts, depth, budget).into_iter().flatten()
        {
            smallest = smallest.min(buffers.total());
            if buffers.total() > budget {
                continue;
            }
            let depth_reason = match depth {
                DepthWidth::U16 => DepthReason::OnlyU16Fits {
                    resolution: resolution_16(camera, far_z()),
                },
                _ => DepthReason::U32Fits,
            };
            return Ok(Plan {
                visibility: Visibility::ZBuffer,
                depth,
                band_rows,
                vertex_stage_once: layout_reason != LayoutReason::BandsVertexStagePerBand,
                buffers,
                method_reason,
                depth_reason,
                layout_reason,
            });
        }
    }
    Err(smallest)
}

/// Sizes the layouts are made of.
struct Counts {
    w: usize,
    h: usize,
    /// Vertex scratch for the largest mesh, for every object's vertices, and the polygon
    /// table, in bytes.
    largest: usize,
    all: usize,
    table: usize,
    /// Compact bands' vertex scratch (vertices and levels) and table, in bytes, when the scene
    /// can be drawn so.
    compact: Option<(usize, usize)>,
}

/// The z-buffer's layouts at `depth`, in the planner's order of preference, as
/// `(band_rows, buffers, why)`: the whole frame, then bands as tall as `budget` allows (one row
/// when even that does not fit: the layout's smallest size); compact bands only when the scene
/// can be drawn so.
fn zbuffer_layouts(
    c: &Counts,
    depth: DepthWidth,
    budget: usize,
) -> [Option<(u16, Buffers, LayoutReason)>; 4] {
    let at = |rows: usize, vertices: usize, polygons: usize| Buffers {
        frame: c.w.saturating_mul(rows),
        depth: c.w.saturating_mul(rows).saturating_mul(depth.bytes()),
        vertices,
        polygons,
        tables: 0,
    };
    // The tallest band whose rows fit beside `fixed` bytes of scratch.
    let rows = |fixed: usize| {
        let per_row = c.w.saturating_mul(1 + depth.bytes()).max(1);
        (budget.saturating_sub(fixed) / per_row).clamp(1, c.h.max(1))
    };
    let once = rows(c.all.saturating_add(c.table));
    let per_band = rows(c.largest);
    let compact = c.compact.map(|(vertices, table)| {
        let r = rows(vertices.saturating_add(table));
        (r as u16, at(r, vertices, table), LayoutReason::CompactBands)
    });
    [
        Some((c.h as u16, at(c.h, c.largest, 0), LayoutReason::WholeFrame)),
        Some((
            once as u16,
            at(once, c.all, c.table),
            LayoutReason::BandsVertexStageOnce,
        )),
        compact,
        Some((
            per_band as u16,
            at(per_band, c.largest, 0),
            LayoutReason::BandsVertexStagePerBand,
        )),
    ]
}

/// `Ok` when compact bands draw `scene` (their module doc): no object is lit Phong, and every
/// object's bounding box, as the planner places it (module doc), lies inside the frustum (the
/// frustum is convex, so its 8 corners do) and projects within `±32767` sub-pixel units: then
/// every vertex the vertex stage places has a compact form. Else the first object that
/// blocks them, and why.
fn compact_fits<const S: u32>(
    scene: &Scene<'_>,
    facts: &[MeshFacts<'_>],
    view: &Placing<'_, S>,
) -> Result<(), CompactBlock> {
    let (projector, frustum) = (view.projector, view.frustum);
    for (i, (object, fact)) in scene.objects.iter().zip(facts).enumerate() {
        let inside = observer_box(object, fact, scene).is_some_and(|b| {
            (0..8).all(|k| {
                let pick = |axis: usize| b[k >> axis & 1][axis];
                frustum.outcode(Vec3::from_bits(pick(0), pick(1), pick(2))) == 0
            })
        });
        let on_screen = place(object, fact, scene, projector)
            .and_then(|p| p.screen)
            .is_some_and(|s| {
                s[0] >= i16::MIN as i64
                    && s[1] >= i16::MIN as i64
                    && s[2] <= i16::MAX as i64
                    && s[3] <= i16::MAX as i64
            });
        match compact_refusal(object) {
            None => {}
            Some(CompactRefusal::LitPhong) => return Err(CompactBlock::LitPhong { object: i }),
            Some(CompactRefusal::Textured) => return Err(CompactBlock::Textured { object: i }),
        }
        if !(inside && on_screen) {
            return Err(CompactBlock::OutsideRange { object: i });
        }
    }
    Ok(())
}

/// Back faces alone for `scene` (rule 1), with `order` sorted far to near; else the reason.
/// The checks run cheapest first: each object's culling and convexity hint (in scene order),
/// then the objects' separation, then the per-view check of each mesh,
/// in reverse drawing order (with `lent`, its vertex stage: the object drawn first is the one
/// whose vertices the scratch keeps).
pub(super) fn back_faces_allowed<const S: u32>(
    scene: &Scene<'_>,
    facts: &[MeshFacts<'_>],
    view: &Placing<'_, S>,
    order: &mut [u16],
    mut lent: Option<&mut Lent<'_, S>>,
) -> Result<MethodReason, MethodReason> {
    let projector = view.projector;
    for (i, (object, fact)) in scene.objects.iter().zip(facts).enumerate() {
        if !object.cull_back_faces {
            return Err(MethodReason::BackFacesDrawn { object: i });
        }
        if matches!(object.transparency, Transparency::Blended(_)) {
            return Err(MethodReason::Blended { object: i });
        }
        if matches!(fact.convexity, Convexity::NotConvex) {
            return Err(MethodReason::NotConvex { object: i });
        }
    }
    separate(scene, facts, projector, order)?;
    for &k in order.iter().rev() {
        let (i, object) = (k as usize, &scene.objects[k as usize]);
        let Convexity::Convex { twins } = facts[i].convexity else {
            continue;
        };
        let Some(mv) = model_view(object, scene) else {
            return Err(MethodReason::LeavesFrustum { object: i });
        };
        let checked = match lent.as_deref_mut().and_then(|l| l.prepare(i, object)) {
            Some(prepared) => apart_prepared(&object.mesh, twins, prepared),
            None => apart_in(
                &object.mesh,
                twins,
                &View {
                    model_view: &mv,
                    frustum: view.frustum,
                    projector,
                },
            ),
        };
        match checked {
            Ok(()) => {}
            Err(Refusal::LeavesFrustum) => return Err(MethodReason::LeavesFrustum { object: i }),
            Err(Refusal::FrontFacesMayOverlap) => {
                return Err(MethodReason::FrontFacesMayOverlap { object: i })
            }
        }
    }
    Ok(MethodReason::ConvexAndSeparable)
}

/// Rule 1b: in a scene where rule 1 holds (`order` far to near), the first object lit per
/// pixel (Phong) whose screen box overlaps that of an object drawn after it (nearer), as
/// [`MethodReason::HiddenPixelsLitPerPixel`]; `None` when there is none.
fn hidden_lit_per_pixel<const S: u32>(
    scene: &Scene<'_>,
    facts: &[MeshFacts<'_>],
    projector: &Projector<S>,
    order: &[u16],
) -> Option<MethodReason> {
    let placed = |i: usize| place(&scene.objects[i], &facts[i], scene, projector);
    for (a, &i) in order.iter().enumerate() {
        let object = &scene.objects[i as usize];
        let lit_per_pixel = object.shade == ShadeMode::Phong
            && matches!(object.intensities, Intensities::Lit { .. });
        if !lit_per_pixel {
            continue;
        }
        let Some(p) = placed(i as usize) else {
            continue;
        };
        for &j in &order[a + 1..] {
            if placed(j as usize).is_some_and(|q| !screens_apart(&p, &q)) {
                return Some(MethodReason::HiddenPixelsLitPerPixel {
                    object: i as usize,
                    nearer: j as usize,
                });
            }
        }
    }
    None
}

/// Sorts `order` far to near by the far end of each object's depth range, and checks that
/// any two objects overlapping on screen are apart in depth (rule 1's separability).
fn separate<const S: u32>(
    scene: &Scene<'_>,
    facts: &[MeshFacts<'_>],
    projector: &Projector<S>,
    order: &mut [u16],
) -> Result<(), MethodReason> {
    let placed = |i: usize| place(&scene.objects[i], &facts[i], scene, projector);
    let key = |i: u16| placed(i as usize).map_or(u32::MAX, |p| p.depth.1);
    // Insertion sort: no heap, n small.
    for k in 1..order.len() {
        let mut j = k;
        while j > 0 && key(order[j - 1]) < key(order[j]) {
            order.swap(j - 1, j);
            j -= 1;
        }
    }
    for a in 0..order.len() {
        for b in a + 1..order.len() {
            let (i, j) = (order[a] as usize, order[b] as usize);
            let apart = match (placed(i), placed(j)) {
                (Some(p), Some(q)) => p.depth.0 > q.depth.1 || screens_apart(&p, &q),
                _ => false,
            };
            if !apart {
                let (a, b) = (i.min(j), i.max(j));
                return Err(MethodReason::ObjectsOverlap { a, b });
            }
        }
    }
    Ok(())
}

/// True when two screen boxes are disjoint.
fn screens_apart(p: &Placed, q: &Placed) -> bool {
    match (p.screen, q.screen) {
        (Some(a), Some(b)) => a[2] < b[0] || b[2] < a[0] || a[3] < b[1] || b[3] < a[1],
        _ => false,
    }
}

/// The object's model → observer transform, as the renderer composes it.
fn model_view(object: &Object<'_>, scene: &Scene<'_>) -> Option<crate::geometry::matrix::Affine3> {
    object.transform.then(scene.camera.view_transform()).ok()
}

/// The box of the object's mesh bounds' 8 corners taken to the observer frame (raw
/// `[min, max]` per axis), `None` when its transform cannot be composed; every vertex the
/// vertex stage places lies in it (module doc).
fn observer_box(
    object: &Object<'_>,
    fact: &MeshFacts<'_>,
    scene: &Scene<'_>,
) -> Option<[[i32; 3]; 2]> {
    let mv = model_view(object, scene)?;
    let [lo, hi] = fact.bounds;
    let corner = |k: usize| {
        let pick = |axis: usize| {
            if k >> axis & 1 == 0 {
                lo[axis]
            } else {
                hi[axis]
            }
        };
        mv.transform_point(Vec3::from_bits(pick(0), pick(1), pick(2)))
            .bits()
    };
    let mut b = [[i32::MAX; 3], [i32::MIN; 3]];
    for k in 0..8 {
        let c = corner(k);
        for a in 0..3 {
            b[0][a] = b[0][a].min(c[a]);
            b[1][a] = b[1][a].max(c[a]);
        }
    }
    Some(b)
}

/// The object's depth range and screen box in this view (module doc), `None` when its
/// transform cannot be composed.
fn place<const S: u32>(
    object: &Object<'_>,
    fact: &MeshFacts<'_>,
    scene: &Scene<'_>,
    projector: &Projector<S>,
) -> Option<Placed> {
    let b = observer_box(object, fact, scene)?;
    let near = projector.near().to_bits();
    let depth_at = |z: i32| {
        projector
            .project_point(Vec3::from_bits(0, 0, z.max(near)))
            .map_or(0, |p| p.1)
    };
    let depth = (
        depth_at(b[0][2]).saturating_sub(DEPTH_MARGIN),
        depth_at(b[1][2]).saturating_add(DEPTH_MARGIN),
    );
    let mut screen = Some([i64::MAX, i64::MAX, i64::MIN, i64::MIN]);
    for k in 0..8 {
        let pick = |axis: usize| b[k >> axis & 1][axis];
        let p = projector.project_point(Vec3::from_bits(pick(0), pick(1), pick(2)));
        screen = match (screen, p) {
            (Some(s), Ok((q, _))) => Some([
                s[0].min(q.x as i64),
                s[1].min(q.y as i64),
                s[2].max(q.x as i64),
                s[3].max(q.y as i64),
            ]),
            _ => None,
        };
    }
    let screen = screen.map(|s| {
        [
            s[0] - SCREEN_MARGIN,
            s[1] - SCREEN_MARGIN,
            s[2] + SCREEN_MARGIN,
            s[3] + SCREEN_MARGIN,
        ]
    });
    Some(Placed {
        depth,
        screen,
        far_z: b[1][2],
    })
}

/// `Δz = z²·(far − near)/(far·near·2^16)` at `z` (raw I16F16; the far plane when `z` is
/// beyond it or unknown): the 16-bit buffer's depth step there.
fn resolution_16(camera: &crate::geometry::camera::Camera, z: i32) -> Coord {
    let lens = camera.lens();
    let (near, far) = (lens.near.to_bits() as u128, lens.far.to_bits() as u128);
    let z = if z <= 0 { far } else { (z as u128).min(far) };
    let raw = z * z * (far - near) / (far * near * (1 << 16)).max(1);
    Coord::from_bits(raw.min(i32::MAX as u128) as i32)
}
