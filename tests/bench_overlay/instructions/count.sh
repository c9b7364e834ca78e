#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Instructions per iteration of a Google Benchmark case, counted by QEMU (count_plugin.c) rather than timed: the same
# measure for the arm64 build under qemu-aarch64 and the x86-64 build under qemu-x86_64 (-cpu max: the AVX2 loops;
# TCG has no AVX-512), repeatable whatever else the machine does.
#
#   count.sh "qemu-aarch64 -L .cache/arm64/sysroot" build-arm64-bench/tests/bench_overlay/overlay_scene_bench BM_Blend/static/YUYV/1280x720
#   count.sh "qemu-x86_64 -cpu max" build/tests/bench_overlay/overlay_scene_bench BM_Blend/static/YUYV/1280x720
#
# The benchmark runs twice, for 2 and 12 iterations (OVERLAYD_BENCH_ITERATIONS, cold_frames.h); the difference of
# the two totals over 10 is the cost of one iteration, without the process's start-up and the case's set-up.
set -euo pipefail
emulator=$1 bench=$2 case=$3
here=$(cd "$(dirname "$0")" && pwd)
plugin=${TMPDIR:-/tmp}/overlayd-count-plugin.so
[ "$plugin" -nt "$here/count_plugin.c" ] || gcc -shared -fPIC -O2 -Wall -Wextra -o "$plugin" "$here/count_plugin.c"

run() { # iterations -> "iterations instructions"
    local out
    # shellcheck disable=SC2086 # the emulator's words
    out=$(OVERLAYD_BENCH_ITERATIONS=$1 $emulator -plugin "$plugin" "$bench" --benchmark_filter="^$case(/iterations:[0-9]+)?\$" 2>&1 |
        sed 's/\x1b\[[0-9;]*m//g')
    local iterations instructions
    iterations=$(awk -v c="$case" '$1 == c || $1 == c "/iterations:" $NF { print $NF }' <<<"$out")
    instructions=$(grep -o "^instructions: [0-9]*" <<<"$out" | cut -d' ' -f2)
    [ -n "$iterations" ] && [ -n "$instructions" ] || { echo "count.sh: no result for $case:" >&2; echo "$out" >&2; exit 1; }
    echo "$iterations $instructions"
}
read -r n1 i1 < <(run 2)
read -r n2 i2 < <(run 12)
[ "$n2" -gt "$n1" ] || { echo "count.sh: the longer run made no more iterations ($n1, $n2)" >&2; exit 1; }
echo "$case: $(( (i2 - i1) / (n2 - n1) )) instructions per iteration ($n1 and $n2 iterations)"
