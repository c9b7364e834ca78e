#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Privacy masks in the encoded outputs, through the real binary: the scene and masks of tests/http/
privacy_mask_test.py (a screen mask and a world mask, each filled and pixelated) encoded by [encoder] openh264 into
an RTSP sink and a recording (kind = "record", 1 s MP4 segments). A frame decoded by ffmpeg from the RTSP stream and
one from a recorded segment are checked against the same scene without the masks (read from the RTSP stream of a
run without them): inside a filled mask every pixel is the fill colour within the H.264 tolerance, though the
checkerboard behind has black and white squares; a pixelated block is uniform, though the same block without the
mask has an edge through it. So nothing of what is behind a mask reaches a viewer or a file. The recording is
tagged with the source's colorimetry (ffprobe), so a player decodes the fill as the colour it is.

    mask_outputs_test.py --overlayd build/daemon/overlayd --workdir /tmp/mask-outputs-test
Exit 0 when every check passed (an AssertionError names the first that failed)."""
import glob
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "http"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402
import privacy_mask_test as masks  # noqa: E402
import rtsp_test  # noqa: E402

# One channel of a flat area after 4:2:0 H.264 at 8 Mbit/s and ffmpeg's conversion to RGB (measured: 2; the
# pixelated blocks' edges ring more, so their middle is the test, as for JPEG). A recording tagged with the wrong
# matrix (BT.709 for this BT.601 source) decodes the fill 14 away: beyond it.
H264_TOLERANCE = 8
FRAMES = 10  # the last of the first frames decoded is checked: past the rate control's settling after a start


def decoded(source, *options, frames=FRAMES):
    """The last of `frames` frames ffmpeg decodes from the source, as rgb24 rows (independent of our encoder)."""
    done = subprocess.run(["ffmpeg", "-v", "error", *options, "-i", source, "-frames:v", str(frames), "-f",
                           "rawvideo", "-pix_fmt", "rgb24", "-"], capture_output=True, timeout=60)
    size = masks.WIDTH * masks.HEIGHT * 3
    count = len(done.stdout) // size
    masks.check(count == frames, f"{source}: decoded {count} of {frames} frames: {done.stderr[-200:]}")
    return done.stdout[(count - 1) * size:count * size]


def run(overlayd, workdir, masked, tag):
    """A daemon with an RTSP sink (and, masked, a recording): (daemon, rtsp url, record directory)."""
    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    directory = os.path.join(workdir, f"{tag}-record")
    os.makedirs(directory, exist_ok=True)
    for old in glob.glob(os.path.join(directory, "*")):
        os.remove(old)
    record = f'[[sink]]\nkind = "record"\ndirectory = "{directory}"\nsegment_s = 1\n' if masked else ""
    config = masks.HEAD + (masks.MASKS if masked else "") + f"""
[encoder]
encoder = "openh264"
bitrate_kbps = 8000
keyframe_interval_s = 0.5
[[sink]]
kind = "rtsp"
listen = "127.0.0.1:{rtsp_port}"
path = "/cam"
{record}""" + daemon_fixture.http_section(http_port, control="open")
    path = os.path.join(workdir, f"{tag}.toml")
    with open(path, "w", encoding="utf-8") as file:
        file.write(config)
    daemon = daemon_fixture.Daemon(overlayd, path, workdir, http_port)
    daemon.wait_ready()
    return daemon, f"rtsp://127.0.0.1:{rtsp_port}/cam", directory


def finished_segment(directory, timeout=15.0):
    """The second finished recorded segment (whole, and past the encoder's start, whose first frames the rate control
    makes coarser). A segment being written is named *.partial until the recorder renames it: only renamed ones
    count, or ffmpeg may open a name that is gone."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        files = sorted(f for f in glob.glob(os.path.join(directory, "*"))
                       if not os.path.basename(f).startswith(".") and not f.endswith(".partial"))
        if len(files) >= 2:
            return files[1]
        time.sleep(0.2)
    masks.check(False, f"{directory}: no finished segment within {timeout} s")


def main():
    overlayd, workdir = rtsp_test.arguments(__doc__)
    rtsp = ("-rtsp_transport", "tcp")

    plain, url, _ = run(overlayd, workdir, False, "plain")
    try:
        world_filled = masks.corners_on_screen(plain.base, masks.WORLD_FILLED)
        world_pixelated = masks.corners_on_screen(plain.base, masks.WORLD_PIXELATED)
        unmasked = decoded(url, *rtsp)
    finally:
        plain.stop()
    for name, polygon in {"street": masks.SCREEN_FILLED, "garden": masks.SCREEN_PIXELATED,
                          "neighbour's window": world_filled, "drive": world_pixelated}.items():
        masks.check_unmasked_differs(unmasked, polygon, f"{name} (RTSP without masks)")

    daemon, url, directory = run(overlayd, workdir, True, "masked")
    try:
        outputs = {"RTSP frame": decoded(url, *rtsp)}
        segment = finished_segment(directory)
        outputs["recorded frame"] = decoded(segment)
        tags = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-show_entries",
                               "stream=color_space,color_range", "-of", "csv=p=0", segment],
                              capture_output=True, text=True, timeout=30).stdout.strip()
        masks.check(tags in ("smpte170m,tv", "tv,smpte170m", "bt470bg,tv", "tv,bt470bg"),
                    f"the recording is tagged with the source's BT.601 limited range: {tags}")
    finally:
        status = daemon.stop()
    masks.check(status == 0, f"overlayd stops cleanly: exit {status}")
    for output, image in outputs.items():
        masks.check_filled(image, masks.SCREEN_FILLED, H264_TOLERANCE, f"{output}, screen mask filled")
        masks.check_filled(image, world_filled, H264_TOLERANCE, f"{output}, world mask filled")
        masks.check_pixelated(image, unmasked, masks.SCREEN_PIXELATED, H264_TOLERANCE, f"{output}, screen pixelated")
        masks.check_pixelated(image, unmasked, world_pixelated, H264_TOLERANCE, f"{output}, world pixelated")
    print(f"mask_outputs_test: {masks.check.count} checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
