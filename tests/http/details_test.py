#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""What a user notices about the HTTP API, through the real binary: stable sink labels in /metrics and /state, the
intrinsics the camera really projects with, the capture time on every JPEG, a fresh first /stream part, refusals
that touch no file, a log line for every change, partial poses, plain JSON errors and readable numbers.

    details_test.py --overlayd build/daemon/overlayd --workdir /tmp/details
    details_test.py ... --only sinks,intrinsics      (a subset, by check name)
Exit 0 when every check passed, 1 with the failed check's message."""
import argparse
import json
import math
import os
import re
import shutil
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402
from http_api_test import Check, curl, curl_json  # noqa: E402

TOKEN = "details-token-for-tests"
SINKS = """
[[sink]]
kind = "null"

[[sink]]
kind = "null"
name = "counter"
"""


check = Check()


def metric_labels(text, name):
    """The label sets of one metric's samples in Prometheus text."""
    return sorted(re.findall("^" + name + r"\{([^}]*)\} ", text, re.M))


def check_sinks(daemon, workdir):
    """Sink labels are identities: the same on every scrape however many frames went by, the config's `name` or
    sink[N]; /state's sink names are the same."""
    _, first, _ = curl(daemon.base, "/metrics")
    time.sleep(0.5)
    _, second, _ = curl(daemon.base, "/metrics")
    labels = metric_labels(first.decode(), "overlayd_sink_frames_total")
    check(labels == metric_labels(second.decode(), "overlayd_sink_frames_total"),
          f"sink labels changed between scrapes: {labels} then "
          f"{metric_labels(second.decode(), 'overlayd_sink_frames_total')}")
    check(labels == sorted(['sink="sink[0]"', 'sink="counter"', 'sink="http"']), f"sink labels: {labels}")
    names = sorted(sink["name"] for sink in daemon.state()["sinks"])
    time.sleep(0.3)
    check(names == sorted(sink["name"] for sink in daemon.state()["sinks"]) == ["counter", "http", "sink[0]"],
          f"/state sink names: {names}")


def demo_pixel(world, fx, fy, cx, cy):
    """The demo camera's pixel for a world point, worked out here from its config (3 m up, 6 m behind the origin and
    1.5 m to its right, looking along +Y pitched 25 degrees down): pixel centres at integers, as [camera.pinhole]
    takes them."""
    pitch = math.radians(25.0)
    d = [world[0] - 1.5, world[1] + 6.0, world[2] - 3.0]
    forward = (0.0, math.cos(pitch), -math.sin(pitch))
    up = (0.0, math.sin(pitch), math.cos(pitch))
    z = sum(a * b for a, b in zip(d, forward))
    return [cx + fx * d[0] / z, cy - fy * sum(a * b for a, b in zip(d, up)) / z]


def check_intrinsics(daemon, workdir):
    """/state's intrinsics are those the camera projects with, in [camera.pinhole]'s convention: fov = 60 vertical
    on 1280x720 is fy = 360 / tan(30 deg), cx = 639.5, cy = 359.5; the origin lands at (500.02, 376.54)."""
    k = daemon.state()["camera"]["intrinsics"]
    f = 360.0 / math.tan(math.radians(30.0))
    expected = {"fx": f, "fy": f, "cx": 639.5, "cy": 359.5}
    check(all(abs(k[key] - value) < 1e-6 for key, value in expected.items()), f"intrinsics {k}, not {expected}")
    points = [(0, 0, 0), (3, 2, 0), (-2, 8, 0), (1, 1, 1)]
    status, projected = curl_json(daemon.base, "/api/project?points=" + ";".join(",".join(map(str, p)) for p in points))
    check(status == 200, f"/api/project: {status}")
    origin = projected[0]["pixel"]
    check(math.dist(origin, [500.02, 376.54]) < 0.01, f"the origin projects to {origin}, not (500.02, 376.54)")
    for point, answer in zip(points, projected):
        mine = demo_pixel(point, k["fx"], k["fy"], k["cx"], k["cy"])
        check(math.dist(mine, answer["pixel"]) < 1e-5,
              f"{point}: the shown intrinsics give {mine}, the camera draws at {answer['pixel']}")


def check_timestamp(daemon, workdir):
    """X-Timestamp-Us is the capture time on CLOCK_MONOTONIC (docs/http.md): between a moment before the request,
    less the snapshot's wait and a frame or two, and the moment the answer came."""
    for raw in ("", "?raw=1"):
        before = time.clock_gettime(time.CLOCK_MONOTONIC)
        status, _, headers = curl(daemon.base, "/snapshot" + raw)
        after = time.clock_gettime(time.CLOCK_MONOTONIC)
        found = re.search(r"X-Timestamp-Us: (\d+)", headers, re.I)
        check(status == 200 and found, f"/snapshot{raw}: {status} {headers}")
        stamp = int(found.group(1)) / 1e6
        check(before - 0.5 <= stamp <= after, f"/snapshot{raw}: X-Timestamp-Us {stamp:.3f} s is not CLOCK_MONOTONIC "
                                               f"between {before:.3f} and {after:.3f}")


def first_stream_part(daemon):
    """(X-Timestamp-Us in s, CLOCK_MONOTONIC when the request was sent) of /stream's first part."""
    with socket.create_connection(("127.0.0.1", daemon.port), timeout=10) as sock:
        sent = time.clock_gettime(time.CLOCK_MONOTONIC)
        sock.sendall(b"GET /stream HTTP/1.1\r\nHost: x\r\n\r\n")
        data = b""
        while not re.search(rb"X-Sequence: \d+\r\n\r\n", data):
            chunk = sock.recv(65536)
            check(chunk, f"/stream ended before its first part: {data[:400]!r}")
            data += chunk
    found = re.search(rb"X-Timestamp-Us: (\d+)", data, re.I)
    check(found, f"/stream: no X-Timestamp-Us in {data[:400]!r}")
    return int(found.group(1)) / 1e6, sent


def check_first_part(daemon, workdir):
    """A viewer who comes after nobody watched for a while gets the newest frame first, not the last one encoded."""
    first_stream_part(daemon)  # a viewer: the feed holds a frame encoded now
    time.sleep(3.0)
    stamp, sent = first_stream_part(daemon)
    check(stamp >= sent - 0.2, f"/stream's first part was captured {sent - stamp:.2f} s before the viewer came")


def check_calibration_refused(daemon, workdir):
    """A calibration path in PUT /api/camera is refused before any file is opened: a missing file, an unreadable one,
    a directory and a real calibration get the same answer, which says nothing about the file."""
    calibration = os.path.join(daemon_fixture.REPO, "config", "examples", "calibration.yaml")
    answers = set()
    for path in ("/nonexistent/x.yaml", "/etc/shadow", "/etc", "/etc/passwd", calibration):
        for body in ({"calibration": path}, {"calibration": path, "yaw": 10.0}):
            status, result = curl_json(daemon.base, "/api/camera", "PUT", json.dumps(body), token=TOKEN)
            check(status == 400, f"PUT {body}: {status} {result}")
            answers.add(result["error"])
    check(len(answers) == 1, f"the answers tell the files apart: {sorted(answers)}")
    check(daemon.state()["camera"]["yaw"] == 90.0, "a refused request changed the camera")


def check_live_pose_said(daemon, workdir):
    """solve-pose --write says where it wrote, not "paste ... or run with --write"; check-config, render and project
    say on stderr that they use the drop-in's pose, and say nothing when there is none."""
    overlayd = daemon.overlayd
    config_path = os.path.join(workdir, "cli.toml")
    open(config_path, "w").write(daemon_fixture.demo_without_sinks())
    dropin = os.path.join(workdir, "cli.live.toml")
    if os.path.exists(dropin):
        os.remove(dropin)
    world = [(x, y, 0.0) for x in (-2, 0, 2) for y in (2, 4, 6)]
    projected = subprocess.run([overlayd, "project", "--config", config_path, "--json", "--"] +
                               [repr(float(c)) for p in world for c in p], capture_output=True, text=True)
    check(projected.returncode == 0 and "live pose" not in projected.stderr,
          f"project without a drop-in: {projected.returncode} {projected.stderr}")
    points = os.path.join(workdir, "cli-marks.csv")
    open(points, "w").write("x,y,z,u,v\n" + "".join(f"{p['world'][0]},{p['world'][1]},{p['world'][2]},"
                                                    f"{p['pixel'][0]!r},{p['pixel'][1]!r}\n"
                                                    for p in json.loads(projected.stdout)))
    solved = subprocess.run([overlayd, "solve-pose", "--config", config_path, "--points", points, "--write"],
                            capture_output=True, text=True)
    check(solved.returncode == 0, f"solve-pose --write: {solved.returncode} {solved.stderr}")
    check("run with --write" not in solved.stdout and "paste" not in solved.stdout and
          f"written to {dropin}" in solved.stdout, f"solve-pose --write printed:\n{solved.stdout}")
    check(not LONG_NUMBER.search(solved.stdout), f"solve-pose printed unrounded numbers:\n{solved.stdout}")
    check(open(dropin).read().startswith("# Written by overlayd (solve-pose --write)"),
          f"the drop-in's header: {open(dropin).read().splitlines()[0]}")
    said = f"using the live pose from {dropin}"
    commands = {"check-config": [overlayd, "check-config", config_path],
                "project": [overlayd, "project", "--config", config_path, "--", "0", "0", "0"],
                "render": [overlayd, "render", "--config", config_path, "--frames", "1", "--output",
                           os.path.join(workdir, "cli-render.y4m")]}
    for name, command in commands.items():
        done = subprocess.run(command, capture_output=True, text=True)
        check(done.returncode == 0 and said in done.stderr, f"{name}: {done.returncode}, stderr: {done.stderr}")
    os.remove(dropin)
    done = subprocess.run(commands["check-config"], capture_output=True, text=True)
    check(done.returncode == 0 and "live pose" not in done.stderr, f"check-config without a drop-in: {done.stderr}")


HOME = {"position": [1.5, -6.0, 3.0], "yaw": 90.0, "pitch": 25.0, "roll": 0.0}


def check_changes_logged(daemon, workdir):
    """Every change through the API and every save is logged with the client's address and what it asked; a refused
    one too."""
    changes = [("/api/camera", json.dumps(dict(HOME, yaw=91.5))), ("/api/layers/grid", '{"visible": false}'),
               ("/api/layers/grid", '{"visible": true}'), ("/api/camera", json.dumps(HOME))]
    for path, body in changes:
        status, result = curl_json(daemon.base, path, "PUT", body, token=TOKEN)
        check(status == 200, f"PUT {path} {body}: {status} {result}")
    status, result = curl_json(daemon.base, "/api/camera", "PUT", '{"fov": 500}', token=TOKEN)
    check(status == 400, f"PUT a fov of 500: {status} {result}")
    status, result = curl_json(daemon.base, "/api/save", "POST", "", token=TOKEN)
    check(status == 200, f"POST /api/save: {status} {result}")
    os.remove(result["saved"])
    time.sleep(0.3)
    log = daemon.log_text()
    for path, body in changes:
        check(f"127.0.0.1 PUT {path} {body}" in log, f"no log line for PUT {path} {body}:\n{log[-3000:]}")
    check(re.search(r"127\.0\.0\.1 PUT /api/camera \{\"fov\": 500\} refused \(400\).*camera\.fov", log),
          f"no log line for the refused change:\n{log[-3000:]}")
    check("\\x0A" not in log, f"a log line ends in an escaped line feed:\n{log[-3000:]}")
    check(re.search(r"127\.0\.0\.1 POST /api/save -> .*details\.live\.toml", log),
          f"no log line for the save:\n{log[-3000:]}")


def check_errors(daemon, workdir):
    """JSON errors in the user's words (no "[json.exception..."), the 404 for an unknown layer lists the layers,
    POST /snapshot and /stream answer 405 with or without the token."""
    for body in ("{x", '{"yaw": 1e400}', "[1, 2", '{"yaw": }'):
        status, result = curl_json(daemon.base, "/api/camera", "PUT", body, token=TOKEN)
        check(status == 400 and "json.exception" not in result["error"] and "the body is not JSON" in result["error"],
              f"PUT /api/camera {body}: {status} {result}")
    status, result = curl_json(daemon.base, "/api/layers/gird", "PUT", '{"visible": false}', token=TOKEN)
    layers = [layer["name"] for layer in daemon.state()["layers"]]
    check(status == 404 and all(layer in result["error"] for layer in layers) and layers,
          f"PUT /api/layers/gird: {status} {result}; the layers are {layers}")
    for path in ("/snapshot", "/stream"):
        for token in (None, TOKEN):
            status, result = curl_json(daemon.base, path, "POST", "", token=token)
            check(status == 405, f"POST {path} {'with' if token else 'without'} the token: {status} {result}")


def check_partial_pose(daemon, workdir):
    """A request naming some of position, yaw, pitch and roll changes only those."""
    for change in ({"yaw": 100.0}, {"pitch": 30.0}, {"roll": -5.0}, {"position": [1.0, -5.0, 2.5]},
                   {"yaw": 80.0, "roll": 2.0}):
        before = daemon.state()["camera"]
        status, result = curl_json(daemon.base, "/api/camera", "PUT", json.dumps(change), token=TOKEN)
        check(status == 200, f"PUT {change}: {status} {result}")
        after = daemon.state()["camera"]
        for key in ("yaw", "pitch", "roll"):
            wanted = change.get(key, before[key])
            check(abs(after[key] - wanted) < 1e-6, f"PUT {change}: {key} {before[key]} became {after[key]}")
        wanted = change.get("position", before["position"])
        check(math.dist(after["position"], wanted) < 1e-6,
              f"PUT {change}: position {before['position']} became {after['position']}")
    status, result = curl_json(daemon.base, "/api/camera", "PUT", json.dumps(HOME), token=TOKEN)
    check(status == 200, f"PUT back home: {status} {result}")


LONG_NUMBER = re.compile(r"\d\.\d{8,}|\de-\d")  # more than 7 decimals, or an exponent (6.8e-17)


def check_readable_numbers(daemon, workdir):
    """/state's camera (pose, orientation, intrinsics) is rounded to what it means: the config's -6 is -6, never
    -6.000000000000003, and 0 is never 6.8e-17."""
    status, result = curl_json(daemon.base, "/api/camera", "PUT", json.dumps(dict(HOME, position=[5.03, -6.0, 3.0])),
                               token=TOKEN)
    check(status == 200, f"PUT: {status} {result}")
    camera = daemon.state()["camera"]
    text = json.dumps(camera)
    check(not LONG_NUMBER.search(text), f"/state's camera has unrounded numbers: {LONG_NUMBER.findall(text)} in {text}")
    check(camera["position"] == [5.03, -6, 3] and camera["yaw"] == 90 and camera["pitch"] == 25 and
          camera["roll"] == 0, f"/state's pose: {camera}")
    status, result = curl_json(daemon.base, "/api/save", "POST", "", token=TOKEN)
    check(status == 200, f"POST /api/save: {status} {result}")
    saved = open(result["saved"]).read()
    comments = "".join(line for line in saved.splitlines(keepends=True) if line.startswith("#"))
    os.remove(result["saved"])
    # The pose in the config's own keys and units (position + yaw/pitch/roll in degrees), not a matrix.
    keys = saved[saved.index("[camera]"):]
    check("\nposition = [5.03, -6.0, 3.0]\n" in keys and "\nyaw = 90.0\n" in keys and "\npitch = 25.0\n" in keys and
          "\nroll = 0.0\n" in keys and "rmat" not in keys and "tvec" not in keys,
          f"the saved pose is not in the config's form (position, yaw, pitch, roll):\n{saved}")
    check("position = [5.03, -6.0, 3.0], yaw = 90.0, pitch = 25.0, roll = 0.0" in comments and
          not LONG_NUMBER.search(comments), f"the saved file's header: {comments}")
    status, result = curl_json(daemon.base, "/api/camera", "PUT", json.dumps(HOME), token=TOKEN)
    check(status == 200, f"PUT back home: {status} {result}")


def ssim(reference, image):
    """SSIM (all planes) of `image` against the uncompressed `reference`, by ffmpeg."""
    done = subprocess.run(["ffmpeg", "-v", "info", "-i", reference, "-i", image, "-lavfi", "[0][1]ssim", "-f", "null",
                           "-"], capture_output=True, text=True, timeout=60)
    found = re.search(r"All:([0-9.]+)", done.stderr)
    check(found, f"ffmpeg ssim {reference} {image}: {done.stderr[-500:]}")
    return float(found.group(1))


BARS_SOURCE = """
[source]
kind = "replay"
format = "YUYV"
width = 1280
height = 720
fps = 30.0
colorimetry = "bt601-limited"

[source.replay]
path = "bars.y4m"
format = "y4m"
loop = true

[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
"""


def compare_with_cjpeg(daemon, workdir, name, config_path):
    """The raw /snapshot of `daemon` against cjpeg -quality 80 of the same frame, rendered by `render` from
    config_path (a still picture: every frame the same)."""
    png = os.path.join(workdir, f"{name}-0000.png")
    done = subprocess.run([daemon.overlayd, "render", "--config", config_path, "--frames", "1", "--output",
                           os.path.join(workdir, f"{name}-%04d.png")], capture_output=True, text=True)
    check(done.returncode == 0, f"render {config_path}: {done.stderr}")
    ppm = os.path.join(workdir, f"{name}.ppm")
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-i", png, ppm], check=True, timeout=60)
    reference = os.path.join(workdir, f"{name}-cjpeg.jpg")
    with open(reference, "wb") as out:
        subprocess.run(["cjpeg", "-quality", "80", ppm], stdout=out, check=True, timeout=60)
    status, ours, headers = curl(daemon.base, "/snapshot?raw=1")
    check(status == 200, f"/snapshot?raw=1: {headers}")
    mine = os.path.join(workdir, f"{name}-stream.jpg")
    open(mine, "wb").write(ours)
    size, size_reference = len(ours), os.path.getsize(reference)
    quality, quality_reference = ssim(png, mine), ssim(png, reference)
    print(f"details_test: {name}: the stream's JPEG {size} bytes SSIM {quality:.4f}; cjpeg -quality 80 "
          f"{size_reference} bytes SSIM {quality_reference:.4f}")
    check(size <= size_reference * 1.01, f"{name}: the stream's JPEG is {size} bytes, libjpeg's {size_reference}")
    check(quality >= quality_reference - 0.003, f"{name}: the stream's JPEG has SSIM {quality}, libjpeg's "
                                                f"{quality_reference}")


def check_jpeg_size(daemon, workdir):
    """The stream's JPEG of a frame is no larger than libjpeg's defaults at the same quality (cjpeg: 4:2:0, standard
    Huffman tables, what µStreamer's CPU encoder writes) and as good within 0.003 SSIM against the uncompressed
    frame: the demo's synthetic ground, and 75% colour bars (as vivid's HDMI input shows) from a replay."""
    check(shutil.which("cjpeg"), "cjpeg is missing (libjpeg-turbo-progs; scripts/install-deps.sh installs it)")
    bare = os.path.join(workdir, "bare.toml")
    text = daemon_fixture.demo_without_sinks()
    open(bare, "w").write(text[:text.index("[[annotation]]")])
    compare_with_cjpeg(daemon, workdir, "ground", bare)

    subprocess.run(["ffmpeg", "-v", "error", "-y", "-f", "lavfi", "-i", "pal75bars=s=1280x720:r=30", "-frames:v",
                    "2", "-pix_fmt", "yuv422p", os.path.join(workdir, "bars.y4m")], check=True, timeout=60)
    port = daemon_fixture.free_port()
    bars = os.path.join(workdir, "bars.toml")
    open(bars, "w").write(BARS_SOURCE + daemon_fixture.http_section(port, control="off"))
    served = daemon_fixture.Daemon(daemon.overlayd, bars, workdir, port)
    served.overlayd = daemon.overlayd
    try:
        served.wait_ready()
        compare_with_cjpeg(served, workdir, "bars", bars)
    finally:
        check(served.stop() == 0, "the colour bars' overlayd did not exit 0")


def check_viewer_unprojects(daemon, workdir):
    """POST /api/unproject changes nothing: a viewer without the token may ask it; a change still needs the token."""
    status, result = curl_json(daemon.base, "/api/unproject", "POST", '{"pixels": [[640, 500]]}')
    check(status == 200 and result[0]["hit"] is not None, f"POST /api/unproject without the token: {status} {result}")
    status, result = curl_json(daemon.base, "/api/camera", "PUT", '{"yaw": 10}')
    check(status == 401, f"PUT /api/camera without the token: {status} {result}")


def check_example_axes(daemon, workdir):
    """distorted_pinhole.toml's axes are in the picture: a frame rendered with them differs from one without."""
    example = os.path.join(daemon_fixture.REPO, "config", "examples", "distorted_pinhole.toml")
    text = daemon_fixture.config_without_sinks(example).replace(
        'calibration = "calibration.yaml"', 'calibration = ' + json.dumps(os.path.join(os.path.dirname(example),
                                                                                        "calibration.yaml")))
    start = text.index('type = "axes"')
    start = text.rindex("[[annotation]]", 0, start)
    end = text.find("[[", start + 2)
    without = text[:start] + (text[end:] if end >= 0 else "")
    pictures = []
    for name, config in (("with-axes", text), ("without-axes", without)):
        path = os.path.join(workdir, f"{name}.toml")
        open(path, "w").write(config)
        done = subprocess.run([daemon.overlayd, "render", "--config", path, "--frames", "1", "--output",
                               os.path.join(workdir, f"{name}-%04d.png")], capture_output=True, text=True)
        check(done.returncode == 0, f"render {name}: {done.stderr}")
        _, _, pixels = daemon_fixture.grey_pixels(open(os.path.join(workdir, f"{name}-0000.png"), "rb").read(),
                                                  workdir, f"{name}.png")
        pictures.append(pixels)
    changed = sum(abs(a - b) > 40 for a, b in zip(*pictures))
    check(changed >= 200, f"distorted_pinhole.toml's axes change {changed} pixels of its picture: not in view")


def check_unknown_steering_shows(daemon, workdir):
    """reverse_camera.toml's "unknown steering" marks (no CAN frames) show on a ground of their own grey: a frame
    over a uniform #9e9e9e picture has marks that differ from it by more than 60 grey levels."""
    example = os.path.join(daemon_fixture.REPO, "config", "examples", "reverse_camera.toml")
    text = daemon_fixture.config_without_sinks(example)
    kept, skip = [], False
    for line in text.splitlines():  # no GPIO chip here; the source a uniform grey replay
        header = line.strip()
        if header.startswith("["):
            skip = header.startswith("[[gpio.") or header.startswith("[source")
        if not skip:
            kept.append(line)
    grey = os.path.join(workdir, "grey.y4m")
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-f", "lavfi", "-i", "color=c=0x9e9e9e:s=1280x720:r=30",
                    "-frames:v", "2", "-pix_fmt", "yuv422p", grey], check=True, timeout=60)
    path = os.path.join(workdir, "reverse.toml")
    port = daemon_fixture.free_port()
    open(path, "w").write(BARS_SOURCE.split("[camera]")[0].replace("bars.y4m", grey) + "\n".join(kept) + "\n" +
                          daemon_fixture.http_section(port, control="off"))
    served = daemon_fixture.Daemon(daemon.overlayd, path, workdir, port)  # `run`: its CAN input has no frames
    try:
        served.wait_ready()
        time.sleep(1.0)  # past the CAN input's timeout: the steering is unknown
        status, jpeg, _ = curl(served.base, "/snapshot")
        check(status == 200, f"/snapshot of the reverse camera: {status}")
    finally:
        check(served.stop() == 0, "the reverse camera's overlayd did not exit 0")
    _, _, pixels = daemon_fixture.grey_pixels(jpeg, workdir, "reverse.jpg")
    background = pixels[len(pixels) // 2]
    bottom = pixels[len(pixels) * 3 // 4:]  # below the HUD text, where the near marks are
    shown = sum(abs(p - background) > 60 for p in pixels[len(pixels) // 4:len(pixels) * 3 // 4])
    check(shown >= 500, f"the unknown-steering marks differ from a #9e9e9e ground in {shown} pixels "
                        f"(ground {background}; bottom rows {min(bottom)}..{max(bottom)})")


def check_demo_labels_readable(daemon, workdir):
    """demo.toml's "5 m" and "10 m" labels (yellow, on the yellow grid and the checker) sit on a dark box of their
    own: the box beside each anchor is dark, whatever the ground under it."""
    config_path = os.path.join(workdir, "labels.toml")
    open(config_path, "w").write(daemon_fixture.demo_without_sinks())
    done = subprocess.run([daemon.overlayd, "render", "--config", config_path, "--frames", "1", "--output",
                           os.path.join(workdir, "labels-%04d.png")], capture_output=True, text=True)
    check(done.returncode == 0, f"render: {done.stderr}")
    width, _, pixels = daemon_fixture.grey_pixels(open(os.path.join(workdir, "labels-0000.png"), "rb").read(),
                                                  workdir, "labels.png")
    projected = subprocess.run([daemon.overlayd, "project", "--config", config_path, "--json", "--", "0", "5", "0",
                                "0", "10", "0"], capture_output=True, text=True)
    check(projected.returncode == 0, f"project: {projected.stderr}")
    for point in json.loads(projected.stdout):
        u, v = (int(round(c)) for c in point["pixel"])
        # The box's pixels that are not glyphs: the darkest half of a 30x16 region right of and below the anchor.
        region = sorted(pixels[(v + y) * width + u + x] for y in range(4, 20) for x in range(8, 38))
        median_dark = region[len(region) // 4]
        check(median_dark < 60, f"the label at {point['world']} has no dark box: its region's lower quartile is "
                                f"{median_dark} (pixel {u}, {v})")


CHECKS = {"sinks": check_sinks, "intrinsics": check_intrinsics, "timestamp": check_timestamp,
          "first_part": check_first_part, "calibration": check_calibration_refused,
          "live_pose": check_live_pose_said, "logged": check_changes_logged,
          "errors": check_errors, "partial_pose": check_partial_pose,
          "numbers": check_readable_numbers, "jpeg_size": check_jpeg_size,
          "unproject": check_viewer_unprojects, "example_axes": check_example_axes,
          "unknown_steering": check_unknown_steering_shows, "labels": check_demo_labels_readable}


def run(overlayd, workdir, only):
    port = daemon_fixture.free_port()
    token_file = os.path.join(workdir, "token")
    open(token_file, "w").write(TOKEN + "\n")
    config_path = os.path.join(workdir, "details.toml")
    open(config_path, "w").write(daemon_fixture.demo_without_sinks() + SINKS +
                                 daemon_fixture.http_section(port, control="token", token_file=token_file))
    for stale in ("details.live.toml",):
        if os.path.exists(os.path.join(workdir, stale)):
            os.remove(os.path.join(workdir, stale))
    daemon = daemon_fixture.Daemon(overlayd, config_path, workdir, port)
    daemon.overlayd, daemon.config_path, daemon.workdir = overlayd, config_path, workdir
    try:
        daemon.wait_ready()
        for name, function in CHECKS.items():
            if not only or name in only:
                function(daemon, workdir)
    except Exception:
        print(daemon.log_tail(40), file=sys.stderr)
        raise
    finally:
        status = daemon.stop()
    check(status == 0, f"overlayd exited {status}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    for tool in ("curl", "ffprobe", "ffmpeg"):
        if not shutil.which(tool):
            print(f"details_test: {tool} is missing (scripts/install-deps.sh installs it)", file=sys.stderr)
            return 1
    os.makedirs(args.workdir, exist_ok=True)
    try:
        run(os.path.abspath(args.overlayd), os.path.abspath(args.workdir), set(filter(None, args.only.split(","))))
    except AssertionError as failure:
        print(f"details_test: FAILED after {check.count} checks: {failure}", file=sys.stderr)
        return 1
    print(f"details_test: {check.count} checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
