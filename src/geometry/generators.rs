//! Mesh generators: the course's unit cube (a static table), UV spheres, the hollow prism of
//! course exercise 4 and tori, written into caller-provided slices.
//!
//! Role in the pipeline: set-up (or build time). Every generator fills `vertices` and
//! `indices` slices the caller owns and returns a [`Mesh`] borrowing them, or
//! [`MeshError::OutputTooSmall`] / [`MeshError::BadParameters`]; a `*_sizes` function gives the
//! exact lengths to allocate. Nothing allocates, nothing panics.
//!
//! ## Conventions
//! Outward faces are counter-clockwise seen from outside ([`mesh`](super::mesh)). Angles come
//! from [`trig`](super::trig) (≤ 1 unit of 2^-30), positions are rounded to I16F16. Sizes must
//! keep the result inside the mesh range (`|coordinate| ≤ 1024`).
//!
//! - **UV sphere** (SCENES.md's exact convention): poles on `y`; vertex 0 is the north pole
//!   `(0, R, 0)`, then `rings − 1` rings of `segments` vertices from north to south, then the
//!   south pole. Ring `k` is at polar angle `θ = π·k/rings`, segment `j` at azimuth
//!   `φ = 2π·j/segments` from `+x`, turning toward `−z` (a positive rotation about `+y`):
//!   `(R sin θ cos φ, R cos θ, −R sin θ sin φ)`. Triangles: the north cap
//!   `(N, (1, j), (1, j+1))`; each band quad split along `(k, j)–(k+1, j+1)` into
//!   `((k, j), (k+1, j), (k+1, j+1))` and `((k, j), (k+1, j+1), (k, j+1))`; the south cap
//!   `((last, j), S, (last, j+1))`. 32 × 16 gives 482 vertices and 960 triangles.
//! - **Hollow prism** (course exercise 4, with `sides = 6` the hollow hexagonal cylinder):
//!   axis `z`, `z ∈ [−h, h]`, outer and inner circumradii; vertices `j`, `n + j`, `2n + j`,
//!   `3n + j` are the outer bottom, outer top, inner bottom, inner top corners at azimuth
//!   `2π·j/n` from `+x` toward `+y`; `4n` quads: outer sides, inner sides (facing the axis), top
//!   and bottom rings.
//! - **Torus**: axis `y`, major radius `R` (tube centre), minor radius `r`; vertex
//!   `(i, j)` = `i·sides + j` at azimuth `φ_i = 2π·i/rings` (toward `−z`, as the sphere) and tube
//!   angle `θ_j = 2π·j/sides`: `((R + r cos θ) cos φ, r sin θ, −(R + r cos θ) sin φ)`; quads.
//!
//! ## Texture coordinates
//! Each generator has its natural per-corner coordinates (Q8.8, parallel to its index table,
//! so seams take both values): the cube maps each face once, `(0, 0), (1, 0), (1, 1), (0, 1)`
//! counter-clockwise seen from outside, from the lower-left corner on the four side faces
//! ([`UNIT_CUBE_UVS`], in [`unit_cube`]); the sphere `u = j / segments` (the closing
//! meridian `1`), `v = k / rings` (0 at the north pole), a pole corner the mean `u` of its
//! triangle's two others ([`uv_sphere_uvs`]); the torus `u = i / rings`, `v = j / sides`
//! ([`torus_uvs`]); the prism `u = j / sides` around it and `v` across each face
//! ([`hollow_prism_uvs`]). Fractions are rounded to nearest.

use super::fixed::{saturate_i32, shr_round, Coord};
use super::mesh::{Mesh, MeshError, MeshTable, PolygonSizes, TexCoord, TEX_ONE};
use super::trig::{sin_cos_bits, BinaryAngle};
use super::vector::Vec3;

/// The course's unit cube `[0, 1]³` (ch. 1, example 2): vertex `i` has coordinates given by
/// the bits of `i` (`x` = bit 0, `y` = bit 1, `z` = bit 2).
pub static UNIT_CUBE_VERTICES: [Vec3; 8] = [
    Vec3::from_int(0, 0, 0),
    Vec3::from_int(1, 0, 0),
    Vec3::from_int(0, 1, 0),
    Vec3::from_int(1, 1, 0),
    Vec3::from_int(0, 0, 1),
    Vec3::from_int(1, 0, 1),
    Vec3::from_int(0, 1, 1),
    Vec3::from_int(1, 1, 1),
];

/// The unit cube's six quads, counter-clockwise seen from outside (the course's table with
/// each polygon's order reversed): `z = 0`, `z = 1`, `y = 0`, `y = 1`, `x = 0`, `x = 1`.
pub static UNIT_CUBE_INDICES: [u16; 24] = [
    0, 2, 3, 1, //
    4, 5, 7, 6, //
    0, 1, 5, 4, //
    2, 6, 7, 3, //
    0, 4, 6, 2, //
    1, 3, 7, 5, //
];

/// The unit cube's texture coordinates, one per corner of [`UNIT_CUBE_INDICES`]: each face
/// shows the whole texture once, `(0, 0), (1, 0), (1, 1), (0, 1)` counter-clockwise seen from
/// outside; on the side faces (`z = 0`, `z = 1`, `x = 0`, `x = 1`) `(0, 0)` is the lower-left
/// corner seen from outside (`y` up) and `v` runs up.
pub static UNIT_CUBE_UVS: [TexCoord; 24] = {
    const O: i16 = 0;
    const I: i16 = TEX_ONE as i16;
    [
        [I, O],
        [I, I],
        [O, I],
        [O, O], // z = 0: vertex 1 is its lower left
        [O, O],
        [I, O],
        [I, I],
        [O, I], // z = 1
        [O, O],
        [I, O],
        [I, I],
        [O, I], // y = 0
        [O, O],
        [I, O],
        [I, I],
        [O, I], // y = 1
        [O, O],
        [I, O],
        [I, I],
        [O, I], // x = 0
        [I, O],
        [I, I],
        [O, I],
        [O, O], // x = 1: vertex 5 is its lower left
    ]
};

/// The unit cube as a mesh living in static memory, with its texture coordinates
/// ([`UNIT_CUBE_UVS`]).
pub fn unit_cube() -> Mesh<'static> {
    // The tables are valid, so the fallback is never taken.
    Mesh::new(
        &UNIT_CUBE_VERTICES,
        &UNIT_CUBE_INDICES,
        PolygonSizes::Uniform(4),
    )
    .and_then(|m| m.with_uvs(&UNIT_CUBE_UVS))
    .unwrap_or_else(|_| Mesh::empty())
}

/// `TEX_ONE · num / den` rounded to nearest (`num ≤ 2·den`): a Q8.8 fraction.
fn frac(num: usize, den: usize) -> i16 {
    ((2 * TEX_ONE as usize * num + den) / (2 * den)) as i16
}

/// Writes `corners` (Q8.8 fractions `[u_num, v_num]` over `den`) into `out`, after checking
/// that it holds `need` pairs.
fn write_uvs(
    out: &mut [TexCoord],
    need: usize,
    den: [usize; 2],
    corners: impl Iterator<Item = [usize; 2]>,
) -> Result<(), MeshError> {
    if out.len() < need {
        return Err(MeshError::OutputTooSmall {
            table: MeshTable::TexCoords,
            given: out.len(),
            needed: need,
        });
    }
    for (slot, [u, v]) in out.iter_mut().zip(corners) {
        *slot = [frac(u, den[0]), frac(v, den[1])];
    }
    Ok(())
}

/// `r·cos a`, `r·sin a` in raw I16F16 (`r` raw, `|r| ≤ 2^32`), saturating.
fn polar(r: i64, a: BinaryAngle) -> (i32, i32) {
    let (s, c) = sin_cos_bits(a);
    let f = |t: i32| saturate_i32(shr_round(r * t as i64, 30)); // |r·t| ≤ 2^62
    (f(c), f(s))
}

fn check_out(vertices: &[Vec3], indices: &[u16], need: (usize, usize)) -> Result<(), MeshError> {
    if need.0 > MAX_GENERATED_VERTICES {
        return Err(MeshError::BadParameters);
    }
    for (table, given, needed) in [
        (MeshTable::Vertices, vertices.len(), need.0),
        (MeshTable::Indices, indices.len(), need.1),
    ] {
        if given < needed {
            return Err(MeshError::OutputTooSmall {
                table,
                given,
                needed,
            });
        }
    }
    Ok(())
}

/// The filled prefixes of the output slices, as shared borrows for the returned mesh.
fn finished<'a>(
    vertices: &'a mut [Vec3],
    indices: &'a mut [u16],
    need: (usize, usize),
) -> Result<(&'a [Vec3], &'a [u16]), MeshError> {
    check_out(vertices, indices, need)?;
    Ok((&vertices[..need.0], &indices[..need.1]))
}

/// Most vertices a generated mesh may have: 65 536 (its indices are `u16`).
pub const MAX_GENERATED_VERTICES: usize = 65_536;

/// `(vertices, indices)` needed by [`uv_sphere`]: `2 + (rings − 1)·segments` and
/// `6·segments·(rings − 1)` (saturating at `usize::MAX` on targets where they do not fit; see
/// [`uv_sphere_sizes_checked`] to validate parameters before allocating).
pub const fn uv_sphere_sizes(segments: u16, rings: u16) -> (usize, usize) {
    let (s, r) = (segments as usize, rings as usize);
    if r < 1 {
        return (2, 0);
    }
    let ring_vertices = (r - 1).saturating_mul(s);
    (
        ring_vertices.saturating_add(2),
        ring_vertices.saturating_mul(6),
    )
}

/// [`uv_sphere_sizes`] when [`uv_sphere`] accepts the counts: `segments ≥ 3`, `rings ≥ 2` and
/// at most [`MAX_GENERATED_VERTICES`] vertices (`2 + (rings − 1)·segments ≤ 65 536`, so at
/// most `6·65 534` indices); [`MeshError::BadParameters`] otherwise. Call it before
/// allocating the output slices: it never allocates or overflows.
pub const fn uv_sphere_sizes_checked(
    segments: u16,
    rings: u16,
) -> Result<(usize, usize), MeshError> {
    // (rings − 1)·segments < 2^32: computed in u64 on every target.
    if segments < 3
        || rings < 2
        || 2 + (rings as u64 - 1) * segments as u64 > MAX_GENERATED_VERTICES as u64
    {
        return Err(MeshError::BadParameters);
    }
    Ok(uv_sphere_sizes(segments, rings))
}

/// A UV sphere of `radius` centred at the origin (SCENES.md's convention, module doc);
/// `segments ≥ 3`, `rings ≥ 2`.
pub fn uv_sphere<'a>(
    segments: u16,
    rings: u16,
    radius: Coord,
    vertices: &'a mut [Vec3],
    indices: &'a mut [u16],
) -> Result<Mesh<'a>, MeshError> {
    if segments < 3 || rings < 2 || radius.to_bits() < 0 {
        return Err(MeshError::BadParameters);
    }
    let need = uv_sphere_sizes(segments, rings);
    check_out(vertices, indices, need)?;
    sphere_points(segments, rings, radius.to_bits() as i64, vertices);
    let (ns, nr) = (segments as usize, rings as usize);
    let south = (need.0 - 1) as u16;
    let at = |k: usize, j: usize| (1 + (k - 1) * ns + j % ns) as u16;
    let mut ii = 0usize;
    let mut tri = |a: u16, b: u16, c: u16| {
        for x in [a, b, c] {
            if let Some(slot) = indices.get_mut(ii) {
                *slot = x;
            }
            ii += 1;
        }
    };
    for j in 0..ns {
        tri(0, at(1, j), at(1, j + 1));
    }
    for k in 1..nr - 1 {
        for j in 0..ns {
            tri(at(k, j), at(k + 1, j), at(k + 1, j + 1));
            tri(at(k, j), at(k + 1, j + 1), at(k, j + 1));
        }
    }
    for j in 0..ns {
        tri(at(nr - 1, j), south, at(nr - 1, j + 1));
    }
    let (vs, is) = finished(vertices, indices, need)?;
    Mesh::triangles(vs, is)
}

/// The texture coordinates of [`uv_sphere`]`(segments, rings, …)`, one per index in its
/// triangle order (module doc): `u = j / segments`, `v = k / rings`, a pole corner the mean
/// `u` of its triangle's two others. `out` needs [`uv_sphere_sizes`]`(…).1` pairs.
pub fn uv_sphere_uvs(segments: u16, rings: u16, out: &mut [TexCoord]) -> Result<(), MeshError> {
    if segments < 3 || rings < 2 {
        return Err(MeshError::BadParameters);
    }
    let need = uv_sphere_sizes_checked(segments, rings)?;
    let (ns, nr) = (segments as usize, rings as usize);
    // Fractions over 2·segments for u (the poles' half steps), over rings for v.
    let at = |k: usize, j: usize| [2 * j, k];
    let north = (0..ns).flat_map(move |j| [[2 * j + 1, 0], at(1, j), at(1, j + 1)]);
    let bands = (1..nr - 1).flat_map(move |k| {
        (0..ns).flat_map(move |j| {
            [
                at(k, j),
                at(k + 1, j),
                at(k + 1, j + 1),
                at(k, j),
                at(k + 1, j + 1),
                at(k, j + 1),
            ]
        })
    });
    let south = (0..ns).flat_map(move |j| [at(nr - 1, j), [2 * j + 1, nr], at(nr - 1, j + 1)]);
    write_uvs(out, need.1, [2 * ns, nr], north.chain(bands).chain(south))
}

/// The analytic vertex normals of [`uv_sphere`]`(segments, rings, …)`: the unit vectors from
/// the centre through each vertex (the course's ch. 4 §2.5: where the surface is known, its
/// own normal rather than the average of the faces' normals), in the generator's vertex
/// order, to I16F16 like the positions (each within 2 units of 2^-16 of the exact unit
/// vector). `out` needs [`uv_sphere_sizes`]`(segments, rings).0` slots; the same parameter
/// errors as the generator.
pub fn uv_sphere_normals(segments: u16, rings: u16, out: &mut [Vec3]) -> Result<(), MeshError> {
    uv_sphere_sizes_checked(segments, rings)?;
    let need = uv_sphere_sizes(segments, rings).0;
    let given = out.len();
    let out = out.get_mut(..need).ok_or(MeshError::OutputTooSmall {
        table: MeshTable::VertexNormals,
        given,
        needed: need,
    })?;
    sphere_points(segments, rings, Coord::ONE.to_bits() as i64, out);
    Ok(())
}

/// Writes the UV sphere's vertices of radius `r` (bits of I16F16) into `out` in the module
/// doc's order (slots past `out`'s end are skipped: callers check the length first).
fn sphere_points(segments: u16, rings: u16, r: i64, out: &mut [Vec3]) {
    let (ns, nr) = (segments as usize, rings as usize);
    let mut vi = 0usize;
    let mut put = |v: Vec3| {
        if let Some(slot) = out.get_mut(vi) {
            *slot = v;
        }
        vi += 1;
    };
    put(Vec3::from_bits(0, r as i32, 0));
    for k in 1..nr {
        // y = R cos θ, radial = R sin θ
        let (y, radial) = polar(r, BinaryAngle::from_turns(k as i64, 2 * rings as u32));
        for j in 0..ns {
            let (x, mz) = polar(
                radial as i64,
                BinaryAngle::from_turns(j as i64, segments as u32),
            );
            put(Vec3::from_bits(x, y, mz.saturating_neg()));
        }
    }
    put(Vec3::from_bits(0, -(r as i32), 0));
}

/// `(vertices, indices)` needed by [`hollow_prism`]: `4·sides` and `16·sides` (4n quads).
pub const fn hollow_prism_sizes(sides: u16) -> (usize, usize) {
    (4 * sides as usize, 16 * sides as usize)
}

/// [`hollow_prism_sizes`] when [`hollow_prism`] accepts the count: `3 ≤ sides ≤ 16 384`
/// (`4·sides ≤` [`MAX_GENERATED_VERTICES`]); [`MeshError::BadParameters`] otherwise.
pub const fn hollow_prism_sizes_checked(sides: u16) -> Result<(usize, usize), MeshError> {
    if sides < 3 || 4 * sides as usize > MAX_GENERATED_VERTICES {
        return Err(MeshError::BadParameters);
    }
    Ok(hollow_prism_sizes(sides))
}

/// Course exercise 4: a hollow prism with `sides` sides (6: the hollow hexagonal cylinder)
/// about the `z` axis, `z ∈ [−half_height, half_height]`, circumradii `outer > inner > 0`.
/// The course's instance is `(6, 1, 0.8, 1)`.
pub fn hollow_prism<'a>(
    sides: u16,
    outer: Coord,
    inner: Coord,
    half_height: Coord,
    vertices: &'a mut [Vec3],
    indices: &'a mut [u16],
) -> Result<Mesh<'a>, MeshError> {
    if sides < 3 || inner <= Coord::ZERO || outer <= inner || half_height <= Coord::ZERO {
        return Err(MeshError::BadParameters);
    }
    let need = hollow_prism_sizes(sides);
    check_out(vertices, indices, need)?;
    let n = sides as usize;
    let h = half_height.to_bits();
    for j in 0..n {
        let a = BinaryAngle::from_turns(j as i64, sides as u32);
        let (ox, oy) = polar(outer.to_bits() as i64, a);
        let (ix, iy) = polar(inner.to_bits() as i64, a);
        for (slot, v) in [
            (j, Vec3::from_bits(ox, oy, -h)),
            (n + j, Vec3::from_bits(ox, oy, h)),
            (2 * n + j, Vec3::from_bits(ix, iy, -h)),
            (3 * n + j, Vec3::from_bits(ix, iy, h)),
        ] {
            if let Some(s) = vertices.get_mut(slot) {
                *s = v;
            }
        }
    }
    let mut ii = 0;
    for j in 0..n {
        let j1 = (j + 1) % n;
        let (ob, ot, ib, it) = (0, n, 2 * n, 3 * n);
        for q in [
            [ob + j, ob + j1, ot + j1, ot + j], // outer side, facing away from the axis
            [ib + j, it + j, it + j1, ib + j1], // inner side, facing the axis
            [ot + j, ot + j1, it + j1, it + j], // top ring, +z
            [ob + j, ib + j, ib + j1, ob + j1], // bottom ring, −z
        ] {
            for x in q {
                if let Some(s) = indices.get_mut(ii) {
                    *s = x as u16;
                }
                ii += 1;
            }
        }
    }
    let (vs, is) = finished(vertices, indices, need)?;
    Mesh::new(vs, is, PolygonSizes::Uniform(4))
}

/// The texture coordinates of [`hollow_prism`]`(sides, …)`, one per index: `u = j / sides`
/// around the prism; `v` from 0 to 1 across each face (from the top edge down on the sides,
/// from the outer edge inward on the rings). `out` needs [`hollow_prism_sizes`]`(sides).1`
/// pairs.
pub fn hollow_prism_uvs(sides: u16, out: &mut [TexCoord]) -> Result<(), MeshError> {
    let need = hollow_prism_sizes_checked(sides)?;
    let corners = (0..sides as usize).flat_map(|j| {
        let j1 = j + 1;
        [
            [j, 1],
            [j1, 1],
            [j1, 0],
            [j, 0], // outer side
            [j, 1],
            [j, 0],
            [j1, 0],
            [j1, 1], // inner side
            [j, 0],
            [j1, 0],
            [j1, 1],
            [j, 1], // top ring
            [j, 0],
            [j, 1],
            [j1, 1],
            [j1, 0], // bottom ring
        ]
    });
    write_uvs(out, need.1, [sides as usize, 1], corners)
}

/// `(vertices, indices)` needed by [`torus`]: `rings·sides` and `4·rings·sides` (saturating
/// at `usize::MAX` where they do not fit; see [`torus_sizes_checked`]).
pub const fn torus_sizes(rings: u16, sides: u16) -> (usize, usize) {
    let n = (rings as usize).saturating_mul(sides as usize);
    (n, n.saturating_mul(4))
}

/// [`torus_sizes`] when [`torus`] accepts the counts: `rings, sides ≥ 3` and
/// `rings·sides ≤` [`MAX_GENERATED_VERTICES`]; [`MeshError::BadParameters`] otherwise. Call
/// it before allocating the output slices.
pub const fn torus_sizes_checked(rings: u16, sides: u16) -> Result<(usize, usize), MeshError> {
    if rings < 3 || sides < 3 || rings as u64 * sides as u64 > MAX_GENERATED_VERTICES as u64 {
        return Err(MeshError::BadParameters);
    }
    Ok(torus_sizes(rings, sides))
}

/// A torus about the `y` axis (module doc): `rings ≥ 3` around the axis, `sides ≥ 3` around
/// the tube, `major > minor > 0`.
pub fn torus<'a>(
    rings: u16,
    sides: u16,
    major: Coord,
    minor: Coord,
    vertices: &'a mut [Vec3],
    indices: &'a mut [u16],
) -> Result<Mesh<'a>, MeshError> {
    if rings < 3 || sides < 3 || minor <= Coord::ZERO || major <= minor {
        return Err(MeshError::BadParameters);
    }
    let need = torus_sizes(rings, sides);
    check_out(vertices, indices, need)?;
    let (nr, ns) = (rings as usize, sides as usize);
    torus_points(
        rings,
        sides,
        major.to_bits() as i64,
        minor.to_bits() as i64,
        vertices,
    );
    let mut ii = 0;
    for i in 0..nr {
        for j in 0..ns {
            let (i1, j1) = ((i + 1) % nr, (j + 1) % ns);
            for x in [i * ns + j, i1 * ns + j, i1 * ns + j1, i * ns + j1] {
                if let Some(s) = indices.get_mut(ii) {
                    *s = x as u16;
                }
                ii += 1;
            }
        }
    }
    let (vs, is) = finished(vertices, indices, need)?;
    Mesh::new(vs, is, PolygonSizes::Uniform(4))
}

/// The texture coordinates of [`torus`]`(rings, sides, …)`, one per index: `u = i / rings`
/// around the axis, `v = j / sides` around the tube (the closing ring and side take 1).
/// `out` needs [`torus_sizes`]`(rings, sides).1` pairs.
pub fn torus_uvs(rings: u16, sides: u16, out: &mut [TexCoord]) -> Result<(), MeshError> {
    let need = torus_sizes_checked(rings, sides)?;
    let (nr, ns) = (rings as usize, sides as usize);
    let corners = (0..nr).flat_map(move |i| {
        (0..ns).flat_map(move |j| [[i, j], [i + 1, j], [i + 1, j + 1], [i, j + 1]])
    });
    write_uvs(out, need.1, [nr, ns], corners)
}

/// The analytic vertex normals of [`torus`]`(rings, sides, …)`: at the vertex of azimuth `φ`
/// and tube angle `θ`, the unit vector `(cos θ cos φ, sin θ, −cos θ sin φ)` from the tube's
/// centre line through the vertex (course ch. 4 §2.5), whatever the radii; I16F16, in the
/// generator's vertex order. `out` needs [`torus_sizes`]`(rings, sides).0` slots.
pub fn torus_normals(rings: u16, sides: u16, out: &mut [Vec3]) -> Result<(), MeshError> {
    torus_sizes_checked(rings, sides)?;
    let need = torus_sizes(rings, sides).0;
    let given = out.len();
    let out = out.get_mut(..need).ok_or(MeshError::OutputTooSmall {
        table: MeshTable::VertexNormals,
        given,
        needed: need,
    })?;
    // The torus of major radius 0 and minor radius 1 is the unit normal at each vertex.
    torus_points(rings, sides, 0, Coord::ONE.to_bits() as i64, out);
    Ok(())
}

/// Writes the torus's vertices (radii in bits of I16F16) into `out` in the module doc's order
/// (slots past `out`'s end are skipped: callers check the length first).
fn torus_points(rings: u16, sides: u16, major: i64, minor: i64, out: &mut [Vec3]) {
    let (nr, ns) = (rings as usize, sides as usize);
    for i in 0..nr {
        let phi = BinaryAngle::from_turns(i as i64, rings as u32);
        for j in 0..ns {
            let (rc, y) = polar(minor, BinaryAngle::from_turns(j as i64, sides as u32));
            let (x, mz) = polar(major + rc as i64, phi);
            if let Some(s) = out.get_mut(i * ns + j) {
                *s = Vec3::from_bits(x, y, mz.saturating_neg());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// Twice the signed area of a polygon's texture coordinates (u right, v up).
    fn uv_area(uvs: &[TexCoord]) -> i64 {
        let n = uvs.len();
        (0..n)
            .map(|k| {
                let (a, b) = (uvs[k], uvs[(k + 1) % n]);
                a[0] as i64 * b[1] as i64 - b[0] as i64 * a[1] as i64
            })
            .sum()
    }

    /// Each cube face shows the texture once, counter-clockwise as its corners (whose order is
    /// counter-clockwise from outside), and on the four side faces `(0, 0)` is a bottom corner
    /// (`y = 0`) and `v` runs up (`v = y`).
    #[test]
    fn cube_faces_map_the_texture_once() {
        let m = unit_cube();
        assert_eq!(m.uvs().len(), 24);
        for (f, (poly, uvs)) in m.polygons().zip(m.uvs().chunks(4)).enumerate() {
            assert_eq!(uv_area(uvs), 2 * 256 * 256, "face {f}");
            let side = !(2..4).contains(&f);
            for (&i, uv) in poly.iter().zip(uvs) {
                let y = (i >> 1 & 1) as i16 * 256;
                if side {
                    assert_eq!(uv[1], y, "face {f} vertex {i}");
                }
            }
        }
    }

    /// The sphere's seam and poles: the north cap's first and last triangles, a band's
    /// closing pair and the south cap's last triangle, typed in from the convention.
    #[test]
    fn sphere_uvs_close_the_ring_and_average_at_the_poles() {
        let (_, ni) = uv_sphere_sizes(32, 16);
        let mut uvs = [[0i16; 2]; 2880];
        assert_eq!(ni, 2880);
        uv_sphere_uvs(32, 16, &mut uvs).unwrap();
        assert_eq!(uvs[0..3], [[4, 0], [0, 16], [8, 16]]);
        assert_eq!(uvs[93..96], [[252, 0], [248, 16], [256, 16]]);
        // Band k = 1, segment 31: (1, 31), (2, 31), (2, 32) and (1, 31), (2, 32), (1, 32).
        let at = 96 + 6 * 31;
        assert_eq!(
            uvs[at..at + 6],
            [
                [248, 16],
                [248, 32],
                [256, 32],
                [248, 16],
                [256, 32],
                [256, 16]
            ]
        );
        assert_eq!(uvs[2877..2880], [[248, 240], [252, 256], [256, 240]]);
        let mut short = [[0i16; 2]; 2879];
        assert!(matches!(
            uv_sphere_uvs(32, 16, &mut short),
            Err(MeshError::OutputTooSmall {
                table: MeshTable::TexCoords,
                given: 2879,
                needed: 2880
            })
        ));
    }

    /// The torus and the prism: every face one whole cell of its grid (the torus's
    /// `(1/rings) × (1/sides)`, the prism's `(1/sides) × 1`, rounded to Q8.8).
    #[test]
    fn torus_and_prism_uvs_tile_their_grids() {
        let mut t = [[0i16; 2]; 4 * 8 * 4];
        torus_uvs(8, 4, &mut t).unwrap();
        for cell in t.chunks(4) {
            assert_eq!(uv_area(cell).abs(), 2 * 32 * 64, "{cell:?}");
        }
        assert_eq!(
            t[4 * 4 * 7 + 4 * 3..][..4],
            [[224, 192], [256, 192], [256, 256], [224, 256]]
        );
        let mut p = [[0i16; 2]; 16 * 6];
        hollow_prism_uvs(6, &mut p).unwrap();
        for q in p.chunks(4) {
            let u = q.iter().map(|c| c[0] as i64);
            let width = u.clone().max().unwrap() - u.min().unwrap();
            assert!(width == 42 || width == 43, "{q:?}");
            assert_eq!(uv_area(q).abs(), 2 * width * 256, "{q:?}");
        }
        assert!(hollow_prism_uvs(2, &mut p).is_err());
    }

    /// Every face's normal points away from the given "inside" reference.
    fn outward(m: &Mesh, inside: impl Fn(Vec3) -> Vec3) {
        for p in m.polygons() {
            let n = m.face_normal_wide(p);
            let c = m.vertices()[p[0] as usize];
            let d = c.sub(inside(c)).bits();
            let dot: f64 = (0..3).map(|i| n[i] as f64 * d[i] as f64).sum();
            assert!(dot > 0.0, "face {p:?} points inward");
        }
    }

    #[test]
    fn analytic_normals_are_unit_vectors_along_the_surface_normal() {
        // Sphere: the normal is the direction from the centre; torus: from the tube's centre
        // line. Both against f64, within 2 units of 2^-16 per component.
        let (nv, ni) = uv_sphere_sizes(12, 7);
        let (mut v, mut ix, mut n) = (
            std::vec![Vec3::ZERO; nv],
            std::vec![0u16; ni],
            std::vec![Vec3::ZERO; nv],
        );
        uv_sphere(12, 7, Coord::from_num(3), &mut v, &mut ix).unwrap();
        uv_sphere_normals(12, 7, &mut n).unwrap();
        let f = |c: Coord| c.to_num::<f64>();
        for (p, q) in v.iter().zip(&n) {
            let len = (f(p.x).powi(2) + f(p.y).powi(2) + f(p.z).powi(2)).sqrt();
            for (a, b) in [(p.x, q.x), (p.y, q.y), (p.z, q.z)] {
                assert!((f(a) / len - f(b)).abs() * 65536.0 <= 2.0, "{p:?} {q:?}");
            }
        }
        let (nv, ni) = torus_sizes(10, 6);
        let (mut v, mut ix, mut n) = (
            std::vec![Vec3::ZERO; nv],
            std::vec![0u16; ni],
            std::vec![Vec3::ZERO; nv],
        );
        let (major, minor) = (Coord::from_num(2), Coord::from_num(0.5));
        torus(10, 6, major, minor, &mut v, &mut ix).unwrap();
        torus_normals(10, 6, &mut n).unwrap();
        for (p, q) in v.iter().zip(&n) {
            // The tube's centre below the vertex: major radius along the vertex's azimuth.
            let rho = (f(p.x).powi(2) + f(p.z).powi(2)).sqrt();
            let c = [f(p.x) * 2.0 / rho, 0.0, f(p.z) * 2.0 / rho];
            let d = [f(p.x) - c[0], f(p.y), f(p.z) - c[2]];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            for (k, b) in [q.x, q.y, q.z].into_iter().enumerate() {
                assert!((d[k] / len - f(b)).abs() * 65536.0 <= 2.0, "{p:?} {q:?}");
            }
        }
        assert_eq!(
            uv_sphere_normals(12, 7, &mut n[..1]),
            Err(MeshError::OutputTooSmall {
                table: MeshTable::VertexNormals,
                given: 1,
                needed: 74
            })
        );
        assert_eq!(torus_normals(2, 6, &mut n), Err(MeshError::BadParameters));
    }

    #[test]
    fn huge_sizes_are_errors() {
        let mut vs = [Vec3::ZERO; 96];
        let mut is = [0u16; 384];
        assert_eq!(
            uv_sphere(8, 4, Coord::MAX, &mut vs, &mut is),
            Err(MeshError::CoordinateOutOfRange)
        );
        assert_eq!(
            torus(12, 8, Coord::MAX, Coord::from_num(30000), &mut vs, &mut is),
            Err(MeshError::CoordinateOutOfRange)
        );
        assert_eq!(
            hollow_prism(6, Coord::MAX, Coord::ONE, Coord::MAX, &mut vs, &mut is),
            Err(MeshError::CoordinateOutOfRange)
        );
        assert_eq!(
            uv_sphere(u16::MAX, u16::MAX, Coord::ONE, &mut vs, &mut is),
            Err(MeshError::BadParameters)
        );
    }

    /// Issue "hostile inputs" #6: the checked sizes refuse what the generators refuse, before
    /// anything is allocated, and agree with them at the vertex limit.
    #[test]
    fn checked_sizes_validate_before_allocating() {
        assert_eq!(
            uv_sphere_sizes_checked(u16::MAX, u16::MAX),
            Err(MeshError::BadParameters)
        );
        assert_eq!(
            torus_sizes_checked(u16::MAX, u16::MAX),
            Err(MeshError::BadParameters)
        );
        assert_eq!(
            hollow_prism_sizes_checked(u16::MAX),
            Err(MeshError::BadParameters)
        );
        for (s, r) in [(2, 5), (5, 1), (0, 0)] {
            assert_eq!(uv_sphere_sizes_checked(s, r), Err(MeshError::BadParameters));
        }
        assert_eq!(torus_sizes_checked(2, 9), Err(MeshError::BadParameters));
        assert_eq!(hollow_prism_sizes_checked(2), Err(MeshError::BadParameters));
        // At the limit: 2 + 2·32767 = 65536 vertices; torus 256·256; prism 16384 sides.
        assert_eq!(
            uv_sphere_sizes_checked(32767, 3),
            Ok(uv_sphere_sizes(32767, 3))
        );
        assert_eq!(
            uv_sphere_sizes_checked(32768, 3),
            Err(MeshError::BadParameters)
        );
        assert_eq!(torus_sizes_checked(256, 256), Ok((65536, 4 * 65536)));
        assert_eq!(torus_sizes_checked(256, 257), Err(MeshError::BadParameters));
        assert_eq!(hollow_prism_sizes_checked(16384), Ok((65536, 16 * 16384)));
        assert_eq!(
            hollow_prism_sizes_checked(16385),
            Err(MeshError::BadParameters)
        );
        // The unchecked sizes saturate instead of wrapping.
        assert_eq!(torus_sizes(u16::MAX, u16::MAX).0, 65535 * 65535);
        // The smallest accepted sphere fits its checked sizes exactly.
        let (nv, ni) = uv_sphere_sizes_checked(3, 2).unwrap();
        let (mut vs, mut is) = ([Vec3::ZERO; 5], [0u16; 18]);
        assert_eq!((nv, ni), (5, 18));
        assert!(uv_sphere(3, 2, Coord::ONE, &mut vs, &mut is).is_ok());
    }

    #[test]
    fn cube_is_outward() {
        let m = unit_cube();
        assert_eq!(m.polygon_count(), 6);
        outward(&m, |_| Vec3::from_bits(32768, 32768, 32768));
    }

    #[test]
    fn sphere_counts_and_orientation() {
        let (nv, ni) = uv_sphere_sizes(32, 16);
        assert_eq!((nv, ni / 3), (482, 960));
        let mut vs = [Vec3::ZERO; 482];
        let mut is = [0u16; 2880];
        let m = uv_sphere(32, 16, Coord::ONE, &mut vs, &mut is).unwrap();
        assert_eq!(m.polygon_count(), 960);
        outward(&m, |_| Vec3::ZERO);
        assert_eq!(m.vertices()[0], Vec3::from_int(0, 1, 0));
        assert_eq!(m.vertices()[481], Vec3::from_int(0, -1, 0));
        let mut small = [0u16; 10];
        assert_eq!(
            uv_sphere(32, 16, Coord::ONE, &mut vs, &mut small),
            Err(MeshError::OutputTooSmall {
                table: MeshTable::Indices,
                given: 10,
                needed: 2_880
            })
        );
        assert_eq!(
            uv_sphere(2, 16, Coord::ONE, &mut vs, &mut is),
            Err(MeshError::BadParameters)
        );
    }

    #[test]
    fn hollow_prism_and_torus_orientation() {
        let mut vs = [Vec3::ZERO; 24];
        let mut is = [0u16; 96];
        let m = hollow_prism(
            6,
            Coord::ONE,
            Coord::from_num(0.8),
            Coord::ONE,
            &mut vs,
            &mut is,
        )
        .unwrap();
        assert_eq!(m.polygon_count(), 24);
        // Inside the material: the point at radius 0.9 on the same azimuth, same height / 2.
        outward(&m, |c| {
            let b = c.bits();
            let r = ((b[0] as f64).hypot(b[1] as f64)).max(1.0);
            let k = 0.9 * 65536.0 / r;
            Vec3::from_bits((b[0] as f64 * k) as i32, (b[1] as f64 * k) as i32, b[2] / 2)
        });
        let mut vs = [Vec3::ZERO; 96];
        let mut is = [0u16; 384];
        let m = torus(
            12,
            8,
            Coord::from_num(2),
            Coord::from_num(0.5),
            &mut vs,
            &mut is,
        )
        .unwrap();
        assert_eq!(m.polygon_count(), 96);
        outward(&m, |c| {
            let b = c.bits();
            let r = (b[0] as f64).hypot(b[2] as f64);
            let k = 2.0 * 65536.0 / r;
            Vec3::from_bits((b[0] as f64 * k) as i32, 0, (b[2] as f64 * k) as i32)
        });
    }
}
