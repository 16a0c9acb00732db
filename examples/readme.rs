//! The README's "Using the core" snippet as a program: a lit torus rendered into a 64 × 48
//! framebuffer and flushed to embedded-graphics' `MockDisplay`, then printed as text.
//!
//! ```text
//! cargo run --example readme
//! ```
//!
//! The part between the `[readme]` and `[/readme]` marker comments is quoted verbatim in
//! README.md (`host-tests/tests/readme_snippet.rs` checks that the two agree). It holds every
//! import the code needs and is the file's only module-level code besides `main`, whose own
//! imports are inside it: so the quoted part compiles on its own, as the whole `src/lib.rs` of
//! a crate with `zscan` and `embedded-graphics` 0.8 as dependencies.

// [readme]
use embedded_graphics::{draw_target::DrawTarget, pixelcolor::Rgb565};
use zscan::prelude::*;

const W: u16 = 64;
const H: u16 = 48;
const PIXELS: usize = W as usize * H as usize;
const N: (usize, usize) = torus_sizes(24, 12); // (vertices, indices) of the mesh

#[rustfmt::skip] // one step a line, as the README shows it
pub fn render(display: &mut impl DrawTarget<Color = Rgb565>) -> Result<RenderStats, zscan::Error> {
    let (mut vertices, mut indices, mut normals) = ([Vec3::ZERO; N.0], [0; N.1], [Vec3::ZERO; N.0]);
    let (major, minor) = (Coord::lit("1"), Coord::lit("0.4"));
    let mesh = torus(24, 12, major, minor, &mut vertices, &mut indices)?; // or tables in flash
    mesh.vertex_normals(&mut normals)?;
    let mut object = Object::new(mesh);
    object.transform = Affine3::builder().rotate_x(BinaryAngle::from_degrees(60)).build()?;
    let material = Material::from_thousandths(150, 600, 400, 20); // ambient, diffuse, specular
    object.intensities = Intensities::Lit { material, normals: &normals };
    object.shade = ShadeMode::Phong; // Flat, GouraudExact, GouraudFast, Phong
    let lights = [Light::Point { position: Vec3::from_int(-3, 4, 5), intensity: 230 }];
    let lens = Lens::new(BinaryAngle::from_degrees(45), Coord::lit("0.5"), Coord::lit("20"));
    let (eye, up) = (Vec3::from_int(0, 0, 4), Vec3::from_int(0, 1, 0));
    let camera = Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(W, H))?;
    let objects = [object];
    let scene = Scene { camera, objects: &objects, background: 0, ambient: 40, lights: &lights };

    let (mut pixels, mut depths) = ([0u8; PIXELS], [0u16; PIXELS]);
    let mut frame = Framebuffer::new(&mut pixels, W, H)?; // your memory: 1 byte per pixel
    let mut depth = DepthBuffer::new(&mut depths, W, H)?; // 2 bytes per pixel (u16)
    let renderer = Renderer::for_scene(&scene)?; // holds the scene, its camera and lights
    let mut scratch = [PreparedVertex::default(); N.0];
    let mut stats = RenderStats::default(); // or StatsWithoutWritten: no per-pixel count
    render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats)?;
    static LUT: Lut<Rgb565> = Lut::<Rgb565>::GREY; // 256 colours, in flash
    flush(&frame, &LUT, display, None).map_err(|_| zscan::Error::Display)?; // any DrawTarget
    Ok(stats)
}
// [/readme]

fn main() -> Result<(), Box<dyn std::error::Error>> {
    use embedded_graphics::{geometry::Point, mock_display::MockDisplay, pixelcolor::RgbColor};

    let mut display = MockDisplay::<Rgb565>::new();
    let stats = render(&mut display)?;
    // The display as text, one character per pixel, from dark to bright.
    let ramp = b" .:-=+*#%@";
    for y in 0..H as i32 {
        let row: String = (0..W as i32)
            .map(|x| {
                let g = display.get_pixel(Point::new(x, y)).map_or(0, |c| c.g()) as usize;
                ramp[g * (ramp.len() - 1) / 63] as char
            })
            .collect();
        println!("{row}");
    }
    println!("{stats:?}");
    if stats.pixels_covered == 0 {
        return Err("the torus covered no pixel".into());
    }
    Ok(())
}
