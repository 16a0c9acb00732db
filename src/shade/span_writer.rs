//! Span writers: the per-pixel loops that turn a triangle's spans into framebuffer writes.
//!
//! Role in the pipeline: the last step of the raster stage. [`draw_triangle`] sets the
//! triangle up once (`raster/setup.rs`: sorted vertices, twice-area, orientation, box, edges),
//! decides its span kind once (`draw_in_range`, the one dispatch point), sets up the exact
//! plane of the kind (attribute 0 is depth, attribute 1 luminance), then for each span of the
//! fill (`fill_setup`, on the same set-up) takes the exact values at the span start from it
//! and runs one generic loop, `depth_span`: depth test (strict, nearer wins, see
//! [`DepthValue`]), palette index from a `Shading`, two stores. Phong's seven attributes are
//! one more span kind of the same loop (`shade/phong.rs`, through `draw_general_exact`), and
//! so is depth only (`DepthOnlyKind`, through `draw_depth_only`: the shadow map's pass 1 into
//! a `DepthTarget`, the map's samples with no framebuffer; the same plane choice and span
//! loop, whose colour side stores nothing).
//!
//! Small triangles (bounding box below `2^K` sub-pixel units on both axes,
//! `K =` `small_bits``(S)`: 64 pixels at `S = 4`) get a
//! `SmallPlane`, whose set-up and span starts are 32-bit arithmetic; the others an
//! `AttributePlane` with `RowStarts`, and the few too large for its 32-bit stepping
//! (`2D ≥ 2^31`: large viewports, guard-band fan triangles) a `WidePlane`, set up out of
//! line (`TriangleSpans::wide`) so the others run the instructions they ran before. All give
//! the same values and feed the same span code (`SpanStarts`): every triangle of the
//! raster's range is drawn. The switch is the 32-bit arithmetic's limit, not a tuned size: every
//! triangle of the standard sphere and bunny is below it, and the 32-bit path measured cheaper
//! there (Cortex-M4 `frame_bunny` −22 %, `frame_sphere` −18 %; host −0.2 % and −1.5 %).
//!
//! On 32-bit cores with a hardware divider (`arith::TINY_WRITER`), those small triangles whose
//! columns lie inside the window (rows are clipped), with exact or flat luminance through a
//! 256-level ramp, go one step further: the tiny-triangle writer (`shade/tiny_triangle.rs`)
//! sets up edges and both planes at once and draws each span out of line, for the same pixels
//! with far fewer values held across the rows (Cortex-M4 `frame_bunny` −19 %, `frame_sphere`
//! −11 %, 16-row bands of the bunny −13 %).
//!
//! Numeric contract: as `attributes`; depth values are the 32-bit
//! normalised depth of the projection stage, stored through [`DepthValue::from_depth32`];
//! luminance is `0..=255` (vertex values above saturate to 255 at the vertices, so every
//! interpolated value is in range and the span loops map it without a test).

use super::attributes::{
    AttributePlane, Constant, Exact, ExactRun, ExactWide, Interpolant, PlaneError, RowStarts,
    SmallPlane, SpanStarts, WidePlane,
};
pub use super::span::LuminanceRamp;
use super::span::{depth_only_span, DepthTargets, Direct, InRange, SpanTarget, Targets};
pub(crate) use super::span::{
    depth_span, CountWritten, Gouraud, Quantizer, Shading, SkipWritten, WrittenCount,
};
use super::tiny_triangle::TinyTriangle;
use crate::arith::euclid::Divisor;
use crate::arith::TINY_WRITER;
use crate::raster::polygon::FillError;
use crate::raster::range::check_range;
use crate::raster::setup::TriangleSetup;
use crate::raster::triangle::fill_setup;
use crate::raster::{SubpixelPoint, Window};
use crate::target::{DepthBuffer, DepthValue, Framebuffer};

/// How a triangle's luminance becomes palette indices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShadeMode {
    /// One index per triangle: the ramp at the mean of the vertex luminances (rounded).
    Flat,
    /// Vertex luminances interpolated exactly (every pixel the correctly rounded value).
    GouraudExact,
    /// Vertex luminances interpolated in 16.16 fixed point (one add per pixel; see `Dda`).
    GouraudFast,
    /// Normals interpolated and lit at every pixel (`phong`); the renderer
    /// draws lit objects in this mode with [`draw_triangle_phong`](super::phong::draw_triangle_phong).
    /// The luminance writers here have no normals: given vertex luminances they interpolate
    /// them as [`GouraudExact`](ShadeMode::GouraudExact).
    Phong,
}

/// Why a triangle was not drawn. Every triangle of the raster's range is drawn, whatever its
/// size: one too large for the 32-bit stepping of `AttributePlane` takes the `WidePlane`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawError {
    /// The fill rejected the vertices (outside the raster's range).
    Fill(FillError),
}

/// Draws a depth-tested, shaded triangle into a frame and its depth buffer.
///
/// `values[i] = [depth, luminance]` at vertex `i` (luminances above 255 count as 255: they
/// saturate at the vertex, not per pixel). Pixels follow the fill rule of
/// [`polygon`](crate::raster::polygon), limited to the rows both buffers hold. Returns
/// `(covered, written)`: the pixels the triangle covers inside the buffers, and those of them
/// that passed the depth test. Zero-area triangles and triangles wholly outside the buffers
/// draw nothing and return `Ok((0, 0))` without setting up interpolation.
pub fn draw_triangle<D: DepthValue, const S: u32>(
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    ramp: LuminanceRamp,
    mode: ShadeMode,
) -> Result<(u32, u32), DrawError> {
    draw_triangle_quantized(frame, depth, v, values, mode, |_, _| ramp)
}

/// [`draw_triangle`] with luminance mapped to indices by the [`Quantizer`] that
/// `quantizer_at(x, y)` gives for the span starting at pixel `(x, y)` (a dithered ramp, say).
/// Flat shading uses the rounded mean of the vertex luminances.
///
/// The shading is decided once per triangle, and each decision runs the one span loop
/// (`TriangleSpans::run`) with its own span kind (`SpanKind`): constant depth and colour
/// (no plane at all), flat colour over the exact depth plane (a one-attribute plane), exact or
/// fast Gouraud (two attributes). A constant depth under Gouraud shading takes the depth plane,
/// whose value is then the vertex depth at every pixel (zero gradient: `M = 0`, the rounded
/// quotient `⌊D / 2D⌋ = 0`), the value the constant would give.
pub(crate) fn draw_triangle_quantized<D: DepthValue, Q: Quantizer, const S: u32>(
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    mode: ShadeMode,
    quantizer_at: impl Fn(i32, i32) -> Q,
) -> Result<(u32, u32), DrawError> {
    draw_triangle_on(
        &mut RasterTarget::new(frame, depth),
        v,
        values,
        mode,
        quantizer_at,
    )
}

/// A frame and its depth buffer prepared once for many triangles ([`draw_triangle_on`]): the
/// window both hold and their samples as whole slices, so that a triangle's set-up does not
/// recompute them.
/// `C` says whether triangles drawn into it count their written pixels ([`WrittenCount`]).
#[derive(Debug)]
pub(crate) struct RasterTarget<'t, D, C = CountWritten> {
    /// Where triangles are drawn: the buffers' window, or part of it ([`Self::restrict`]).
    window: Window,
    /// The window both buffers hold.
    buffers: Window,
    targets: Targets<'t, D>,
    count: C,
}

impl<'t, D: DepthValue> RasterTarget<'t, D> {
    /// Borrows `frame` and `depth` for drawing; written pixels are counted.
    pub fn new(frame: &'t mut Framebuffer<'_>, depth: &'t mut DepthBuffer<'_, D>) -> Self {
        RasterTarget::with_count(frame, depth, CountWritten)
    }
}

impl<'t, D: DepthValue, C: WrittenCount> RasterTarget<'t, D, C> {
    /// Borrows `frame` and `depth` for drawing, counting written pixels as `count` says.
    pub fn with_count(
        frame: &'t mut Framebuffer<'_>,
        depth: &'t mut DepthBuffer<'_, D>,
        count: C,
    ) -> Self {
        let buffers = drawable_window(frame, depth);
        RasterTarget {
            window: buffers,
            buffers,
            targets: Targets::new(frame, depth),
            count,
        }
    }
}

impl<D, C> RasterTarget<'_, D, C> {
    /// Draws from now on only inside `window` ∩ the buffers' window: the pixels a triangle
    /// then writes are exactly those of the whole triangle inside it (the fill clips spans to
    /// the window, the tiny writer declines a triangle whose columns leave it). The visibility
    /// methods draw parts of triangles this way (a band of rows, one side of a split, an area
    /// of Warnock's subdivision).
    #[inline]
    pub(crate) fn restrict(&mut self, window: Window) {
        self.window = self.buffers.intersect(&window);
    }

    /// The window both buffers hold (what [`Self::restrict`] intersects with).
    #[inline]
    pub(crate) fn buffers(&self) -> Window {
        self.buffers
    }
}

/// What draws one triangle: the span kind ([`span_kind`]) and whether the tiny-triangle writer
/// is tried first ([`tiny_kind`]), composed by `plan` for the tests. Decided once per
/// triangle, before any set-up; the size class (tiny box, small
/// plane, general plane) follows from the set-up itself, each smaller class falling back to
/// the next when the triangle does not fit it.
#[cfg(test)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TrianglePlan {
    /// What each span writes.
    pub(crate) kind: Kind,
    /// Whether, and how, small triangles take the tiny-triangle writer.
    pub(crate) tiny: Tiny,
}

/// The span kinds of [`draw_triangle_on`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Constant depth and colour: no plane at all (`TriangleSpans::constant`).
    Constant,
    /// Flat colour over the exact depth plane (one attribute, `FlatKind`).
    Flat,
    /// Exact Gouraud: depth and luminance planes (`ExactKind`).
    Exact,
    /// Fast Gouraud: the exact depth, a 16.16 luminance (`FastKind`).
    Fast,
}

/// Whether the tiny-triangle writer (`shade/tiny_triangle.rs`) is tried first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Tiny {
    /// Not for this triangle (or not on this core).
    No,
    /// With the ramp's first index added to the luminance and stored as it is (a 256-level
    /// ramp).
    Direct,
    /// With the luminance mapped per pixel by the quantizer (exact Gouraud through any other
    /// ramp or a dithered one).
    Mapped,
}

/// The one decision of how a triangle is drawn (the two halves below, composed): from the
/// shading mode asked for, whether the depth and the luminance are constant over the triangle
/// (equal vertex values), whether the quantizer is a 256-level ramp whose index can be
/// interpolated directly ([`Quantizer::offset`]), and whether the core takes the tiny-triangle
/// writer (`arith::TINY_WRITER`). [`draw_triangle_on`] asks the halves in turn, so that the
/// quantizer is consulted only for triangles that may take the tiny writer.
#[cfg(test)]
pub(crate) const fn plan(
    mode: ShadeMode,
    depth_constant: bool,
    luminance_constant: bool,
    direct_ramp: bool,
    tiny_writer: bool,
) -> TrianglePlan {
    let kind = span_kind(mode, depth_constant, luminance_constant);
    let tiny = if tiny_writer && kind.may_take_tiny() {
        tiny_kind(kind, direct_ramp)
    } else {
        Tiny::No
    };
    TrianglePlan { kind, tiny }
}

/// The span kind: a constant luminance is flat whatever the mode, and flat at constant depth
/// needs no plane ([`Kind::Constant`]); Phong without normals is exact Gouraud.
#[inline(always)]
pub(crate) const fn span_kind(
    mode: ShadeMode,
    depth_constant: bool,
    luminance_constant: bool,
) -> Kind {
    match mode {
        _ if luminance_constant => {
            if depth_constant {
                Kind::Constant
            } else {
                Kind::Flat
            }
        }
        ShadeMode::Flat if depth_constant => Kind::Constant,
        ShadeMode::Flat => Kind::Flat,
        ShadeMode::GouraudFast => Kind::Fast,
        ShadeMode::GouraudExact | ShadeMode::Phong => Kind::Exact,
    }
}

impl Kind {
    /// True for the kinds the tiny-triangle writer draws: exact Gouraud and flat colour over a
    /// depth plane (never fast Gouraud, nor constant depth and colour).
    #[inline(always)]
    pub(crate) const fn may_take_tiny(self) -> bool {
        matches!(self, Kind::Exact | Kind::Flat)
    }
}

/// How a kind that [`may take the tiny writer`](Kind::may_take_tiny) takes it: exact Gouraud
/// through any quantizer, flat colour only through a 256-level ramp (a flat triangle of
/// another ramp maps once per span on the general path, which measured faster: the lit flat
/// sphere of a 32-level ramp +17 % through the tiny writer).
#[inline(always)]
pub(crate) const fn tiny_kind(kind: Kind, direct_ramp: bool) -> Tiny {
    match kind {
        _ if direct_ramp => Tiny::Direct,
        Kind::Exact => Tiny::Mapped,
        _ => Tiny::No,
    }
}

/// [`draw_triangle_quantized`] into a prepared [`RasterTarget`] (the renderer's form: one
/// target per object and band). The one place that decides which path draws a triangle:
/// `plan`, then the set-up of that path.
///
/// Vertices outside the raster's range (`|x|, |y| ≤ 2^28 − 1` sub-pixel units, `S ≤ 16`) are
/// [`DrawError::Fill`] with [`FillError::CoordinateOutOfRange`], checked here once, before any
/// arithmetic (the plane set-up and the fill that follow rely on it and do not check again).
/// Any triangle within the range is drawn, whatever its size.
pub(crate) fn draw_triangle_on<D: DepthValue, Q: Quantizer, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    mode: ShadeMode,
    quantizer_at: impl Fn(i32, i32) -> Q,
) -> Result<(u32, u32), DrawError> {
    check_range(&v).map_err(DrawError::Fill)?;
    Ok(draw_in_range(target, v, values, mode, quantizer_at))
}

/// [`draw_in_range`] for a triangle with a vertex depth above [`DepthValue::MAX_DEPTH32`]: the
/// depths clamped to it, then drawn as any other (set up again: rare, and one body of the
/// writer kept).
#[cold]
#[inline(never)]
fn draw_clamped<D: DepthValue, Q: Quantizer, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    mode: ShadeMode,
    quantizer_at: impl Fn(i32, i32) -> Q,
) -> (u32, u32) {
    let values = values.map(|[z, l]| [z.min(D::MAX_DEPTH32), l]);
    draw_in_range(target, v, values, mode, quantizer_at)
}

/// [`draw_triangle_on`] for vertices already within the raster's range: the renderer's
/// consumers call it with projected vertices, which the projector keeps within
/// `±(2^28 − 1)` (checked there once per vertex, asserted by the set-up in checked builds).
/// Cannot fail: every triangle of the range is drawn.
///
/// The one place that decides which path draws a triangle: its set-up, the span kind
/// ([`span_kind`]), the tiny writer where it applies ([`tiny_kind`], [`draw_tiny`]), else
/// the plane of the kind ([`draw_general`]).
pub(crate) fn draw_in_range<D: DepthValue, Q: Quantizer, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    mode: ShadeMode,
    quantizer_at: impl Fn(i32, i32) -> Q,
) -> (u32, u32) {
    // Depths clamp to the deepest value that stores below FAR, so a surface just before `far`
    // still wins against the clear (target::depth's module doc). Rare, so out of line: three
    // clamped values kept in this writer took registers from its span loops (Cortex-M4
    // frame_sphere_fast +2.9 %).
    if values.iter().any(|[z, _]| *z > D::MAX_DEPTH32) {
        return draw_clamped(target, v, values, mode, quantizer_at);
    }
    let t = TriangleSetup::in_range(v);
    // Luminances above 255 saturate at the vertices: every interpolated value then lies in
    // 0..=255, which the span loops rely on ([`InRange`]).
    let values = values.map(|[z, l]| [z, l.min(255)]);
    // A plane is flat exactly when its vertex values are equal (the triangle has area).
    let constant = |i: usize| values[0][i] == values[1][i] && values[0][i] == values[2][i];
    // The depth plane's flatness matters only for a flat luminance (`span_kind`): tested
    // there alone, so that Gouraud triangles do not pay its four compares.
    let luminance_constant = constant(1);
    // A sample of no bits (`NoDepth`: the visibility methods without a depth buffer) has
    // one value, which `from_depth32` gives for every depth: the depth is constant over any
    // triangle, and a flat one needs no plane at all (`Kind::Constant`; the flat kind's depth
    // plane cost about 80 instructions a span on the Cortex-M4 for nothing).
    let depth_constant =
        (luminance_constant || mode == ShadeMode::Flat) && (D::BITS == 0 || constant(0));
    let kind = span_kind(mode, depth_constant, luminance_constant);
    if TINY_WRITER && kind.may_take_tiny() {
        if let Some(drawn) = draw_tiny(target, &t, values, kind, &quantizer_at) {
            return drawn;
        }
    }
    // (After the tiny writer, which tests the columns itself and clips the rows.)
    if !bounds_meet(&t, &target.window) {
        return (0, 0);
    }
    draw_general(target, &t, values, kind, quantizer_at)
}

/// The luminance of a flat triangle: the vertices' one value, or their rounded mean.
#[inline(always)]
fn flat_luminance(values: &[[u32; 2]; 3]) -> u32 {
    let l = values.map(|[_, l]| l);
    if l[0] == l[1] && l[0] == l[2] {
        l[0]
    } else {
        (l[0] + l[1] + l[2] + 1) / 3
    }
}

/// The tiny-triangle writer for a kind that may take it, as [`tiny_kind`] says, or `None`
/// where it does not apply (the general path draws the triangle then).
#[inline(always)]
fn draw_tiny<D: DepthValue, Q: Quantizer, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    t: &TriangleSetup<S>,
    values: [[u32; 2]; 3],
    kind: Kind,
    quantizer_at: &impl Fn(i32, i32) -> Q,
) -> Option<(u32, u32)> {
    let v0 = t.given[0];
    let first = quantizer_at(v0.x >> S, v0.y >> S).offset();
    match tiny_kind(kind, first.is_some()) {
        Tiny::Direct => {
            let first = first.unwrap_or(0) as u32;
            let values = if kind == Kind::Flat {
                let flat = flat_luminance(&values) + first;
                values.map(|[z, _]| [z, flat])
            } else {
                values.map(|[z, l]| [z, l + first])
            };
            let tiny = TinyTriangle::<S>::new(t, values, &target.window)?;
            Some(tiny.draw(&mut target.targets, target.count, &|_, _| Direct))
        }
        Tiny::Mapped => tiny_mapped(target, *t, values, quantizer_at),
        Tiny::No => None,
    }
}

/// The general path of [`draw_in_range`]: the span loop of `kind` over the fill, with the plane
/// the kind needs.
#[inline(always)]
fn draw_general<D: DepthValue, Q: Quantizer, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    t: &TriangleSetup<S>,
    values: [[u32; 2]; 3],
    kind: Kind,
    quantizer_at: impl Fn(i32, i32) -> Q,
) -> (u32, u32) {
    let spans = TriangleSpans {
        t: *t,
        window: target.window,
        targets: &mut target.targets,
        count: target.count,
    };
    match kind {
        Kind::Constant => spans.constant(values[0][0], flat_luminance(&values), quantizer_at),
        Kind::Flat => spans.planar(
            values.map(|a| [a[0]]),
            FlatKind {
                luminance: Constant(flat_luminance(&values)),
                quantizer_at,
            },
        ),
        Kind::Exact | Kind::Fast => {
            // A 256-level ramp adds its first index: interpolating `first + lum` gives the
            // same values shifted (exact rounding and the 16.16 start commute with adding an
            // integer), and the loops store them as they are, with two fewer live values.
            let v0 = t.given[0];
            if let Some(first) = quantizer_at(v0.x >> S, v0.y >> S).offset() {
                let values = values.map(|[z, l]| [z, l + first as u32]);
                return match kind {
                    Kind::Fast => spans.planar(values, FastKind(|_, _| Direct)),
                    _ => spans.planar(values, ExactKind(|_, _| Direct)),
                };
            }
            match kind {
                Kind::Fast => spans.planar(values, FastKind(quantizer_at)),
                _ => spans.planar(values, ExactKind(quantizer_at)),
            }
        }
    }
}

/// Triangle `t` with the `N` vertex attributes `values` (attribute 0 the depth, at most
/// [`DepthValue::MAX_DEPTH32`]) drawn by span kind `kind` over the general or wide plane, each
/// span started exactly ([`Exact`]): the writer of kinds whose every attribute is
/// interpolated per pixel (Phong's seven).
#[inline(always)]
pub(crate) fn draw_general_exact<
    D: DepthValue,
    C: WrittenCount,
    K: SpanKind<N>,
    const N: usize,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C>,
    t: &TriangleSetup<S>,
    values: [[u32; N]; 3],
    kind: K,
) -> (u32, u32) {
    let spans = TriangleSpans {
        t: *t,
        window: target.window,
        targets: &mut target.targets,
        count: target.count,
    };
    spans.general(values, kind, false)
}

/// The tiny-triangle writer for luminances of `0..=255` mapped by `quantizer_at` (a ramp of
/// fewer than 256 levels, or dithered), or `None` where it does not apply. Out of line: a
/// second set-up inlined into [`draw_in_range`] cost its 256-level path registers
/// (measured on the Cortex-M4: the standard bunny frame +1.4 %).
#[inline(never)]
fn tiny_mapped<D: DepthValue, Q: Quantizer, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    t: TriangleSetup<S>,
    values: [[u32; 2]; 3],
    quantizer_at: &impl Fn(i32, i32) -> Q,
) -> Option<(u32, u32)> {
    let tiny = TinyTriangle::<S>::new(&t, values, &target.window)?;
    Some(tiny.draw(&mut target.targets, target.count, quantizer_at))
}

/// The two writers the tiny writer's tests compare (`shade/tiny_triangle.rs`): set-up `t`
/// with `values` drawn into `target` by the tiny writer (`None` where it does not apply), or
/// by the general path's exact planes (`TriangleSpans::planar` with [`ExactKind`]).
#[cfg(test)]
pub(super) fn draw_tiny_or_planar<D: DepthValue, Q: Quantizer, C: WrittenCount, const S: u32>(
    target: &mut RasterTarget<'_, D, C>,
    t: TriangleSetup<S>,
    values: [[u32; 2]; 3],
    quantizer_at: impl Fn(i32, i32) -> Q,
    tiny: bool,
) -> Option<(u32, u32)> {
    if tiny {
        return tiny_mapped(target, t, values, &quantizer_at);
    }
    let spans = TriangleSpans {
        t,
        window: target.window,
        targets: &mut target.targets,
        count: target.count,
    };
    Some(spans.planar(values, ExactKind(quantizer_at)))
}

/// Bounding-box width (pixels) from which a triangle's spans use [`ExactRun`].
const MIN_RUN_WIDTH: u32 = 16;

/// How a span loop gets its exact interpolants from the exact starts `E` of its plane
/// ([`Exact`], or [`ExactWide`](super::attributes::ExactWide) for a [`WidePlane`]): as they
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

/// What one span of a triangle writes, given its `N` exact interpolants at the span start:
/// chosen once per triangle, so the span loop holds one kind only. The kinds: constant depth
/// and colour (no plane: [`TriangleSpans::constant`]), [`FlatKind`], [`ExactKind`],
/// [`FastKind`] and [`DepthOnlyKind`] here, and Phong's (`shade/phong.rs`).
pub(crate) trait SpanKind<const N: usize> {
    /// Writes the span (`colours`, `depths`: its pixels) starting at pixel `(x, y)`; `attrs[0]`
    /// is the depth. Returns the pixels written (0 when `count` does not count them).
    fn write<D: DepthValue, I: Interpolant, St: SpanStarts<N>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: &mut [D],
        attrs: [I; N],
        starts: &St,
        at: (i32, i32),
        count: C,
    ) -> u32;
}

/// Flat colour over the exact depth plane (one attribute).
struct FlatKind<QF> {
    luminance: Constant,
    quantizer_at: QF,
}

impl<Q: Quantizer, QF: Fn(i32, i32) -> Q> SpanKind<1> for FlatKind<QF> {
    #[inline(always)]
    fn write<D: DepthValue, I: Interpolant, St: SpanStarts<1>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: &mut [D],
        [z]: [I; 1],
        _: &St,
        (x, y): (i32, i32),
        count: C,
    ) -> u32 {
        let shading = Gouraud {
            luminance: self.luminance,
            quantizer: (self.quantizer_at)(x, y),
        };
        depth_span(colours, depths, z, shading, count)
    }
}

/// Exact Gouraud: depth and luminance planes.
struct ExactKind<QF>(QF);

impl<Q: Quantizer, QF: Fn(i32, i32) -> Q> SpanKind<2> for ExactKind<QF> {
    #[inline(always)]
    fn write<D: DepthValue, I: Interpolant, St: SpanStarts<2>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: &mut [D],
        [z, luminance]: [I; 2],
        _: &St,
        (x, y): (i32, i32),
        count: C,
    ) -> u32 {
        let shading = InRange {
            luminance,
            quantizer: (self.0)(x, y),
        };
        depth_span(colours, depths, z, shading, count)
    }
}

/// Fast Gouraud: the exact depth, the luminance as a 16.16 [`Dda`](super::attributes::Dda)
/// (its start costs a division: only this kind computes it).
struct FastKind<QF>(QF);

impl<Q: Quantizer, QF: Fn(i32, i32) -> Q> SpanKind<2> for FastKind<QF> {
    #[inline(always)]
    fn write<D: DepthValue, I: Interpolant, St: SpanStarts<2>, C: WrittenCount>(
        &self,
        colours: &mut [u8],
        depths: &mut [D],
        [z, _]: [I; 2],
        starts: &St,
        (x, y): (i32, i32),
        count: C,
    ) -> u32 {
        // The 16.16 value starts within 2^-16 + 1/2 above the exact one and its truncated
        // increment only lowers it: it stays in 0..=255 with the vertex values.
        let shading = InRange {
            luminance: starts.dda_at(1, x, y),
            quantizer: (self.0)(x, y),
        };
        depth_span(colours, depths, z, shading, count)
    }
}

/// Depth only: the exact depth plane (one attribute), the nearer depth stored, no colour
/// ([`depth_only_span`]). Drawn into a [`DepthTarget`], whose colour slices are empty.
struct DepthOnlyKind;

impl SpanKind<1> for DepthOnlyKind {
    #[inline(always)]
    fn write<D: DepthValue, I: Interpolant, St: SpanStarts<1>, C: WrittenCount>(
        &self,
        _: &mut [u8],
        depths: &mut [D],
        [z]: [I; 1],
        _: &St,
        _: (i32, i32),
        count: C,
    ) -> u32 {
        depth_only_span(depths, z, count)
    }
}

/// A depth buffer without a frame, prepared once for many depth-only triangles
/// ([`draw_depth_only`]): a shadow map's samples, `width × height` from row 0.
#[derive(Debug)]
pub(crate) struct DepthTarget<'t, D> {
    window: Window,
    targets: DepthTargets<'t, D>,
}

impl<'t, D: DepthValue> DepthTarget<'t, D> {
    /// Borrows `samples` (at least `width × height`, row by row) for drawing depths.
    pub(crate) fn new(samples: &'t mut [D], width: u16, height: u16) -> Self {
        DepthTarget {
            window: Window::new(0, 0, width as i32, height as i32),
            targets: DepthTargets::new(samples, width as usize),
        }
    }
}

/// The depth-only span kind ([`DepthOnlyKind`]) of set-up triangle `t` with vertex depths
/// `depths` (any `u32`: a depth whose stored value is `FAR` stores nothing, as the strict test
/// against a cleared sample fails) into `target`, through the writer's plane choice (small,
/// general with its runs, or wide: the same exact value at every texel) and span loop.
/// Returns the samples the triangle covers inside the target.
pub(crate) fn draw_depth_only<D: DepthValue, const S: u32>(
    target: &mut DepthTarget<'_, D>,
    t: &TriangleSetup<S>,
    depths: [u32; 3],
) -> u32 {
    let spans = TriangleSpans {
        t: *t,
        window: target.window,
        targets: &mut target.targets,
        count: SkipWritten,
    };
    spans.planar(depths.map(|z| [z]), DepthOnlyKind).0
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
struct TriangleSpans<'a, T, C, const S: u32> {
    t: TriangleSetup<S>,
    window: Window,
    targets: &'a mut T,
    count: C,
}

impl<T: SpanTarget, C: WrittenCount, const S: u32> TriangleSpans<'_, T, C, S> {
    /// Constant depth `z` and flat luminance `lum`: no plane, any size (a zero-area triangle
    /// covers nothing in the fill).
    #[inline(always)]
    fn constant<Q: Quantizer>(
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
    fn planar<K: SpanKind<N>, const N: usize>(self, values: [[u32; N]; 3], kind: K) -> (u32, u32) {
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
    fn general<K: SpanKind<N>, const N: usize>(
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

/// The pixels both buffers hold (a band's rows, the frame's width).
#[inline(always)]
pub(crate) fn drawable_window<D: DepthValue>(
    frame: &Framebuffer<'_>,
    depth: &DepthBuffer<'_, D>,
) -> Window {
    frame.window().intersect(&Window::new(
        0,
        depth.top(),
        depth.width() as i32,
        depth.top() + depth.height() as i32,
    ))
}

/// True when the bounding box of `t` (rounded outward to pixels) meets `window`.
#[inline(always)]
fn bounds_meet<const S: u32>(t: &TriangleSetup<S>, window: &Window) -> bool {
    let ([x_lo, x_hi], [y_lo, y_hi]) = (t.x, t.y);
    (x_hi >> S) >= window.x0
        && (x_lo >> S) < window.x1
        && (y_hi >> S) >= window.y0
        && (y_lo >> S) < window.y1
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: i32, y: i32) -> SubpixelPoint<4> {
        SubpixelPoint::from_pixel(x, y)
    }

    /// Vertices past the raster's range are an error before any plane arithmetic (the
    /// products of i32::MIN/MAX coordinates overflowed in the planes' set-up), at every
    /// extreme and in both builds (the suite runs with overflow checks too).
    #[test]
    fn out_of_range_vertices_are_errors_before_set_up() {
        let mut px = [0u8; 16 * 16];
        let mut zs = [0u16; 16 * 16];
        let mut fb = Framebuffer::new(&mut px, 16, 16).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, 16, 16).unwrap();
        let p = SubpixelPoint::<4>::new;
        let far = (1 << 28) - 1;
        let values = [[1u32 << 20, 10], [1 << 21, 200], [1 << 22, 90]];
        for bad in [i32::MIN, i32::MAX, far + 1, -far - 1] {
            for k in 0..3 {
                let mut v = [p(0, 0), p(160, 0), p(0, 160)];
                v[k] = if k == 1 { p(bad, 3) } else { p(5, bad) };
                for mode in [
                    ShadeMode::Flat,
                    ShadeMode::GouraudExact,
                    ShadeMode::GouraudFast,
                ] {
                    let r = draw_triangle(&mut fb, &mut zb, v, values, LuminanceRamp::GREY, mode);
                    assert_eq!(
                        r,
                        Err(DrawError::Fill(FillError::CoordinateOutOfRange {
                            vertex: k
                        })),
                        "{bad} at {k}, {mode:?}"
                    );
                }
            }
        }
        // The range's ends themselves pass the check (the triangle may still be too large for
        // the planes: that is the other error, not a range error).
        let v = [p(far, far), p(-far, far), p(far, -far)];
        let r = draw_triangle(
            &mut fb,
            &mut zb,
            v,
            values,
            LuminanceRamp::GREY,
            ShadeMode::Flat,
        );
        assert!(!matches!(r, Err(DrawError::Fill(_))), "{r:?}");
    }

    /// The dispatch decisions, as a table: each row is what the module doc and the span
    /// kinds promise for one combination (mode; constant depth, constant luminance, 256-level
    /// ramp, tiny writer on the core).
    #[test]
    fn plan_decides_as_documented() {
        use ShadeMode::*;
        let p = |kind, tiny| TrianglePlan { kind, tiny };
        let rows = [
            // A constant luminance is flat whatever the mode; at constant depth, no plane.
            (
                (GouraudExact, true, true, true, true),
                p(Kind::Constant, Tiny::No),
            ),
            (
                (Phong, false, true, true, true),
                p(Kind::Flat, Tiny::Direct),
            ),
            (
                (GouraudFast, false, true, false, true),
                p(Kind::Flat, Tiny::No),
            ),
            ((Flat, true, false, true, true), p(Kind::Constant, Tiny::No)),
            (
                (Flat, false, false, true, true),
                p(Kind::Flat, Tiny::Direct),
            ),
            ((Flat, false, false, false, true), p(Kind::Flat, Tiny::No)),
            // Phong without normals is exact Gouraud; exact takes the tiny writer through
            // any quantizer, fast never does.
            (
                (Phong, false, false, true, true),
                p(Kind::Exact, Tiny::Direct),
            ),
            (
                (GouraudExact, true, false, false, true),
                p(Kind::Exact, Tiny::Mapped),
            ),
            (
                (GouraudFast, false, false, true, true),
                p(Kind::Fast, Tiny::No),
            ),
            // Cores without the tiny writer never try it.
            (
                (GouraudExact, false, false, true, false),
                p(Kind::Exact, Tiny::No),
            ),
            ((Flat, false, false, true, false), p(Kind::Flat, Tiny::No)),
        ];
        for ((mode, z, l, direct, tiny), expected) in rows {
            assert_eq!(
                plan(mode, z, l, direct, tiny),
                expected,
                "{mode:?} {z} {l} {direct}"
            );
        }
    }

    /// A [`SkipWritten`] target draws exactly what a counting one draws, covers the same
    /// pixels and reports 0 written, for every span kind (constant depth and colour with its
    /// 16-pixel blocks, flat over a depth plane, exact and fast Gouraud), the second triangle
    /// partly hidden behind the first.
    #[test]
    fn skip_written_draws_the_same_pixels() {
        let front = [p(0, 0), p(40, 0), p(0, 40)];
        let back = [p(4, 4), p(40, 10), p(10, 40)];
        for mode in [
            ShadeMode::Flat,
            ShadeMode::GouraudExact,
            ShadeMode::GouraudFast,
        ] {
            for slope in [0u32, 1 << 24] {
                let draw = |count: bool| {
                    let mut px = [0u8; 40 * 40];
                    let mut zs = [0u16; 40 * 40];
                    let mut fb = Framebuffer::new(&mut px, 40, 40).unwrap();
                    let mut zb = DepthBuffer::new(&mut zs, 40, 40).unwrap();
                    zb.clear();
                    let mut totals = (0, 0);
                    for (t, z) in [(front, 1u32 << 28), (back, 3 << 28)] {
                        let values = [[z, 10], [z + slope, 250], [z + 2 * slope, 90]];
                        let (c, w) = if count {
                            let mut target = RasterTarget::new(&mut fb, &mut zb);
                            draw_triangle_on(&mut target, t, values, mode, |_, _| {
                                LuminanceRamp::GREY
                            })
                        } else {
                            let mut target =
                                RasterTarget::with_count(&mut fb, &mut zb, SkipWritten);
                            draw_triangle_on(&mut target, t, values, mode, |_, _| {
                                LuminanceRamp::GREY
                            })
                        }
                        .unwrap();
                        totals = (totals.0 + c, totals.1 + w);
                    }
                    (px, zs, totals)
                };
                let (px, zs, (covered, written)) = draw(true);
                let (px2, zs2, (covered2, written2)) = draw(false);
                assert!(px == px2 && zs == zs2, "{mode:?} slope {slope}");
                assert_eq!((covered2, written2), (covered, 0), "{mode:?} slope {slope}");
                // The back triangle is partly hidden: fewer pixels written than covered.
                assert!(
                    written > 800 && written < covered,
                    "{mode:?} slope {slope}: {written} of {covered}"
                );
            }
        }
    }

    /// Two overlapping triangles at constant depths: the nearer wins whatever the order, and
    /// equal depths keep the first drawn (strict test).
    #[test]
    fn nearer_wins_in_any_order() {
        let near = [p(0, 0), p(16, 0), p(0, 16)];
        let far = [p(2, 2), p(14, 2), p(2, 14)];
        for order in [[true, false], [false, true]] {
            let mut px = [0u8; 16 * 16];
            let mut zs = [0u16; 16 * 16];
            let mut fb = Framebuffer::new(&mut px, 16, 16).unwrap();
            let mut zb = DepthBuffer::new(&mut zs, 16, 16).unwrap();
            zb.clear();
            for is_near in order {
                let (tri, d, lum) = if is_near {
                    (near, 1000u32 << 16, 200)
                } else {
                    (far, 2000u32 << 16, 100)
                };
                draw_triangle(
                    &mut fb,
                    &mut zb,
                    tri,
                    [[d, lum]; 3],
                    LuminanceRamp::GREY,
                    ShadeMode::GouraudExact,
                )
                .unwrap();
            }
            assert_eq!(fb.pixel(3, 3), Some(200));
            assert_eq!(zb.get(3, 3), Some(1000));
            assert_eq!(fb.pixel(15, 15), Some(0));
            assert_eq!(zb.get(15, 15), Some(u16::MAX));
        }
        // Equal depth: the first triangle drawn keeps the pixel.
        let mut px = [0u8; 16 * 16];
        let mut zs = [0u32; 16 * 16];
        let mut fb = Framebuffer::new(&mut px, 16, 16).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, 16, 16).unwrap();
        zb.clear();
        draw_triangle(
            &mut fb,
            &mut zb,
            near,
            [[7, 10]; 3],
            LuminanceRamp::GREY,
            ShadeMode::Flat,
        )
        .unwrap();
        draw_triangle(
            &mut fb,
            &mut zb,
            far,
            [[7, 20]; 3],
            LuminanceRamp::GREY,
            ShadeMode::Flat,
        )
        .unwrap();
        assert_eq!(fb.pixel(3, 3), Some(10));
    }

    /// Gouraud luminance through the ramp: a horizontal gradient 0 → 255 across 16 pixels.
    #[test]
    fn luminance_gradient_and_band_clipping() {
        let tri = [p(0, 0), p(16, 0), p(0, 16)];
        let vals = [[5u32, 0], [5, 256], [5, 0]];
        let mut px = [0u8; 16 * 4];
        let mut zs = [0u16; 16 * 4];
        // A band holding rows 4..8 only: rows outside are not touched, no panic.
        let mut fb = Framebuffer::band(&mut px, 16, 4, 4).unwrap();
        let mut zb = DepthBuffer::band(&mut zs, 16, 4, 4).unwrap();
        zb.clear();
        let (covered, written) = draw_triangle(
            &mut fb,
            &mut zb,
            tri,
            vals,
            LuminanceRamp::GREY,
            ShadeMode::GouraudExact,
        )
        .unwrap();
        // Rows 4..8 of the triangle x + y < 16 cover 12 + 11 + 10 + 9 pixels.
        assert_eq!(covered, 42);
        assert_eq!(written, 42);
        // The vertex value 256 saturates to 255 at the vertex: the luminance at (x, y) is
        // 255·x/16, correctly rounded.
        for y in 4..8 {
            for x in 0..(16 - y) {
                let want = (255 * x as u32 + 8) / 16;
                assert_eq!(fb.pixel(x, y), Some(want as u8), "({x},{y})");
            }
        }
    }

    /// A 256-level ramp's triangles interpolate `first + lum` directly
    /// ([`Quantizer::offset`]): the same pixels as mapping each luminance through the ramp,
    /// wrap-around past index 255 included, for exact and fast Gouraud.
    #[test]
    fn offset_ramps_draw_what_the_ramp_maps() {
        /// The same mapping as the ramp, without offering the offset.
        #[derive(Clone, Copy)]
        struct Mapped(LuminanceRamp);
        impl Quantizer for Mapped {
            const IS_CONSTANT: bool = true;
            fn index(&self, lum: u32) -> u8 {
                self.0.index(lum)
            }
            fn step(&mut self) {}
        }
        let mut rng = crate::test_rng::XorShift(0x2545_F491_4F6C_DD1Du64);
        let mut rnd = |m: u32| (rng.next_u64() % m as u64) as u32;
        let mut pixels = 0;
        for _ in 0..200 {
            let tri = [0; 3].map(|_| {
                SubpixelPoint::<4>::new(rnd(24 * 16) as i32 - 64, rnd(24 * 16) as i32 - 64)
            });
            let values = [0; 3].map(|_| [rnd(u32::MAX), rnd(256)]);
            let ramp = LuminanceRamp {
                first: rnd(256) as u8,
                levels: 256,
            };
            for mode in [ShadeMode::GouraudExact, ShadeMode::GouraudFast] {
                let draw = |mapped: bool| {
                    let mut px = [0u8; 20 * 20];
                    let mut zs = [0u32; 20 * 20];
                    let mut fb = Framebuffer::new(&mut px, 20, 20).unwrap();
                    let mut zb = DepthBuffer::new(&mut zs, 20, 20).unwrap();
                    zb.clear();
                    let r = if mapped {
                        draw_triangle_quantized(&mut fb, &mut zb, tri, values, mode, |_, _| {
                            Mapped(ramp)
                        })
                    } else {
                        draw_triangle_quantized(&mut fb, &mut zb, tri, values, mode, |_, _| ramp)
                    };
                    (r, px)
                };
                let (direct, mapped) = (draw(false), draw(true));
                assert_eq!(direct, mapped, "{tri:?} {values:?} {ramp:?} {mode:?}");
                pixels += direct.0.map_or(0, |(covered, _)| covered);
            }
        }
        assert!(pixels > 10_000, "{pixels}");
    }

    /// Luminances above 255 saturate at the vertices, in every mode and with the dithered
    /// ramp: far out-of-range values give the top of the ramp, never a wrapped index.
    #[test]
    fn out_of_range_luminance_saturates_at_the_vertices() {
        let tri = [p(0, 0), p(16, 0), p(0, 16)];
        let ramp = LuminanceRamp {
            first: 10,
            levels: 32,
        };
        for mode in [
            ShadeMode::Flat,
            ShadeMode::GouraudExact,
            ShadeMode::GouraudFast,
            ShadeMode::Phong,
        ] {
            for values in [[[5u32, 300]; 3], [[5, 255], [5, 1 << 20], [5, u32::MAX]]] {
                for dithered in [false, true] {
                    let mut px = [0u8; 16 * 16];
                    let mut zs = [0u16; 16 * 16];
                    let mut fb = Framebuffer::new(&mut px, 16, 16).unwrap();
                    let mut zb = DepthBuffer::new(&mut zs, 16, 16).unwrap();
                    zb.clear();
                    let (covered, written) = if dithered {
                        draw_triangle_quantized(&mut fb, &mut zb, tri, values, mode, |x, y| {
                            crate::shade::dither::Bayer4::at(ramp, x, y)
                        })
                    } else {
                        draw_triangle_quantized(&mut fb, &mut zb, tri, values, mode, |_, _| ramp)
                    }
                    .unwrap();
                    assert_eq!((covered, written), (136, 136));
                    for y in 0..16 {
                        for x in 0..(16 - y) {
                            assert_eq!(fb.pixel(x, y), Some(41), "{mode:?} ({x},{y})");
                        }
                    }
                }
            }
        }
    }

    /// The depth-only kind ([`draw_depth_only`]: the writer's plane choice, small, general with
    /// its runs or wide, and the span loop without colour) stores at every texel what the exact
    /// plane evaluated there directly gives ([`WidePlane::exact`] at each texel of the fill,
    /// no stepping), where it is nearer than the stored sample, for 16- and 32-bit samples over
    /// random contents, and reports the covered texels; triangles of every size class, depths
    /// at both ends of the range (those stored as `FAR` are never stored) and zero area.
    #[test]
    fn depth_only_stores_the_exact_nearer_depth() {
        fn check<D: DepthValue + core::fmt::Debug>(
            rng: &mut crate::test_rng::XorShift,
            to: impl Fn(u64) -> D,
        ) -> u32 {
            const W: usize = 48;
            const H: usize = 40;
            let mut drawn = 0;
            for i in 0..3000 {
                // Boxes from a few texels to far beyond the map (general and wide planes).
                let reach = [40i64, 400, 2000, 1 << 20, 1 << 27][i % 5];
                let mut v = [0; 3].map(|_| {
                    let mut c = |n: usize| rng.range(-reach, reach + ((n as i64) << 4));
                    SubpixelPoint::<4>::new(c(W) as i32, c(H) as i32)
                });
                if i % 97 == 0 {
                    v[2] = v[1]; // zero area
                }
                let depths = [0; 3].map(|_| match rng.below(8) {
                    0 => u32::MAX - rng.below(1 << 17) as u32,
                    1 => rng.below(1 << 17) as u32,
                    _ => rng.next_u64() as u32,
                });
                let init: [D; W * H] = core::array::from_fn(|_| to(rng.next_u64()));
                let mut got = init;
                let t = TriangleSetup::in_range(v);
                let covered = draw_depth_only(
                    &mut DepthTarget::new(&mut got, W as u16, H as u16),
                    &t,
                    depths,
                );
                let mut want = init;
                let mut want_covered = 0;
                if let Ok(plane) = WidePlane::<1, 4>::of(&t, depths.map(|z| [z])) {
                    let window = Window::new(0, 0, W as i32, H as i32);
                    fill_setup(&t, &window, |s| {
                        for x in s.x0..s.x1 {
                            let d = D::from_depth32(plane.exact(0, x, s.y).value());
                            let stored = &mut want[s.y as usize * W + x as usize];
                            if d.nearer(*stored) {
                                *stored = d;
                            }
                            want_covered += 1;
                        }
                    });
                }
                assert_eq!(got, want, "{v:?} {depths:?}");
                assert_eq!(covered, want_covered, "{v:?} {depths:?}");
                drawn += covered;
            }
            drawn
        }
        // Half the samples far (as a cleared map), the others anywhere.
        let mut rng = crate::test_rng::XorShift::new(0x5EED_0019);
        let drawn = check::<u16>(&mut rng, |r| {
            if r & 1 == 1 {
                u16::MAX
            } else {
                (r >> 16) as u16
            }
        });
        assert!(drawn > 500_000, "{drawn}");
        let drawn = check::<u32>(&mut rng, |r| {
            if r & 1 == 1 {
                u32::MAX
            } else {
                (r >> 32) as u32
            }
        });
        assert!(drawn > 500_000, "{drawn}");
    }
}
