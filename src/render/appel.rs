//! Appel's quantitative invisibility ("invisibilité quantitative", Arête/arête [Appel 67] in
//! the course's survey of hidden-line methods): the visible pieces of every edge of a closed
//! polyhedron, as exact 2D segments, with no depth buffer.
//!
//! Role in the pipeline: beside the polygon stage, an alternative to the z-buffer's hidden
//! lines (`lines.rs`, [`Wireframe::Hidden`](super::Wireframe::Hidden)). The vertex stage
//! ([`Renderer::prepare`]) projects the object; then everything happens on the projected
//! mesh, in the sub-pixel screen frame with the 32-bit depths. The pieces go to a caller's
//! sink ([`Renderer::appel_segments`]: a vector output for plotters, vector displays, an SVG
//! file) or are drawn with the lines' Bresenham ([`Wireframe::Appel`](super::Wireframe::Appel),
//! [`Renderer::draw_appel`]).
//!
//! ## The surface and its quantitative invisibility
//! Each polygon is cut into the fan of triangles `(v0, vk, vk+1)`. In screen space
//! (`x`, `y` sub-pixel, depth `d`, smaller nearer) each triangle is the plane through its three
//! projected corners, as the z-buffer interpolates it, and every view ray is the vertical line
//! `(x, y) = const` (the projection's depth is affine in screen space). A triangle is a
//! **front face** when its projected twice-area is negative (`cull.rs`'s rule); a zero area
//! counts as not front. A **contour edge** ("ligne de contour") is an edge between a front
//! and a not-front triangle (a fan's diagonal included: it bounds the front region too).
//! The **quantitative invisibility** `QI` of a point of an edge is the number of front
//! triangles whose projection holds the point and whose plane is strictly nearer there; the
//! point is visible where `QI = 0`. On a closed surface a view ray that meets the surface in
//! front of a point enters the solid through a front face first, so counting front faces
//! is enough.
//!
//! ## The walk along an edge (edge coherence)
//! For an edge `P0 → P1` (from its smaller vertex index), with `t ∈ [0, 1]` along it:
//! 1. `QI` just after `P0` is **counted directly** (the survey: "comparaison systématique
//!    avec l'ensemble des faces") at the point `P0 + εu + ε'n` (`u = P1 − P0`,
//!    `n = (−u_y, u_x)`, `ε' ≪ ε` infinitesimal): every test takes the sign of its value at
//!    `P0`, else of its rate along `u`, else along `n`, so no point is ever on a triangle's
//!    boundary. A triangle whose plane holds the whole edge (its own faces) is never in front.
//! 2. Along the edge, `QI` changes only where the edge's projection crosses a contour edge
//!    in front of it: `+1` entering the contour's front triangle, `−1` leaving it. Crossings
//!    are found on the line shifted by `ε'n`, so a contour vertex lying on the line counts on
//!    the side of `−n` (each contour chain crosses once, or not at all, where it touches the
//!    line); crossings at `t = 0` or `t = 1` exactly are in the direct counts. They are sorted
//!    exactly (rational `t`) and walked.
//! 3. `QI` just before `P1` is counted directly again and must equal the walked value;
//!    otherwise (the projected surface intersects itself after rounding, or a vertex lies on
//!    an edge) the object is refused ([`AppelError::WalkDisagrees`]): never a silently wrong
//!    picture.
//!
//! An edge whose two triangles are back faces (positive area) is hidden wherever it lies
//! (the view ray reaches it from inside the solid) and is not walked.
//!
//! ## What is refused ([`AppelError`], inside [`RenderError::Appel`])
//! A mesh that is not closed and consistently wound (every edge of the fans shared by exactly
//! two triangles, in opposite directions), a vertex outside the view volume (crossing the
//! near plane, beyond the far plane or the guard band: Appel needs every vertex projected),
//! a contour edge meeting an edge in space at a point inside it, an edge passing through a
//! front triangle it does not share a vertex with (the projected mesh intersects itself:
//! there `QI` changes with no contour crossing, exact `orient3d` tests in the direct counts'
//! loop), a walk that disagrees with the direct count, and scratch too small. Nothing is drawn or handed to the sink before the
//! checks of the whole mesh; a refusal during the walk stops it (the sink may have had the
//! pieces of earlier edges).
//!
//! ## Numeric contract
//! Projected coordinates are within `±(2^28 − 1)` sub-pixel units (the projector's range) and
//! depths `u32`: differences below `2^29` and `2^33`. A crossing's parameter is
//! `t = num / den` with `|num|, den < 2^60` (`i64`); sorting compares `num·den'` in `i128`
//! (`< 2^120`). Whether a contour is in front at a crossing is the sign of a 3×3 determinant
//! of screen-and-depth differences (`< 2^95`, `i128`); the direct count's plane tests are
//! barycentric sums `Σ (d_k − d)·2A_k` (`< 2^95`, `i128`). All exact: no rounding decides
//! anything.
//!
//! ## The pieces
//! A piece is a closed interval `[t_a, t_b]` of an edge where `QI = 0` (adjacent intervals
//! merged). [`AppelSegment`] keeps the exact parameters and the end points rounded to the
//! nearest sub-pixel unit (ties toward `+∞`). Drawn ([`Renderer::draw_appel`]), a piece is
//! the pixels of the whole edge's [`SubpixelLine`] (`raster::line`) whose centre's parameter
//! along the major axis lies in `[t_a, t_b]`: the same pixels the z-buffer's walker would
//! test, with no rounding of the piece's ends.
//!
//! ## Scratch ([`AppelScratch`])
//! `edges`: one [`AppelEdge`] per half-edge of the fans, `3·T` for `T` triangles
//! ([`AppelScratch::edges_needed`]); `crossings`: one [`AppelCrossing`] per contour crossing
//! of the edge with the most (at most the number of contour edges). A short table is
//! refused with [`AppelError::ScratchTooSmall`] naming it and the size needed so far.

use super::{PreparedVertex, RenderError, Renderer};
use crate::geometry::mesh::Mesh;
use crate::output::Framebuffer;
use crate::raster::line::SubpixelLine;
use crate::raster::triangle::twice_area;
use crate::raster::SubpixelPoint;
use crate::scene::Object;
use core::cmp::Ordering;

/// One half-edge of the fan triangles, then one undirected edge (module doc, "Scratch").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AppelEdge {
    /// First vertex (in the front triangle's winding for a contour edge).
    a: u16,
    /// Second vertex.
    b: u16,
    /// The triangle's third vertex (the front triangle's, for a contour edge).
    third: u16,
    /// Bit 0: a polygon's own edge (not a fan's diagonal). Bit 1: front triangle. After
    /// pairing, bit 2: a contour edge; bit 3: walked (drawn).
    flags: u8,
}

impl AppelEdge {
    /// The zeroed entry, for scratch built at compile time.
    pub const ZERO: Self = AppelEdge {
        a: 0,
        b: 0,
        third: 0,
        flags: 0,
    };
}

const OWN: u8 = 1;
const FRONT: u8 = 2;
const CONTOUR: u8 = 4;
const WALKED: u8 = 8;

/// One crossing of an edge with a contour edge: `t = num / den`, `step` ±1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AppelCrossing {
    num: i64,
    den: i64,
    step: i8,
}

impl AppelCrossing {
    /// The zeroed entry, for scratch built at compile time.
    pub const ZERO: Self = AppelCrossing {
        num: 0,
        den: 1,
        step: 0,
    };
}

/// Caller memory for Appel's method (module doc, "Scratch").
#[derive(Debug)]
pub struct AppelScratch<'a> {
    /// The half-edges, `3·T` entries for `T` fan triangles.
    pub edges: &'a mut [AppelEdge],
    /// One edge's crossings with the contour.
    pub crossings: &'a mut [AppelCrossing],
}

impl AppelScratch<'_> {
    /// Entries `edges` needs for `mesh`: three per fan triangle.
    pub fn edges_needed(mesh: &Mesh<'_>) -> usize {
        let mut n = 0;
        for poly in mesh.polygons() {
            n += 3 * poly.len().saturating_sub(2);
        }
        n
    }
}

/// Which table of [`AppelScratch`] is short.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AppelTable {
    /// The half-edges.
    Edges,
    /// One edge's crossings.
    Crossings,
}

/// Why Appel's method refused an object (module doc, "What is refused").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AppelError {
    /// A vertex is not projected (outside the near or far plane, or the guard band).
    VertexOutsideView {
        /// The vertex's index in the mesh.
        vertex: u16,
    },
    /// An edge is not shared by exactly two triangles in opposite directions (a boundary
    /// edge, a non-manifold edge, or faces wound inconsistently); `count` triangles hold it.
    NotClosed {
        /// The edge's vertices.
        edge: [u16; 2],
        /// Triangles (of the polygons' fans) holding it.
        count: usize,
    },
    /// A contour edge meets the edge in space at a point inside it.
    ContourMeetsEdge {
        /// The walked edge.
        edge: [u16; 2],
        /// The contour edge.
        contour: [u16; 2],
    },
    /// An edge passes through a front triangle (the mesh intersects itself in screen space).
    EdgePiercesFace {
        /// The edge.
        edge: [u16; 2],
        /// The triangle's vertices.
        face: [u16; 3],
    },
    /// The walked invisibility at the end of an edge differs from the direct count there.
    WalkDisagrees {
        /// The edge.
        edge: [u16; 2],
        /// The walked value.
        walked: i32,
        /// The direct count.
        counted: i32,
    },
    /// A scratch table is too small.
    ScratchTooSmall {
        /// Which table.
        table: AppelTable,
        /// Entries it holds.
        given: usize,
        /// Entries needed (for crossings: at least; more edges may need more).
        needed: usize,
    },
    /// [`Renderer::draw_wireframe`](super::Renderer::draw_wireframe) was asked for
    /// [`Wireframe::Appel`](super::Wireframe::Appel), which needs its own scratch: use
    /// [`Renderer::draw_appel`].
    NeedsScratch,
}

impl core::fmt::Display for AppelError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            AppelError::VertexOutsideView { vertex } => write!(
                f,
                "vertex {vertex} is outside the view volume (near or far plane, guard band): \
                 Appel's method needs every vertex projected"
            ),
            AppelError::NotClosed { edge, count } => write!(
                f,
                "edge {}–{} is held by {count} triangle(s), not by two wound in opposite \
                 directions: Appel's method needs a closed, consistently wound mesh",
                edge[0], edge[1]
            ),
            AppelError::ContourMeetsEdge { edge, contour } => write!(
                f,
                "contour edge {}–{} meets edge {}–{} in space inside it",
                contour[0], contour[1], edge[0], edge[1]
            ),
            AppelError::EdgePiercesFace { edge, face } => write!(
                f,
                "edge {}–{} passes through face {}–{}–{}: the mesh intersects itself",
                edge[0], edge[1], face[0], face[1], face[2]
            ),
            AppelError::WalkDisagrees {
                edge,
                walked,
                counted,
            } => write!(
                f,
                "the quantitative invisibility walked along edge {}–{} ends at {walked}, the \
                 direct count there is {counted} (the projected mesh intersects itself)",
                edge[0], edge[1]
            ),
            AppelError::ScratchTooSmall {
                table,
                given,
                needed,
            } => write!(
                f,
                "the {} scratch holds {given} entries, {needed} needed",
                match table {
                    AppelTable::Edges => "half-edge",
                    AppelTable::Crossings => "crossing",
                }
            ),
            AppelError::NeedsScratch => write!(
                f,
                "the Appel wireframe needs its own scratch: draw it with draw_appel"
            ),
        }
    }
}

impl core::error::Error for AppelError {}

/// One visible piece of an edge (module doc, "The pieces").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AppelSegment<const S: u32> {
    /// The edge's vertices, from its smaller index.
    pub edge: [u16; 2],
    /// The edge's projected end points.
    pub ends: [SubpixelPoint<S>; 2],
    /// The piece's parameters along the edge, each `(num, den)` with `0 ≤ num ≤ den`.
    pub range: [(i64, i64); 2],
    /// The piece's end points, rounded to the nearest sub-pixel unit (ties toward `+∞`).
    pub from: SubpixelPoint<S>,
    /// See `from`.
    pub to: SubpixelPoint<S>,
}

/// A projected vertex: `x`, `y` sub-pixel, depth.
type P3 = [i128; 3];

fn point<const S: u32>(v: &PreparedVertex<S>) -> P3 {
    [v.screen.x as i128, v.screen.y as i128, v.depth as i128]
}

/// Twice the signed area of `(a, b, c)` in screen space (exact: differences below `2^31`), for
/// the direct counts' perturbation tests, whose points include a vertex moved by an edge's
/// direction or normal (`plus`): those may leave the raster's range, which the one
/// orientation of projected vertices, [`twice_area`], assumes.
fn area(a: P3, b: P3, c: P3) -> i128 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The sign of the first non-zero of `values`.
fn first_sign(values: [i128; 3]) -> Ordering {
    for v in values {
        if v != 0 {
            return v.cmp(&0);
        }
    }
    Ordering::Equal
}

impl<const S: u32> Renderer<S> {
    /// Hands each visible piece of every edge of `object` to `sink`, by Appel's quantitative
    /// invisibility (module doc). `scratch` holds the vertex stage's output. Returns the
    /// number of pieces.
    ///
    /// Errors: [`RenderError::Appel`] (module doc, "What is refused"), the vertex scratch, the
    /// object's transform.
    pub fn appel_segments(
        &self,
        object: &Object<'_>,
        scratch: &mut [PreparedVertex<S>],
        appel: &mut AppelScratch<'_>,
        mut sink: impl FnMut(&AppelSegment<S>),
    ) -> Result<u32, RenderError> {
        self.prepare(object, scratch)?;
        let prepared = &scratch[..object.mesh.vertices().len()];
        let mut pieces = 0;
        walk_object(prepared, &object.mesh, appel, &mut |s| {
            pieces += 1;
            sink(s)
        })
        .map_err(RenderError::Appel)?;
        Ok(pieces)
    }

    /// Draws the visible pieces of `object`'s edges (Appel's method, module doc) into `frame`
    /// in palette `index`, with no depth buffer. Returns the pixels drawn.
    ///
    /// Errors: as [`appel_segments`](Self::appel_segments); a frame smaller than the viewport.
    pub fn draw_appel(
        &self,
        object: &Object<'_>,
        scratch: &mut [PreparedVertex<S>],
        appel: &mut AppelScratch<'_>,
        index: u8,
        frame: &mut Framebuffer<'_>,
    ) -> Result<u32, RenderError> {
        self.check_frame(frame)?;
        let window = frame.window();
        let mut drawn = 0;
        self.appel_segments(object, scratch, appel, |s| {
            drawn += draw_piece(s, &window, index, frame);
        })?;
        Ok(drawn)
    }
}

/// The pixels of the whole edge's line whose centre lies in the piece (module doc).
fn draw_piece<const S: u32>(
    s: &AppelSegment<S>,
    window: &crate::raster::Window,
    index: u8,
    frame: &mut Framebuffer<'_>,
) -> u32 {
    // The projector's range is inside the line walker's: the set-up cannot fail.
    let Ok(Some(line)) = SubpixelLine::new(s.ends[0], s.ends[1], window) else {
        return 0;
    };
    let (n, travel, unit) = (line.length as i128, line.travel as i128, line.unit as i128);
    let [(na, da), (nb, db)] = s.range.map(|(p, q)| (p as i128, q as i128));
    // Pixel k sits at major distance travel + k·unit: t = that / n.
    let first = (na * n - travel * da + unit * da - 1)
        .div_euclid(unit * da)
        .max(0);
    let last = (nb * n - travel * db).div_euclid(unit * db);
    if n == 0 || last < first {
        return 0;
    }
    let mut drawn = 0;
    for p in line
        .pixels()
        .skip(first as usize)
        .take((last - first + 1) as usize)
    {
        frame.set_pixel(p.x, p.y, index);
        drawn += 1;
    }
    drawn
}

/// The whole method on a prepared object (module doc).
fn walk_object<const S: u32>(
    prepared: &[PreparedVertex<S>],
    mesh: &Mesh<'_>,
    appel: &mut AppelScratch<'_>,
    sink: &mut impl FnMut(&AppelSegment<S>),
) -> Result<(), AppelError> {
    if let Some(v) = prepared.iter().position(|p| p.outcode != 0) {
        return Err(AppelError::VertexOutsideView { vertex: v as u16 });
    }
    let p = |i: u16| point(&prepared[i as usize]);
    let screen = |i: u16| prepared[i as usize].screen;
    // 1. The half-edges of the fans, each with its triangle's third vertex and facing.
    let needed = AppelScratch::edges_needed(mesh);
    let given = appel.edges.len();
    let half = appel
        .edges
        .get_mut(..needed)
        .ok_or(AppelError::ScratchTooSmall {
            table: AppelTable::Edges,
            given,
            needed,
        })?;
    let mut k = 0;
    for poly in mesh.polygons() {
        let m = poly.len();
        for j in 1..m.saturating_sub(1) {
            let tri = [poly[0], poly[j], poly[j + 1]];
            let front = twice_area(screen(tri[0]), screen(tri[1]), screen(tri[2])) < 0;
            for e in 0..3 {
                // A fan's own edges: v0–v1 of the first triangle, vj–vj+1, the last's closing.
                let own = match e {
                    0 => j == 1,
                    1 => true,
                    _ => j == m - 2,
                };
                half[k] = AppelEdge {
                    a: tri[e],
                    b: tri[(e + 1) % 3],
                    third: tri[(e + 2) % 3],
                    flags: (own as u8 * OWN) | (front as u8 * FRONT),
                };
                k += 1;
            }
        }
    }
    // 2. Pair them: each undirected edge twice, in opposite directions.
    let key = |e: &AppelEdge| (e.a.min(e.b), e.a.max(e.b), e.a);
    half.sort_unstable_by_key(key);
    let mut edges = 0;
    let mut i = 0;
    while i < half.len() {
        let (lo, hi) = (half[i].a.min(half[i].b), half[i].a.max(half[i].b));
        let mut j = i;
        while j < half.len() && key(&half[j]).0 == lo && key(&half[j]).1 == hi {
            j += 1;
        }
        let (x, y) = (half[i], half[i + 1..].first().copied().unwrap_or(half[i]));
        if j - i != 2 || x.a == y.a || (x.flags & OWN) != (y.flags & OWN) || lo == hi {
            return Err(AppelError::NotClosed {
                edge: [lo, hi],
                count: j - i,
            });
        }
        let (xf, yf) = (x.flags & FRONT != 0, y.flags & FRONT != 0);
        let back = |e: &AppelEdge| twice_area(screen(e.a), screen(e.b), screen(e.third)) > 0;
        // A contour edge keeps its front triangle's winding and third vertex.
        let mut rec = if yf && !xf { y } else { x };
        rec.flags &= OWN;
        if xf != yf {
            rec.flags |= CONTOUR;
        }
        if x.flags & OWN != 0 && !(back(&x) && back(&y)) {
            rec.flags |= WALKED;
        }
        half[edges] = rec;
        edges += 1;
        i = j;
    }
    // Contour edges first.
    let table = &mut half[..edges];
    table.sort_unstable_by_key(|e| e.flags & CONTOUR == 0);
    let contours = table.iter().take_while(|e| e.flags & CONTOUR != 0).count();
    let (table, crossings) = (&*table, &mut *appel.crossings);
    // The direct counts read the front triangles from the mesh's fans: no table needed.
    for e in table.iter().filter(|e| e.flags & WALKED != 0) {
        let (a, b) = (e.a.min(e.b), e.a.max(e.b));
        walk_edge(
            (a, b),
            &p,
            mesh,
            &table[..contours],
            crossings,
            prepared,
            sink,
        )?;
    }
    Ok(())
}

/// `QI` just after `P0` and just before `P1`, counted over the front triangles of the fans
/// (module doc, step 1), for the edge `P0 → P1` of vertices `ends`; refuses an edge that
/// passes through a front triangle it does not touch at a vertex (the mesh intersects
/// itself: the walk would miss that change).
fn direct_counts<const S: u32>(
    (p0, p1): (P3, P3),
    ends: [u16; 2],
    (p, xy): (&impl Fn(u16) -> P3, &impl Fn(u16) -> SubpixelPoint<S>),
    mesh: &Mesh<'_>,
) -> Result<(i32, i32), AppelError> {
    let u = [p1[0] - p0[0], p1[1] - p0[1]];
    let n = [-u[1], u[0]];
    let plus = |q: P3, v: [i128; 2]| [q[0] + v[0], q[1] + v[1], q[2]];
    let lo = [p0[0].min(p1[0]), p0[1].min(p1[1])].map(|c| c as i32);
    let hi = [p0[0].max(p1[0]), p0[1].max(p1[1])].map(|c| c as i32);
    let mut qi = (0, 0);
    for poly in mesh.polygons() {
        for j in 1..poly.len().saturating_sub(1) {
            let v = [poly[0], poly[j], poly[j + 1]];
            // The cheap rejections first: the bounding boxes (i32), then the facing (i64).
            let c = v.map(xy);
            let (tlo, thi) = (
                [
                    c[0].x.min(c[1].x).min(c[2].x),
                    c[0].y.min(c[1].y).min(c[2].y),
                ],
                [
                    c[0].x.max(c[1].x).max(c[2].x),
                    c[0].y.max(c[1].y).max(c[2].y),
                ],
            );
            if (0..2).any(|k| thi[k] < lo[k] || hi[k] < tlo[k]) {
                continue;
            }
            if twice_area(c[0], c[1], c[2]) >= 0 {
                continue;
            }
            let t = v.map(p);
            let (tlo, thi) = (tlo.map(|c| c as i128), thi.map(|c| c as i128));
            let holds = |q: P3| (0..2).all(|k| tlo[k] <= q[k] && q[k] <= thi[k]);
            // In front of `start`, just inside the edge (toward `other`), shifted by ε'n.
            let in_front = |start: P3, other: P3, dir: i128| {
                // Inside: each side's orientation negative (front winding), perturbed.
                let inside = (0..3).all(|e| {
                    let (x, y) = (t[e], t[(e + 1) % 3]);
                    let at = |q: P3| area(x, y, q);
                    let o0 = at(start);
                    let ou = dir * (at(plus(x, u)) - at(x));
                    let on = at(plus(x, n)) - at(x);
                    first_sign([o0, ou, on]) == Ordering::Less
                });
                // F(q, d) = Σ (d_k − d)·2A_k(q) = area2·(D_T(q) − d): in front when F > 0.
                let f = |q: P3| {
                    (t[0][2] - q[2]) * area(q, t[1], t[2])
                        + (t[1][2] - q[2]) * area(t[0], q, t[2])
                        + (t[2][2] - q[2]) * area(t[0], t[1], q)
                };
                inside && first_sign([f(start), f(other), 0]) == Ordering::Greater
            };
            if holds(p0) && in_front(p0, p1, 1) {
                qi.0 += 1;
            }
            if holds(p1) && in_front(p1, p0, -1) {
                qi.1 += 1;
            }
            if v.iter().any(|x| ends.contains(x)) {
                continue;
            }
            let sides = [
                orient3d(t[0], t[1], t[2], p0),
                orient3d(t[0], t[1], t[2], p1),
            ];
            if sides[0] == 0 || sides[1] == 0 || (sides[0] > 0) == (sides[1] > 0) {
                continue;
            }
            let around = [0, 1, 2].map(|e| orient3d(p0, p1, t[e], t[(e + 1) % 3]).signum());
            if around.iter().all(|&o| o >= 0) || around.iter().all(|&o| o <= 0) {
                return Err(AppelError::EdgePiercesFace {
                    edge: ends,
                    face: v,
                });
            }
        }
    }
    Ok(qi)
}

/// `det[b − a, c − a, x − a]` in screen space and depth (exact: differences below `2^29`,
/// `2^29`, `2^33`, products below `2^92`).
fn orient3d(a: P3, b: P3, c: P3, x: P3) -> i128 {
    let (u, v, w) = (
        [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
        [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        [x[0] - a[0], x[1] - a[1], x[2] - a[2]],
    );
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// Walks one edge (module doc, steps 1 to 3) and hands its pieces to `sink`.
fn walk_edge<const S: u32>(
    (a, b): (u16, u16),
    p: &impl Fn(u16) -> P3,
    mesh: &Mesh<'_>,
    contours: &[AppelEdge],
    crossings: &mut [AppelCrossing],
    prepared: &[PreparedVertex<S>],
    sink: &mut impl FnMut(&AppelSegment<S>),
) -> Result<(), AppelError> {
    let (p0, p1) = (p(a), p(b));
    let u = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
    if u[0] == 0 && u[1] == 0 {
        return Ok(()); // projects to a point: the ends of its neighbours
    }
    let mut count = 0;
    let (ux, uy) = (u[0] as i64, u[1] as i64);
    let (x0, y0) = (p0[0] as i64, p0[1] as i64);
    for c in contours {
        // Which side of the line each end lies on: exact in i64 (products below 2^58).
        let side = |i: u16| {
            let q = &prepared[i as usize].screen;
            ux * (q.y as i64 - y0) - uy * (q.x as i64 - x0)
        };
        let (s0, s1) = (side(c.a) as i128, side(c.b) as i128);
        if (s0 > 0) == (s1 > 0) {
            continue;
        }
        let (q0, q1) = (p(c.a), p(c.b));
        let v = [q1[0] - q0[0], q1[1] - q0[1]];
        let cross = u[0] * v[1] - u[1] * v[0];
        let w = [q0[0] - p0[0], q0[1] - p0[1]];
        let mut num = w[0] * v[1] - w[1] * v[0];
        let mut den = cross;
        if den < 0 {
            (num, den) = (-num, -den);
        }
        if num <= 0 || num >= den {
            continue; // at or beyond an end: in the direct counts
        }
        // det[u, Q0 − P0, Q1 − P0] = δ·(s0 − s1), δ the contour's depth minus the edge's.
        let (qa, qb) = (
            [q0[0] - p0[0], q0[1] - p0[1], q0[2] - p0[2]],
            [q1[0] - p0[0], q1[1] - p0[1], q1[2] - p0[2]],
        );
        let det = u[0] * (qa[1] * qb[2] - qa[2] * qb[1]) - u[1] * (qa[0] * qb[2] - qa[2] * qb[0])
            + u[2] * (qa[0] * qb[1] - qa[1] * qb[0]);
        if det == 0 {
            return Err(AppelError::ContourMeetsEdge {
                edge: [a, b],
                contour: [c.a, c.b],
            });
        }
        let nearer = (det < 0) == (s0 - s1 > 0);
        if !nearer {
            continue;
        }
        let given = crossings.len();
        let slot = crossings
            .get_mut(count)
            .ok_or(AppelError::ScratchTooSmall {
                table: AppelTable::Crossings,
                given,
                needed: count + 1,
            })?;
        *slot = AppelCrossing {
            num: num as i64,
            den: den as i64,
            step: if cross > 0 { 1 } else { -1 },
        };
        count += 1;
    }
    let list = &mut crossings[..count];
    let cmp = |x: &AppelCrossing, y: &AppelCrossing| {
        (x.num as i128 * y.den as i128).cmp(&(y.num as i128 * x.den as i128))
    };
    list.sort_unstable_by(cmp);
    let ends = [prepared[a as usize].screen, prepared[b as usize].screen];
    let emit = |from: (i64, i64), to: (i64, i64), sink: &mut dyn FnMut(&AppelSegment<S>)| {
        let at = |(num, den): (i64, i64)| {
            let r = |c0: i128, d: i128| {
                let (num, den) = (num as i128, den as i128);
                (2 * (c0 * den + num * d) + den).div_euclid(2 * den) as i32
            };
            SubpixelPoint::new(r(p0[0], u[0]), r(p0[1], u[1]))
        };
        sink(&AppelSegment {
            edge: [a, b],
            ends,
            range: [from, to],
            from: at(from),
            to: at(to),
        });
    };
    let xy = |i: u16| prepared[i as usize].screen;
    let (mut qi, counted) = direct_counts((p0, p1), [a, b], (p, &xy), mesh)?;
    let mut open: Option<(i64, i64)> = (qi == 0).then_some((0, 1));
    let mut k = 0;
    while k < list.len() {
        let mut j = k;
        while j < list.len() && cmp(&list[j], &list[k]) == Ordering::Equal {
            qi += list[j].step as i32;
            j += 1;
        }
        let t = (list[k].num, list[k].den);
        match (open, qi == 0) {
            (Some(from), false) => {
                emit(from, t, &mut *sink);
                open = None;
            }
            (None, true) => open = Some(t),
            _ => {}
        }
        k = j;
    }
    if counted != qi {
        return Err(AppelError::WalkDisagrees {
            edge: [a, b],
            walked: qi,
            counted,
        });
    }
    if let Some(from) = open {
        emit(from, (1, 1), &mut *sink);
    }
    Ok(())
}
