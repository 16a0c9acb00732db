//! Lines and points in space: a line list's segments, a mesh's edges (wireframes) and its
//! vertices as points, through the renderer's stages and the depth buffer.
//!
//! Role in the pipeline: beside the polygon stage. Every entry runs the vertex stage
//! ([`Renderer::prepare`]) on the object, then per segment:
//! 1. **3D clip** against the view volume (`clip::frustum::clip_segment`: near, far and the
//!    guard band's side planes, each cut computed from the inside end, exactly on the near
//!    plane); a segment wholly inside keeps its prepared end points, one behind the eye is cut
//!    at the near plane, one wholly outside a plane is dropped.
//! 2. **Projection** of its end points with sub-pixel precision and their 32-bit depths (the
//!    projector of the triangles: the same positions and depths as the surfaces' corners).
//! 3. **Raster**: the pixels of the exact segment between the sub-pixel end points
//!    ([`SubpixelLine`], `raster::line`: the course's Bresenham on sub-pixel ends, clipped
//!    exactly to the window), each with the exactly rounded depth of the segment at its
//!    centre, depth-tested (`raster::depth_line`).
//!
//! ## The offset rule
//! A line pixel is pulled toward the eye by a number of units of the 32-bit depth before the
//! z-buffer's strict test, and stores its pulled depth when it passes (`raster::depth_line`).
//! - Segments of a line list ([`Renderer::draw_lines`], [`Wireframe::All`]) and points are
//!   pulled by [`LineStyle::depth_offset`] alone ([`DEFAULT_DEPTH_OFFSET`] = 2^12).
//! - **The edges of a face** ([`Wireframe::Front`], [`Wireframe::Hidden`]) are drawn with
//!   that face, pulled by `depth_offset + 2^(32 − b) + ⌈max(|∂D/∂x|, |∂D/∂y|) / 2⌉`: one
//!   step of the `b`-bit buffer, and half a pixel of the face's depth slope (its plane on
//!   screen, from the first triangle the polygon stage hands for it). A line pixel sits at
//!   the exact edge's major coordinate, at most half a pixel from the edge along the minor
//!   axis, where the face stores its plane's depth: that pull makes **every edge pixel of a
//!   face show on the face** whatever the face's slope (grazing faces included), and hides it
//!   behind any surface farther than the pull in front of it. A hidden edge within half a
//!   pixel's depth of the face that hides it shows through.
//!
//! ## Wireframes ([`Wireframe`])
//! - [`Wireframe::All`]: every edge of the mesh once, from its edge table
//!   ([`Mesh::edges`](crate::geometry::mesh::Mesh::edges): the undirected edges, a shared
//!   edge once), depth-tested.
//! - [`Wireframe::Front`]: the edges of the polygons the polygon stage draws with back faces
//!   culled (its own rejection and culling, `cull.rs`), each with its face's pull: Roberts's
//!   observation that for a convex object these are exactly the visible edges. An edge shared
//!   by two front polygons is walked twice, the pixels the first walk drew unchanged by the
//!   second.
//! - [`Wireframe::Hidden`]: hidden lines removed through the depth buffer: the object's faces
//!   into depth only (the polygon stage with the writer's depth-only kind, frame untouched),
//!   then the edges of the faces drawn (as in front mode, the object's own culling),
//!   depth-tested against them.
//! - [`Wireframe::Appel`]: hidden lines removed exactly by Appel's quantitative invisibility,
//!   with no depth buffer (`render::appel`); drawn by [`Renderer::draw_appel`], which takes
//!   that method's scratch ([`Renderer::draw_wireframe`] refuses the mode in words).
//!
//! ## Points
//! [`Renderer::draw_points`] draws each vertex inside the view volume as a square of
//! `size × size` pixels (1 to [`MAX_POINT_SIZE`]) around the pixel nearest its projection
//! (ties toward the smaller coordinate, as the lines' minor axis), all at the vertex's depth,
//! through the same test and offset.
//!
//! Numeric contract: as the polygon stage's (mesh coordinates `|c| ≤ 1024`, observer frame
//! I16F16, projected end points within the guard band, `±(2^28 − 1)` sub-pixel units at most,
//! inside the line walker's `±2^30`); depths 32-bit.

use super::consumer::{Corner, DepthOnlyWriter, TriangleConsumer};
use super::object::checked_scratch;
use super::{PreparedVertex, RenderError, RenderStats, Renderer};
use crate::clip::frustum::clip_segment;
use crate::geometry::mesh::Polygons;
use crate::geometry::vector::Vec3;
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::raster::depth_line::{draw_depth_line, LineTarget, Walk};
use crate::raster::line::SubpixelLine;
use crate::raster::triangle::{drawable_window, DepthTarget};
use crate::raster::{SubpixelPoint, Window};
use crate::scene::Object;

/// The default [`LineStyle::depth_offset`]: `2^12` units of the 32-bit depth (module doc).
pub const DEFAULT_DEPTH_OFFSET: u32 = 1 << 12;

/// The largest side of a point's square, in pixels.
pub const MAX_POINT_SIZE: u8 = 16;

/// How 3D lines (and points) are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LineStyle {
    /// The palette index written.
    pub index: u8,
    /// Toward the eye before the depth test, in 32-bit depth units (module doc).
    pub depth_offset: u32,
    /// One-ended or two-ended walk: the same pixels.
    pub walk: Walk,
}

impl LineStyle {
    /// Lines of palette `index`, the [`DEFAULT_DEPTH_OFFSET`], walked from one end.
    pub const fn new(index: u8) -> Self {
        LineStyle {
            index,
            depth_offset: DEFAULT_DEPTH_OFFSET,
            walk: Walk::OneEnded,
        }
    }
}

/// Which edges of an object a wireframe draws (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Wireframe {
    /// Every edge once.
    All,
    /// The edges of the front-facing polygons.
    Front,
    /// Every edge, hidden lines removed through the depth buffer (faces into depth first).
    Hidden,
    /// Every edge's visible pieces by Appel's quantitative invisibility, no depth buffer
    /// (`render::appel`; drawn by [`Renderer::draw_appel`], which takes its scratch).
    Appel,
}

impl Wireframe {
    /// The mode's name as scenes write it (`all`, `front`, `hidden`, `appel`).
    pub const fn name(self) -> &'static str {
        match self {
            Wireframe::All => "all",
            Wireframe::Front => "front",
            Wireframe::Hidden => "hidden",
            Wireframe::Appel => "appel",
        }
    }
}

/// One prepared end point: its observer-frame position, and its projection when the vertex
/// stage made one.
type End<const S: u32> = PreparedVertex<S>;

impl<const S: u32> Renderer<S> {
    /// Draws the segments `segments` (pairs of indices into `object`'s vertex table) of
    /// `object` into `frame` through `depth` (module doc). `scratch` holds the vertex stage's
    /// output (one per vertex). Returns the pixels drawn.
    ///
    /// Errors: the buffers smaller than the viewport, a short scratch, a segment naming a
    /// vertex the mesh has not ([`RenderError::SegmentOutOfRange`]; nothing drawn), the
    /// object's transform.
    pub fn draw_lines<D: DepthValue>(
        &self,
        object: &Object<'_>,
        segments: &[[u16; 2]],
        scratch: &mut [PreparedVertex<S>],
        style: &LineStyle,
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
    ) -> Result<u32, RenderError> {
        self.check_targets(frame, depth)?;
        check_segments(segments, object.mesh.vertices().len())?;
        self.prepare(object, scratch)?;
        let prepared = &scratch[..object.mesh.vertices().len()];
        let (window, mut target) = line_target(frame, depth);
        let mut drawn = 0;
        for &[i, j] in segments {
            let (a, b) = (&prepared[i as usize], &prepared[j as usize]);
            drawn += self.segment(a, b, &window, &mut target, (style.depth_offset, style))?;
        }
        Ok(drawn)
    }

    /// Draws every vertex of `object` inside the view volume as a point: a `size × size`
    /// square (module doc). Returns the pixels drawn.
    ///
    /// Errors: `size` outside `1..=`[`MAX_POINT_SIZE`]
    /// ([`RenderError::PointSizeOutOfRange`]), the buffers, the scratch, the transform.
    pub fn draw_points<D: DepthValue>(
        &self,
        object: &Object<'_>,
        scratch: &mut [PreparedVertex<S>],
        size: u8,
        style: &LineStyle,
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
    ) -> Result<u32, RenderError> {
        if !(1..=MAX_POINT_SIZE).contains(&size) {
            return Err(RenderError::PointSizeOutOfRange {
                size,
                max: MAX_POINT_SIZE,
            });
        }
        self.check_targets(frame, depth)?;
        self.prepare(object, scratch)?;
        let (window, mut target) = line_target(frame, depth);
        let (lo, hi) = ((size as i32 - 1) / 2, size as i32 / 2);
        let mut drawn = 0;
        for v in &scratch[..object.mesh.vertices().len()] {
            if v.outcode != 0 {
                continue;
            }
            let (x, y) = (
                nearest_pixel::<S>(v.screen.x),
                nearest_pixel::<S>(v.screen.y),
            );
            let square = Window::new(x - lo, y - lo, x + hi + 1, y + hi + 1).intersect(&window);
            for py in square.y0..square.y1 {
                for px in square.x0..square.x1 {
                    let p = embedded_graphics_core::geometry::Point::new(px, py);
                    drawn += target.plot(p, v.depth, style.depth_offset, style.index) as u32;
                }
            }
        }
        Ok(drawn)
    }

    /// Draws `object` as a wireframe in `mode` (module doc). `edges` is the mesh's edge table
    /// ([`Mesh::edges`](crate::geometry::mesh::Mesh::edges)), read by [`Wireframe::All`]
    /// only (the other modes walk the faces; they may be given `&[]`). The hidden mode
    /// writes the faces' depths into `depth` first (the frame untouched). Returns the pixels
    /// drawn.
    ///
    /// Errors: as [`draw_lines`](Self::draw_lines); a polygon above the clipper's size.
    #[allow(clippy::too_many_arguments)]
    pub fn draw_wireframe<D: DepthValue>(
        &self,
        object: &Object<'_>,
        edges: &[[u16; 2]],
        mode: Wireframe,
        scratch: &mut [PreparedVertex<S>],
        style: &LineStyle,
        frame: &mut Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
    ) -> Result<u32, RenderError> {
        let object = match mode {
            Wireframe::All => {
                return self.draw_lines(object, edges, scratch, style, frame, depth);
            }
            Wireframe::Front => Object {
                cull_back_faces: true,
                ..*object
            },
            Wireframe::Hidden => *object,
            Wireframe::Appel => {
                return Err(RenderError::Appel(super::AppelError::NeedsScratch));
            }
        };
        self.check_targets(frame, depth)?;
        self.prepare(&object, scratch)?;
        let prepared = checked_scratch(&object, scratch)?;
        let rows = (frame.top().max(depth.top()), {
            let f = frame.top() + frame.height() as i32;
            f.min(depth.top() + depth.height() as i32)
        });
        let stage = self.stage(&object, prepared, rows, None);
        let mut stats = RenderStats::default();
        if mode == Wireframe::Hidden {
            let mut target = DepthTarget::of_buffer(frame, depth);
            let writer = DepthOnlyWriter {
                target: &mut target,
            };
            stage.run(&mut stats, |_, _, _, _| [0i32; 0], writer)?;
        }
        let (window, target) = line_target(frame, depth);
        let step = match D::BITS {
            1..=31 => 1u32 << (32 - D::BITS),
            _ => 0,
        };
        let mut writer = EdgeWriter {
            renderer: self,
            prepared,
            polygons: object.mesh.polygons(),
            next: 0,
            window,
            target,
            style,
            pull: style.depth_offset.saturating_add(step),
            drawn: 0,
        };
        stage.run(&mut stats, |_, _, _, _| [0i32; 0], &mut writer)?;
        Ok(writer.drawn)
    }

    /// One segment between prepared vertices: kept, or clipped in 3D and projected, then
    /// walked with its depth (module doc). Returns the pixels drawn.
    fn segment<D: DepthValue>(
        &self,
        a: &End<S>,
        b: &End<S>,
        window: &Window,
        target: &mut LineTarget<'_, D>,
        (pull, style): (u32, &LineStyle),
    ) -> Result<u32, RenderError> {
        let ends = if a.outcode == 0 && b.outcode == 0 {
            ((a.screen, a.depth), (b.screen, b.depth))
        } else {
            let planes = self.frustum.planes();
            let Some((p, q)) = clip_segment(planes, |v| self.frustum.outcode(v), a.view, b.view)
            else {
                return Ok(0);
            };
            (self.project(p)?, self.project(q)?)
        };
        let ((p0, d0), (p1, d1)) = ends;
        let line = SubpixelLine::new(p0, p1, window)
            .map_err(|_| RenderError::Projection(crate::project::ProjectError::OutOfRange))?;
        Ok(match line {
            Some(line) => draw_depth_line(target, &line, (d0, d1), pull, style.index, style.walk),
            None => 0,
        })
    }

    /// The projection of a clipped end point.
    fn project(&self, p: Vec3) -> Result<(SubpixelPoint<S>, u32), RenderError> {
        self.projector
            .project_point(p)
            .map_err(RenderError::Projection)
    }
}

/// [`RenderError::SegmentOutOfRange`] for the first segment naming a vertex not below
/// `vertices`.
fn check_segments(segments: &[[u16; 2]], vertices: usize) -> Result<(), RenderError> {
    for (segment, ends) in segments.iter().enumerate() {
        for &vertex in ends {
            if vertex as usize >= vertices {
                return Err(RenderError::SegmentOutOfRange {
                    segment,
                    vertex,
                    vertices,
                });
            }
        }
    }
    Ok(())
}

/// The window both buffers hold and the line walker's view of them.
fn line_target<'a, D: DepthValue>(
    frame: &'a mut Framebuffer<'_>,
    depth: &'a mut DepthBuffer<'_, D>,
) -> (Window, LineTarget<'a, D>) {
    let window = drawable_window(frame, depth);
    let (stride, top) = (frame.stride(), frame.top());
    let (depth_stride, depth_top) = (depth.width() as usize, depth.top());
    let target = LineTarget {
        pixels: frame.pixels_mut(),
        stride,
        top,
        depths: depth.samples_mut(),
        depth_stride,
        depth_top,
    };
    (window, target)
}

/// The pixel nearest sub-pixel coordinate `c` (`2^-S` units), ties toward the smaller:
/// `⌈(2c − U) / 2U⌉`.
fn nearest_pixel<const S: u32>(c: i32) -> i32 {
    let u = 1i64 << S;
    (-((u - 2 * c as i64).div_euclid(2 * u))) as i32
}

/// The edge consumer of the front and hidden wireframes: for the first triangle the polygon
/// stage hands for a polygon (in increasing polygon order), the polygon's own edges, pulled by
/// the face's slope (module doc, "The offset rule").
struct EdgeWriter<'r, 'o, 't, D, const S: u32> {
    renderer: &'r Renderer<S>,
    prepared: &'r [PreparedVertex<S>],
    /// The mesh's polygons, `next` the index of the one `polygons` yields next.
    polygons: Polygons<'o>,
    next: usize,
    window: Window,
    target: LineTarget<'t, D>,
    style: &'r LineStyle,
    /// The pull of every face edge before the slope: `depth_offset + 2^(32 − b)`.
    pull: u32,
    drawn: u32,
}

impl<D: DepthValue, const S: u32, const N: usize> TriangleConsumer<S, N>
    for EdgeWriter<'_, '_, '_, D, S>
{
    fn triangle(
        &mut self,
        polygon: usize,
        c: [Corner<S, N>; 3],
    ) -> Result<(u32, u32), RenderError> {
        if polygon < self.next {
            return Ok((0, 0)); // a later triangle of a polygon already drawn
        }
        let mut poly = None;
        while self.next <= polygon {
            poly = self.polygons.next();
            self.next += 1;
        }
        let Some(poly) = poly else {
            return Ok((0, 0));
        };
        let pull = self.pull.saturating_add(half_slope(&c));
        for (k, &i) in poly.iter().enumerate() {
            let j = poly[(k + 1) % poly.len()];
            let (a, b) = (&self.prepared[i as usize], &self.prepared[j as usize]);
            self.drawn +=
                self.renderer
                    .segment(a, b, &self.window, &mut self.target, (pull, self.style))?;
        }
        Ok((0, 0))
    }
}

/// `⌈max(|∂D/∂x|, |∂D/∂y|) / 2⌉`, the depth a triangle's plane spans over half a pixel
/// (saturating; 0 for a triangle of no area, which covers nothing). Exact in `i128`: screen
/// differences below `2^29`, depth differences below `2^32`.
fn half_slope<const S: u32, const N: usize>(c: &[Corner<S, N>; 3]) -> u32 {
    let (x, y, d) = (
        c.map(|c| c.screen.x as i128),
        c.map(|c| c.screen.y as i128),
        c.map(|c| c.depth as i128),
    );
    let area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if area == 0 {
        return 0;
    }
    let gx = ((d[1] - d[0]) * (y[2] - y[0]) - (d[2] - d[0]) * (y[1] - y[0])) << S;
    let gy = ((x[1] - x[0]) * (d[2] - d[0]) - (x[2] - x[0]) * (d[1] - d[0])) << S;
    let g = gx.abs().max(gy.abs());
    let a2 = 2 * area.abs();
    let half = (g + a2 - 1) / a2;
    half.min(u32::MAX as i128) as u32
}
