//! Warnock's area subdivision (the survey's "échantillonnage de surface"): a window of the
//! frame is drawn at once when what shows in it is simple, else split into four, down to one
//! pixel, where the exact depth decides.
//!
//! The **looker** ([`Looker::relation`]) classifies a stored triangle against a window: its
//! pixels (lattice points) are all covered by the triangle (*surrounding*), none (*disjoint*),
//! or some, the triangle's box inside the window (*contained*) or not (*intersecting*). The
//! **thinker** ([`Warnock::verdict`]) decides, from the triangles that are not disjoint (the
//! window's candidates, filtered from its parent's), whether the window is simple:
//!
//! - **empty**: no candidate, the background shows (the frame was cleared to it);
//! - **one**: one candidate, drawn restricted to the window, no depth;
//! - **front**: a surrounding candidate that the z-buffer would keep at every pixel of the
//!   window against every other candidate, drawn restricted to the window;
//! - **pixel**: the front verdict on a one-pixel window, which is always simple: every
//!   candidate covers its one lattice point (surrounds it), each depth bound is the depth
//!   there, and the front test is the z-buffer's own comparison (the nearest exactly rounded
//!   depth, the earliest stored on ties);
//! - **split**: else, four sub-windows (two when one side is one pixel).
//!
//! Exactness. Coverage is the fill's rule (`raster::polygon`): a lattice point is covered when
//! it lies inside every edge's half-plane, closed for a left edge (interior to its right) or a
//! horizontal top edge, open for the others. The covered set is convex, so a window's pixels
//! are all covered when its four corner pixels are, and none when one edge has all four corner
//! pixels outside (or the boxes are apart). A depth is the z-buffer's stored value: vertex
//! depths clamped to [`DepthValue::MAX_DEPTH32`] (`u32`), the affine plane rounded half up
//! (`raster::triangle::plane`). Rounding is monotone and the plane affine, so over a window a plane's
//! extreme stored values are its rounded values at corner pixels (extended beyond the triangle
//! for a candidate that covers part of the window: a bound on what it stores there). The z-buffer
//! keeps the earlier of two equal depths, so the front triangle `T` wins against `U` when
//! `max T < min U`, or `max T = min U` and `T` was stored first. Every pixel drawn is then the
//! pixel the 32-bit z-buffer writes (`tests/visibility.rs` compares them).
//!
//! Refused in words: a core-lit Phong object ([`RenderError::PhongUnsupported`]: a stored
//! corner keeps a level, not a normal) and a fast Gouraud object
//! ([`VisibilityError::FastGouraudInParts`]: a triangle drawn window by window would start its
//! 16.16 luminance steps at each window's first column, not at its span's, and differ from the
//! z-buffer by a level at some pixels); draw those with exact Gouraud, the scan-line or the
//! z-buffer.
//!
//! Memory (caller slices, [`WarnockMemory`]): a stored triangle (52 bytes) per front triangle;
//! a stack of candidate lists (a `u32` per candidate, each level's list after its parent's: at
//! most the front triangles plus the lists along one path of the subdivision); a stack of
//! windows (at most `1 + 3·levels`, `levels = ⌈log2 max(width, height)⌉`: 28 at 320 × 240).
//! Exceeding any is an error naming it and its capacity, never a wrong picture. No depth
//! buffer: the claim is the 32-bit z-buffer's picture (a 16-bit one differs where its depths
//! tie, `docs/BENCHMARKS.md`).
//!
//! Cost: a window is simple only when one triangle covers it or one surrounding triangle is in
//! front, so along every edge of a mesh (two triangles sharing it, neither surrounding) the
//! windows split down to pixels, and each window drawn sets up its triangle again: ×11–22 the
//! z-buffer frame on the Cortex-M4 for the standard scenes (`docs/BENCHMARKS.md`).
//!
//! Numeric contract: corners within `±(2^28 − 1)` sub-pixel units, pixels within the frame
//! (`< 2^16` pixels, `< 2^(16 + S) ≤ 2^32` sub-pixel units). Edge functions in `i64`: normal
//! components `< 2^29` (corner to corner), differences `< 2^32 + 2^28` (corner to pixel), so
//! `|e| < 2·(2^61 + 2^57) < 2^63`. Depth planes in `i128`: `gx, gy < 2^62`, `D < 2^59`,
//! `M = gx·dx + gy·dy < 2^96`.

use super::backface::without_depth;
use super::store::{collect, StoredTriangle};
use super::VisibilityError;
use crate::output::{DepthValue, Framebuffer, NoDepth};
use crate::raster::triangle::{RasterTarget, ShadeMode, WrittenCount};
use crate::raster::Window;
use crate::render::{check_transparency, Draws};
use crate::render::{PreparedVertex, RenderError, RenderStats, SceneRenderer, StatsSink};
use crate::scene::Scene;

/// The most subdivision levels (a side of `2^16` pixels halves 16 times to one pixel).
const MAX_LEVELS: usize = 17;

/// A candidate list entry's flag: the triangle surrounds the window.
const SURROUNDS: u32 = 1 << 31;

/// A window waiting on the subdivision stack, with its level (0: the frame).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Area {
    window: Window,
    level: u8,
}

impl Area {
    /// An unused slot, for declaring a stack (`[Area::DEFAULT; N]`, also in a `static`).
    pub const DEFAULT: Area = Area {
        window: Window::new(0, 0, 0, 0),
        level: 0,
    };
}

impl Default for Area {
    fn default() -> Self {
        Area::DEFAULT
    }
}

/// Caller memory of [`render_warnock`] (module doc).
#[derive(Debug)]
pub struct WarnockMemory<'a, const S: u32 = 4> {
    /// The front triangles.
    pub triangles: &'a mut [StoredTriangle<S>],
    /// The candidate lists of the windows being subdivided, one after the other.
    pub candidates: &'a mut [u32],
    /// The windows waiting to be visited.
    pub windows: &'a mut [Area],
}

/// How a triangle meets a window's pixels ([`Looker::relation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Relation {
    /// Covers no pixel of the window.
    Disjoint,
    /// May cover some pixels; its box leaves the window.
    Intersecting,
    /// May cover some pixels; its box lies within the window.
    Contained,
    /// Covers every pixel of the window.
    Surrounding,
}

/// Clears `frame` to the background, stores every object's front triangles and draws them by
/// area subdivision (module doc): the 32-bit z-buffer's picture with no depth buffer. A
/// core-lit Phong object is [`RenderError::PhongUnsupported`], a fast Gouraud object
/// [`VisibilityError::FastGouraudInParts`].
/// The windows visited are added to `windows`.
pub fn render_warnock<T: StatsSink, const S: u32>(
    renderer: &SceneRenderer<'_, S>,
    frame: &mut Framebuffer<'_>,
    scratch: &mut [PreparedVertex<S>],
    memory: WarnockMemory<'_, S>,
    stats: &mut T,
) -> Result<(), VisibilityError> {
    let scene = renderer.scene();
    renderer.renderer().check_frame(frame)?;
    check_transparency(renderer.scene(), "Warnock's subdivision", Draws::Neither)?;
    let counts = stats.counts();
    let WarnockMemory {
        triangles,
        candidates,
        windows,
    } = memory;
    // Every triangle may be drawn in windows, where fast Gouraud's 16.16 steps would start
    // at the window's first column: refused (module doc).
    let fast = scene
        .objects
        .iter()
        .position(|o| o.shade == ShadeMode::GouraudFast);
    if let Some(object) = fast {
        return Err(VisibilityError::FastGouraudInParts { object });
    }
    let capacity = triangles.len().min(candidates.len());
    let n = collect(renderer, scratch, &mut triangles[..capacity], counts)?;
    frame.clear(scene.background);
    without_depth(frame, |frame, depth| {
        let target = RasterTarget::with_count(frame, depth, T::Count::default());
        let mut warnock = Warnock {
            scene,
            triangles: &triangles[..n],
            lists: candidates,
            starts: [0; MAX_LEVELS + 1],
            windows,
            target,
            stats: counts,
        };
        warnock.run()
    })
}

/// The subdivision's state: the stored triangles, the stacks and the target.
struct Warnock<'a, 's, 't, C, const S: u32> {
    scene: &'a Scene<'s>,
    triangles: &'a [StoredTriangle<S>],
    /// Candidate lists: level `L`'s in `lists[starts[L]..starts[L + 1]]`.
    lists: &'a mut [u32],
    starts: [usize; MAX_LEVELS + 1],
    windows: &'a mut [Area],
    target: RasterTarget<'t, NoDepth, C>,
    stats: &'a mut RenderStats,
}

/// What the thinker decided for a window.
enum Verdict {
    Empty,
    /// Draw this triangle over the window (one candidate, or the surrounding one in front).
    Draw(u32, bool),
    /// Draw this triangle at the one pixel (the nearest there, the earliest on ties).
    Pixel(u32),
    Split,
}

impl<C: WrittenCount, const S: u32> Warnock<'_, '_, '_, C, S> {
    /// Visits windows depth first from the whole frame.
    fn run(&mut self) -> Result<(), VisibilityError> {
        let stack_capacity = self.windows.len();
        let full = self.target.buffers();
        if full.is_empty() {
            return Ok(());
        }
        let mut top = 0;
        self.push(&mut top, full, 0)?;
        while top > 0 {
            top -= 1;
            let Area { window, level } = self.windows[top];
            let level = level as usize;
            self.filter(window, level)?;
            let verdict = self.verdict(window, level);
            let counts = &mut self.stats.method.windows;
            match verdict {
                Verdict::Empty => counts.empty += 1,
                Verdict::Draw(t, front) => {
                    if front {
                        counts.front += 1;
                    } else {
                        counts.one += 1;
                    }
                    self.draw(t, window)?;
                }
                Verdict::Pixel(t) => {
                    counts.pixel += 1;
                    self.draw(t, window)?;
                }
                Verdict::Split => {
                    counts.split += 1;
                    if level + 1 >= MAX_LEVELS {
                        // A window of at most 2^16 pixels a side is one pixel by then, and a
                        // one-pixel window is always simple (module doc): not reached.
                        return Err(VisibilityError::SubdivisionStackFull {
                            capacity: stack_capacity,
                        });
                    }
                    let (x0, y0, x1, y1) = (window.x0, window.y0, window.x1, window.y1);
                    let (mx, my) = (x0 + (x1 - x0 + 1) / 2, y0 + (y1 - y0 + 1) / 2);
                    // Pushed bottom-right first: the top-left quarter is visited first.
                    for w in [
                        Window::new(mx, my, x1, y1),
                        Window::new(x0, my, mx, y1),
                        Window::new(mx, y0, x1, my),
                        Window::new(x0, y0, mx, my),
                    ] {
                        if !w.is_empty() {
                            self.push(&mut top, w, level + 1)?;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Pushes a window on the stack, or says the stack is full.
    fn push(
        &mut self,
        top: &mut usize,
        window: Window,
        level: usize,
    ) -> Result<(), VisibilityError> {
        let capacity = self.windows.len();
        let slot = self
            .windows
            .get_mut(*top)
            .ok_or(VisibilityError::SubdivisionStackFull { capacity })?;
        *slot = Area {
            window,
            level: level as u8,
        };
        *top += 1;
        let peak = &mut self.stats.method.stack_peak;
        *peak = (*peak).max(*top as u32);
        Ok(())
    }

    /// Writes the window's candidates (its parent's that are not disjoint from it, in stored
    /// order, flagged [`SURROUNDS`] when they surround it) as level `level`'s list.
    fn filter(&mut self, window: Window, level: usize) -> Result<(), VisibilityError> {
        let looker = Looker::<S>::new(window);
        let start = self.starts[level];
        let mut end = start;
        let capacity = self.lists.len();
        let full = VisibilityError::SubdivisionCandidatesFull { capacity };
        let parent = if level == 0 {
            0..0
        } else {
            self.starts[level - 1]..start
        };
        let from_parent = level > 0;
        let count = if from_parent {
            parent.len()
        } else {
            self.triangles.len()
        };
        for i in 0..count {
            let t = if from_parent {
                self.lists[parent.start + i] & !SURROUNDS
            } else {
                i as u32
            };
            let flag = match looker.relation(&self.triangles[t as usize]) {
                Relation::Disjoint => continue,
                Relation::Surrounding => SURROUNDS,
                Relation::Intersecting | Relation::Contained => 0,
            };
            *self.lists.get_mut(end).ok_or(full)? = t | flag;
            end += 1;
        }
        self.starts[level + 1] = end;
        let peak = &mut self.stats.method.candidates_peak;
        *peak = (*peak).max(end as u32);
        Ok(())
    }

    /// The thinker (module doc), on level `level`'s list.
    fn verdict(&self, window: Window, level: usize) -> Verdict {
        let list = &self.lists[self.starts[level]..self.starts[level + 1]];
        match list {
            [] => return Verdict::Empty,
            [one] => return Verdict::Draw(one & !SURROUNDS, false),
            _ => {}
        }
        let looker = Looker::<S>::new(window);
        // The surrounding candidate with the nearest farthest depth (the earliest on ties): if
        // any surrounding candidate is in front of all others, this one is.
        let front = list
            .iter()
            .filter(|&&e| e & SURROUNDS != 0)
            .map(|&e| {
                let t = e & !SURROUNDS;
                (looker.depth_bounds(&self.triangles[t as usize]).1, t)
            })
            .min();
        if let Some((far, t)) = front {
            let wins = list.iter().all(|&e| {
                let u = e & !SURROUNDS;
                u == t || {
                    let near = looker.depth_bounds(&self.triangles[u as usize]).0;
                    far < near || (far == near && t < u)
                }
            });
            if wins {
                let pixel = window.x1 - window.x0 == 1 && window.y1 - window.y0 == 1;
                return if pixel {
                    Verdict::Pixel(t)
                } else {
                    Verdict::Draw(t, true)
                };
            }
        }
        Verdict::Split
    }

    /// Draws triangle `t` restricted to `window`, counting.
    fn draw(&mut self, t: u32, window: Window) -> Result<(), RenderError> {
        let full = self.target.buffers();
        self.target.restrict(window);
        let drawn = self.triangles[t as usize].draw(self.scene, &mut self.target);
        self.target.restrict(full);
        self.stats.add_triangle(drawn?);
        Ok(())
    }
}

/// The looker: a window's corner pixels in sub-pixel units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Looker<const S: u32> {
    /// Left and right corner columns, top and bottom corner rows (`x0 ≤ x1`, `y0 ≤ y1`).
    x: [i64; 2],
    y: [i64; 2],
}

impl<const S: u32> Looker<S> {
    /// The looker of a non-empty window.
    pub(crate) fn new(w: Window) -> Self {
        Looker {
            x: [(w.x0 as i64) << S, ((w.x1 - 1) as i64) << S],
            y: [(w.y0 as i64) << S, ((w.y1 - 1) as i64) << S],
        }
    }

    /// The window's four corner pixels.
    fn corners(&self) -> [(i64, i64); 4] {
        let ([x0, x1], [y0, y1]) = (self.x, self.y);
        [(x0, y0), (x1, y0), (x0, y1), (x1, y1)]
    }

    /// How `t` meets the window's pixels (module doc): exact for surrounding (every pixel
    /// covered), conservative for disjoint (no pixel covered when said, perhaps none when not).
    pub(crate) fn relation(&self, t: &StoredTriangle<S>) -> Relation {
        let xs = t.v.map(|p| p.x as i64);
        let ys = t.v.map(|p| p.y as i64);
        let (x_lo, x_hi) = (min3(xs), max3(xs));
        let (y_lo, y_hi) = (min3(ys), max3(ys));
        if x_hi < self.x[0] || x_lo > self.x[1] || y_hi < self.y[0] || y_lo > self.y[1] {
            return Relation::Disjoint;
        }
        let corners = self.corners();
        let mut inside_all = [true; 4];
        for edge in HalfPlane::of(t) {
            let inside = corners.map(|(x, y)| edge.holds(x, y));
            if inside == [false; 4] {
                return Relation::Disjoint;
            }
            for (all, i) in inside_all.iter_mut().zip(inside) {
                *all &= i;
            }
        }
        if inside_all == [true; 4] {
            Relation::Surrounding
        } else if x_lo >= self.x[0] && x_hi <= self.x[1] && y_lo >= self.y[0] && y_hi <= self.y[1] {
            Relation::Contained
        } else {
            Relation::Intersecting
        }
    }

    /// The smallest and largest depth `t`'s plane stores over the window's pixels (module doc:
    /// the plane extended beyond the triangle bounds what it stores where it covers).
    pub(crate) fn depth_bounds(&self, t: &StoredTriangle<S>) -> (i128, i128) {
        let plane = DepthPlane::of(t);
        // An affine function is smallest at the corner its gradient points away from.
        let lo_x = if plane.gx >= 0 { self.x[0] } else { self.x[1] };
        let lo_y = if plane.gy >= 0 { self.y[0] } else { self.y[1] };
        let hi_x = if plane.gx >= 0 { self.x[1] } else { self.x[0] };
        let hi_y = if plane.gy >= 0 { self.y[1] } else { self.y[0] };
        (plane.at(lo_x, lo_y), plane.at(hi_x, hi_y))
    }
}

fn min3(v: [i64; 3]) -> i64 {
    v[0].min(v[1]).min(v[2])
}

fn max3(v: [i64; 3]) -> i64 {
    v[0].max(v[1]).max(v[2])
}

/// One edge's half-plane of the fill rule (module doc): `e(P) = n·(P − p)` with `n` the
/// inward normal, a point inside when `e > 0`, or `e = 0` on a closed edge.
#[derive(Debug, Clone, Copy)]
struct HalfPlane {
    p: (i64, i64),
    n: (i64, i64),
    closed: bool,
}

impl HalfPlane {
    /// The three edges of a triangle with area (stored triangles have).
    fn of<const S: u32>(t: &StoredTriangle<S>) -> [HalfPlane; 3] {
        let s = t.twice_area().signum();
        let v = t.v.map(|p| (p.x as i64, p.y as i64));
        [0, 1, 2].map(|k| {
            let (p, q) = (v[k], v[(k + 1) % 3]);
            let n = (-s * (q.1 - p.1), s * (q.0 - p.0));
            HalfPlane {
                p,
                n,
                closed: n.0 > 0 || (n.0 == 0 && n.1 > 0),
            }
        })
    }

    /// Whether the point `(x, y)` (sub-pixel units) is inside this edge's half-plane
    /// (module doc: `|e| < 2^63`).
    fn holds(&self, x: i64, y: i64) -> bool {
        let e = self.n.0 * (x - self.p.0) + self.n.1 * (y - self.p.1);
        e > 0 || (e == 0 && self.closed)
    }
}

/// Whether `t` covers the lattice point `(x, y)` (sub-pixel units): the fill's rule.
#[cfg(test)]
fn covers<const S: u32>(t: &StoredTriangle<S>, x: i64, y: i64) -> bool {
    HalfPlane::of(t).iter().all(|e| e.holds(x, y))
}

/// A stored triangle's depth plane as the z-buffer evaluates it (`raster::triangle::plane`):
/// `A(p) = A0 + M(p)/D` rounded half up, with the vertex depths clamped as the writer clamps
/// them for a 32-bit buffer.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DepthPlane {
    origin: (i64, i64),
    a0: i128,
    gx: i128,
    gy: i128,
    /// Twice the area, made positive (`gx`, `gy` negated with it).
    d: i128,
}

impl DepthPlane {
    pub(crate) fn of<const S: u32>(t: &StoredTriangle<S>) -> DepthPlane {
        let a = t
            .depth
            .map(|z| z.min(<u32 as DepthValue>::MAX_DEPTH32) as i128);
        let x = t.v.map(|p| p.x as i128);
        let y = t.v.map(|p| p.y as i128);
        let (a1, a2) = (a[1] - a[0], a[2] - a[0]);
        let (x1, x2, y1, y2) = (x[1] - x[0], x[2] - x[0], y[1] - y[0], y[2] - y[0]);
        let gx = a1 * y2 - a2 * y1;
        let gy = a2 * x1 - a1 * x2;
        let d = t.twice_area() as i128;
        let s = if d < 0 { -1 } else { 1 };
        DepthPlane {
            origin: (t.v[0].x as i64, t.v[0].y as i64),
            a0: a[0],
            gx: s * gx,
            gy: s * gy,
            d: s * d,
        }
    }

    /// The stored value at the point `(x, y)` (sub-pixel units): `A0 + ⌊(2M + D) / 2D⌋`.
    pub(crate) fn at(&self, x: i64, y: i64) -> i128 {
        let m = self.gx * (x - self.origin.0) as i128 + self.gy * (y - self.origin.1) as i128;
        self.a0 + (2 * m + self.d).div_euclid(2 * self.d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::triangle::fill_triangle;
    use crate::raster::triangle::plane::AttributePlane;
    use crate::raster::SubpixelPoint;
    use crate::test_rng::XorShift;

    /// A random stored triangle with area, corners within ±`r` sub-pixel units of the
    /// origin (often on the lattice, so that edges and corners pass through pixels).
    fn random_triangle(rng: &mut XorShift, r: i64) -> StoredTriangle<4> {
        loop {
            let mut t = StoredTriangle::<4>::DEFAULT;
            for k in 0..3 {
                let mut c = || {
                    let v = rng.range(-r, r) as i32;
                    if rng.chance(40) {
                        v & !15
                    } else {
                        v
                    }
                };
                t.v[k] = SubpixelPoint::new(c(), c());
                t.depth[k] = match rng.below(4) {
                    0 => u32::MAX,
                    1 => rng.below(1000) as u32,
                    _ => rng.next_u64() as u32,
                };
            }
            if t.twice_area() != 0 {
                return t;
            }
        }
    }

    /// The fill's pixels of `t` in `w`, row-major.
    fn filled(t: &StoredTriangle<4>, w: Window) -> [[bool; 48]; 48] {
        let mut px = [[false; 48]; 48];
        fill_triangle(t.v, &w, |s| {
            for x in s.x0..s.x1 {
                px[(s.y - w.y0) as usize][(x - w.x0) as usize] = true;
            }
        })
        .unwrap();
        px
    }

    #[test]
    fn coverage_and_depth_are_the_writers() {
        let mut rng = XorShift::new(0x03a7_0017);
        let w = Window::new(-24, -24, 24, 24);
        for _ in 0..400 {
            let t = random_triangle(&mut rng, 20 << 4);
            let px = filled(&t, w);
            let plane = DepthPlane::of(&t);
            let values = t.depth.map(|z| [z.min(u32::MAX - 1)]);
            let exact = AttributePlane::<1, 4>::new(t.v, values).unwrap();
            for y in w.y0..w.y1 {
                for x in w.x0..w.x1 {
                    let (sx, sy) = ((x as i64) << 4, (y as i64) << 4);
                    let fill = px[(y - w.y0) as usize][(x - w.x0) as usize];
                    assert_eq!(covers(&t, sx, sy), fill, "{t:?} at ({x}, {y})");
                    if fill {
                        let z = exact.values_at(x, y)[0] as i128;
                        assert_eq!(plane.at(sx, sy), z, "{t:?} at ({x}, {y})");
                    }
                }
            }
        }
    }

    #[test]
    fn the_looker_is_exact_for_surrounding_and_safe_for_disjoint() {
        let mut rng = XorShift::new(0x0010_0ce5);
        let w = Window::new(-24, -24, 24, 24);
        let mut seen = [0u32; 4];
        for _ in 0..300 {
            let t = random_triangle(&mut rng, 24 << 4);
            let px = filled(&t, w);
            let plane = DepthPlane::of(&t);
            for _ in 0..20 {
                let (x0, y0) = (rng.range(-24, 23) as i32, rng.range(-24, 23) as i32);
                let (x1, y1) = (
                    rng.range(x0 as i64 + 1, 24) as i32,
                    rng.range(y0 as i64 + 1, 24) as i32,
                );
                let window = Window::new(x0, y0, x1, y1);
                let looker = Looker::<4>::new(window);
                let relation = looker.relation(&t);
                let (lo, hi) = looker.depth_bounds(&t);
                let mut covered = 0;
                for y in y0..y1 {
                    for x in x0..x1 {
                        if px[(y - w.y0) as usize][(x - w.x0) as usize] {
                            covered += 1;
                            let z = plane.at((x as i64) << 4, (y as i64) << 4);
                            assert!(lo <= z && z <= hi, "{t:?} {window:?}");
                        }
                    }
                }
                let all = (x1 - x0) * (y1 - y0);
                let expected_surrounding = covered == all;
                assert_eq!(
                    relation == Relation::Surrounding,
                    expected_surrounding,
                    "{t:?} {window:?}"
                );
                if relation == Relation::Disjoint {
                    assert_eq!(covered, 0, "{t:?} {window:?}");
                }
                seen[relation as usize] += 1;
            }
        }
        // Every relation occurs in the sample.
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
    }
}
