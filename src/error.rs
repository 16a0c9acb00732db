//! The crate's error vocabulary.
//!
//! Every stage reports what went wrong with an error enum of its own ([`BufferError`],
//! [`MeshError`], [`RenderError`], …). Each implements [`Display`](core::fmt::Display) with a
//! message that names what failed and, where there is one, the limit that was exceeded, and
//! [`core::error::Error`], so it can be printed, logged or boxed as it is.
//!
//! [`Error`] gathers them all: every stage error converts into it with `From`, so a function
//! that sets up buffers, builds a camera and renders a frame can return
//! `Result<_, zscan::Error>` and use `?` on each call; on a host, `zscan::Error` (and every
//! stage error) also goes into `Box<dyn std::error::Error>` with `?`. Messages are
//! self-contained: an error that wraps another one prints the inner message after its own
//! prefix, and [`source`](core::error::Error::source) returns `None`.
//!
//! Most messages live here; the enums whose files already printed themselves
//! ([`LutError`], [`BufferError`], [`FillError`], [`CircleError`], [`LineError`],
//! [`ShadowError`], [`RenderError`], [`VisibilityError`]) keep their `Display` beside their
//! definition.
//!
//! A hidden-surface method's error ([`VisibilityError`]) that only wraps the pipeline's
//! ([`VisibilityError::Render`]) converts into [`Error::Render`], as the z-buffer's frames
//! report it; the methods' own refusals into [`Error::Visibility`].

use core::fmt;

use crate::clip::frustum::ClipError;
use crate::geometry::camera::CameraError;
use crate::geometry::matrix::MatrixError;
use crate::geometry::mesh::MeshError;
use crate::lighting::{LightingError, MAX_LIGHTS};
use crate::output::{BufferError, LutError};
use crate::project::ProjectError;
use crate::raster::circle::CircleError;
use crate::raster::line::LineError;
use crate::raster::polygon::FillError;
use crate::raster::triangle::edge_walker::{MAX_COORD, MAX_SUBPIXEL_BITS};
use crate::raster::triangle::plane::PlaneError;
use crate::raster::triangle::DrawError;
use crate::render::RenderError;
use crate::shadow::ShadowError;
use crate::visibility::VisibilityError;

impl fmt::Display for ProjectError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ProjectError::BehindNearPlane => {
                write!(
                    f,
                    "point is nearer than the near plane (z < near); clip it first"
                )
            }
            ProjectError::OutOfRange => write!(
                f,
                "projected point is outside the raster's range of ±{MAX_COORD} sub-pixel units"
            ),
            ProjectError::SubpixelBitsTooLarge => write!(
                f,
                "sub-pixel bits exceed the raster's maximum of {MAX_SUBPIXEL_BITS}"
            ),
            ProjectError::Orthographic(stage) => write!(
                f,
                "{stage} needs a perspective camera and cannot use the orthographic camera"
            ),
        }
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::BadPolygonSize => write!(f, "a polygon has fewer than 3 vertices"),
            MeshError::IndexCountMismatch => {
                write!(
                    f,
                    "the polygon sizes do not add up to the number of indices"
                )
            }
            MeshError::IndexOutOfRange => {
                write!(f, "a polygon index is not below the number of vertices")
            }
            MeshError::CoordinateOutOfRange => {
                write!(f, "a vertex coordinate exceeds the mesh range of ±1024")
            }
            MeshError::OutputTooSmall {
                table,
                given,
                needed,
            } => write!(f, "the {table} holds {given} entries, {needed} are needed"),
            MeshError::UvCountMismatch { given, needed } => write!(
                f,
                "the texture coordinate table holds {given} pairs, one per index ({needed}) \
                 is needed"
            ),
            MeshError::BadParameters => write!(
                f,
                "generator parameters are invalid (too few segments or rings, radii out of \
                 order) or need more than 65536 vertices"
            ),
        }
    }
}

impl fmt::Display for MatrixError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MatrixError::OutOfRange => write!(
                f,
                "transform out of range: a linear entry beyond ±64 or a translation beyond \
                 ±32768 (I16F16)"
            ),
            MatrixError::ZeroAxis => write!(f, "rotation axis is the zero vector"),
            MatrixError::NotRigid => write!(
                f,
                "transform is not rigid: its linear part is not a rotation within 2^-12"
            ),
        }
    }
}

impl fmt::Display for CameraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CameraError::ZeroViewDirection => {
                write!(
                    f,
                    "camera view direction (target − position) is the zero vector"
                )
            }
            CameraError::UpParallelToView => {
                write!(
                    f,
                    "camera up vector is zero or parallel to the view direction"
                )
            }
            CameraError::FovOutOfRange => write!(
                f,
                "field of view must be strictly between 0 and 180 degrees (half a turn)"
            ),
            CameraError::FocalTooLong => write!(
                f,
                "field of view too narrow: a focal length reaches 32768 pixels"
            ),
            CameraError::BadViewport => write!(
                f,
                "viewport has a zero width, height or pixel size, or an image extent above \
                 2^20 physical units"
            ),
            CameraError::BadDepthRange => write!(f, "depth range must satisfy 0 < near < far"),
            CameraError::OutOfRange => write!(
                f,
                "a camera position or distance leaves the I16F16 range of ±32768"
            ),
            CameraError::BadExtent => write!(
                f,
                "orthographic view extent must be positive and give between 2^-16 and 2^15 \
                 pixels per world unit"
            ),
        }
    }
}

impl fmt::Display for ClipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ClipError::CapacityExceeded => write!(
                f,
                "polygon has more vertices than the clipper's capacity (its parameter N)"
            ),
            ClipError::PlaneOutOfRange => {
                write!(f, "clip plane coefficient a, b or c exceeds ±8192")
            }
        }
    }
}

impl fmt::Display for LightingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LightingError::TooManyLights => {
                write!(
                    f,
                    "more than {MAX_LIGHTS} lights (the lighting stage's maximum)"
                )
            }
            LightingError::ZeroDirection => {
                write!(
                    f,
                    "a directional light has the zero vector as its direction"
                )
            }
            LightingError::OutputTooSmall {
                table,
                given,
                needed,
            } => write!(
                f,
                "lighting: the {table} holds {given} entries, the mesh needs {needed}"
            ),
            LightingError::Transform(e) => write!(f, "lighting: model-view transform: {e}"),
            LightingError::ZeroAxis { light } => {
                write!(
                    f,
                    "light {light}: a spot light has the zero vector as its axis"
                )
            }
            LightingError::ConeOutOfRange { light } => write!(
                f,
                "light {light}: spot cone out of range: needs 0 <= inner < outer <= 90 degrees \
                 and cos(inner) - cos(outer) >= 1/64"
            ),
            LightingError::AttenuationOutOfRange { light } => write!(
                f,
                "light {light}: attenuation out of range: constant must be in 1..=256, linear \
                 and quadratic in 0..=256"
            ),
        }
    }
}

impl fmt::Display for PlaneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlaneError::Degenerate => {
                write!(f, "triangle has zero area: no attribute plane to set up")
            }
            PlaneError::TooLarge => write!(
                f,
                "triangle too large for the 32-bit stepping plane: twice its area reaches 2^30 \
                 square sub-pixel units (the wide plane takes it)"
            ),
        }
    }
}

impl fmt::Display for DrawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DrawError::Fill(e) => write!(f, "fill: {e}"),
        }
    }
}

impl core::error::Error for LutError {}
impl core::error::Error for ProjectError {}
impl core::error::Error for MeshError {}
impl core::error::Error for MatrixError {}
impl core::error::Error for CameraError {}
impl core::error::Error for ClipError {}
impl core::error::Error for FillError {}
impl core::error::Error for LightingError {}
impl core::error::Error for PlaneError {}
impl core::error::Error for DrawError {}
impl core::error::Error for RenderError {}

/// Defines [`Error`] with one variant per stage error (and [`Error::Display`]), each stage
/// error's `From` conversion and the `Display` that prints the stage error's own message: the
/// list of stages is written once.
/// Variants after the `;` get no `From` (it is written by hand).
macro_rules! stage_errors {
    (
        $($(#[$doc:meta])* $variant:ident($ty:ty),)*
        ;
        $($(#[$own_doc:meta])* $own:ident($own_ty:ty),)*
    ) => {
        /// Any error of the crate: one variant per stage error, each with a `From`
        /// conversion, so `?` turns a stage's error into this one (and this one, like every
        /// stage error, into `Box<dyn std::error::Error>` on a host).
        ///
        /// Its message is the stage error's own. A display's error type is the driver's, not
        /// the crate's: displays that cannot fail (`Infallible`, as the simulator and
        /// embedded-graphics' mock display) convert with `?` too; for others,
        /// [`Error::Display`] stands for the driver's error
        /// (`flush(..).map_err(|_| zscan::Error::Display)?`).
        ///
        /// ```
        /// use zscan::output::Framebuffer;
        ///
        /// fn too_small() -> Result<(), zscan::Error> {
        ///     let mut pixels = [0u8; 10];
        ///     let _frame = Framebuffer::new(&mut pixels, 4, 4)?; // 16 bytes needed
        ///     Ok(())
        /// }
        /// let e = too_small().unwrap_err();
        /// assert!(matches!(e, zscan::Error::Buffer(_)));
        /// assert_eq!(e.to_string(), "buffer holds 10 elements but 16 are needed");
        /// ```
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        #[non_exhaustive]
        pub enum Error {
            $($(#[$doc])* $variant($ty),)*
            $($(#[$own_doc])* $own($own_ty),)*
            /// The display's driver rejected the pixels sent to it (its error type is the
            /// driver's: map it with `.map_err(|_| zscan::Error::Display)`).
            Display,
        }

        $(
            impl From<$ty> for Error {
                fn from(e: $ty) -> Error {
                    Error::$variant(e)
                }
            }
        )*

        impl fmt::Display for Error {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                match self {
                    $(Error::$variant(e) => fmt::Display::fmt(e, f),)*
                    $(Error::$own(e) => fmt::Display::fmt(e, f),)*
                    Error::Display => write!(f, "the display rejected the pixels sent to it"),
                }
            }
        }
    };
}

stage_errors!(
    /// A colour look-up table could not be built.
    Lut(LutError),
    /// A caller buffer could not be wrapped as a framebuffer, depth buffer or mask.
    Buffer(BufferError),
    /// A point could not be projected.
    Project(ProjectError),
    /// A mesh or a generator's output is invalid.
    Mesh(MeshError),
    /// A transform could not be built or combined.
    Matrix(MatrixError),
    /// A camera could not be built.
    Camera(CameraError),
    /// Clipping failed.
    Clip(ClipError),
    /// A polygon could not be filled.
    Fill(FillError),
    /// A circle could not be drawn.
    Circle(CircleError),
    /// A line could not be clipped or drawn.
    Line(LineError),
    /// Lighting could not be set up.
    Lighting(LightingError),
    /// An attribute plane could not be set up.
    Plane(PlaneError),
    /// A triangle was not drawn.
    Draw(DrawError),
    /// A shadow map could not be set up, drawn or applied.
    Shadow(ShadowError),
    /// A frame or object could not be rendered.
    Render(RenderError),
    /// No plan was made for a scene.
    Plan(crate::visibility::PlanError),
    /// A mesh's planner facts were not computed.
    Facts(crate::visibility::FactsError),
    /// A texture or shade table was refused (`texture`).
    Texture(crate::texture::TextureError),
    /// A screen-door opacity is out of range.
    Opacity(crate::raster::triangle::OpacityError),
    /// A blend table could not be built.
    Blend(crate::output::BlendError),
    ;
    /// A hidden-surface method refused a frame (its memory, its budget, an object or scene
    /// outside its rule: `visibility`).
    Visibility(VisibilityError),
);

impl From<VisibilityError> for Error {
    /// The pipeline's error a method only passed on becomes [`Error::Render`].
    fn from(e: VisibilityError) -> Error {
        match e {
            VisibilityError::Render(e) => Error::Render(e),
            e => Error::Visibility(e),
        }
    }
}

impl From<core::convert::Infallible> for Error {
    fn from(e: core::convert::Infallible) -> Error {
        match e {}
    }
}

impl core::error::Error for Error {}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::raster::line::MAX_COORD as LINE_MAX_COORD;
    use embedded_graphics_core::geometry::Point;
    use std::boxed::Box;
    use std::string::{String, ToString};
    use std::vec::Vec;

    /// The message of `e`, checked non-empty and identical through [`Error`].
    fn message<E: core::error::Error + Into<Error> + Copy>(e: E) -> String {
        let text = e.to_string();
        assert!(!text.is_empty(), "{e:?} has an empty message");
        assert_eq!(
            e.into().to_string(),
            text,
            "zscan::Error changes {e:?}'s message"
        );
        text
    }

    /// Every message of a list, non-empty and pairwise distinct.
    fn messages<E: core::error::Error + Into<Error> + Copy>(all: &[E]) -> Vec<String> {
        let texts: Vec<String> = all.iter().map(|&e| message(e)).collect();
        for (i, a) in texts.iter().enumerate() {
            for b in &texts[i + 1..] {
                assert_ne!(a, b, "two variants print the same message");
            }
        }
        texts
    }

    #[test]
    fn lut_error_names_the_256_entries() {
        let t = messages(&[
            LutError::TooManyEntries { needed: 300 },
            LutError::ZeroLevels,
        ]);
        assert!(t[0].contains("300") && t[0].contains("256"), "{}", t[0]);
        assert!(t[1].contains("level"), "{}", t[1]);
    }

    #[test]
    fn target_error_names_sizes() {
        let t = messages(&[
            BufferError::ZeroSize,
            BufferError::StrideTooSmall {
                stride: 3,
                width: 4,
            },
            BufferError::BufferTooSmall {
                needed: 16,
                len: 10,
            },
            BufferError::SizeMismatch,
            BufferError::NotWholePages { top: 4, height: 12 },
        ]);
        assert!(t[0].contains("at least 1"), "{}", t[0]);
        assert!(
            t[4].contains("row 4") && t[4].contains("12 rows"),
            "{}",
            t[4]
        );
        assert!(t[1].contains('3') && t[1].contains('4'), "{}", t[1]);
        assert!(t[2].contains("16") && t[2].contains("10"), "{}", t[2]);
        assert!(t[3].contains("depth"), "{}", t[3]);
    }

    #[test]
    fn project_error_names_the_raster_limits() {
        let t = messages(&[
            ProjectError::BehindNearPlane,
            ProjectError::OutOfRange,
            ProjectError::SubpixelBitsTooLarge,
            ProjectError::Orthographic("the shadow pass"),
        ]);
        assert!(
            t[3].contains("the shadow pass needs a perspective camera"),
            "{}",
            t[3]
        );
        assert!(t[0].contains("near"), "{}", t[0]);
        assert!(t[1].contains("268435455"), "{}", t[1]);
        assert!(t[2].contains("16"), "{}", t[2]);
    }

    #[test]
    fn mesh_error_names_the_limits() {
        let t = messages(&[
            MeshError::BadPolygonSize,
            MeshError::IndexCountMismatch,
            MeshError::IndexOutOfRange,
            MeshError::CoordinateOutOfRange,
            MeshError::OutputTooSmall {
                table: crate::geometry::mesh::MeshTable::Indices,
                given: 10,
                needed: 3840,
            },
            MeshError::BadParameters,
        ]);
        assert!(t[0].contains("fewer than 3"), "{}", t[0]);
        assert!(t[3].contains("±1024"), "{}", t[3]);
        let sizes = ["index table", "10", "3840"];
        assert!(sizes.iter().all(|w| t[4].contains(w)), "{}", t[4]);
        assert!(t[5].contains("65536"), "{}", t[5]);
    }

    #[test]
    fn matrix_error_names_the_limits() {
        let t = messages(&[
            MatrixError::OutOfRange,
            MatrixError::ZeroAxis,
            MatrixError::NotRigid,
        ]);
        assert!(t[0].contains("±64") && t[0].contains("±32768"), "{}", t[0]);
        assert!(t[1].contains("axis"), "{}", t[1]);
        assert!(t[2].contains("2^-12"), "{}", t[2]);
    }

    #[test]
    fn camera_error_names_the_limits() {
        let t = messages(&[
            CameraError::ZeroViewDirection,
            CameraError::UpParallelToView,
            CameraError::FovOutOfRange,
            CameraError::FocalTooLong,
            CameraError::BadViewport,
            CameraError::BadDepthRange,
            CameraError::OutOfRange,
            CameraError::BadExtent,
        ]);
        assert!(t[7].contains("2^15 pixels per world unit"), "{}", t[7]);
        assert!(t[2].contains("180 degrees"), "{}", t[2]);
        assert!(t[3].contains("32768 pixels"), "{}", t[3]);
        assert!(t[4].contains("2^20"), "{}", t[4]);
        assert!(t[5].contains("0 < near < far"), "{}", t[5]);
        assert!(t[6].contains("±32768"), "{}", t[6]);
    }

    #[test]
    fn clip_error_names_the_plane_limit() {
        let t = messages(&[ClipError::CapacityExceeded, ClipError::PlaneOutOfRange]);
        assert!(t[0].contains("capacity"), "{}", t[0]);
        assert!(t[1].contains("±8192"), "{}", t[1]);
    }

    #[test]
    fn fill_error_names_capacity_and_range() {
        let t = messages(&[
            FillError::TooManyEdges { capacity: 24 },
            FillError::CoordinateOutOfRange { vertex: 2 },
            FillError::CoordinateOutOfRange { vertex: usize::MAX },
        ]);
        assert!(t[0].contains("24"), "{}", t[0]);
        assert!(
            t[1].contains("vertex 2") && t[1].contains("268435455"),
            "{}",
            t[1]
        );
        assert!(t[2].contains("16") && !t[2].contains("vertex"), "{}", t[2]);
    }

    #[test]
    fn circle_error_names_the_radius_limit() {
        let t = message(CircleError::RadiusTooLarge { radius: u32::MAX });
        assert!(t.contains("4294967295") && t.contains("1073741824"), "{t}");
    }

    #[test]
    fn line_error_names_the_coordinate_limit() {
        let t = message(LineError::CoordinateOutOfRange {
            point: Point::new(i32::MAX, 0),
        });
        assert!(t.contains(&LINE_MAX_COORD.to_string()), "{t}");
    }

    #[test]
    fn lighting_error_names_the_light_limit() {
        let t = messages(&[
            LightingError::TooManyLights,
            LightingError::ZeroDirection,
            LightingError::OutputTooSmall {
                table: crate::geometry::mesh::MeshTable::VertexNormals,
                given: 100,
                needed: 482,
            },
            LightingError::Transform(MatrixError::OutOfRange),
            LightingError::ZeroAxis { light: 2 },
            LightingError::ConeOutOfRange { light: 1 },
            LightingError::AttenuationOutOfRange { light: 3 },
        ]);
        assert!(
            t[4].contains("light 2") && t[4].contains("axis"),
            "{}",
            t[4]
        );
        assert!(t[5].contains("light 1") && t[5].contains("90"), "{}", t[5]);
        assert!(
            t[6].contains("light 3") && t[6].contains("1..=256"),
            "{}",
            t[6]
        );
        assert!(t[0].contains(&MAX_LIGHTS.to_string()), "{}", t[0]);
        let sizes = ["vertex normal table", "100", "482"];
        assert!(sizes.iter().all(|w| t[2].contains(w)), "{}", t[2]);
        assert!(t[3].contains("±64"), "the inner message is kept: {}", t[3]);
    }

    #[test]
    fn plane_error_names_the_area_limit() {
        let t = messages(&[PlaneError::Degenerate, PlaneError::TooLarge]);
        assert!(t[0].contains("zero area"), "{}", t[0]);
        assert!(t[1].contains("2^30"), "{}", t[1]);
    }

    #[test]
    fn draw_error_names_the_fill_error() {
        let t = messages(&[
            DrawError::Fill(FillError::TooManyEdges { capacity: 7 }),
            DrawError::Fill(FillError::CoordinateOutOfRange { vertex: 2 }),
        ]);
        assert!(t[0].starts_with("fill: ") && t[0].contains('7'), "{}", t[0]);
        assert!(
            t[1].contains("vertex 2") && t[1].contains("268435455"),
            "{}",
            t[1]
        );
    }

    #[test]
    fn shadow_error_names_the_limits() {
        let t = messages(&[
            ShadowError::BadSize,
            ShadowError::BadLight,
            ShadowError::OutOfRange,
            ShadowError::Transform,
            ShadowError::Projection(ProjectError::OutOfRange),
            ShadowError::PolygonTooLarge,
            ShadowError::Raster,
            ShadowError::FrameMismatch,
        ]);
        assert!(t[0].contains("2^14") && t[0].contains("2^19"), "{}", t[0]);
        assert!(t[2].contains("8192"), "{}", t[2]);
        assert!(
            t[4].contains("268435455"),
            "the inner message is kept: {}",
            t[4]
        );
        assert!(t[7].contains("2^16"), "{}", t[7]);
    }

    #[test]
    fn render_error_names_the_limits() {
        let t = messages(&[
            RenderError::ScratchTooSmall {
                given: 114,
                needed: 482,
            },
            RenderError::IntensitiesTooShort {
                table: crate::render::IntensityTable::PerPolygon,
                given: 5,
                needed: 6,
            },
            RenderError::PolygonTooLarge,
            RenderError::Transform(MatrixError::ZeroAxis),
            RenderError::Projection(ProjectError::BehindNearPlane),
            RenderError::Clip(ClipError::PlaneOutOfRange),
            RenderError::Draw(DrawError::Fill(FillError::CoordinateOutOfRange {
                vertex: 0,
            })),
            RenderError::BandMemoryTooSmall {
                part: crate::render::BandPart::Depths,
                given: 5000,
                needed: 5120,
            },
            RenderError::Lighting(LightingError::TooManyLights),
            RenderError::BandMemoryTooSmall {
                part: crate::render::BandPart::Vertices,
                given: 100,
                needed: 1839,
            },
            RenderError::NotCompact {
                object: 2,
                vertex: 17,
            },
            RenderError::PolygonTableTooSmall {
                given: 3000,
                needed: 3674,
            },
            RenderError::TargetSmallerThanViewport {
                buffer: crate::render::TargetBuffer::Frame,
                size: (320, 200),
                viewport: (320, 240),
            },
        ]);
        // Every size error names its buffer and both sizes.
        let has = |k: usize, words: &[&str]| {
            assert!(words.iter().all(|w| t[k].contains(w)), "{}", t[k]);
        };
        has(0, &["vertex scratch", "114", "482"]);
        has(1, &["per-polygon intensity table", "5", "6 polygons"]);
        has(7, &["band depth samples", "5000", "5120"]);
        has(11, &["polygon table", "3000", "3674"]);
        has(
            12,
            &["framebuffer", "320 × 200", "320 × 240 viewport", "cropped"],
        );
        assert!(t[2].contains("24"), "{}", t[2]);
        let sizes = ["100", "1839", "compact vertices"];
        assert!(sizes.iter().all(|w| t[9].contains(w)), "{}", t[9]);
        assert!(t[10].contains("vertex 17 of object 2"), "{}", t[10]);
    }

    #[test]
    fn visibility_error_names_the_limits() {
        let t = messages(&[
            VisibilityError::TriangleStoreFull { capacity: 300 },
            VisibilityError::SplitBudgetExhausted { budget: 7 },
            VisibilityError::PainterCycle,
            VisibilityError::SubdivisionStackFull { capacity: 40 },
            VisibilityError::SubdivisionCandidatesFull { capacity: 900 },
            VisibilityError::ActiveTableFull { capacity: 12 },
            VisibilityError::FastGouraudInParts { object: 3 },
            VisibilityError::TooManyObjects { max: 256 },
            VisibilityError::NoSuchObject {
                index: 5,
                objects: 2,
            },
            VisibilityError::ReverseRefused(crate::visibility::MethodReason::Empty),
            VisibilityError::NotPlanned {
                method: "warnock",
                depth_bytes: 4,
            },
        ]);
        let has = |k: usize, words: &[&str]| {
            assert!(words.iter().all(|w| t[k].contains(w)), "{}", t[k]);
        };
        has(0, &["triangle store", "300"]);
        has(1, &["painter", "7 splits"]);
        has(2, &["cycle"]);
        has(3, &["stack of 40 windows"]);
        has(4, &["900 candidate entries"]);
        has(5, &["active table", "12"]);
        has(6, &["object 3", "fast Gouraud"]);
        has(7, &["more than 256 objects"]);
        has(8, &["index 5", "2 objects"]);
        has(9, &["reverse painter", "no object"]);
        has(10, &["warnock", "4 bytes"]);
    }

    /// A method's error that only wraps the pipeline's converts into [`Error::Render`], its
    /// own refusals into [`Error::Visibility`]; the message is the same either way.
    #[test]
    fn visibility_error_converts_to_the_stage_that_failed() {
        let render = RenderError::PolygonTooLarge;
        let wrapped = VisibilityError::from(render);
        assert_eq!(wrapped.to_string(), render.to_string());
        assert_eq!(Error::from(wrapped), Error::Render(render));
        let own = VisibilityError::PainterCycle;
        assert_eq!(Error::from(own), Error::Visibility(own));
    }

    /// `?` goes from a stage error into [`Error`] and from both into a boxed error.
    #[test]
    fn question_mark_converts() {
        fn stage() -> Result<(), MeshError> {
            Err(MeshError::IndexOutOfRange)
        }
        fn crate_level() -> Result<(), Error> {
            stage()?;
            Ok(())
        }
        fn boxed_stage() -> Result<(), Box<dyn std::error::Error>> {
            stage()?;
            Ok(())
        }
        fn boxed_crate() -> Result<(), Box<dyn std::error::Error>> {
            crate_level()?;
            Ok(())
        }
        assert_eq!(crate_level(), Err(Error::Mesh(MeshError::IndexOutOfRange)));
        let expect = MeshError::IndexOutOfRange.to_string();
        assert_eq!(boxed_stage().unwrap_err().to_string(), expect);
        assert_eq!(boxed_crate().unwrap_err().to_string(), expect);
        fn infallible() -> Result<(), Error> {
            Ok::<(), core::convert::Infallible>(())?;
            Ok(())
        }
        assert_eq!(infallible(), Ok(()));
        assert!(Error::Display.to_string().contains("display"));
    }
}
