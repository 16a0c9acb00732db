//! The decision: how a triangle is drawn, decided once per triangle, and the writers' entry
//! points.
//!
//! Role in the pipeline: the raster stage's triangle writer. [`draw_triangle`] sets the
//! triangle up once (`setup`: sorted vertices, twice-area, orientation, box, edges), decides
//! its span kind once (`draw_in_range`, the one dispatch point), and hands it to the tiny
//! writer (`tiny`) or to the span loop over the fill (`spans`), which sets up the exact
//! plane of the kind (attribute 0 is depth, attribute 1 luminance), takes the exact values at
//! each span start from it and runs one generic loop, `depth_span` (`span`): depth test
//! (strict, nearer wins, see [`DepthValue`]), palette index from a `Shading`, two stores.
//! Phong's seven attributes are one more span kind of the same loop (`PhongKind` in `kinds`,
//! drawn by [`draw_triangle_phong`] here through `draw_general_exact`), and
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
//! 256-level ramp, go one step further: the tiny-triangle writer (`raster/triangle/tiny.rs`)
//! sets up edges and both planes at once and draws each span out of line, for the same pixels
//! with far fewer values held across the rows (Cortex-M4 `frame_bunny` −19 %, `frame_sphere`
//! −11 %, 16-row bands of the bunny −13 %).
//!
//! Numeric contract: as the planes (`plane`); depth values are the 32-bit
//! normalised depth of the projection stage, stored through [`DepthValue::from_depth32`];
//! luminance is `0..=255` (vertex values above saturate to 255 at the vertices, so every
//! interpolated value is in range and the span loops map it without a test).

use super::interpolants::Constant;
use super::kinds::{DepthOnlyKind, ExactKind, FastKind, FlatKind, PhongKind, SpanKind};
use super::setup::TriangleSetup;
use super::slices::{DepthTarget, RasterTarget, SpanTarget};
use super::span::{Direct, LuminanceRamp, Quantizer, SkipWritten, WrittenCount};
use super::spans::TriangleSpans;
use super::textured::{TexCorner, TexturedKind};
use super::tiny::TinyTriangle;
use crate::arith::{TINY_FLAT, TINY_WRITER};
use crate::geometry::vector::Vec3;
use crate::lighting::phong;
use crate::lighting::{Illumination, Material};
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::raster::polygon::FillError;
use crate::raster::range::check_range;
use crate::raster::{SubpixelPoint, Window};
use crate::texture::Texturing;

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
    /// draws lit objects in this mode with [`draw_triangle_phong`](draw_triangle_phong).
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

/// Whether the tiny-triangle writer (`raster/triangle/tiny.rs`) is tried first.
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
pub(crate) fn draw_triangle_on<
    D: DepthValue,
    Q: Quantizer,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
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
fn draw_clamped<
    D: DepthValue,
    Q: Quantizer,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
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
pub(crate) fn draw_in_range<
    D: DepthValue,
    Q: Quantizer,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    mode: ShadeMode,
    quantizer_at: impl Fn(i32, i32) -> Q,
) -> (u32, u32) {
    // Depths clamp to the deepest value that stores below FAR, so a surface just before `far`
    // still wins against the clear (output::depth's module doc). Rare, so out of line: three
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
    if TINY_WRITER && kind.may_take_tiny() && (TINY_FLAT || kind != Kind::Flat) {
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
fn draw_tiny<
    D: DepthValue,
    Q: Quantizer,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
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
fn draw_general<
    D: DepthValue,
    Q: Quantizer,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
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

/// Draws a depth-tested textured triangle into a frame and its depth buffer: at vertex `i`,
/// `values[i] = [depth, luminance]` (the luminance read only when `texturing` is lit),
/// `uvs[i]` its Q8.8 texture coordinates and `weights[i]` its perspective weight (any scale
/// proportional to `1/z`, as the renderer's `A − D`; [`texture`](crate::texture) says how
/// the texel is chosen). Returns `(covered, written)` as [`draw_triangle`] does; vertices
/// outside the raster's range are [`DrawError::Fill`].
pub fn draw_triangle_textured<D: DepthValue, const S: u32>(
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    uvs: [[i16; 2]; 3],
    weights: [u64; 3],
    texturing: &Texturing<'_>,
) -> Result<(u32, u32), DrawError> {
    check_range(&v).map_err(DrawError::Fill)?;
    let corners = [0, 1, 2].map(|i| TexCorner {
        uv: uvs[i].map(i32::from),
        weight: weights[i],
    });
    let mut target = RasterTarget::new(frame, depth);
    Ok(draw_textured_on(&mut target, v, values, corners, texturing))
}

/// The textured span kind (`textured`) over the exact depth plane, and the luminance plane
/// when lit (`values[i] = [depth, luminance]`; depths clamp to [`DepthValue::MAX_DEPTH32`],
/// luminances to 255, as [`draw_in_range`] does), for vertices within the raster's range.
pub(crate) fn draw_textured_on<
    D: DepthValue,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
    v: [SubpixelPoint<S>; 3],
    values: [[u32; 2]; 3],
    corners: [TexCorner; 3],
    texturing: &Texturing<'_>,
) -> (u32, u32) {
    let t = TriangleSetup::in_range(v);
    if !bounds_meet(&t, &target.window) {
        return (0, 0);
    }
    let Some(kind) = TexturedKind::new(&t, corners, texturing) else {
        return (0, 0); // zero area: covers nothing
    };
    let values = values.map(|[z, l]| [z.min(D::MAX_DEPTH32), l.min(255)]);
    let spans = TriangleSpans {
        t,
        window: target.window,
        targets: &mut target.targets,
        count: target.count,
    };
    if texturing.shades.is_some() {
        spans.planar(values, kind)
    } else {
        spans.planar(values.map(|[z, _]| [z]), kind)
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
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
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
fn tiny_mapped<
    D: DepthValue,
    Q: Quantizer,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
    t: TriangleSetup<S>,
    values: [[u32; 2]; 3],
    quantizer_at: &impl Fn(i32, i32) -> Q,
) -> Option<(u32, u32)> {
    let tiny = TinyTriangle::<S>::new(&t, values, &target.window)?;
    Some(tiny.draw(&mut target.targets, target.count, quantizer_at))
}

/// The two writers the tiny writer's tests compare (`raster/triangle/tiny.rs`): set-up `t`
/// with `values` drawn into `target` by the tiny writer (`None` where it does not apply), or
/// by the general path's exact planes (`TriangleSpans::planar` with [`ExactKind`]).
#[cfg(test)]
pub(crate) fn draw_tiny_or_planar<
    D: DepthValue,
    Q: Quantizer,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
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

/// True when the bounding box of `t` (rounded outward to pixels) meets `window`.
#[inline(always)]
fn bounds_meet<const S: u32>(t: &TriangleSetup<S>, window: &Window) -> bool {
    let ([x_lo, x_hi], [y_lo, y_hi]) = (t.x, t.y);
    (x_hi >> S) >= window.x0
        && (x_lo >> S) < window.x1
        && (y_hi >> S) >= window.y0
        && (y_lo >> S) < window.y1
}

// Phong: seven attributes (depth, normal, position) lit at every pixel, through the general
// writer's planes and span loop with Phong's span kind.

/// One triangle corner for Phong shading.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PhongVertex<const S: u32> {
    /// Sub-pixel screen position.
    pub screen: SubpixelPoint<S>,
    /// Normalised depth (as [`draw_triangle`](super::draw_triangle)).
    pub depth: u32,
    /// Observer-frame position.
    pub position: Vec3,
    /// Observer-frame normal (any non-zero length; zero lights with ambient only).
    pub normal: Vec3,
}

/// What is fixed for a Phong-shaded object: lights, material, ramp, and whether to dither.
#[derive(Debug, Clone, Copy)]
pub struct PhongContext<'a> {
    /// The frame's lights in the observer frame.
    pub illumination: &'a Illumination,
    /// The object's material.
    pub material: Material,
    /// Intensity → palette index.
    pub ramp: LuminanceRamp,
    /// Ordered 4×4 dithering between adjacent levels (`dither`).
    pub dither: bool,
}

/// The 7 stored attributes of a corner: depth, offset unit normal, offset position.
fn corner_values<const S: u32>(v: &PhongVertex<S>) -> [u32; 7] {
    let [n0, n1, n2, p0, p1, p2] = phong::corner_attributes(v.position, v.normal);
    [v.depth, n0, n1, n2, p0, p1, p2]
}

/// Draws a depth-tested, Phong-shaded triangle. Pixels, bands and the return value
/// `(covered, written)` as [`draw_triangle`](super::draw_triangle): vertices
/// outside the raster's range are [`DrawError::Fill`] (checked once, by the set-up), any
/// triangle within it is drawn (one too large for the `AttributePlane` through the
/// `WidePlane`, out of line).
pub fn draw_triangle_phong<D: DepthValue, const S: u32>(
    frame: &mut Framebuffer<'_>,
    depth: &mut DepthBuffer<'_, D>,
    corners: [PhongVertex<S>; 3],
    ctx: &PhongContext<'_>,
) -> Result<(u32, u32), DrawError> {
    draw_phong_on(&mut RasterTarget::new(frame, depth), corners, ctx)
}

/// [`draw_triangle_phong`] into a prepared [`RasterTarget`] (the renderer's form: one target
/// per object and band), counting written pixels as the target says.
pub(crate) fn draw_phong_on<
    D: DepthValue,
    C: WrittenCount,
    T: SpanTarget<Depth = D>,
    const S: u32,
>(
    target: &mut RasterTarget<'_, D, C, T>,
    corners: [PhongVertex<S>; 3],
    ctx: &PhongContext<'_>,
) -> Result<(u32, u32), DrawError> {
    let t = TriangleSetup::new(corners.map(|c| c.screen)).map_err(DrawError::Fill)?;
    // Depths clamp to the deepest value that stores below FAR (output::depth's module doc).
    let values = corners.map(|c| {
        let mut a = corner_values(&c);
        a[0] = a[0].min(D::MAX_DEPTH32);
        a
    });
    Ok(draw_general_exact(target, &t, values, PhongKind(ctx)))
}

#[cfg(test)]
mod tests {
    use super::super::fill::fill_setup;
    use super::super::interpolants::Interpolant;
    use super::super::wide_plane::WidePlane;
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
                            super::super::dither::Bayer4::at(ramp, x, y)
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

#[cfg(test)]
mod phong_tests {
    use super::*;
    use crate::geometry::vector::Vec3;
    use crate::lighting::{Illumination, Light, Material};

    /// A triangle whose three normals lean outward: the interpolated normal faces the eye at
    /// the centre, where the per-pixel highlight peaks.
    #[test]
    fn highlight_at_the_centre() {
        let ill = Illumination::observer(
            0,
            &[Light::Directional {
                toward: Vec3::from_int(0, 0, -1),
                intensity: 255,
            }],
        )
        .unwrap();
        let ctx = PhongContext {
            illumination: &ill,
            material: Material::from_thousandths(0, 0, 1000, 50),
            ramp: LuminanceRamp::GREY,
            dither: false,
        };
        let corner = |x: i32, y: i32, nx: i32, ny: i32| PhongVertex::<4> {
            screen: SubpixelPoint::from_pixel(x, y),
            depth: 1000,
            position: Vec3::from_int(x - 16, 16 - y, 100),
            normal: Vec3::from_int(nx, ny, -4),
        };
        let tri = [
            corner(0, 0, -2, 2),
            corner(32, 0, 2, 2),
            corner(16, 32, 0, -2),
        ];
        let mut px = [0u8; 32 * 32];
        let mut zs = [0u16; 32 * 32];
        let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
        let mut zb = DepthBuffer::new(&mut zs, 32, 32).unwrap();
        zb.clear();
        let (covered, written) = draw_triangle_phong(&mut fb, &mut zb, tri, &ctx).unwrap();
        assert!(covered > 400 && written == covered);
        let max = fb
            .rows()
            .flat_map(|(_, r)| r.iter().copied())
            .max()
            .unwrap();
        assert!(max > 200, "{max}");
        assert!(fb.pixel(1, 0).unwrap() < 20);
    }
}
