#!/usr/bin/env bash
# Instruction counts of the benchmark cases (benches/cases.rs): host (callgrind) and
# Cortex-M4 (QEMU mps2-an386 + tools/qemu-icount), side by side, with each Cortex-M count's
# cycle estimate (the Cortex-M4 / Cortex-M0+ timing tables, tools/qemu-icount/src/cycles.rs)
# and frame_bunny's frames per second on an STM32F411 at 100 MHz (Cortex-M4) and, with --m0,
# an RP2040 at 133 MHz (Cortex-M0+). See docs/BENCHMARKS.md.
# Needs valgrind, qemu-system-arm, the thumbv7em-none-eabihf (and, for --m0,
# thumbv6m-none-eabi) targets and llvm-tools (.ci/run installs them all).
#   scripts/bench.sh            host + Cortex-M4
#   scripts/bench.sh --m0       also Cortex-M0 (QEMU microbit with enlarged RAM)
#   scripts/bench.sh --no-host --m0   the Cortex-M columns and both frame rates only
#   scripts/bench.sh --help     all options of `zscan bench`
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet --release -p zscan-host --bin zscan
exec "${CARGO_TARGET_DIR:-target}/release/zscan" bench "$@"
