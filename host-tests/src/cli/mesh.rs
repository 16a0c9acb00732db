//! `zscan mesh IN.obj|.stl|.ply -o mesh.rs [--centre] [--turn-y DEG] [--scale S | --fit F]`:
//! writes a Rust module of `static` tables for a device to `include!`, so that it computes
//! nothing at start:
//! - `VERTICES: [Vec3; N]`, the placed positions rounded to I16F16 (`round(v · 65536)`, half
//!   away from zero; a coordinate past the core's `±1024` is an error naming the vertex);
//! - `INDICES: [u16; K]`, the polygons' vertex numbers as the file winds them (one triangle per
//!   source row through `triangle_indices` for triangle meshes), with `SIZES: [u8; M]` when the
//!   polygons' sizes differ;
//! - `NORMALS: [Vec3; N]`, the area-weighted unit vertex normals, exactly what
//!   [`Mesh::vertex_normals`] computes on the device (for `Intensities::Lit`);
//! - `MESH: Mesh<'static>`, validated at compile time;
//! - `FACTS: MeshFacts<'static>`, the planner's facts ([`MeshFacts::of`]: bounds, rounding
//!   guard, convexity certificate with a creased mesh's face pairs as `static` tables).
//!
//! - `UVS: [TexCoord; K]`, when the source gives texture coordinates for every face corner (an
//!   OBJ file's `vt`, read by [`crate::obj`]: Q8.8, the core's `v` is `1 − v`), one per index,
//!   and `MESH` carries them (`Mesh::with_uvs`); the header says why when there are none (the
//!   PLY reader skips `s`/`t`/`u`/`v` properties, STL has none).
//!
//! Simplification (`--cluster N`, before placement): [`crate::cluster`], vertex clustering on
//! an `N × N × N` grid, for displays too small for every edge (`examples/flash-mesh`'s coarse
//! bunny, `--cluster 6`).
//!
//! Placement ([`crate::scenes::place`]): `--centre` centres the bounding box on the origin
//! (again after a turn), `--turn-y` turns about `+y` by degrees, then `--scale` multiplies or
//! `--fit` scales the mesh to SCENES.md's "fit to F" (its height on the standard camera's
//! screen). `zscan mesh host-tests/meshes/bunny.obj --centre --turn-y 90 --fit 0.7` gives the
//! standard bunny's tables (`host-tests/tests/mesh_module.rs` draws them).
//!
//! Readers: OBJ ([`crate::obj`]), STL and ASCII PLY ([`crate::mesh_files`], which says why no
//! parsing crate).
use super::CliError;
use crate::obj::ObjMesh;
use crate::scenes::{place, Placement, Size};
use std::fmt::Write as _;
use std::path::PathBuf;
use zscan::geometry::mesh::{Mesh, PolygonSizes};
use zscan::geometry::vector::Vec3;
use zscan::visibility::{Convexity, MeshFacts};

/// Arguments of `zscan mesh`.
#[derive(clap::Args, Debug)]
pub struct MeshArgs {
    /// The mesh file: `.obj`, `.stl` (ASCII or binary) or `.ply` (ASCII).
    pub input: PathBuf,
    /// The Rust module to write.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Simplify first: cluster the vertices on an N × N × N grid of the bounding box
    /// (N in 2..=256; `zscan_host::cluster`), for small displays.
    #[arg(long, value_name = "N")]
    pub cluster: Option<u32>,
    /// Centre the bounding box on the origin (again after `--turn-y`).
    #[arg(long)]
    pub centre: bool,
    /// Turn about +y by this many degrees (right-hand rule), after centring.
    #[arg(long, value_name = "DEG")]
    pub turn_y: Option<f64>,
    /// Multiply every coordinate by S (last).
    #[arg(long, value_name = "S", conflicts_with = "fit")]
    pub scale: Option<f64>,
    /// Scale so that the mesh is F of the screen height of SCENES.md's standard camera (last).
    #[arg(long, value_name = "F")]
    pub fit: Option<f64>,
}

/// Runs `zscan mesh`.
pub fn run(args: MeshArgs) -> Result<(), CliError> {
    let mut mesh = crate::mesh_files::load_mesh(&args.input)?;
    if let Some(n) = args.cluster {
        mesh = crate::cluster::cluster(&mesh, n)?;
    }
    let placement = placement(&args)?;
    let name = args
        .input
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let text = mesh_source(&mesh, &placement, &format!("{name}{}", flags(&args)))?;
    std::fs::write(&args.output, &text)
        .map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    crate::outln!("{} ({} bytes)", args.output.display(), text.len())?;
    Ok(())
}

/// The placement the flags ask for, or what is wrong with them.
pub fn placement(args: &MeshArgs) -> Result<Placement, String> {
    let finite = |what: &str, v: Option<f64>| match v {
        Some(x) if !x.is_finite() || x <= 0.0 => {
            Err(format!("{what} {x}: must be a positive finite number"))
        }
        _ => Ok(v),
    };
    let size = match (finite("--scale", args.scale)?, finite("--fit", args.fit)?) {
        (Some(s), _) => Size::Scale(s),
        (_, Some(f)) => Size::Fit(f),
        _ => Size::Keep,
    };
    if let Some(d) = args.turn_y.filter(|d| !d.is_finite()) {
        return Err(format!("--turn-y {d}: must be a finite number of degrees"));
    }
    Ok(Placement {
        centre: args.centre,
        turn_y_degrees: args.turn_y,
        size,
    })
}

/// The flags as the header repeats them.
fn flags(args: &MeshArgs) -> String {
    let mut s = String::new();
    if let Some(n) = args.cluster {
        let _ = write!(s, " --cluster {n}");
    }
    if args.centre {
        s += " --centre";
    }
    let mut add = |flag: &str, v: Option<f64>| {
        if let Some(v) = v {
            let _ = write!(s, " --{flag} {v}");
        }
    };
    add("turn-y", args.turn_y);
    add("scale", args.scale);
    add("fit", args.fit);
    s
}

/// Rows of numbers, `per_line` to a line.
fn rows<T: std::fmt::Debug>(out: &mut String, items: &[T], per_line: usize) {
    for chunk in items.chunks(per_line) {
        let row: Vec<String> = chunk
            .iter()
            .map(|x| format!("{x:?}").replace(' ', ""))
            .collect();
        let _ = writeln!(out, "    {},", row.join(", "));
    }
}

/// The Rust module of `mesh` placed by `placement` (module doc); `source` names the input and
/// flags in the header.
pub fn mesh_source(mesh: &ObjMesh, placement: &Placement, source: &str) -> Result<String, String> {
    let (placed, scale) = place(&mesh.vertices, placement);
    let mut bits = Vec::with_capacity(placed.len());
    for (i, v) in placed.iter().enumerate() {
        let mut b = [0i32; 3];
        for (k, &c) in v.iter().enumerate() {
            b[k] = super::export::to_i16f16(c).map_err(|e| format!("vertex {i}: {e}"))?;
        }
        bits.push(b);
    }
    let vertices: Vec<Vec3> = bits
        .iter()
        .map(|b| Vec3::from_bits(b[0], b[1], b[2]))
        .collect();
    let indices: Vec<u16> = mesh.polygons.iter().flatten().map(|&i| i as u16).collect();
    let sizes: Vec<u8> = mesh.polygons.iter().map(|p| p.len() as u8).collect();
    let uniform = match sizes.first() {
        Some(&n) if sizes.iter().all(|&s| s == n) => Some(n),
        None => Some(3),
        _ => None,
    };
    let core_sizes = uniform.map_or(PolygonSizes::PerPolygon(&sizes), PolygonSizes::Uniform);
    let core = Mesh::new(&vertices, &indices, core_sizes).map_err(|e| {
        format!(
            "the placed mesh is not one the core draws ({e:?}): coordinates must lie within \
             ±1024 (use --scale or --fit)"
        )
    })?;
    let mut normals = vec![Vec3::ZERO; vertices.len()];
    core.vertex_normals(&mut normals)
        .map_err(|e| format!("vertex normals: {e:?}"))?;
    let uvs = mesh.texture_coordinates();
    let mut words = vec![0u32; MeshFacts::words_needed(&core)];
    let facts = MeshFacts::of(&core, &mut words).map_err(|e| format!("planner facts: {e}"))?;

    let n = vertices.len();
    let mut out = String::new();
    let kind = match uniform {
        Some(3) => "triangles".to_string(),
        Some(k) => format!("polygons of {k} vertices"),
        None => "polygons".to_string(),
    };
    let convexity = match facts.convexity {
        Convexity::Convex { twins } => format!(
            "may be convex (an edge table of {} corners, checked per view)",
            twins.len()
        ),
        Convexity::NotConvex => "not convex".to_string(),
    };
    let _ = write!(
        out,
        "// Mesh module generated by `zscan mesh {source}`\n\
         // (zscan-host {}). Do not edit.\n\
         //\n\
         // {n} vertices, {} {kind}; scale {scale} applied after placement.\n\
         // Planner facts: {convexity}.\n\
         // Texture coordinates: {}.\n\
         // Tables in I16F16 raw bits (round(v * 65536)); polygons counter-clockwise seen from the\n\
         // front, as the file winds them.\n\n",
        env!("CARGO_PKG_VERSION"),
        mesh.polygons.len(),
        match &uvs {
            Ok(t) => format!("{} in UVS (Q8.8, v = 1 - the file's v)", t.len()),
            Err(e) if e.kind == crate::obj::ObjErrorKind::NoTexCoords => {
                "none in the source".to_string()
            }
            Err(e) => format!("not written ({e})"),
        },
    );
    let vec3s = "zscan::geometry::mesh::vec3s_from_bits";
    let _ = writeln!(out, "/// Vertex positions in the model frame.");
    let _ = writeln!(
        out,
        "pub static VERTICES: [zscan::geometry::vector::Vec3; {n}] = {vec3s}(&["
    );
    rows(&mut out, &bits, 4);
    let _ = writeln!(out, "]);\n");
    let _ = writeln!(out, "/// The polygons' vertex indices, concatenated.");
    if uniform == Some(3) {
        let triangles: Vec<[u16; 3]> = indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        let _ = writeln!(
            out,
            "pub static INDICES: [u16; {}] = zscan::geometry::mesh::triangle_indices(&[",
            indices.len()
        );
        rows(&mut out, &triangles, 6);
        let _ = writeln!(out, "]);\n");
    } else {
        let _ = writeln!(out, "pub static INDICES: [u16; {}] = [", indices.len());
        rows(&mut out, &indices, 16);
        let _ = writeln!(out, "];\n");
    }
    let sizes_expr = match uniform {
        Some(k) => format!("zscan::geometry::mesh::PolygonSizes::Uniform({k})"),
        None => {
            let _ = writeln!(out, "/// Each polygon's vertex count.");
            let _ = writeln!(out, "pub static SIZES: [u8; {}] = [", sizes.len());
            rows(&mut out, &sizes, 32);
            let _ = writeln!(out, "];\n");
            "zscan::geometry::mesh::PolygonSizes::PerPolygon(&SIZES)".to_string()
        }
    };
    let _ = writeln!(
        out,
        "/// Area-weighted unit vertex normals (`Mesh::vertex_normals` of [`MESH`]), for lit objects."
    );
    let _ = writeln!(
        out,
        "pub static NORMALS: [zscan::geometry::vector::Vec3; {n}] = {vec3s}(&["
    );
    let normal_bits: Vec<[i32; 3]> = normals.iter().map(|v| v.bits()).collect();
    rows(&mut out, &normal_bits, 4);
    let _ = writeln!(out, "]);\n");
    // The mesh, with its coordinates when it has them.
    let ok = match &uvs {
        Ok(t) => {
            let _ = writeln!(
                out,
                "/// Texture coordinates in Q8.8, one per index (`Mesh::with_uvs`)."
            );
            let _ = writeln!(
                out,
                "pub static UVS: [zscan::geometry::mesh::TexCoord; {}] = [",
                t.len()
            );
            rows(&mut out, t, 8);
            let _ = writeln!(out, "];\n");
            "match mesh.with_uvs(&UVS) {\n            \
             Ok(mesh) => mesh,\n            \
             Err(_) => panic!(\"the texture coordinates are not one per index\"),\n        \
             }"
        }
        Err(_) => "mesh",
    };
    let _ = writeln!(out, "/// The mesh, validated at compile time.");
    let _ = writeln!(
        out,
        "pub static MESH: zscan::geometry::mesh::Mesh<'static> =\n    \
         match zscan::geometry::mesh::Mesh::new(&VERTICES, &INDICES, {sizes_expr}) {{\n        \
         Ok(mesh) => {ok},\n        \
         Err(_) => panic!(\"the generated tables do not form a valid mesh\"),\n    }};\n"
    );
    let convexity = match facts.convexity {
        Convexity::NotConvex => "zscan::visibility::Convexity::NotConvex".to_string(),
        Convexity::Convex { twins } => {
            let _ = writeln!(
                out,
                "/// Each corner's twin (the corner of the reverse edge, `NO_TWIN` for none): the\n\
                 /// planner's edge table, checked at every use."
            );
            let _ = writeln!(out, "static TWINS: [u32; {}] = [", twins.len());
            rows(&mut out, twins, 16);
            let _ = writeln!(out, "];\n");
            "zscan::visibility::Convexity::Convex { twins: &TWINS }".to_string()
        }
    };
    let _ = writeln!(
        out,
        "/// The planner's facts of [`MESH`] (`MeshFacts::of`), computed once here.\n\
         pub static FACTS: zscan::visibility::MeshFacts<'static> = zscan::visibility::MeshFacts {{\n    \
         convexity: {convexity},\n    \
         bounds: {:?},\n}};",
        facts.bounds
    );
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(scale: Option<f64>, fit: Option<f64>, turn_y: Option<f64>) -> MeshArgs {
        MeshArgs {
            input: "in.obj".into(),
            output: "out.rs".into(),
            cluster: None,
            centre: true,
            turn_y,
            scale,
            fit,
        }
    }

    /// A unit cube turned 30° about x and 40° about y in `f64`: rounded to I16F16 it is
    /// convex as designed but creased as stored (as SCENES.md's cube).
    fn turned_cube() -> ObjMesh {
        let (ax, ay) = (30f64.to_radians(), 40f64.to_radians());
        let vertices = (0..8)
            .map(|k| {
                let p = [0, 1, 2].map(|a| if k >> a & 1 == 0 { -0.5 } else { 0.5 });
                let (y, z) = (
                    p[1] * ax.cos() - p[2] * ax.sin(),
                    p[1] * ax.sin() + p[2] * ax.cos(),
                );
                [
                    p[0] * ay.cos() + z * ay.sin(),
                    y,
                    -p[0] * ay.sin() + z * ay.cos(),
                ]
            })
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let polygons = quads
            .iter()
            .flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]])
            .collect();
        ObjMesh {
            vertices,
            polygons,
            ..ObjMesh::default()
        }
    }

    #[test]
    fn a_creased_mesh_keeps_its_certificate_tables() {
        let keep = Placement {
            centre: false,
            turn_y_degrees: None,
            size: Size::Keep,
        };
        let text = mesh_source(&turned_cube(), &keep, "cube.obj").unwrap();
        // The certificate as the core computes it from the written vertices.
        let rows = |name: &str| {
            let at = text.find(&format!("pub static {name}")).unwrap();
            text[at..]
                .lines()
                .skip(1)
                .take_while(|l| !l.starts_with(']'))
                .collect::<String>()
        };
        let numbers: Vec<i32> = rows("VERTICES")
            .split(|c: char| !(c.is_ascii_digit() || c == '-'))
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().unwrap())
            .collect();
        let vertices: Vec<Vec3> = numbers
            .chunks(3)
            .map(|c| Vec3::from_bits(c[0], c[1], c[2]))
            .collect();
        let indices: Vec<u16> = turned_cube()
            .polygons
            .iter()
            .flatten()
            .map(|&i| i as u16)
            .collect();
        let mesh = Mesh::new(&vertices, &indices, PolygonSizes::Uniform(3)).unwrap();
        let mut words = vec![0u32; MeshFacts::words_needed(&mesh)];
        let facts = MeshFacts::of(&mesh, &mut words).unwrap();
        let Convexity::Convex { twins } = facts.convexity else {
            panic!("the turned cube should keep its edge table");
        };
        assert!(text.contains(&format!("static TWINS: [u32; {}]", twins.len())));
        assert!(text.contains("Convexity::Convex { twins: &TWINS }"));
        assert!(text.contains("triangle_indices(&["));
    }

    /// An OBJ file's `vt` corners become a `UVS` table that `MESH` carries; without them the
    /// header says so and `MESH` has none.
    #[test]
    fn texture_coordinates_are_written_when_the_source_has_them() {
        let quad = crate::obj::parse_obj(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 2 0\nvt 2 0.5\n\
             f 1/1 2/2 3/3\nf 1/1 3/3 4/1\n",
        )
        .unwrap();
        let text = mesh_source(&quad, &STANDARD_KEEP, "quad.obj").unwrap();
        assert!(
            text.contains(
                "pub static UVS: [zscan::geometry::mesh::TexCoord; 6] = [\n    \
                 [0,256], [512,256], [512,128], [0,256], [512,128], [0,256],\n];"
            ),
            "{text}"
        );
        assert!(
            text.contains("Ok(mesh) => match mesh.with_uvs(&UVS) {"),
            "{text}"
        );
        assert!(text.contains("// Texture coordinates: 6 in UVS"), "{text}");
        assert_eq!(text.matches("pub static MESH").count(), 1, "{text}");
        let bare = ObjMesh {
            uvs: Vec::new(),
            ..quad.clone()
        };
        let text = mesh_source(&bare, &STANDARD_KEEP, "quad.obj").unwrap();
        assert!(!text.contains("UVS"), "{text}");
        assert!(text.contains("// Texture coordinates: none in the source."));
    }

    #[test]
    fn mixed_polygons_get_a_sizes_table() {
        let pyramid = ObjMesh {
            vertices: vec![
                [0., 0., 0.],
                [1., 0., 0.],
                [1., 0., 1.],
                [0., 0., 1.],
                [0.5, 1., 0.5],
            ],
            polygons: vec![
                vec![0, 1, 2, 3],
                vec![0, 4, 1],
                vec![1, 4, 2],
                vec![2, 4, 3],
                vec![3, 4, 0],
            ],
            ..ObjMesh::default()
        };
        let text = mesh_source(&pyramid, &STANDARD_KEEP, "pyramid.obj").unwrap();
        assert!(
            text.contains("pub static SIZES: [u8; 5] = [\n    4, 3, 3, 3, 3,\n];"),
            "{text}"
        );
        assert!(text.contains("PolygonSizes::PerPolygon(&SIZES)"));
        assert!(text.contains("pub static INDICES: [u16; 16] = ["));
    }

    const STANDARD_KEEP: Placement = Placement {
        centre: false,
        turn_y_degrees: None,
        size: Size::Keep,
    };

    #[test]
    fn bad_placements_are_refused_in_words() {
        let cube = turned_cube();
        let huge = Placement {
            size: Size::Scale(1e4),
            ..STANDARD_KEEP
        };
        let e = mesh_source(&cube, &huge, "cube.obj").unwrap_err();
        assert!(e.contains("±1024"), "{e}");
        let beyond = Placement {
            size: Size::Scale(1e6),
            ..STANDARD_KEEP
        };
        let e = mesh_source(&cube, &beyond, "cube.obj").unwrap_err();
        assert!(e.starts_with("vertex 0:") && e.contains("I16F16"), "{e}");
        for (a, what) in [
            (args(Some(-1.0), None, None), "--scale -1"),
            (args(None, Some(f64::NAN), None), "--fit NaN"),
            (args(None, None, Some(f64::INFINITY)), "--turn-y inf"),
        ] {
            let e = placement(&a).unwrap_err();
            assert!(e.starts_with(what), "{e}");
        }
        assert_eq!(
            placement(&args(None, Some(0.7), Some(90.0))).unwrap(),
            crate::scenes::STANDARD_BUNNY
        );
    }
}
