//! What a user names to render a lit mesh and show it on an embedded-graphics display, in
//! one import: `use zscan::prelude::*;`.
//!
//! Re-exports only; every item keeps its home module (linked from each name) and its
//! documentation there. The list follows a frame's set-up in order: the mesh and its place
//! in the world, its light and shading, the camera, the renderer and its memory (or the
//! planner's, [`plan`] and [`draw_plan`]), the target buffers and the flush.
//!
//! Every name here is distinct from those of `embedded_graphics::prelude`, so both preludes
//! can be glob-imported side by side (zscan's angle type is [`BinaryAngle`], not `Angle`).
//!
//! ```
//! use zscan::prelude::*;
//!
//! let lens = Lens::new(BinaryAngle::from_degrees(60), Coord::lit("0.5"), Coord::lit("20"));
//! let camera = Camera::look_at(
//!     Vec3::from_int(0, 0, 4),
//!     Vec3::ZERO,
//!     Vec3::from_int(0, 1, 0),
//!     lens,
//!     Viewport::new(32, 24),
//! )?;
//! let objects = [Object::new(unit_cube())];
//! let scene = Scene { camera, objects: &objects, background: 0, ambient: 0, lights: &[] };
//! let renderer = Renderer::for_scene(&scene)?;
//! let (mut pixels, mut depths) = ([0u8; 32 * 24], [0u16; 32 * 24]);
//! let mut frame = Framebuffer::new(&mut pixels, 32, 24)?;
//! let mut depth = DepthBuffer::new(&mut depths, 32, 24)?;
//! let mut scratch = [PreparedVertex::default(); 8];
//! let mut stats = RenderStats::default();
//! render_scene(&renderer, &mut frame, &mut depth, &mut scratch, &mut stats)?;
//! assert!(stats.pixels_covered > 0);
//! # Ok::<(), zscan::Error>(())
//! ```

// The mesh and its place in the world.
pub use crate::geometry::fixed::Coord;
pub use crate::geometry::generators::{
    torus, torus_normals, torus_sizes, torus_uvs, unit_cube, uv_sphere, uv_sphere_normals,
    uv_sphere_sizes, uv_sphere_uvs,
};
pub use crate::geometry::matrix::{Affine3, Affine3Builder};
pub use crate::geometry::mesh::{triangle_indices, vec3s_from_bits, Mesh, PolygonSizes, TexCoord};
pub use crate::geometry::trig::BinaryAngle;
pub use crate::geometry::vector::Vec3;
pub use crate::scene::{Intensities, Object, Scene, Transparency};

// Light and shading.
pub use crate::lighting::{Attenuation, Cone, Light, Material};
pub use crate::raster::triangle::{LuminanceRamp, Opacity, ShadeMode};

// Textures.
pub use crate::texture::{shade_table, ShadeTable, Texture, TextureMode, Texturing};

// The camera.
pub use crate::geometry::camera::{Camera, FovAxis, Lens, Viewport};

// The renderer and its memory.
pub use crate::render::{
    render_in_bands, render_scene, BandScratch, PolygonRows, PreparedVertex, RenderStats, Renderer,
    StatsSink, StatsWithoutWritten,
};
pub use crate::render::{BandSink, DisplaySink, DoubleBands};

// Lines and points in space: wireframes, line lists, points.
pub use crate::render::{
    AppelCrossing, AppelEdge, AppelError, AppelScratch, AppelSegment, LineStyle, Wireframe,
};

// The planner: a plan within a memory budget, drawn from memory it sizes.
pub use crate::render::{CompactVertex, PolygonTop};
pub use crate::visibility::{draw_plan, plan, MeshFacts, PlanMemory, PlanSizes};

// The target buffers, the palette and the display.
pub use crate::output::{
    flush, mask_words_needed, pack_pages, page_bytes, shaded_index, BlendTable, DepthBuffer,
    DepthValue, Framebuffer, Lut,
};

// Errors.
pub use crate::visibility::VisibilityError;
pub use crate::Error;
