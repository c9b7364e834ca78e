#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Every benchmark program on a Release build (as a user builds it), each with Google Benchmark's JSON output, merged
# into one file with the machine and the date (out/bench/bench-DATE.json), then the same-run ratios as Markdown
# tables (docs/speed.md's tables are this output). Reported, not asserted: each program refuses to time a wrong
# answer, but the figures depend on the machine and on what else runs on it.
#
# Usage: scripts/bench.sh [extra Google Benchmark flags]
#   BUILD_DIR    Release build folder (default build-release; configured if missing)
#   OUT_DIR      where the merged JSON goes (default out/bench)
#   MIN_TIME     --benchmark_min_time per case (default 0.2 s); REPETITIONS (default 3, the median is used)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build-release}
out_dir=${OUT_DIR:-out/bench}
min_time=${MIN_TIME:-0.2}
repetitions=${REPETITIONS:-3}

# The programs, as paths under the build folder.
benches=(
    tests/bench/projection_bench
    tests/bench/jpeg_bench
    tests/bench_overlay/overlay_scene_bench
    tests/bench_overlay/overlay_blend_bench
    tests/bench_overlay/overlay_sink_bench
    tests/bench_overlay/overlay_stroke_bench
)
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
    cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DOVERLAYD_BUILD_BENCHMARKS=ON
fi
build_type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build_dir/CMakeCache.txt")
[ "$build_type" = Release ] || echo "bench.sh: $build_dir is a $build_type build, not Release" >&2
targets=()
for bench in "${benches[@]}"; do targets+=(--target "$(basename "$bench")"); done
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}" >&2 # stdout: the tables only

mkdir -p "$out_dir"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for bench in "${benches[@]}"; do
    name=$(basename "$bench")
    echo "bench.sh: $name" >&2
    # The console table and the ratio lines go to the log; the JSON to its own file.
    "$build_dir/$bench" --benchmark_min_time="$min_time" --benchmark_repetitions="$repetitions" \
        --benchmark_color=false --benchmark_out="$work/$name.json" --benchmark_out_format=json "$@" \
        >"$work/$name.log" 2>&1 || { cat "$work/$name.log" >&2; exit 1; }
    grep "^ratio" "$work/$name.log" >&2 || true
done
out="$out_dir/bench-$(date -u +%Y%m%dT%H%M%SZ).json"
python3 scripts/bench_table.py merge "$out" "$work"/*.json
echo "bench.sh: wrote $out" >&2
