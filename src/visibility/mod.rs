//! Hidden-surface methods after the polygon stage: which surface shows at each pixel, decided
//! by the cheapest method a scene allows.
//!
//! Role in the pipeline: the frame stage's choice of visibility. The z-buffer
//! ([`render_scene`](crate::render::render_scene), [`render_in_bands`](crate::render::render_in_bands))
//! resolves any scene at the cost of a depth sample per pixel. The survey of hidden-surface
//! algorithms (seed 003) and the course (seed 000, ch. 3 §2) describe cheaper methods with
//! narrower claims; each is here a consumer of the polygon stage's culled, clipped, projected
//! triangles (the seam, `render/consumer.rs`), drawn by the same triangle writer, so that
//! where a method is correct it gives the z-buffer's pixels:
//!
//! | [`Visibility`] | memory beside the frame | correct for |
//! |---|---|---|
//! | [`BackFace`](Visibility::BackFace) (`backface.rs`) | none | one closed convex mesh; objects drawn back to front that a plane separates |
//! | [`ReversePainter`](Visibility::ReversePainter) (`reverse.rs`) | a bit per pixel (`⌈w·h/32⌉` words) | as back faces alone: culled convex objects apart in depth where they overlap on screen, drawn near to far |
//! | [`Painter`](Visibility::Painter) (`painter.rs`) | a stored triangle and an index per front triangle, plus pieces | any scene (Newell's tests, splitting where they fail) |
//! | [`ScanLine`](Visibility::ScanLine) (`scanline.rs`) | a stored triangle and an index per front triangle, a band of rows and its depth | any scene (the z-buffer's picture at the depth width of its band) |
//! | [`Warnock`](Visibility::Warnock) (`warnock.rs`) | a stored triangle per front triangle, stacks of candidate indices and of windows | any scene (the 32-bit z-buffer's depths and tie rule, decided per window) |
//! | [`ZBuffer`](Visibility::ZBuffer) (`render/`) | a depth sample per pixel (or per band pixel) | any scene |
//!
//! Where each breaks: the reverse painter is refused in words outside back faces alone's
//! scenes ([`VisibilityError::ReverseRefused`], the planner's reason); back faces alone draws the last
//! of two overlapping front faces (the
//! bunny: 279 wrong pixels); the painter without test 6 draws a cycle or interpenetration in
//! the wrong order (101 and 514 wrong pixels in `tests/visibility.rs`), and with it judges each
//! piece by its own outline and draws them right (the bunny: 2 splits; a piece may be cut as
//! often as the store holds pieces: every one of 200 dense random soups and two interpenetrating
//! cubes from any view), refusing a frame whose pieces its tests still cannot order
//! ([`VisibilityError::PainterCycle`]) or whose split budget or store
//! is short (an error naming the budget or the capacity); the scan-line never differs from the
//! z-buffer of its depth width, Warnock's subdivision never from the 32-bit z-buffer.
//! Ties follow the z-buffer's rule in every method that claims its picture: at an equal depth
//! the surface drawn first (stored first, in scene order) is kept; the painter orders exact
//! planes, so it keeps the rule where the exact depths tie and where they differ by a depth unit
//! or more, and paints the exactly nearer surface where two differ by less (at 32-bit depth,
//! within `2^-32` of the depth range). A 16-bit z-buffer ties (z-fights) far more often, growing
//! with far/near (counted in `tests/visibility.rs`: two surfaces 0.5 units apart 40 units away,
//! 42 wrong pixels of 3,530 at far/near = 1000, 3,390 at 10,000, against the 32-bit picture;
//! none for the 32-bit methods, and the scan-line at 16 bits draws the 16-bit picture). Every
//! capacity exhausted (store, split budget, active table, Warnock's stacks) is an error, never
//! a picture.
//!
//! The methods' errors are this folder's own vocabulary, [`VisibilityError`] (`error.rs`): each
//! method's refusals (its stores and stacks, its budget, an object it cannot draw in parts, a
//! scene outside its rule, a hand-made plan), and the shared pipeline's
//! [`RenderError`](crate::render::RenderError) wrapped as [`VisibilityError::Render`]. Every
//! entry here returns it (the banded ones through their callback's error type); `render`
//! names no method, so it does not import this folder. The methods' counts are
//! [`MethodCounts`], beside the pipeline's in `stats.rs`.
//!
//! Objects the storing methods refuse, in words: the painter, the scan-line and Warnock keep a
//! level per corner, so a core-lit Phong object (normals per corner, lit per pixel) is
//! [`RenderError::PhongUnsupported`](crate::render::RenderError::PhongUnsupported): draw it
//! with the z-buffer (or back faces alone, which draws at once); a scene holding one, such as
//! `host-tests/scenes/example.toml` and `demo.toml`, is drawn by those two only. Warnock's
//! subdivision and the painter's pieces draw parts of triangles, where fast Gouraud's 16.16
//! luminance steps would start at the part's first column instead of the whole span's: Warnock
//! refuses a fast Gouraud object and the painter a split of one
//! ([`VisibilityError::FastGouraudInParts`]); the
//! scan-line's bands cut rows only and draw it as the z-buffer does.
//!
//! [`plan`] picks the cheapest method a scene allows within a RAM budget, from what is cheap
//! to know (`plan.rs`): each mesh's [`MeshFacts`] (bounds, convexity hint and edge table,
//! computed once, `facts.rs`), the objects' depth ranges and screen boxes. Culled, separable
//! objects whose drawn faces cover each pixel at most once in this view (an exact check on
//! the rounded screen positions, `facts.rs`) need no depth buffer
//! ([`render_back_faces_in_order`], far to near), or, when a Phong object lies behind a nearer
//! one on screen, the reverse painter ([`render_reverse_painter`], near to far through a bit
//! per pixel, each pixel lit once); other scenes take the z-buffer, whole or in bands, 32-bit
//! unless only 16-bit fits. [`plan_frame`] plans and draws as one entry
//! (`planned.rs`): the per-view check of a mesh runs the renderer's vertex stage into the
//! caller's scratch, and a plan of back faces alone comes back as a [`BackFaceFrame`] that draws
//! from those prepared vertices instead of running the vertex stage again. Any plan draws
//! through one entry, [`draw_plan`] (`draw_plan.rs`), from caller memory the plan sizes
//! ([`PlanSizes`], [`PlanMemory`]), each finished band handed to the caller's callback.
//!
//! Every method's own counts (Newell's tests by number, splits; the active table's peak;
//! Warnock's windows by verdict and stack peaks) go to [`RenderStats::method`](crate::render::RenderStats),
//! a few adds per pair, triangle or window.
//!
//! Shared conventions: triangles are collected in scene order; a stored triangle keeps its
//! corners exactly as the polygon stage handed them (sub-pixel position, 32-bit depth, level),
//! so drawing it later writes the pixels it would have written at once. The z-buffer keeps the
//! first of two surfaces at equal stored depth, and so does every method here (above).
//!
//! Numeric contract: positions within the projector's `±(2^28 − 1)` sub-pixel range, depths
//! `u32`, levels `0..=255`; the painter's plane tests use `i64` normals and `i128` (or exact
//! 192-bit) products, bounded in `painter.rs`.

mod backface;
mod draw_plan;
#[cfg(test)]
mod entry_tests;
mod error;
mod facts;
mod outline;
mod painter;
mod plan;
mod plane;
mod planned;
mod reverse;
mod scanline;
mod store;
mod warnock;

pub use crate::stats::{MethodCounts, WindowCounts};
pub use backface::{render_back_faces, render_back_faces_in_order};
pub use draw_plan::{draw_plan, PlanMemory, PlanSizes};
pub use error::VisibilityError;
pub use facts::{Convexity, FactsError, MeshFacts, NO_TWIN};
pub use painter::{render_painter, Normal, PainterMemory, SplitPolicy};
pub use plan::{
    plan, Buffers, CompactBlock, DepthReason, DepthWidth, LayoutReason, MethodReason, Plan,
    PlanError, DEPTH_MARGIN, SCREEN_MARGIN,
};
pub use planned::{plan_frame, BackFaceFrame, PlannedFrame};
pub use reverse::render_reverse_painter;
pub use scanline::{render_scan_lines, ScanLineMemory};
pub use store::StoredTriangle;
pub use warnock::{render_warnock, Area, WarnockMemory};

/// A hidden-surface method ([module doc](self)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Visibility {
    /// Back faces culled, front faces drawn in scene order with no depth buffer.
    BackFace,
    /// Depth-sort painter (Newell, Newell and Sancha 1972) with the survey's six tests.
    Painter,
    /// The reverse painter (course ch. 3, algorithm 3.2): separable convex objects near to
    /// far, a mask of one bit per pixel, each pixel painted once (`reverse.rs`).
    ReversePainter,
    /// Scan-line: a triangle table by first row, an active list, a band of depth rows.
    ScanLine,
    /// Warnock's area subdivision: windows drawn when simple, else split, down to a pixel.
    Warnock,
    /// Full-frame (or banded) depth buffer.
    ZBuffer,
}

impl Visibility {
    /// Every method, cheapest first.
    pub const ALL: [Visibility; 6] = [
        Visibility::BackFace,
        Visibility::ReversePainter,
        Visibility::Painter,
        Visibility::ScanLine,
        Visibility::Warnock,
        Visibility::ZBuffer,
    ];

    /// The method's name as the command line spells it.
    pub const fn name(self) -> &'static str {
        match self {
            Visibility::BackFace => "backface",
            Visibility::Painter => "painter",
            Visibility::ReversePainter => "reverse-painter",
            Visibility::ScanLine => "scanline",
            Visibility::Warnock => "warnock",
            Visibility::ZBuffer => "zbuffer",
        }
    }

    /// The method named `name` ([`Self::name`]).
    pub fn from_name(name: &str) -> Option<Visibility> {
        Visibility::ALL.into_iter().find(|v| v.name() == name)
    }
}

impl core::fmt::Display for Visibility {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}
