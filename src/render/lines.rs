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
//! A line pixel is pulled toward the eye by [`LineStyle::depth_offset`] units of the 32-bit
//! depth before the z-buffer's strict test, and stores its pulled depth when it passes. A
//! surface stores its plane's depth at the pixel centre, while an edge of that surface has
//! the depth of the edge, up to half a pixel away on the surface: the offset must exceed half
//! a pixel of the surface's depth slope for the edge to show on its own surface, and stay
//! below the depth gap to the surfaces it should hide behind.
//! [`DEFAULT_DEPTH_OFFSET`] = 2^22 (1/1024 of the depth range): for SCENES.md's lens (near
//! 0.5, far 10) at distance 4 that is ≈ 0.03 world units, half a pixel of a face seen at 80°
//! from its normal at 320 × 240; hidden edges nearer than that behind a surface show through.
//! A 16-bit buffer stores the top 16 bits: the offset is 64 of its steps.
//!
//! ## Wireframes ([`Wireframe`])
//! - [`Wireframe::All`]: every edge of the mesh once, from its edge table
//!   ([`Mesh::edges`](crate::geometry::mesh::Mesh::edges): the undirected edges, a shared edge once), depth-tested.
//! - [`Wireframe::Front`]: the edges of the front-facing polygons (the polygon stage's own
//!   culling decision, `cull.rs`), depth-tested: Roberts's observation that for a convex
//!   object these are exactly the visible edges. An edge shared by two front polygons is
//!   walked twice; the second walk draws nothing (same pixels, same depths, and the test is
//!   strict: tested).
//! - [`Wireframe::Hidden`]: hidden lines removed through the depth buffer: the object's faces
//!   into depth only (the polygon stage with the writer's depth-only kind, frame untouched),
//!   then every edge of the table depth-tested against them.
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

use super::consumer::DepthOnlyWriter;
use super::object::checked_scratch;
use super::{PreparedVertex, RenderError, RenderStats, Renderer};
use crate::clip::frustum::clip_segment;
use crate::geometry::vector::Vec3;
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::raster::depth_line::{draw_depth_line, LineTarget, Walk};
use crate::raster::line::SubpixelLine;
use crate::raster::triangle::{drawable_window, DepthTarget};
use crate::raster::{SubpixelPoint, Window};
use crate::scene::Object;

/// The default [`LineStyle::depth_offset`]: `2^22` units of the 32-bit depth (module doc).
pub const DEFAULT_DEPTH_OFFSET: u32 = 1 << 22;

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
}

impl Wireframe {
    /// The mode's name as scenes write it (`all`, `front`, `hidden`).
    pub const fn name(self) -> &'static str {
        match self {
            Wireframe::All => "all",
            Wireframe::Front => "front",
            Wireframe::Hidden => "hidden",
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
            drawn += self.segment(a, b, &window, &mut target, style)?;
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
            let (x, y) = (nearest_pixel::<S>(v.screen.x), nearest_pixel::<S>(v.screen.y));
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
    /// ([`Mesh::edges`](crate::geometry::mesh::Mesh::edges)), read by [`Wireframe::All`] and [`Wireframe::Hidden`] (
    /// [`Wireframe::Front`] walks the front polygons instead and may be given `&[]`). The
    /// hidden mode writes the faces' depths into `depth` first (the frame untouched). Returns
    /// the pixels drawn.
    ///
    /// Errors: as [`draw_lines`](Self::draw_lines); an edge naming a vertex the mesh has not;
    /// a polygon above the clipper's size.
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
        match mode {
            Wireframe::All => self.draw_lines(object, edges, scratch, style, frame, depth),
            Wireframe::Hidden => {
                self.check_targets(frame, depth)?;
                check_segments(edges, object.mesh.vertices().len())?;
                self.prepare(object, scratch)?;
                self.faces_into_depth(object, scratch, frame, depth)?;
                let prepared = &scratch[..object.mesh.vertices().len()];
                let (window, mut target) = line_target(frame, depth);
                let mut drawn = 0;
                for &[i, j] in edges {
                    let (a, b) = (&prepared[i as usize], &prepared[j as usize]);
                    drawn += self.segment(a, b, &window, &mut target, style)?;
                }
                Ok(drawn)
            }
            Wireframe::Front => {
                self.check_targets(frame, depth)?;
                self.prepare(object, scratch)?;
                let culled = Object {
                    cull_back_faces: true,
                    ..*object
                };
                let prepared = checked_scratch(&culled, scratch)?;
                let rows = (0, self.camera.viewport().height as i32);
                let stage = self.stage(&culled, prepared, rows, None);
                let (window, mut target) = line_target(frame, depth);
                let (mut drawn, mut stats) = (0, RenderStats::default());
                for poly in object.mesh.polygons() {
                    if matches!(stage.decide(poly, &mut stats)?, super::polygon_stage::Path::Skip) {
                        continue;
                    }
                    for (k, &i) in poly.iter().enumerate() {
                        let j = poly[(k + 1) % poly.len()];
                        let (a, b) = (&prepared[i as usize], &prepared[j as usize]);
                        drawn += self.segment(a, b, &window, &mut target, style)?;
                    }
                }
                Ok(drawn)
            }
        }
    }

    /// The hidden-line pass: `object`'s faces (prepared in `scratch`) into `depth` alone.
    fn faces_into_depth<D: DepthValue>(
        &self,
        object: &Object<'_>,
        scratch: &[PreparedVertex<S>],
        frame: &Framebuffer<'_>,
        depth: &mut DepthBuffer<'_, D>,
    ) -> Result<(), RenderError> {
        let prepared = checked_scratch(object, scratch)?;
        let rows = (frame.top().max(depth.top()), {
            let f = frame.top() + frame.height() as i32;
            f.min(depth.top() + depth.height() as i32)
        });
        let stage = self.stage(object, prepared, rows, None);
        let mut target = DepthTarget::of_buffer(frame, depth);
        let writer = DepthOnlyWriter {
            target: &mut target,
        };
        stage.run(&mut RenderStats::default(), |_, _, _, _| [0i32; 0], writer)
    }

    /// One segment between prepared vertices: kept, or clipped in 3D and projected, then
    /// walked with its depth (module doc). Returns the pixels drawn.
    fn segment<D: DepthValue>(
        &self,
        a: &End<S>,
        b: &End<S>,
        window: &Window,
        target: &mut LineTarget<'_, D>,
        style: &LineStyle,
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
            Some(line) => draw_depth_line(
                target,
                &line,
                (d0, d1),
                style.depth_offset,
                style.index,
                style.walk,
            ),
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
