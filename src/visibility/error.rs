//! Why a hidden-surface method did not draw a frame: [`VisibilityError`], the methods' own
//! refusals (a store, a budget or a stack of caller memory too small, an object the method
//! cannot draw in parts, a scene outside its rule, a hand-made plan) beside the shared
//! pipeline's ([`RenderError`], wrapped as [`VisibilityError::Render`]).
//!
//! The pipeline's stages (vertex, polygon, raster, bands) report in `render`'s vocabulary and
//! never name a method; each method here reports its own limits in this one. Every message
//! names what failed, the object or the memory, and the limit; a wrapped [`RenderError`]
//! prints its own message unchanged.

use super::plan::MethodReason;
use crate::render::RenderError;

/// Why a hidden-surface method ([`Visibility`](super::Visibility)) did not draw a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VisibilityError {
    /// The shared pipeline's error (vertex and polygon stages, writer, buffers), as the
    /// z-buffer's frames report it.
    Render(RenderError),
    /// A visibility method that stores triangles before drawing them (painter, scan-line,
    /// Warnock) was given more front triangles (with the painter's pieces) than its caller
    /// memory holds.
    TriangleStoreFull {
        /// Triangles the store holds.
        capacity: usize,
    },
    /// The painter's overlap resolution needed more splits (Newell's test 6) than its budget.
    SplitBudgetExhausted {
        /// Splits the caller's budget allows.
        budget: usize,
    },
    /// The painter's tests could not order a group of pieces that no further split separates
    /// (each already cut by the others' planes; the tests judge a piece by an outline a sliver
    /// larger than it): the frame is refused rather than drawn in a wrong order.
    PainterCycle,
    /// Warnock's subdivision needed more windows on its stack than the caller's memory holds.
    SubdivisionStackFull {
        /// Windows the stack holds.
        capacity: usize,
    },
    /// Warnock's subdivision needed more candidate entries (the lists of the windows being
    /// subdivided, one after the other) than the caller's memory holds.
    SubdivisionCandidatesFull {
        /// Entries the candidate stack holds.
        capacity: usize,
    },
    /// The scan-line method's active table holds fewer triangles than reach one band.
    ActiveTableFull {
        /// Triangles the active table holds.
        capacity: usize,
    },
    /// The painter would split a triangle of a fast Gouraud object, or Warnock's subdivision
    /// was given one: both draw parts of triangles (a piece row by row, a window), where the
    /// 16.16 luminance steps start at the part's first pixel instead of the whole span's, so
    /// some pixels would differ by a level from the z-buffer's (draw the object with exact
    /// Gouraud, or the frame with the scan-line or the z-buffer).
    FastGouraudInParts {
        /// The object's index in the scene.
        object: usize,
    },
    /// A scene with more objects than the method can name: 256 for the methods that store
    /// triangles (a stored triangle names its object in one byte), 65,536 for the reverse
    /// painter's `u16` order.
    TooManyObjects {
        /// The most objects the method names.
        max: usize,
    },
    /// A drawing order names an object the scene does not have (or is shorter than the
    /// scene's objects, for the reverse painter, which writes it).
    NoSuchObject {
        /// The index named.
        index: u16,
        /// Objects in the scene.
        objects: usize,
    },
    /// The reverse painter was given a scene where a front-to-back order is not right (the
    /// planner's rule 1 fails for this reason): draw it with the z-buffer.
    ReverseRefused(MethodReason),
    /// [`draw_plan`](super::draw_plan) was given a plan whose method and depth width the
    /// planner never makes together (a `Plan` built by hand).
    NotPlanned {
        /// The plan's method, by its name (`Visibility::name`).
        method: &'static str,
        /// The plan's bytes of depth per sample.
        depth_bytes: usize,
    },
}

impl From<RenderError> for VisibilityError {
    fn from(e: RenderError) -> Self {
        VisibilityError::Render(e)
    }
}

impl core::fmt::Display for VisibilityError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            VisibilityError::Render(e) => write!(f, "{e}"),
            VisibilityError::TriangleStoreFull { capacity } => write!(
                f,
                "more front triangles than the triangle store's {capacity}"
            ),
            VisibilityError::SplitBudgetExhausted { budget } => write!(
                f,
                "the painter's overlaps need more than its budget of {budget} splits"
            ),
            VisibilityError::PainterCycle => write!(
                f,
                "the painter's tests cannot order a cycle of pieces (use the scan-line or z-buffer)"
            ),
            VisibilityError::SubdivisionStackFull { capacity } => write!(
                f,
                "Warnock's subdivision needs more than its stack of {capacity} windows"
            ),
            VisibilityError::SubdivisionCandidatesFull { capacity } => write!(
                f,
                "Warnock's subdivision needs more than its {capacity} candidate entries"
            ),
            VisibilityError::ActiveTableFull { capacity } => write!(
                f,
                "more triangles reach one band than the active table's {capacity}"
            ),
            VisibilityError::FastGouraudInParts { object } => write!(
                f,
                "object {object} is fast Gouraud, whose 16.16 shading steps differ from the \
                 z-buffer's when a triangle is drawn in parts (the painter's pieces, Warnock's \
                 windows): use exact Gouraud, the scan-line or the z-buffer"
            ),
            VisibilityError::TooManyObjects { max } => {
                write!(f, "more than {max} objects in the scene")
            }
            VisibilityError::NoSuchObject { index, objects } => write!(
                f,
                "the drawing order names object index {index}, but the scene has {objects} \
                 objects (indices 0 to {objects} − 1)"
            ),
            VisibilityError::ReverseRefused(reason) => write!(
                f,
                "the reverse painter draws the z-buffer's picture only for culled convex \
                 objects apart in depth where they overlap on screen; here {reason}"
            ),
            VisibilityError::NotPlanned {
                method,
                depth_bytes,
            } => write!(
                f,
                "a plan of method {method} with {depth_bytes} bytes of depth per sample is not \
                 one the planner makes: draw_plan draws back faces with no depth and the z-buffer \
                 with 16- or 32-bit depth"
            ),
        }
    }
}

impl core::error::Error for VisibilityError {}

/// The pipeline's error `e` as a caller's error type `E` (one that takes a
/// [`VisibilityError`]): wrapped as [`VisibilityError::Render`], then converted.
pub(super) fn through<E: From<VisibilityError>>(e: RenderError) -> E {
    E::from(VisibilityError::Render(e))
}

/// A caller's error type `E` (one that takes a [`VisibilityError`]) seen as one that takes the
/// pipeline's [`RenderError`] too ([`through`]): what the z-buffer's banded entries, generic
/// over their callback's error, are called with from a method's entry.
pub(super) struct Through<E>(pub(super) E);

impl<E: From<VisibilityError>> From<RenderError> for Through<E> {
    fn from(e: RenderError) -> Self {
        Through(through(e))
    }
}
