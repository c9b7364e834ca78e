#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""kind = "file" through the real path: `overlayd run` (synthetic source, [encoder] openh264) writes the encoder's
elementary stream into one file; after SIGTERM ffprobe, an independent reader, reads it as a raw H.264 byte stream
of the configured size, whose first frame is a keyframe (the sink starts at one) and which holds about as many
frames as the run lasted. The FWHT half of this sink (vicodec) is proven in the VM tier (checks/47-m2m-encode.sh).

    file_test.py --overlayd build/daemon/overlayd --workdir /tmp/file-test
Exit 0 when every check passed, 1 when any failed."""
import argparse
import os
import signal
import subprocess
import sys
import time

failures = []


def check(ok, what):
    print(("PASS " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


CONFIG = """
[source]
kind = "synthetic"
format = "NV12"
width = 320
height = 240
fps = 30.0
[source.synthetic]
pattern = "checkerboard-scene"
[encoder]
encoder = "openh264"
bitrate_kbps = 1000
keyframe_interval_s = 1.0
[[sink]]
kind = "file"
path = "{path}"
"""


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    out = os.path.join(args.workdir, "out.h264")
    if os.path.exists(out):
        os.remove(out)
    config = os.path.join(args.workdir, "file.toml")
    with open(config, "w", encoding="utf-8") as file:
        file.write(CONFIG.format(path=out))
    log_path = os.path.join(args.workdir, "file.log")
    with open(log_path, "w") as log:
        process = subprocess.Popen([args.overlayd, "run", "--config", config], stdin=subprocess.DEVNULL,
                                   stdout=subprocess.DEVNULL, stderr=log)
        time.sleep(4)
        process.send_signal(signal.SIGTERM)
        try:
            rc = process.wait(20)
        except subprocess.TimeoutExpired:
            process.kill()
            rc = process.wait()
    text = open(log_path, encoding="utf-8", errors="replace").read()
    check(rc == 0, f"overlayd run exits 0 on SIGTERM (got {rc})")
    check("h264 to " + out + " (openh264enc)" in text, "the log names the sink's codec, file and encoder")
    size = os.path.getsize(out) if os.path.exists(out) else 0
    result = subprocess.run(["ffprobe", "-v", "error", "-f", "h264", "-count_frames", "-select_streams", "v:0",
                             "-show_entries", "stream=width,height,nb_read_frames", "-of", "default=nw=1", out],
                            capture_output=True, text=True, check=False)
    fields = dict(line.split("=", 1) for line in result.stdout.split() if "=" in line)
    frames = int(fields.get("nb_read_frames", "0") or 0)
    check(fields.get("width") == "320" and fields.get("height") == "240",
          f"ffprobe reads {size} bytes as H.264 {fields.get('width')}x{fields.get('height')}")
    # 4 s at 30 fps, less the start (encoder and GStreamer loading): at least 1 s of it.
    check(30 <= frames <= 130, f"{frames} frames decoded (30..130 for a 4 s run)")
    first = subprocess.run(["ffprobe", "-v", "error", "-f", "h264", "-select_streams", "v:0", "-read_intervals",
                            "%+#1", "-show_entries", "frame=key_frame,pict_type", "-of", "default=nw=1", out],
                           capture_output=True, text=True, check=False).stdout.split()
    check("key_frame=1" in first, f"the file starts at a keyframe ({' '.join(first)})")
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
