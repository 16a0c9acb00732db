//! Subcommands of the `zscan` tool, one module each. Every `run` returns a descriptive error
//! string on bad input instead of panicking, and writes standard output and error through
//! [`out`] (a closed or full output is an error in words, not a panic).

pub mod bench;
pub mod chart;
pub mod export;
pub mod failures;
pub mod lines;
pub mod mesh;
pub mod out;
pub mod ranged;
pub mod render;
pub mod spans;
pub mod svg;
pub mod texture_chart;
pub mod visibility_chart;

/// Largest picture side the tool draws (`zscan lines`, `zscan render`'s viewport): 4096
/// pixels, so a picture's buffers (one byte of index, up to four of depth, three of colour per
/// pixel) stay below 128 MiB whatever the input asks for.
pub const MAX_PICTURE_SIDE: u16 = 4096;

/// `Ok` when a `width × height` picture is within [`MAX_PICTURE_SIDE`] on both sides and not
/// empty; otherwise the message names `what`, the values and the range. Checked before any
/// buffer is allocated.
pub fn check_picture_size(what: &str, width: u16, height: u16) -> Result<(), String> {
    let range = 1..=MAX_PICTURE_SIDE;
    if !range.contains(&width) || !range.contains(&height) {
        return Err(format!(
            "{what}: {width}×{height} pixels is outside the supported sizes \
             (width and height in 1..={MAX_PICTURE_SIDE})"
        ));
    }
    Ok(())
}

/// The error type of the subcommands: a message for the user.
pub type CliError = Box<dyn std::error::Error + Send + Sync>;
