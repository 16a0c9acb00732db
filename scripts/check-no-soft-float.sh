#!/usr/bin/env bash
# Fails when zscan's integer-only core pulls in a software floating-point routine on a
# Cortex-M0 (thumbv6m-none-eabi: no FPU, so every f32/f64 operation becomes a libcall such as
# __aeabi_fmul or __addsf3), and prints the core's code size on a Cortex-M4 (thumbv7em).
#
# What is checked (all with llvm-nm from the rustup component llvm-tools):
#  1. the core built for thumbv6m WITHOUT LTO, so its rlib holds machine code for its
#     non-generic functions (except small ones rustc leaves to cross-crate inlining): no
#     undefined or defined soft-float symbol;
#  2. the Cortex-M example built for thumbv6m, a linked binary that calls the core's raster
#     functions through the benchmark cases (generic and inlined code included): no soft-float
#     symbol linked in;
#  3. the thumbv7em example: no hardware float instruction (v*.f32 / v*.f64) in zscan's code.
#
# Usage: scripts/check-no-soft-float.sh           run the checks
#        scripts/check-no-soft-float.sh --self-test  show that the detector fails on a float:
#            compiles a one-line f32 multiply for thumbv6m and expects the check to reject it.
set -euo pipefail
cd "$(dirname "$0")/.."

SYSROOT=$(rustc --print sysroot)
HOST=$(rustc -vV | sed -n 's/^host: //p')
BIN="$SYSROOT/lib/rustlib/$HOST/bin"
NM="$BIN/llvm-nm"
SIZE="$BIN/llvm-size"
OBJDUMP="$BIN/llvm-objdump"
[ -x "$NM" ] || { echo "llvm-nm not found: rustup component add llvm-tools" >&2; exit 2; }
TARGET_DIR=${CARGO_TARGET_DIR:-target}

# Soft-float routines: ARM EABI (__aeabi_fadd, __aeabi_d2iz, __aeabi_i2f, __aeabi_ul2d, ...),
# libgcc/compiler-rt style (__addsf3, __floatsisf, __fixdfsi, __extendsfdf2, __eqsf2, ...),
# and libm's float functions (sinf, sqrt, powf, ...).
SOFT_FLOAT_RE='^(__aeabi_[fd][a-z0-9]*|__aeabi_u?[il]2[fd]|__[a-z]*(sf|df|tf|hf)[a-z0-9]*|(sin|cos|tan|asin|acos|atan|atan2|sqrt|cbrt|hypot|floor|ceil|round|trunc|rint|fmod|pow|powi|exp|exp2|log|log2|log10|fma|fabs|copysign)f?)$'

# Reads `llvm-nm` output on stdin; prints the soft-float symbols found (demangled names are
# not needed: these routines are C symbols).
soft_float_symbols() {
    awk '{print $NF}' | grep -E "$SOFT_FLOAT_RE" | sort -u || true
}

check_nm() { # label, files...
    local label=$1; shift
    local found
    found=$("$NM" --no-sort "$@" 2>/dev/null | soft_float_symbols)
    if [ -n "$found" ]; then
        echo "FAIL: $label references soft-float routines:" >&2
        echo "$found" | sed 's/^/    /' >&2
        return 1
    fi
    echo "ok: $label: no soft-float symbol"
}

if [ "${1:-}" = "--self-test" ]; then
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    # `#[no_mangle]` so rustc emits the function (small pub functions are otherwise left to
    # cross-crate inlining and not compiled into the library at all).
    printf '#![no_std]\n#[no_mangle]\npub extern "C" fn zscan_selftest_scale(a: f32, b: i32) -> i32 { (a * b as f32) as i32 }\n' >"$tmp/float.rs"
    rustc --edition 2021 --target thumbv6m-none-eabi --crate-type lib -C opt-level=2 \
        -C codegen-units=1 --emit obj -o "$tmp/float.o" "$tmp/float.rs"
    echo "self-test: an f32 multiply compiled for thumbv6m; the FAIL report below is expected"
    if check_nm "self-test object (f32 multiply)" "$tmp/float.o"; then
        echo "SELF-TEST FAILED: a float multiply went undetected" >&2
        exit 1
    fi
    echo "self-test ok: the check rejects an f32 multiply on thumbv6m"
    exit 0
fi

echo "== core rlib for thumbv6m-none-eabi (no LTO: machine code of its non-generic functions)"
CARGO_PROFILE_RELEASE_LTO=false cargo build --quiet --release -p zscan --target thumbv6m-none-eabi \
    --target-dir "$TARGET_DIR/no-soft-float"
rlib=$(ls -t "$TARGET_DIR"/no-soft-float/thumbv6m-none-eabi/release/deps/libzscan-*.rlib | head -n1)
check_nm "core rlib $(basename "$rlib")" "$rlib"

echo "== Cortex-M example for thumbv6m-none-eabi (linked, LTO)"
cargo build --quiet --release --example cortex_m_bench --features cortex-m-example --target thumbv6m-none-eabi
elf6="$TARGET_DIR/thumbv6m-none-eabi/release/examples/cortex_m_bench"
check_nm "linked example $(basename "$elf6") (thumbv6m)" "$elf6"

echo "== Cortex-M example for thumbv7em-none-eabihf: FPU instructions in zscan code"
cargo build --quiet --release --example cortex_m_bench --features cortex-m-example --target thumbv7em-none-eabihf
elf7="$TARGET_DIR/thumbv7em-none-eabihf/release/examples/cortex_m_bench"
fpu=$("$OBJDUMP" -d --no-show-raw-insn --demangle "$elf7" |
    awk '/^[0-9a-f]+ </ {f=$0} /\tv[a-z]+\.f(32|64)/ && f ~ /zscan|cases/ {print f": "$0}' || true)
if [ -n "$fpu" ]; then
    echo "FAIL: floating-point instructions in zscan code:" >&2
    echo "$fpu" | head -20 >&2
    exit 1
fi
echo "ok: no floating-point instruction in zscan code (thumbv7em)"

echo "== code size (thumbv7em-none-eabihf, opt-level 3, LTO)"
"$SIZE" -A "$elf7" | awk '$1==".text"{print "example .text: "$2" bytes (firmware total: core + semihosting + formatting + cases)"}'
"$NM" --print-size --size-sort --radix=d --demangle "$elf7" |
    awk '$4 ~ /^zscan::/ {n++; s+=$2+0} END {print "core (zscan::) functions linked: "n", "s" bytes"}'
"$NM" --print-size --size-sort --radix=d --demangle "$elf6" |
    awk '$4 ~ /^zscan::/ {n++; s+=$2+0} END {print "core (zscan::) functions linked on thumbv6m: "n", "s" bytes"}'
CARGO_PROFILE_RELEASE_LTO=false cargo build --quiet --release -p zscan --target thumbv7em-none-eabihf \
    --target-dir "$TARGET_DIR/no-soft-float"
rlib7=$(ls -t "$TARGET_DIR"/no-soft-float/thumbv7em-none-eabihf/release/deps/libzscan-*.rlib | head -n1)
"$SIZE" "$rlib7" 2>/dev/null | awk 'NR>1 && $1 ~ /^[0-9]+$/ {t+=$1} END {print "core rlib (thumbv7em, opt-level 3, no LTO, non-generic code only): text "t" bytes"}'
echo "no-soft-float check passed"
