#!/usr/bin/env bash
# The project's test command (named in README and run by .ci/run): every test of the
# workspace, in release mode (the exhaustive raster tests are slow in debug builds), then
# again with overflow checks and debug assertions on (the `checked` profile of Cargo.toml).
# Arguments are passed to both runs (e.g. a test name filter).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --release "$@"
cargo test --workspace --profile checked "$@"
