//! Transparency in 8-bit colour (`zscan::raster::triangle::transparency`): the screen door's
//! pixels against an independent account of the mask, in every method that draws it; the
//! blended pixels against the blend table's lookups of the z-buffer's layers; the blend table
//! against a nearest-colour search written here; the refusals, in words.

use zscan::geometry::camera::Camera;
use zscan::geometry::vector::Vec3;
use zscan::lighting::Material;
use zscan::output::{BlendError, BlendTable, DepthBuffer, Framebuffer, Lut, BLEND_ENTRIES};
use zscan::raster::triangle::{Opacity, OpacityError, ShadeMode};
use zscan::render::{
    render_scene, BandScratch, PolygonRows, PreparedVertex, RenderError, RenderStats, Renderer,
    TransparencyKind,
};
use zscan::scene::{Intensities, Object, Scene, Transparency};
use zscan::visibility::Visibility;
use zscan_host::core_render::{
    render_compact_picture, render_picture, render_visible, scene_of, to_core,
};
use zscan_host::failures::{camera, soup_object, v};
use zscan_host::scenes::standard_scene;

use embedded_graphics::pixelcolor::Rgb888;

/// The 4×4 Bayer matrix, written out here from its recursive definition
/// `B2 = [[0, 2], [3, 1]]`, `B4 = [[4·B2 + 0, 4·B2 + 2], [4·B2 + 3, 4·B2 + 1]]`.
fn bayer(x: i32, y: i32) -> u8 {
    let b2 = |x: i32, y: i32| [[0u8, 2], [3, 1]][(y & 1) as usize][(x & 1) as usize];
    4 * b2(x, y) + b2(x >> 1, y >> 1)
}

/// Whether an object of screen-door opacity `k` covers pixel `(x, y)`: `k` of every 16.
fn in_mask(k: u8, x: i32, y: i32) -> bool {
    bayer(x, y) < k
}

/// The whole-frame z-buffer's picture and 32-bit depths (`render_scene`).
fn z_buffer(scene: &Scene<'_>) -> Result<(Vec<u8>, Vec<u32>), RenderError> {
    let vp = *scene.camera.viewport();
    let (w, h) = (vp.width, vp.height);
    let renderer = Renderer::for_scene(scene)?;
    let n = w as usize * h as usize;
    let (mut px, mut zs) = (vec![0u8; n], vec![0u32; n]);
    let mut frame = Framebuffer::new(&mut px, w, h).unwrap();
    let mut depth = DepthBuffer::new(&mut zs, w, h).unwrap();
    let vertices: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let mut scratch = vec![PreparedVertex::default(); vertices.max(1)];
    let mut stats = RenderStats::default();
    render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats)?;
    Ok((px, zs))
}

/// The banded z-buffer's picture (`render_in_bands`, bands of `rows`).
fn z_bands(scene: &Scene<'_>, rows: u16) -> Result<Vec<u8>, RenderError> {
    let vp = *scene.camera.viewport();
    let renderer = Renderer::for_scene(scene)?;
    let vertices: usize = scene.objects.iter().map(|o| o.mesh.vertices().len()).sum();
    let polygons: usize = scene.objects.iter().map(|o| o.mesh.polygon_count()).sum();
    let mut scratch = vec![PreparedVertex::default(); vertices.max(1)];
    let mut table = vec![PolygonRows::default(); polygons];
    let band_scratch = BandScratch {
        vertices: &mut scratch,
        polygons: &mut table,
    };
    let (px, _, _) =
        render_picture::<u16, 4>(&renderer, (vp.width, vp.height), Some(rows), band_scratch)?;
    Ok(px)
}

/// The expected picture of `objects` with screen-door opacities `opacity[i]` (`None`
/// opaque): at each pixel, the opaque z-buffer picture of the objects whose mask covers it
/// (a screen-door object draws nothing at a pixel outside its mask, and is opaque inside it).
fn screen_door_reference(objects: &[Object<'_>], opacity: &[Option<u8>], cam: Camera) -> Vec<u8> {
    let vp = *cam.viewport();
    let w = vp.width as i32;
    let masked: Vec<usize> = (0..objects.len())
        .filter(|&i| opacity[i].is_some())
        .collect();
    // One opaque picture per subset of the screen-door objects present.
    let pictures: Vec<Vec<u8>> = (0..1u32 << masked.len())
        .map(|subset| {
            let present: Vec<Object<'_>> = (0..objects.len())
                .filter(|&i| {
                    masked
                        .iter()
                        .position(|&m| m == i)
                        .is_none_or(|bit| subset >> bit & 1 == 1)
                })
                .map(|i| {
                    let mut o = objects[i];
                    o.transparency = Transparency::Opaque;
                    o
                })
                .collect();
            z_buffer(&scene_of(&present, cam)).unwrap().0
        })
        .collect();
    (0..pictures[0].len())
        .map(|p| {
            let (x, y) = (p as i32 % w, p as i32 / w);
            let subset = masked.iter().enumerate().fold(0, |s, (bit, &i)| {
                s | ((in_mask(opacity[i].unwrap(), x, y) as usize) << bit)
            });
            pictures[subset][p]
        })
        .collect()
}

/// With `opacity` set on the objects it names.
fn with_opacity<'a>(objects: &[Object<'a>], opacity: &[Option<u8>]) -> Vec<Object<'a>> {
    objects
        .iter()
        .zip(opacity)
        .map(|(o, k)| {
            let mut o = *o;
            if let Some(k) = k {
                o.transparency = Transparency::ScreenDoor(Opacity::new(*k).unwrap());
            }
            o
        })
        .collect()
}

/// The standard bunny (not convex: its own farther faces show through the holes) as a screen
/// door of every opacity, plain and dithered, exact and fast Gouraud: the z-buffer, whole and
/// in bands, draws exactly the mask's pixels of the opaque picture, the background elsewhere.
#[test]
fn screen_door_bunny_is_the_mask_of_the_opaque_picture() {
    let core = to_core(&standard_scene("bunny").unwrap()).unwrap();
    let mut covered = 0usize;
    for k in [0u8, 1, 5, 8, 13, 16] {
        for (shade, dither) in [
            (ShadeMode::GouraudExact, false),
            (ShadeMode::GouraudExact, true),
            (ShadeMode::GouraudFast, false),
            (ShadeMode::Flat, true),
        ] {
            let mut o = core.object(shade).unwrap();
            o.dither = dither;
            o.ramp = zscan::raster::triangle::LuminanceRamp {
                first: 0,
                levels: 40,
            };
            let objects = [o];
            let want = screen_door_reference(&objects, &[Some(k)], core.camera);
            let doors = with_opacity(&objects, &[Some(k)]);
            let scene = scene_of(&doors, core.camera);
            let (got, _) = z_buffer(&scene).unwrap();
            assert_eq!(got, want, "opacity {k} {shade:?} dither {dither}");
            assert_eq!(z_bands(&scene, 16).unwrap(), want, "bands, opacity {k}");
            covered += got.iter().filter(|&&p| p != 0).count();
        }
    }
    assert!(covered > 50_000, "{covered}");
}

/// Three overlapping soups (a backdrop, then two screen doors of different opacities, drawn in
/// either scene order): every method that draws the z-buffer's picture draws the reference,
/// and Warnock's refuses in words.
#[test]
fn screen_doors_in_every_method() {
    let back = [v(-3.0, -2.0, -2.0), v(3.0, -2.0, -2.0), v(0.0, 2.5, -2.0)];
    let mid = [v(-2.5, -1.5, 0.0), v(2.0, -1.0, 0.2), v(-0.5, 2.0, -0.3)];
    let front = [v(-1.0, -2.0, 1.0), v(2.5, 0.0, 1.2), v(0.0, 1.5, 0.8)];
    let (ia, la) = ([0u16, 1, 2], [200u8]);
    let (lb, lc) = ([120u8], [60u8]);
    let cam = camera(96, 72);
    for order in [[0usize, 1, 2], [0, 2, 1]] {
        let soups = [
            soup_object(&back, &ia, &la),
            soup_object(&mid, &ia, &lb),
            soup_object(&front, &ia, &lc),
        ];
        let objects: Vec<Object<'_>> = order.iter().map(|&i| soups[i]).collect();
        let opacity: Vec<Option<u8>> = order
            .iter()
            .map(|&i| [None, Some(6), Some(11)][i])
            .collect();
        let want = screen_door_reference(&objects, &opacity, cam);
        let doors = with_opacity(&objects, &opacity);
        let scene = scene_of(&doors, cam);
        let renderer = Renderer::for_scene(&scene).unwrap();
        assert_eq!(z_buffer(&scene).unwrap().0, want, "{order:?}");
        for rows in [1, 7, 72] {
            assert_eq!(z_bands(&scene, rows).unwrap(), want, "bands {rows}");
        }
        let (compact, _, _) = render_compact_picture::<u16, 4>(&renderer, (96, 72), 8).unwrap();
        assert_eq!(compact, want, "compact bands {order:?}");
        for method in [Visibility::Painter, Visibility::ScanLine] {
            let (got, _) = render_visible(&renderer, (96, 72), method, Some(64), 8).unwrap();
            assert_eq!(got, want, "{method} {order:?}");
        }
        // Back faces alone draw in scene order: right when it is far to near.
        if order == [0, 1, 2] {
            let (got, _) =
                render_visible(&renderer, (96, 72), Visibility::BackFace, None, 1).unwrap();
            assert_eq!(got, want, "back faces");
        }
        let err = render_visible(&renderer, (96, 72), Visibility::Warnock, None, 1).unwrap_err();
        let object = order
            .iter()
            .position(|&i| i == 1)
            .unwrap()
            .min(order.iter().position(|&i| i == 2).unwrap());
        assert_eq!(
            err,
            RenderError::TransparencyRefused {
                object: Some(object),
                kind: TransparencyKind::ScreenDoor,
                method: "Warnock's subdivision"
            }
            .into()
        );
        let words = err.to_string();
        assert!(
            words.contains(&format!("object {object}")) && words.contains("Warnock"),
            "{words}"
        );
        // Both masks show at some pixels, and the backdrop through both at others.
        assert!(want.contains(&60) && want.contains(&120) && want.contains(&200));
    }
}

/// The entries of a blend table of `alpha/256` over `lut`.
fn table(lut: &Lut<Rgb888>, alpha: u16) -> Box<[u8; BLEND_ENTRIES]> {
    let mut entries: Box<[u8; BLEND_ENTRIES]> = vec![0u8; BLEND_ENTRIES]
        .into_boxed_slice()
        .try_into()
        .unwrap();
    BlendTable::build(lut, alpha, &mut entries).unwrap();
    entries
}

/// A palette of 256 scattered colours (a fixed linear congruence), so that nearest-colour
/// ties and far mixes both occur.
fn scattered_palette() -> Lut<Rgb888> {
    let mut lut = Lut::filled(Rgb888::new(0, 0, 0));
    let mut s = 12345u32;
    for i in 0..=255u8 {
        s = s.wrapping_mul(1_103_515_245).wrapping_add(12_345);
        let c = |k: u32| ((s >> k) & 0xF0) as u8; // 16 values a channel: many ties
        lut.set(i, Rgb888::new(c(4), c(12), c(20)));
    }
    lut
}

/// Every entry of the table is the palette's nearest colour to the rounded mix, the lowest
/// index on ties (a search written here, in `i64`), at several opacities; past 256 refused.
#[test]
fn blend_table_is_the_nearest_palette_entry_to_the_mix() {
    use embedded_graphics::pixelcolor::RgbColor;
    let lut = scattered_palette();
    let rgb: Vec<[i64; 3]> = lut
        .entries()
        .iter()
        .map(|c| [c.r() as i64, c.g() as i64, c.b() as i64])
        .collect();
    for alpha in [0u16, 1, 77, 128, 256] {
        let t = table(&lut, alpha);
        let t = BlendTable::from_entries(&t);
        for s in (0..256).step_by(3) {
            for d in (0..256).step_by(5) {
                let mix: Vec<i64> = (0..3)
                    .map(|k| {
                        let a = alpha as i64;
                        // Round half up: ⌊x + 1/2⌋ of (a·s + (256 − a)·d)/256.
                        (a * rgb[s][k] + (256 - a) * rgb[d][k] + 128).div_euclid(256)
                    })
                    .collect();
                let dist = |i: usize| -> i64 { (0..3).map(|k| (rgb[i][k] - mix[k]).pow(2)).sum() };
                let want = (0..256).min_by_key(|&i| (dist(i), i)).unwrap();
                assert_eq!(
                    t.get(s as u8, d as u8) as usize,
                    want,
                    "alpha {alpha} ({s}, {d})"
                );
            }
        }
    }
    let mut entries = vec![0u8; BLEND_ENTRIES];
    let entries: &mut [u8; BLEND_ENTRIES] = entries.as_mut_slice().try_into().unwrap();
    let err = BlendTable::build(&lut, 257, entries).unwrap_err();
    assert_eq!(err, BlendError::AlphaPastOne { alpha: 257 });
    assert!(err.to_string().contains("257/256"));
    assert_eq!(Opacity::new(17), Err(OpacityError { given: 17 }));
    assert!(Opacity::new(17).unwrap_err().to_string().contains("17"));
}

/// A backdrop and two blended soups, one nearer than the other, in any scene order: each
/// pixel is the table's lookups of the z-buffer's layers, far to near: the opaque picture
/// under, then each blended soup where its opaque picture is nearer than the opaque depth.
#[test]
fn blended_pixels_are_the_table_lookups_of_the_layers() {
    let back = [v(-3.0, -2.0, -2.0), v(3.0, -2.0, -2.0), v(0.0, 2.5, -2.0)];
    let far = [v(-2.5, -1.5, -0.5), v(2.0, -1.0, -0.5), v(-0.5, 2.0, -0.5)];
    let near = [v(-1.0, -2.0, 1.0), v(2.5, 0.0, 1.0), v(0.0, 1.5, 1.0)];
    let (ia, la, lb, lc) = ([0u16, 1, 2], [200u8], [120u8], [60u8]);
    let cam = camera(96, 72);
    let lut = scattered_palette();
    let (ta, tb) = (table(&lut, 90), table(&lut, 200));
    let (ta, tb) = (BlendTable::from_entries(&ta), BlendTable::from_entries(&tb));
    let backdrop = soup_object(&back, &ia, &la);
    let (mut a, mut b) = (soup_object(&far, &ia, &lb), soup_object(&near, &ia, &lc));
    // The floor of the backdrop's picture: both soups blend over the backdrop, and a part
    // of the far one over the background.
    let (under, zu) = z_buffer(&scene_of(&[backdrop], cam)).unwrap();
    let layer = |o: Object<'_>| z_buffer(&scene_of(&[backdrop, o], cam)).unwrap();
    let ((src_a, za), (src_b, zb)) = (layer(a), layer(b));
    let want: Vec<u8> = (0..under.len())
        .map(|p| {
            let mut px = under[p];
            if za[p] != zu[p] {
                px = ta.get(src_a[p], px);
            }
            if zb[p] != zu[p] {
                px = tb.get(src_b[p], px);
            }
            px
        })
        .collect();
    a.transparency = Transparency::Blended(ta);
    b.transparency = Transparency::Blended(tb);
    let mut blended_pixels = 0;
    for objects in [[backdrop, a, b], [b, a, backdrop], [a, backdrop, b]] {
        let scene = scene_of(&objects, cam);
        let (got, depth) = z_buffer(&scene).unwrap();
        assert_eq!(got, want);
        // Blended objects store no depth: the opaque depths remain.
        assert_eq!(depth, zu);
        let renderer = Renderer::for_scene(&scene).unwrap();
        for rows in [1, 9, 72] {
            assert_eq!(z_bands(&scene, rows).unwrap(), want, "bands {rows}");
            let (compact, _, _) =
                render_compact_picture::<u32, 4>(&renderer, (96, 72), rows).unwrap();
            assert_eq!(compact, want, "compact bands {rows}");
        }
        blended_pixels = (0..want.len()).filter(|&p| want[p] != under[p]).count();
    }
    // Both soups blended somewhere, and over each other.
    let both = (0..want.len())
        .filter(|&p| za[p] != zu[p] && zb[p] != zu[p])
        .count();
    assert!(
        blended_pixels > 1000 && both > 300,
        "{blended_pixels} {both}"
    );
}

/// Blended objects refused by every method that cannot order them, screen doors by Warnock's
/// and both on a core-lit Phong object, each naming the object and the method.
#[test]
fn refusals_name_the_object_and_the_method() {
    let tri = [v(-1.0, -1.0, 0.0), v(1.0, -1.0, 0.0), v(0.0, 1.0, 0.0)];
    let (ia, la) = ([0u16, 1, 2], [200u8]);
    let cam = camera(32, 24);
    let entries = table(&Lut::<Rgb888>::GREY, 128);
    let t = BlendTable::from_entries(&entries);
    let opaque = soup_object(&tri, &ia, &la);
    let mut blended = opaque;
    blended.transparency = Transparency::Blended(t);
    let objects = [opaque, blended];
    let scene = scene_of(&objects, cam);
    let renderer = Renderer::for_scene(&scene).unwrap();
    for (method, words) in [
        (Visibility::BackFace, "back faces alone"),
        (Visibility::Painter, "the painter"),
        (Visibility::ScanLine, "the scan-line"),
        (Visibility::Warnock, "Warnock's subdivision"),
    ] {
        let err = render_visible(&renderer, (32, 24), method, None, 4).unwrap_err();
        assert_eq!(
            err,
            RenderError::TransparencyRefused {
                object: Some(1),
                kind: TransparencyKind::Blended,
                method: words
            }
            .into()
        );
        let text = err.to_string();
        assert!(
            text.starts_with("object 1 is blended") && text.contains(words),
            "{text}"
        );
    }
    // The z-buffer's frames draw it.
    assert!(z_buffer(&scene).is_ok());
    assert!(render_compact_picture::<u16, 4>(&renderer, (32, 24), 4).is_ok());

    // A core-lit Phong object, screen door or blended: refused by the z-buffer, by name, and
    // when drawn alone.
    let normals = [Vec3::from_int(0, 0, 1); 3];
    let mut phong = opaque;
    phong.intensities = Intensities::Lit {
        material: Material::from_thousandths(200, 700, 300, 20),
        normals: &normals,
    };
    phong.shade = ShadeMode::Phong;
    for (transparency, kind) in [
        (
            Transparency::ScreenDoor(Opacity::new(7).unwrap()),
            TransparencyKind::ScreenDoor,
        ),
        (Transparency::Blended(t), TransparencyKind::Blended),
    ] {
        phong.transparency = transparency;
        let objects = [opaque, phong];
        let scene = scene_of(&objects, cam);
        let refused = |object| RenderError::TransparencyRefused {
            object,
            kind,
            method: "Phong shading",
        };
        assert_eq!(z_buffer(&scene).unwrap_err(), refused(Some(1)));
        let renderer = Renderer::for_scene(&scene).unwrap();
        let (mut px, mut zs) = (vec![0u8; 32 * 24], vec![0u16; 32 * 24]);
        let mut frame = Framebuffer::new(&mut px, 32, 24).unwrap();
        let mut depth = DepthBuffer::new(&mut zs, 32, 24).unwrap();
        let mut scratch = vec![PreparedVertex::default(); 3];
        let err = renderer
            .renderer()
            .draw_object(
                &phong,
                &mut scratch,
                &mut frame,
                &mut depth,
                &mut RenderStats::default(),
            )
            .unwrap_err();
        assert_eq!(err, refused(None));
        assert!(err.to_string().starts_with("the object is"), "{err}");
    }
}
