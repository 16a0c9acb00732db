//! The cycle model's unit tests (`src/cycles.rs`'s `tests` module), built without the plugin's
//! QEMU-only symbols: `cargo test --manifest-path tools/qemu-icount/Cargo.toml`.
#[allow(dead_code)]
#[path = "../src/cycles.rs"]
mod cycles;
