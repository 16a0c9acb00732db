#!/usr/bin/env bash
# The standard bunny, 320x240, z-buffered, on a Cortex-M0 with 32 KB of RAM and 256 KB of
# flash (issue 18; see docs/BENCHMARKS.md, "32 KB footprint"). Builds examples/footprint (its
# own memory.x: the nRF51822-QFAC's sizes), runs it on QEMU's microbit with its RAM set to
# 32 KB, counts its instructions with tools/qemu-icount, runs the benchmark firmware
# (examples/cortex_m_bench.rs) for the frame_bunny case's count and checksum, and prints one
# line:
#   footprint: target=cortex-m0 ram_limit=32768 ram_used=N stack_peak=S instructions=I full_frame_instructions=F checksum=C full_frame_checksum=C2
# ram_used = the ELF's statics (.data + .bss + .uninit) + the painted stack's high-water mark.
# Fails (non-zero) if C != C2 or ram_used > 32768.
#   scripts/footprint.sh             Cortex-M0 (QEMU microbit, -global nrf51-soc.sram-size=0x8000)
#   scripts/footprint.sh --m4        the same firmware on a Cortex-M4 (QEMU mps2-an386)
#   scripts/footprint.sh --no-build  use the existing builds
# Needs qemu-system-arm, the thumbv6m-none-eabi / thumbv7em-none-eabihf targets and llvm-tools
# (.ci/run installs them).
set -euo pipefail
cd "$(dirname "$0")/.."

CORE=m0
BUILD=1
for arg in "$@"; do
    case "$arg" in
    --m4) CORE=m4 ;;
    --no-build) BUILD=0 ;;
    *)
        echo "usage: scripts/footprint.sh [--m4] [--no-build]" >&2
        exit 2
        ;;
    esac
done

RAM_LIMIT=32768
TARGET_DIR=$(mkdir -p "${CARGO_TARGET_DIR:-target}" && cd "${CARGO_TARGET_DIR:-target}" && pwd)
if [ "$CORE" = m0 ]; then
    TARGET=thumbv6m-none-eabi
    NAME=cortex-m0
    # The footprint firmware runs with exactly 32 KB of RAM (flash is 256 KB by default); the
    # benchmark firmware's full frame needs the RAM enlarged, as in scripts/bench.sh.
    QEMU_FOOTPRINT=(-machine microbit -global nrf51-soc.sram-size=0x8000)
    QEMU_BENCH=(-machine microbit -global nrf51-soc.sram-size=0x400000
        -global nrf51-soc.flash-size=0x400000)
else
    TARGET=thumbv7em-none-eabihf
    NAME=cortex-m4
    QEMU_FOOTPRINT=(-machine mps2-an386 -cpu cortex-m4)
    QEMU_BENCH=(-machine mps2-an386 -cpu cortex-m4)
fi
QEMU_COMMON=(-nographic -semihosting-config enable=on,target=native -icount shift=0)

BIN="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin"
PLUGIN="$TARGET_DIR/qemu-icount/release/libqemu_icount.so"
FOOTPRINT_ELF="$TARGET_DIR/examples/$TARGET/release/zscan-example-footprint"
BENCH_ELF="$TARGET_DIR/$TARGET/release/examples/cortex_m_bench"

if [ "$BUILD" = 1 ]; then
    cargo build --quiet --release --manifest-path tools/qemu-icount/Cargo.toml \
        --target-dir "$TARGET_DIR/qemu-icount"
    cargo build --quiet --release --example cortex_m_bench --features cortex-m-example \
        --target "$TARGET"
    cargo build --quiet --release --locked --manifest-path examples/footprint/Cargo.toml \
        --target "$TARGET" --target-dir "$TARGET_DIR/examples"
fi

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() {
    echo "footprint: FAILURE: $*" >&2
    exit 1
}

# Runs ELF $1 under QEMU (machine arguments after it) with the counting plugin; stdout to
# $WORK/<name>.out, the plugin's region lines to $WORK/<name>.regions.
counted_run() {
    local elf=$1 name=$2
    shift 2
    local nm begin end
    nm=$("$BIN/llvm-nm" "$elf")
    begin=$(awk '$3=="zscan_bench_begin"{print "0x"$1}' <<<"$nm")
    end=$(awk '$3=="zscan_bench_end"{print "0x"$1}' <<<"$nm")
    [ -n "$begin" ] && [ -n "$end" ] || fail "marker symbols not found in $elf"
    timeout 300 qemu-system-arm "$@" "${QEMU_COMMON[@]}" -kernel "$elf" \
        -plugin "$PLUGIN,begin=$begin,end=$end" >"$WORK/$name.out" 2>"$WORK/$name.err" ||
        fail "$name: QEMU exit status $? ($(cat "$WORK/$name.out" "$WORK/$name.err" | tail -n 3))"
    grep -q '^qemu-icount: regions [0-9]* errors 0$' "$WORK/$name.err" ||
        fail "$name: plugin protocol errors"
    awk '$1=="qemu-icount:" && $2=="region" {print $4}' "$WORK/$name.err" >"$WORK/$name.regions"
}

# The footprint firmware: statics from the ELF, stack peak and checksum from its line, the
# frame's instructions as the sum of its counted regions (region 0 is the empty one: the
# markers' own cost, subtracted from every other).
counted_run "$FOOTPRINT_ELF" footprint "${QEMU_FOOTPRINT[@]}"
LINE=$(grep '^footprint-firmware ' "$WORK/footprint.out") || fail "no footprint line"
field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<" $2"; }
STACK=$(field stack_peak "$LINE")
CHECKSUM=$(field checksum "$LINE")
STATICS=$("$BIN/llvm-size" -A "$FOOTPRINT_ELF" |
    awk '$1==".data" || $1==".bss" || $1==".uninit" {s += $2} END {print s + 0}')
INSTRUCTIONS=$(awk 'NR==1 {empty=$1; next} {sum += $1 - empty} END {print sum}' \
    "$WORK/footprint.regions")
RAM_USED=$((STATICS + STACK))

# The benchmark firmware: frame_bunny's region (its index among the cases) minus the empty
# case's, and its checksum.
counted_run "$BENCH_ELF" bench "${QEMU_BENCH[@]}"
INDEX=$(grep '^zscan-bench case ' "$WORK/bench.out" | awk '$3=="frame_bunny" {print NR}')
[ -n "$INDEX" ] || fail "no frame_bunny case in the benchmark firmware's output"
FULL=$(awk -v k="$INDEX" 'NR==1 {empty=$1} NR==k {raw=$1} END {print raw - empty}' \
    "$WORK/bench.regions")
FULL_CHECKSUM=$(grep '^zscan-bench case frame_bunny ' "$WORK/bench.out" |
    sed -n 's/.* checksum=\([0-9a-f]*\).*/\1/p')

echo "footprint: target=$NAME ram_limit=$RAM_LIMIT ram_used=$RAM_USED stack_peak=$STACK" \
    "instructions=$INSTRUCTIONS full_frame_instructions=$FULL checksum=$CHECKSUM" \
    "full_frame_checksum=$FULL_CHECKSUM"
[ "$CHECKSUM" = "$FULL_CHECKSUM" ] || fail "checksum $CHECKSUM differs from frame_bunny's $FULL_CHECKSUM"
[ "$RAM_USED" -le "$RAM_LIMIT" ] || fail "$RAM_USED bytes of RAM used, above $RAM_LIMIT"
