#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Privacy masks through the real binary: a screen mask and a world mask, each filled and pixelated, checked in every
output the daemon has on this machine without a VM -- /snapshot, /snapshot?raw=1, a part of /stream (MJPEG) and the
Y4M sink -- against the same scene without the masks (the V4L2 output is the VM tier's: tests/vm). Inside a filled
mask every pixel is the fill colour (within the JPEG tolerance), though the checkerboard behind it has black and
white squares; a pixelated block is uniform, though the same block without the mask has an edge through it. A world
mask follows PUT /api/camera to where /api/project puts its corners; hiding its layer is refused with the reason."""
import argparse
import json
import os
import subprocess
import sys
import time
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402

WIDTH, HEIGHT = 1280, 720
FILL = (200, 40, 40)  # "#c82828": far from both grey squares of the checkerboard
BLOCK = 16
JPEG_TOLERANCE = 14  # one channel of a flat area after 4:2:0 JPEG at the feed's quality and our conversion
Y4M_TOLERANCE = 3    # the Y4M frame's YUYV converted to RGB by ffmpeg: rounding only

HEAD = """
[daemon]
log_level = "info"

[source]
kind = "synthetic"
format = "YUYV"
width = 1280
height = 720
fps = 15.0
colorimetry = "bt601-limited"

[source.synthetic]
pattern = "checkerboard-scene"
checker_metres = 1.0

[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
roll = 0.0
fov = 60.0
fov_axis = "vertical"
near = 0.1
far = 200.0

[[annotation]]
name = "centre"
type = "crosshair"
position = [640.0, 100.0]
style = { layer = "marks" }
"""

# Screen masks in pixel corners (top-left origin); world masks as squares on the ground (z = 0), metres.
SCREEN_FILLED = [[40, 480], [360, 480], [360, 704], [40, 704]]
SCREEN_PIXELATED = [[896, 480], [1232, 480], [1232, 704], [896, 704]]
WORLD_FILLED = [[-1.5, 1.5, 0.0], [1.5, 1.5, 0.0], [1.5, 4.5, 0.0], [-1.5, 4.5, 0.0]]
WORLD_PIXELATED = [[3.5, 6.5, 0.0], [7.5, 6.5, 0.0], [7.5, 10.5, 0.0], [3.5, 10.5, 0.0]]

MASKS = f"""
[[annotation]]
name = "street"
type = "mask"
points = {json.dumps(SCREEN_FILLED)}
fill = "#c82828"
style = {{ layer = "private" }}

[[annotation]]
name = "garden"
type = "mask"
points = {json.dumps(SCREEN_PIXELATED)}
fill = "pixelate"
block_px = {BLOCK}
style = {{ layer = "private" }}

[[annotation]]
name = "neighbour's window"
type = "mask"
points = {json.dumps(WORLD_FILLED)}
fill = "#c82828"
style = {{ layer = "private" }}

[[annotation]]
name = "drive"
type = "mask"
points = {json.dumps(WORLD_PIXELATED)}
fill = "pixelate"
block_px = {BLOCK}
style = {{ layer = "private" }}
"""


class Check:
    def __init__(self):
        self.count = 0

    def __call__(self, condition, message):
        self.count += 1
        if not condition:
            raise AssertionError(message)


check = Check()
opener = daemon_fixture.loopback_opener


def request(base, path, method="GET", body=None):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(base + path, data=data, method=method,
                                 headers={"Content-Type": "application/json"} if data else {})
    try:
        with opener.open(req, timeout=10) as response:
            return response.status, response.read()
    except urllib.error.HTTPError as error:
        return error.code, error.read()


def rgb(image, workdir, name, input_format=()):
    """The image decoded by ffmpeg to rgb24 rows (independent of our encoder and converters)."""
    path = os.path.join(workdir, name)
    with open(path, "wb") as file:
        file.write(image)
    decoded = subprocess.run(["ffmpeg", "-v", "error", *input_format, "-i", path, "-frames:v", "1", "-f", "rawvideo",
                              "-pix_fmt", "rgb24", "-"], capture_output=True, timeout=30, check=True).stdout
    check(len(decoded) == WIDTH * HEIGHT * 3, f"{name}: decoded {len(decoded)} bytes")
    return decoded


def mjpeg_part(base):
    """The first whole JPEG of /stream."""
    data = b""
    with opener.open(base + "/stream", timeout=10) as response:
        while True:
            data += response.read1(65536)
            start = data.find(b"\xff\xd8")
            end = data.find(b"\xff\xd9", start + 2) if start >= 0 else -1
            if end > 0:
                return data[start:end + 2]


def y4m_frame(path):
    """The last whole frame of the Y4M file, as a one-frame Y4M."""
    data = open(path, "rb").read()
    header, _, rest = data.partition(b"\n")
    frame_bytes = WIDTH * HEIGHT * 2
    frames = rest.split(b"FRAME\n")
    whole = [f for f in frames if len(f) == frame_bytes]
    check(whole, f"{path}: no whole frame yet")
    return header + b"\n" + b"FRAME\n" + whole[-1]


def inside(polygon, x, y, margin):
    """Pixel centre (x, y) inside the convex polygon (pixel corners) and at least margin px from every edge."""
    sign = 0
    for i in range(len(polygon)):
        (ax, ay), (bx, by) = polygon[i], polygon[(i + 1) % len(polygon)]
        ex, ey = bx - ax, by - ay
        cross = ex * (y + 0.5 - ay) - ey * (x + 0.5 - ax)
        distance = cross / (ex * ex + ey * ey) ** 0.5
        if abs(distance) < margin:
            return False
        side = 1 if distance > 0 else -1
        if sign and side != sign:
            return False
        sign = side
    return True


def pixels_in(polygon, margin):
    xs = [p[0] for p in polygon]
    ys = [p[1] for p in polygon]
    return [(x, y) for y in range(max(0, int(min(ys))), min(HEIGHT, int(max(ys)) + 1))
            for x in range(max(0, int(min(xs))), min(WIDTH, int(max(xs)) + 1)) if inside(polygon, x, y, margin)]


def at(image, x, y):
    i = (y * WIDTH + x) * 3
    return image[i], image[i + 1], image[i + 2]


def corners_on_screen(base, world):
    """The world polygon's corners as pixel corners, from /api/project (pixel centres at integers)."""
    query = ";".join(",".join(str(c) for c in p) for p in world)
    status, body = request(base, "/api/project?points=" + query)
    result = json.loads(body)
    check(status == 200 and all(p["visible"] for p in result), f"/api/project: {status} {result}")
    return [[p["pixel"][0] + 0.5, p["pixel"][1] + 0.5] for p in result]


def check_filled(image, polygon, tolerance, what):
    # JPEG's 4:2:0 chroma blurs a sharp edge by up to a chroma block (16 px of the frame): the middle is the test.
    area = pixels_in(polygon, margin=16 if tolerance > Y4M_TOLERANCE else 2)
    check(len(area) > 1000, f"{what}: only {len(area)} pixels inside")
    worst = max(max(abs(c - f) for c, f in zip(at(image, x, y), FILL)) for x, y in area)
    check(worst <= tolerance, f"{what}: a masked pixel is {worst} from the fill colour")


def blocks_in(polygon):
    """The BLOCK x BLOCK blocks (aligned to the frame's origin) wholly inside the polygon, 2 px from its edges."""
    out = []
    for by in range(0, HEIGHT, BLOCK):
        for bx in range(0, WIDTH, BLOCK):
            corners = [(bx, by), (bx + BLOCK - 1, by), (bx, by + BLOCK - 1), (bx + BLOCK - 1, by + BLOCK - 1)]
            if all(inside(polygon, x, y, 2) for x, y in corners):
                out.append((bx, by))
    return out


def spread(image, bx, by, inset):
    values = [at(image, x, y)[c] for y in range(by + inset, by + BLOCK - inset)
              for x in range(bx + inset, bx + BLOCK - inset) for c in range(3)]
    return max(values) - min(values)


def check_pixelated(image, unmasked, polygon, tolerance, what):
    blocks = blocks_in(polygon)
    check(len(blocks) >= 4, f"{what}: only {len(blocks)} whole blocks inside")
    detailed = [b for b in blocks if spread(unmasked, *b, inset=0) > 60]
    check(detailed, f"{what}: no block has an edge behind it without the mask (the test would prove nothing)")
    inset = 2 if tolerance > Y4M_TOLERANCE else 0  # JPEG rings at a block's border: its middle is the test
    worst = max(spread(image, *b, inset=inset) for b in blocks)
    check(worst <= 2 * tolerance, f"{what}: a pixelated block spreads {worst} (not uniform)")


def check_unmasked_differs(unmasked, polygon, what):
    area = pixels_in(polygon, margin=4)
    values = [at(unmasked, x, y)[0] for x, y in area]
    check(max(values) - min(values) > 60, f"{what}: the scene behind is flat without the mask")


def run(overlayd, workdir, masked, tag):
    port = daemon_fixture.free_port()
    y4m = os.path.join(workdir, f"{tag}.y4m")
    config = HEAD + (MASKS if masked else "") + f"""
[[sink]]
kind = "y4m"
path = "{y4m}"
""" + daemon_fixture.http_section(port, control="open")
    path = os.path.join(workdir, f"{tag}.toml")
    open(path, "w").write(config)
    daemon = daemon_fixture.Daemon(overlayd, path, workdir, port)
    daemon.wait_ready()
    return daemon, y4m


def outputs(daemon, y4m, workdir, tag):
    base = daemon.base
    time.sleep(0.3)
    _, snap = request(base, "/snapshot")
    _, raw = request(base, "/snapshot?raw=1")
    return {
        "snapshot": (rgb(snap, workdir, f"{tag}-snapshot.jpg"), JPEG_TOLERANCE),
        "raw snapshot": (rgb(raw, workdir, f"{tag}-raw.jpg"), JPEG_TOLERANCE),
        "mjpeg part": (rgb(mjpeg_part(base), workdir, f"{tag}-stream.jpg"), JPEG_TOLERANCE),
        "y4m frame": (rgb(y4m_frame(y4m), workdir, f"{tag}-frame.y4m"), Y4M_TOLERANCE),
    }


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)

    plain, plain_y4m = run(args.overlayd, args.workdir, False, "plain")
    try:
        world_filled = corners_on_screen(plain.base, WORLD_FILLED)
        world_pixelated = corners_on_screen(plain.base, WORLD_PIXELATED)
        unmasked = outputs(plain, plain_y4m, args.workdir, "plain")
    finally:
        plain.stop()
    polygons = {"street": SCREEN_FILLED, "garden": SCREEN_PIXELATED, "neighbour's window": world_filled,
                "drive": world_pixelated}
    for name, polygon in polygons.items():
        check_unmasked_differs(unmasked["y4m frame"][0], polygon, name)

    daemon, y4m = run(args.overlayd, args.workdir, True, "masked")
    try:
        state = daemon.state()
        check([m["name"] for m in state["masks"]] == list(polygons), f"/state masks: {state['masks']}")
        for output, (image, tolerance) in outputs(daemon, y4m, args.workdir, "masked").items():
            check_filled(image, SCREEN_FILLED, tolerance, f"{output}, screen mask filled")
            check_filled(image, world_filled, tolerance, f"{output}, world mask filled")
            check_pixelated(image, unmasked[output][0], SCREEN_PIXELATED, tolerance, f"{output}, screen pixelated")
            check_pixelated(image, unmasked[output][0], world_pixelated, tolerance, f"{output}, world pixelated")

        # Hiding the masks' layer is refused with the reason; another layer still switches.
        status, body = request(daemon.base, "/api/layers/private", "PUT", {"visible": False})
        check(status == 400 and b"privacy mask" in body, f"PUT /api/layers/private hidden: {status} {body}")
        status, body = request(daemon.base, "/api/layers/marks", "PUT", {"visible": False})
        check(status == 200, f"PUT /api/layers/marks hidden: {status} {body}")

        # The camera turns: the world mask moves to where its corners now project.
        moved = {"position": [1.5, -6.0, 3.0], "yaw": 100.0, "pitch": 30.0, "roll": 0.0, "fov": 60.0, "near": 0.1,
                 "far": 200.0}
        status, body = request(daemon.base, "/api/camera", "PUT", moved)
        check(status == 200, f"PUT /api/camera: {status} {body}")
        moved_filled = corners_on_screen(daemon.base, WORLD_FILLED)
        shift = max(abs(a - b) for p, q in zip(moved_filled, world_filled) for a, b in zip(p, q))
        check(shift > 40, f"the camera change moved the world mask's corners only {shift} px")
        time.sleep(0.5)
        _, raw = request(daemon.base, "/snapshot?raw=1")
        image = rgb(raw, args.workdir, "moved-raw.jpg")
        check_filled(image, moved_filled, JPEG_TOLERANCE, "raw snapshot after the camera change, world mask")
        check(daemon.stop() == 0, "overlayd did not exit cleanly")
    finally:
        daemon.stop()
    print(f"privacy_mask_test: {check.count} checks passed")


if __name__ == "__main__":
    main()
