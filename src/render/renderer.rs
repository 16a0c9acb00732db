//! [`Renderer`]: what is fixed for a frame (the camera's projector, frustum and view
//! transform, the lights in the observer frame), built once from a camera; [`SceneRenderer`]:
//! a renderer built from a scene, holding that scene, so that the scene is the one source of
//! the camera and lights it is drawn with.
//!
//! Every entry that draws a whole scene ([`render_scene`](super::render_scene),
//! [`render_in_bands`](super::render_in_bands), the methods of
//! [`visibility`](crate::visibility)) takes a [`SceneRenderer`] and no separate scene: a scene
//! cannot be drawn with another scene's camera or lights. Objects may change from frame to
//! frame under a fixed camera and lights ([`SceneRenderer::with_objects`], no new set-up);
//! a new camera or new lights need a new [`SceneRenderer`]. A bare [`Renderer`] draws single
//! objects ([`Renderer::draw_object`]) with the lights it was given
//! ([`Renderer::with_lights`]).

use super::RenderError;
use crate::clip::frustum::Frustum;
use crate::geometry::camera::Camera;
use crate::geometry::matrix::Affine3;
use crate::project::Projector;
use crate::scene::{Object, Scene};
use crate::shade::lighting::{Illumination, Light};

/// Everything fixed for a frame: the camera's projector, frustum and view transform, and the
/// lights in the observer frame.
#[derive(Debug, Clone, Copy)]
pub struct Renderer<const S: u32 = 4> {
    pub(super) camera: Camera,
    pub(super) projector: Projector<S>,
    pub(super) frustum: Frustum,
    pub(super) view: Affine3,
    pub(super) illumination: Illumination,
}

impl<const S: u32> Renderer<S> {
    /// The renderer of `camera` at `S` sub-pixel bits, with the default guard band. Its
    /// lighting is ambient only, at full intensity (`I_a = 255`, no lights): lit objects show
    /// `k_a·255` until [`with_lights`](Self::with_lights) sets the scene's lights.
    pub fn new(camera: &Camera) -> Result<Self, RenderError> {
        let illumination = Illumination::observer(255, &[]).map_err(RenderError::Lighting)?;
        Self::build(camera, illumination)
    }

    /// The renderer of `camera` lit by `illumination` (built in place: the renderer is
    /// hundreds of bytes, and a copy costs thousands of Cortex-M instructions).
    #[inline(always)]
    fn build(camera: &Camera, illumination: Illumination) -> Result<Self, RenderError> {
        // A `match`, not `map_err(…)?`: converting the whole `Result` moved the 56-byte
        // projector through two unaligned temporaries, three byte-wise copies (Cortex-M4
        // `setup` 10,462 instructions against 9,794 with the match).
        let projector = match Projector::new(camera) {
            Ok(p) => p,
            Err(e) => return Err(RenderError::Projection(e)),
        };
        Ok(Renderer {
            camera: *camera,
            projector,
            frustum: Frustum::new::<S>(camera, Frustum::DEFAULT_GUARD)
                .map_err(RenderError::Clip)?,
            view: *camera.view_transform(),
            illumination,
        })
    }

    /// This renderer with ambient intensity `ambient` and `lights` (world frame, at most
    /// [`MAX_LIGHTS`](crate::shade::lighting::MAX_LIGHTS)) for lit objects.
    pub fn with_lights(mut self, ambient: u8, lights: &[Light]) -> Result<Self, RenderError> {
        self.illumination =
            Illumination::new(&self.camera, ambient, lights).map_err(RenderError::Lighting)?;
        Ok(self)
    }

    /// The camera this renderer projects for.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The projector the vertex stage places vertices with (for the planner, which must place
    /// them as the renderer does).
    pub(crate) fn projector(&self) -> &Projector<S> {
        &self.projector
    }

    /// The frustum the vertex stage takes outcodes against.
    pub(crate) fn frustum(&self) -> &Frustum {
        &self.frustum
    }

    /// The object's model → observer transform.
    pub(super) fn model_view(&self, object: &Object<'_>) -> Result<Affine3, RenderError> {
        object
            .transform
            .then(&self.view)
            .map_err(RenderError::Transform)
    }
}

impl Renderer {
    /// The renderer of `scene` at the default 4 sub-pixel bits, holding the scene: its
    /// camera, ambient intensity and lights, set up once, and its objects, drawn by
    /// [`render_scene`](super::render_scene) and the other scene entries.
    /// `Renderer::for_scene(&scene)?` needs no type annotation; other precisions use
    /// [`SceneRenderer::<S>::new`](SceneRenderer::new).
    pub fn for_scene<'a>(scene: &Scene<'a>) -> Result<SceneRenderer<'a, 4>, RenderError> {
        SceneRenderer::new(scene)
    }
}

/// A scene and its [`Renderer`], built from the scene's camera, ambient intensity and lights:
/// what every scene entry ([`render_scene`](super::render_scene),
/// [`render_in_bands`](super::render_in_bands), [`visibility`](crate::visibility)) draws, so
/// that a scene is always drawn with its own camera and lights (module doc).
///
/// ```
/// use zscan::prelude::*;
///
/// let lens = Lens::new(Angle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
/// let up = Vec3::from_int(0, 1, 0);
/// let camera = Camera::look_at(Vec3::from_int(0, 0, 4), Vec3::ZERO, up, lens, Viewport::new(32, 24))?;
/// let lights = [Light::Directional { toward: Vec3::from_int(0, 0, 1), intensity: 200 }];
/// let cube = Object::new(unit_cube());
/// let scene = Scene { camera, objects: &[cube], background: 0, ambient: 30, lights: &lights };
/// let renderer = Renderer::for_scene(&scene)?; // camera and lights set up once
/// let (mut pixels, mut depths) = ([0u8; 32 * 24], [0u16; 32 * 24]);
/// let mut frame = Framebuffer::new(&mut pixels, 32, 24)?;
/// let mut depth = DepthBuffer::new(&mut depths, 32, 24)?;
/// let mut scratch = [PreparedVertex::default(); 8];
/// for turn in 0..3 {
///     // Each frame its objects, under the same camera and lights.
///     let mut moved = cube;
///     moved.transform = Affine3::builder().rotate_y(Angle::from_degrees(20 * turn)).build()?;
///     let objects = [moved];
///     let frame_renderer = renderer.with_objects(&objects);
///     let mut stats = RenderStats::default();
///     render_scene(&frame_renderer, &mut frame, &mut depth, &mut scratch, &mut stats)?;
///     assert!(stats.pixels_covered > 0);
/// }
/// # Ok::<(), zscan::Error>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct SceneRenderer<'a, const S: u32 = 4> {
    renderer: Renderer<S>,
    scene: Scene<'a>,
}

impl<'a, const S: u32> SceneRenderer<'a, S> {
    /// The renderer of `scene` at `S` sub-pixel bits ([`Renderer::for_scene`] at the default
    /// 4 bits): its camera, ambient intensity and lights (at most
    /// [`MAX_LIGHTS`](crate::shade::lighting::MAX_LIGHTS)) set up once.
    pub fn new(scene: &Scene<'a>) -> Result<Self, RenderError> {
        let illumination = Illumination::new(&scene.camera, scene.ambient, scene.lights)
            .map_err(RenderError::Lighting)?;
        Ok(SceneRenderer {
            renderer: Renderer::build(&scene.camera, illumination)?,
            scene: *scene,
        })
    }

    /// The same camera, lights and background drawing `objects` instead (a frame of an
    /// animation: no set-up runs again).
    pub fn with_objects<'b>(&self, objects: &'b [Object<'b>]) -> SceneRenderer<'b, S>
    where
        'a: 'b,
    {
        SceneRenderer {
            renderer: self.renderer,
            scene: Scene {
                objects,
                ..self.scene
            },
        }
    }

    /// The scene this renderer draws.
    pub fn scene(&self) -> &Scene<'a> {
        &self.scene
    }

    /// Its renderer (camera and lights set up), for drawing its objects one by one.
    pub fn renderer(&self) -> &Renderer<S> {
        &self.renderer
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::camera::{Lens, Viewport};
    use crate::geometry::fixed::Coord;
    use crate::geometry::generators::unit_cube;
    use crate::geometry::trig::Angle;
    use crate::geometry::vector::Vec3;
    use crate::render::{render_in_bands, render_scene, BandScratch, PreparedVertex, RenderStats};
    use crate::scene::Intensities;
    use crate::shade::lighting::Material;
    use crate::target::{DepthBuffer, Framebuffer};
    use crate::visibility::{
        render_back_faces, render_painter, Normal, PainterMemory, SplitPolicy,
    };
    use crate::visibility::{render_scan_lines, ScanLineMemory, StoredTriangle};

    const W: u16 = 32;
    const H: u16 = 24;
    const N: usize = W as usize * H as usize;

    /// A flat-lit cube seen from `eye`, lit by a point light at `light`.
    fn camera(eye: Vec3) -> Camera {
        let lens = Lens::new(Angle::from_degrees(50), Coord::lit("0.5"), Coord::lit("20"));
        let up = Vec3::from_int(0, 1, 0);
        Camera::look_at(eye, Vec3::ZERO, up, lens, Viewport::new(W, H)).unwrap()
    }

    fn cube() -> Object<'static> {
        let mut cube = Object::new(unit_cube());
        cube.transform = Affine3::builder()
            .translate(Vec3::from_bits(-1 << 15, -1 << 15, -1 << 15))
            .build()
            .unwrap();
        cube.intensities = Intensities::Lit {
            material: Material::from_thousandths(100, 800, 0, 1),
            normals: &[],
        };
        cube.shade = crate::shade::span_writer::ShadeMode::Flat;
        cube
    }

    /// The picture of `objects` drawn one by one, through the depth buffer, with a renderer
    /// built from `camera`, `ambient` and `lights` directly (not from a scene).
    fn reference(
        camera: &Camera,
        ambient: u8,
        lights: &[Light],
        objects: &[Object<'_>],
    ) -> [u8; N] {
        let r = Renderer::<4>::new(camera)
            .unwrap()
            .with_lights(ambient, lights)
            .unwrap();
        let (mut pixels, mut depths) = ([0u8; N], [0u16; N]);
        let mut frame = Framebuffer::new(&mut pixels, W, H).unwrap();
        let mut depth = DepthBuffer::new(&mut depths, W, H).unwrap();
        frame.clear(0);
        depth.clear();
        let mut scratch = [PreparedVertex::default(); 8];
        for o in objects {
            let stats = &mut RenderStats::default();
            r.draw_object(o, &mut scratch, &mut frame, &mut depth, stats)
                .unwrap();
        }
        pixels
    }

    /// The pictures of every scene entry for `renderer`: render_scene, render_in_bands,
    /// back faces alone, the painter and the scan-line.
    fn entries(renderer: &SceneRenderer<'_, 4>) -> [[u8; N]; 5] {
        let mut out = [[0u8; N]; 5];
        let mut scratch = [PreparedVertex::default(); 8];
        let stats = &mut RenderStats::default();
        let mut depths = [0u16; N];
        {
            let mut frame = Framebuffer::new(&mut out[0], W, H).unwrap();
            let mut depth = DepthBuffer::new(&mut depths, W, H).unwrap();
            render_scene(renderer, &mut frame, &mut depth, &mut scratch, stats).unwrap();
        }
        let (mut band, mut band_depth) = ([0u8; W as usize * 5], [0u16; W as usize * 5]);
        let copy = |picture: &mut [u8; N], f: &mut Framebuffer<'_>| {
            for (y, row) in f.rows() {
                let at = y as usize * W as usize;
                picture[at..at + row.len()].copy_from_slice(row);
            }
            Ok::<(), RenderError>(())
        };
        let scratch_b = BandScratch {
            vertices: &mut scratch,
            polygons: &mut [],
        };
        render_in_bands(
            renderer,
            (&mut band, &mut band_depth),
            (W, H, 5),
            scratch_b,
            stats,
            |f, _| copy(&mut out[1], f),
        )
        .unwrap();
        {
            let mut frame = Framebuffer::new(&mut out[2], W, H).unwrap();
            render_back_faces(renderer, &mut frame, &mut scratch, stats).unwrap();
        }
        let (mut triangles, mut order) = ([StoredTriangle::DEFAULT; 16], [0u32; 16]);
        {
            let mut frame = Framebuffer::new(&mut out[3], W, H).unwrap();
            let mut normals = [Normal::DEFAULT; 16];
            let memory = PainterMemory {
                triangles: &mut triangles,
                order: &mut order,
                normals: &mut normals,
            };
            let policy = SplitPolicy::Budget(4);
            render_painter(renderer, &mut frame, &mut scratch, memory, policy, stats).unwrap();
        }
        let mut active = [0u32; 16];
        let memory = ScanLineMemory {
            triangles: &mut triangles,
            order: &mut order,
            active: &mut active,
            pixels: &mut band,
            depths: &mut band_depth,
        };
        render_scan_lines(renderer, (W, H, 5), &mut scratch, memory, stats, |f, _| {
            copy(&mut out[4], f)
        })
        .unwrap();
        out
    }

    /// The scene is the one source of the camera and lights it is drawn with: no entry takes a
    /// scene beside its renderer, so scene B cannot be drawn with the camera and lights of a
    /// renderer built for scene A (the mismatch the former `render_scene(&renderer, &scene,
    /// …)` allowed). Every entry draws its renderer's scene exactly as a renderer built from
    /// that scene's camera and lights draws its objects; scenes A and B differ, so an entry
    /// that used other parts would fail; and new objects under a renderer
    /// ([`SceneRenderer::with_objects`]) keep that renderer's camera and lights.
    #[test]
    fn scene_entries_draw_with_the_scenes_own_camera_and_lights() {
        let objects = [cube()];
        let (lights_a, lights_b) = (
            [Light::Point {
                position: Vec3::from_int(3, 4, 5),
                intensity: 255,
            }],
            [Light::Directional {
                toward: Vec3::from_int(-1, 0, 1),
                intensity: 120,
            }],
        );
        let a = Scene {
            camera: camera(Vec3::from_int(1, 1, 2)),
            objects: &objects,
            background: 0,
            ambient: 20,
            lights: &lights_a,
        };
        let b = Scene {
            camera: camera(Vec3::from_int(-2, 1, 1)),
            ambient: 60,
            lights: &lights_b,
            ..a
        };
        let picture_a = reference(&a.camera, a.ambient, a.lights, a.objects);
        let picture_b = reference(&b.camera, b.ambient, b.lights, b.objects);
        assert_ne!(picture_a, picture_b, "the two scenes must look different");
        assert!(picture_b.iter().filter(|&&p| p != 0).count() > 50);
        for (scene, picture) in [(&a, &picture_a), (&b, &picture_b)] {
            let renderer = Renderer::for_scene(scene).unwrap();
            assert_eq!(renderer.renderer().camera(), &scene.camera);
            for (entry, drawn) in entries(&renderer).iter().enumerate() {
                assert!(
                    drawn == picture,
                    "entry {entry} drew another camera or lights"
                );
            }
        }
        // Objects moved under A's renderer: A's camera and lights, the new objects.
        let mut moved = cube();
        moved.transform = Affine3::builder()
            .rotate_y(Angle::from_degrees(30))
            .build()
            .unwrap();
        let moved = [moved];
        let under_a = Renderer::for_scene(&a).unwrap();
        let under_a = under_a.with_objects(&moved);
        assert_eq!(under_a.scene().camera, a.camera);
        let expected = reference(&a.camera, a.ambient, a.lights, &moved);
        assert_ne!(expected, picture_a);
        assert!(entries(&under_a)[0] == expected);
    }
}
