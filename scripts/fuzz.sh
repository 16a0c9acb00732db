#!/usr/bin/env bash
# A long seeded fuzz campaign (docs/RELIABILITY.md):
#   scripts/fuzz.sh [--checked] [--progress] COUNT [SEED] [FIRST]
# runs COUNT cases (default 100000) of the campaign SEED (default 1), from case index FIRST
# (default 0: two shards of one campaign run as FIRST = 0 and FIRST = COUNT), over the scene
# parser and renderer, the OBJ reader, `zscan spans`, the core's buffers, the planner (`plan`,
# `plan_frame`, `draw_plan` with random memory), every visibility method against the z-buffer
# and the fill under both rules and through `ConvexWindow` against the exact reference
# (host-tests/src/fuzz/, one file per family). It prints every input
# tried, or with --progress one line every 100,000 cases (a case is regenerated from its seed
# and index), then the build, the cases per target, the accepted inputs, the time per target
# and the failures. --checked runs the `checked` profile (overflow checks and debug
# assertions on) instead of release. Failing cases are written to
# host-tests/fuzz-corpus/found-*.case, which `cargo test` then replays.
set -euo pipefail
cd "$(dirname "$0")/.."
profile=--release
log=inputs
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --checked) profile="--profile checked" ;;
    --progress) log=progress ;;
    *) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
# shellcheck disable=SC2086 # $profile is one or two words
ZSCAN_FUZZ_CASES="${1:-100000}" ZSCAN_FUZZ_SEED="${2:-1}" ZSCAN_FUZZ_FIRST="${3:-0}" \
  ZSCAN_FUZZ_LOG="$log" \
  exec cargo test $profile -p zscan-host --test fuzz -- --ignored long_campaign --nocapture
