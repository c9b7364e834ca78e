#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The arm64 tier from a fresh Debian 12 x86-64 machine: the same sources cross-built for arm64 (aarch64) with
# Debian's cross compiler against a sysroot of Debian's own arm64 packages (scripts/arm64/sysroot.sh, cached in
# .cache/arm64), then the unit and replay tiers run by CTest under qemu-aarch64 (CMAKE_CROSSCOMPILING_EMULATOR; the
# replay tests start the arm64 `overlayd` through it too). V4L2 ioctls are not translated by qemu-user, so the V4L2
# logic is covered here by its seam tests, as natively.
#
# Environment: BUILD_DIR (default build-arm64), OVERLAYD_ARM64_CACHE (default .cache/arm64).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
build_dir=${BUILD_DIR:-build-arm64}
scripts/install-deps.sh --arm64
sysroot=$(scripts/arm64/sysroot.sh "${OVERLAYD_ARM64_CACHE:-.cache/arm64}")
echo "test-arm64: sysroot ready after $((SECONDS - start)) s"
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake -DOVERLAYD_ARM64_SYSROOT="$sysroot" \
    -DOVERLAYD_BUILD_TESTS=ON -DOVERLAYD_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
echo "test-arm64: cross build done after $((SECONDS - start)) s"
file "$build_dir/daemon/overlayd"
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
echo "test-arm64: unit and replay tiers passed under qemu-aarch64 after $((SECONDS - start)) s"
