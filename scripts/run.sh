#!/usr/bin/env bash
# Installs what is missing, builds, and runs overlayd's main job on its embedded default: the synthetic 3D scene
# (a checkerboard ground seen through a distorting camera, with a projected grid and axes) written to a PNG.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build_dir=${BUILD_DIR:-build}
mkdir -p out
"$build_dir/daemon/overlayd-preview" out/preview.png
echo "open out/preview.png to see it"
