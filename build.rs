//! Two jobs, both for the target being built:
//! - with the `cortex-m-example` feature, puts `memory.x` (the benchmark firmware's memory
//!   layout) on the linker's search path (the file is only read by cortex-m-rt's `link.x`;
//!   without the feature nothing is added, so a firmware depending on zscan links with its
//!   own `memory.x`);
//! - sets `cfg(hardware_divide)` where a 32-bit division is one instruction: x86, x86-64,
//!   AArch64, and 32-bit Arm with 32-bit atomics (Cortex-M3/M4 and richer; ARMv6-M, the
//!   Cortex-M0/M0+, has neither). `raster::euclid::HARDWARE_DIVIDE` is this cfg; a type whose
//!   fields differ by it (`raster::euclid::DivisorU32`) reads it directly.
use std::{env, fs, path::PathBuf};

fn main() {
    // Only for the benchmark firmware (feature `cortex-m-example`): a link search path set
    // here reaches every binary that depends on zscan, whose own memory.x it would shadow.
    if env::var_os("CARGO_FEATURE_CORTEX_M_EXAMPLE").is_some() {
        let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
        fs::copy("memory.x", out.join("memory.x")).expect("memory.x at the crate root");
        println!("cargo::rustc-link-search={}", out.display());
    }
    println!("cargo::rerun-if-changed=memory.x");
    println!("cargo::rerun-if-changed=build.rs");

    println!("cargo::rustc-check-cfg=cfg(hardware_divide)");
    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let atomics = env::var("CARGO_CFG_TARGET_HAS_ATOMIC").unwrap_or_default();
    let arm_with_atomics = arch == "arm" && atomics.split(',').any(|a| a == "32");
    if matches!(arch.as_str(), "x86" | "x86_64" | "aarch64") || arm_with_atomics {
        println!("cargo::rustc-cfg=hardware_divide");
    }
}
