//! One triangle's spans: the plane its span kind needs, and the loop over the fill's spans.
//!
//! Role in the pipeline: between the decision (`draw`, which picks the span kind once per
//! triangle) and the per-pixel loop (`span`). [`TriangleSpans`] sets up the exact plane of a
//! kind (small, general with its runs, or wide: the same values), walks the spans of the
//! fill on the same set-up, slices each from its target (`slices`) and lets the kind
//! (`kinds`) write it. The fill's span callback is a closure of this folder, inlined: the
//! span code reaches the writer's values in registers.
//!
//! Numeric contract: as the planes (`plane`); spans are clipped to the window (half-open) by
//! the fill; the counts are `u32` (a triangle inside the buffers covers fewer than `2^32`
//! pixels).

use super::fill::fill_setup;
use super::interpolants::{Constant, Exact, ExactRun, Interpolant, SpanStarts};
use super::kinds::SpanKind;
use super::plane::{AttributePlane, PlaneError, RowStarts};
use super::setup::TriangleSetup;
use super::slices::SpanTarget;
use super::small_plane::SmallPlane;
use super::span::{depth_span, Gouraud, Quantizer, WrittenCount};
use super::wide_plane::{ExactWide, WidePlane};
use crate::arith::euclid::Divisor;
use crate::raster::Window;

/// Bounding-box width (pixels) from which a triangle's spans use [`ExactRun`].
const MIN_RUN_WIDTH: u32 = 16;

/// How a span loop gets its exact interpolants from the exact starts `E` of its plane
/// ([`Exact`], or [`ExactWide`](super::interpolants::ExactWide) for a [`WidePlane`]): as they
/// are, or as [`ExactRun`] accumulators (one add per pixel) when every span is short enough.
trait FromExact<E> {
    type I: Interpolant;
    /// Per-triangle data derived from a first exact state.
    fn prepare(e: &E) -> Self;
    /// The interpolant for a span starting at `e`.
    fn start(&self, e: &E) -> Self::I;
}

impl<E: Interpolant> FromExact<E> for E {
    type I = E;
    #[inline(always)]
    fn prepare(e: &E) -> Self {
        *e
    }
    #[inline(always)]
    fn start(&self, e: &E) -> E {
        *e
    }
}

/// The per-triangle 32.32 step of an [`ExactRun`] and its prepared `2D`.
struct ExactRunFrom((u64, Divisor));

impl FromExact<Exact> for ExactRunFrom {
    type I = ExactRun;
    #[inline(always)]
    fn prepare(e: &Exact) -> Self {
        ExactRunFrom(ExactRun::prepare(e))
    }
    #[inline(always)]
    fn start(&self, e: &Exact) -> ExactRun {
        ExactRun::start(e, &self.0)
    }
}

/// One triangle's span drawing, set up (see [`draw_triangle_quantized`]).
///
/// The set-up is held by value, like every argument of an out-of-line callee
/// (`TriangleSpans::wide`, `tiny_mapped`): a reference would keep the whole set-up in memory
/// on every path (Cortex-M4 `frame_bunny` +3.8 %, measured), a copy is made only on the
/// path that calls.
///
/// `T` is where its spans are written ([`SpanTarget`]): a frame and its depth buffer
/// ([`Targets`]), or depth samples alone ([`DepthTargets`], the depth-only kind).
pub(super) struct TriangleSpans<'a, T, C, const S: u32> {
    pub(super) t: TriangleSetup<S>,
    pub(super) window: Window,
    pub(super) targets: &'a mut T,
    pub(super) count: C,
}

impl<T: SpanTarget, C: WrittenCount, const S: u32> TriangleSpans<'_, T, C, S> {
    /// Constant depth `z` and flat luminance `lum`: no plane, any size (a zero-area triangle
    /// covers nothing in the fill).
    #[inline(always)]
    pub(super) fn constant<Q: Quantizer>(
        self,
        z: u32,
        lum: u32,
        quantizer_at: impl Fn(i32, i32) -> Q,
    ) -> (u32, u32) {
        let (mut covered, mut written) = (0u32, 0u32);
        let targets = &mut *self.targets;
        fill_setup(&self.t, &self.window, |s| {
            covered += s.x1.wrapping_sub(s.x0) as u32;
            let Some((c, zs)) = targets.span(&s) else {
                return;
            };
            let shading = Gouraud {
                luminance: Constant(lum),
                quantizer: quantizer_at(s.x0, s.y),
            };
            written += depth_span(c, zs, Constant(z), shading, self.count);
        });
        (covered, written)
    }

    /// The exact plane of `values` (attribute 0 is the depth), small, general or wide, and the
    /// span loop over it with span kind `kind`.
    #[inline(always)]
    pub(super) fn planar<K: SpanKind<N>, const N: usize>(
        self,
        values: [[u32; N]; 3],
        kind: K,
    ) -> (u32, u32) {
        // Small planes step plain Exact values: their spans are short, and ExactRun starts
        // (a 64-bit division each) measured dearer on the Cortex-M4 (standard sphere +10 %).
        if let Some(small) = SmallPlane::<N, S>::of(&self.t, values) {
            return self.run::<Exact, _, K, N>(small, kind);
        }
        self.general(values, kind, true)
    }

    /// [`Self::planar`] without the small plane: the general plane (its span starts
    /// [`ExactRun`]s for mid-width triangles when `runs`), or the wide one.
    #[inline(always)]
    pub(super) fn general<K: SpanKind<N>, const N: usize>(
        self,
        values: [[u32; N]; 3],
        kind: K,
        runs: bool,
    ) -> (u32, u32) {
        let plane = match AttributePlane::<N, S>::of(&self.t, values) {
            Ok(p) => p,
            Err(PlaneError::Degenerate) => return (0, 0),
            Err(PlaneError::TooLarge) => return self.wide(values, kind),
        };
        // The longest span is at most the bounding box's width in pixels plus one.
        let width = ((self.t.x[1] - self.t.x[0]) >> S) as u32 + 2;
        // ExactRun costs a 64-bit division per span start and saves ~6 instructions per pixel.
        // Threshold measured with callgrind on the standard cube, sphere and bunny (4, 16, 32 and
        // never tried; 16 was best on all three), when every triangle took the general plane.
        if runs && (MIN_RUN_WIDTH..=plane.run_limit()).contains(&width) {
            self.run::<ExactRunFrom, _, K, N>(RowStarts::new(&plane), kind)
        } else {
            self.run::<Exact, _, K, N>(RowStarts::new(&plane), kind)
        }
    }

    /// [`Self::planar`] for a triangle too large for the [`AttributePlane`] (`2D ≥ 2^31`):
    /// the [`WidePlane`], out of line so that the common triangles' path stays as it was.
    #[cold]
    #[inline(never)]
    fn wide<K: SpanKind<N>, const N: usize>(self, values: [[u32; N]; 3], kind: K) -> (u32, u32) {
        match WidePlane::<N, S>::of(&self.t, values) {
            Ok(plane) => self.run::<ExactWide, _, K, N>(plane, kind),
            Err(_) => (0, 0), // zero area: covers nothing
        }
    }

    /// The span loop: every span of the fill, sliced from the buffers, its exact starts taken
    /// from `starts` (made [`ExactRun`]s by `F`), written by `kind`.
    #[inline(always)]
    fn run<F: FromExact<St::Exact>, St: SpanStarts<N>, K: SpanKind<N>, const N: usize>(
        self,
        mut starts: St,
        kind: K,
    ) -> (u32, u32) {
        let (mut covered, mut written) = (0u32, 0u32);
        let mut per_triangle: Option<[F; N]> = None;
        let targets = &mut *self.targets;
        fill_setup(&self.t, &self.window, |s| {
            covered += s.x1.wrapping_sub(s.x0) as u32;
            let Some((c, z)) = targets.span(&s) else {
                return;
            };
            let e = starts.exact_at(s.x0, s.y);
            let f = per_triangle.get_or_insert_with(|| e.each_ref().map(F::prepare));
            let attrs = core::array::from_fn(|i| f[i].start(&e[i]));
            written += kind.write(c, z, attrs, &starts, (s.x0, s.y), self.count);
        });
        (covered, written)
    }
}
