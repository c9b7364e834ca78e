#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The configure's libcamera gate (drivers/libcamera/CMakeLists.txt): one API only. A libcamera older than 0.3 (a
# planted libcamera.pc that says 0.0.3, Debian 12's own) fails the configure with the way to get 0.3; the same tree
# with -DOVERLAYD_LIBCAMERA=OFF configures, without the libcamera source.
#   libcamera_gate_test.sh SOURCE_DIR
set -euo pipefail
source_dir=$(realpath "$1")
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
mkdir -p "$work/pc"
cat >"$work/pc/libcamera.pc" <<PC
Name: libcamera
Description: Debian 12's own libcamera, as its .pc file says it
Version: 0.0.3
Cflags:
Libs:
PC
configure() { # configure NAME [CMAKE OPTIONS]: the output in $work/NAME.log, the exit status returned
    local name=$1 && shift
    PKG_CONFIG_PATH="$work/pc" cmake -S "$source_dir" -B "$work/$name" -G Ninja -DOVERLAYD_BUILD_TESTS=OFF \
        -DOVERLAYD_BUILD_BENCHMARKS=OFF "$@" >"$work/$name.log" 2>&1
}
fail=0
if configure gate; then
    echo "FAIL: the configure accepted libcamera 0.0.3"
    fail=1
elif ! tr -s ' \n' ' ' <"$work/gate.log" | grep -q "libcamera 0.0.3 found, overlayd's libcamera source needs 0.3 or later.*bookworm-backports.*scripts/install-deps.sh.*-DOVERLAYD_LIBCAMERA=OFF"; then
    echo "FAIL: the configure refused libcamera 0.0.3 without saying how to get 0.3:"
    cat "$work/gate.log"
    fail=1
fi
if ! configure off -DOVERLAYD_LIBCAMERA=OFF; then
    echo "FAIL: -DOVERLAYD_LIBCAMERA=OFF did not configure:"
    cat "$work/off.log"
    fail=1
elif ! grep -q "^OVERLAYD_HAVE_LIBCAMERA:INTERNAL=OFF" "$work/off/CMakeCache.txt"; then
    echo "FAIL: -DOVERLAYD_LIBCAMERA=OFF configured the libcamera source"
    fail=1
fi
[ $fail = 0 ] && echo "libcamera gate: 0.0.3 refused with the way to 0.3; OFF builds the rest"
exit $fail
