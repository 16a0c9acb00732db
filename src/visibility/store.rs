//! The triangle store: the methods that see every triangle before drawing any (painter,
//! scan-line) keep the polygon stage's triangles here, in caller memory.
//!
//! A [`StoredTriangle`] is exactly what the z-buffer's level writer would have drawn at once
//! (three sub-pixel corners, their 32-bit depths and levels, and the object they belong to, for
//! its ramp, dither and shading mode), so [`StoredTriangle::draw`] writes the same pixels
//! later, into whatever part of the frame ([`RasterTarget::restrict`]) the method asks.
//!
//! Numeric contract: corners within the projector's `±(2^28 − 1)` sub-pixel range (what the
//! polygon stage hands on), depths `u32` clamped by the writer as on the z-buffer path,
//! levels `0..=255` (clipped corners' interpolated levels are clamped here, as the level
//! writer clamps them), objects `0..=255`.

use crate::geometry::vector::Vec3;
use crate::output::DepthValue;
use crate::raster::triangle::{twice_area, RasterTarget, WrittenCount};
use crate::raster::SubpixelPoint;
use crate::render::consumer::{Corner, LevelWriter, TriangleConsumer};
use crate::render::RenderError;
use crate::scene::Scene;

use super::VisibilityError;

/// No cut: see [`StoredTriangle::cuts`].
pub(crate) const NO_CUT: u32 = u32::MAX;
/// A cut's side bit: the piece keeps the samples in front of (not behind) the plane.
pub(crate) const CUT_FRONT: u32 = 1 << 31;

/// The most triangles (with the painter's pieces) a store may hold: indices and cut
/// references are 31-bit.
pub(crate) const MAX_STORED: usize = (1 << 31) - 1;

/// One front triangle kept for later drawing (24 + 12 + 4 + 4 + 4 + 4 = 52 bytes at any `S`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StoredTriangle<const S: u32 = 4> {
    /// Sub-pixel corners, as the polygon stage handed them.
    pub(crate) v: [SubpixelPoint<S>; 3],
    /// The corners' 32-bit depths.
    pub(crate) depth: [u32; 3],
    /// The corners' levels.
    pub(crate) level: [u8; 3],
    /// Index of the object in the scene.
    pub(crate) object: u8,
    /// The painter's pieces (Newell's test 6): the last plane this piece was cut by, the
    /// index of a stored triangle with [`CUT_FRONT`] set when the piece keeps the samples in
    /// front of that plane (else those behind it); [`NO_CUT`] for a whole triangle. The
    /// piece's earlier cuts are its parent's ([`cuts`]), so a piece may take as many cuts as
    /// the store holds pieces.
    pub(crate) cut: u32,
    /// The stored triangle this piece was cut from (a piece or the whole triangle; unused
    /// when [`Self::cut`] is [`NO_CUT`]).
    pub(crate) parent: u32,
    /// The stored triangle this is a piece of (its own index when whole): pieces share their
    /// base's corners and plane, so cuts name bases.
    pub(crate) base: u32,
}

impl<const S: u32> Default for StoredTriangle<S> {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl<const S: u32> StoredTriangle<S> {
    /// An unused slot, for declaring a store (`[StoredTriangle::DEFAULT; N]`, also in a
    /// `static`).
    pub const DEFAULT: Self = StoredTriangle {
        v: [SubpixelPoint::new(0, 0); 3],
        depth: [0; 3],
        level: [0; 3],
        object: 0,
        cut: NO_CUT,
        parent: 0,
        base: 0,
    };
}

impl<const S: u32> StoredTriangle<S> {
    /// Draws the triangle into `target` (its window as restricted) with its object's ramp,
    /// dither and shading, through the z-buffer's level writer; returns `(covered, written)`.
    #[inline]
    pub(crate) fn draw<D: DepthValue, C: WrittenCount>(
        &self,
        scene: &Scene<'_>,
        target: &mut RasterTarget<'_, D, C>,
    ) -> Result<(u32, u32), RenderError> {
        let Some(object) = scene.objects.get(self.object as usize) else {
            return Ok((0, 0));
        };
        let corner = |k: usize| Corner {
            screen: self.v[k],
            depth: self.depth[k],
            view: Vec3::ZERO,
            attrs: [self.level[k] as i32],
        };
        LevelWriter { target, object }.triangle(0, [corner(0), corner(1), corner(2)])
    }

    /// Twice the signed screen area (sub-pixel units², `|·| < 2^59`): its sign is the
    /// orientation, zero for a triangle that covers no pixel.
    pub(crate) fn twice_area(&self) -> i64 {
        let [a, b, c] = self.v;
        twice_area(a, b, c)
    }

    /// Whether this is a piece of a triangle (it has a cut), not a whole one.
    pub(crate) fn is_piece(&self) -> bool {
        self.cut != NO_CUT
    }

    /// Smallest and largest corner depth.
    pub(crate) fn depth_range(&self) -> (u32, u32) {
        let [a, b, c] = self.depth;
        (a.min(b).min(c), a.max(b).max(c))
    }

    /// Rows whose pixels the triangle may cover: `⌈min y⌉ ..= ⌊max y⌋` in pixels.
    pub(crate) fn rows(&self) -> (i32, i32) {
        let (lo, hi) = (
            self.v[0].y.min(self.v[1].y).min(self.v[2].y),
            self.v[0].y.max(self.v[1].y).max(self.v[2].y),
        );
        (-((-lo) >> S), hi >> S)
    }
}

/// The cuts of stored triangle `t` (none for a whole triangle), the latest first: its own,
/// then its parent's, back to the whole triangle. `store` holds `t`'s parents (the painter's
/// store: a piece's parent is stored before it, so the walk ends).
pub(crate) fn cuts<'a, const S: u32>(
    store: &'a [StoredTriangle<S>],
    t: &'a StoredTriangle<S>,
) -> impl Iterator<Item = u32> + Clone + 'a {
    let mut at = Some(t);
    core::iter::from_fn(move || {
        let piece = at.filter(|p| p.is_piece())?;
        at = store.get(piece.parent as usize);
        Some(piece.cut)
    })
}

/// The consumer that stores each triangle of one object, in order, into `store[len..]`.
///
/// The polygon stage's seam reports in the pipeline's vocabulary ([`RenderError`]), which
/// has no word for a method's full store: a triangle that finds the store full sets `full`
/// and is dropped, the stage goes on to the object's end, and [`collect`] reports
/// [`VisibilityError::TriangleStoreFull`] then. The stage stops at its first error, so an
/// error it returns after `full` was set came later, and the store's is the one reported, as
/// if the stage had stopped there.
pub(crate) struct Collector<'a, const S: u32> {
    pub(crate) store: &'a mut [StoredTriangle<S>],
    pub(crate) len: usize,
    pub(crate) object: u8,
    /// A triangle found the store full (and was dropped).
    pub(crate) full: bool,
}

impl<const S: u32> TriangleConsumer<S, 1> for Collector<'_, S> {
    #[inline]
    fn triangle(&mut self, _: usize, c: [Corner<S, 1>; 3]) -> Result<(u32, u32), RenderError> {
        let t = StoredTriangle {
            v: c.map(|c| c.screen),
            depth: c.map(|c| c.depth),
            level: c.map(|c| c.attrs[0].clamp(0, 255) as u8),
            object: self.object,
            cut: NO_CUT,
            parent: self.len as u32,
            base: self.len as u32,
        };
        // A triangle of no area covers no pixel (the fill draws none): not kept.
        if t.twice_area() == 0 {
            return Ok((0, 0));
        }
        let capacity = self.store.len().min(MAX_STORED);
        match self
            .store
            .get_mut(..capacity)
            .and_then(|s| s.get_mut(self.len))
        {
            Some(slot) => {
                *slot = t;
                self.len += 1;
            }
            None => self.full = true,
        }
        Ok((0, 0))
    }
}

/// Runs the vertex and polygon stages of every object of the renderer's scene, storing its
/// front triangles into `store`; returns how many. More than `store` holds is
/// [`VisibilityError::TriangleStoreFull`] naming its capacity; a scene of more than 256
/// objects (a stored triangle names its object in a byte) is
/// [`VisibilityError::TooManyObjects`].
pub(crate) fn collect<const S: u32>(
    renderer: &crate::render::SceneRenderer<'_, S>,
    scratch: &mut [crate::render::PreparedVertex<S>],
    store: &mut [StoredTriangle<S>],
    stats: &mut crate::render::RenderStats,
) -> Result<usize, VisibilityError> {
    let (scene, renderer) = (renderer.scene(), renderer.renderer());
    if scene.objects.len() > 256 {
        return Err(VisibilityError::TooManyObjects { max: 256 });
    }
    let capacity = store.len().min(MAX_STORED);
    let mut len = 0;
    for (i, object) in scene.objects.iter().enumerate() {
        if object.texture.is_some() {
            return Err(RenderError::TextureUnsupported {
                object: i,
                method: "a visibility method that stores triangles",
            }
            .into());
        }
        renderer.prepare(object, scratch)?;
        let mut collector = Collector {
            store: &mut *store,
            len,
            object: i as u8,
            full: false,
        };
        let stage = renderer.collect_levels(object, scratch, stats, &mut collector);
        if collector.full {
            return Err(VisibilityError::TriangleStoreFull { capacity });
        }
        stage?;
        len = collector.len;
    }
    stats.method.stored = len as u32;
    Ok(len)
}

/// Fills `order` with the indices `0..order.len()` of stored triangles, sorted by `key`, then
/// by index (so equal keys keep the stored order).
pub(crate) fn sort_order<K: Ord>(order: &mut [u32], key: impl Fn(usize) -> K) {
    for (i, o) in order.iter_mut().enumerate() {
        *o = i as u32;
    }
    order.sort_unstable_by_key(|&i| (key(i as usize), i));
}
