//! Render targets: where the raster stage's pixels end up.
//!
//! Role in the pipeline: the last stage. The raster stage writes palette indices into a
//! caller-provided [`Framebuffer`] (one `u8` per pixel) and, when a scene needs hidden-surface
//! removal, depth values into a caller-provided [`DepthBuffer`]. A [`Lut`] maps the 256 indices
//! to display colours, and [`flush`] sends the frame (or only its dirty rectangle) to any
//! embedded-graphics `DrawTarget` through `fill_contiguous`, the fast path display drivers
//! implement.
//!
//! Memory always comes from the caller: nothing here allocates. A frame may also be a *band*
//! (rows `top..top + height` of a taller picture), so a 320×240 display can be drawn in a few KB.
//!
//! Conventions: `x` grows to the right, `y` downward; row `y` of a buffer starts at
//! `(y - top) * stride`. Sizes are `u16` (a display is at most 65 535 pixels wide), so every
//! index computed here fits `usize` on 16-bit and wider targets without overflow.

mod depth;
mod flush;
mod framebuffer;
mod lut;
mod palette_index;

pub use depth::{DepthBuffer, DepthValue};
pub use flush::flush;
pub use framebuffer::Framebuffer;
pub use lut::{shaded_index, Lut, LutError};
pub use palette_index::PaletteIndex;

/// Why a buffer could not be wrapped as a render target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TargetError {
    /// Width or height is zero.
    ZeroSize,
    /// The stride is smaller than the width.
    StrideTooSmall {
        /// The stride given.
        stride: usize,
        /// The width it must at least be.
        width: u16,
    },
    /// The slice is too short for `height` rows of `stride` elements (the last row needs only `width`).
    BufferTooSmall {
        /// Elements needed.
        needed: usize,
        /// Elements given.
        len: usize,
    },
    /// A depth buffer does not have the framebuffer's size.
    SizeMismatch,
}

impl core::fmt::Display for TargetError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TargetError::ZeroSize => write!(f, "width and height must be at least 1"),
            TargetError::StrideTooSmall { stride, width } => {
                write!(f, "stride {stride} is smaller than the width {width}")
            }
            TargetError::BufferTooSmall { needed, len } => {
                write!(f, "buffer holds {len} elements but {needed} are needed")
            }
            TargetError::SizeMismatch => write!(f, "depth buffer and framebuffer differ in size"),
        }
    }
}

impl core::error::Error for TargetError {}

/// Checks a `width × height` buffer with `stride` against a slice length; returns the length needed.
pub(crate) fn check_layout(
    len: usize,
    width: u16,
    height: u16,
    stride: usize,
) -> Result<usize, TargetError> {
    if width == 0 || height == 0 {
        return Err(TargetError::ZeroSize);
    }
    if stride < width as usize {
        return Err(TargetError::StrideTooSmall { stride, width });
    }
    // (height - 1) * stride + width, computed with checked arithmetic: a huge stride must not wrap.
    let needed = (height as usize - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(width as usize))
        .ok_or(TargetError::BufferTooSmall {
            needed: usize::MAX,
            len,
        })?;
    if len < needed {
        return Err(TargetError::BufferTooSmall { needed, len });
    }
    Ok(needed)
}
