//! zscan's footprint firmware: the standard bunny (1,839 vertices, 3,674 triangles, mesh in
//! flash), 320×240, exact Gouraud with the 16-bit z-buffer's picture, drawn on a Cortex-M0
//! with **32 KB of RAM and 256 KB of flash** (the nRF51822-QFAC's sizes: `memory.x` beside
//! `Cargo.toml`) by `render_in_compact_bands` in bands of 10 rows; each finished band is streamed
//! into the bench cases' FNV-1a checksum, as a display flush would stream it. It prints, over
//! semihosting, one line:
//!
//! ```text
//! footprint-firmware stack_peak=<bytes> checksum=<fnv1a hex> covered=<pixels> bands=<n>
//! ```
//!
//! then exits with status 0. `scripts/footprint.sh` builds and runs it and adds the statics
//! (from the ELF) and the instruction counts.
//!
//! - **Stack peak**: at start, every word between the end of the statics (cortex-m-rt's
//!   `_stack_end`) and the current stack pointer is painted with a pattern; after the frame,
//!   the lowest word no longer holding it gives the high-water mark (`_stack_start` minus its
//!   address). All of the frame's memory lives on `main`'s stack (band, compact vertices and
//!   polygon table in `cases::scene::CompactMemory`), so it is inside that figure.
//! - **Instructions**: region markers for the `qemu-icount` plugin (`tools/qemu-icount`), as
//!   in `examples/cortex_m_bench.rs`: region 0 is empty (the markers' own cost); the frame is
//!   counted from the call of `compact_bands` to its return, except while a band is hashed
//!   (the band callback closes the region before hashing and opens it again after), so the
//!   count compares with the `frame_bunny` bench case, whose region holds no checksum.
//!
//! A crate of its own (its own workspace and lock file), so that its `memory.x` is the one
//! linked. Build and run on the Cortex-M0 (`scripts/footprint.sh` does this and more):
//! ```text
//! cargo build --release --manifest-path examples/footprint/Cargo.toml \
//!   --target thumbv6m-none-eabi --target-dir target/examples
//! qemu-system-arm -machine microbit -global nrf51-soc.sram-size=0x8000 -nographic \
//!   -semihosting-config enable=on,target=native -icount shift=0 \
//!   -kernel target/examples/thumbv6m-none-eabi/release/zscan-example-footprint
//! ```
#![no_std]
#![no_main]

use core::hint::black_box;
use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;

#[path = "../../../benches/cases.rs"]
#[allow(dead_code)]
mod cases;

/// Last marker written; gives each marker a body of its own (no identical-code folding).
static MARK: AtomicU32 = AtomicU32::new(0);

/// Opens a counted region (the plugin watches this function's first block).
#[no_mangle]
#[inline(never)]
pub extern "C" fn zscan_bench_begin(region: u32) {
    MARK.store(0xB000_0000 | region, Ordering::Relaxed);
    black_box(&MARK);
}

/// Closes the region opened by [`zscan_bench_begin`].
#[no_mangle]
#[inline(never)]
pub extern "C" fn zscan_bench_end(region: u32) {
    MARK.store(0xE000_0000 | region, Ordering::Relaxed);
    black_box(&MARK);
}

/// The word painted over the free stack.
const PAINT: u32 = 0xA5C3_5A3C;

extern "C" {
    /// cortex-m-rt's lowest stack address: the end of the statics (`.data`, `.bss`, `.uninit`).
    static _stack_end: u32;
    /// cortex-m-rt's initial stack pointer: the end of RAM.
    static _stack_start: u32;
}

/// `(lowest, highest)` address of the stack.
fn stack_bounds() -> (usize, usize) {
    (
        core::ptr::addr_of!(_stack_end) as usize,
        core::ptr::addr_of!(_stack_start) as usize,
    )
}

/// Paints every word from the end of the statics to 64 bytes below this function's stack
/// pointer (out of line: its own frame lies above that).
#[inline(never)]
fn paint_stack() {
    let sp = cortex_m::register::msp::read() as usize;
    let mut at = stack_bounds().0;
    while at + 64 < sp {
        // SAFETY: `at` is word-aligned (cortex-m-rt aligns `_stack_end` to 4) and lies between
        // the end of the statics and below the live stack: RAM that nothing else uses yet.
        unsafe { (at as *mut u32).write_volatile(PAINT) };
        at += 4;
    }
}

/// The stack's high-water mark in bytes: from the top of RAM down to the lowest word that no
/// longer holds the paint.
fn stack_peak() -> usize {
    let (low, high) = stack_bounds();
    let mut at = low;
    // SAFETY: word-aligned reads inside the stack's RAM.
    while at < high && unsafe { (at as *const u32).read_volatile() } == PAINT {
        at += 4;
    }
    high - at
}

#[entry]
fn main() -> ! {
    // The frame's memory, on the stack like the rest (27,986 bytes: see CompactSizes::bytes).
    let mut memory = cases::scene::CompactMemory::new();
    paint_stack();
    zscan_bench_begin(0);
    zscan_bench_end(0);
    let mut checksum = cases::FNV1A_START;
    let mut bands = 0u32;
    zscan_bench_begin(1);
    let covered = cases::scene::compact_bands(&cases::scene::BUNNY, &mut memory, |band| {
        zscan_bench_end(1);
        // The display flush: each row, top to bottom, into the checksum.
        for (_, row) in band.rows() {
            checksum = cases::fnv1a_from(checksum, row);
        }
        bands += 1;
        zscan_bench_begin(1);
        Ok::<(), zscan::render::RenderError>(())
    });
    zscan_bench_end(1);
    let peak = stack_peak();
    match covered {
        Ok(covered) => {
            hprintln!(
                "footprint-firmware stack_peak={} checksum={:08x} covered={} bands={}",
                peak,
                checksum,
                covered,
                bands
            );
            debug::exit(debug::EXIT_SUCCESS);
        }
        Err(e) => {
            hprintln!("footprint-firmware error: {}", e);
            debug::exit(debug::EXIT_FAILURE);
        }
    }
    #[allow(clippy::empty_loop)]
    loop {}
}
