#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# overlayd side by side with the tools users would pick instead: the same scene (overlay_scene_bench's Speed scene:
# a perspective ground grid of 19 + 19 lines 2 px wide, an XYZ triad 3 px wide, 3 labels, anti-aliased) over the
# same raw 1920x1080 YUYV frames (ffmpeg's testsrc2) with overlayd, FFmpeg's filters, OpenCV's drawing and
# GStreamer's overlay elements, each run as its own process on one thread; prints each tool's CPU time per frame
# with and without drawing, and the ratios to overlayd, as a Markdown table (docs/speed.md, "Side by side").
# Each tool's first frame is checked to show the scene overlayd draws before anything is timed. --encoded adds
# the encoded row (scripts/peers/encoded.py): overlay + x264 encode, overlayd against FFmpeg (docs/streaming.md).
#
# Usage: scripts/compare-peers.sh [--frames N] [--runs R] [--tools LIST] [--out DIR] [--build-dir DIR]
#                                 [--no-build] [--no-install] [--encoded]
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
    cat <<'EOF'
Usage: scripts/compare-peers.sh [options]
  --frames N       frames to render per run (default 300; the frames file is N x 4 MB)
  --runs R         runs of every tool, interleaved; the table shows medians and the ranges (default 1)
  --tools LIST     comma-separated, of overlayd,ffmpeg,opencv,gst-cairo,gst-overlay (default all)
  --out DIR        work folder: frames, scene, configs, each tool's checked frame (default out/peers)
  --build-dir DIR  where overlayd and opencv_peer are built (default build-release, a Release build)
  --no-build       use the binaries in --build-dir as they are
  --no-install     do not install missing packages: run the tools that are there, then exit 77 if any was missing
  --encoded        then the encoded row: overlay + encode (x264), overlayd against FFmpeg, 150 frames of 720p
Installs when missing (apt-get): ffmpeg, gstreamer1.0-tools, gstreamer1.0-plugins-base, gstreamer1.0-plugins-good,
gstreamer1.0-x, python3-gi, python3-gi-cairo, gir1.2-gstreamer-1.0, fonts-dejavu-core.
EOF
}

frames=300 runs=1 tools="overlayd,ffmpeg,opencv,gst-cairo,gst-overlay" out=out/peers build_dir=build-release
build=1 install=1 encoded=0
while [ $# -gt 0 ]; do
    case "$1" in
    --frames) frames=${2:?--frames needs a number}; shift 2 ;;
    --runs) runs=${2:?--runs needs a number}; shift 2 ;;
    --tools) tools=${2:?--tools needs a list}; shift 2 ;;
    --out) out=${2:?--out needs a folder}; shift 2 ;;
    --build-dir) build_dir=${2:?--build-dir needs a folder}; shift 2 ;;
    --no-build) build=0; shift ;;
    --no-install) install=0; shift ;;
    --encoded) encoded=1; shift ;;
    -h | --help) usage; exit 0 ;;
    *) echo "compare-peers.sh: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
    esac
done
[[ $frames =~ ^[1-9][0-9]*$ ]] || { echo "compare-peers.sh: --frames must be a positive integer" >&2; exit 2; }
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "compare-peers.sh: --runs must be a positive integer" >&2; exit 2; }
IFS=, read -ra wanted <<<"$tools"
for t in "${wanted[@]}"; do
    case "$t" in overlayd | ffmpeg | opencv | gst-cairo | gst-overlay) ;;
    *) echo "compare-peers.sh: unknown tool '$t'" >&2; exit 2 ;;
    esac
done

# The packages each tool needs beyond the build's own (ffmpeg also makes the frames).
packages_for() {
    case "$1" in
    ffmpeg) echo ffmpeg fonts-dejavu-core ;;
    gst-cairo) echo gstreamer1.0-tools gstreamer1.0-plugins-base gstreamer1.0-plugins-good python3-gi \
        python3-gi-cairo gir1.2-gstreamer-1.0 gir1.2-gst-plugins-base-1.0 fonts-dejavu-core ;;
    gst-overlay) echo gstreamer1.0-tools gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-x \
        python3-gi gir1.2-gstreamer-1.0 fonts-dejavu-core ;;
    esac
}
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }

missing=()
for p in ffmpeg $(for t in "${wanted[@]}"; do packages_for "$t"; done | tr ' ' '\n' | sort -u); do
    installed "$p" || [[ " ${missing[*]} " == *" $p "* ]] || missing+=("$p")
done
skipped=()
if [ ${#missing[@]} -gt 0 ] && [ $install = 1 ]; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    echo "compare-peers.sh: installing ${missing[*]}" >&2
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
elif [ ${#missing[@]} -gt 0 ]; then
    installed ffmpeg || { echo "compare-peers.sh: ffmpeg is missing (it makes the frames)" >&2; exit 77; }
    kept=()
    for t in "${wanted[@]}"; do
        need=0
        for p in $(packages_for "$t"); do installed "$p" || need=1; done
        if [ $need = 1 ]; then skipped+=("$t"); else kept+=("$t"); fi
    done
    echo "compare-peers.sh: not installed (--no-install): ${missing[*]}; skipping ${skipped[*]}" >&2
    wanted=("${kept[@]}")
fi

if [ $build = 1 ]; then
    if [ ! -f "$build_dir/CMakeCache.txt" ]; then
        cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >&2
    fi
    cmake --build "$build_dir" -j "$(nproc)" --target overlayd opencv_peer \
        $([ $encoded = 1 ] && echo overlayd_stream_module) >&2
fi

list=$(IFS=,; echo "${wanted[*]}")
python3 scripts/peers/compare.py --overlayd "$build_dir/daemon/overlayd" \
    --opencv-peer "$build_dir/tests/peers/opencv_peer" --frames "$frames" --runs "$runs" --tools "$list" \
    --work "$out"
if [ $encoded = 1 ]; then
    python3 scripts/peers/encoded.py --overlayd "$build_dir/daemon/overlayd" --runs "$runs" --work "$out/encoded"
fi
if [ ${#skipped[@]} -gt 0 ]; then
    echo "compare-peers.sh: skipped ${skipped[*]} (packages missing)" >&2
    exit 77
fi
