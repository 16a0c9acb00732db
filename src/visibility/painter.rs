//! The depth-sort painter (Newell, Newell and Sancha 1972; the survey's "priorité
//! dynamique", course ch. 3 §2.1): front triangles sorted by their farthest depth, overlaps
//! resolved by the survey's tests, drawn back to front with no depth buffer.
//!
//! Space: the tests work on the projected triangles, `(X, Y, D)` with `X, Y` the sub-pixel
//! screen position and `D` the 32-bit depth. The projection's depth is affine in screen
//! position over a triangle (the z-buffer interpolates it linearly), so a triangle is a plane
//! there too, and "behind" means a larger `D` at the same `(X, Y)`: exactly what the z-buffer
//! compares at each pixel. `P` may be painted before `Q` (Q then wins where they overlap) when
//! one of these holds, tried in the survey's order:
//!
//! 1. their depth ranges do not overlap (`P`'s nearest corner is at least as far as `Q`'s
//!    farthest);
//! 2. their screen boxes are disjoint in `x`, or in `y`;
//! 3. `P` lies wholly behind (or on) `Q`'s plane;
//! 4. `Q` lies wholly in front of (or on) `P`'s plane;
//! 5. their projections are disjoint (the line through an edge of one has the other on it or
//!    outside: their interiors are disjoint, and the fill rule draws no sample for both, so
//!    mesh neighbours sharing an edge or a corner pass; `separated`), or they share no pixel
//!    sample of the frame (no lattice point of the frame lies inside or on the edges of both,
//!    row by row, exactly: `share_a_sample`). Two triangles that touch or overlap only
//!    between pixel centres (the bunny's folds near its outline) then need no split.
//!
//! **Ties** follow the z-buffer's rule: where two surfaces are at exactly the same depth, the
//! z-buffer keeps the one it drew first, the triangle stored first (scene order). So "or on"
//! in tests 1, 3 and 4 holds only when `Q` was stored before `P` (painting `Q` last keeps it);
//! when `P` was stored first, `P` must lie strictly behind `Q`. A triangle touching another's
//! plane (an edge on it) counts as crossing it on the side the rule gives the touching
//! points, so such pairs are split too. Exact ties are those of the exact planes through the
//! stored corners: coplanar surfaces whose projected depth is the same plane (a face seen
//! head-on, two triangles sharing their corners' depths). Where two planes differ by less
//! than one depth unit at a sample, the z-buffer's rounded depths may tie where the exact
//! ones do not. A cut sorts `P`'s samples as the z-buffer does, by rounded depths (half up,
//! as the z-buffer stores them) and on equal ones by the tie rule: a sample goes with the
//! piece behind `Q`'s plane exactly where the z-buffer would keep `Q` over `P`, so pieces
//! follow the rounded ties too (two triangles of one polygon whose fan folds over itself, a
//! few pixels along their shared edge, are the common case). A pair ordered whole by test 3
//! or 4 is ordered by its exact planes: there the painter paints the exactly nearer one (at
//! 32-bit depth, within `2^-32` of the depth range).
//!
//! When every test fails, `Q` is moved before `P` and marked; a marked `Q` failing again is a
//! cycle (or interpenetration), and test 6 **splits** `P` by `Q`'s plane into the piece behind
//! it and the piece in front. When neither crosses the other's plane (each is cut by it
//! already), the cycle runs through other moved entries: one of them is split by the plane of
//! another that it crosses, preferably one it may not precede, else any (a **third plane**:
//! the pieces then lie on one side of it each). A group of pieces none of which crosses the
//! plane of another has an order (each plane leaves the others on one side: ordering by one
//! plane, then within each side, is the binary partition by the triangles' own planes), and
//! tests 3 and 4 see that order through the third planes too: `A` cut behind a plane that
//! `B` lies wholly in front of may be painted before `B`, and so may `A` wholly behind a plane
//! that `B` was cut in front of. Splitting goes on while the split budget and the store allow
//! (each named in its error when it runs out); a group that no split and no test can order
//! is refused as [`VisibilityError::PainterCycle`] (none is left in the tests' random scenes:
//! soups of large triangles, interpenetrating cubes from any view). A piece keeps `P`'s
//! corners (so its pixels get `P`'s exact depth and level) and its cuts, a chain through the
//! store (its last cut and the piece it was cut from, whose cuts it inherits), so a piece may
//! be cut as often as the store holds pieces and the split budget allows; drawn row by row,
//! each row restricted to the columns whose samples lie on its side of the cut planes, so the
//! pieces of `P` write exactly `P`'s pixels. The tests judge a piece by its own
//! polygon: tests 1–4 by its **outline** (`outline.rs`: the triangle clipped by its cuts moved
//! a depth unit outward, a superset of the piece with exact integer vertices, clipped by its
//! latest three cuts, so what
//! holds for the outline holds for the piece, and an empty outline is a piece with no sample),
//! by its cuts (a piece behind `Q`'s plane passes test 3 against `Q`; a plane that cut both,
//! one behind and one in front, separates them, and so does a third plane that cut one when
//! the other's outline lies on the other side; their rounded depths may tie on that plane, so
//! the outline must then lie a whole depth unit off it unless the tie rule already gives the
//! pair this order), and test 5 by its base triangle. With [`SplitPolicy::Never`] a cycle draws
//! `P` in the tests' order instead: the painter without test 6, whose wrong pixels
//! `tests/visibility.rs` counts.
//!
//! Refused in words (an error, never a picture): a store too small for the front triangles
//! and pieces ([`VisibilityError::TriangleStoreFull`], naming its capacity), a split budget too
//! small ([`VisibilityError::SplitBudgetExhausted`], naming it: the frame's
//! [`MethodCounts::painter_splits`](super::MethodCounts) is what it needs), a group of
//! pieces the tests still cannot order ([`VisibilityError::PainterCycle`]), a core-lit Phong object
//! (its corners carry normals, not levels: [`RenderError::PhongUnsupported`]; draw it with the
//! z-buffer or back faces alone), and a split of a fast Gouraud triangle
//! ([`VisibilityError::FastGouraudInParts`]: a piece is drawn row by row from its own first column,
//! where the 16.16 luminance steps start differently from the whole span's; whole fast Gouraud
//! triangles are drawn as the z-buffer draws them).
//!
//! Numeric contract: corners within `±(2^28 − 1)` sub-pixel units, depths `u32`. A plane's
//! normal `(n_x, n_y, n_d)` has `|n_x|, |n_y| < 2^62` (products of a `< 2^29` and a `< 2^32`
//! difference, two of them) and `n_d` = twice the screen area, `|n_d| < 2^59`: `i64`. A point's
//! side of a plane is `n·(p − p0) < 2^62·2^29·2 + 2^59·2^32 < 2^93`: `i128`. A sample's side of
//! a cut plane is exact in `i128` too (`sample_side`). Memory: a stored triangle (52 bytes)
//! and a `u32` of order per front triangle and per piece (two pieces per split), and a plane
//! normal (24 bytes) per front triangle, computed once after the store is filled (the tests
//! read it instead of recomputing the plane per pair). A piece's cuts cost nothing more: each
//! piece holds its last one.

use core::cmp::Reverse;

use super::backface::without_depth;
use super::outline::Outline;
pub use super::plane::Normal;
use super::plane::{Plane, Store};
use super::store::{collect, cuts, sort_order, StoredTriangle, CUT_FRONT};
use super::VisibilityError;
use crate::output::{Framebuffer, NoDepth};
use crate::raster::triangle::{RasterTarget, ShadeMode};
use crate::raster::Window;
use crate::render::{check_transparency, Draws};
use crate::render::{PreparedVertex, RenderError, RenderStats, SceneRenderer, StatsSink};
use crate::scene::Scene;

/// The order entry's mark: the triangle was moved before another once (Newell's loop).
const MOVED: u32 = 1 << 31;

/// What the painter does when Newell's tests 1–5 cannot order a cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SplitPolicy {
    /// Test 6: split, at most this many times per frame (then
    /// [`VisibilityError::SplitBudgetExhausted`]).
    Budget(usize),
    /// No test 6: the blocked triangle is drawn in the sorted order (wrong where a cycle or
    /// interpenetration overlaps; for measuring what test 6 buys).
    Never,
}

/// Caller memory of [`render_painter`].
#[derive(Debug)]
pub struct PainterMemory<'a, const S: u32 = 4> {
    /// The front triangles, then the pieces the splits make.
    pub triangles: &'a mut [StoredTriangle<S>],
    /// The drawing order, one entry per stored triangle (as long as `triangles`).
    pub order: &'a mut [u32],
    /// Each front triangle's plane normal, computed once (24 bytes per front triangle; the
    /// pieces share their triangle's).
    pub normals: &'a mut [Normal],
}

/// Clears `frame`, stores the front triangles of every object of the renderer's scene, orders
/// them by Newell's tests (module doc) and paints them back to front with no depth buffer: the
/// 32-bit z-buffer's picture, ties included, where exact depths tie or differ by a unit or more.
///
/// Errors (module doc): [`VisibilityError::TriangleStoreFull`] (front triangles and pieces beyond
/// `memory`), [`VisibilityError::SplitBudgetExhausted`], [`VisibilityError::PainterCycle`],
/// [`RenderError::PhongUnsupported`] (a core-lit Phong object: draw it with the z-buffer),
/// [`VisibilityError::FastGouraudInParts`] (a fast Gouraud triangle that would be split), and the
/// renderer's own.
pub fn render_painter<T: StatsSink, const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    frame: &mut Framebuffer<'_>,
    scratch: &mut [PreparedVertex<S>],
    memory: PainterMemory<'_, S>,
    policy: SplitPolicy,
    stats: &mut T,
) -> Result<(), VisibilityError> {
    let scene = renderer.scene();
    renderer.renderer().check_frame(frame)?;
    check_transparency(renderer.scene(), "the painter", Draws::ScreenDoor)?;
    let counts = stats.counts();
    let PainterMemory {
        triangles,
        order,
        normals,
    } = memory;
    let capacity = triangles.len().min(order.len());
    let triangles = &mut triangles[..capacity];
    let order = &mut order[..capacity];
    let n = collect(renderer, scratch, triangles, counts)?;
    let full = VisibilityError::TriangleStoreFull {
        capacity: normals.len(),
    };
    let normals = normals.get_mut(..n).ok_or(full)?;
    for (normal, t) in normals.iter_mut().zip(triangles.iter()) {
        *normal = Plane::of(t).normal();
    }
    let normals = &*normals;
    frame.clear(scene.background);
    sort_order(&mut order[..n], |i| Reverse(triangles[i].depth_range().1));
    without_depth(frame, |frame, depth| {
        let mut target = RasterTarget::with_count(frame, depth, T::Count::default());
        let window = target.buffers();
        let mut painter = Painter::new(scene, window, triangles, normals, order, n);
        while let Some(t) = painter.next(policy)? {
            let all = (&*painter.triangles, normals);
            draw_piece(scene, &painter.triangles[t], all, &mut target, counts)?;
        }
        let m = &mut counts.method;
        m.painter_tests = painter.tests;
        m.painter_ambiguities = painter.ambiguities;
        m.painter_splits = painter.splits as u32;
        m.pieces = (painter.stored - n) as u32;
        Ok(())
    })
}

/// Newell's ordering loop over the stored triangles.
struct Painter<'m, const S: u32> {
    /// The scene (its objects' shading: a fast Gouraud triangle is not split).
    scene: &'m Scene<'m>,
    /// The frame's pixels: pairs that share no sample in it may be painted in either order.
    window: Window,
    triangles: &'m mut [StoredTriangle<S>],
    /// The front triangles' plane normals (by base index).
    normals: &'m [Normal],
    /// `order[..count]`: the triangles not painted yet; `order[..moved]` were moved to the
    /// front (Newell's marks), `order[moved..count]` are sorted by farthest depth, descending.
    order: &'m mut [u32],
    moved: usize,
    count: usize,
    /// Triangles and pieces in `triangles`.
    stored: usize,
    splits: usize,
    /// Entries moved to the front since the last paint or split.
    moves: usize,
    /// Pair tests decided by test 1–5, and pairs none decided (`MethodCounts`).
    tests: [u32; 5],
    ambiguities: u32,
}

impl<'m, const S: u32> Painter<'m, S> {
    /// The loop over `n` stored triangles, `order[..n]` sorted by farthest depth, descending,
    /// nothing painted, moved or split yet.
    fn new(
        scene: &'m Scene<'m>,
        window: Window,
        triangles: &'m mut [StoredTriangle<S>],
        normals: &'m [Normal],
        order: &'m mut [u32],
        n: usize,
    ) -> Self {
        Painter {
            scene,
            window,
            triangles,
            normals,
            order,
            count: n,
            stored: n,
            splits: 0,
            moves: 0,
            moved: 0,
            tests: [0; 5],
            ambiguities: 0,
        }
    }
}

impl<const S: u32> Painter<'_, S> {
    /// The next triangle to paint (its index in the store), or `None` when all are.
    ///
    /// Invariant: `order[moved..count]` stays sorted by farthest depth, descending (moving an
    /// entry to the front grows the moved part, pieces are inserted at their place), so the
    /// scan for triangles whose depth range overlaps the first one's stops at the first sorted
    /// entry that does not.
    fn next(&mut self, policy: SplitPolicy) -> Result<Option<usize>, VisibilityError> {
        loop {
            if self.count == 0 {
                return Ok(None);
            }
            let p = (self.order[0] & !MOVED) as usize;
            let Some(k) = self.blocker(p) else {
                self.paint_first();
                return Ok(Some(p));
            };
            self.ambiguities += 1;
            let q = (self.order[k] & !MOVED) as usize;
            // Q first, marked: when it was not moved yet, or when the tests show that Q may
            // be painted before P (a cut piece meets the triangle that cut it), as long as
            // moves since the last paint stay below the entries left (beyond, the marked
            // entries go round a cycle of the tests).
            let reorder =
                self.order[k] & MOVED == 0 || (self.moves < self.count && self.may_precede(q, p));
            if reorder {
                self.order[..=k].rotate_right(1);
                self.order[0] |= MOVED;
                if k >= self.moved {
                    self.moved += 1;
                }
                self.moves += 1;
                continue;
            }
            match policy {
                SplitPolicy::Never => {
                    self.paint_first();
                    return Ok(Some(p));
                }
                SplitPolicy::Budget(budget) => {
                    // Split the one that crosses the other's plane (P first, as Newell);
                    // when neither does, one lies wholly in front of the other's plane and
                    // only the marks stood in the way: Q goes first.
                    let all = (&*self.triangles, self.normals);
                    let cut = if straddles(all, p, q) {
                        Some((0, q))
                    } else if straddles(all, q, p) {
                        Some((k, p))
                    } else {
                        // P and Q are cut by each other's planes already: a cycle through
                        // other moved entries. Split one of them by the plane of another
                        // that it may not precede and crosses.
                        self.split_in_cycle(k)
                    };
                    match cut {
                        Some((at, by)) => {
                            if self.splits >= budget {
                                return Err(VisibilityError::SplitBudgetExhausted { budget });
                            }
                            self.splits += 1;
                            self.moves = 0;
                            self.split(at, by)?;
                        }
                        None if self.moves <= 2 * self.count => {
                            self.order[..=k].rotate_right(1);
                            if k >= self.moved {
                                self.moved += 1;
                            }
                            self.moves += 1;
                        }
                        None => return Err(VisibilityError::PainterCycle),
                    }
                }
            }
        }
    }

    /// The first entry after the first whose triangle `p` may not be painted before, if any:
    /// every moved entry, then the sorted ones while their farthest depth is beyond `p`'s
    /// nearest (test 1 holds for the rest).
    fn blocker(&mut self, p: usize) -> Option<usize> {
        let (p_near, _) = self.triangles[p].depth_range();
        for k in 1..self.moved {
            if !self.may_precede(p, (self.order[k] & !MOVED) as usize) {
                return Some(k);
            }
        }
        for k in self.moved.max(1)..self.count {
            let q = (self.order[k] & !MOVED) as usize;
            // Test 1 for the rest (at an equal depth the tie rule decides: `deciding_test`).
            if self.triangles[q].depth_range().1 < p_near {
                self.tests[0] += 1;
                return None;
            }
            if !self.may_precede(p, q) {
                return Some(k);
            }
        }
        None
    }

    /// Whether painting `a` before `b` is right wherever they overlap (tests 1–5), counted.
    fn may_precede(&mut self, a: usize, b: usize) -> bool {
        match deciding_test((self.triangles, self.normals), self.window, a, b) {
            Some(test) => {
                self.tests[test] += 1;
                true
            }
            None => false,
        }
    }

    /// A split that may break a cycle among the moved entries `order[..=last]` (and
    /// `order[..moved]`): `(at, by)` for the first entry `order[at]` that may not precede
    /// another, `by`, whose plane it crosses.
    fn split_in_cycle(&self, last: usize) -> Option<(usize, usize)> {
        let all = (&*self.triangles, self.normals);
        let group = self.moved.max(last + 1).min(self.count);
        let entry = |i: usize| (self.order[i] & !MOVED) as usize;
        let find = |blocked: bool| {
            (0..group).find_map(|i| {
                let x = entry(i);
                (0..group)
                    .map(entry)
                    .find(|&y| {
                        y != x
                            && straddles(all, x, y)
                            && (!blocked || deciding_test(all, self.window, x, y).is_none())
                    })
                    .map(|y| (i, y))
            })
        };
        find(true).or_else(|| find(false))
    }

    /// Removes the first entry (painted).
    fn paint_first(&mut self) {
        self.order.copy_within(1..self.count, 0);
        self.count -= 1;
        self.moved = self.moved.saturating_sub(1);
        self.moves = 0;
    }

    /// Test 6: replaces the entry `order[at]` by its piece behind `q`'s plane and inserts its
    /// piece in front at its place in the sorted part of the order.
    fn split(&mut self, at: usize, q: usize) -> Result<(), VisibilityError> {
        let capacity = self.triangles.len();
        if self.stored + 2 > capacity || self.count + 1 > self.order.len() {
            return Err(VisibilityError::TriangleStoreFull { capacity });
        }
        let p = (self.order[at] & !MOVED) as usize;
        let plane = self.triangles[q].base;
        let whole = self.triangles[p];
        let object = whole.object as usize;
        let fast = self.scene.objects.get(object).map(|o| o.shade);
        if fast == Some(ShadeMode::GouraudFast) {
            return Err(VisibilityError::FastGouraudInParts { object });
        }
        let (mut behind, mut front) = (whole, whole);
        behind.cut = plane;
        front.cut = plane | CUT_FRONT;
        behind.parent = p as u32;
        front.parent = p as u32;
        let (b, f) = (self.stored, self.stored + 1);
        self.triangles[b] = behind;
        self.triangles[f] = front;
        self.stored += 2;
        self.order[at] = b as u32 | (self.order[at] & MOVED);
        // The front piece at its place among the rest (farthest depth descending).
        let key = whole.depth_range().1;
        let from = self.moved.max(1);
        let rest = &self.order[from..self.count];
        let at = from
            + rest
                .partition_point(|&e| self.triangles[(e & !MOVED) as usize].depth_range().1 >= key);
        self.order.copy_within(at..self.count, at + 1);
        self.order[at] = f as u32;
        self.count += 1;
        Ok(())
    }
}

/// Which of tests 1–5 (module doc) shows that painting `a` before `b` is right wherever they
/// overlap (0 for test 1), if one does. Whole triangles are judged by their corners, pieces by
/// their outlines (`outline.rs`).
///
/// The tie rule: where `a` and `b` are at exactly the same depth the z-buffer keeps the one
/// it drew first, the earlier stored base triangle. When that is `b`, painting `b` last keeps
/// it, so "behind or at the same depth" suffices; when it is `a`, `a` must lie strictly
/// behind `b` wherever they overlap (`margin` 1 below: a strict inequality of integers).
fn deciding_test<const S: u32>(
    all: Store<'_, S>,
    window: Window,
    a: usize,
    b: usize,
) -> Option<usize> {
    let t = all.0;
    let (ta, tb) = (&t[a], &t[b]);
    if ta.is_piece() || tb.is_piece() {
        return deciding_test_pieces(all, window, ta, tb);
    }
    let margin = tie_margin(ta, tb);
    let (a_near, _) = ta.depth_range();
    let (_, b_far) = tb.depth_range();
    // 1. Depth ranges.
    if a_near as i64 >= b_far as i64 + margin as i64 {
        return Some(0);
    }
    // 2. Screen boxes, x then y.
    let (ax, ay) = boxes(ta);
    let (bx, by) = boxes(tb);
    if ax.1 < bx.0 || bx.1 < ax.0 || ay.1 < by.0 || by.1 < ay.0 {
        return Some(1);
    }
    // 3. A behind B's plane.
    let b_plane = Plane::stored(all, tb.base);
    if (0..3).all(|k| b_plane.behind(ta, k) >= margin) {
        return Some(2);
    }
    // 4. B in front of A's plane.
    let a_plane = Plane::stored(all, ta.base);
    if (0..3).all(|k| a_plane.behind(tb, k) <= -margin) {
        return Some(3);
    }
    // 5. Projections disjoint, or sharing no sample of the frame.
    (separated(ta, tb) || separated(tb, ta) || !share_a_sample(ta, tb, window)).then_some(4)
}

/// 1 when `a` was stored (so drawn by the z-buffer) before `b`, which then keeps `a` where
/// both are at one depth: painting `a` before `b` needs `a` strictly behind. 0 otherwise.
fn tie_margin<const S: u32>(a: &StoredTriangle<S>, b: &StoredTriangle<S>) -> i128 {
    (a.base < b.base) as i128
}

/// [`deciding_test`] when `ta` or `tb` is a piece: tests 1–4 on the outlines (supersets of
/// the pieces, `outline.rs`) and on the cuts (a piece cut by the other's plane lies on its
/// side, samples at an equal rounded depth on the side the tie rule gives them: `draw_piece`),
/// test 5
/// on the base triangles. An empty piece (no sample) may go anywhere: counted as test 2.
fn deciding_test_pieces<const S: u32>(
    all: Store<'_, S>,
    window: Window,
    ta: &StoredTriangle<S>,
    tb: &StoredTriangle<S>,
) -> Option<usize> {
    let (oa, ob) = (Outline::of(all, ta), Outline::of(all, tb));
    if oa.is_empty() || ob.is_empty() {
        return Some(1);
    }
    let margin = tie_margin(ta, tb);
    let depths = |t: &StoredTriangle<S>| t.depth.map(|d| d as i64);
    let (a_near, _) = oa.range(depths(ta));
    let (_, b_far) = ob.range(depths(tb));
    // 1. Depth ranges.
    if a_near >= b_far + margin as i64 {
        return Some(0);
    }
    // 2. Screen boxes, x then y.
    let xs = |t: &StoredTriangle<S>| t.v.map(|p| p.x as i64);
    let ys = |t: &StoredTriangle<S>| t.v.map(|p| p.y as i64);
    let (ax, ay) = (oa.range(xs(ta)), oa.range(ys(ta)));
    let (bx, by) = (ob.range(xs(tb)), ob.range(ys(tb)));
    if ax.1 < bx.0 || bx.1 < ax.0 || ay.1 < by.0 || by.1 < ay.0 {
        return Some(1);
    }
    // 3. A behind B's plane (its outline, or a cut that says so), or behind a plane that B
    // is in front of (both cut by it: the plane separates them). A cut keeps the samples at
    // the plane's rounded depth on the side the tie rule gives them, so a piece behind B's plane
    // shows behind B at every sample, ties included, and so does a separated pair.
    let (cuts_a, cuts_b) = (cuts(all.0, ta), cuts(all.0, tb));
    let b_plane = Plane::stored(all, tb.base);
    let separating = cuts_a
        .clone()
        .any(|c| c & CUT_FRONT == 0 && cuts_b.clone().any(|d| d == c | CUT_FRONT));
    if cuts_a.clone().any(|c| c == tb.base)
        || separating
        || oa.side_bounds(b_plane.oriented(ta)).0 >= margin
    {
        return Some(2);
    }
    // 4. B in front of A's plane.
    let a_plane = Plane::stored(all, ta.base);
    if cuts_b.clone().any(|c| c == ta.base | CUT_FRONT)
        || ob.side_bounds(a_plane.oriented(tb)).1 <= -margin
    {
        return Some(3);
    }
    // 3 and 4 by a third plane: A cut behind a plane that B lies wholly in front of, or B
    // cut in front of a plane that A lies wholly behind. The cut piece's samples are at a
    // rounded depth behind (in front of) the plane's or at the same one, and the other's at
    // the same rounded depth as the plane's or beyond: where all three tie, painting B last
    // is right only when B was stored first (the cut then says which of the piece and the
    // plane was stored first). Otherwise the other must lie a whole depth unit off the
    // plane (`Plane::unit`), so that its rounded depths differ from the plane's.
    let tie_on = |cut: u32, piece: &StoredTriangle<S>, behind: bool| {
        margin == 1 && ((cut < piece.base) == behind)
    };
    if cuts_a.clone().any(|c| {
        c & CUT_FRONT == 0 && c != tb.base && {
            let plane = Plane::stored(all, c);
            let m = tie_on(c, ta, true) as i128 * plane.unit();
            ob.side_bounds(plane.oriented(tb)).1 <= -m
        }
    }) {
        return Some(2);
    }
    if cuts_b.clone().any(|c| {
        let by = c & !CUT_FRONT;
        c & CUT_FRONT != 0 && by != ta.base && {
            let plane = Plane::stored(all, by);
            let m = tie_on(by, tb, false) as i128 * plane.unit();
            oa.side_bounds(plane.oriented(ta)).0 >= m
        }
    }) {
        return Some(3);
    }
    // 5. Projections disjoint, or sharing no sample of the frame (the base triangles'; a
    // piece lies within its base).
    (separated(ta, tb) || separated(tb, ta) || !share_a_sample(ta, tb, window)).then_some(4)
}

/// Whether `a` (its outline, for a piece) has points on both sides of `b`'s plane, and `a`
/// is not cut by it already. A point on the plane counts on the side the tie rule gives it:
/// in front when `a` was stored first (the z-buffer keeps `a` there), else behind; so a
/// triangle that touches the other's plane along an edge, where both may draw a sample at
/// one depth, is split there too. The outline's bounds may say so of a piece wholly on one
/// side: a split then makes an empty piece, which draws nothing.
fn straddles<const S: u32>(all: Store<'_, S>, a: usize, b: usize) -> bool {
    let (ta, tb) = (&all.0[a], &all.0[b]);
    if cuts(all.0, ta).any(|c| c & !CUT_FRONT == tb.base) {
        return false;
    }
    let plane = Plane::stored(all, tb.base);
    let first = tie_margin(ta, tb);
    if ta.is_piece() {
        let (lo, hi) = Outline::of(all, ta).side_bounds(plane.oriented(ta));
        return lo < first && hi >= first;
    }
    let sides = [0, 1, 2].map(|k| plane.behind(ta, k));
    let tied = if first == 1 { -1 } else { 1 };
    let sides = sides.map(|s| if s == 0 { tied } else { s });
    sides.contains(&1) && sides.contains(&-1)
}

/// The sub-pixel bounding box: `((x_lo, x_hi), (y_lo, y_hi))`.
fn boxes<const S: u32>(t: &StoredTriangle<S>) -> ((i32, i32), (i32, i32)) {
    let xs = t.v.map(|p| p.x);
    let ys = t.v.map(|p| p.y);
    (
        (
            xs.into_iter().min().unwrap_or(0),
            xs.into_iter().max().unwrap_or(0),
        ),
        (
            ys.into_iter().min().unwrap_or(0),
            ys.into_iter().max().unwrap_or(0),
        ),
    )
}

/// True when the line through an edge of `a` has every corner of `b` on it or outside `a`
/// (`i64`: edge functions of `< 2^29` differences, `< 2^59`). Their interiors are then
/// disjoint, and no sample is drawn by both: the fill rule covers a lattice point on an
/// edge exactly when the point moved by `(ε, ε²)` lies inside (closed for a left or a
/// horizontal top edge, open for the others, `raster::polygon`), and that moved point cannot
/// lie inside both. So triangles of a mesh that share an edge or a corner are separated
/// when they do not overlap.
fn separated<const S: u32>(a: &StoredTriangle<S>, b: &StoredTriangle<S>) -> bool {
    let orient = a.twice_area().signum();
    (0..3).any(|k| {
        let (p, q) = (a.v[k], a.v[(k + 1) % 3]);
        let (ex, ey) = (q.x as i64 - p.x as i64, q.y as i64 - p.y as i64);
        b.v.iter().all(|r| {
            let e = ex * (r.y as i64 - p.y as i64) - ey * (r.x as i64 - p.x as i64);
            e * orient <= 0
        })
    })
}

/// Whether some pixel sample of `window` lies inside or on the edges of both `a` and `b`
/// (their closed triangles, a superset of what the fill rule draws of each): when none does,
/// no pixel is drawn by both, and either may be painted first. Row by row over the rows both
/// may cover, each row's columns of each triangle exactly (`closed_columns`), stopping at the
/// first row where they meet.
fn share_a_sample<const S: u32>(
    a: &StoredTriangle<S>,
    b: &StoredTriangle<S>,
    window: Window,
) -> bool {
    let ((ra_lo, ra_hi), (rb_lo, rb_hi)) = (a.rows(), b.rows());
    let rows = ra_lo.max(rb_lo).max(window.y0)..=ra_hi.min(rb_hi).min(window.y1 - 1);
    rows.into_iter().any(|y| {
        let (a_lo, a_hi) = closed_columns(a, y);
        let (b_lo, b_hi) = closed_columns(b, y);
        let lo = a_lo.max(b_lo).max(window.x0 as i64);
        let hi = a_hi.min(b_hi).min(window.x1 as i64 - 1);
        lo <= hi
    })
}

/// The columns `lo..=hi` (empty when `lo > hi`) of row `y` whose samples `(x·2^S, y·2^S)`
/// lie inside or on the edges of `t`. Each edge's function is affine along the row,
/// `c·X + d ≥ 0` inside, with `|c| < 2^29` and `|d| < 2^60` (`i128`); its bound on `X` is
/// divided by `2^S` with the floor or ceiling, exactly.
fn closed_columns<const S: u32>(t: &StoredTriangle<S>, y: i32) -> (i64, i64) {
    let orient = t.twice_area().signum() as i128;
    let sample_y = (y as i128) << S;
    let (mut lo, mut hi) = (i64::MIN, i64::MAX);
    for k in 0..3 {
        let (p, q) = (t.v[k], t.v[(k + 1) % 3]);
        let (ex, ey) = ((q.x - p.x) as i128, (q.y - p.y) as i128);
        // e(X) = ex·(Y − p_y) − ey·(X − p_x), inside where orient·e ≥ 0.
        let c = -ey * orient;
        let d = (ex * (sample_y - p.y as i128) + ey * p.x as i128) * orient;
        let unit = c << S;
        if c > 0 {
            // x ≥ −d / (c·2^S).
            lo = lo.max(-d.div_euclid(unit) as i64);
        } else if c < 0 {
            // x ≤ d / (−c·2^S).
            hi = hi.min(d.div_euclid(-unit) as i64);
        } else if d < 0 {
            return (1, 0);
        }
    }
    (lo, hi)
}

/// Paints `t` (a whole triangle at once; a piece row by row, each row's columns restricted to
/// the samples on its side of every cut).
///
/// A sample of a piece of `P` cut by `X`'s plane lies behind it when the z-buffer would keep
/// `X` there: `X`'s depth rounded as the z-buffer rounds it is below `P`'s, or equal with `X`
/// stored first. The exact depths then differ by less than a unit wherever the rounded and
/// exact sides disagree, so along a row each cut keeps a run of columns where `P` lies a unit
/// or more on its side of the plane, within the run where it lies less than a unit on the
/// other (both found by bisection: the exact side is affine along a row), and the columns
/// between are decided one by one.
fn draw_piece<const S: u32, C: crate::raster::triangle::WrittenCount>(
    scene: &Scene<'_>,
    t: &StoredTriangle<S>,
    all: Store<'_, S>,
    target: &mut RasterTarget<'_, NoDepth, C>,
    stats: &mut RenderStats,
) -> Result<(), RenderError> {
    if !t.is_piece() {
        stats.add_triangle(t.draw(scene, target)?);
        return Ok(());
    }
    let full = target.buffers();
    let own = Plane::stored(all, t.base);
    let ((x_lo, x_hi), _) = boxes(t);
    let (row_lo, row_hi) = t.rows();
    let cols = ((-((-x_lo) >> S)).max(full.x0), (x_hi >> S).min(full.x1 - 1));
    // Each cut: its plane, whether the piece keeps the samples behind it, and whether the
    // cutting triangle was stored first (it hides `P`'s samples at its rounded depth).
    let cut_of = |cut: u32| {
        let by = cut & !CUT_FRONT;
        (Plane::stored(all, by), cut & CUT_FRONT == 0, by < t.base)
    };
    let kept = |x: i32, y: i32| {
        let (sx, sy) = ((x as i64) << S, (y as i64) << S);
        let depth = own.rounded_depth(sx, sy);
        cuts(all.0, t).all(|cut| {
            let (plane, keep_behind, first) = cut_of(cut);
            let other = plane.rounded_depth(sx, sy);
            (depth > other || (depth == other && first)) == keep_behind
        })
    };
    let mut sum = (0, 0);
    for y in row_lo.max(full.y0)..=row_hi.min(full.y1 - 1) {
        // `a..b`: the columns each cut may keep; `c..d` within: those each cut keeps.
        let (mut a, mut b) = (cols.0, cols.1 + 1);
        for cut in cuts(all.0, t) {
            let (plane, keep_behind, _) = cut_of(cut);
            let side = |x: i32, shift: i64| {
                plane.sample_side_moved(&own, (x as i64) << S, (y as i64) << S, shift)
            };
            (a, b) = if keep_behind {
                kept_columns(a, b, |x| side(x, -1) > 0)
            } else {
                kept_columns(a, b, |x| side(x, 1) < 0)
            };
        }
        let (mut c, mut d) = (a, b);
        for cut in cuts(all.0, t) {
            let (plane, keep_behind, _) = cut_of(cut);
            let side = |x: i32, shift: i64| {
                plane.sample_side_moved(&own, (x as i64) << S, (y as i64) << S, shift)
            };
            (c, d) = if keep_behind {
                kept_columns(c, d, |x| side(x, 1) >= 0)
            } else {
                kept_columns(c, d, |x| side(x, -1) <= 0)
            };
        }
        if c >= d {
            (c, d) = (b, b);
        }
        // Runs of kept columns: those of `a..c` and `d..b` one by one, `c..d` at once.
        let mut x = a;
        while x < b {
            let start = x;
            while x < b && (c <= x && x < d || kept(x, y)) {
                x = if x == c { d } else { x + 1 };
            }
            if start < x {
                target.restrict(Window::new(start, y, x, y + 1));
                let (n, w) = t.draw(scene, target)?;
                sum = (sum.0 + n, sum.1 + w);
            } else {
                x += 1;
            }
        }
    }
    target.restrict(full);
    stats.add_triangle(sum);
    Ok(())
}

/// The columns of `a..b` where `keep` holds, given that `keep` changes at most once along
/// the row: `a..b` itself, a prefix or suffix of it, or nothing.
fn kept_columns(a: i32, b: i32, keep: impl Fn(i32) -> bool) -> (i32, i32) {
    if a >= b {
        return (a, a);
    }
    let (first, last) = (keep(a), keep(b - 1));
    match (first, last) {
        (true, true) => (a, b),
        (false, false) => (a, a),
        // The first column where the answer flips, by bisection: keep(lo) == first.
        _ => {
            let (mut lo, mut hi) = (a, b - 1);
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if keep(mid) == first {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            if first {
                (a, hi)
            } else {
                (hi, b)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::camera::{Camera, Lens, Viewport};
    use crate::geometry::fixed::Coord;
    use crate::geometry::generators::unit_cube;
    use crate::geometry::trig::BinaryAngle;
    use crate::geometry::vector::Vec3;
    use crate::output::DepthBuffer;
    use crate::raster::SubpixelPoint;
    use crate::scene::Object;
    use crate::test_rng::XorShift;

    const W: u16 = 56;
    const H: u16 = 56;
    const N: usize = W as usize * H as usize;

    /// A stored whole triangle of object 0: sub-pixel corners, depths and levels.
    fn stored(v: [(i32, i32); 3], depth: [u32; 3], level: [u8; 3], at: u32) -> StoredTriangle {
        StoredTriangle {
            v: v.map(|(x, y)| SubpixelPoint::new(x, y)),
            depth,
            level,
            base: at,
            ..StoredTriangle::DEFAULT
        }
    }

    /// The pictures of `store` (whole triangles of object 0 of `scene`) by the painter's loop
    /// (Newell's tests and splits, `draw_piece`) and by the 32-bit z-buffer drawing them in
    /// store order; and the painter's split count.
    fn painter_and_zbuffer(
        scene: &Scene<'_>,
        store: &[StoredTriangle],
    ) -> ([u8; N], [u8; N], usize) {
        let n = store.len();
        let mut triangles = [StoredTriangle::DEFAULT; 16];
        triangles[..n].copy_from_slice(store);
        let mut normals = [Normal::DEFAULT; 16];
        for (normal, t) in normals.iter_mut().zip(store) {
            *normal = Plane::of(t).normal();
        }
        let mut order = [0u32; 16];
        sort_order(&mut order[..n], |i| Reverse(triangles[i].depth_range().1));
        let (mut painted, mut zbuffered) = ([0u8; N], [0u8; N]);
        let mut splits = 0;
        let mut frame = Framebuffer::new(&mut painted, W, H).unwrap();
        frame.clear(0);
        let mut stats = RenderStats::default();
        without_depth(&mut frame, |frame, depth| {
            let mut target = RasterTarget::new(frame, depth);
            let window = target.buffers();
            let mut painter = Painter::new(scene, window, &mut triangles, &normals, &mut order, n);
            while let Some(t) = painter.next(SplitPolicy::Budget(64))? {
                let all = (&*painter.triangles, &normals[..]);
                draw_piece(scene, &painter.triangles[t], all, &mut target, &mut stats)?;
            }
            splits = painter.splits;
            Ok::<(), VisibilityError>(())
        })
        .unwrap();
        let mut frame = Framebuffer::new(&mut zbuffered, W, H).unwrap();
        frame.clear(0);
        let mut depths = [0u32; N];
        let mut depth = DepthBuffer::new(&mut depths, W, H).unwrap();
        depth.clear();
        let mut target = RasterTarget::new(&mut frame, &mut depth);
        for t in store {
            t.draw(scene, &mut target).unwrap();
        }
        (painted, zbuffered, splits)
    }

    /// Two triangles of one polygon's fan that folds over itself (they share corner 0 and
    /// overlap): at pixel (22, 15) the second is exactly nearer, by less than a depth unit, and
    /// both round to the same 32-bit depth, where the z-buffer keeps the first drawn. The
    /// painter splits the second by the first's plane and must sort that sample as the
    /// z-buffer does: its picture equals the z-buffer's at every pixel.
    #[test]
    fn pieces_follow_the_z_buffers_rounded_ties() {
        let lens = Lens::new(
            BinaryAngle::from_degrees(50),
            Coord::lit("0.5"),
            Coord::lit("20"),
        );
        let (eye, up) = (Vec3::from_int(0, 0, 4), Vec3::from_int(0, 1, 0));
        let camera = Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(W, H)).unwrap();
        let mut object = Object::new(unit_cube());
        object.shade = ShadeMode::GouraudExact;
        let objects = [object];
        let scene = Scene {
            camera,
            objects: &objects,
            background: 0,
            ambient: 255,
            lights: &[],
        };
        let first = stored(
            [(799, -6), (-449, 447), (827, 815)],
            [228_737_183, 226_690_414, 228_752_700],
            [165, 108, 114],
            0,
        );
        let second = stored(
            [(799, -6), (11, -234), (55, 1095)],
            [228_737_183, 227_462_940, 227_487_324],
            [165, 150, 249],
            1,
        );
        // The premise at the sample (22, 15): exact depths differ, rounded ones tie.
        let (a, b) = (Plane::of(&first), Plane::of(&second));
        let (x, y) = (22 << 4, 15 << 4);
        assert_eq!(a.sample_side(&b, x, y), -1, "the second exactly nearer");
        assert_eq!(a.rounded_depth(x, y), b.rounded_depth(x, y));
        let (painted, zbuffered, splits) = painter_and_zbuffer(&scene, &[first, second]);
        assert!(splits > 0, "the pair is split");
        let at = 15 * W as usize + 22;
        let alone = painter_and_zbuffer(&scene, &[second]).1;
        assert_ne!(zbuffered[at], alone[at], "the first one shows at (22, 15)");
        let differing = (0..N).filter(|&i| painted[i] != zbuffered[i]).count();
        assert_eq!(differing, 0, "pixels differing from the z-buffer");
    }

    /// `closed_columns` against the definition: every sample of a row tested on the three
    /// edge functions (inside or on each, for either orientation).
    #[test]
    fn closed_columns_are_the_samples_on_or_inside() {
        let mut rng = XorShift::new(0x0c01_0030);
        let mut seen = 0;
        for _ in 0..2000 {
            let mut t = StoredTriangle::<4>::DEFAULT;
            // Small triangles (corners within 24 × 24 pixels), some with lattice corners.
            t.v = [0; 3].map(|_| {
                let (x, y) = (rng.range(-64, 384) as i32, rng.range(-64, 384) as i32);
                if rng.chance(20) {
                    SubpixelPoint::new(x & !15, y & !15)
                } else {
                    SubpixelPoint::new(x, y)
                }
            });
            let area = t.twice_area();
            if area == 0 {
                continue;
            }
            for y in -5..25 {
                let (lo, hi) = closed_columns(&t, y);
                for x in -5..25i64 {
                    let (sx, sy) = (x << 4, (y as i64) << 4);
                    let inside = (0..3).all(|k| {
                        let (p, q) = (t.v[k], t.v[(k + 1) % 3]);
                        let e = (q.x as i64 - p.x as i64) * (sy - p.y as i64)
                            - (q.y as i64 - p.y as i64) * (sx - p.x as i64);
                        e * area.signum() >= 0
                    });
                    assert_eq!(inside, lo <= x && x <= hi, "{:?} row {y} col {x}", t.v);
                    seen += inside as u32;
                }
            }
        }
        assert!(seen > 10_000, "{seen} samples inside");
    }
}
