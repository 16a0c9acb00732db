//! Textures: 8-bit palette images in caller memory, how a textured object samples them, and
//! the shade table that lights a texel.
//!
//! Role in the pipeline: data, read by the raster stage's textured span kind
//! (`raster::triangle`) and named by a scene's [`Object`](crate::scene::Object) through
//! [`Texturing`]. A texture is a slice of palette indices (flash or RAM) with its size
//! ([`Texture`]); a lit texture goes through a [`ShadeTable`] (texel colour × light level →
//! palette index, the colour maps of the classic 8-bit software renderers), built once by
//! [`shade_table`], a `const fn`, from an RGB palette; an unlit texture writes its texels
//! directly.
//!
//! ## Texture coordinates
//! Per polygon corner (a table parallel to the mesh's index table, so that a seam, a cube's
//! faces or a sphere's closing meridian, gives a vertex different coordinates in different
//! polygons: [`Mesh::with_uvs`](crate::geometry::mesh::Mesh::with_uvs)), in **Q8.8**
//! ([`TexCoord`](crate::geometry::mesh::TexCoord): `i16`, `1.0 = 256`): `−128 ≤ u, v < 128`, so a face may repeat its texture
//! up to 255 times. `(0, 0)` is the texture's first texel's corner, `u` runs along a row
//! (columns), `v` down the rows.
//!
//! ## Which texel (course ch. 4 §2.4: what is linear in the scene is not linear on screen)
//! At the pixel centre `p`, with `λ_i(p)` the screen barycentric weights of the corners (the
//! same sub-pixel vertices as the fill and the depth plane) and `q_i` the corner's
//! **perspective weight**, the coordinate is the ratio of two planes
//! `u(p) = Σ λ_i q_i u_i / Σ λ_i q_i`, and the texel column is `⌊W·u(p)⌋` wrapped (`mod W`,
//! power-of-two sides) or clamped to `0..W` (any side); rows likewise with `v` and `H`.
//! The weight is `1/z` as the depth holds it: the projection's `D = A − K/z` gives
//! `K/z = A − D`, and per triangle the three `A − D_i` are shifted right together until the
//! largest is below `2^16` (`q_i = max(1, (A − D_i) >> s)`). Orthographic cameras (depth
//! linear in `z`) and the affine mode take `q_i = 1`. [`TextureMode`] says how exactly the
//! raster honours the ratio: exactly at every pixel, exactly every 8 or 16 pixels and
//! linearly between, or affinely.
//!
//! Numeric contract: sides `1..=1024` texels ([`MAX_TEXTURE_SIDE`]); coordinates Q8.8 (`i16`,
//! every value allowed); a shade table holds `levels · 256` entries (`1 ≤ levels ≤ 256`), the
//! row of luminance `l` (`0..=255`) being `⌊l · levels / 256⌋`. A slice shorter than its size
//! says is a [`TextureError`] naming the table and both lengths.

mod shade;

pub use shade::{shade_table, ShadeTable};

/// Largest texture side, in texels.
pub const MAX_TEXTURE_SIDE: u16 = 1024;

/// How the raster honours the perspective-correct coordinate (module doc), chosen per object
/// like [`ShadeMode`](crate::raster::triangle::ShadeMode).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureMode {
    /// Every pixel shows the texel of the exact ratio at its centre (a floor taken exactly
    /// with integer arithmetic).
    Exact,
    /// Exact every 16 pixels along a span (and at its last pixel), linear in between.
    Subdivided16,
    /// Exact every 8 pixels along a span (and at its last pixel), linear in between.
    Subdivided8,
    /// No perspective correction: the coordinates interpolated linearly on screen.
    Affine,
}

impl TextureMode {
    /// Pixels between exact evaluations along a span (0: every pixel, exact; `u32::MAX`:
    /// none but the span's start, affine).
    pub(crate) const fn segment(self) -> u32 {
        match self {
            TextureMode::Exact => 0,
            TextureMode::Subdivided16 => 16,
            TextureMode::Subdivided8 => 8,
            TextureMode::Affine => u32::MAX,
        }
    }
}

/// The table a texture error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureTable {
    /// The texels of a [`Texture`].
    Texels,
    /// A [`ShadeTable`]'s entries.
    Shades,
}

impl core::fmt::Display for TextureTable {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            TextureTable::Texels => "texel table",
            TextureTable::Shades => "shade table",
        })
    }
}

/// Why a texture, a shade table or a textured object was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureError {
    /// A side is 0 or above [`MAX_TEXTURE_SIDE`].
    BadSize {
        /// The side given.
        side: u16,
        /// The largest allowed.
        max: u16,
    },
    /// A table is shorter than its size says.
    WrongLength {
        /// Which table.
        table: TextureTable,
        /// Entries given.
        given: usize,
        /// Entries needed.
        needed: usize,
    },
    /// A shade table's level count is not in `1..=256`.
    BadLevels {
        /// The count given.
        levels: u16,
    },
}

impl core::fmt::Display for TextureError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TextureError::BadSize { side, max } => {
                write!(f, "texture side {side} is outside 1..={max} texels")
            }
            TextureError::WrongLength {
                table,
                given,
                needed,
            } => write!(f, "{table} holds {given} entries, {needed} needed"),
            TextureError::BadLevels { levels } => {
                write!(f, "shade table of {levels} levels: 1..=256 allowed")
            }
        }
    }
}

impl core::error::Error for TextureError {}

/// An image of palette indices, row by row (`texels[row · width + column]`), borrowed so that
/// it can live in flash. Power-of-two sides wrap; any other side clamps (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Texture<'a> {
    texels: &'a [u8],
    width: u16,
    height: u16,
}

impl<'a> Texture<'a> {
    /// The texture of `width × height` texels in `texels` (at least `width · height` of them;
    /// sides `1..=`[`MAX_TEXTURE_SIDE`]).
    pub const fn new(texels: &'a [u8], width: u16, height: u16) -> Result<Self, TextureError> {
        let mut k = 0;
        while k < 2 {
            let side = if k == 0 { width } else { height };
            if side == 0 || side > MAX_TEXTURE_SIDE {
                return Err(TextureError::BadSize {
                    side,
                    max: MAX_TEXTURE_SIDE,
                });
            }
            k += 1;
        }
        let needed = width as usize * height as usize;
        if texels.len() < needed {
            return Err(TextureError::WrongLength {
                table: TextureTable::Texels,
                given: texels.len(),
                needed,
            });
        }
        Ok(Texture {
            texels,
            width,
            height,
        })
    }

    /// Width in texels.
    pub const fn width(&self) -> u16 {
        self.width
    }

    /// Height in texels.
    pub const fn height(&self) -> u16 {
        self.height
    }

    /// The texel of column `i` and row `j` (any integers), wrapped on a power-of-two side
    /// and clamped on another.
    #[inline(always)]
    pub fn texel(&self, i: i32, j: i32) -> u8 {
        let c = fold(i, self.width);
        let r = fold(j, self.height);
        self.texels
            .get(r * self.width as usize + c)
            .copied()
            .unwrap_or(0)
    }
}

impl Texture<'_> {
    /// The texel at `k = row · width + column` (0 past the table, which [`Texture::new`]
    /// rules out for `k < width · height`).
    #[inline(always)]
    pub(crate) fn texel_at(&self, k: usize) -> u8 {
        self.texels.get(k).copied().unwrap_or(0)
    }
}

/// Texel index `i` on a side of `n` texels: `i mod n` for a power of two, else clamped.
#[inline(always)]
fn fold(i: i32, n: u16) -> usize {
    if n.is_power_of_two() {
        (i & (n as i32 - 1)) as usize
    } else {
        i.clamp(0, n as i32 - 1) as usize
    }
}

/// How a textured object is coloured: its texture, the exactness of the perspective
/// ([`TextureMode`]) and, when lit, the shade table its texel and light level go through
/// (`None`: the texel is written as it is, the object's levels unused).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Texturing<'a> {
    /// The image.
    pub texture: Texture<'a>,
    /// Exact, subdivided or affine.
    pub mode: TextureMode,
    /// Texel × light level → palette index, or `None` for unlit texels.
    pub shades: Option<ShadeTable<'a>>,
}
