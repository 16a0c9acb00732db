//! Shadows by the course's two-pass z-buffer method (chapter 4, §1.3), for directional and
//! point lights.
//!
//! Role in the pipeline: beside lighting, around the renderer. **Pass 1**
//! ([`ShadowMap::render`]) draws every occluder's depth *as seen from the light* into a
//! caller-provided map of `u16` or `u32` samples, through the renderer's triangle writer with
//! its depth-only span kind: the raster stage's exact triangle fill and exact depth
//! interpolation, no colour (nearest wins, both faces). **Pass 2** asks, for a visible
//! point, whether its depth from the light is at most the map's nearest texel plus a bias (the
//! course's `S_i`: 0 in shadow, 1 lit): for one world point ([`ShadowMap::is_lit`],
//! [`ShadowMap::classify`]), or for every written pixel of a rendered frame or band
//! ([`ShadowPass::apply`], which back-projects the pixel from the frame's depth buffer and
//! lets the caller remap the palette index of shadowed pixels).
//!
//! One mechanism serves both lights; only the map's projection differs
//! ([`projection`]):
//!
//! | light | map | constructor |
//! |---|---|---|
//! | directional | orthographic along the light over a bounding sphere (`centre`, `r`) | [`ShadowMap::new`] |
//! | point | perspective from the light position, looking at `centre`, field of view framing the sphere | [`ShadowMap::point`] |
//! | spot | perspective from the light position along its axis, field of view framing its cone (outer half-angle below 60°) | [`ShadowMap::spot`] |
//! | either, from a [`Light`](crate::lighting::Light) | the above | [`ShadowMap::for_light`] |
//! | any aimed perspective (a spot, one face of a cube map) | the given [`Camera`](crate::geometry::camera::Camera) | [`ShadowMap::from_camera`] |
//!
//! ## Conventions
//! - The map is a screen of `w × h` texels whose texel `(i, j)` is the lattice point `(i, j)`
//!   of the raster (pixel-centred, principal point `((w − 1)/2, (h − 1)/2)`). Pass 1 stores
//!   at each texel the depth of the nearest occluder covering that lattice point (the fill
//!   rule of [`raster`](crate::raster)); pass 2 reads the texel nearest to the point's
//!   projection (rounded sub-pixel position, `S = 4`).
//! - **Depth** is a 32-bit normalised depth `D`, smaller nearer, for both projections:
//!   orthographic `D = (z + r)·(2^32 − 1)/2r` (`z` along the light's travel, origin at the
//!   centre); perspective the renderer's `D(z) = A − K/z` (`project`:
//!   `A = (2^32 − 1)·far/(far − near)`, `K = A·near`), affine in screen space, so the exact
//!   fill and exact interpolation of pass 1 are exact for both. A `u16` map keeps the top 16
//!   bits ([`DepthValue::from_depth32`](crate::output::DepthValue::from_depth32)), a `u32` map
//!   all of them. **Biases are always in units of the 32-bit depth**, whatever the storage: a
//!   point of depth `d` is lit when `from_depth32(d − bias) ≤ stored` (so the `u16` map's
//!   truncation never adds acne, only up to `2^16` units of leaking).
//! - **Outside the map is lit**: a point whose projection falls outside the `w × h` texels,
//!   or (perspective) that is behind the light or nearer to it than the near plane, is
//!   reported [`Visibility::Outside`] and treated as lit. A framed point-light map sees a
//!   pyramid whose half-angle across the map's smaller side is at most 60° (a 120° field of
//!   view): a point light inside (or very near) its bounding sphere cannot see all of it from
//!   one map; the part outside the pyramid is lit (tested; aim several maps with
//!   [`ShadowMap::from_camera`] to cover more).
//! - **Near plane** (perspective): occluder polygons are clipped by the 3D clipper
//!   (`clip::frustum`) against the map's near plane, far plane and a
//!   guard band of twice the map's extent before projection, so polygons crossing the near
//!   plane or reaching behind the light are cut, never projected through `z ≤ 0`; parts nearer
//!   to the light than `near` cast no shadow. The orthographic map clips to the box
//!   `|x|, |y| ≤ 2r`, `|z| ≤ r` the same way: geometry outside the bounding sphere's slab
//!   is ignored.
//!
//! ## Resolution
//! - Orthographic: a texel is `2r/w` world units wide, everywhere; depth resolution
//!   `2r/2^32` (`u32`) or `2r/2^16` (`u16`) world units.
//! - Perspective: at distance `z` along the map's axis a texel spans `z/f` world units across
//!   the ray, `f = (w/2)/tan(fov/2)` the focal length in texels, stretched by `1/cos θ` on a
//!   surface whose normal makes the angle `θ` with the ray. Shadow outlines are sharp to about
//!   one texel footprint. Depth resolution at distance `z`: `z²/K` world units per 32-bit
//!   depth unit (`2^16` times more for a `u16` map), i.e. the renderer's
//!   `Δz ≈ z²(far − near)/(far·near·2^b)`. [`ShadowMap::point`] picks `far = d + r` and
//!   `near = max(d − r, far/256)` (`d` the light's distance to the centre), so a `u16` map
//!   resolves at worst `far/256` at `far`; use `u32` samples when the light is close.
//!
//! ## Bias: acne and leaking
//! A texel stores the occluder's depth at the texel's centre, while the tested point is up to
//! half a texel away from it on each axis; the rounding of its sub-pixel projection adds
//! `1/32` texel, and that of the occluder's projected vertices (which shifts the interpolated
//! plane) another `1/32`. On a planar receiver `D` is affine in map space with gradient
//! `(∂D/∂u, ∂D/∂v)` depth units per texel, so a lit point can be up to
//! `δ = (18/32)(|∂D/∂u| + |∂D/∂v|)` deeper than the texel it reads. Exactly:
//! - orthographic, receiver normal `n` (light frame): `∂D/∂u = −(2^32 − 1)·n_x/(w·n_z)`,
//!   `∂D/∂v = (2^32 − 1)·n_y/(h·n_z)`: `(2^32 − 1)·tan θ/w` per texel along the slope, `θ`
//!   the angle between the normal and the light; [`ShadowMap::texel_depth`] is
//!   `(2^32 − 1)/w`;
//! - perspective, receiver plane `n·p = c` in the light frame (`|c|` = the plane's distance
//!   `h` from the light for a unit `n`): `∂D/∂u = −K·n_x/(f_x·c)`, `∂D/∂v = K·n_y/(f_y·c)`,
//!   i.e. at most `K·sin φ/(f·h)` per texel (`φ` the tilt between the normal and the map's
//!   axis), the same at every point of the plane. **Depth units per world unit vary with the
//!   distance**: `dD/dz = K/z²`, so a bias of `b` units lets an occluder within `b·z²/K` world
//!   units (along the axis) in front of a receiver at distance `z` go unseen: leaking grows
//!   with `z²`, while the acne bound above does not depend on `z` at all.
//!
//! The rule ([`ShadowMap::plane_bias`]) for a receiver plane is
//! `bias = ⌈δ⌉ + (slack + 2⁻¹⁵)·dD/dz|max + 16`: the slope term; the world-unit error of the
//! tested points (`slack`: zero for exact points, the observer depth step for back-projected
//! pixels, [`observer_depth_slack`]) plus the I16F16 rounding of both passes' coordinates,
//! converted with the largest `dD/dz` on the plane inside the map (`(2^32 − 1)/2r`, or `K/z²`
//! with `z ≥ max(near, h·cos β)`, `β` the angle from the axis to the map's corner); and 16
//! units for the depth rounding of the projection (≤ 6 per vertex and per point) and of the
//! interpolation. A scene takes the largest over the receiver planes facing the light.
//! - **acne** (too little bias): a lit surface shadows itself in stripes or speckles;
//! - **leaking** (too much bias): where the receiver is nearer than the bias (in world units as
//!   above: `b·2r/2^32`, or `b·z²/K`) behind the occluder's surface facing the light, the
//!   shadow disappears. Both faces are drawn, so that distance is the gap plus the path of the
//!   ray through the occluder: the shadow of a thick box shrinks from its rim (rays grazing its
//!   edges) while the part behind its full width stays; thin objects and those almost touching
//!   their receiver lose theirs first.
//!
//! Measured on a floor and a box in `host-tests/tests/shadows.rs`, for a point and a
//! directional light: with the rule, no acne and no leaking outside a band of 1.5 texels
//! around the shadow's outline; a quarter of it leaves acne on about 40 % of the lit floor
//! (the rule is within a factor of two of the least bias that works); leaking needs tens of
//! times the rule on that scene (the box is thick).
//!
//! ## Numeric contract
//! - Map sizes: `1 ≤ w, h ≤ 2^14` (perspective: `≥ 4`) and `w·h ≤ 2^19`. Clipped polygons
//!   then stay inside `(2w + 2) × (2h + 2)` texels, so every fan triangle's doubled area is
//!   below `2^30` sub-pixel units², the 32-bit stepping's limit of the writer's general plane
//!   (`AttributePlane`; its wide plane would take a larger one, with the same values).
//! - Orthographic: `0 < r ≤ 8192` units (the clip planes' `2r` fits I16F16); texel positions
//!   are `i0 + x·8w/r` sub-pixel units by one `i64` product with a 31-bit multiplier
//!   (`|x·m| < 2^62`); depth `(z + r)·m_d >> s` with `z + r` clamped to `0..=2r` (`< 2^31`)
//!   and a 32-bit multiplier (`< 2^63` in `u64`), clamped to `2^32 − 1`.
//! - Perspective: the light's [`Camera`](crate::geometry::camera::Camera) and
//!   [`Projector`](crate::project::Projector) (`S = 4`): every range and error bound of
//!   `project` applies (depth within 6 units of `D(z)`).
//! - Pass 2 over a frame: see [`pass`] (integer only: one 32-bit reciprocal, two
//!   reciprocal-based `i64` divisions, one affine transform and one projection per pixel).
//! - Memory: the caller's `w·h` samples; nothing allocated; polygons of up to
//!   [`MAX_POLYGON_VERTICES`](crate::clip::frustum::MAX_POLYGON_VERTICES) vertices.

mod map;
pub mod pass;
pub mod projection;

pub use map::{ShadowMap, MAX_POINT_FOV_DEGREES, NEAR_FAR_RATIO};
pub use pass::{observer_depth_slack, DepthSample, ShadowPass, ShadowStats};

use crate::project::ProjectError;

/// Why a shadow map could not be set up, drawn or applied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShadowError {
    /// The sample slice is shorter than `width × height`, or a size is zero, too small for a
    /// perspective map (`< 4`) or too large (`> 2^14`, or `width × height > 2^19`).
    BadSize,
    /// Zero light direction, non-positive radius, or a light frame that cannot be built.
    BadLight,
    /// A position, distance or radius leaves the range the map supports: `d + r` (the
    /// perspective map's far plane) or `2r` beyond I16F16, a radius above 8192, or a sphere
    /// so small as seen from the light that the focal length would reach 2^15 texels (use a
    /// directional map for such a distant light).
    OutOfRange,
    /// An occluder's or the observer's transform overflowed, or the camera is not rigid.
    Transform,
    /// The light's or the observer's camera cannot be projected.
    Projection(ProjectError),
    /// An occluder polygon has more vertices than the clipper holds.
    PolygonTooLarge,
    /// A triangle could not be drawn into the map (outside the raster's range or too large;
    /// not expected within the documented sizes).
    Raster,
    /// A spot's cone, with the map's one-texel margin, needs a wider field of view than a
    /// map's projection allows ([`MAX_POINT_FOV_DEGREES`], 120°:
    /// an outer half-angle below 60°).
    SpotConeTooWide,
    /// The frame and the depth buffer differ in size or rows, or do not fit the camera's
    /// viewport, or the viewport is too wide for the back-projection (`|i − i0| ≥ 2^16`).
    FrameMismatch,
    /// A pixel given to [`ShadowPass::observer_point`] or [`ShadowPass::classify_pixel`] is
    /// outside the camera's viewport `0 ≤ x < width`, `0 ≤ y < height`.
    PixelOutOfRange {
        /// The pixel's column.
        x: i32,
        /// The pixel's row.
        y: i32,
        /// The viewport's width.
        width: u16,
        /// The viewport's height.
        height: u16,
    },
}

impl core::fmt::Display for ShadowError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ShadowError::BadSize => write!(
                f,
                "shadow map samples shorter than width × height, or a size zero, below 4 \
                 (perspective), above 2^14 or with width × height above 2^19"
            ),
            ShadowError::BadLight => write!(
                f,
                "light unusable: zero direction, non-positive radius or no light frame"
            ),
            ShadowError::OutOfRange => write!(
                f,
                "light distance or radius out of range: beyond I16F16 (±32768), a radius above \
                 8192, or a focal length reaching 2^15 texels"
            ),
            ShadowError::Transform => {
                write!(
                    f,
                    "occluder or observer transform overflowed, or camera not rigid"
                )
            }
            ShadowError::Projection(e) => write!(f, "shadow projection: {e}"),
            ShadowError::PolygonTooLarge => {
                write!(
                    f,
                    "occluder polygon has more vertices than the clipper holds"
                )
            }
            ShadowError::Raster => write!(f, "triangle outside the raster's limits"),
            ShadowError::SpotConeTooWide => write!(
                f,
                "spot cone too wide for a shadow map: its outer half-angle plus one texel must \
                 fit a {} degree field of view (half-angle below {} degrees)",
                map::MAX_POINT_FOV_DEGREES,
                map::MAX_POINT_FOV_DEGREES / 2
            ),
            ShadowError::FrameMismatch => write!(
                f,
                "frame, depth buffer and camera viewport do not match, or the viewport is too \
                 wide for the back-projection (|i − i0| ≥ 2^16)"
            ),
            ShadowError::PixelOutOfRange {
                x,
                y,
                width,
                height,
            } => write!(
                f,
                "pixel ({x}, {y}) is outside the camera's {width}×{height} viewport \
                 (0 ≤ x < {width}, 0 ≤ y < {height})"
            ),
        }
    }
}

impl core::error::Error for ShadowError {}

/// What the shadow test says about a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Visibility {
    /// The light reaches the point: its depth is at most the texel's plus the bias.
    Lit,
    /// An occluder nearer to the light covers the point's texel.
    Shadowed,
    /// The point projects outside the map, behind the light or nearer than the near plane:
    /// the map knows nothing of it and it counts as lit.
    Outside,
}

impl Visibility {
    /// True unless [`Visibility::Shadowed`].
    pub fn is_lit(self) -> bool {
        self != Visibility::Shadowed
    }
}
