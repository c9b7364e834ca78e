#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""[[input.text]] through the real path: a text slot fed by a file, changed with `echo > file` (and by rename, and by
deleting it) while `overlayd run` streams; /state reports the value and the next snapshots show the new text in the
text's box and nowhere else.

    text_input_test.py --overlayd build/daemon/overlayd --workdir /tmp/text-input
Exit 0 when every check passed, 1 with the failed check's message."""
import argparse
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402

WIDTH, HEIGHT = 640, 360
# The status text's box: 20 px glyphs at (10, 10), at most 24 characters of it.
BOX = (0, 0, 400, 40)
CONFIG = """
[source]
kind = "synthetic"
format = "NV12"
width = 640
height = 360
fps = 30.0
[source.synthetic]
pattern = "checkerboard-scene"
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
[[annotation]]
name = "status line"
type = "text"
text = "{slot:status}"
position = [10.0, 10.0]
size_px = 20.0
background = "#000000"
style = { colour = "white", layer = "hud" }
[[input.text]]
slot = "status"
file = "status.txt"
"""


def snapshot_grey(base, workdir, name):
    done = subprocess.run(["curl", "-sS", "--max-time", "10", base + "/snapshot"], capture_output=True, timeout=20)
    if done.returncode != 0:
        raise AssertionError(f"/snapshot: curl exited {done.returncode}")
    width, height, pixels = daemon_fixture.grey_pixels(done.stdout, workdir, name)
    if (width, height) != (WIDTH, HEIGHT):
        raise AssertionError(f"{name}: {width}x{height}, not {WIDTH}x{HEIGHT}")
    return pixels


def changed_pixels(a, b, inside):
    """Pixels differing by more than JPEG noise, inside or outside the text's box."""
    x0, y0, x1, y1 = BOX
    count = 0
    for y in range(HEIGHT):
        for x in range(WIDTH):
            if ((x0 <= x < x1 and y0 <= y < y1) == inside) and abs(a[y * WIDTH + x] - b[y * WIDTH + x]) > 40:
                count += 1
    return count


def wait_for_value(daemon, expected):
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline:
        state = daemon.state()
        if state["text_slots"].get("status") == expected and state["inputs"][0]["value"] == expected:
            return
        time.sleep(0.05)
    raise AssertionError(f"/state never showed {expected!r}: {daemon.state().get('inputs')}")


def run(overlayd, workdir):
    status_file = os.path.join(workdir, "status.txt")
    with open(status_file, "w") as f:
        f.write("PARKED\n")
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, "text.toml")
    with open(config, "w") as f:
        f.write(CONFIG + daemon_fixture.http_section(port, control="off"))
    daemon = daemon_fixture.Daemon(overlayd, config, workdir, port)
    try:
        daemon.wait_ready()
        wait_for_value(daemon, "PARKED")
        parked = snapshot_grey(daemon.base, workdir, "parked.jpg")
        same = snapshot_grey(daemon.base, workdir, "parked-again.jpg")
        if changed_pixels(parked, same, True) != 0:
            raise AssertionError("two snapshots of the same text differ in its box: the comparison is too noisy")

        subprocess.run(f"echo 'REVERSING 2 m' > {status_file}", shell=True, check=True)
        wait_for_value(daemon, "REVERSING 2 m")
        reversing = snapshot_grey(daemon.base, workdir, "reversing.jpg")
        inside, outside = changed_pixels(parked, reversing, True), changed_pixels(parked, reversing, False)
        print(f"echo > file: {inside} pixels changed in the text's box, {outside} outside it")
        if inside < 100 or outside != 0:
            raise AssertionError(f"echo > file: {inside} pixels changed in the box (want >= 100), {outside} outside")

        os.replace(write_temp(workdir, "DRIVE\nignored second line"), status_file)
        wait_for_value(daemon, "DRIVE")
        os.remove(status_file)
        wait_for_value(daemon, "")
        empty = snapshot_grey(daemon.base, workdir, "empty.jpg")
        if changed_pixels(reversing, empty, True) < 100:
            raise AssertionError("deleting the file did not clear the text")
    except Exception:
        print(daemon.log_text()[-3000:], file=sys.stderr)
        raise
    finally:
        code = daemon.stop()
    if code != 0:
        raise AssertionError(f"overlayd exited {code}")


def write_temp(workdir, text):
    path = os.path.join(workdir, "status.tmp")
    with open(path, "w") as f:
        f.write(text)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    try:
        run(os.path.abspath(args.overlayd), args.workdir)
    except AssertionError as failure:
        print(f"text_input_test: FAILED: {failure}", file=sys.stderr)
        return 1
    print("text_input_test: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
