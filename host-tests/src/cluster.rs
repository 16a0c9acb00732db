//! Vertex clustering, the coarse meshes of small displays (`zscan mesh --cluster N`): the
//! mesh's bounding box is cut into an `N × N × N` grid of equal cells (`N` in `2..=256`),
//! every vertex moves to the mean of the vertices in its cell (one vertex per occupied cell,
//! numbered in order of first use by the polygons), a polygon with two corners in one cell is
//! dropped (it would be degenerate), and so is a polygon that repeats an earlier one (the
//! same corners in the same cyclic order; the reverse winding is another face and stays).
//!
//! Numbers: `f64` on the host, before placement (`--centre`, `--fit` then see the clustered
//! mesh). A coordinate `c` of an axis spanning `[lo, hi]` falls in cell
//! `min(⌊(c − lo) / (hi − lo) · N⌋, N − 1)`, an axis of zero span in cell 0. Texture
//! coordinates are not carried (a cell's corners do not share one).
use crate::obj::ObjMesh;
use std::collections::{HashMap, HashSet};

/// The grid sizes `--cluster` takes.
pub const CELLS: std::ops::RangeInclusive<u32> = 2..=256;

/// `mesh` clustered on an `n × n × n` grid (module doc), or why not: `n` outside [`CELLS`],
/// a vertex that is not finite, or no polygon left.
pub fn cluster(mesh: &ObjMesh, n: u32) -> Result<ObjMesh, String> {
    if !CELLS.contains(&n) {
        return Err(format!(
            "--cluster {n}: the grid must have {} to {} cells per axis",
            CELLS.start(),
            CELLS.end()
        ));
    }
    if let Some(i) = mesh
        .vertices
        .iter()
        .position(|v| v.iter().any(|c| !c.is_finite()))
    {
        return Err(format!("--cluster: vertex {i} is not finite"));
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for v in &mesh.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    let cell_of = |v: &[f64; 3]| -> [u32; 3] {
        let mut c = [0u32; 3];
        for k in 0..3 {
            let span = hi[k] - lo[k];
            if span > 0.0 {
                c[k] = (((v[k] - lo[k]) / span * f64::from(n)).floor() as u32).min(n - 1);
            }
        }
        c
    };
    // Each cell's sum and count, over every vertex of the file.
    let cells: Vec<[u32; 3]> = mesh.vertices.iter().map(cell_of).collect();
    let mut sums: HashMap<[u32; 3], ([f64; 3], u32)> = HashMap::new();
    for (v, c) in mesh.vertices.iter().zip(&cells) {
        let s = sums.entry(*c).or_insert(([0.0; 3], 0));
        for (sum, x) in s.0.iter_mut().zip(v) {
            *sum += x;
        }
        s.1 += 1;
    }
    let mut number: HashMap<[u32; 3], usize> = HashMap::new();
    let mut vertices = Vec::new();
    let mut polygons = Vec::new();
    let mut seen: HashSet<Vec<usize>> = HashSet::new();
    for p in &mesh.polygons {
        let corners: Vec<[u32; 3]> = p.iter().map(|&i| cells[i]).collect();
        let distinct: HashSet<&[u32; 3]> = corners.iter().collect();
        if distinct.len() < corners.len() {
            continue;
        }
        let q: Vec<usize> = corners
            .iter()
            .map(|c| {
                *number.entry(*c).or_insert_with(|| {
                    let (s, count) = sums[c];
                    vertices.push(s.map(|x| x / f64::from(count)));
                    vertices.len() - 1
                })
            })
            .collect();
        // Rotated to start at its smallest vertex: one key per cyclic order.
        let first = (0..q.len()).min_by_key(|&i| q[i]).unwrap_or(0);
        let key: Vec<usize> = q[first..].iter().chain(&q[..first]).copied().collect();
        if seen.insert(key) {
            polygons.push(q);
        }
    }
    if polygons.is_empty() {
        return Err(format!(
            "--cluster {n}: no polygon is left (every one has two corners in one cell)"
        ));
    }
    Ok(ObjMesh {
        vertices,
        polygons,
        ..ObjMesh::default()
    })
}
