#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""[[input.path]] through the real path: a polyline's points fed by a file while `overlayd run` streams. Written,
replaced by rename, made malformed (by rename and by `printf > file`) and deleted; after each, /state reports the
points (or the refusal, naming file:line) and the next snapshot shows the magenta path where `overlayd project` (the
real binary's projection, independent of the renderer) puts the points, and not where a path never written would be.

    path_input_test.py --overlayd build/daemon/overlayd --workdir /tmp/path-input
Exit 0 when every check passed, 1 when any failed (each check prints PASS or FAIL with its numbers)."""
import argparse
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402

WIDTH, HEIGHT = 640, 360
ANNOTATION = "planned path"
# The camera of text_input_test.py, looking along +Y at the ground z = 0. The annotation's own points (a short
# segment from the origin) are replaced by the file's from the start: a missing file is an empty path.
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
name = "planned path"
type = "polyline"
points = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]   # replaced by the file's points once the daemon runs
style = { colour = "#ff00ff", width = 4.0, layer = "plan" }
[[input.path]]
annotation = "planned path"
file = "path.txt"
"""
CONFIG_POINTS = [(0.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
RADIUS = 3          # px around an expected pixel where the line must (or must not) be
PRESENT = 0.90      # a path is shown when magenta is near at least this share of its sampled pixels
ABSENT = 0.10       # and not shown when near fewer than this share


def curve(mirror=False, count=25):
    """A curve on the ground from (-2, 0) to (2, 6) (mirrored: from (2, 0) to (-2, 6)), count points."""
    sign = -1.0 if mirror else 1.0
    return [(sign * -2.0 * math.cos(math.pi * i / (count - 1)), 6.0 * i / (count - 1), 0.0) for i in range(count)]


# Never written to the file: two straight lines beside the curves, where magenta must never be.
DECOY = [[(-3.5, 0.5, 0.0), (-3.5, 5.5, 0.0)], [(3.5, 0.5, 0.0), (3.5, 5.5, 0.0)]]


def path_text(points, title):
    """The file's text: a comment, a blank line, and the points with the separators the format allows."""
    lines = [f"# {title}: {len(points)} points, x y z in metres", ""]
    for i, (x, y, z) in enumerate(points):
        lines.append(f"{x:.4f}, {y:.4f}, {z:.1f}" if i % 3 == 1 else f"{x:.4f} {y:.4f} {z:.1f}")
    return "\n".join(lines) + "\n"


def samples(polylines, per_segment=4):
    """World points along every segment of each polyline (each a list of points), its last vertex included."""
    out = []
    for line in polylines:
        for a, b in zip(line, line[1:]):
            for k in range(per_segment):
                t = k / per_segment
                out.append(tuple(a[c] + (b[c] - a[c]) * t for c in range(3)))
        out.append(line[-1])
    return out


def project(overlayd, config, world):
    """The pixels of the visible world points, from `overlayd project --json` (not from the renderer)."""
    coordinates = [f"{c:.6f}" for point in world for c in point]
    done = subprocess.run([overlayd, "project", "--config", config, "--json", "--"] + coordinates,
                          capture_output=True, text=True, timeout=30)
    if done.returncode != 0:
        raise AssertionError(f"overlayd project exited {done.returncode}: {done.stderr.strip()}")
    result = json.loads(done.stdout)
    pixels = [p["pixel"] for p in result if p["visible"] and p["pixel"]
              and RADIUS <= p["pixel"][0] < WIDTH - RADIUS and RADIUS <= p["pixel"][1] < HEIGHT - RADIUS]
    if len(pixels) < 0.9 * len(world):
        raise AssertionError(f"overlayd project: only {len(pixels)} of {len(world)} points inside the frame")
    return pixels


def snapshot_rgb(base, workdir, name):
    """The next frame's JPEG (saved as workdir/name, size checked by daemon_fixture), decoded by ffmpeg to rgb24."""
    done = subprocess.run(["curl", "-sS", "--max-time", "10", base + "/snapshot"], capture_output=True, timeout=20)
    if done.returncode != 0:
        raise AssertionError(f"/snapshot: curl exited {done.returncode}")
    width, height, _ = daemon_fixture.grey_pixels(done.stdout, workdir, name)
    if (width, height) != (WIDTH, HEIGHT):
        raise AssertionError(f"{name}: {width}x{height}, not {WIDTH}x{HEIGHT}")
    decoded = subprocess.run(["ffmpeg", "-v", "error", "-i", os.path.join(workdir, name), "-f", "rawvideo",
                              "-pix_fmt", "rgb24", "-"], capture_output=True, timeout=30, check=True)
    if len(decoded.stdout) != WIDTH * HEIGHT * 3:
        raise AssertionError(f"{name}: decoded {len(decoded.stdout)} bytes, not {WIDTH}x{HEIGHT} rgb24")
    return decoded.stdout


def magenta(rgb, x, y):
    """#ff00ff through NV12 and JPEG: generous against colour noise; the grey checkerboard and the sky never pass."""
    i = (y * WIDTH + x) * 3
    r, g, b = rgb[i], rgb[i + 1], rgb[i + 2]
    return r > 150 and g < 110 and b > 150


def share_near(rgb, pixels):
    """The share of pixels with magenta within RADIUS px."""
    hits = 0
    for u, v in pixels:
        u, v = int(round(u)), int(round(v))
        window = ((x, y) for y in range(v - RADIUS, v + RADIUS + 1) for x in range(u - RADIUS, u + RADIUS + 1))
        if any(magenta(rgb, x, y) for x, y in window):
            hits += 1
    return hits / len(pixels)


def away_from(pixels, other, distance=8.0):
    """The pixels farther than `distance` px from every pixel of `other` (where two paths cross, both are near)."""
    return [p for p in pixels if all(math.dist(p, q) > distance for q in other)]


def magenta_count(rgb):
    return sum(1 for y in range(HEIGHT) for x in range(WIDTH) if magenta(rgb, x, y))


def path_entry(daemon):
    entries = [e for e in daemon.state()["inputs"] if e.get("kind") == "path"]
    if len(entries) != 1:
        raise AssertionError(f"/state inputs: {len(entries)} path entries, want 1: {daemon.state()['inputs']}")
    return entries[0]


def wait_for(daemon, accept, what, timeout=5.0):
    """The path's /state entry once accept(entry) holds; AssertionError naming `what` and the last entry if not."""
    deadline = time.monotonic() + timeout
    entry = None
    while time.monotonic() < deadline:
        entry = path_entry(daemon)
        if accept(entry):
            return entry
        time.sleep(0.02)
    raise AssertionError(f"/state never showed {what} within {timeout} s: {entry}")


def replace_file(workdir, path_file, text):
    """Writes a temporary file in the same folder, then renames it over the path file (an atomic change)."""
    temporary = os.path.join(workdir, "path.tmp")
    with open(temporary, "w") as f:
        f.write(text)
    os.replace(temporary, path_file)


def line_error(entry, line):
    """Whether the entry's error names path.txt at this line (not line 23 for line 2)."""
    return re.search(rf"path\.txt:{line}(?!\d)", entry.get("error", "")) is not None


class Checks:
    def __init__(self):
        self.failed = []

    def run(self, name, body):
        try:
            detail = body()
            print(f"PASS {name}: {detail}")
        except (AssertionError, OSError, subprocess.SubprocessError, ValueError) as failure:
            print(f"FAIL {name}: {failure}")
            self.failed.append(name)


def run(overlayd, workdir):
    path_file = os.path.join(workdir, "path.txt")
    for stale in (path_file, os.path.join(workdir, "path.tmp")):
        if os.path.exists(stale):
            os.remove(stale)
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, "path.toml")
    with open(config, "w") as f:
        f.write(CONFIG + daemon_fixture.http_section(port, control="off"))

    path_a, path_b = curve(), curve(mirror=True)
    pixels_a = project(overlayd, config, samples([path_a]))
    pixels_b = project(overlayd, config, samples([path_b]))
    pixels_a_only = away_from(pixels_a, pixels_b)
    pixels_decoy = project(overlayd, config, samples(DECOY))
    pixels_config = project(overlayd, config, samples([CONFIG_POINTS], per_segment=8))
    checks = Checks()
    daemon = daemon_fixture.Daemon(overlayd, config, workdir, port)
    try:
        daemon.wait_ready()

        def missing_at_start():
            entry = wait_for(daemon, lambda e: e.get("points") == 0, "points = 0 for the missing file")
            expected = {"kind": "path", "annotation": ANNOTATION, "file": path_file}
            wrong = {k: entry.get(k) for k, v in expected.items() if entry.get(k) != v}
            if wrong or "error" in entry or not isinstance(entry.get("age_s"), (int, float)):
                raise AssertionError(f"/state entry {entry}: want {expected}, a numeric age_s and no error")
            rgb = snapshot_rgb(daemon.base, workdir, "0-missing.jpg")
            near_config, total = share_near(rgb, pixels_config), magenta_count(rgb)
            if near_config >= ABSENT or total > 20:
                raise AssertionError(f"no file, yet magenta near {near_config:.0%} of the config's own segment, "
                                     f"{total} magenta pixels in the frame (want an empty path: none)")
            return f"/state {entry}; magenta near {near_config:.0%} of the config's segment, {total} px in all"

        def written():
            with open(path_file, "w") as f:
                f.write(path_text(path_a, "path A"))
            entry = wait_for(daemon, lambda e: e.get("points") == len(path_a) and "error" not in e,
                             f"points = {len(path_a)} after writing path A")
            rgb = snapshot_rgb(daemon.base, workdir, "1-path-a.jpg")
            near_a, near_decoy = share_near(rgb, pixels_a), share_near(rgb, pixels_decoy)
            detail = (f"points={entry['points']}; magenta near {near_a:.0%} of path A's {len(pixels_a)} projected "
                      f"pixels, near {near_decoy:.0%} of the unwritten path's {len(pixels_decoy)}")
            if near_a < PRESENT or near_decoy >= ABSENT:
                raise AssertionError(detail + f" (want >= {PRESENT:.0%} and < {ABSENT:.0%})")
            return detail

        def renamed():
            replace_file(workdir, path_file, path_text(path_b, "path B, path A mirrored"))
            # Both paths have the same number of points: wait for the snapshot to change, then check it all.
            deadline = time.monotonic() + 5
            while True:
                rgb = snapshot_rgb(daemon.base, workdir, "2-path-b.jpg")
                near_b, near_a = share_near(rgb, pixels_b), share_near(rgb, pixels_a_only)
                if near_b >= PRESENT or time.monotonic() > deadline:
                    break
            entry = path_entry(daemon)
            detail = (f"points={entry.get('points')}; magenta near {near_b:.0%} of path B's pixels, near {near_a:.0%} "
                      f"of path A's {len(pixels_a_only)} away from where they cross")
            if entry.get("points") != len(path_b) or "error" in entry or near_b < PRESENT or near_a >= ABSENT:
                raise AssertionError(detail + f" (want points={len(path_b)}, no error, >= {PRESENT:.0%} and "
                                     f"< {ABSENT:.0%}); entry {entry}")
            return detail

        def malformed_renamed():
            # Line 6 is "abc" after a comment, a blank line and three good lines.
            good = "".join(f"{x:.4f} {y:.4f} {z:.1f}\n" for x, y, z in path_a[:3])
            replace_file(workdir, path_file, "# malformed\n\n" + good + "abc\n")
            entry = wait_for(daemon, lambda e: line_error(e, 6), "an error naming path.txt:6")
            log_names = re.search(r"path\.txt:6(?!\d)", daemon.log_text()) is not None
            if entry.get("points") != len(path_b) or not log_names:
                raise AssertionError(f"after the malformed file: points={entry.get('points')} (want "
                                     f"{len(path_b)}, unchanged), log names path.txt:6: {log_names}; entry {entry}")
            return f"error {entry['error']!r}, points={entry['points']} unchanged, logged with file:line"

        def malformed_echoed():
            # `printf ... > path.txt`: the shell truncates the file, then writes it; k good lines, then "1 2". Ten times:
            # a reader that takes the truncated, empty file for an empty path loses the race only sometimes.
            kept = []
            for k in range(1, 11):
                lines = " ".join(shlex.quote(f"{x:.3f} {y:.3f} {z:.1f}") for x, y, z in path_a[:k])
                subprocess.run(f"printf '%s\\n' {lines} '1 2' > {shlex.quote(path_file)}", shell=True, check=True)
                entry = wait_for(daemon, lambda e: line_error(e, k + 1), f"an error naming path.txt:{k + 1}")
                kept.append(entry.get("points"))
            if any(points != len(path_b) for points in kept):
                raise AssertionError(f"points after each of 10 `printf > path.txt` with a 2-number line: {kept} "
                                     f"(want {len(path_b)} each time: the points shown stay); last entry {entry}")
            return f"error {entry['error']!r}, points {kept} unchanged after 10 truncating writes"

        def still_shown():
            rgb = snapshot_rgb(daemon.base, workdir, "3-malformed.jpg")
            near_b, near_a = share_near(rgb, pixels_b), share_near(rgb, pixels_a_only)
            detail = f"after the malformed files, magenta near {near_b:.0%} of path B's pixels, {near_a:.0%} of A's"
            if near_b < PRESENT or near_a >= ABSENT:
                raise AssertionError(detail + f" (want path B still shown: >= {PRESENT:.0%} and < {ABSENT:.0%})")
            return detail

        def deleted():
            replace_file(workdir, path_file, path_text(path_b, "path B again"))
            wait_for(daemon, lambda e: e.get("points") == len(path_b) and "error" not in e,
                     f"points = {len(path_b)} and no error after writing path B again")
            os.remove(path_file)
            entry = wait_for(daemon, lambda e: e.get("points") == 0, "points = 0 after deleting the file")
            rgb = snapshot_rgb(daemon.base, workdir, "4-deleted.jpg")
            near_b, total = share_near(rgb, pixels_b), magenta_count(rgb)
            detail = f"points=0; magenta near {near_b:.0%} of path B's pixels, {total} magenta px in the frame"
            if "error" in entry or near_b >= ABSENT or total > 20:
                raise AssertionError(detail + f" (want no error, < {ABSENT:.0%}, none); entry {entry}")
            return detail

        checks.run("0 missing file at start = empty path", missing_at_start)
        checks.run("1 written file shown where projected", written)
        checks.run("2 replaced by rename", renamed)
        checks.run("3a malformed file (renamed in) refused, points stay", malformed_renamed)
        checks.run("3b malformed file (printf > file) refused, points stay", malformed_echoed)
        checks.run("3c previous path still shown", still_shown)
        checks.run("4 deleted file = empty path", deleted)
        if checks.failed:
            print(daemon.log_tail(20), file=sys.stderr)
    except Exception:
        print(daemon.log_tail(20), file=sys.stderr)
        raise
    finally:
        code = daemon.stop()
    if checks.failed:
        raise AssertionError(f"{len(checks.failed)} check(s) failed: {', '.join(checks.failed)}")
    if code != 0:
        raise AssertionError(f"overlayd exited {code}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    # Absolute: the config's relative `file` resolves against the config's folder, and the binary runs from here.
    workdir = os.path.abspath(args.workdir)
    os.makedirs(workdir, exist_ok=True)
    try:
        run(os.path.abspath(args.overlayd), workdir)
    except AssertionError as failure:
        print(f"path_input_test: FAILED: {failure}", file=sys.stderr)
        return 1
    print("path_input_test: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
