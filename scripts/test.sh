#!/usr/bin/env bash
# The whole test suite from a fresh Debian 12 machine: install what is missing, build, run every test, then the
# benchmarks once (their ratios are reported, not asserted; each benchmark checks its results match first).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build_dir=${BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
