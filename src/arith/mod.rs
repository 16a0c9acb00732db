//! The integer arithmetic every stage shares, and the one statement of what each target core
//! can do.
//!
//! Role: vocabulary below the pipeline. [`wide`] gives exact 32×32→64-bit products,
//! [`euclid`] TIPE's Euclidean division (floored quotient and remainder) with prepared
//! reciprocals for repeated divisors, [`isqrt`] the exact integer square root. Each states its
//! numeric contract; nothing here wraps or panics on the documented ranges.
//!
//! ## What each core can do
//! The facts below are the only place the crate asks which core it is built for (with
//! [`TINY_WRITER`], [`TINY_FLAT`] and [`TINY_WALKS_EDGES`], the one fast path and its forms,
//! derived from them). `build.rs` classifies the target once and sets
//! `cfg(hardware_divide)`; the others are read from the target's own cfgs. Every
//! choice made from them changes speed, never results: all targets draw the same pixels (the
//! CI compares the Cortex-M4 and Cortex-M0 checksums with the host's).
//!
//! | fact | x86-64, AArch64 | Cortex-M3/M4/M7 (thumbv7m/7em) | Cortex-M0/M0+ (thumbv6m) |
//! |---|---|---|---|
//! | [`HARDWARE_DIVIDE`]: a 32-bit division is one instruction | yes | yes (`sdiv`, `udiv`) | no: library routine |
//! | [`NARROW_MULTIPLY`]: no 32×32→64-bit multiply | no | no (`smull`) | yes: four 16-bit products inline |
//! | [`WIDE_REGISTERS`]: 64-bit registers, a 64-bit division is one instruction | yes | no | no |
//! | [`TINY_WRITER`]: the tiny-triangle writer is used | no | yes | yes |
//! | [`TINY_FLAT`]: flat triangles take it too | - | yes | no |
//! | [`TINY_WALKS_EDGES`]: its edges are walked, not divided per row | - | no | yes |

pub mod euclid;
pub mod isqrt;
pub(crate) mod scale;
pub mod wide;

/// True where a 32-bit division is one instruction: x86, x86-64, AArch64, and 32-bit Arm with
/// 32-bit atomics (Cortex-M3/M4 and richer cores; ARMv6-M, `thumbv6m`, has none), recognised
/// that way on stable Rust by `build.rs` (as `cfg(hardware_divide)`). Elsewhere (Cortex-M0/M0+)
/// a division is a library routine whose loop runs once per quotient bit, so divisions biased
/// to be unsigned (no sign fix-up, but a quotient 11 to 16 bits longer) take their signed forms
/// there, and a small triangle's divisions by its area go through reciprocals
/// ([`euclid::DivisorU32`]). A core misjudged by this test (an ARMv6K or ARMv7-A core without a
/// divider) is slower, not wrong.
pub const HARDWARE_DIVIDE: bool = cfg!(hardware_divide);

/// True on cores without a 32×32→64-bit multiply (ARMv6-M: Cortex-M0/M0+, recognised on
/// stable Rust as 32-bit Arm without 32-bit atomics, the same classification as `build.rs`'s).
/// There LLVM turns `a as i64 * b as i64` into a call of `__aeabi_lmul`, a full 64×64-bit
/// multiply (about 37 instructions, and the call's clobbered registers spill around it), and
/// [`wide::mul_wide`] takes four 16×16-bit products inline instead. Elsewhere the plain product
/// is one instruction (`smull`, `imul`).
pub const NARROW_MULTIPLY: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// True on 64-bit targets: 64-bit values live in one register and a 64-bit division is one
/// instruction, so paths that narrow operands to 32 bits first (the edge walkers' short edges,
/// [`euclid::div_floor_i64`]'s 32-bit case, the planes' 32-bit set-up) would only cost there.
pub const WIDE_REGISTERS: bool = cfg!(target_pointer_width = "64");

/// Whether small triangles take the tiny-triangle writer (`raster/triangle/tiny.rs`): on 32-bit
/// cores, where its 32-bit set-up replaces the general path's spilled state (Cortex-M4
/// `frame_bunny` −19 %, `frame_sphere` −11 %, `frame_bunny_bands16` −13 %; Cortex-M0, with
/// its edges walked and its divisions through the area's reciprocal, `frame_bunny` −6.3 %,
/// `frame_sphere` −0.4 %). Not on 64-bit hosts, whose general path is already 64-bit
/// arithmetic (x86-64 `frame_sphere` +1.7 %, `frame_bunny_flat` +10.8 %). The pictures are the
/// same either way (tested).
pub const TINY_WRITER: bool = !WIDE_REGISTERS;

/// Whether flat triangles (one luminance over a depth plane) take the tiny-triangle writer too:
/// not where a division is a library call, whose general path steps one attribute to the tiny
/// writer's two (Cortex-M0 `frame_bunny_flat` 6.05 M instructions there, 6.74 M through the
/// tiny writer).
pub const TINY_FLAT: bool = HARDWARE_DIVIDE;

/// Whether the tiny-triangle writer walks its edges from row to row by subtraction (one
/// division per edge) rather than dividing on every row: where a division is a library call.
pub const TINY_WALKS_EDGES: bool = !HARDWARE_DIVIDE;

/// `v / 2^s` rounded to nearest (ties toward +∞); `s = 0` returns `v`, `s > 62` gives 0.
/// Never overflows: the rounding bit is added after the shift.
#[inline(always)]
pub(crate) const fn shr_round(v: i64, s: u32) -> i64 {
    if s == 0 {
        v
    } else if s > 62 {
        0
    } else {
        // |v >> s| ≤ 2^62, so adding the rounding bit cannot overflow.
        (v >> s) + ((v >> (s - 1)) & 1)
    }
}
