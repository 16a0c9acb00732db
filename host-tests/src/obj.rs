//! A Wavefront OBJ reader for the host: vertex positions (`v`), texture coordinates (`vt`)
//! and polygons (`f`) of any vertex count, in all index forms (`i`, `i/t`, `i//n`, `i/t/n`),
//! negative (relative) indices and comments. Other statements (`vn`, `g`, `o`, `s`, `usemtl`,
//! `mtllib`, …) are skipped. Errors carry the 1-based line number.
//!
//! ## Texture coordinates
//! Per polygon corner ([`ObjMesh::uvs`], parallel to the polygons' indices, as the core's
//! `Mesh::with_uvs` takes them), in the core's Q8.8
//! ([`TexCoord`], `1.0 = 256`, `−128 ≤ u, v < 128`): the core's
//! `u` is the file's `u`, its `v` is `1 − v` (OBJ's `v` runs up the image, the core's rows run
//! down it from row 0 at the top), both rounded to the nearest 1/256. A mesh has them when
//! every corner of every face names a `vt`; they are only needed for a texture, so their
//! problems (a `vt` whose value leaves the range, a corner without one while others have one,
//! an index past the `vt` lines) do not stop the mesh from loading: the first one is kept
//! with its line ([`ObjMesh::texture_coordinates`] returns it).
//!
//! ## Limits
//! Every limit is checked before the memory it bounds is allocated, so no file can make the
//! reader allocate more than the mesh it describes needs:
//! - a file is read up to [`MAX_OBJ_BYTES`] (64 MiB); a longer one (or an endless device such
//!   as `/dev/zero`) is [`ObjErrorKind::FileTooLarge`] after reading one byte past the limit;
//! - at most [`MAX_OBJ_VERTICES`] (65 536, what the core's `u16` indices address) vertices and
//!   [`MAX_OBJ_FACES`] (2^20) faces, each of at most [`MAX_FACE_VERTICES`] (255) vertices;
//! - a face index is any `i64` written in the file; `0`, and positive or negative (relative)
//!   indices beyond the vertices defined so far, are [`ObjErrorKind::IndexOutOfRange`] (no
//!   arithmetic on the index can overflow: relative indices use `unsigned_abs`).
//!
//! Output is `f64` positions and 0-based polygon index lists; [`ObjMesh::to_zscan`] converts to
//! the core's flash-friendly tables ([`zscan::geometry::mesh`]).

use std::fmt;
use std::path::Path;

use zscan::geometry::fixed::Coord;
use zscan::geometry::mesh::{TexCoord, TEX_ONE};
use zscan::geometry::vector::Vec3;

/// Longest OBJ file read: 64 MiB.
pub const MAX_OBJ_BYTES: u64 = 64 << 20;
/// Most vertices an OBJ file may define (the core's `u16` indices address 65 536).
pub const MAX_OBJ_VERTICES: usize = 65_536;
/// Most faces an OBJ file may define: 2^20.
pub const MAX_OBJ_FACES: usize = 1 << 20;
/// Most vertices of one face (the core's polygon sizes are `u8`).
pub const MAX_FACE_VERTICES: usize = 255;

/// A parsed OBJ file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjMesh {
    /// Vertex positions, in file order.
    pub vertices: Vec<[f64; 3]>,
    /// Polygons as 0-based vertex indices, in file order (at least 3 each).
    pub polygons: Vec<Vec<usize>>,
    /// Texture coordinates, one per polygon corner in the order of `polygons` (module doc),
    /// or empty: the file gives none, or [`uv_error`](Self::uv_error) says why not.
    pub uvs: Vec<TexCoord>,
    /// The first problem with the texture coordinates, with its line (module doc).
    pub uv_error: Option<ObjError>,
}

/// What went wrong, and where.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjError {
    /// 1-based line number (0 for errors not tied to a line, e.g. reading the file).
    pub line: usize,
    /// The problem.
    pub kind: ObjErrorKind,
}

/// The kinds of [`ObjError`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ObjErrorKind {
    /// A number could not be parsed (the offending text).
    BadNumber(String),
    /// A `v` line with fewer than three coordinates.
    TooFewCoordinates,
    /// A coordinate that is NaN or infinite.
    NonFinite,
    /// An `f` line with fewer than three vertices.
    TooFewVertices,
    /// Index 0, which OBJ does not allow.
    ZeroIndex,
    /// An index beyond the vertices defined so far (the index as written).
    IndexOutOfRange(i64),
    /// The file could not be read.
    Io(String),
    /// The file is longer than [`MAX_OBJ_BYTES`] (the path).
    FileTooLarge(String),
    /// More than [`MAX_OBJ_VERTICES`] vertices.
    TooManyVertices,
    /// More than [`MAX_OBJ_FACES`] faces.
    TooManyFaces,
    /// A face with more than [`MAX_FACE_VERTICES`] vertices.
    FaceTooLarge,
    /// A `vt` value (as written) whose Q8.8 form leaves `−128 ≤ · < 128` (module doc).
    TexCoordOutOfRange(String),
    /// A `vt` line without `u`, or a value that is not a finite number (as written).
    BadTexCoord(String),
    /// A texture index beyond the `vt` lines so far, or 0 (as written).
    TexIndexOutOfRange(i64),
    /// A face corner without a texture index where other corners have one.
    MissingTexCoord,
    /// No face corner names a texture coordinate.
    NoTexCoords,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: ", self.line)?;
        match &self.kind {
            ObjErrorKind::BadNumber(s) => write!(f, "cannot parse number {s:?}"),
            ObjErrorKind::TooFewCoordinates => write!(f, "vertex needs x, y and z"),
            ObjErrorKind::NonFinite => write!(f, "vertex coordinate is not finite"),
            ObjErrorKind::TooFewVertices => write!(f, "face needs at least 3 vertices"),
            ObjErrorKind::ZeroIndex => write!(f, "vertex index 0 is not valid (OBJ is 1-based)"),
            ObjErrorKind::IndexOutOfRange(i) => write!(f, "vertex index {i} out of range"),
            ObjErrorKind::Io(e) => write!(f, "{e}"),
            ObjErrorKind::FileTooLarge(p) => write!(
                f,
                "{p}: file is longer than the OBJ reader's limit of {MAX_OBJ_BYTES} bytes"
            ),
            ObjErrorKind::TooManyVertices => {
                write!(
                    f,
                    "more than {MAX_OBJ_VERTICES} vertices (the core's u16 indices)"
                )
            }
            ObjErrorKind::TooManyFaces => write!(f, "more than {MAX_OBJ_FACES} faces"),
            ObjErrorKind::FaceTooLarge => {
                write!(f, "face with more than {MAX_FACE_VERTICES} vertices")
            }
            ObjErrorKind::TexCoordOutOfRange(s) => write!(
                f,
                "texture coordinate {s} is outside the core's Q8.8 range (u and 1 − v must lie \
                 in −128 ≤ · < 128)"
            ),
            ObjErrorKind::BadTexCoord(s) => {
                write!(f, "texture coordinate {s:?} is not a finite number")
            }
            ObjErrorKind::TexIndexOutOfRange(i) => {
                write!(f, "texture coordinate index {i} out of range")
            }
            ObjErrorKind::MissingTexCoord => write!(
                f,
                "a face corner has no texture coordinate index while others have one"
            ),
            ObjErrorKind::NoTexCoords => write!(f, "no face names texture coordinates (vt)"),
        }
    }
}

impl std::error::Error for ObjError {}

/// Parses OBJ text.
pub fn parse_obj(text: &str) -> Result<ObjMesh, ObjError> {
    let mut mesh = ObjMesh::default();
    // The `vt` lines read so far: their Q8.8 pair or their problem.
    let mut vts: Vec<Result<TexCoord, ObjError>> = Vec::new();
    // Corners naming a `vt`, corners naming none.
    let (mut named, mut unnamed) = (0usize, None::<usize>);
    for (n, raw) in text.lines().enumerate() {
        let line = n + 1;
        let err = |kind| ObjError { line, kind };
        let content = raw.split('#').next().unwrap_or("");
        let mut words = content.split_whitespace();
        match words.next() {
            Some("v") => {
                let mut c = [0.0f64; 3];
                for slot in c.iter_mut() {
                    let w = words
                        .next()
                        .ok_or_else(|| err(ObjErrorKind::TooFewCoordinates))?;
                    *slot = w
                        .parse::<f64>()
                        .map_err(|_| err(ObjErrorKind::BadNumber(w.to_string())))?;
                    if !slot.is_finite() {
                        return Err(err(ObjErrorKind::NonFinite));
                    }
                }
                if mesh.vertices.len() >= MAX_OBJ_VERTICES {
                    return Err(err(ObjErrorKind::TooManyVertices));
                }
                mesh.vertices.push(c);
            }
            Some("vt") => {
                if vts.len() >= MAX_OBJ_TEX_COORDS {
                    return Err(err(ObjErrorKind::TooManyVertices));
                }
                vts.push(tex_coord(words.next(), words.next()).map_err(err));
            }
            Some("f") => {
                if mesh.polygons.len() >= MAX_OBJ_FACES {
                    return Err(err(ObjErrorKind::TooManyFaces));
                }
                let mut poly = Vec::new();
                for w in words {
                    if poly.len() >= MAX_FACE_VERTICES {
                        return Err(err(ObjErrorKind::FaceTooLarge));
                    }
                    let mut fields = w.split('/');
                    let first = fields.next().unwrap_or("");
                    let i: i64 = first
                        .parse()
                        .map_err(|_| err(ObjErrorKind::BadNumber(first.to_string())))?;
                    // count ≤ MAX_OBJ_VERTICES; |i| as u64 cannot overflow (i64::MIN included).
                    let count = mesh.vertices.len() as u64;
                    let magnitude = i.unsigned_abs();
                    let idx = match i {
                        0 => return Err(err(ObjErrorKind::ZeroIndex)),
                        _ if magnitude > count => {
                            return Err(err(ObjErrorKind::IndexOutOfRange(i)))
                        }
                        i if i > 0 => magnitude - 1,
                        _ => count - magnitude,
                    };
                    poly.push(idx as usize);
                    match fields.next().filter(|t| !t.is_empty()) {
                        None => {
                            unnamed.get_or_insert(line);
                        }
                        Some(t) => {
                            named += 1;
                            let uv = t
                                .parse::<i64>()
                                .map_err(|_| err(ObjErrorKind::BadNumber(t.to_string())))
                                .and_then(|i| {
                                    let count = vts.len() as u64;
                                    let m = i.unsigned_abs();
                                    match i {
                                        _ if i == 0 || m > count => {
                                            Err(err(ObjErrorKind::TexIndexOutOfRange(i)))
                                        }
                                        i if i > 0 => vts[(m - 1) as usize].clone(),
                                        _ => vts[(count - m) as usize].clone(),
                                    }
                                });
                            match uv {
                                Ok(uv) if mesh.uv_error.is_none() => mesh.uvs.push(uv),
                                Ok(_) => {}
                                Err(e) => {
                                    mesh.uv_error.get_or_insert(e);
                                }
                            }
                        }
                    }
                }
                if poly.len() < 3 {
                    return Err(err(ObjErrorKind::TooFewVertices));
                }
                mesh.polygons.push(poly);
            }
            _ => {}
        }
    }
    if let (Some(line), true) = (unnamed, named > 0) {
        mesh.uv_error.get_or_insert(ObjError {
            line,
            kind: ObjErrorKind::MissingTexCoord,
        });
    }
    if mesh.uv_error.is_some() || named == 0 {
        mesh.uvs = Vec::new();
    }
    Ok(mesh)
}

/// Most `vt` lines read (each kept until the faces are read): as many as vertices.
pub const MAX_OBJ_TEX_COORDS: usize = MAX_OBJ_VERTICES;

/// A `vt` line's `u` and `v` (absent: 0) in Q8.8 (module doc: the core's `v` is `1 − v`).
fn tex_coord(u: Option<&str>, v: Option<&str>) -> Result<TexCoord, ObjErrorKind> {
    let value = |w: &str| match w.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(ObjErrorKind::BadTexCoord(w.to_string())),
    };
    let u_text = u.ok_or_else(|| ObjErrorKind::BadTexCoord(String::new()))?;
    let v_text = v.unwrap_or("0");
    let (u, v) = (value(u_text)?, value(v_text)?);
    let q8 = |x: f64, written: String| {
        let q = (x * TEX_ONE as f64).round();
        if (i16::MIN as f64..=i16::MAX as f64).contains(&q) {
            Ok(q as i16)
        } else {
            Err(ObjErrorKind::TexCoordOutOfRange(written))
        }
    };
    Ok([
        q8(u, format!("u = {u_text}"))?,
        q8(1.0 - v, format!("v = {v_text}"))?,
    ])
}

/// Reads and parses an OBJ file of at most [`MAX_OBJ_BYTES`] (see the module doc).
pub fn load_obj(path: impl AsRef<Path>) -> Result<ObjMesh, ObjError> {
    use std::io::Read;
    let path = path.as_ref();
    let io = |e: std::io::Error| ObjError {
        line: 0,
        kind: ObjErrorKind::Io(format!("{}: {e}", path.display())),
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(MAX_OBJ_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_OBJ_BYTES {
        return Err(ObjError {
            line: 0,
            kind: ObjErrorKind::FileTooLarge(path.display().to_string()),
        });
    }
    let text = String::from_utf8(bytes).map_err(|e| ObjError {
        line: 0,
        kind: ObjErrorKind::Io(format!("{}: not UTF-8 text: {e}", path.display())),
    })?;
    parse_obj(&text)
}

impl ObjMesh {
    /// The texture coordinates, one per polygon corner, or why there are none (module doc).
    pub fn texture_coordinates(&self) -> Result<&[TexCoord], ObjError> {
        match &self.uv_error {
            Some(e) => Err(e.clone()),
            None if self.uvs.is_empty() => Err(ObjError {
                line: 0,
                kind: ObjErrorKind::NoTexCoords,
            }),
            None => Ok(&self.uvs),
        }
    }

    /// Number of triangles after fanning every polygon (`Σ (n − 2)`).
    pub fn triangle_count(&self) -> usize {
        self.polygons.iter().map(|p| p.len() - 2).sum()
    }

    /// Signed volume `Σ P_0·(P_i × P_{i+1})/6` over the fanned polygons: positive when the
    /// faces wind counter-clockwise seen from outside.
    pub fn signed_volume(&self) -> f64 {
        let v = &self.vertices;
        let mut s = 0.0;
        for p in &self.polygons {
            let a = v[p[0]];
            for w in p[1..].windows(2) {
                let (b, c) = (v[w[0]], v[w[1]]);
                s += a[0] * (b[1] * c[2] - b[2] * c[1])
                    + a[1] * (b[2] * c[0] - b[0] * c[2])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]);
            }
        }
        s / 6.0
    }

    /// Axis-aligned bounding box `(min, max)`.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &self.vertices {
            for i in 0..3 {
                lo[i] = lo[i].min(v[i]);
                hi[i] = hi[i].max(v[i]);
            }
        }
        (lo, hi)
    }

    /// The core's tables: vertices mapped through `f` and rounded to I16F16 (saturating),
    /// concatenated indices, per-polygon sizes. `None` if there are more than 65 536 vertices
    /// or a polygon with more than 255.
    pub fn to_zscan(
        &self,
        f: impl Fn([f64; 3]) -> [f64; 3],
    ) -> Option<(Vec<Vec3>, Vec<u16>, Vec<u8>)> {
        if self.vertices.len() > 65_536 || self.polygons.iter().any(|p| p.len() > 255) {
            return None;
        }
        let vs = self
            .vertices
            .iter()
            .map(|&v| {
                let [x, y, z] = f(v);
                Vec3::new(
                    Coord::saturating_from_num(x),
                    Coord::saturating_from_num(y),
                    Coord::saturating_from_num(z),
                )
            })
            .collect();
        let is = self.polygons.iter().flatten().map(|&i| i as u16).collect();
        let ss = self.polygons.iter().map(|p| p.len() as u8).collect();
        Some((vs, is, ss))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms_negative_indices_comments() {
        let text = "# a quad and a triangle\nv 0 0 0\nv 1 0 0 # trailing\nv 1 1 0 1.0\nv 0 1 0\n\
                    vt 0 0\nvn 0 0 1\ng g1\nf 1/1/1 2/1/1 3//1 4\nf -4 -3 -1\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.polygons, vec![vec![0, 1, 2, 3], vec![0, 1, 3]]);
        assert_eq!(m.triangle_count(), 3);
    }

    #[test]
    fn errors_have_line_numbers() {
        let e = parse_obj("v 0 0 0\nv 1 0\n").unwrap_err();
        assert_eq!((e.line, e.kind), (2, ObjErrorKind::TooFewCoordinates));
        let e = parse_obj("v 0 0 0\n\nf 1 2 3\n").unwrap_err();
        assert_eq!((e.line, e.kind), (3, ObjErrorKind::IndexOutOfRange(2)));
        let e = parse_obj("v 0 0 x\n").unwrap_err();
        assert_eq!(e.kind, ObjErrorKind::BadNumber("x".into()));
        let e = parse_obj("v 0 0 0\nf 1 0 1\n").unwrap_err();
        assert_eq!((e.line, e.kind), (2, ObjErrorKind::ZeroIndex));
        let e = parse_obj("v 0 0 0\nf 1 1\n").unwrap_err();
        assert_eq!(e.kind, ObjErrorKind::TooFewVertices);
        let e = parse_obj("v 0 0 0\nf -2 1 1\n").unwrap_err();
        assert_eq!(e.kind, ObjErrorKind::IndexOutOfRange(-2));
        assert_eq!(
            parse_obj("v nan 0 0").unwrap_err().kind,
            ObjErrorKind::NonFinite
        );
        assert!(load_obj("/nonexistent.obj")
            .unwrap_err()
            .to_string()
            .contains("line 0"));
    }

    /// `vt` in `v/vt` and `v/vt/vn` corners (relative indices too) become per-corner Q8.8
    /// coordinates, `u` as written and `v` as `1 − v`, rounded to 1/256.
    #[test]
    fn texture_coordinates_per_corner() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n\
                    vt 0.25 0.75 0\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf 1/-4 3/-2 4/-1\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.uv_error, None);
        assert_eq!(
            m.texture_coordinates().unwrap(),
            &[
                [0, 256],
                [256, 256],
                [256, 0],
                [64, 64],
                [0, 256],
                [256, 0],
                [64, 64]
            ]
        );
        // 1/512 rounds away from zero; the range's ends: u = −128 and 1 − v = 127.99609375.
        let m =
            parse_obj("v 0 0 0\nvt 0.001953125 1\nvt -128 -126.99609375\nf 1/1 1/2 1/1\n").unwrap();
        assert_eq!(m.uvs, vec![[1, 0], [-32768, 32767], [1, 0]]);
        // Without `vt` corners there are none, and the mesh loads as before.
        let m = parse_obj("v 0 0 0\nvt 5 5\nf 1 1 1\n").unwrap();
        assert_eq!(m.polygons.len(), 1);
        assert_eq!(
            m.texture_coordinates().unwrap_err().kind,
            ObjErrorKind::NoTexCoords
        );
    }

    /// Texture coordinate problems keep their line and stop only their own use: the mesh
    /// loads, [`ObjMesh::texture_coordinates`] names the first problem.
    #[test]
    fn texture_coordinate_errors_have_line_numbers() {
        let check = |text: &str, line: usize, kind: ObjErrorKind, words: &str| {
            let m = parse_obj(text).unwrap();
            assert!(m.uvs.is_empty(), "{text}");
            let e = m.texture_coordinates().unwrap_err();
            assert_eq!((e.line, &e.kind), (line, &kind), "{text}");
            assert!(e.to_string().contains(words), "{e}");
        };
        let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        check(
            &format!("{tri}vt 0 0\nvt 128 0\nf 1/1 2/2 3/1\n"),
            5,
            ObjErrorKind::TexCoordOutOfRange("u = 128".into()),
            "u = 128 is outside the core's Q8.8 range",
        );
        check(
            &format!("{tri}vt 0 129.5\nf 1/1 2/1 3/1\n"),
            4,
            ObjErrorKind::TexCoordOutOfRange("v = 129.5".into()),
            "1 − v must lie in −128 ≤ · < 128",
        );
        check(
            &format!("{tri}vt 0 nan\nf 1/1 2/1 3/1\n"),
            4,
            ObjErrorKind::BadTexCoord("nan".into()),
            "not a finite number",
        );
        check(
            &format!("{tri}vt 0 0\nf 1/1 2/2 3/1\n"),
            5,
            ObjErrorKind::TexIndexOutOfRange(2),
            "texture coordinate index 2 out of range",
        );
        check(
            &format!("{tri}vt 0 0\nf 1/1 2/1 3/1\nf 1 2 3\n"),
            6,
            ObjErrorKind::MissingTexCoord,
            "no texture coordinate index while others have one",
        );
        // An out-of-range `vt` that no face names is no problem.
        let m = parse_obj(&format!("{tri}vt 500 0\nvt 0 0\nf 1/2 2/2 3/2\n")).unwrap();
        assert_eq!(m.uvs, vec![[0, 256]; 3]);
    }

    /// Issue "hostile inputs" #5: `i64::MIN` (and other huge indices) are out of range, with
    /// no overflow negating them.
    #[test]
    fn extreme_indices_are_out_of_range() {
        for i in [i64::MIN, i64::MIN + 1, i64::MAX, -4, 4] {
            let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {i}\n");
            let e = parse_obj(&text).unwrap_err();
            assert_eq!(
                (e.line, e.kind),
                (4, ObjErrorKind::IndexOutOfRange(i)),
                "{i}"
            );
        }
        let m = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 2 -1\n").unwrap();
        assert_eq!(m.polygons, vec![vec![0, 1, 2]]);
    }

    /// Issue "hostile inputs" #6: an endless file stops at the size limit; counts are limited
    /// before they are allocated.
    #[test]
    fn limits_are_checked_before_allocating() {
        let e = load_obj("/dev/zero").unwrap_err();
        assert_eq!(e.kind, ObjErrorKind::FileTooLarge("/dev/zero".into()));
        assert!(e.to_string().contains(&MAX_OBJ_BYTES.to_string()), "{e}");
        let many = "v 0 0 0\n".repeat(MAX_OBJ_VERTICES + 1);
        let e = parse_obj(&many).unwrap_err();
        assert_eq!(
            (e.line, e.kind),
            (MAX_OBJ_VERTICES + 1, ObjErrorKind::TooManyVertices)
        );
        let big_face = format!("v 0 0 0\nf{}\n", " 1".repeat(MAX_FACE_VERTICES + 1));
        assert_eq!(
            parse_obj(&big_face).unwrap_err().kind,
            ObjErrorKind::FaceTooLarge
        );
        let ok_face = format!("v 0 0 0\nf{}\n", " 1".repeat(MAX_FACE_VERTICES));
        assert_eq!(
            parse_obj(&ok_face).unwrap().polygons[0].len(),
            MAX_FACE_VERTICES
        );
        let faces = format!("v 0 0 0\n{}", "f 1 1 1\n".repeat(MAX_OBJ_FACES + 1));
        let e = parse_obj(&faces).unwrap_err();
        assert_eq!(
            (e.line, e.kind),
            (MAX_OBJ_FACES + 2, ObjErrorKind::TooManyFaces)
        );
    }
}
