#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs what is missing, builds, and runs overlayd on its embedded default, config/examples/demo.toml: a
# synthetic 1280x720 camera over a checkerboard ground with a projected grid, axes, labels and a timestamp. It stops
# by itself after 150 frames (5 s at 30 fps) and leaves out/demo.y4m and a PNG snapshot every 30 frames.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --demo # the daemon's build only; scripts/test.sh adds the test tools
scripts/build.sh overlayd # only the daemon this runs (scripts/test.sh builds the rest)
build_dir=${BUILD_DIR:-build}
mkdir -p out
"$build_dir/daemon/overlayd" run --config config/examples/demo.toml --frames 150
echo
echo "Done. To look at the result:"
echo "  ffplay out/demo.y4m              # the 150-frame video (or: mpv out/demo.y4m)"
echo "  xdg-open out/demo-0000.png       # snapshots every 30 frames: $(ls out/demo-*.png 2>/dev/null | tr '\n' ' ')"
echo "Change the camera or the annotations in config/examples/demo.toml; 'overlayd check-config FILE' validates it."
