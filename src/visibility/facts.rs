//! What the planner knows of a mesh before any frame: its bounding box and its convexity
//! certificate, computed once ([`MeshFacts::of`]) and storable in flash beside the mesh (every
//! field is public and `const`-constructible).
//!
//! ## Convexity, and the creases of rounded meshes
//! [`Convexity::Convex`]: every vertex on or behind every face plane
//! ([`Mesh::is_convex`], exact). Then no two front faces overlap on screen and back-face
//! culling alone gives the z-buffer's picture.
//!
//! Meshes that are convex as designed but whose vertices were turned and rounded to I16F16
//! (SCENES.md's cube and sphere) fail that test by a rounding step (about `2·10^-5` of their
//! size). [`Convexity::Creased`] keeps for them the exact facts that decide, per view, whether
//! any two front faces can overlap. The argument, for a closed, consistently oriented triangle
//! mesh seen from an eye `E` outside it:
//!
//! 1. If front faces `A` and `B` overlap at a screen point, with `A` nearer (`a` on `A`, `b` on
//!    `B`, `a` between `E` and `b` on the ray), then `a` is strictly in front of `B`'s plane
//!    (`E` is, `b` is on it), so **some vertex of `A` is strictly in front of `B`'s plane**.
//!    Faces that share an edge (traversed in opposite directions) never overlap when both are
//!    front: their third vertices project on opposite sides of the shared edge. So `A` is in
//!    `B`'s list of *occluders* ([`Creases::occluders`]: not sharing an edge with `B`, with a
//!    vertex strictly in front of its plane).
//! 2. The ray enters the solid at `a` and again at `b` (front faces), so it leaves it in
//!    between, at `c` on a face `C` that is not front. `c` lies between `E` and `b`: strictly
//!    in front of `B`'s plane. `E` is behind (or on) `C`'s plane and `c` on it, so `b`, beyond
//!    `c`, is strictly in front of it. **`B` and `C` each have a vertex strictly in front of the
//!    other's plane** ([`Creases::mutual`]), and in this view one is front and the other not.
//!
//! So for each view, [`Creases::hold`] looks only at the mutual pairs whose faces straddle the
//! silhouette, and for the front one, `B`, at its occluders `A` that are front too: if the two
//! projected triangles, as the renderer draws them, are separated by a line through an edge of
//! either (exact `i64` orientation tests), they share no pixel (the fill rule's top-left
//! convention draws a sample on a shared line for one side only). If every such pair is
//! separated, no two front faces overlap and back faces alone give the z-buffer's picture.
//! An exactly convex mesh has no mutual pair; the rounded standard cube has 6 (the diagonals of
//! its faces, creased a rounding step in or out, and 2 more), the sphere 296.
//!
//! The planner does not use a certificate under a mirroring transform (negative determinant):
//! it turns the mesh inside out, and step 2's solid would hold the eye.
//!
//! ## Rounding
//! What the argument takes as given (as [`Mesh::is_convex`] does): the mesh as its vertex
//! table places it, mapped by the object's transform and projected exactly. The renderer rounds
//! the observer-frame positions to I16F16 and the screen positions to `2^-S` pixel; the pairs
//! decided here are tested on those rounded screen positions, the others are argued on the
//! mesh. Where the rounding is comparable with the triangles (an object a few pixels across or
//! less), triangles that share only a vertex can fold onto each other: a 51-vertex sphere under
//! a pixel across drew 1 pixel wrong by back faces alone. So the planner trusts the certificate
//! only under a **rounding guard**: the rounding, taken back to the mesh's frame, must move each
//! vertex by at most [`MeshFacts::tolerance`], the mesh's shortest edge over [`FOLD_GUARD`]
//! (`plan.rs` bounds the move per view). This is a guard, not a proof: the divisor is set with
//! a margin of 2 over the smallest that keeps the picture on the tests' 9,000 random small and
//! far objects (`host-tests/tests/plan.rs`); the tests compare with the z-buffer pixel by pixel.
//!
//! Numeric contract: mesh coordinates `|c| ≤ 2^26` raw, so a point–plane side
//! `(v − p_0)·n` is below `2^27·2^63·3 < 2^92` (`i128`); projected positions are within
//! `±(2^28 − 1)` sub-pixel units, so a screen orientation is below `2^59` (`i64`). Face
//! indices are `u32`.

use crate::clip::frustum::Frustum;
use crate::geometry::matrix::Affine3;
use crate::geometry::mesh::{Mesh, PolygonSizes};
use crate::project::Projector;
use crate::raster::SubpixelPoint;
use crate::render::PreparedVertex;

/// A mesh's convexity certificate (the module doc of `visibility/facts.rs` gives the
/// argument).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Convexity<'a> {
    /// Every vertex on or behind every face plane: back faces alone draw it right from any
    /// view.
    Convex,
    /// A closed triangle mesh convex but for creases: back faces alone draw it right in the
    /// views where its creases hold (checked per frame by the planner).
    Creased(Creases<'a>),
    /// Neither (or the certificate did not fit its buffer, or the mesh is not a closed,
    /// consistently oriented triangle mesh): front faces may overlap.
    NotConvex,
}

/// The face pairs that decide, per view, whether a creased mesh's front faces overlap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Creases<'a> {
    /// `[b, c]`: faces each with a vertex strictly in front of the other's plane.
    pub mutual: &'a [[u32; 2]],
    /// `[b, a]`, sorted by `b`: face `a` shares no edge with face `b` and has a vertex strictly
    /// in front of `b`'s plane.
    pub occluders: &'a [[u32; 2]],
}

/// What the planner knows of a mesh, computed once ([`MeshFacts::of`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshFacts<'a> {
    /// The convexity certificate.
    pub convexity: Convexity<'a>,
    /// Smallest and largest raw coordinate per axis, over all vertices (zeros when empty).
    pub bounds: [[i32; 3]; 2],
    /// The rounding guard: the most (raw mesh units, per coordinate) the renderer's rounding
    /// may move a vertex, taken back to the mesh's frame, for the planner to trust the
    /// certificate: the mesh's shortest edge (`‖·‖∞`) over 4 (`FOLD_GUARD`, module doc,
    /// "Rounding").
    pub tolerance: i32,
}

/// The rounding guard's divisor: the renderer's rounding must move each vertex by at most
/// this fraction of the mesh's shortest edge (module doc, "Rounding").
pub(crate) const FOLD_GUARD: i32 = 4;

/// The shortest edge of `mesh`'s polygons, `‖·‖∞` raw (`i32::MAX` without an edge).
fn shortest_edge(mesh: &Mesh<'_>) -> i32 {
    let vertex = |i: u16| mesh.vertices().get(i as usize).map_or([0; 3], |v| v.bits());
    let mut shortest = i32::MAX as i64;
    for poly in mesh.polygons() {
        for (k, &i) in poly.iter().enumerate() {
            let (u, v) = (vertex(i), vertex(poly[(k + 1) % poly.len()]));
            let d = (0..3).map(|a| (u[a] as i64 - v[a] as i64).abs()).max();
            shortest = shortest.min(d.unwrap_or(0));
        }
    }
    shortest.min(i32::MAX as i64) as i32
}

/// `(v − p0)·n`, exact (module doc's bound).
fn side(v: [i32; 3], p0: [i32; 3], n: [i64; 3]) -> i128 {
    (0..3)
        .map(|k| (v[k] as i64 - p0[k] as i64) as i128 * n[k] as i128)
        .sum()
}

/// True when triangles `a` and `b` share an edge traversed in opposite directions.
fn share_edge(a: &[u16], b: &[u16]) -> bool {
    (0..3).any(|i| (0..3).any(|j| a[i] == b[(j + 1) % 3] && a[(i + 1) % 3] == b[j]))
}

impl<'a> MeshFacts<'a> {
    /// The facts of `mesh`: its bounds and its convexity, with a creased mesh's face pairs
    /// written into `pairs` (two `u32` per pair; a certificate longer than `pairs` makes the
    /// mesh [`Convexity::NotConvex`], which is conservative). Cost: [`Mesh::is_convex`], then
    /// for a mesh that fails it `O(faces²)` point–plane tests; compute it once and keep it
    /// (`MeshFacts` is plain data: a `static` beside the mesh's tables).
    pub fn of(mesh: &Mesh<'_>, pairs: &'a mut [[u32; 2]]) -> MeshFacts<'a> {
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
        let convexity = if mesh.is_convex() {
            Convexity::Convex
        } else {
            creases(mesh, pairs).map_or(Convexity::NotConvex, Convexity::Creased)
        };
        let tolerance = shortest_edge(mesh) / FOLD_GUARD;
        MeshFacts {
            convexity,
            bounds,
            tolerance,
        }
    }
}

/// The creases of a closed, consistently oriented triangle mesh, or `None` (not such a mesh,
/// or `pairs` too short).
fn creases<'a>(mesh: &Mesh<'_>, pairs: &'a mut [[u32; 2]]) -> Option<Creases<'a>> {
    if mesh.sizes() != PolygonSizes::Uniform(3) {
        return None;
    }
    let faces = mesh.indices();
    let vertex = |i: u16| mesh.vertices().get(i as usize).map_or([0; 3], |v| v.bits());
    let plane = |f: &[u16]| (mesh.face_normal_wide(f), vertex(f[0]));
    let ahead = |f: &[u16], (n, p0): ([i64; 3], [i32; 3])| {
        n != [0; 3] && f.iter().any(|&i| side(vertex(i), p0, n) > 0)
    };
    let (mut occluders, mut mutual) = (0usize, 0usize);
    for (bi, b) in faces.chunks_exact(3).enumerate() {
        let pb = plane(b);
        // Closed and consistently oriented: each directed edge of `b` is met reversed exactly
        // once, and never in the same direction, by the other faces.
        let mut reversed = [0u32; 3];
        for (ci, c) in faces.chunks_exact(3).enumerate() {
            if ci == bi {
                continue;
            }
            for k in 0..3 {
                let (u, v) = (b[k], b[(k + 1) % 3]);
                for j in 0..3 {
                    let (x, y) = (c[j], c[(j + 1) % 3]);
                    if (x, y) == (u, v) {
                        return None;
                    }
                    reversed[k] += ((x, y) == (v, u)) as u32;
                }
            }
            if !ahead(c, pb) {
                continue;
            }
            if !share_edge(b, c) {
                *pairs.get_mut(occluders)? = [bi as u32, ci as u32];
                occluders += 1;
            }
            if ci > bi && ahead(b, plane(c)) {
                mutual += 1;
                let at = pairs.len().checked_sub(mutual)?;
                if at < occluders {
                    return None;
                }
                pairs[at] = [bi as u32, ci as u32];
            }
            if occluders + mutual > pairs.len() {
                return None;
            }
        }
        if reversed != [1; 3] {
            return None;
        }
    }
    let pairs: &'a [[u32; 2]] = pairs;
    let at = pairs.len() - mutual;
    Some(Creases {
        mutual: &pairs[at..],
        occluders: &pairs[..occluders],
    })
}

/// How [`Creases::hold`] places a mesh's vertices on screen when no vertex stage ran for it:
/// the renderer's own transform, frustum and projector.
pub(crate) struct View<'v, const S: u32> {
    pub(crate) model_view: &'v Affine3,
    pub(crate) frustum: &'v Frustum,
    pub(crate) projector: &'v Projector<S>,
}

impl Creases<'_> {
    /// True when no two front faces of `mesh` overlap on screen (module doc): every mutual
    /// pair straddling the silhouette has its front face separated on screen from each of that
    /// face's front occluders. `at(i)` is vertex `i` on screen as the vertex stage places it,
    /// `None` outside the frustum (or unprojected); a face with such a vertex (clipped) makes
    /// the answer `false`.
    pub(crate) fn hold<const S: u32>(
        &self,
        mesh: &Mesh<'_>,
        at: &mut impl FnMut(u16) -> Option<SubpixelPoint<S>>,
    ) -> bool {
        let mut face = |f: u32| -> Option<[SubpixelPoint<S>; 3]> {
            let k = f as usize * 3;
            let idx = mesh.indices().get(k..k + 3)?;
            Some([at(idx[0])?, at(idx[1])?, at(idx[2])?])
        };
        for &[b, c] in self.mutual {
            let (Some(tb), Some(tc)) = (face(b), face(c)) else {
                return false;
            };
            let (fb, fc) = (twice_area(&tb) < 0, twice_area(&tc) < 0);
            if fb == fc {
                continue;
            }
            let (front, t) = if fb { (b, tb) } else { (c, tc) };
            let from = self.occluders.partition_point(|p| p[0] < front);
            for &[_, a] in self.occluders[from..].iter().take_while(|p| p[0] == front) {
                let Some(ta) = face(a) else {
                    return false;
                };
                if twice_area(&ta) < 0 && !separated(&t, &ta) {
                    return false;
                }
            }
        }
        true
    }

    /// [`hold`](Self::hold) with `mesh`'s vertices placed in `view` as the check needs them
    /// (each at most once per slot of a 2 KB cache).
    pub(crate) fn hold_in<const S: u32>(&self, mesh: &Mesh<'_>, view: &View<'_, S>) -> bool {
        let mut cache = Placed::<S>::new();
        self.hold(mesh, &mut |i| cache.vertex(mesh, i, view))
    }

    /// [`hold`](Self::hold) with `mesh`'s vertices as the vertex stage left them in
    /// `prepared` (as long as its vertex table).
    pub(crate) fn hold_prepared<const S: u32>(
        &self,
        mesh: &Mesh<'_>,
        prepared: &[PreparedVertex<S>],
    ) -> bool {
        let mut at = |i: u16| {
            let p = prepared.get(i as usize)?;
            (p.outcode == 0).then_some(p.screen)
        };
        self.hold(mesh, &mut at)
    }
}

/// Entries of [`Placed`]: a power of two.
const PLACED: usize = 128;

/// The screen positions [`Creases::hold_in`] has placed, direct-mapped by vertex index (2 KB
/// on the stack): neighbouring face pairs share vertices, so most are placed once, not once
/// per face (measured on the standard sphere: `plan_sphere` in `docs/BENCHMARKS.md`).
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
    /// frustum (the polygon stage would clip its faces).
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

/// `(q − p) × (r − p)` on screen (`< 2^59`, module doc).
fn orient<const S: u32>(p: SubpixelPoint<S>, q: SubpixelPoint<S>, r: SubpixelPoint<S>) -> i64 {
    (q.x as i64 - p.x as i64) * (r.y as i64 - p.y as i64)
        - (q.y as i64 - p.y as i64) * (r.x as i64 - p.x as i64)
}

/// Twice the signed screen area: negative for a front face (the renderer's culling rule).
fn twice_area<const S: u32>(t: &[SubpixelPoint<S>; 3]) -> i64 {
    orient(t[0], t[1], t[2])
}

/// True when a line through an edge of one triangle has the other on its far side (or on it):
/// their interiors are disjoint, and the fill rule draws no sample for both.
fn separated<const S: u32>(t: &[SubpixelPoint<S>; 3], u: &[SubpixelPoint<S>; 3]) -> bool {
    let by_edge_of = |t: &[SubpixelPoint<S>; 3], u: &[SubpixelPoint<S>; 3]| {
        (0..3).any(|k| {
            let (p, q, r) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let own = orient(p, q, r).signum();
            own != 0 && u.iter().all(|&x| orient(p, q, x).signum() * own <= 0)
        })
    };
    by_edge_of(t, u) || by_edge_of(u, t)
}
