#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The README's pictures, made by the real binary so that they show what it does today:
#   docs/images/demo.png     the demo scene's first frame (overlayd render of config/examples/demo.toml)
#   docs/alignment-page.png  the alignment page in headless Chromium, overlayd serving the demo scene
# Needs a built overlayd (scripts/build.sh overlayd) and, for the page, Debian's chromium and python3-websocket
# (scripts/install-deps.sh installs both). BUILD_DIR overrides build/.
set -euo pipefail
cd "$(dirname "$0")/.."
overlayd=${BUILD_DIR:-build}/daemon/overlayd
mkdir -p docs/images
"$overlayd" render --config config/examples/demo.toml --frames 1 --output docs/images/demo.png
echo "wrote docs/images/demo.png"
python3 scripts/alignment_picture.py --overlayd "$overlayd" --output docs/alignment-page.png
