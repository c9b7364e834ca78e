#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The GStreamer side of scripts/compare-peers.sh: runs one gst-launch pipeline to its end in this process (so that
every GStreamer case, drawing or not, pays the same start-up), and, when the pipeline has a cairooverlay named
`draw`, draws the scene file's lines and text with cairo on every frame (anti-aliased), as a user of cairooverlay
writes it. Run by Debian's own Python (python3-gi, python3-gi-cairo).

Usage: gst_peer.py PIPELINE [SCENE]   SCENE: lines of `line x0 y0 x1 y1 width r g b` / `text x y size r g b TEXT`
"""
import sys

import gi

gi.require_version("Gst", "1.0")
from gi.repository import Gst  # noqa: E402


def read_scene(path):
    items = []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if fields and fields[0] == "line":
                items.append(("line", [float(v) for v in fields[1:9]]))
            elif fields and fields[0] == "text":
                items.append(("text", [float(v) for v in fields[1:7]], line.split(None, 7)[7].rstrip("\n")))
    return items


def draw_scene(items):
    def draw(_overlay, ctx, _timestamp, _duration):
        for item in items:
            if item[0] == "line":
                x0, y0, x1, y1, width, r, g, b = item[1]
                ctx.set_source_rgb(r / 255, g / 255, b / 255)
                ctx.set_line_width(width)
                ctx.move_to(x0 + 0.5, y0 + 0.5)  # cairo's pixel centres are at +0.5, OpenCV's at integers
                ctx.line_to(x1 + 0.5, y1 + 0.5)
                ctx.stroke()
            else:
                (x, y, size, r, g, b), text = item[1], item[2]
                ctx.set_source_rgb(r / 255, g / 255, b / 255)
                ctx.select_font_face("DejaVu Sans")
                ctx.set_font_size(size)
                ctx.move_to(x, y + size)
                ctx.show_text(text)

    return draw


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    Gst.init(None)
    pipeline = Gst.parse_launch(sys.argv[1])
    overlay = pipeline.get_by_name("draw")
    if overlay is not None:
        overlay.connect("draw", draw_scene(read_scene(sys.argv[2])))
    pipeline.set_state(Gst.State.PLAYING)
    message = pipeline.get_bus().timed_pop_filtered(Gst.CLOCK_TIME_NONE, Gst.MessageType.EOS | Gst.MessageType.ERROR)
    pipeline.set_state(Gst.State.NULL)
    if message.type == Gst.MessageType.ERROR:
        error, debug = message.parse_error()
        print(f"gst_peer: {error.message} ({debug})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
