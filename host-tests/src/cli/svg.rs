//! `zscan render --svg`: the visible pieces of the objects drawn with `wireframe = "appel"`
//! (the core's Appel method, `render::appel`) as a plain SVG, a vector output for plotters
//! and vector displays.
//!
//! The picture is the viewport, `width × height` pixels, `viewBox="0 0 width height"`. Each
//! piece is one `<line>` from its `from` to its `to` end point (the core's sub-pixel points,
//! rounded to the nearest `2^-S` pixel): the pixel `(x, y)` of the raster picture covers
//! `[x, x + 1) × [y, y + 1)` and its centre is the sub-pixel point `(x·2^S, y·2^S)`, so an
//! SVG coordinate is `c / 2^S + 0.5`, written with as many decimals as it needs (exact:
//! `2^S` divides a power of ten). Stroke: the `[lut]` colour of the object's `line_index`,
//! one pixel wide, round caps.

use super::render::{appel_pieces, LoadedScene, SUBPIXEL_BITS};
use embedded_graphics::pixelcolor::RgbColor;
use zscan::render::{AppelSegment, Renderer, Wireframe};
use zscan::scene::Object;

/// The SVG coordinate of sub-pixel coordinate `c`, exact (module doc).
pub fn svg_coordinate(c: i32) -> String {
    let unit = 1i64 << SUBPIXEL_BITS;
    let scaled = (2 * c as i64 + unit) * 10_000 / (2 * unit); // 10^4 / 2^S = 625: exact
    let (whole, frac) = (scaled.div_euclid(10_000), scaled.rem_euclid(10_000));
    let text = format!("{whole}.{frac:04}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The visible pieces of every Appel object of `scene`, in object order, with their object's
/// palette index.
pub fn appel_segments(
    scene: &LoadedScene,
) -> Result<Vec<(u8, AppelSegment<SUBPIXEL_BITS>)>, String> {
    let renderer = Renderer::<SUBPIXEL_BITS>::new(&scene.camera)
        .map_err(|e| format!("camera: {}", super::render::render_error_words(&e)))?;
    let objects: Vec<Object<'_>> = scene.core_objects(None)?;
    let mut out = Vec::new();
    let mut any = false;
    for (k, (object, prepared)) in objects.iter().zip(&scene.objects).enumerate() {
        if prepared.wireframe != Some(Wireframe::Appel) {
            continue;
        }
        any = true;
        let mut scratch = vec![Default::default(); object.mesh.vertices().len()];
        let index = prepared.line_index;
        appel_pieces(
            object,
            |memory, scratch| {
                renderer.appel_segments(object, scratch, memory, |s| out.push((index, *s)))
            },
            &mut scratch,
        )
        .map_err(|e| {
            format!(
                "object {} (wireframe \"appel\"): {}",
                k + 1,
                super::render::render_error_words(&e)
            )
        })?;
    }
    if !any {
        return Err(
            "--svg writes the objects drawn with wireframe = \"appel\": the scene has none".into(),
        );
    }
    Ok(out)
}

/// The SVG text of `scene`'s Appel pieces (module doc).
pub fn appel_svg(scene: &LoadedScene) -> Result<String, String> {
    let vp = *scene.camera.viewport();
    let mut text = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\">\n",
        w = vp.width,
        h = vp.height
    );
    let bg = scene.lut.get(scene.background);
    text += &format!(
        "<rect width=\"{}\" height=\"{}\" fill=\"#{:02x}{:02x}{:02x}\"/>\n",
        vp.width,
        vp.height,
        bg.r(),
        bg.g(),
        bg.b()
    );
    for (index, s) in appel_segments(scene)? {
        let c = scene.lut.get(index);
        text += &format!(
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#{:02x}{:02x}{:02x}\" \
             stroke-width=\"1\" stroke-linecap=\"round\"/>\n",
            svg_coordinate(s.from.x),
            svg_coordinate(s.from.y),
            svg_coordinate(s.to.x),
            svg_coordinate(s.to.y),
            c.r(),
            c.g(),
            c.b()
        );
    }
    text += "</svg>\n";
    Ok(text)
}
