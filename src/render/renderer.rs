//! [`Renderer`]: what is fixed for a frame (the camera's projector, frustum and view
//! transform, the lights in the observer frame), built once from a camera or a scene.

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
        Ok(Renderer {
            camera: *camera,
            projector: Projector::new(camera).map_err(RenderError::Projection)?,
            frustum: Frustum::new::<S>(camera, Frustum::DEFAULT_GUARD)
                .map_err(RenderError::Clip)?,
            view: *camera.view_transform(),
            illumination: Illumination::observer(255, &[]).map_err(RenderError::Lighting)?,
        })
    }

    /// This renderer with ambient intensity `ambient` and `lights` (world frame, at most
    /// [`MAX_LIGHTS`](crate::shade::lighting::MAX_LIGHTS)) for lit objects.
    pub fn with_lights(mut self, ambient: u8, lights: &[Light]) -> Result<Self, RenderError> {
        self.illumination =
            Illumination::new(&self.camera, ambient, lights).map_err(RenderError::Lighting)?;
        Ok(self)
    }

    /// The renderer of a scene: its camera, ambient intensity and lights.
    pub fn for_scene(scene: &Scene<'_>) -> Result<Self, RenderError> {
        Renderer::new(&scene.camera)?.with_lights(scene.ambient, scene.lights)
    }

    /// The lights in the observer frame.
    pub fn illumination(&self) -> &Illumination {
        &self.illumination
    }

    /// The camera this renderer projects for.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The object's model → observer transform.
    pub(super) fn model_view(&self, object: &Object<'_>) -> Result<Affine3, RenderError> {
        object
            .transform
            .then(&self.view)
            .map_err(RenderError::Transform)
    }
}
