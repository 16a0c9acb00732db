//! The raster target's slices: the frame's and the depth buffer's pixels handed to each span
//! of a triangle as two slices.
//!
//! Role in the pipeline: between the span loop over a triangle's spans (`spans`) and the
//! output buffers (`output`). A [`RasterTarget`] is a frame and its depth buffer prepared once
//! for many triangles (the window both hold, their samples as whole slices); a
//! [`DepthTarget`] a depth buffer alone (a shadow map's samples). Each hands the span loop
//! every span's pixels through [`SpanTarget`].
//!
//! Numeric contract: a span slice is a checked `get_mut` (a span outside the buffers is
//! skipped, never a panic); rows are absolute picture rows (a band's buffers start at their
//! `top`); the window is half-open, as [`Window`].

use super::span::{CountWritten, SpanTest, WrittenCount};
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::raster::{Span, Window};

/// A frame and its depth buffer prepared once for many triangles ([`draw_triangle_on`]): the
/// window both hold and their samples as whole slices, so that a triangle's set-up does not
/// recompute them.
/// `C` says whether triangles drawn into it count their written pixels ([`WrittenCount`]).
#[derive(Debug)]
///
/// `T` is how each span's pixels are handed out and tested ([`SpanTarget`]): the frame and its
/// depth buffer ([`Targets`], the depth test), or the frame and the reverse painter's mask
/// (`MaskTargets`, `mask_span.rs`); `D` is its depth type.
pub(crate) struct RasterTarget<'t, D, C = CountWritten, T = Targets<'t, D>> {
    /// Where triangles are drawn: the buffers' window, or part of it ([`Self::restrict`]).
    pub(super) window: Window,
    /// The window both buffers hold.
    buffers: Window,
    pub(super) targets: T,
    pub(super) count: C,
    pub(super) depth: core::marker::PhantomData<&'t D>,
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
        RasterTarget::over(buffers, Targets::new(frame, depth), count)
    }
}

impl<'t, D, C, T> RasterTarget<'t, D, C, T> {
    /// Draws into `targets`, whose buffers hold `buffers`, counting written pixels as `count`
    /// says.
    #[inline(always)]
    pub(crate) fn over(buffers: Window, targets: T, count: C) -> Self {
        RasterTarget {
            window: buffers,
            buffers,
            targets,
            count,
            depth: core::marker::PhantomData,
        }
    }
}

impl<D, C, T> RasterTarget<'_, D, C, T> {
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

/// A depth buffer without a frame, prepared once for many depth-only triangles
/// ([`draw_depth_only`]): a shadow map's samples, `width × height` from row 0.
#[derive(Debug)]
pub(crate) struct DepthTarget<'t, D> {
    pub(super) window: Window,
    pub(super) targets: DepthTargets<'t, D>,
}

impl<'t, D: DepthValue> DepthTarget<'t, D> {
    /// Borrows `samples` (at least `width × height`, row by row) for drawing depths.
    pub(crate) fn new(samples: &'t mut [D], width: u16, height: u16) -> Self {
        DepthTarget {
            window: Window::new(0, 0, width as i32, height as i32),
            targets: DepthTargets::new(samples, width as usize),
        }
    }

    /// Borrows the samples of the z-buffer `depth` (a whole frame's or a band's) for drawing
    /// depths into the pixels it holds that `frame` holds too (the hidden-line pass of a
    /// wireframe: faces into depth only, then edges).
    pub(crate) fn of_buffer(frame: &Framebuffer<'_>, depth: &'t mut DepthBuffer<'_, D>) -> Self {
        let window = drawable_window(frame, depth);
        let (stride, top) = (depth.width() as usize, depth.top());
        let mut targets = DepthTargets::new(depth.samples_mut(), stride);
        targets.top = top;
        DepthTarget { window, targets }
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

/// The colour and depth buffers of one triangle as whole slices, sliced per span without the
/// per-span row and column checks of [`Framebuffer::span_mut`]: the spans come from
/// [`fill_triangle`](crate::raster::triangle::fill_triangle) inside [`drawable_window`], whose rows both buffers hold and whose
/// columns are `0..width` of both. Each span slice is still a checked `get_mut` (a span outside
/// the slices is skipped, never a panic).
#[derive(Debug)]
pub(crate) struct Targets<'t, D> {
    colours: &'t mut [u8],
    colour_stride: usize,
    colour_top: i32,
    depths: &'t mut [D],
    depth_stride: usize,
    depth_top: i32,
}

impl<'t, D: DepthValue> Targets<'t, D> {
    #[inline(always)]
    pub(crate) fn new(frame: &'t mut Framebuffer<'_>, depth: &'t mut DepthBuffer<'_, D>) -> Self {
        let (colour_stride, colour_top) = (frame.stride(), frame.top());
        let (depth_stride, depth_top) = (depth.width() as usize, depth.top());
        Targets {
            colours: frame.pixels_mut(),
            colour_stride,
            colour_top,
            depths: depth.samples_mut(),
            depth_stride,
            depth_top,
        }
    }

    /// The pixels of span `s` (inside the drawable window) in both buffers.
    #[inline(always)]
    pub(crate) fn span(&mut self, s: &Span) -> Option<(&mut [u8], &mut [D])> {
        let len = s.x1.wrapping_sub(s.x0) as usize;
        let at = |y: i32, top: i32, stride: usize| {
            (y.wrapping_sub(top) as usize)
                .wrapping_mul(stride)
                .wrapping_add(s.x0 as usize)
        };
        let c = at(s.y, self.colour_top, self.colour_stride);
        let z = at(s.y, self.depth_top, self.depth_stride);
        Some((
            self.colours.get_mut(c..c.wrapping_add(len))?,
            self.depths.get_mut(z..z.wrapping_add(len))?,
        ))
    }
}

/// Where the one triangle writer's span loop takes each span's pixels: the samples of the
/// depth buffer and the colours beside them. [`Targets`] (a frame and its depth buffer) for the
/// shaded kinds; [`DepthTargets`] (depth samples alone, no colours: an empty colour slice) for
/// the depth-only kind, whose span ignores the colours.
pub(crate) trait SpanTarget {
    /// The depth type of its test.
    type Depth: DepthValue;
    /// A span's per-pixel test ([`SpanTest`]): its depth samples, or its mask bits.
    type Test<'s>: SpanTest<Depth = Self::Depth>
    where
        Self: 's;
    /// The pixels of span `s` (inside the drawable window): colours and their test.
    fn span(&mut self, s: &Span) -> Option<(&mut [u8], Self::Test<'_>)>;

    /// The `len` pixels from `(x, y)`.
    #[inline(always)]
    fn span_at(&mut self, x: i32, y: i32, len: usize) -> Option<(&mut [u8], Self::Test<'_>)> {
        self.span(&Span {
            y,
            x0: x,
            x1: x + len as i32,
        })
    }
}

impl<D: DepthValue> SpanTarget for Targets<'_, D> {
    type Depth = D;
    type Test<'s>
        = &'s mut [D]
    where
        Self: 's;

    #[inline(always)]
    fn span(&mut self, s: &Span) -> Option<(&mut [u8], &mut [D])> {
        Targets::span(self, s)
    }
}

/// The depth samples of a z-buffer without a frame (a shadow map's, `width` samples a row from
/// row 0), sliced per span like [`Targets`]: one checked `get_mut` per span (a span outside
/// the samples is skipped, never a panic). Its colours are empty: only the depth-only kind
/// draws into it.
#[derive(Debug)]
pub(crate) struct DepthTargets<'t, D> {
    depths: &'t mut [D],
    stride: usize,
    /// The absolute row of the first sample row (0 for a shadow map; a band's `top`).
    top: i32,
}

impl<'t, D: DepthValue> DepthTargets<'t, D> {
    /// The samples `depths`, `stride` to a row.
    #[inline(always)]
    pub(crate) fn new(depths: &'t mut [D], stride: usize) -> Self {
        DepthTargets {
            depths,
            stride,
            top: 0,
        }
    }
}

impl<D: DepthValue> SpanTarget for DepthTargets<'_, D> {
    type Depth = D;
    type Test<'s>
        = &'s mut [D]
    where
        Self: 's;

    #[inline(always)]
    fn span(&mut self, s: &Span) -> Option<(&mut [u8], &mut [D])> {
        let len = s.x1.wrapping_sub(s.x0) as usize;
        let at = (s.y.wrapping_sub(self.top) as usize)
            .wrapping_mul(self.stride)
            .wrapping_add(s.x0 as usize);
        Some((&mut [], self.depths.get_mut(at..at.wrapping_add(len))?))
    }
}
