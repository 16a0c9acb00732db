//! zscan's Cortex-M benchmark firmware: runs every case of `benches/cases.rs` on a 320×240
//! framebuffer and prints, over semihosting, one line per case:
//!
//! ```text
//! zscan-bench case <name> pixels=<n> checksum=<fnv1a hex> systick_instructions=<n>
//! ```
//!
//! between a `zscan-bench begin cases=<n> systick_resolution=40` line and a `zscan-bench end`
//! line, then exits with `debug::exit(EXIT_SUCCESS)` (QEMU's exit status 0).
//!
//! Two measurements of each case's call, both *instructions* (QEMU has no cycle model):
//! - **exact**: the call sits between `zscan_bench_begin` and `zscan_bench_end`, marker
//!   functions whose addresses the `qemu-icount` plugin (`tools/qemu-icount`) watches; the
//!   plugin prints `qemu-icount: region <k> <instructions>` to stderr, `k` = case index.
//! - **SysTick**: with `-icount shift=0` on `mps2-an386`, SysTick (core clock) ticks once per
//!   40 guest instructions, so `systick_instructions` has a resolution of 40 instructions
//!   (±40 per reading). On QEMU's `microbit` (16 MHz) it ticks once per 62.5 instructions
//!   (resolution 63).
//!
//! Both include the constant harness overhead; subtract the `empty` case (case 0).
//!
//! Build and run (see docs/BENCHMARKS.md):
//! ```text
//! cargo build --release --example cortex_m_bench --features cortex-m-example --target thumbv7em-none-eabihf
//! qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic \
//!   -semihosting-config enable=on,target=native -icount shift=0 \
//!   -kernel target/thumbv7em-none-eabihf/release/examples/cortex_m_bench
//! ```
//! For the Cortex-M0, build for `thumbv6m-none-eabi` and run on `-machine microbit` with
//! `-global nrf51-soc.sram-size=0x400000 -global nrf51-soc.flash-size=0x400000` (no real nRF51
//! has that much RAM; instruction counts do not depend on it).
#![no_std]
#![no_main]

use core::hint::black_box;
use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m::peripheral::{syst::SystClkSource, Peripherals, SYST};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;
use zscan::output::Framebuffer;

#[path = "../benches/cases.rs"]
#[allow(dead_code)]
mod cases;

/// Last marker written; gives each marker a body of its own (no identical-code folding).
static MARK: AtomicU32 = AtomicU32::new(0);

/// Opens a measured region (the plugin watches this function's first block).
#[no_mangle]
#[inline(never)]
pub extern "C" fn zscan_bench_begin(case: u32) {
    MARK.store(0xB000_0000 | case, Ordering::Relaxed);
    // Without an observer the store (and then the call) would be optimised away.
    black_box(&MARK);
}

/// Closes the measured region opened by [`zscan_bench_begin`].
#[no_mangle]
#[inline(never)]
pub extern "C" fn zscan_bench_end(case: u32) {
    MARK.store(0xE000_0000 | case, Ordering::Relaxed);
    black_box(&MARK);
}

/// Executes exactly `2 * n` instructions (`subs` + `bne` per iteration) for `n >= 1`.
#[inline(never)]
fn spin(n: u32) {
    // SAFETY: the asm only decrements a scratch register it owns and branches locally; it
    // touches no memory and no other register (asm is needed here: it is the one way to get
    // a loop whose instruction count the compiler cannot change).
    unsafe {
        core::arch::asm!(
            "2:",
            "subs {0}, #1",
            "bne 2b",
            inout(reg) n => _,
            options(nomem, nostack),
        );
    }
}

/// One counted region around `spin(n)`: the self-test's only code path.
#[inline(never)]
fn measured_spin(region: u32, n: u32) {
    zscan_bench_begin(region);
    spin(n);
    zscan_bench_end(region);
}

/// SysTick reload: the full 24 bits.
const RELOAD: u32 = 0x00FF_FFFF;
/// Guest instructions per SysTick tick under `-icount shift=0`, times 2 (QEMU's virtual clock
/// runs one instruction per ns; SysTick counts the board's core clock): 40 on mps2-an386
/// (25 MHz), 62.5 on microbit (16 MHz). The hard-float build runs on mps2-an386, the
/// thumbv6m build on microbit.
#[cfg(target_abi = "eabihf")]
const TWICE_INSTRUCTIONS_PER_TICK: u32 = 80;
#[cfg(not(target_abi = "eabihf"))]
const TWICE_INSTRUCTIONS_PER_TICK: u32 = 125;

#[entry]
fn main() -> ! {
    let mut p = Peripherals::take().expect("first and only take");
    p.SYST.set_clock_source(SystClkSource::Core);
    p.SYST.set_reload(RELOAD);
    p.SYST.clear_current();
    p.SYST.enable_counter();

    // The framebuffer and the storage (depth samples, vertex scratch) live on the stack
    // (cortex-m-rt puts it at the top of the 4 MB RAM), declared once like an application's
    // buffers.
    let mut pixels = [0u8; cases::FB_LEN];
    let mut storage = cases::Storage::new();
    hprintln!(
        "zscan-bench begin cases={} systick_resolution={}",
        cases::CASES.len(),
        TWICE_INSTRUCTIONS_PER_TICK.div_ceil(2)
    );
    for (i, case) in cases::CASES.iter().enumerate() {
        let mut fb = Framebuffer::new(&mut pixels, cases::WIDTH, cases::HEIGHT)
            .expect("the buffer has the cases' size");
        // Warm-up call (keeps the host and target harnesses identical), then the measured one.
        fb.clear(0);
        black_box((case.run)(black_box(&mut fb), black_box(&mut storage)));
        fb.clear(0);
        // `black_box` makes the framebuffer escape and the call indirect, so the compiler can
        // neither move drawing across the markers nor inline the case into the loop.
        let run = black_box(case.run);
        let fb = black_box(&mut fb);
        let storage = black_box(&mut storage);
        let t0 = SYST::get_current();
        zscan_bench_begin(i as u32);
        let px = run(fb, storage);
        zscan_bench_end(i as u32);
        let t1 = SYST::get_current();
        let ticks = t0.wrapping_sub(t1) & RELOAD;
        let sum = cases::fnv1a(&pixels);
        hprintln!(
            "zscan-bench case {} pixels={} checksum={:08x} systick_instructions={}",
            case.name,
            px,
            sum,
            ticks * TWICE_INSTRUCTIONS_PER_TICK / 2
        );
    }
    // Self-test of the counter: two regions around a loop of exactly 2 instructions per
    // iteration; the plugin's counts must differ by exactly 2 × (2000 - 1000) = 2000.
    // Both regions run the very same code (`measured_spin`), so their overheads are equal
    // whatever the compiler does around the call.
    for (k, n) in [1000u32, 2000].into_iter().enumerate() {
        measured_spin(black_box((cases::CASES.len() + k) as u32), black_box(n));
        hprintln!("zscan-bench selftest spin={}", n);
    }
    hprintln!("zscan-bench end");
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}
