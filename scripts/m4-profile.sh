#!/usr/bin/env bash
# Per-function Cortex-M4 (or, with --m0, Cortex-M0) instruction profile of one benchmark case (benches/cases.rs), from the
# qemu-icount plugin's per-translation-block counts inside that case's region, attributed to
# the firmware's symbols (llvm-nm). Instructions, not cycles; inlined code counts in its caller.
#   scripts/m4-profile.sh frame_bunny [TOP]
#   scripts/m4-profile.sh --m0 frame_bunny [TOP]   the Cortex-M0 (QEMU microbit, RAM enlarged)
# Needs what scripts/bench.sh needs (qemu-system-arm, the thumbv7em target, llvm-tools).
set -euo pipefail
cd "$(dirname "$0")/.."
TARGET=thumbv7em-none-eabihf
MACHINE=(-machine mps2-an386 -cpu cortex-m4)
CORE=Cortex-M4
if [ "${1:-}" = --m0 ]; then
    shift
    TARGET=thumbv6m-none-eabi
    MACHINE=(-machine microbit -global nrf51-soc.sram-size=0x400000
        -global nrf51-soc.flash-size=0x400000)
    CORE=Cortex-M0
fi
CASE=${1:?usage: scripts/m4-profile.sh [--m0] CASE [TOP]}
TOP=${2:-25}
TARGET_DIR=${CARGO_TARGET_DIR:-target}
cargo build --quiet --release -p zscan-host --bin zscan
cargo build --quiet --release --example cortex_m_bench --features cortex-m-example \
    --target "$TARGET"
cargo build --quiet --release --manifest-path tools/qemu-icount/Cargo.toml \
    --target-dir "$TARGET_DIR/qemu-icount"
ELF="$TARGET_DIR/$TARGET/release/examples/cortex_m_bench"
PLUGIN="$TARGET_DIR/qemu-icount/release/libqemu_icount.so"
NM="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin/llvm-nm"
# Region k is the k-th case in the firmware's order (the host prints the same order).
K=$("$TARGET_DIR/release/zscan" bench --checksums |
    awk -v c="$CASE" '$3 == c { print NR - 1; found = 1 } END { if (!found) exit 1 }') ||
    { echo "unknown case $CASE" >&2; exit 1; }
BEGIN=$("$NM" "$ELF" | awk '$3=="zscan_bench_begin"{print "0x"$1}')
END=$("$NM" "$ELF" | awk '$3=="zscan_bench_end"{print "0x"$1}')
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
timeout 300 qemu-system-arm "${MACHINE[@]}" -nographic \
    -semihosting-config enable=on,target=native -icount shift=0 -kernel "$ELF" \
    -plugin "$PLUGIN,begin=$BEGIN,end=$END,profile=$WORK/profile.txt,profile_region=$K" \
    >/dev/null 2>&1
"$NM" --demangle --numeric-sort --defined-only "$ELF" |
    awk '$2 ~ /^[tTwW]$/ { addr = $1; $1 = ""; $2 = ""; sub(/^  /, ""); print addr "\t" $0 }' \
        >"$WORK/symbols.txt"
python3 - "$WORK/symbols.txt" "$WORK/profile.txt" "$TOP" "$CASE" "$CORE" <<'EOF'
import bisect, re, sys
syms = []
for line in open(sys.argv[1]):
    a, name = line.rstrip("\n").split("\t", 1)
    syms.append((int(a, 16) & ~1, re.sub(r"::h[0-9a-f]{16}$", "", name)))
syms.sort()
addrs = [a for a, _ in syms]
total, per = 0, {}
for line in open(sys.argv[2]):
    a, n, c = line.split()
    a, cost = int(a, 16) & ~1, int(n) * int(c)
    i = bisect.bisect_right(addrs, a) - 1
    name = syms[i][1] if i >= 0 else "?"
    per[name] = per.get(name, 0) + cost
    total += cost
print(f"{sys.argv[4]}: {total:,} instructions ({sys.argv[5]}, inside the region)")
for name, cost in sorted(per.items(), key=lambda kv: -kv[1])[: int(sys.argv[3])]:
    print(f"{cost:>12,} {100 * cost / total:5.1f}%  {name[:110]}")
EOF
