#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Host half of the VM tier's CAN steering check (tests/vm/guest/checks/90-can-steering.sh).

The guest sent steering-wheel angles A and B over vcan0 and kept overlayd's /snapshot JPEGs: one per angle, one after
the signal went stale and one raw (?raw=1, the frame before the overlay). This script computes the rear wheel tracks
independently (Ackermann: road-wheel angle d = wheel / steering_ratio, turning centre (0, R) with R = wheelbase /
tan d, backing up by arc length s turns the body by -s / R about it; the wheels start at y = +-track_width / 2), has
`overlayd project` put them into pixels, and checks the snapshots:

  can-steering-tracks-A/B      the track colour lies near most projected track points of that angle, the mark
                               colours near the projected distance marks;
  can-steering-moved           each snapshot lacks the other angle's tracks where they are far from its own lines;
  can-steering-snapshot-stale  after the timeout (and -snapshot-out-of-range after a value outside min..max, if the
                               guest kept that snapshot): no track or mark colour anywhere, and the straight distance
                               marks in the stale colour where the raw frame is a dark checker square.

Only python3 (3.11: tomllib) and ffmpeg (JPEG -> RGB24). Prints PASS/FAIL lines like the guest (one FAIL
can-steering-host line when an input is missing); a non-zero exit only when it crashed.

    can_steering.py ARTIFACTS_DIR OVERLAYD CONFIG
"""
import json
import math
import os
import subprocess
import sys
import tomllib

NEIGHBOURHOOD = 3  # pixels either side: the line is 4 px wide, JPEG and anti-aliasing blur its colour
SAMPLE_STEP = 0.1  # metres of arc between track samples
MIN_FAR_POINTS = 15  # the other angle's points far from this one's lines: enough to prove the lines moved
FAR_PX = 14.0  # "far": this many pixels from every line drawn in a snapshot (its tracks and marks)

# overlayd's named colours (config/toml_reader.cpp)
COLOURS = {"white": (255, 255, 255), "black": (0, 0, 0), "red": (255, 0, 0), "green": (0, 255, 0),
           "blue": (0, 0, 255), "yellow": (255, 255, 0), "cyan": (0, 255, 255), "magenta": (255, 0, 255),
           "orange": (255, 165, 0)}


def line(name, ok, detail):
    print(f"{'PASS' if ok else 'FAIL'} {name}: {detail}", flush=True)


def parse_colour(text):
    text = text.strip().lower()
    if text in COLOURS:
        return COLOURS[text]
    if text.startswith("#") and len(text) in (7, 9):
        return tuple(int(text[i:i + 2], 16) for i in (1, 3, 5))
    raise ValueError(f"colour {text!r} is not one this script knows")


def colour_near(pixel, want, tol):
    """JPEG (4:2:2 from YUYV, quality 90) over a 4 px line: each channel within tol of the wanted colour."""
    return all(abs(p - w) <= tol for p, w in zip(pixel, want))


def is_track_colour(pixel, want):
    """A saturated colour (every channel 0 or 255: yellow, red, green...) loses chroma in JPEG and over a thin line:
    its full channels must be >= 140 and at least 70 above its empty ones (yellow over the checker's greys 60 and
    150 and the sky 140, 170, 200 fails that). Other colours: each channel within 40."""
    if all(c in (0, 255) for c in want) and 0 < sum(want) < 765:
        high = [p for p, c in zip(pixel, want) if c == 255]
        low = [p for p, c in zip(pixel, want) if c == 0]
        return min(high) >= 140 and min(high) - max(low) >= 70
    return colour_near(pixel, want, 40)


class Image:
    def __init__(self, path, width, height):
        raw = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt", "rgb24", "-"],
                             check=True, capture_output=True).stdout
        if len(raw) != width * height * 3:
            raise ValueError(f"{path}: decoded {len(raw)} bytes, want {width}x{height} RGB24")
        self.data, self.w, self.h = raw, width, height

    def at(self, x, y):
        i = (y * self.w + x) * 3
        return self.data[i], self.data[i + 1], self.data[i + 2]

    def any_near(self, u, v, test, radius=NEIGHBOURHOOD):
        x0, y0 = int(round(u)), int(round(v))
        for y in range(max(0, y0 - radius), min(self.h, y0 + radius + 1)):
            for x in range(max(0, x0 - radius), min(self.w, x0 + radius + 1)):
                if test(self.at(x, y)):
                    return True
        return False

    def count(self, test):
        return sum(1 for i in range(0, len(self.data), 3) if test(self.data[i:i + 3]))


def after_reversing(px, py, s, d_rad, wheelbase):
    """Body point (px, py) after the rear axle centre backed up by arc length s with road-wheel angle d."""
    if abs(math.tan(d_rad)) < 1e-12:
        return px - s, py
    r = wheelbase / math.tan(d_rad)  # signed: positive turns left, centre at (0, r)
    a = -s / r  # the body's rotation about the centre
    dx, dy = px, py - r
    return dx * math.cos(a) - dy * math.sin(a), r + dx * math.sin(a) + dy * math.cos(a)


def guide_geometry(guide, wheel_deg):
    """Tracks (two lists of (x, y, 0) in the car frame) and marks ([(left, right)]) for a steering-wheel angle."""
    d = math.radians(wheel_deg / guide.get("steering_ratio", 1.0))
    wb, half, length = guide["wheelbase"], guide["track_width"] / 2, guide["length"]
    n = int(round(length / SAMPLE_STEP))
    tracks = [[(*after_reversing(0.0, side * half, length * i / n, d, wb), 0.0) for i in range(n + 1)]
              for side in (1, -1)]
    marks = [((*after_reversing(0.0, half, m, d, wb), 0.0), (*after_reversing(0.0, -half, m, d, wb), 0.0))
             for m in guide.get("distance_marks", []) if 0 <= m <= length]
    return tracks, marks


def frame_to_world(config, name, point):
    """The car frame's pose (translation + yaw about z, the only kind this config uses) applied to a point."""
    frames = {f["name"]: f for f in config.get("frame", [])}
    x, y, z = point
    while name and name != "world":
        f = frames[name]
        if any(f.get(k, 0.0) for k in ("pitch", "roll")) or "rotation" in f or "quaternion" in f:
            raise ValueError(f"frame {name}: only translation + yaw is handled here")
        yaw = math.radians(f.get("yaw", 0.0))
        t = f.get("translation", [0.0, 0.0, 0.0])
        x, y = x * math.cos(yaw) - y * math.sin(yaw), x * math.sin(yaw) + y * math.cos(yaw)
        x, y, z = x + t[0], y + t[1], z + t[2]
        name = f.get("parent", "world")
    return x, y, z


def project(overlayd, config_path, config, frame, points):
    """Pixels of car-frame points through `overlayd project --json` (None behind the camera)."""
    args = [overlayd, "project", "--config", config_path, "--json", "--"]
    for p in points:
        args += [repr(c) for c in frame_to_world(config, frame, p)]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    result = json.loads(out)
    if len(result) != len(points):
        raise ValueError(f"overlayd project answered {len(result)} points for {len(points)}")
    # Outside the viewport still has a pixel (a mark's end may be off the image while the rest shows); behind the
    # camera has none.
    return [tuple(r["pixel"]) if r.get("pixel") is not None else None for r in result]


def projected_geometry(overlayd, config_path, config, guide, wheel_deg):
    tracks, marks = guide_geometry(guide, wheel_deg)
    flat = tracks[0] + tracks[1] + [p for m in marks for p in m]
    px = project(overlayd, config_path, config, guide.get("frame", "world"), flat)
    n = len(tracks[0])
    track_px = [px[:n], px[n:2 * n]]
    mark_px = [(px[2 * n + 2 * i], px[2 * n + 2 * i + 1]) for i in range(len(marks))]
    return track_px, mark_px


def inside(p, w, h, margin=NEIGHBOURHOOD + 1):
    return p is not None and margin <= p[0] < w - margin and margin <= p[1] < h - margin


def segment_distance(p, a, b):
    ax, ay = a
    bx, by = b
    dx, dy = bx - ax, by - ay
    t = 0.0 if dx == dy == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / (dx * dx + dy * dy)))
    return math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy)


def drawn_segments(track_px, mark_px):
    """The 2D segments one snapshot's overlay consists of (visible ends only)."""
    segs = []
    for track in track_px:
        segs += [(a, b) for a, b in zip(track, track[1:]) if a is not None and b is not None]
    segs += [(a, b) for a, b in mark_px if a is not None and b is not None]
    return segs


def mark_samples(mark_px, per_mark=12):
    """Points along each projected mark (a straight segment in 3D is straight in the pinhole image)."""
    out = []
    for i, (a, b) in enumerate(mark_px):
        if a is None or b is None:
            out.append([])
            continue
        out.append([(a[0] + (b[0] - a[0]) * k / per_mark, a[1] + (b[1] - a[1]) * k / per_mark)
                    for k in range(1, per_mark)])  # not the ends: they lie on the tracks
    return out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    art, overlayd, config_path = sys.argv[1:]
    paths = {k: os.path.join(art, f"can-steering-{k}.jpg") for k in ("a", "b", "stale", "raw")}
    angles_path = os.path.join(art, "can-steering-angles.txt")
    missing = [p for p in list(paths.values()) + [angles_path] if not os.path.exists(p)]
    if missing:
        line("can-steering-host", False, f"the guest left no {', '.join(os.path.basename(m) for m in missing)}")
        return 0
    if not os.access(overlayd, os.X_OK):
        line("can-steering-host", False, f"no overlayd binary at {overlayd} to project the tracks with")
        return 0
    angles = dict(l.split() for l in open(angles_path) if l.strip())
    wheel_a, wheel_b = float(angles["A"]), float(angles["B"])
    with open(config_path, "rb") as f:
        config = tomllib.load(f)
    w, h = config["source"]["width"], config["source"]["height"]
    target = config["input"]["can"][0]["target"].removesuffix(".steering")
    guide = next(a for a in config["annotation"] if a["name"] == target and a["type"] == "guide-lines")
    track_colour = parse_colour(guide["style"]["colour"])
    mark_colours = [parse_colour(c) for c in guide.get("mark_colours", [])]
    stale_colour = parse_colour(guide.get("stale_colour", "#9e9e9e"))
    ratio = guide.get("steering_ratio", 1.0)

    images = {k: Image(p, w, h) for k, p in paths.items()}
    geo = {k: projected_geometry(overlayd, config_path, config, guide, deg)
           for k, deg in (("a", wheel_a), ("b", wheel_b), ("straight", 0.0))}

    def is_track(p):
        return is_track_colour(p, track_colour)

    def track_points(key):
        return [p for track in geo[key][0] for p in track if inside(p, w, h)]

    # Tracks and marks of each angle in its own snapshot.
    for key, deg in (("a", wheel_a), ("b", wheel_b)):
        pts = track_points(key)
        hits = sum(images[key].any_near(u, v, is_track) for u, v in pts)
        frac = hits / len(pts) if pts else 0.0
        mark_detail, marks_ok = [], True
        for i, samples in enumerate(mark_samples(geo[key][1])):
            want = mark_colours[i] if i < len(mark_colours) else track_colour
            inside_pts = [p for p in samples if inside(p, w, h)]
            got = sum(images[key].any_near(u, v, lambda px: is_track_colour(px, want)) for u, v in inside_pts)
            mfrac = got / len(inside_pts) if inside_pts else 0.0
            marks_ok &= mfrac >= 0.7 or not inside_pts
            mark_detail.append(f"{guide['distance_marks'][i]} m {got}/{len(inside_pts)}")
        tan_d = math.tan(math.radians(deg / ratio))
        r = f"{guide['wheelbase'] / tan_d:+.2f} m" if abs(tan_d) > 1e-12 else "straight"
        line(f"can-steering-tracks-{key.upper()}", len(pts) >= 40 and frac >= 0.85 and marks_ok,
             f"wheel {deg:+.1f} deg / ratio {ratio:g} = road {deg / ratio:+.2f} deg, R {r}: track colour "
             f"within {NEIGHBOURHOOD} px of {hits}/{len(pts)} projected track points ({frac:.0%}, want >= 85%); "
             f"mark colours: {', '.join(mark_detail)} (want >= 70% each)")

    # The lines moved: the other angle's track points far from everything this snapshot draws are not track-coloured.
    moved_ok, moved_detail = True, []
    for key, other in (("a", "b"), ("b", "a")):
        segs = drawn_segments(*geo[key])
        far = [p for p in track_points(other) if min(segment_distance(p, a, b) for a, b in segs) > FAR_PX]
        hits = sum(images[key].any_near(u, v, is_track) for u, v in far)
        frac = hits / len(far) if far else 1.0
        moved_ok &= len(far) >= MIN_FAR_POINTS and frac <= 0.1
        moved_detail.append(f"snapshot {key.upper()}: {hits}/{len(far)} of {other.upper()}'s track points more than "
                            f"{FAR_PX:g} px from {key.upper()}'s lines are track-coloured")
    shift = [math.hypot(pa[0] - pb[0], pa[1] - pb[1]) for ta, tb in zip(geo["a"][0], geo["b"][0])
             for pa, pb in zip(ta, tb) if inside(pa, w, h) and inside(pb, w, h)]
    line("can-steering-moved", moved_ok,
         f"{'; '.join(moved_detail)} (want >= {MIN_FAR_POINTS} points, <= 10%); the same arc length lies up to "
         f"{max(shift, default=0):.0f} px apart between A and B in the image")

    # Unknown (stale, out of range): no track or mark colour anywhere; the straight marks in the stale colour.
    raw = images["raw"]
    saturated = [track_colour] + [c for c in mark_colours if c != track_colour]

    def any_saturated(px):
        return any(is_track_colour(px, c) for c in saturated)

    # A mark proves itself where it covers a pixel that is dark (60) in the raw frame: the light squares (150) look
    # like the stale grey (158). The marks at 1.5, 2.5 and 3.5 m lie on the 0.5 m checker's edges, half over dark.
    def covers_dark(image, u, v, radius=2):
        x0, y0 = int(round(u)), int(round(v))
        found_dark = False
        for y in range(max(0, y0 - radius), min(h, y0 + radius + 1)):
            for x in range(max(0, x0 - radius), min(w, x0 + radius + 1)):
                if max(raw.at(x, y)) <= 100:
                    found_dark = True
                    px = image.at(x, y)
                    if colour_near(px, stale_colour, 28) and max(px) - min(px) <= 24:
                        return True, True
        return found_dark, False

    def unknown_check(name, image, what):
        total = image.count(any_saturated)
        left = {k: sum(image.any_near(u, v, is_track) for u, v in track_points(k)) for k in ("a", "b", "straight")}
        dark_pts, grey_hits = 0, 0
        for samples in mark_samples(geo["straight"][1]):
            for u, v in samples:
                if inside((u, v), w, h):
                    dark, grey = covers_dark(image, u, v)
                    dark_pts += dark
                    grey_hits += grey
        grey_frac = grey_hits / dark_pts if dark_pts else 0.0
        ok = total <= 40 and all(n == 0 for n in left.values()) and dark_pts >= 6 and grey_frac >= 0.8
        line(name, ok,
             f"{what}: {total} pixels of the track or mark colours in the whole frame (want <= 40: JPEG noise); "
             f"track-coloured near the projected tracks of A {left['a']}, B {left['b']}, straight "
             f"{left['straight']} (want 0); the stale colour {guide.get('stale_colour', '#9e9e9e')} on a pixel "
             f"dark in the raw frame within 2 px of {grey_hits}/{dark_pts} straight-mark points (want >= 80% of >= 6)")

    unknown_check("can-steering-snapshot-stale", images["stale"], "after the timeout")
    range_path = os.path.join(art, "can-steering-range.jpg")
    if os.path.exists(range_path):
        unknown_check("can-steering-snapshot-out-of-range", Image(range_path, w, h), "a value outside min..max")
    return 0


if __name__ == "__main__":
    sys.exit(main())
