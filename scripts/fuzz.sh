#!/usr/bin/env bash
# A long seeded fuzz campaign (docs/RELIABILITY.md): `scripts/fuzz.sh COUNT [SEED]` runs COUNT
# cases (default 100000) of the campaign SEED (default 1) over the scene parser and renderer,
# the OBJ reader, `zscan spans` and the core API, printing every input tried. Failing cases
# are written to host-tests/fuzz-corpus/found-*.case, which `cargo test` then replays.
set -euo pipefail
cd "$(dirname "$0")/.."
ZSCAN_FUZZ_CASES="${1:-100000}" ZSCAN_FUZZ_SEED="${2:-1}" \
  exec cargo test --release -p zscan-host --test fuzz -- --ignored long_campaign --nocapture
