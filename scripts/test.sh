#!/usr/bin/env bash
# The project's test command (named in README and run by .ci/run): every test of the
# workspace, in release mode (the exhaustive raster tests are slow in debug builds).
set -euo pipefail
cd "$(dirname "$0")/.."
exec cargo test --workspace --release "$@"
