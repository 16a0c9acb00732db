//! `zscan mesh --cluster N` (`zscan_host::cluster`): a subdivided square whose clustering is
//! worked out by hand, repeated faces, the refused grid sizes, and properties of random meshes
//! (every index in range, no polygon with a repeated vertex, no more polygons than given).

use zscan_host::cluster::cluster;
use zscan_host::obj::ObjMesh;
use zscan_host::test_rng::XorShift;

/// The unit square in z = 0 cut into 4 × 4 squares (vertex `(i, j)` at `(i/4, j/4, 0)`, number
/// `5j + i`), each square as triangles `a b c` and `a c d` from its corner `a = (i, j)`
/// counter-clockwise.
fn subdivided_square() -> ObjMesh {
    let vertices = (0..25)
        .map(|k| [(k % 5) as f64 / 4.0, (k / 5) as f64 / 4.0, 0.0])
        .collect();
    let mut polygons = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            let (a, b, c, d) = (5 * j + i, 5 * j + i + 1, 5 * j + i + 6, 5 * j + i + 5);
            polygons.push(vec![a, b, c]);
            polygons.push(vec![a, c, d]);
        }
    }
    ObjMesh {
        vertices,
        polygons,
        ..ObjMesh::default()
    }
}

/// On a 2 × 2 × 2 grid, x and y cut at 1/2: columns 0 and 1 fall in cell 0, columns 2 to 4 in
/// cell 1 (rows alike); z has no span, one cell. Only the square at (1, 1) has its four
/// corners in four cells; every other square has two corners in one cell in both triangles.
/// The cells' means: (0 + 1/4)/2 = 1/8 and (1/2 + 3/4 + 1)/3 = 3/4 per axis; vertices numbered
/// as the kept triangles first use them.
#[test]
fn a_subdivided_square_keeps_its_middle_square() {
    let out = cluster(&subdivided_square(), 2).unwrap();
    assert_eq!(
        out.vertices,
        vec![
            [0.125, 0.125, 0.0],
            [0.75, 0.125, 0.0],
            [0.75, 0.75, 0.0],
            [0.125, 0.75, 0.0],
        ]
    );
    assert_eq!(out.polygons, vec![vec![0, 1, 2], vec![0, 2, 3]]);
}

/// A face given again (rotated) is dropped; its reverse winding is another face and stays.
#[test]
fn repeated_faces_are_dropped_reversed_ones_kept() {
    let mesh = ObjMesh {
        vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 1.0]],
        polygons: vec![vec![0, 1, 2], vec![1, 2, 0], vec![0, 2, 1], vec![2, 0, 1]],
        ..ObjMesh::default()
    };
    let out = cluster(&mesh, 256).unwrap();
    assert_eq!(out.vertices, mesh.vertices);
    assert_eq!(out.polygons, vec![vec![0, 1, 2], vec![0, 2, 1]]);
}

#[test]
fn grid_sizes_outside_2_to_256_and_empty_results_are_refused() {
    for n in [0, 1, 257, u32::MAX] {
        let e = cluster(&subdivided_square(), n).unwrap_err();
        assert_eq!(
            e,
            format!("--cluster {n}: the grid must have 2 to 256 cells per axis")
        );
    }
    // The one triangle lies in the first of the 2 × 2 × 2 cells the far vertex spans.
    let small = ObjMesh {
        vertices: vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.1, 0.0, 0.0],
            [0.0, 0.1, 0.0],
        ],
        polygons: vec![vec![0, 2, 3]],
        ..ObjMesh::default()
    };
    assert_eq!(
        cluster(&small, 2).unwrap_err(),
        "--cluster 2: no polygon is left (every one has two corners in one cell)"
    );
    assert_eq!(cluster(&small, 16).unwrap().polygons, vec![vec![0, 1, 2]]);
    let mut far = small.clone();
    far.vertices[2] = [f64::NAN, 0.0, 0.0];
    assert_eq!(
        cluster(&far, 2).unwrap_err(),
        "--cluster: vertex 2 is not finite"
    );
}

/// Random meshes (random points, random triangles and quads): the result's indices are in
/// range, no polygon repeats a vertex or an earlier polygon, no more polygons than given, and
/// every vertex lies within the input's bounding box (a mean of its points).
#[test]
fn random_meshes_give_valid_smaller_meshes() {
    let mut rng = XorShift::new(0x5eed_c105);
    for case in 0..300 {
        let nv = 3 + rng.below(60) as usize;
        let vertices: Vec<[f64; 3]> = (0..nv)
            .map(|_| [0; 3].map(|_| rng.uniform(-2.0, 2.0)))
            .collect();
        let polygons: Vec<Vec<usize>> = (0..1 + rng.below(80))
            .map(|_| {
                let k = if rng.chance(20) { 4 } else { 3 };
                let mut p: Vec<usize> = Vec::new();
                while p.len() < k.min(nv) {
                    let v = rng.below(nv as u64) as usize;
                    if !p.contains(&v) {
                        p.push(v);
                    }
                }
                p
            })
            .collect();
        let mesh = ObjMesh {
            vertices,
            polygons,
            ..ObjMesh::default()
        };
        let n = 2 + rng.below(30) as u32;
        let Ok(out) = cluster(&mesh, n) else {
            continue;
        };
        assert!(out.polygons.len() <= mesh.polygons.len(), "case {case}");
        assert!(out.vertices.len() <= mesh.vertices.len(), "case {case}");
        let mut seen = std::collections::HashSet::new();
        for p in &out.polygons {
            assert!(p.len() >= 3 && p.iter().all(|&i| i < out.vertices.len()));
            for (a, &i) in p.iter().enumerate() {
                assert!(
                    !p[a + 1..].contains(&i),
                    "case {case}: {p:?} repeats a vertex"
                );
            }
            let first = (0..p.len()).min_by_key(|&i| p[i]).unwrap();
            let key: Vec<usize> = p[first..].iter().chain(&p[..first]).copied().collect();
            assert!(seen.insert(key), "case {case}: {p:?} twice");
        }
        for v in &out.vertices {
            for k in 0..3 {
                let lo = mesh
                    .vertices
                    .iter()
                    .map(|w| w[k])
                    .fold(f64::INFINITY, f64::min);
                let hi = mesh
                    .vertices
                    .iter()
                    .map(|w| w[k])
                    .fold(f64::NEG_INFINITY, f64::max);
                assert!(v[k] >= lo - 1e-12 && v[k] <= hi + 1e-12, "case {case}");
            }
        }
    }
}
