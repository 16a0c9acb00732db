//! The README's "Using the core" code block is the marked region of `examples/readme.rs`
//! (between the `// [readme]` and `// [/readme]` lines), character for character, so the
//! README shows code that compiles and runs (`cargo run --example readme`).

use std::path::Path;

/// The lines strictly between the line `open` and the line `close` of `text`.
fn between<'a>(text: &'a str, open: &str, close: &str) -> Vec<&'a str> {
    let mut lines = text.lines();
    assert!(
        lines.by_ref().any(|l| l.trim_end() == open),
        "no line {open:?}"
    );
    let region: Vec<&str> = lines
        .by_ref()
        .take_while(|l| l.trim_end() != close)
        .collect();
    region
}

#[test]
fn readme_block_is_the_example_region() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let example = std::fs::read_to_string(root.join("examples/readme.rs")).expect("example");
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let code = between(&example, "// [readme]", "// [/readme]");
    assert!(code.len() > 10, "the example's region is empty");
    // The README's block: the fenced `rust` block right after the marker comment.
    let after_marker = between(
        &readme,
        "<!-- quoted from examples/readme.rs -->",
        "<!-- end -->",
    );
    let fenced: Vec<&str> = after_marker
        .iter()
        .copied()
        .skip_while(|l| *l != "```rust")
        .skip(1)
        .take_while(|l| *l != "```")
        .collect();
    assert_eq!(
        fenced.join("\n"),
        code.join("\n"),
        "README.md's \"Using the core\" block differs from examples/readme.rs's marked region; \
         copy the region into the README"
    );
}

/// `zscan::prelude` and `embedded_graphics::prelude` glob-imported side by side: naming every
/// item of zscan's prelude (the `use self::{..}` in `preludes_glob_together` below) would not
/// compile if one of them were also an item of embedded-graphics' prelude (E0659, "ambiguous";
/// `Angle` was). The list is checked against `src/prelude.rs`, so that a new name is covered.
mod both_preludes {
    #[allow(unused_imports)]
    use embedded_graphics::prelude::*;
    #[allow(unused_imports)]
    use zscan::prelude::*;

    #[allow(unused_imports)]
    use self::{
        draw_plan as _, flush as _, mask_words_needed as _, pack_pages as _, page_bytes as _,
        plan as _, render_in_bands as _, render_scene as _, shade_table as _, shaded_index as _,
        torus as _, torus_normals as _, torus_sizes as _, torus_uvs as _, triangle_indices as _,
        unit_cube as _, uv_sphere as _, uv_sphere_normals as _, uv_sphere_sizes as _,
        uv_sphere_uvs as _, vec3s_from_bits as _, Affine3 as _, Affine3Builder as _,
        AppelCrossing as _, AppelEdge as _, AppelError as _, AppelScratch as _, AppelSegment as _,
        Attenuation as _, BandScratch as _, BandSink as _, BinaryAngle as _, BlendTable as _,
        Camera as _, CompactVertex as _, Cone as _, Coord as _, DepthBuffer as _, DepthValue as _,
        DisplaySink as _, DoubleBands as _, Error as _, FovAxis as _, Framebuffer as _,
        Intensities as _, Lens as _, Light as _, LineStyle as _, LuminanceRamp as _, Lut as _,
        Material as _, Mesh as _, MeshFacts as _, Object as _, Opacity as _, PlanMemory as _,
        PlanSizes as _, PolygonRows as _, PolygonSizes as _, PolygonTop as _, PreparedVertex as _,
        RenderStats as _, Renderer as _, Scene as _, ShadeMode as _, ShadeTable as _,
        StatsSink as _, StatsWithoutWritten as _, TexCoord as _, Texture as _, TextureMode as _,
        Texturing as _, Transparency as _, Vec3 as _, Viewport as _, VisibilityError as _,
        Wireframe as _,
    };

    /// The names above, as `src/prelude.rs` exports them.
    pub const NAMED: &[&str] = &[
        "flush",
        "mask_words_needed",
        "pack_pages",
        "page_bytes",
        "render_in_bands",
        "render_scene",
        "shaded_index",
        "torus",
        "torus_sizes",
        "unit_cube",
        "BandSink",
        "DisplaySink",
        "DoubleBands",
        "torus_normals",
        "uv_sphere_normals",
        "uv_sphere",
        "uv_sphere_sizes",
        "Affine3",
        "Affine3Builder",
        "AppelCrossing",
        "AppelEdge",
        "AppelError",
        "AppelScratch",
        "AppelSegment",
        "Attenuation",
        "BandScratch",
        "BinaryAngle",
        "Camera",
        "Cone",
        "Coord",
        "DepthBuffer",
        "DepthValue",
        "Error",
        "VisibilityError",
        "FovAxis",
        "Framebuffer",
        "Intensities",
        "Lens",
        "Light",
        "LineStyle",
        "Lut",
        "LuminanceRamp",
        "Material",
        "Mesh",
        "Object",
        "PolygonRows",
        "PolygonSizes",
        "PreparedVertex",
        "RenderStats",
        "Renderer",
        "Scene",
        "ShadeMode",
        "StatsSink",
        "StatsWithoutWritten",
        "Vec3",
        "Viewport",
        "Wireframe",
        "CompactVertex",
        "MeshFacts",
        "PlanMemory",
        "PlanSizes",
        "PolygonTop",
        "draw_plan",
        "plan",
        "triangle_indices",
        "vec3s_from_bits",
        "torus_uvs",
        "uv_sphere_uvs",
        "TexCoord",
        "shade_table",
        "ShadeTable",
        "Texture",
        "TextureMode",
        "Texturing",
        "BlendTable",
        "Opacity",
        "Transparency",
    ];
}

#[test]
fn preludes_glob_together() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let prelude = std::fs::read_to_string(root.join("src/prelude.rs")).expect("src/prelude.rs");
    // Every name of every `pub use` item (`a::b::Name;` or `a::{B, C};`), spread over lines.
    let mut exported: Vec<String> = Vec::new();
    let mut rest = prelude.as_str();
    while let Some(at) = rest.find("\npub use ") {
        let item = &rest[at + 9..];
        let end = item.find(';').expect("a `pub use` ends with `;`");
        let path = &item[..end];
        let names = match path.find('{') {
            Some(open) => &path[open + 1..path.rfind('}').expect("closing brace")],
            None => &path[path.rfind("::").map_or(0, |i| i + 2)..],
        };
        exported.extend(
            names
                .split(',')
                .map(|n| n.trim().rsplit(' ').next().unwrap_or("").to_string())
                .filter(|n| !n.is_empty()),
        );
        rest = &item[end..];
    }
    let mut named: Vec<String> = both_preludes::NAMED.iter().map(|s| s.to_string()).collect();
    exported.sort();
    named.sort();
    assert_eq!(
        exported, named,
        "src/prelude.rs and the list of host-tests/tests/readme_snippet.rs differ: add the new \
         names to both lists there"
    );
}
