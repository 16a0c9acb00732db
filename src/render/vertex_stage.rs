//! The vertex stage ([`Renderer::prepare`]), once per mesh vertex: model → observer frame with
//! one combined [`Affine3`], the vertex's [`Frustum`](crate::clip::frustum::Frustum) outcode,
//! and, when it is inside the frustum (near, far and the guard band), its projection
//! (sub-pixel screen position and normalised depth); for lit Gouraud objects its lit level,
//! for levels given per vertex a copy of that level. Results go to caller scratch, one
//! [`PreparedVertex`] (28 bytes) per mesh vertex, or, through the same loop
//! (`Renderer::prepare_with`, which hands each vertex to a store of the caller's), to the
//! 8-byte [`CompactVertex`](super::CompactVertex) of compact bands (`compact.rs`).
//!
//! Numeric contract: mesh coordinates `|c| ≤ 1024`
//! ([`MAX_MESH_COORD_BITS`](crate::geometry::mesh::MAX_MESH_COORD_BITS)); observer-frame
//! positions saturate to the I16F16 range. Once per object the stage bounds them from the
//! mesh's largest coordinate ([`Affine3::point_bounds`]); when that bound is below `2^30` (and
//! the frustum's side products fit 32 bits, `Frustum::narrow_fits`) it runs a loop without
//! saturation and with a 32-bit outcode, equal within the bound (tested against the general
//! loop). Levels are `0..=255`.

use super::Renderer;
use super::{IntensityTable, RenderError};
use crate::geometry::matrix::Affine3;
use crate::geometry::vector::Vec3;
use crate::raster::triangle::ShadeMode;
use crate::raster::SubpixelPoint;
use crate::scene::{Intensities, Object};

/// Outcode bit marking a vertex that could not be projected (forces the clipping path).
pub(super) const UNPROJECTED: u8 = 0x80;

/// One mesh vertex after the vertex stage: 28 bytes (the scratch a mesh needs is 28 bytes per
/// vertex; the bunny's 1,839 vertices take 51 KB).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PreparedVertex<const S: u32 = 4> {
    /// Observer-frame position.
    pub view: Vec3,
    /// Screen position (valid when `outcode == 0`).
    pub screen: SubpixelPoint<S>,
    /// Normalised depth (valid when `outcode == 0`).
    pub depth: u32,
    /// Frustum outcode: bit `i` set when outside plane `i`; 0 when projected.
    pub outcode: u8,
    /// Level `0..=255` of the vertex: lit, for a Gouraud-shaded lit object, or given
    /// ([`Intensities::PerVertex`], 0 past the end of a short table), where the polygon stage
    /// reads it with the vertex; 0 otherwise. It fits in the structure's padding.
    pub level: u8,
}

impl<const S: u32> PreparedVertex<S> {
    /// The zeroed vertex ([`Default`]), for scratch built at compile time: a `static` of them
    /// (`[PreparedVertex::ZERO; N]`) is zero-initialised memory (`.bss`), built in place
    /// rather than on the stack. The vertex stage overwrites every vertex it uses.
    pub const ZERO: Self = PreparedVertex {
        view: Vec3::ZERO,
        screen: SubpixelPoint::new(0, 0),
        depth: 0,
        outcode: 0,
        level: 0,
    };
}

impl<const S: u32> Default for PreparedVertex<S> {
    fn default() -> Self {
        Self::ZERO
    }
}

impl<const S: u32> Renderer<S> {
    /// The vertex stage for `object`: fills `scratch[..vertex count]`.
    pub fn prepare(
        &self,
        object: &Object<'_>,
        scratch: &mut [PreparedVertex<S>],
    ) -> Result<(), RenderError> {
        let (given, needed) = (scratch.len(), object.mesh.vertices().len());
        let scratch = scratch
            .get_mut(..needed)
            .ok_or(RenderError::ScratchTooSmall { given, needed })?;
        self.prepare_with(object, scratch, &mut |_, out, p| *out = p)
    }

    /// The vertex stage for `object` into `out` (as long as its vertex table; the caller
    /// checked): each vertex `i` is handed to `emit(i, &mut out[i], prepared)`, which stores
    /// it in its own form (the [`PreparedVertex`] itself, or the compact form of
    /// `compact.rs`). One stage for both: inlined, the full form's loop is unchanged.
    #[inline(always)]
    pub(super) fn prepare_with<T>(
        &self,
        object: &Object<'_>,
        out: &mut [T],
        emit: &mut impl FnMut(usize, &mut T, PreparedVertex<S>),
    ) -> Result<(), RenderError> {
        let vertices = object.mesh.vertices();
        let m = self.model_view(object)?;
        // Lit Gouraud objects are lit here, once per vertex, in the observer frame.
        let lit = match object.intensities {
            Intensities::Lit { material, normals }
                if !matches!(object.shade, ShadeMode::Flat | ShadeMode::Phong) =>
            {
                if normals.len() < vertices.len() {
                    return Err(RenderError::IntensitiesTooShort {
                        table: IntensityTable::Normals,
                        given: normals.len(),
                        needed: vertices.len(),
                    });
                }
                Some((material, normals))
            }
            _ => None,
        };
        // Levels given per vertex are copied beside the vertex, where the polygon stage reads
        // them with it.
        let given = match object.intensities {
            Intensities::PerVertex(t) => t,
            _ => &[],
        };
        // Once per object: when no vertex of the mesh (all within ±max_coord_bits) can leave
        // the i32 range, nor make the frustum's side products leave 32 bits, the loop without
        // saturation and with the 32-bit outcode runs; both give the same values there.
        let narrow = self
            .frustum
            .narrow_fits(m.point_bounds(object.mesh.max_coord_bits()));
        // One loop per level source, so that the given-levels loop carries nothing of lighting.
        match lit {
            Some((material, normals)) => {
                let level = |i: usize, view: Vec3| {
                    let n = normals
                        .get(i)
                        .map_or([0; 3], |n| m.transform_vector(*n).bits());
                    let n = [n[0] as i64, n[1] as i64, n[2] as i64];
                    self.illumination.intensity(&material, view, n)
                };
                self.prepare_vertices(narrow, &m, vertices, out, &level, emit);
            }
            None => {
                let level = |i: usize, _: Vec3| given.get(i).copied().unwrap_or(0);
                self.prepare_vertices(narrow, &m, vertices, out, &level, emit);
            }
        }
        Ok(())
    }

    /// [`prepare_loop`](Self::prepare_loop) without saturation and with the 32-bit outcode
    /// when `narrow` (the object's bound passed [`Frustum::narrow_fits`](crate::clip::frustum::Frustum::narrow_fits)), else the general one.
    #[inline(always)]
    fn prepare_vertices<T>(
        &self,
        narrow: bool,
        m: &Affine3,
        vertices: &[Vec3],
        out: &mut [T],
        level: &impl Fn(usize, Vec3) -> u8,
        emit: &mut impl FnMut(usize, &mut T, PreparedVertex<S>),
    ) {
        if narrow {
            self.prepare_loop::<true, T>(m, vertices, out, level, emit);
        } else {
            self.prepare_loop::<false, T>(m, vertices, out, level, emit);
        }
    }

    /// The per-vertex loop of [`prepare`](Self::prepare): `NARROW` when the object's bound
    /// passed [`Frustum::narrow_fits`](crate::clip::frustum::Frustum::narrow_fits) ([`Affine3::transform_point_wrapping`] and
    /// [`Frustum::outcode_narrow`](crate::clip::frustum::Frustum::outcode_narrow), equal to the saturating transform and the 64-bit outcode
    /// within that bound), else the general transform and outcode.
    /// `level(i, view)` gives vertex `i`'s level; `emit` stores the vertex in `out`.
    #[inline(always)]
    fn prepare_loop<const NARROW: bool, T>(
        &self,
        m: &Affine3,
        vertices: &[Vec3],
        out: &mut [T],
        level: &impl Fn(usize, Vec3) -> u8,
        emit: &mut impl FnMut(usize, &mut T, PreparedVertex<S>),
    ) {
        for (i, (out, v)) in out.iter_mut().zip(vertices).enumerate() {
            let (view, mut outcode);
            if NARROW {
                view = m.transform_point_wrapping(*v);
                outcode = self.frustum.outcode_narrow(view);
            } else {
                view = m.transform_point(*v);
                outcode = self.frustum.outcode(view);
            }
            let (mut screen, mut depth) = (SubpixelPoint::new(0, 0), 0);
            if outcode == 0 {
                match self.projector.project_point(view) {
                    Ok((p, d)) => (screen, depth) = (p, d),
                    Err(_) => outcode = UNPROJECTED,
                }
            }
            let prepared = PreparedVertex {
                view,
                screen,
                depth,
                outcode,
                level: level(i, view),
            };
            emit(i, out, prepared);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::camera::Camera;

    /// The lit level lives in the padding: a prepared vertex stays 28 bytes (7 words), as its
    /// doc says.
    #[test]
    fn prepared_vertex_is_seven_words() {
        assert_eq!(core::mem::size_of::<PreparedVertex<4>>(), 28);
    }

    /// The compile-time vertex is the origin, projected nowhere, unlit.
    #[test]
    fn zero_vertex_is_all_zero_fields() {
        let z = PreparedVertex::<4>::ZERO;
        assert_eq!((z.view, z.screen.x, z.screen.y), (Vec3::ZERO, 0, 0));
        assert_eq!((z.depth, z.outcode, z.level), (0, 0, 0));
    }

    /// The vertex loop without saturation and with the 32-bit outcode gives the same prepared
    /// vertices as the general one, for objects whose bound lets `prepare` choose it.
    #[test]
    fn narrow_vertex_loop_equals_general_loop() {
        use crate::geometry::camera::{FovAxis, Lens, Viewport};
        use crate::geometry::fixed::Coord;
        use crate::geometry::mesh::{Mesh, MAX_MESH_COORD_BITS};
        use crate::geometry::trig::BinaryAngle;
        let c = |x: f64| Coord::from_num(x);
        let lens = Lens {
            fov: BinaryAngle::from_degrees(60),
            axis: FovAxis::Vertical,
            near: c(0.5),
            far: c(10.0),
        };
        let cam = Camera::new(
            Vec3::new(c(0.3), c(1.0), c(-4.0)),
            Vec3::new(c(0.0), c(-0.2), c(1.0)),
            Vec3::new(c(0.0), c(1.0), c(0.0)),
            lens,
            Viewport::new(320, 240),
        )
        .unwrap();
        let r = Renderer::<4>::new(&cam).unwrap();
        let mut rng = crate::test_rng::XorShift(0xC0FF_EE12_3456_789Bu64);
        let mut rnd = || rng.next_u64();
        let (mut narrow_runs, mut codes) = (0, [0u32; 2]);
        for n in 0..60 {
            let span = [1u64 << 10, 1 << 17, 1 << 22, MAX_MESH_COORD_BITS as u64][n % 4];
            let mut coord = || ((rnd() % (2 * span + 1)) as i64 - span as i64) as i32;
            let mut vs = [Vec3::ZERO; 64];
            for v in vs.iter_mut() {
                *v = Vec3::from_bits(coord(), coord(), coord());
            }
            vs[0] = Vec3::from_bits(span as i32, -(span as i32), span as i32);
            let levels: [u8; 40] = core::array::from_fn(|i| (i * 7) as u8);
            let mesh = Mesh::triangles(&vs, &[]).unwrap();
            let mut obj = Object::new(mesh);
            obj.intensities = Intensities::PerVertex(&levels);
            let s = [0.01, 0.3, 1.0, 4.0, 60.0][n % 5];
            let rot = Affine3::rotation_axis(
                Vec3::new(c(1.0), c(2.0), c(-0.5)),
                BinaryAngle::from_degrees(n as i32 * 37),
            )
            .unwrap();
            let t = Affine3::translation(Vec3::new(c(0.5), c(-0.25), c((n % 7) as f64)));
            obj.transform = Affine3::scale(c(s))
                .unwrap()
                .then(&rot)
                .unwrap()
                .then(&t)
                .unwrap();
            let m = r.model_view(&obj).unwrap();
            let narrow = r.frustum.narrow_fits(m.point_bounds(mesh.max_coord_bits()));
            narrow_runs += narrow as u32;
            let mut a = [PreparedVertex::<4>::default(); 64];
            let mut b = [PreparedVertex::<4>::default(); 64];
            r.prepare(&obj, &mut a).unwrap();
            let level = |i: usize, _: Vec3| levels.get(i).copied().unwrap_or(0);
            let emit = &mut |_, o: &mut PreparedVertex<4>, p| *o = p;
            r.prepare_loop::<false, _>(&m, &vs, &mut b, &level, emit);
            assert_eq!(a, b, "n={n} narrow={narrow}");
            if narrow {
                r.prepare_loop::<true, _>(&m, &vs, &mut a, &level, emit);
                assert_eq!(a, b, "n={n}");
                for v in &a {
                    codes[(v.outcode != 0) as usize] += 1;
                }
            }
        }
        // Both paths ran, and the narrow one saw projected and outside vertices.
        assert!((10..60).contains(&narrow_runs), "{narrow_runs}");
        assert!(codes[0] > 50 && codes[1] > 50, "{codes:?}");
    }
}
