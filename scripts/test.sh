#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The whole test suite from a fresh Debian 12 machine: install what is missing, build, run every test through
# CTest, then print the projection benchmark's speed ratios against OpenCV measured in the same run (reported,
# not asserted: these machines drift by up to 1.5x; the benchmark itself refuses to time mismatching results).
# scripts/bench.sh runs every benchmark on a Release build for the tables of docs/speed.md.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# ON, not AUTO: without GoogleTest or Google Benchmark this must fail, not quietly build no tests.
scripts/build.sh -DOVERLAYD_BUILD_TESTS=ON -DOVERLAYD_BUILD_BENCHMARKS=ON
build_dir=${BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
"$build_dir/tests/bench/projection_bench" --benchmark_min_time=0.05 --benchmark_color=false 2>/dev/null |
    grep -o "ratio .*" || true
