//! STL and PLY readers for `zscan mesh`, beside the OBJ reader ([`crate::obj`]): each gives
//! an [`ObjMesh`] (`f64` positions, 0-based polygons) under the OBJ reader's limits
//! ([`MAX_OBJ_BYTES`], [`MAX_OBJ_VERTICES`], [`MAX_OBJ_FACES`], [`MAX_FACE_VERTICES`]), with
//! errors that name the line (or, for binary STL, the facet).
//!
//! - **STL**, ASCII (`solid … facet … outer loop … vertex x y z … endsolid`) or binary (80-byte
//!   header, `u32` facet count, 50 bytes per facet: normal, three corners as little-endian
//!   `f32`, attribute). STL repeats each corner per facet; corners with bit-identical
//!   coordinates are merged into one vertex (in order of first use), so that the mesh is
//!   indexed and closed meshes stay closed. The facet normals are not read (the winding is).
//! - **PLY**, ASCII only (`format ascii 1.0`): the `vertex` element's `x`, `y`, `z` properties
//!   (any scalar type, any order, other properties skipped) and the `face` element's list
//!   property (`vertex_indices` or `vertex_index`); other elements are skipped. Binary PLY is
//!   refused in words.
//!
//! No parsing crate: ASCII numbers go through `f64::from_str`, which rounds the decimal text
//! correctly to the nearest `f64` (as the OBJ reader does), and binary STL's `f32`s widen to
//! `f64` exactly; `stl_io` keeps ASCII coordinates as `f32` (a first rounding before the
//! I16F16 one) and reads neither PLY, and the PLY crates bring a generic property model this
//! reader does not need.

use std::collections::HashMap;
use std::path::Path;

use crate::obj::{ObjMesh, MAX_FACE_VERTICES, MAX_OBJ_BYTES, MAX_OBJ_FACES, MAX_OBJ_VERTICES};

/// Reads `path` as OBJ, STL or PLY by its extension (case-insensitive).
pub fn load_mesh(path: &Path) -> Result<ObjMesh, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let name = path.display();
    match ext.as_deref() {
        Some("obj") => crate::obj::load_obj(path).map_err(|e| format!("{name}: {e}")),
        Some("stl") => parse_stl(&read_limited(path)?).map_err(|e| format!("{name}: {e}")),
        Some("ply") => {
            let bytes = read_limited(path)?;
            let text = std::str::from_utf8(&bytes)
                .map_err(|_| format!("{name}: not ASCII PLY (binary PLY is not read)"))?;
            parse_ply(text).map_err(|e| format!("{name}: {e}"))
        }
        _ => Err(format!(
            "{name}: unknown mesh format (the extension must be .obj, .stl or .ply)"
        )),
    }
}

/// The file's bytes, up to [`MAX_OBJ_BYTES`].
fn read_limited(path: &Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut bytes = Vec::new();
    file.take(MAX_OBJ_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.len() as u64 > MAX_OBJ_BYTES {
        return Err(format!(
            "{}: file is longer than the mesh reader's limit of {MAX_OBJ_BYTES} bytes",
            path.display()
        ));
    }
    Ok(bytes)
}

/// Merges STL corners into indexed vertices (bit-identical coordinates are one vertex).
#[derive(Default)]
struct Corners {
    mesh: ObjMesh,
    index: HashMap<[u64; 3], usize>,
}

impl Corners {
    fn vertex(&mut self, v: [f64; 3]) -> Result<usize, String> {
        if v.iter().any(|c| !c.is_finite()) {
            return Err("vertex coordinate is not finite".into());
        }
        let key = v.map(|c| (c + 0.0).to_bits()); // -0 and +0 are one corner
        if let Some(&i) = self.index.get(&key) {
            return Ok(i);
        }
        if self.mesh.vertices.len() >= MAX_OBJ_VERTICES {
            return Err(format!(
                "more than {MAX_OBJ_VERTICES} distinct vertices (the core's u16 indices)"
            ));
        }
        self.mesh.vertices.push(v);
        self.index.insert(key, self.mesh.vertices.len() - 1);
        Ok(self.mesh.vertices.len() - 1)
    }

    fn facet(&mut self, corners: [[f64; 3]; 3]) -> Result<(), String> {
        if self.mesh.polygons.len() >= MAX_OBJ_FACES {
            return Err(format!("more than {MAX_OBJ_FACES} facets"));
        }
        let mut polygon = Vec::with_capacity(3);
        for c in corners {
            polygon.push(self.vertex(c)?);
        }
        self.mesh.polygons.push(polygon);
        Ok(())
    }
}

/// Parses an STL file, binary or ASCII (module doc).
pub fn parse_stl(bytes: &[u8]) -> Result<ObjMesh, String> {
    let binary_count = bytes
        .get(80..84)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as u64);
    match binary_count {
        Some(n) if 84 + 50 * n == bytes.len() as u64 => parse_binary_stl(bytes, n as usize),
        _ => {
            let text = std::str::from_utf8(bytes).map_err(|_| {
                "neither binary STL (its size is not 84 + 50 × its facet count) nor ASCII STL \
                 (not text)"
                    .to_string()
            })?;
            parse_ascii_stl(text)
        }
    }
}

fn parse_binary_stl(bytes: &[u8], n: usize) -> Result<ObjMesh, String> {
    let mut corners = Corners::default();
    for (f, facet) in bytes[84..].chunks_exact(50).take(n).enumerate() {
        let float = |k: usize| {
            let b = &facet[12 + 4 * k..16 + 4 * k];
            f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64
        };
        let corner = |c: usize| [float(3 * c), float(3 * c + 1), float(3 * c + 2)];
        corners
            .facet([corner(0), corner(1), corner(2)])
            .map_err(|e| format!("facet {}: {e}", f + 1))?;
    }
    Ok(corners.mesh)
}

fn parse_ascii_stl(text: &str) -> Result<ObjMesh, String> {
    let mut corners = Corners::default();
    let mut facet: Vec<[f64; 3]> = Vec::new();
    let mut solid = false;
    for (n, raw) in text.lines().enumerate() {
        let line = n + 1;
        let err = |e: String| format!("line {line}: {e}");
        let mut words = raw.split_whitespace();
        match words.next() {
            Some("solid") => solid = true,
            Some("vertex") => {
                let v = three_numbers(&mut words).map_err(err)?;
                if facet.len() == 3 {
                    return Err(err("a facet with more than 3 vertices".into()));
                }
                facet.push(v);
            }
            Some("endfacet") => {
                let [a, b, c] = facet[..] else {
                    return Err(err(format!(
                        "a facet with {} vertices (STL facets have 3)",
                        facet.len()
                    )));
                };
                corners.facet([a, b, c]).map_err(err)?;
                facet.clear();
            }
            Some("facet" | "outer" | "endloop" | "endsolid") | None => {}
            Some(w) if solid => return Err(err(format!("unexpected {w:?} in an ASCII STL"))),
            Some(_) => return Err(err("an ASCII STL file starts with \"solid\"".into())),
        }
    }
    if !solid {
        return Err("empty file: an ASCII STL file starts with \"solid\"".into());
    }
    Ok(corners.mesh)
}

/// Three finite numbers.
fn three_numbers<'a>(words: &mut impl Iterator<Item = &'a str>) -> Result<[f64; 3], String> {
    let mut v = [0.0; 3];
    for c in &mut v {
        let w = words.next().ok_or("a vertex needs x, y and z")?;
        *c = w
            .parse::<f64>()
            .map_err(|_| format!("cannot parse number {w:?}"))?;
        if !c.is_finite() {
            return Err("vertex coordinate is not finite".into());
        }
    }
    Ok(v)
}

/// One element of a PLY header: its name, count and properties (`name`, is a list).
struct Element<'a> {
    name: &'a str,
    count: usize,
    properties: Vec<(&'a str, bool)>,
}

/// Parses an ASCII PLY file (module doc).
pub fn parse_ply(text: &str) -> Result<ObjMesh, String> {
    let mut lines = text.lines().enumerate();
    let mut elements: Vec<Element<'_>> = Vec::new();
    let mut line_of_body = 0;
    for (n, raw) in lines.by_ref() {
        let line = n + 1;
        let err = |e: &str| format!("line {line}: {e}");
        let words: Vec<&str> = raw.split_whitespace().collect();
        match words.as_slice() {
            ["ply"] if line == 1 => {}
            _ if line == 1 => return Err(err("a PLY file starts with \"ply\"")),
            ["format", "ascii", _] => {}
            ["format", f, _] => {
                return Err(err(&format!(
                    "format {f} is not read: only ASCII PLY (convert the file to ascii)"
                )))
            }
            ["comment", ..] | ["obj_info", ..] | [] => {}
            ["element", name, count] => {
                let count = count
                    .parse::<usize>()
                    .map_err(|_| err(&format!("cannot parse element count {count:?}")))?;
                elements.push(Element {
                    name,
                    count,
                    properties: Vec::new(),
                });
            }
            ["property", "list", _, _, name] | ["property", _, name] => {
                let list = words[1] == "list";
                let element = elements
                    .last_mut()
                    .ok_or_else(|| err("a property before any element"))?;
                element.properties.push((name, list));
            }
            ["end_header"] => {
                line_of_body = line + 1;
                break;
            }
            _ => return Err(err(&format!("unexpected header line {raw:?}"))),
        }
    }
    if line_of_body == 0 {
        return Err("no end_header line".into());
    }
    let mut mesh = ObjMesh::default();
    for element in &elements {
        match element.name {
            "vertex" if element.count > MAX_OBJ_VERTICES => {
                return Err(format!(
                    "{} vertices: more than {MAX_OBJ_VERTICES} (the core's u16 indices)",
                    element.count
                ))
            }
            "face" if element.count > MAX_OBJ_FACES => {
                return Err(format!(
                    "{} faces: more than {MAX_OBJ_FACES}",
                    element.count
                ))
            }
            _ => {}
        }
        let at = |name: &str| element.properties.iter().position(|p| p.0 == name);
        for _ in 0..element.count {
            let (n, raw) = lines.next().ok_or_else(|| {
                format!(
                    "the file ends before its {} {} elements",
                    element.count, element.name
                )
            })?;
            let line = n + 1;
            let err = |e: String| format!("line {line}: {e}");
            let words: Vec<&str> = raw.split_whitespace().collect();
            match element.name {
                "vertex" => {
                    let axes = [at("x"), at("y"), at("z")];
                    if element.properties.iter().any(|p| p.1) {
                        return Err(err("a list property on vertices is not read".into()));
                    }
                    let mut v = [0.0; 3];
                    for (c, axis) in v.iter_mut().zip(axes) {
                        let k = axis.ok_or_else(|| err("vertices need x, y and z".into()))?;
                        let w = words.get(k).ok_or_else(|| err("too few values".into()))?;
                        *c = w
                            .parse::<f64>()
                            .map_err(|_| err(format!("cannot parse number {w:?}")))?;
                        if !c.is_finite() {
                            return Err(err("vertex coordinate is not finite".into()));
                        }
                    }
                    mesh.vertices.push(v);
                }
                "face" => {
                    let list = element.properties.iter().position(|p| p.1);
                    if list != Some(0) || element.properties.len() != 1 {
                        return Err(err(
                            "faces are read with one list property (vertex_indices) only".into(),
                        ));
                    }
                    let count = words
                        .first()
                        .and_then(|w| w.parse::<usize>().ok())
                        .ok_or_else(|| err("cannot parse the face's vertex count".into()))?;
                    if count < 3 {
                        return Err(err("face needs at least 3 vertices".into()));
                    }
                    if count > MAX_FACE_VERTICES {
                        return Err(err(format!(
                            "face with more than {MAX_FACE_VERTICES} vertices"
                        )));
                    }
                    if words.len() != count + 1 {
                        return Err(err(format!(
                            "a face of {count} vertices lists {}",
                            words.len() - 1
                        )));
                    }
                    let mut polygon = Vec::with_capacity(count);
                    for w in &words[1..] {
                        let i = w
                            .parse::<usize>()
                            .map_err(|_| err(format!("cannot parse vertex index {w:?}")))?;
                        polygon.push(i);
                    }
                    mesh.polygons.push(polygon);
                }
                _ => {}
            }
        }
    }
    let nv = mesh.vertices.len();
    for (f, p) in mesh.polygons.iter().enumerate() {
        if let Some(&i) = p.iter().find(|&&i| i >= nv) {
            return Err(format!(
                "face {f}: vertex index {i} out of range ({nv} vertices, 0-based)"
            ));
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron, counter-clockwise seen from outside, in each format.
    const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

    fn ascii_stl() -> String {
        let m = crate::obj::parse_obj(OBJ).unwrap();
        let mut s = String::from("solid tetra\n");
        for p in &m.polygons {
            s += "  facet normal 0 0 0\n    outer loop\n";
            for &i in p {
                let v = m.vertices[i];
                s += &format!("      vertex {} {} {}\n", v[0], v[1], v[2]);
            }
            s += "    endloop\n  endfacet\n";
        }
        s + "endsolid tetra\n"
    }

    fn binary_stl() -> Vec<u8> {
        let m = crate::obj::parse_obj(OBJ).unwrap();
        let mut b = vec![0u8; 80];
        b.extend((m.polygons.len() as u32).to_le_bytes());
        for p in &m.polygons {
            b.extend([0u8; 12]);
            for &i in p {
                for c in m.vertices[i] {
                    b.extend((c as f32).to_le_bytes());
                }
            }
            b.extend([0u8; 2]);
        }
        b
    }

    const PLY: &str = "ply\nformat ascii 1.0\ncomment a tetrahedron\nelement vertex 4\n\
        property float x\nproperty float y\nproperty float z\nproperty float s\n\
        element face 4\nproperty list uchar int vertex_indices\nend_header\n\
        0 0 0 0.5\n1 0 0 0.5\n0 1 0 0.5\n0 0 1 0.5\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

    /// Each polygon as its corners' coordinates.
    fn corners(m: &ObjMesh) -> Vec<Vec<[f64; 3]>> {
        let polygon = |p: &Vec<usize>| p.iter().map(|&i| m.vertices[i]).collect();
        m.polygons.iter().map(polygon).collect()
    }

    /// STL merges the repeated corners into 4 vertices (numbered by first use); PLY keeps the
    /// file's numbering.
    #[test]
    fn stl_and_ply_read_the_obj_mesh() {
        let obj = crate::obj::parse_obj(OBJ).unwrap();
        for stl in [parse_stl(ascii_stl().as_bytes()), parse_stl(&binary_stl())] {
            let stl = stl.unwrap();
            assert_eq!((stl.vertices.len(), corners(&stl)), (4, corners(&obj)));
        }
        assert_eq!(parse_ply(PLY).unwrap(), obj);
    }

    #[test]
    fn errors_name_the_line_or_facet() {
        let bad = ascii_stl().replacen("vertex 1 0 0", "vertex 1 x 0", 1);
        let e = parse_stl(bad.as_bytes()).unwrap_err();
        assert!(e.starts_with("line ") && e.contains("\"x\""), "{e}");
        let four = ascii_stl().replacen("endloop", "vertex 0 0 0\n endloop", 1);
        assert!(parse_stl(four.as_bytes())
            .unwrap_err()
            .contains("more than 3"));
        let mut nan = binary_stl();
        nan[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
        assert_eq!(
            parse_stl(&nan).unwrap_err(),
            "facet 1: vertex coordinate is not finite"
        );
        assert!(parse_stl(b"\xff\xfe")
            .unwrap_err()
            .contains("neither binary"));
        let e = parse_ply(&PLY.replace("3 1 2 3", "3 1 2 9")).unwrap_err();
        assert!(e.contains("vertex index 9 out of range"), "{e}");
        let e = parse_ply(&PLY.replace("ascii", "binary_little_endian")).unwrap_err();
        assert!(e.contains("only ASCII PLY"), "{e}");
        let e = parse_ply(&PLY.replace("3 0 2 1\n", "3 0 2\n")).unwrap_err();
        assert!(e.starts_with("line 16:"), "{e}");
        let e = parse_ply(&PLY.replace("element face 4", "element face 5")).unwrap_err();
        assert!(e.contains("ends before its 5 face"), "{e}");
        let e = load_mesh(Path::new("mesh.3ds")).unwrap_err();
        assert!(e.contains(".obj, .stl or .ply"), "{e}");
    }
}
