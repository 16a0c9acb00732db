#!/usr/bin/env bash
# Instruction counts of the benchmark cases (benches/cases.rs): host (callgrind) and
# Cortex-M4 (QEMU mps2-an386 + tools/qemu-icount), side by side. See docs/BENCHMARKS.md.
# Needs valgrind, qemu-system-arm, the thumbv7em-none-eabihf (and, for --m0,
# thumbv6m-none-eabi) targets and llvm-tools (.ci/run installs them all).
#   scripts/bench.sh            host + Cortex-M4
#   scripts/bench.sh --m0       also Cortex-M0 (QEMU microbit with enlarged RAM)
#   scripts/bench.sh --help     all options of `zscan bench`
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet --release -p zscan-host --bin zscan
exec "${CARGO_TARGET_DIR:-target}/release/zscan" bench "$@"
