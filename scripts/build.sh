#!/usr/bin/env bash
# Configures and builds overlayd into $BUILD_DIR (default build/): every target, or only the ones named as arguments
# (scripts/run.sh builds just the daemon it runs). Warnings are errors under CI.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
