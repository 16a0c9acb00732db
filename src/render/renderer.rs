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

use super::{RenderError, TargetBuffer};
use crate::clip::frustum::Frustum;
use crate::geometry::camera::Camera;
use crate::geometry::matrix::Affine3;
use crate::lighting::{Illumination, Light};
use crate::output::{DepthBuffer, DepthValue, Framebuffer};
use crate::project::Projector;
use crate::scene::{Object, Scene};

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

    /// [`RenderError::TargetSmallerThanViewport`] unless a `buffer` of `size` pixels holds the
    /// camera's viewport: as wide, and as tall unless it is a `band` (some rows by design).
    /// Every drawing entry checks its buffers (or the frame size it is given) with this before
    /// drawing, so that a short or narrow buffer is refused instead of cropping the picture.
    pub(crate) fn check_covers(
        &self,
        buffer: TargetBuffer,
        size: (u16, u16),
        band: bool,
    ) -> Result<(), RenderError> {
        let v = self.camera.viewport();
        if size.0 < v.width || (!band && size.1 < v.height) {
            return Err(RenderError::TargetSmallerThanViewport {
                buffer,
                size,
                viewport: (v.width, v.height),
            });
        }
        Ok(())
    }

    /// [`check_covers`](Self::check_covers) for a framebuffer.
    pub(crate) fn check_frame(&self, frame: &Framebuffer<'_>) -> Result<(), RenderError> {
        let size = (frame.width(), frame.height());
        self.check_covers(TargetBuffer::Frame, size, frame.is_band())
    }

    /// [`check_covers`](Self::check_covers) for a framebuffer and a depth buffer.
    pub(crate) fn check_targets<D: DepthValue>(
        &self,
        frame: &Framebuffer<'_>,
        depth: &DepthBuffer<'_, D>,
    ) -> Result<(), RenderError> {
        self.check_frame(frame)?;
        let size = (depth.width(), depth.height());
        self.check_covers(TargetBuffer::Depth, size, depth.is_band())
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
    /// [`MAX_LIGHTS`](crate::lighting::MAX_LIGHTS)) for lit objects.
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
/// let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
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
///     moved.transform = Affine3::builder().rotate_y(BinaryAngle::from_degrees(20 * turn)).build()?;
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
    /// [`MAX_LIGHTS`](crate::lighting::MAX_LIGHTS)) set up once.
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
