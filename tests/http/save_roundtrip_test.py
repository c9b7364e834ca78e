#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""POST /api/save keeps the whole live camera, through the real binary: every camera key PUT through /api/camera,
saved, then `overlayd project` on the saved config (a separate process reading the config and its drop-in) gives the
pixels the live /api/project gives, to 1e-9 px (relatively as close far off the frame); a restarted daemon's pose-only save keeps the field of view an
earlier save wrote; `solve-pose --write` keeps the drop-in's intrinsics (its marks reproject onto their pixels); a
planted temporary file or symlink neither redirects nor breaks a save.

    save_roundtrip_test.py --overlayd build/daemon/overlayd --workdir /tmp/save-roundtrip
Exit 0 when every check passed, 1 with the failed check's message."""
import argparse
import glob
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402
from http_api_test import TOKEN, check, curl_json  # noqa: E402

# Points all over the view, near and far, off-axis, behind the camera (clipped the same way or not at all), just in
# front of the camera (before a near plane moved out) and between two far planes.
WORLD_POINTS = [(x, y, z) for x in (-6, -1.5, 0, 2.5, 7) for y in (-9, -3, 0.5, 4, 12, 60) for z in (0, 1.25, 4)] + \
    [(0.0, -5.8, 2.95), (0.05, -5.75, 2.9), (0.0, 150.0, 0.0), (3.0, 300.0, 1.0)]
# A change per camera key, applied in this order over the live camera (each on top of the ones before), so that
# a save also has to replace what an earlier save wrote. A lens needs pinhole intrinsics.
CHANGES = [
    {"fov": 47.123456789012345, "fov_axis": "horizontal"},
    {"near": 0.3700000000000001, "far": 123.456789},
    {"far": "inf"},
    {"depth_range": "0..1"},
    {"fov": 61.0, "fov_axis": "vertical", "far": 500.0, "depth_range": "-1..1"},
    {"pinhole": {"fx": 1001.25, "fy": 999.75, "cx": 641.3, "cy": 358.9, "skew": 0.4}},
    {"distortion": {"model": "plumb_bob", "coefficients": [-0.21, 0.034, 0.0011, -0.0007, 0.0021]}},
    {"distortion": {"model": "rational_polynomial",
                    "coefficients": [-0.2, 0.03, 0.001, -0.0008, 0.002, 0.01, -0.004, 0.0007]}},
    {"distortion": {"model": "equidistant", "coefficients": [0.05, -0.01, 0.002, -0.0003]}},
    {"distortion": {"model": "none"}},
    {"pinhole": {"fx": 1500.5, "fy": 1500.5, "cx": 961.0, "cy": 539.0, "width": 1920, "height": 1080},
     "distortion": {"model": "plumb_bob", "coefficients": [-0.1, 0.01, 0.0, 0.0, 0.0]}},
    {"pinhole": {"fx": 1500.5, "fy": 1500.5, "cx": 961.0, "cy": 601.0, "width": 1920, "height": 1200},
     "calibration_crop": "center"},
    {"calibration_crop": [0.0, 60.0, 1920.0, 1080.0]},
    {"frustum": {"left": -0.06, "right": 0.055, "bottom": -0.033, "top": 0.031}, "near": 0.05,
     "distortion": {"model": "none"}},
    {"window": {"focal": 1.5, "centre": [0.01, -0.02], "half_width": 0.8, "half_height": 0.45}},
    {"orthographic": {"left": -8.0, "right": 8.0, "bottom": -4.5, "top": 4.5}, "near": 0.1, "far": 80.0},
    {"orthographic": {"width": 16.0, "height": 9.0}},
    {"pinhole": {"fx": 900.0, "fy": 901.0, "cx": 640.5, "cy": 360.5}, "far": "inf",
     "distortion": {"model": "plumb_bob", "coefficients": [-0.05, 0.002, 0.0, 0.0, 0.0]}},
    {"eye": [1.0, -7.0, 2.5], "target": [0.3, 2.0, 0.1], "up": [0.0, 0.0, 1.0]},
    {"eye": [-1.0, -6.5, 3.0], "gaze": [0.1, 1.0, -0.3]},
    {"prp": [0.5, -8.0, 4.0], "vpn": [0.0, -1.0, 0.4], "vup": [0.0, 0.0, 1.0]},
    {"position": [0.2, -6.0, 3.1], "orientation": [0.7, 0.1, 0.2, 0.68], "axes": "body"},
    {"position": [0.2, -6.0, 3.1], "orientation": [0.5, -0.5, 0.5, -0.5], "axes": "optical"},
    {"position": [0.2, -6.0, 3.1], "orientation": [0.6, 0.62, 0.1, 0.2], "axes": "opengl"},
    {"position": [0.3, -6.1, 2.9], "yaw": 88.5, "pitch": 23.25, "roll": -1.125},
    {"rvec": [1.9, 0.1, -0.05], "tvec": [0.2, 1.1, 6.3]},
    {"rmat": [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]], "tvec": [0.0, 2.0, 7.0]},
]


def live_pixels(base):
    query = ";".join(",".join(repr(float(c)) for c in p) for p in WORLD_POINTS)
    status, result = curl_json(base, "/api/project?points=" + query)
    check(status == 200, f"/api/project: {status} {result}")
    return result


def saved_pixels(overlayd, config_path):
    """What a fresh process reads from the saved config: `overlayd project --json`."""
    numbers = [repr(float(c)) for p in WORLD_POINTS for c in p]
    done = subprocess.run([overlayd, "project", "--config", config_path, "--json", "--"] + numbers,
                          capture_output=True, text=True, timeout=60)
    check(done.returncode == 0, f"overlayd project on the saved config: {done.returncode} {done.stderr}")
    return json.loads(done.stdout)


def same_projection(live, saved, what):
    check(len(live) == len(saved), f"{what}: {len(live)} live points, {len(saved)} saved")
    for a, b in zip(live, saved):
        check(a["visible"] == b["visible"] and (a["pixel"] is None) == (b["pixel"] is None),
              f"{what}: {a['world']}: live {a['visible']} {a['pixel']}, saved {b['visible']} {b['pixel']}")
        if a["pixel"] is not None:
            # The pose goes back in the config's own keys (degrees here), equal to about 1e-15: 1e-9 px on the frame,
            # relatively as close for a point half a million pixels off it, next to the camera plane.
            slack = 1e-9 + 1e-12 * math.hypot(*a["pixel"])
            check(math.dist(a["pixel"], b["pixel"]) <= slack and abs(a["depth"] - b["depth"]) <= 1e-9,
                  f"{what}: {a['world']}: live pixel {a['pixel']} depth {a['depth']}, saved config {b['pixel']} "
                  f"depth {b['depth']}")


def save(base, dropin):
    status, result = curl_json(base, "/api/save", "POST", "", token=TOKEN)
    check(status == 200 and result == {"saved": dropin}, f"/api/save: {status} {result}")


def put_camera(base, change):
    status, result = curl_json(base, "/api/camera", "PUT", json.dumps(change), token=TOKEN)
    check(status == 200, f"PUT /api/camera {change}: {status} {result}")


def round_trip_every_key(overlayd, config_path, dropin, base):
    for change in CHANGES:
        put_camera(base, change)
        save(base, dropin)
        same_projection(live_pixels(base), saved_pixels(overlayd, config_path), f"after {json.dumps(change)}")
    visible = sum(p["visible"] for p in live_pixels(base))
    check(visible >= 5, f"only {visible} points visible at the end: the comparison saw too little")


def planted_temporaries(overlayd, config_path, dropin, base, workdir):
    """A link at the name a save used to write through, and a file there, are neither followed nor touched."""
    victim = os.path.join(workdir, "victim.txt")
    open(victim, "w").write("not the drop-in\n")
    planted = dropin + ".tmp"
    os.symlink(victim, planted)
    put_camera(base, {"fov": 52.5})
    save(base, dropin)
    check(open(victim).read() == "not the drop-in\n", "the save wrote through a planted .tmp symlink")
    check(os.path.islink(planted) and not os.path.islink(dropin), "the planted link was moved over the drop-in")
    same_projection(live_pixels(base), saved_pixels(overlayd, config_path), "with a planted .tmp symlink")
    os.remove(planted)
    open(planted, "w").write("someone else's file\n")
    put_camera(base, {"fov": 53.5})
    save(base, dropin)
    check(os.path.isfile(planted) and open(planted).read() == "someone else's file\n",
          "the save overwrote or moved a planted .tmp file")
    same_projection(live_pixels(base), saved_pixels(overlayd, config_path), "with a planted .tmp file")
    os.remove(planted)
    os.mkdir(planted)  # a folder there made every save fail
    put_camera(base, {"fov": 54.5})
    save(base, dropin)
    os.rmdir(planted)
    left = glob.glob(os.path.join(workdir, ".*.tmp"))
    check(not left, f"temporaries left behind: {left}")


def restarted_pose_only_save(overlayd, config_path, dropin, workdir, port):
    """An earlier run saved a field of view; the next run saves a new pose only: the fov stays."""
    daemon = daemon_fixture.Daemon(overlayd, config_path, workdir, port)
    try:
        base = daemon.base
        daemon.wait_ready()
        put_camera(base, {"fov": 41.0, "near": 0.25})
        save(base, dropin)
        check(daemon.stop() == 0, "overlayd did not exit 0 on SIGTERM")
        daemon = daemon_fixture.Daemon(overlayd, config_path, workdir, port)
        daemon.wait_ready()
        put_camera(base, {"position": [0.5, -6.5, 3.2], "yaw": 91.0, "pitch": 24.0, "roll": 0.5})
        save(base, dropin)
        same_projection(live_pixels(base), saved_pixels(overlayd, config_path), "a restarted pose-only save")
        status, state = curl_json(base, "/state")
        check(status == 200 and abs(state["camera"]["intrinsics"]["vfov"] - 41.0) < 1e-9,
              f"the restarted daemon's fov: {state.get('camera')}")
    finally:
        check(daemon.stop() == 0, "overlayd did not exit 0 on SIGTERM")


def solve_pose_keeps_intrinsics(overlayd, workdir):
    """A drop-in with pinhole intrinsics and a lens: marks made through it are solved, written, and reproject onto
    themselves."""
    config_path = os.path.join(workdir, "marks.toml")
    open(config_path, "w").write(daemon_fixture.demo_without_sinks())
    dropin = os.path.join(workdir, "marks.live.toml")
    open(dropin, "w").write('[camera]\neye = [1.5, -7.0, 2.8]\ntarget = [0.0, 3.0, 0.0]\n'
                            'pinhole = { fx = 1400.0, fy = 1402.0, cx = 650.5, cy = 355.5 }\n'
                            'near = 0.2\ndistortion = { model = "plumb_bob", '
                            'coefficients = [-0.12, 0.02, 0.0, 0.0, 0.0] }\n')
    marks_world = [(x, y, z) for x, y, z in WORLD_POINTS if z == 0 and abs(x) <= 3 and 0 <= y <= 12]
    projected = subprocess.run([overlayd, "project", "--config", config_path, "--json", "--"] +
                               [repr(float(c)) for p in marks_world for c in p], capture_output=True, text=True)
    check(projected.returncode == 0, f"project for the marks: {projected.stderr}")
    marks = [p for p in json.loads(projected.stdout) if p["visible"]]
    check(len(marks) >= 6, f"only {len(marks)} marks visible")
    points = os.path.join(workdir, "marks.txt")
    open(points, "w").write("".join(f"{p['world'][0]} {p['world'][1]} {p['world'][2]} {p['pixel'][0]!r} "
                                    f"{p['pixel'][1]!r}\n" for p in marks))
    # Move the drop-in's pose away, so that what --write saves is the solved pose.
    text = open(dropin).read().replace("eye = [1.5, -7.0, 2.8]", "eye = [1.0, -6.0, 3.0]")
    open(dropin, "w").write(text)
    solved = subprocess.run([overlayd, "solve-pose", "--config", config_path, "--points", points, "--write"],
                            capture_output=True, text=True)
    check(solved.returncode == 0, f"solve-pose --write: {solved.returncode} {solved.stderr}")
    again = subprocess.run([overlayd, "project", "--config", config_path, "--json", "--"] +
                           [repr(float(c)) for p in marks for c in p["world"]], capture_output=True, text=True)
    check(again.returncode == 0, f"project after --write: {again.stderr}")
    worst = max(math.dist(a["pixel"], b["pixel"]) for a, b in zip(marks, json.loads(again.stdout)))
    check(worst < 1e-3, f"the marks reproject {worst} px away after solve-pose --write")
    check("solve-pose --write" in open(dropin).read(), "the drop-in does not say solve-pose wrote it")


def run(overlayd, workdir):
    """Each part on its own (a failed part does not hide the others); the failures' messages."""
    port = daemon_fixture.free_port()
    token_file = os.path.join(workdir, "token")
    open(token_file, "w").write(TOKEN + "\n")
    config_path = os.path.join(workdir, "save.toml")
    open(config_path, "w").write(daemon_fixture.demo_without_sinks() +
                                 daemon_fixture.http_section(port, control="token", token_file=token_file))
    dropin = os.path.join(workdir, "save.live.toml")
    failures = []

    def part(name, function, *args):
        if os.path.exists(dropin):
            os.remove(dropin)
        try:
            function(*args)
        except AssertionError as failure:
            failures.append(f"{name}: {failure}")

    part("restart", restarted_pose_only_save, overlayd, config_path, dropin, workdir, port)
    for name, function in (("every key", round_trip_every_key), ("planted", planted_temporaries)):
        if os.path.exists(dropin):
            os.remove(dropin)  # each part starts from the main file's camera
        daemon = daemon_fixture.Daemon(overlayd, config_path, workdir, port)
        try:
            daemon.wait_ready()
            args = (overlayd, config_path, dropin, daemon.base) + ((workdir,) if name == "planted" else ())
            part(name, function, *args)
        finally:
            daemon.stop()
    part("solve-pose", solve_pose_keeps_intrinsics, overlayd, workdir)
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    failures = run(os.path.abspath(args.overlayd), args.workdir)
    for failure in failures:
        print(f"FAIL: {failure}", file=sys.stderr)
    if failures:
        return 1
    print(f"ok: {check.count} checks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
