#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Configures and builds overlayd into $BUILD_DIR (default build/): every target, or only the ones named as arguments
# (scripts/run.sh builds just the daemon it runs). Arguments starting with -D go to the configure step
# (scripts/test.sh: -DOVERLAYD_BUILD_TESTS=ON). Warnings are errors under CI.
#
# One build type, RelWithDebInfo, for the demo and the tests alike: they share the build folder, so the tests reuse the
# daemon the demo built instead of compiling it again (scripts/bench.sh keeps its own Release folder).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
configure=()
targets=()
for arg in "$@"; do
    case "$arg" in
    -D*) configure+=("$arg") ;;
    *) targets+=(--target "$arg") ;;
    esac
done
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${configure[@]}"
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
