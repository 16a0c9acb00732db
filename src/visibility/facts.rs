//! What the planner knows of a mesh before any frame: its bounding box and its edge table,
//! computed once ([`MeshFacts::of`], `O(corners · log corners)`) and storable in flash beside
//! the mesh (every field is public and `const`-constructible); and the per-view check that
//! decides, on the screen positions the renderer actually draws, whether back faces alone
//! draw a mesh as the z-buffer does ([`front_faces_apart`]).
//!
//! ## The per-view check: the silhouette decides
//! The renderer draws a polygon whose vertices are all inside the frustum (outcode 0) as the
//! fan of triangles `(P_0, P_k, P_{k+1})` of its rounded screen vertices, when the fan's signed
//! area is negative (culling, `render/cull.rs`); each fan triangle is filled whatever its
//! orientation, by the half-open rule of `raster/edge_walker.rs` (a sample on a left edge or a
//! top edge is in, on a right or bottom edge out). That rule is the exact point-in-triangle
//! test for the sample moved by `(ε, ε²)` (`ε → 0⁺`, `y` down): a sample `s` is covered by a
//! triangle of non-zero area exactly when its boundary winds once around `s⁺`, and a triangle
//! of zero area covers nothing, as its boundary winds zero times around `s⁺`.
//!
//! Let `D` be the drawn polygons of one object. When **every fan triangle of every drawn
//! polygon has signed area `≤ 0`** (all wind the same way, `−1`, around what they cover), the
//! number of drawn triangles covering a sample is `c(s) = −Σ_t w(∂t, s⁺) = −w(B, s⁺)`, where
//! `B = Σ_{t} ∂t` is the boundary of the drawn fans as a chain of directed screen segments
//! (winding numbers add over chains). A fan's inner diagonals cancel in `B`, and so does an
//! edge of a drawn polygon against the same edge, reversed, of another drawn polygon: `B` is
//! the **silhouette** of the drawn faces (each remaining directed edge of a drawn polygon).
//! Only the pairing of edges with their reverse is taken from the mesh ([`Convexity::Convex`]'s
//! `twins`, checked per use: a wrong table only keeps edges in `B`).
//!
//! The check then asks that `B` be **star-shaped** around the centroid `c` of its edges' start
//! points: every edge of `B` turns strictly the same way around `c` (exact orientation tests,
//! `c` kept as a fraction), and `B` winds exactly once around `c` (crossings of the ray from `c`
//! towards `+x`). Then every ray from `c` crosses `B` exactly once (the crossings all have one
//! sign and add up to the winding at `c`), so for any point `p` the ray from `p` away from `c`
//! crosses `B` once or never: `w(B, p) ∈ {0, ±1}` everywhere off `B`, and `c(s) ≤ 1` at every
//! sample (`c(s) ≥ 0`, being a count). An empty `B` gives `c ≡ 0`. **No sample is covered by
//! two drawn triangles of the object**: back faces alone draw at each sample the one triangle
//! the z-buffer draws there, with the same spans and shading. The argument uses nothing but the
//! rounded screen positions of this view: coplanar or overlapping faces, self-intersecting
//! polygons, faces of zero area in the mesh, thin or tiny objects and mirroring transforms are
//! all decided as drawn (a fold makes `c(s) = 2` somewhere, which the check cannot pass).
//!
//! A polygon with a vertex outside the frustum (clipped, or rejected) makes the check refuse
//! ([`Refusal::LeavesFrustum`]): the clipper's new vertices are not looked at.
//!
//! ## The edge table and the convexity hint
//! [`MeshFacts::of`] pairs every corner `h` of a mesh of one polygon size (the directed edge
//! from its vertex to the next corner's) with the corner whose edge is its reverse, when exactly
//! one edge joins the two vertices each way (sorting the edges: `O(corners · log corners)`,
//! [`MeshFacts::words_needed`] words of caller memory). The check reads it in `O(corners)` per
//! view with no memory of its own.
//!
//! The table is kept only for meshes that may pass the check: [`Convexity::NotConvex`] when an
//! edge is met twice the same way or when two paired polygons fold inward by more than about
//! a degree (a vertex of one in front of the other's plane by more than `1/64` of the plane
//! normal's `‖·‖₁` times its offset's `‖·‖∞`), or when polygon sizes vary or exceed 16
//! corners. This is a **hint**
//! that spares the per-view check on meshes that would fail it (a torus, the bunny); it is
//! not part of the argument, which holds whatever the table says.
//!
//! Numeric contract: mesh coordinates `|c| ≤ 2^26` raw, so a point–plane side `(v − p_0)·n`
//! is below `2^92` (`i128`); projected positions are within `±(2^28 − 1)` sub-pixel units and
//! `B` has fewer than `2^32` edges, so a position scaled by their count is below `2^61` and an
//! orientation below `2^123` (`i128`). Corners are numbered in `u32` ([`NO_TWIN`] is the
//! largest value); a mesh of `u32::MAX` corners or more is [`Convexity::NotConvex`].

use crate::clip::frustum::Frustum;
use crate::geometry::matrix::Affine3;
use crate::geometry::mesh::{Mesh, PolygonSizes};
use crate::project::Projector;
use crate::raster::SubpixelPoint;
use crate::render::{screen_area, PreparedVertex};

/// A mesh's convexity hint and edge table (the module doc of `visibility/facts.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Convexity<'a> {
    /// Polygons of one size, no edge met twice the same way, no paired polygons folding inward
    /// beyond the hint's margin: back faces alone may draw it, as each view's check decides.
    Convex {
        /// Per corner `h` (index into the mesh's index table), the corner whose edge is the
        /// reverse of `h`'s, or [`NO_TWIN`].
        twins: &'a [u32],
    },
    /// Not a candidate for back faces alone: the planner keeps a depth buffer for it.
    NotConvex,
}

/// [`Convexity::Convex`]'s mark of a corner whose edge has no reverse (or more than one).
pub const NO_TWIN: u32 = u32::MAX;

/// What the planner knows of a mesh, computed once ([`MeshFacts::of`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshFacts<'a> {
    /// The convexity hint, with the edge table the per-view check reads.
    pub convexity: Convexity<'a>,
    /// Smallest and largest raw coordinate per axis, over all vertices (zeros when empty).
    pub bounds: [[i32; 3]; 2],
}

/// Why [`MeshFacts::of`] made no facts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FactsError {
    /// The buffer is shorter than [`MeshFacts::words_needed`].
    BufferTooSmall {
        /// Words needed.
        needed: usize,
        /// Words given.
        given: usize,
    },
}

impl core::fmt::Display for FactsError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FactsError::BufferTooSmall { needed, given } => write!(
                f,
                "the mesh's facts need {needed} words (u32) of buffer, {given} given \
                 (MeshFacts::words_needed)"
            ),
        }
    }
}

impl core::error::Error for FactsError {}

/// The hint's margin: paired polygons fold inward by at most `1/2^FOLD_HINT_BITS` (module
/// doc).
const FOLD_HINT_BITS: u32 = 6;

/// The polygon size of a mesh the check can read, with its corner count (`None`: polygon sizes
/// vary or exceed [`MAX_CORNERS`], or too many corners to number in `u32`).
fn uniform(mesh: &Mesh<'_>) -> Option<(usize, usize)> {
    let n = mesh.indices().len();
    match mesh.sizes() {
        PolygonSizes::Uniform(k)
            if (3..=MAX_CORNERS).contains(&(k as usize)) && n < NO_TWIN as usize =>
        {
            Some((k as usize, n))
        }
        _ => None,
    }
}

/// The corner after `h` in its polygon (polygons of `k` corners).
fn next(h: usize, k: usize) -> usize {
    if h % k == k - 1 {
        h + 1 - k
    } else {
        h + 1
    }
}

/// `(v − p0)·n`, exact (module doc's bound).
fn side(v: [i32; 3], p0: [i32; 3], n: [i64; 3]) -> i128 {
    (0..3)
        .map(|k| (v[k] as i64 - p0[k] as i64) as i128 * n[k] as i128)
        .sum()
}

impl<'a> MeshFacts<'a> {
    /// The `u32` words [`of`](Self::of) needs for `mesh`: twice its corners (the first half
    /// keeps the edge table, the second is sorting scratch) for a mesh of one polygon size,
    /// none otherwise (such a mesh is [`Convexity::NotConvex`]).
    pub fn words_needed(mesh: &Mesh<'_>) -> usize {
        uniform(mesh).map_or(0, |(_, n)| 2 * n)
    }

    /// The facts of `mesh`: its bounds, its convexity hint and edge table (module doc), the
    /// table written into `words` (at least [`words_needed`](Self::words_needed) long, else
    /// [`FactsError::BufferTooSmall`]). Cost `O(corners · log corners)`; compute it once and
    /// keep it (`MeshFacts` is plain data: a `static` beside the mesh's tables).
    pub fn of(mesh: &Mesh<'_>, words: &'a mut [u32]) -> Result<MeshFacts<'a>, FactsError> {
        let needed = Self::words_needed(mesh);
        if words.len() < needed {
            return Err(FactsError::BufferTooSmall {
                needed,
                given: words.len(),
            });
        }
        let mut bounds = [[i32::MAX; 3], [i32::MIN; 3]];
        for v in mesh.vertices() {
            for (k, &c) in v.bits().iter().enumerate() {
                bounds[0][k] = bounds[0][k].min(c);
                bounds[1][k] = bounds[1][k].max(c);
            }
        }
        if mesh.vertices().is_empty() {
            bounds = [[0; 3]; 2];
        }
        let convexity = match uniform(mesh) {
            Some((k, n)) => {
                let (twins, scratch) = words[..2 * n].split_at_mut(n);
                if pair_edges(mesh, k, twins, scratch) && !folds_inward(mesh, k, twins) {
                    Convexity::Convex { twins }
                } else {
                    Convexity::NotConvex
                }
            }
            None => Convexity::NotConvex,
        };
        Ok(MeshFacts { convexity, bounds })
    }
}

/// Writes each corner's twin into `twins` (module doc; `scratch` as long), sorting the corners
/// by their edge's two vertices. False when an edge is met twice the same way.
fn pair_edges(mesh: &Mesh<'_>, k: usize, twins: &mut [u32], scratch: &mut [u32]) -> bool {
    let idx = mesh.indices();
    // `twins[h]` holds the vertex `h`'s edge ends at until `h`'s group is paired.
    for (h, t) in twins.iter_mut().enumerate() {
        *t = idx[next(h, k)] as u32;
    }
    for (h, s) in scratch.iter_mut().enumerate() {
        *s = h as u32;
    }
    // The undirected edge, then its direction (`a > b` last).
    let key = |twins: &[u32], h: u32| {
        let (a, b) = (idx[h as usize] as u32, twins[h as usize]);
        ((a.min(b) as u64) << 17) | ((a.max(b) as u64) << 1) | (a > b) as u64
    };
    scratch.sort_unstable_by_key(|&h| key(twins, h));
    let mut start = 0;
    while start < scratch.len() {
        let edge = key(twins, scratch[start]) >> 1;
        let mut end = start + 1;
        while end < scratch.len() && key(twins, scratch[end]) >> 1 == edge {
            end += 1;
        }
        let group = &scratch[start..end];
        let keys = (
            key(twins, group[0]) & 1,
            group.get(1).map(|&h| key(twins, h) & 1),
        );
        if group.len() >= 2 && (keys.1 == Some(keys.0) || group.get(2).is_some()) {
            return false; // an edge met twice the same way
        }
        match *group {
            [a, b] => {
                twins[a as usize] = b;
                twins[b as usize] = a;
            }
            [a] => twins[a as usize] = NO_TWIN,
            _ => {}
        }
        start = end;
    }
    true
}

/// True when two paired polygons fold inward beyond the hint's margin (module doc).
fn folds_inward(mesh: &Mesh<'_>, k: usize, twins: &[u32]) -> bool {
    let idx = mesh.indices();
    let vertex = |i: u16| mesh.vertices().get(i as usize).map_or([0; 3], |v| v.bits());
    twins.iter().enumerate().any(|(h, &t)| {
        if t == NO_TWIN {
            return false;
        }
        let (p, q) = (h / k * k, t as usize / k * k);
        let n = mesh.face_normal_wide(&idx[p..p + k]);
        let p0 = vertex(idx[p]);
        let norm: i128 = n.iter().map(|&c| (c as i128).abs()).sum();
        idx[q..q + k].iter().any(|&i| {
            let v = vertex(i);
            let reach = (0..3)
                .map(|a| (v[a] as i64 - p0[a] as i64).abs())
                .max()
                .unwrap_or(0) as i128;
            side(v, p0, n) << FOLD_HINT_BITS > norm * reach
        })
    })
}

/// Why the per-view check refuses back faces alone for a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Refusal {
    /// A polygon has a vertex outside the frustum (it would be clipped or rejected).
    LeavesFrustum,
    /// Two drawn triangles may cover one sample (module doc).
    FrontFacesMayOverlap,
}

/// Back faces alone draw `mesh` as the z-buffer does in this view (module doc): `at(i)` is
/// vertex `i` on screen as the vertex stage places it, `None` outside the frustum; `twins` is
/// the mesh's edge table. `O(corners)` calls of `at` and orientation tests; 256 bytes of
/// stack.
pub(crate) fn front_faces_apart<const S: u32>(
    mesh: &Mesh<'_>,
    twins: &[u32],
    at: &mut impl FnMut(u16) -> Option<SubpixelPoint<S>>,
) -> Result<(), Refusal> {
    let Some((k, n)) = uniform(mesh) else {
        return Err(Refusal::FrontFacesMayOverlap);
    };
    let mut check = Check {
        idx: mesh.indices(),
        k,
        n,
        twins,
        at,
    };
    let (mut sum, mut m) = ([0i128; 2], 0i128);
    check.silhouette(&mut |a, _| {
        sum[0] += a.x as i128;
        sum[1] += a.y as i128;
        m += 1;
        true
    })?;
    if m == 0 {
        return Ok(());
    }
    // Positions relative to the centroid, scaled by `m`.
    let rel = |p: SubpixelPoint<S>| [p.x as i128 * m - sum[0], p.y as i128 * m - sum[1]];
    let (mut turn, mut winding) = (0i128, 0i32);
    check.silhouette(&mut |a, b| {
        let (a, b) = (rel(a), rel(b));
        let cross = a[0] * b[1] - a[1] * b[0];
        if cross == 0 || cross.signum() * turn < 0 {
            return false;
        }
        turn = cross.signum();
        if a[1] <= 0 && b[1] > 0 && cross > 0 {
            winding += 1;
        } else if a[1] > 0 && b[1] <= 0 && cross < 0 {
            winding -= 1;
        }
        true
    })?;
    if winding.abs() == 1 {
        Ok(())
    } else {
        Err(Refusal::FrontFacesMayOverlap)
    }
}

/// The largest polygon the per-view check reads (meshes of larger polygons are
/// [`Convexity::NotConvex`]).
const MAX_CORNERS: usize = 16;

/// One run of [`front_faces_apart`].
struct Check<'c, F> {
    idx: &'c [u16],
    /// Corners per polygon, and in all.
    k: usize,
    n: usize,
    twins: &'c [u32],
    at: &'c mut F,
}

impl<F> Check<'_, F> {
    /// Places the corners of the polygon whose first corner is `p` into `out`: `Ok(true)` when
    /// it is drawn (every fan triangle checked to turn the drawn way), `Ok(false)` when culled.
    fn drawn<const S: u32>(
        &mut self,
        p: usize,
        out: &mut [SubpixelPoint<S>; MAX_CORNERS],
    ) -> Result<bool, Refusal>
    where
        F: FnMut(u16) -> Option<SubpixelPoint<S>>,
    {
        let k = self.k;
        for (c, &i) in out.iter_mut().zip(&self.idx[p..p + k]) {
            *c = (self.at)(i).ok_or(Refusal::LeavesFrustum)?;
        }
        if screen_area(k, |j| out[j]) >= 0 {
            return Ok(false);
        }
        if (1..k - 1).any(|j| orient(out[0], out[j], out[j + 1]) > 0) {
            return Err(Refusal::FrontFacesMayOverlap);
        }
        Ok(true)
    }

    /// Hands each silhouette edge's screen ends to `edge` (module doc); an edge it refuses
    /// (`false`) ends the run.
    fn silhouette<const S: u32>(
        &mut self,
        edge: &mut impl FnMut(SubpixelPoint<S>, SubpixelPoint<S>) -> bool,
    ) -> Result<(), Refusal>
    where
        F: FnMut(u16) -> Option<SubpixelPoint<S>>,
    {
        let (k, n) = (self.k, self.n);
        let origin = SubpixelPoint::<S>::new(0, 0);
        let (mut c, mut other) = ([origin; MAX_CORNERS], [origin; MAX_CORNERS]);
        for p in (0..n).step_by(k) {
            if !self.drawn(p, &mut c)? {
                continue;
            }
            for j in 0..k {
                let h = p + j;
                let t = self.twins.get(h).map_or(NO_TWIN, |&t| t) as usize;
                let paired = t < n
                    && self.twins.get(t) == Some(&(h as u32))
                    && self.idx[t] == self.idx[next(h, k)]
                    && self.idx[next(t, k)] == self.idx[h];
                if paired && self.drawn(t / k * k, &mut other)? {
                    continue;
                }
                if !edge(c[j], c[(j + 1) % k]) {
                    return Err(Refusal::FrontFacesMayOverlap);
                }
            }
        }
        Ok(())
    }
}

/// How [`front_faces_apart`] places a mesh's vertices on screen when no vertex stage ran for
/// it: the renderer's own transform, frustum and projector.
pub(crate) struct View<'v, const S: u32> {
    pub(crate) model_view: &'v Affine3,
    pub(crate) frustum: &'v Frustum,
    pub(crate) projector: &'v Projector<S>,
}

/// [`front_faces_apart`] with `mesh`'s vertices placed in `view` as the check needs them
/// (each at most once per slot of a 2 KB cache).
pub(crate) fn apart_in<const S: u32>(
    mesh: &Mesh<'_>,
    twins: &[u32],
    view: &View<'_, S>,
) -> Result<(), Refusal> {
    let mut cache = Placed::<S>::new();
    front_faces_apart(mesh, twins, &mut |i| cache.vertex(mesh, i, view))
}

/// [`front_faces_apart`] with `mesh`'s vertices as the vertex stage left them in `prepared`
/// (as long as its vertex table).
pub(crate) fn apart_prepared<const S: u32>(
    mesh: &Mesh<'_>,
    twins: &[u32],
    prepared: &[PreparedVertex<S>],
) -> Result<(), Refusal> {
    let mut at = |i: u16| {
        let p = prepared.get(i as usize)?;
        (p.outcode == 0).then_some(p.screen)
    };
    front_faces_apart(mesh, twins, &mut at)
}

/// Entries of [`Placed`]: a power of two.
const PLACED: usize = 128;

/// The screen positions [`apart_in`] has placed, direct-mapped by vertex index (2 KB on the
/// stack): neighbouring polygons share vertices, so most are placed once, not once per
/// polygon.
struct Placed<const S: u32> {
    /// Vertex index + 1 (0: empty), and its position (`None`: outside the frustum).
    slots: [(u32, Option<SubpixelPoint<S>>); PLACED],
}

impl<const S: u32> Placed<S> {
    fn new() -> Self {
        Placed {
            slots: [(0, None); PLACED],
        }
    }

    /// Vertex `i` on screen, as the vertex stage places it, or `None` when it is outside the
    /// frustum (the polygon stage would clip its polygons).
    fn vertex(&mut self, mesh: &Mesh<'_>, i: u16, view: &View<'_, S>) -> Option<SubpixelPoint<S>> {
        let slot = &mut self.slots[i as usize % PLACED];
        if slot.0 != i as u32 + 1 {
            *slot = (i as u32 + 1, place_vertex(mesh, i, view));
        }
        slot.1
    }
}

/// Vertex `i` on screen, as the vertex stage places it, or `None` outside the frustum.
fn place_vertex<const S: u32>(
    mesh: &Mesh<'_>,
    i: u16,
    view: &View<'_, S>,
) -> Option<SubpixelPoint<S>> {
    let p = view
        .model_view
        .transform_point(*mesh.vertices().get(i as usize)?);
    if view.frustum.outcode(p) != 0 {
        return None;
    }
    Some(view.projector.project_point(p).ok()?.0)
}

/// `(q − p) × (r − p)` on screen (`< 2^59`, module doc): the raster's one orientation.
fn orient<const S: u32>(p: SubpixelPoint<S>, q: SubpixelPoint<S>, r: SubpixelPoint<S>) -> i64 {
    crate::raster::triangle::twice_area(p, q, r)
}
