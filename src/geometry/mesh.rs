//! Polygon meshes as the course stores them (ch. 1 §4): a vertex table and a polygon table,
//! both borrowed slices so a mesh can live in flash; face normals, vertex normals, culling.
//!
//! Role in the pipeline: the input of the geometry stage. A frame walks
//! [`Mesh::polygons`], culls back faces, transforms, clips and projects the rest.
//!
//! ## Storage
//! - `vertices: &[Vec3]`: each vertex once (model frame, [`Coord`]).
//! - `indices: &[u16]`: the polygons' vertex numbers, concatenated.
//! - [`PolygonSizes`]: either one size for all polygons (`Uniform(3)` for a triangle mesh) or a
//!   per-polygon `&[u8]` (the course's "number of vertices" column). Polygons have 3 to 255
//!   vertices and may be non-triangular (they should be planar and convex for the fill to draw
//!   what the normal describes).
//!
//! Tables in flash are built at compile time from rows of raw bits by [`vec3s_from_bits`] and
//! [`triangle_indices`] (`zscan mesh` writes such a module from an OBJ, STL or PLY file).
//!
//! [`Mesh::new`] validates everything once (sizes, total count, index range, coordinate range),
//! so later walks cannot fail; they still use checked slicing and never panic.
//!
//! ## Orientation and culling
//! **Front faces are counter-clockwise seen from outside** (SCENES.md; the course uses the
//! opposite convention in its figures, so its tables are reversed here). The outward normal of
//! polygon `P_0 … P_{n−1}` is the fan sum `N = Σ (P_i − P_0) × (P_{i+1} − P_0)`, twice the
//! vector area (exact for any planar polygon, area-weighted by construction). A face is visible
//! from `Ω` when `(Ω − P)·N > 0` for a point `P` of the face (course ch. 1 §4, fig. 1.14;
//! edge-on faces, `= 0`, are culled since they cover no area).
//!
//! ## Numeric contract
//! Vertex coordinates are limited to `|c| ≤ 1024` ([`MAX_MESH_COORD_BITS`] = 2^26 raw), so
//! edge vectors are below 2^27, each cross component below 2^55 and a fan sum over at most 253
//! triangles below 2^63: [`Mesh::face_normal_wide`] is exact in Q32 `i64`. Culling scales `N`
//! down to below 2^29 before the dot product with `Ω − P` (`|Ω − P| < 2^32`), so three products
//! stay below 2^61 each. Vertex normals accumulate in `i32` after a per-mesh shift chosen so
//! that no vertex's sum can overflow (see [`Mesh::vertex_normals`]).

use super::fixed::Coord;
use super::vector::{unit_bits, Vec3};

/// A texture coordinate pair `[u, v]` in Q8.8 (`1.0 = 256`, so `−128 ≤ u, v < 128`: a face
/// may repeat its texture up to 255 times), one per polygon corner ([`Mesh::with_uvs`]).
pub type TexCoord = [i16; 2];

/// One texture repeat (`1.0`) in [`TexCoord`] units.
pub const TEX_ONE: i32 = 256;

/// Largest raw mesh coordinate magnitude: 2^26 (1024.0 in I16F16).
pub const MAX_MESH_COORD_BITS: i32 = 1 << 26;

/// A table a mesh function writes or reads ([`MeshError::OutputTooSmall`],
/// [`LightingError::OutputTooSmall`](crate::lighting::LightingError::OutputTooSmall)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshTable {
    /// Vertex positions (a generator's output).
    Vertices,
    /// Polygon indices (a generator's output).
    Indices,
    /// One normal per polygon ([`Mesh::face_normals`]).
    FaceNormals,
    /// One normal per vertex ([`Mesh::vertex_normals`]).
    VertexNormals,
    /// One intensity level per vertex or per polygon (the lighting functions' output).
    Levels,
    /// The undirected edges ([`Mesh::edges`]).
    Edges,
    /// Texture coordinates, one per index (a generator's output).
    TexCoords,
}

impl core::fmt::Display for MeshTable {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            MeshTable::Vertices => "vertex table",
            MeshTable::Indices => "index table",
            MeshTable::FaceNormals => "face normal table",
            MeshTable::VertexNormals => "vertex normal table",
            MeshTable::Levels => "level table",
            MeshTable::Edges => "edge table",
            MeshTable::TexCoords => "texture coordinate table",
        })
    }
}

/// What is wrong with a mesh or an output buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshError {
    /// A polygon size is below 3.
    BadPolygonSize,
    /// The sizes do not add up to the number of indices.
    IndexCountMismatch,
    /// An index is not below the number of vertices.
    IndexOutOfRange,
    /// A vertex coordinate exceeds ±1024.
    CoordinateOutOfRange,
    /// An output slice is shorter than required.
    OutputTooSmall {
        /// Which output.
        table: MeshTable,
        /// Entries it holds.
        given: usize,
        /// Entries needed.
        needed: usize,
    },
    /// The texture coordinate table ([`Mesh::with_uvs`]) is not one per index.
    UvCountMismatch {
        /// Coordinates given.
        given: usize,
        /// Indices in the mesh.
        needed: usize,
    },
    /// A generator's parameters are invalid (too few segments, radii out of order, …) or
    /// need more than 65 536 vertices.
    BadParameters,
}

/// How many vertices each polygon has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PolygonSizes<'a> {
    /// Every polygon has this many vertices.
    Uniform(u8),
    /// Polygon `i` has `sizes[i]` vertices.
    PerPolygon(&'a [u8]),
}

/// A borrowed polygon mesh (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mesh<'a> {
    vertices: &'a [Vec3],
    indices: &'a [u16],
    sizes: PolygonSizes<'a>,
    polygon_count: usize,
    /// Largest raw coordinate magnitude over all vertices (`≤ MAX_MESH_COORD_BITS`).
    max_coord: u32,
    /// Texture coordinates, one per index (empty: none).
    uvs: &'a [TexCoord],
}

/// Iterator over a mesh's polygons as index slices.
#[derive(Debug, Clone)]
pub struct Polygons<'a> {
    indices: &'a [u16],
    sizes: PolygonSizes<'a>,
    next: usize,
    start: usize,
    count: usize,
}

impl<'a> Iterator for Polygons<'a> {
    type Item = &'a [u16];

    #[inline]
    fn next(&mut self) -> Option<&'a [u16]> {
        if self.next >= self.count {
            return None;
        }
        let n = match self.sizes {
            PolygonSizes::Uniform(n) => n as usize,
            PolygonSizes::PerPolygon(s) => *s.get(self.next)? as usize,
        };
        let poly = self.indices.get(self.start..self.start + n)?;
        self.start += n;
        self.next += 1;
        Some(poly)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let r = self.count - self.next.min(self.count);
        (r, Some(r))
    }
}

/// True when the face with outward normal `normal` through `point` faces the eye at `eye`:
/// `(eye − point)·normal > 0`. Exact in `i64` for any [`Vec3`] inputs whose `normal` is a unit
/// (or at least below 2^16 raw per component); per-frame culling with precomputed
/// [`Mesh::face_normals`].
#[inline]
pub fn faces_eye(normal: Vec3, point: Vec3, eye: Vec3) -> bool {
    let n = normal.bits();
    let p = point.bits();
    let e = eye.bits();
    let d = |i: usize| (e[i] as i64 - p[i] as i64) * (n[i] as i64).clamp(-(1 << 29), 1 << 29);
    d(0) + d(1) + d(2) > 0
}

/// A table of [`Vec3`] from raw I16F16 bits (`Vec3::from_bits` per row), for vertex and
/// normal tables kept in flash: `static VERTICES: [Vec3; N] = vec3s_from_bits(&[[x, y, z], …]);`
/// is built at compile time (what `zscan mesh` writes).
pub const fn vec3s_from_bits<const N: usize>(bits: &[[i32; 3]; N]) -> [Vec3; N] {
    let mut out = [Vec3::ZERO; N];
    let mut i = 0;
    while i < N {
        out[i] = Vec3::from_bits(bits[i][0], bits[i][1], bits[i][2]);
        i += 1;
    }
    out
}

/// The concatenated index table of triangles written one per row: `K` must be
/// `3 × triangles.len()` (else a compile-time error where it is evaluated in a `static`, a
/// panic at run time), so that `static INDICES: [u16; 3 * M] = triangle_indices(&[[a, b, c], …]);`
/// keeps a triangle per row in the source and a flat table in flash.
pub const fn triangle_indices<const K: usize>(triangles: &[[u16; 3]]) -> [u16; K] {
    assert!(
        K == 3 * triangles.len(),
        "triangle_indices: K must be 3 × the triangles"
    );
    let mut out = [0u16; K];
    let mut i = 0;
    while i < K {
        out[i] = triangles[i / 3][i % 3];
        i += 1;
    }
    out
}

impl<'a> Mesh<'a> {
    /// A validated mesh.
    pub const fn new(
        vertices: &'a [Vec3],
        indices: &'a [u16],
        sizes: PolygonSizes<'a>,
    ) -> Result<Mesh<'a>, MeshError> {
        // `const fn` (while loops, no iterators) so that a mesh in flash can be validated at
        // compile time: `const MESH: Mesh = match Mesh::new(..) { Ok(m) => m, .. }`.
        let mut i = 0;
        let mut max_coord = 0u32;
        while i < vertices.len() {
            let b = vertices[i].bits();
            let lim = MAX_MESH_COORD_BITS as u32;
            let mut k = 0;
            while k < 3 {
                let a = b[k].unsigned_abs();
                if a > lim {
                    return Err(MeshError::CoordinateOutOfRange);
                }
                if a > max_coord {
                    max_coord = a;
                }
                k += 1;
            }
            i += 1;
        }
        let polygon_count = match sizes {
            PolygonSizes::Uniform(n) => {
                if n < 3 {
                    return Err(MeshError::BadPolygonSize);
                }
                if indices.len() % n as usize != 0 {
                    return Err(MeshError::IndexCountMismatch);
                }
                indices.len() / n as usize
            }
            PolygonSizes::PerPolygon(s) => {
                let (mut k, mut total) = (0, 0usize);
                while k < s.len() {
                    if s[k] < 3 {
                        return Err(MeshError::BadPolygonSize);
                    }
                    total += s[k] as usize;
                    k += 1;
                }
                if total != indices.len() {
                    return Err(MeshError::IndexCountMismatch);
                }
                s.len()
            }
        };
        let mut j = 0;
        while j < indices.len() {
            if indices[j] as usize >= vertices.len() {
                return Err(MeshError::IndexOutOfRange);
            }
            j += 1;
        }
        Ok(Mesh {
            vertices,
            indices,
            sizes,
            polygon_count,
            max_coord,
            uvs: &[],
        })
    }

    /// The mesh with no vertices and no polygons.
    pub const fn empty() -> Mesh<'static> {
        Mesh {
            vertices: &[],
            indices: &[],
            sizes: PolygonSizes::Uniform(3),
            polygon_count: 0,
            max_coord: 0,
            uvs: &[],
        }
    }

    /// A validated triangle mesh (`indices` in threes).
    pub fn triangles(vertices: &'a [Vec3], indices: &'a [u16]) -> Result<Mesh<'a>, MeshError> {
        Mesh::new(vertices, indices, PolygonSizes::Uniform(3))
    }

    /// The mesh with texture coordinates `uvs`, one per corner of every polygon, parallel to
    /// the index table (`uvs[k]` belongs to the corner `indices[k]`), so that a vertex on a
    /// seam takes different coordinates in different polygons. Any Q8.8 value is in range;
    /// a table of another length than the index table is [`MeshError::UvCountMismatch`].
    pub const fn with_uvs(self, uvs: &'a [TexCoord]) -> Result<Mesh<'a>, MeshError> {
        if uvs.len() != self.indices.len() {
            return Err(MeshError::UvCountMismatch {
                given: uvs.len(),
                needed: self.indices.len(),
            });
        }
        Ok(Mesh { uvs, ..self })
    }

    /// The texture coordinates, one per index (empty when the mesh has none).
    pub fn uvs(&self) -> &'a [TexCoord] {
        self.uvs
    }

    /// The largest raw coordinate magnitude `|c|` over all vertices (0 for an empty mesh;
    /// at most [`MAX_MESH_COORD_BITS`]), found by [`Mesh::new`]: the vertex stage bounds an
    /// object's observer-frame coordinates with it once per frame.
    pub const fn max_coord_bits(&self) -> u32 {
        self.max_coord
    }

    /// The vertex table.
    pub fn vertices(&self) -> &'a [Vec3] {
        self.vertices
    }

    /// The concatenated polygon indices.
    pub fn indices(&self) -> &'a [u16] {
        self.indices
    }

    /// The polygon sizes.
    pub fn sizes(&self) -> PolygonSizes<'a> {
        self.sizes
    }

    /// Number of polygons.
    pub fn polygon_count(&self) -> usize {
        self.polygon_count
    }

    /// The polygons, in table order, as index slices.
    pub fn polygons(&self) -> Polygons<'a> {
        Polygons {
            indices: self.indices,
            sizes: self.sizes,
            next: 0,
            start: 0,
            count: self.polygon_count,
        }
    }

    #[inline]
    fn vertex(&self, i: u16) -> Vec3 {
        self.vertices.get(i as usize).copied().unwrap_or(Vec3::ZERO)
    }

    /// `Σ (P_i − P_0) × (P_{i+1} − P_0)`: the outward normal scaled by twice the area, exact,
    /// raw Q32 (see the module doc for the range).
    pub fn face_normal_wide(&self, polygon: &[u16]) -> [i64; 3] {
        let mut n = [0i64; 3];
        let Some(&first) = polygon.first() else {
            return n;
        };
        let p0 = self.vertex(first);
        for w in polygon.windows(2).skip(1) {
            let a = self.vertex(w[0]).sub(p0);
            let b = self.vertex(w[1]).sub(p0);
            let c = a.cross_wide(b);
            for (acc, ci) in n.iter_mut().zip(c) {
                *acc = acc.saturating_add(ci);
            }
        }
        n
    }

    /// The unit outward normal of `polygon` (I16F16), or `None` if it has no area.
    pub fn face_normal(&self, polygon: &[u16]) -> Option<Vec3> {
        let u = unit_bits(self.face_normal_wide(polygon), 16)?;
        Some(Vec3::from_bits(u[0], u[1], u[2]))
    }

    /// Writes each polygon's unit normal into `out` (zero for degenerate polygons).
    pub fn face_normals(&self, out: &mut [Vec3]) -> Result<(), MeshError> {
        if out.len() < self.polygon_count {
            return Err(MeshError::OutputTooSmall {
                table: MeshTable::FaceNormals,
                given: out.len(),
                needed: self.polygon_count,
            });
        }
        for (o, p) in out.iter_mut().zip(self.polygons()) {
            *o = self.face_normal(p).unwrap_or(Vec3::ZERO);
        }
        Ok(())
    }

    /// Whether the mesh is convex: every vertex lies on or behind the plane of every polygon
    /// of non-zero area (through its first vertex, with its exact outward fan normal
    /// [`face_normal_wide`](Self::face_normal_wide)). Exact: edge vectors `< 2^27`, normals
    /// `< 2^63`, each product `< 2^90` in `i128`. Then no two front faces overlap on screen,
    /// so back-face culling alone draws the mesh right
    /// ([`visibility`](crate::visibility)). `O(polygons × vertices)`: compute it once (a
    /// 1,839-vertex, 3,674-triangle mesh takes 6.8 M point–plane tests) and keep it with the
    /// mesh. A non-planar polygon's own vertices may lie off its fan plane, which makes the
    /// answer `false` (conservative).
    pub fn is_convex(&self) -> bool {
        self.polygons().all(|poly| {
            let n = self.face_normal_wide(poly);
            if n == [0; 3] {
                return true;
            }
            let p0 = poly.first().map_or(Vec3::ZERO, |&i| self.vertex(i)).bits();
            self.vertices.iter().all(|v| {
                let v = v.bits();
                let side: i128 = (0..3)
                    .map(|k| (v[k] as i64 - p0[k] as i64) as i128 * n[k] as i128)
                    .sum();
                side <= 0
            })
        })
    }

    /// True when `polygon` faces `eye` (given in the mesh's own frame): `(Ω − P_0)·N > 0`,
    /// with the exact normal.
    pub fn is_front_facing(&self, polygon: &[u16], eye: Vec3) -> bool {
        let Some(&first) = polygon.first() else {
            return false;
        };
        let n = self.face_normal_wide(polygon);
        let max = n.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
        let shift = (64 - max.leading_zeros()).saturating_sub(29);
        let p = self.vertex(first).bits();
        let e = eye.bits();
        let mut s = 0i64;
        for i in 0..3 {
            s += (e[i] as i64 - p[i] as i64) * (n[i] >> shift);
        }
        s > 0
    }

    /// Vertex normals: for each vertex, the sum of the (area-weighted, un-normalised) normals
    /// of the polygons using it, normalised (SCENES.md's smooth normals); zero for unused
    /// vertices or sums that cancel. `out` needs at least one slot per vertex.
    ///
    /// No scratch memory: `out` first counts each vertex's valence `v`, then holds the sums of
    /// the face normals shifted right by the smallest `k` for which `v_max·(N_max/2^k + 1)` is
    /// below 2^31 (no sum can overflow), then the normalised results.
    pub fn vertex_normals(&self, out: &mut [Vec3]) -> Result<(), MeshError> {
        let (given, nv) = (out.len(), self.vertices.len());
        let out = out.get_mut(..nv).ok_or(MeshError::OutputTooSmall {
            table: MeshTable::VertexNormals,
            given,
            needed: nv,
        })?;
        out.fill(Vec3::ZERO);
        let mut nmax = 0u64;
        for poly in self.polygons() {
            let n = self.face_normal_wide(poly);
            nmax = nmax.max(n.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0));
            for &i in poly {
                if let Some(o) = out.get_mut(i as usize) {
                    o.x = Coord::from_bits(o.x.to_bits().saturating_add(1));
                }
            }
        }
        let vmax = out
            .iter()
            .map(|o| o.x.to_bits() as u64)
            .max()
            .unwrap_or(0)
            .max(1);
        let mut k = 0u32;
        while k < 63 && ((nmax >> k) + 1).saturating_mul(vmax) >= 1 << 31 {
            k += 1;
        }
        out.fill(Vec3::ZERO);
        for poly in self.polygons() {
            let n = self.face_normal_wide(poly).map(|c| (c >> k) as i32);
            for &i in poly {
                if let Some(o) = out.get_mut(i as usize) {
                    let b = o.bits();
                    *o = Vec3::from_bits(
                        b[0].saturating_add(n[0]),
                        b[1].saturating_add(n[1]),
                        b[2].saturating_add(n[2]),
                    );
                }
            }
        }
        for o in out.iter_mut() {
            let b = o.bits();
            *o = unit_bits([b[0] as i64, b[1] as i64, b[2] as i64], 16)
                .map(|u| Vec3::from_bits(u[0], u[1], u[2]))
                .unwrap_or(Vec3::ZERO);
        }
        Ok(())
    }
}

impl Mesh<'_> {
    /// The mesh's undirected edges, each once (`[a, b]` with `a < b`, sorted), into `out`:
    /// returns how many. `out` must hold one entry per polygon corner (the mesh's index
    /// count) while they are sorted; the edges take its first entries.
    ///
    /// Errors: [`MeshError::OutputTooSmall`] when `out` is shorter than the index count.
    pub fn edges(&self, out: &mut [[u16; 2]]) -> Result<usize, MeshError> {
        let (needed, given) = (self.indices().len(), out.len());
        let table = out.get_mut(..needed).ok_or(MeshError::OutputTooSmall {
            table: MeshTable::Edges,
            given,
            needed,
        })?;
        let mut k = 0;
        for poly in self.polygons() {
            for (c, &i) in poly.iter().enumerate() {
                let j = poly[(c + 1) % poly.len()];
                table[k] = [i.min(j), i.max(j)];
                k += 1;
            }
        }
        table.sort_unstable();
        // Keep the first of each run of equal edges (and no degenerate [i, i]).
        let mut kept = 0;
        for r in 0..needed {
            let e = table[r];
            if e[0] != e[1] && (kept == 0 || table[kept - 1] != e) {
                table[kept] = e;
                kept += 1;
            }
        }
        Ok(kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(Coord::from_num(x), Coord::from_num(y), Coord::from_num(z))
    }

    /// Tables built at compile time from rows of raw bits are the tables written by hand.
    #[test]
    fn const_tables_from_rows() {
        static V: [Vec3; 3] = vec3s_from_bits(&[[0, 0, 0], [1 << 16, 0, -5], [0, 1 << 16, 7]]);
        static I: [u16; 6] = triangle_indices(&[[0, 1, 2], [2, 1, 0]]);
        static M: Mesh<'static> = match Mesh::new(&V, &I, PolygonSizes::Uniform(3)) {
            Ok(m) => m,
            Err(_) => panic!("a valid mesh"),
        };
        assert_eq!(V[1], Vec3::from_bits(1 << 16, 0, -5));
        assert_eq!(V[2].bits(), [0, 1 << 16, 7]);
        assert_eq!(I, [0, 1, 2, 2, 1, 0]);
        assert_eq!(M.polygon_count(), 2);
    }

    /// A length that is not three indices per triangle is refused (at compile time in a
    /// `static`; here, evaluated at run time, a panic naming the rule).
    #[test]
    #[should_panic(expected = "K must be 3")]
    fn triangle_indices_checks_its_length() {
        let rows = [[0u16, 1, 2]];
        let _: [u16; 4] = triangle_indices(&rows);
    }

    #[test]
    fn validation() {
        let vs = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(1.0, 1.0, 0.0),
        ];
        assert!(Mesh::triangles(&vs, &[0, 1, 2]).is_ok());
        assert_eq!(
            Mesh::triangles(&vs, &[0, 1, 2]).unwrap().max_coord_bits(),
            1 << 16
        );
        let neg = [v(0.5, -3.25, 2.0)];
        assert_eq!(
            Mesh::triangles(&neg, &[]).unwrap().max_coord_bits(),
            13 << 14
        );
        assert_eq!(Mesh::empty().max_coord_bits(), 0);
        assert_eq!(
            Mesh::triangles(&vs, &[0, 1, 4]),
            Err(MeshError::IndexOutOfRange)
        );
        assert_eq!(
            Mesh::triangles(&vs, &[0, 1]),
            Err(MeshError::IndexCountMismatch)
        );
        assert_eq!(
            Mesh::new(&vs, &[0, 1], PolygonSizes::Uniform(2)),
            Err(MeshError::BadPolygonSize)
        );
        let sizes = [3u8, 4];
        let m = Mesh::new(
            &vs,
            &[0, 1, 2, 0, 1, 3, 2],
            PolygonSizes::PerPolygon(&sizes),
        )
        .unwrap();
        let polys: heapless::Vec<&[u16], 4> = m.polygons().collect();
        assert_eq!(polys.as_slice(), &[&[0u16, 1, 2][..], &[0, 1, 3, 2][..]]);
        let far = [Vec3::from_int(2000, 0, 0)];
        assert_eq!(
            Mesh::triangles(&far, &[]),
            Err(MeshError::CoordinateOutOfRange)
        );
    }

    #[test]
    fn normals_and_culling() {
        // CCW seen from +z: normal +z.
        let vs = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(1.0, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
        ];
        let m = Mesh::new(&vs, &[0, 1, 2, 3], PolygonSizes::Uniform(4)).unwrap();
        let poly = m.polygons().next().unwrap();
        assert_eq!(m.face_normal_wide(poly), [0, 0, 2 << 32]);
        assert_eq!(m.face_normal(poly), Some(v(0.0, 0.0, 1.0)));
        assert!(m.is_front_facing(poly, v(0.3, 0.3, 5.0)));
        assert!(!m.is_front_facing(poly, v(0.3, 0.3, -5.0)));
        assert!(!m.is_front_facing(poly, v(5.0, 0.3, 0.0)));
        assert!(faces_eye(v(0.0, 0.0, 1.0), vs[0], v(100.0, -3.0, 0.001)));
        let mut vn = [Vec3::ZERO; 4];
        m.vertex_normals(&mut vn).unwrap();
        assert!(vn.iter().all(|n| *n == v(0.0, 0.0, 1.0)));
        assert_eq!(
            m.vertex_normals(&mut vn[..3]),
            Err(MeshError::OutputTooSmall {
                table: MeshTable::VertexNormals,
                given: 3,
                needed: 4
            })
        );
    }
}
