//! zscan-host: the std side of zscan.
//!
//! - [`image`]: writing framebuffers through a LUT to PNG, PGM and PPM.
//! - [`obj`]: reading Wavefront OBJ meshes (positions and polygons).
//! - [`mod@reference`]: independent reference implementations (exact rational fill, Bresenham by
//!   definition, ...), kept apart from the production code they check.
//! - [`cluster`]: vertex clustering, the coarse meshes of small displays.
//! - [`cli`]: the subcommands of the `zscan` tool.
//! - [`failures`]: where the hidden-surface methods fail, as scenes, counts and pictures.
//! - [`texture_failures`]: where the fast texture modes depart from the exact one and from the
//!   `f64` definition, as counts and pictures.
#![deny(missing_docs)]
// Standard output and error go through `cli::out` (a failure is an error, not a panic).
#![deny(clippy::print_stdout, clippy::print_stderr)]

pub mod cli;
pub mod cluster;
pub mod core_render;
pub mod failures;
pub mod fuzz;
pub mod image;
pub mod mesh_files;
pub mod obj;
pub mod reference;
pub mod scenes;
#[path = "../../src/test_rng.rs"]
pub mod test_rng;
pub mod texture_failures;
pub mod texture_png;
