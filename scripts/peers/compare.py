#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""scripts/compare-peers.sh's measuring half: the same scene over the same raw 1080p YUYV frames with overlayd,
FFmpeg, OpenCV and GStreamer, each tool's CPU time per frame (user + system of its process, from wait4's rusage,
all threads), with and without drawing, and the ratios to overlayd.

The scene (overlay_scene_bench's "Speed scene"): a ground grid of 19 + 19 lines 0.5 m apart, 2 px wide, an XYZ
triad 1.5 m long, 3 px wide, and 3 text labels, seen by a pinhole camera 6 m behind the origin and 2.5 m up,
pitched 22 degrees down. overlayd draws it from its config file; the peers draw the same 2D lines, whose ends
overlayd's own `project` command gives, so every tool draws the same pixels' worth of lines.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time

WIDTH, HEIGHT, FPS = 1920, 1080, 30
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
GRID = dict(origin=0.25, spacing=0.5, extent=4.75)  # 19 lines a direction: i = -9..9 (overlay/shapes/line_shapes.cpp)
AXIS_LENGTH = 1.5
LABELS = [("origin", (0.0, 0.0, 0.0)), ("corner A", (4.75, 4.75, 0.0)), ("corner B", (4.75, -4.75, 0.0))]
LABEL_OFFSET, LABEL_PX = 4.0, 20.0
GRID_RGB, AXIS_RGB, TEXT_RGB = (230, 230, 230), [(255, 0, 0), (0, 255, 0), (0, 0, 255)], (255, 255, 255)

CAMERA = f"""[camera]
position = [-6.0, 0.0, 2.5]
yaw = 0.0
pitch = 22.0
near = 0.1
far = 200.0

[camera.pinhole]
fx = {0.8 * WIDTH}
fy = {0.8 * WIDTH}
cx = {(WIDTH - 1) / 2}
cy = {(HEIGHT - 1) / 2}
"""

SCENE = f"""
[[annotation]]
name = "grid"
type = "grid"
origin = [{GRID['origin']}, {GRID['origin']}, 0.0]
spacing = {GRID['spacing']}
extent = {GRID['extent']}
style = {{ colour = {list(GRID_RGB)}, width = 2.0 }}

[[annotation]]
name = "axes"
type = "axes"
length = {AXIS_LENGTH}
style = {{ width = 3.0 }}
""" + "".join(f"""
[[annotation]]
name = "{text}"
type = "label"
anchor = {list(anchor)}
text = "{text}"
offset_px = [{LABEL_OFFSET}, {LABEL_OFFSET}]
size_px = {LABEL_PX}
style = {{ colour = "white" }}
""" for text, anchor in LABELS)


def overlayd_config(frames_path, with_scene):
    return f"""# Written by scripts/peers/compare.py.
[daemon]
stats_interval = 0.0

[source]
kind = "replay"
format = "YUYV"
width = {WIDTH}
height = {HEIGHT}
fps = {FPS}

[source.replay]
path = "{frames_path}"
format = "raw"

{CAMERA}
{SCENE if with_scene else ""}
[[sink]]
kind = "null"
"""


def grid_segments():
    count = int(GRID["extent"] / GRID["spacing"] + 1e-9)
    o, e = GRID["origin"], GRID["extent"]
    segments = []
    for i in range(-count, count + 1):  # u = const, then v = const, as overlayd's grid
        c = o + i * GRID["spacing"]
        segments.append(((c, o - e, 0.0), (c, o + e, 0.0)))
    for i in range(-count, count + 1):
        c = o + i * GRID["spacing"]
        segments.append(((o - e, c, 0.0), (o + e, c, 0.0)))
    return segments


def project(overlayd, config, points):
    coordinates = [str(v) for p in points for v in p]
    out = subprocess.run([overlayd, "project", "--config", config, "--json", "--", *coordinates], check=True,
                         capture_output=True, text=True).stdout
    pixels = []
    for report in json.loads(out):
        if report["pixel"] is None:
            sys.exit(f"compare.py: {report['world']} does not project ({report.get('reason')}): the scene is wrong")
        pixels.append(report["pixel"])
    return pixels


def write_scene(overlayd, config, path):
    """The scene's 2D items for the peers, projected by overlayd: `line ...` and `text ...` lines."""
    segments = grid_segments()
    axes = [((0, 0, 0), tuple(AXIS_LENGTH if k == a else 0.0 for k in range(3))) for a in range(3)]
    ends = [p for s in segments + axes for p in s]
    pixels = project(overlayd, config, ends + [anchor for _, anchor in LABELS])
    lines = []
    for k, (width, rgb) in enumerate([(2, GRID_RGB)] * len(segments) + [(3, c) for c in AXIS_RGB]):
        (x0, y0), (x1, y1) = pixels[2 * k], pixels[2 * k + 1]
        lines.append(f"line {x0:.3f} {y0:.3f} {x1:.3f} {y1:.3f} {width} {rgb[0]} {rgb[1]} {rgb[2]}")
    for (text, _), (x, y) in zip(LABELS, pixels[len(ends):]):
        lines.append(f"text {x + LABEL_OFFSET:.1f} {y + LABEL_OFFSET:.1f} {LABEL_PX:g} 255 255 255 {text}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return [line.split(" ", 7) for line in lines if line.startswith("text")]


class Tool:
    """One peer: `command(frames, output, draw)` gives the argv of a run over the first `frames` frames."""

    def __init__(self, name, what, command):
        self.name, self.what, self.command = name, what, command


def make_tools(args, work, texts):
    frames = os.path.join(work, "frames.yuv")
    scene, png = os.path.join(work, "scene.txt"), os.path.join(work, "scene.png")
    frame_bytes = WIDTH * HEIGHT * 2

    def overlayd(n, out, draw):
        config = os.path.join(work, "overlayd.toml" if draw else "overlayd-empty.toml")
        return [args.overlayd, "render", "--config", config, "--frames", str(n), "--output", out,
                "--log-level", "warning"]

    def ffmpeg(n, out, draw):
        threads = ["-threads", "1", "-filter_threads", "1", "-filter_complex_threads", "1"]
        cmd = ["ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", *threads, "-f", "rawvideo", "-pix_fmt",
               "yuyv422", "-s", f"{WIDTH}x{HEIGHT}", "-framerate", str(FPS), "-i", frames]
        if draw:
            text = ",".join(f"drawtext=fontfile={FONT}:text='{t[7]}':x={float(t[1]):.0f}:y={float(t[2]):.0f}"
                            f":fontsize={LABEL_PX:g}:fontcolor=white" for t in texts)
            cmd += ["-i", png, "-filter_complex", f"[0:v][1:v]overlay=format=yuv422,{text}"]
        return cmd + ["-frames:v", str(n), "-f", "rawvideo", "-pix_fmt", "yuyv422", "-y", out]

    def opencv(n, out, draw):
        return [args.opencv_peer, "draw" if draw else "copy", scene, frames, out, str(WIDTH), str(HEIGHT), str(n)]

    source = (f"filesrc location={frames} blocksize={frame_bytes} num-buffers={{n}} ! rawvideoparse width={WIDTH} "
              f"height={HEIGHT} format=yuy2 framerate={FPS}/1")
    sink = "filesink location={out}"

    def gst_cairo(n, out, draw):
        convert = "videoconvert n-threads=1"
        middle = f" ! {convert} ! cairooverlay name=draw ! {convert} ! video/x-raw,format=YUY2" if draw else ""
        return [args.gi_python, args.gst_peer, f"{source}{middle} ! {sink}".format(n=n, out=out), scene]

    def gst_overlay(n, out, draw):
        texts_ = "".join(f" ! textoverlay text=\"{t[7]}\" font-desc=\"DejaVu Sans {LABEL_PX:g}px\" "
                         f"auto-resize=false draw-shadow=false draw-outline=false "
                         f"halignment=left valignment=top xpad=0 ypad=0 deltax={float(t[1]):.0f} "
                         f"deltay={float(t[2]):.0f}" for t in texts)
        middle = f" ! gdkpixbufoverlay location={png}{texts_}" if draw else ""
        return [args.gi_python, args.gst_peer, f"{source}{middle} ! {sink}".format(n=n, out=out)]

    return [
        Tool("overlayd", "render: the cached overlay blended in YUYV (the camera is still)", overlayd),
        Tool("ffmpeg", "overlay filter (the lines pre-rendered to a PNG) + 3 drawtext", ffmpeg),
        Tool("opencv", "cvtColor to BGR, cv::line LINE_AA + cv::putText, back to YUYV", opencv),
        Tool("gst-cairo", "videoconvert ! cairooverlay (draws each frame) ! videoconvert", gst_cairo),
        Tool("gst-overlay", "gdkpixbufoverlay (the lines' PNG) + 3 textoverlay, in YUY2", gst_overlay),
    ]


def cpu_seconds(argv):
    """User + system CPU seconds of one run of argv (its process and all its threads)."""
    child = subprocess.Popen(argv, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    if status != 0:
        sys.exit(f"compare.py: failed (status {status}): {' '.join(argv)}")
    return usage.ru_utime + usage.ru_stime


def blend_timer(tool, frames, out):
    """What overlayd's render reports as its mean blend time per frame (its closing info line)."""
    argv = tool.command(frames, out, True)
    log = subprocess.run(argv[:-2] + ["--log-level", "info"], check=True, capture_output=True, text=True)
    found = re.search(r" blend ([0-9.]+) ms", log.stdout + log.stderr)
    return found.group(1) if found else "?"


def changed_pixels(reference, frame):
    """Indices of the pixels whose luma differs from the reference's by more than 24 (a conversion's rounding
    changes many pixels by a few steps; a drawn line by much more over most of this picture)."""
    return {i for i, (a, b) in enumerate(zip(reference[0::2], frame[0::2])) if abs(a - b) > 24}


def check_drawings(overlayd, tools, work):
    """Each tool draws one frame into a file: its changed pixels must be about as many as overlayd's, and mostly
    the same ones, else it drew something else (or nothing) and its time would mean nothing. overlayd draws first
    (the reference), whether or not it is timed."""
    check = os.path.join(work, "check")
    os.makedirs(check, exist_ok=True)
    with open(os.path.join(work, "frames.yuv"), "rb") as f:
        reference = f.read(WIDTH * HEIGHT * 2)
    ours = None
    problems = []
    for tool in [overlayd] + [t for t in tools if t is not overlayd]:
        out = os.path.join(check, f"{tool.name}.yuv")
        cpu_seconds(tool.command(1, out, True))
        with open(out, "rb") as f:
            changed = changed_pixels(reference, f.read(WIDTH * HEIGHT * 2))
        if ours is None:
            ours = changed
        shared = len(changed & ours) / max(1, len(ours))
        print(f"check: {tool.name:12s} changed {100 * len(changed) / (WIDTH * HEIGHT):5.2f}% of the pixels, "
              f"{100 * shared:5.1f}% of overlayd's ({out})", file=sys.stderr)
        if not ours or not 0.5 <= len(changed) / len(ours) <= 2.0 or shared < 0.6:
            problems.append(tool.name)
    if problems:
        sys.exit(f"compare.py: {', '.join(problems)} did not draw the scene overlayd draws (see above)")


def make_frames(args, work):
    path = os.path.join(work, "frames.yuv")
    size = WIDTH * HEIGHT * 2 * args.frames
    if os.path.exists(path) and os.path.getsize(path) == size:
        return
    print(f"compare.py: {args.frames} frames of ffmpeg's testsrc2 into {path}", file=sys.stderr)
    subprocess.run(["ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-f", "lavfi", "-i",
                    f"testsrc2=size={WIDTH}x{HEIGHT}:rate={FPS}", "-frames:v", str(args.frames), "-f", "rawvideo",
                    "-pix_fmt", "yuyv422", "-y", path], check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--opencv-peer", required=True)
    parser.add_argument("--gst-peer", default=os.path.join(os.path.dirname(__file__), "gst_peer.py"))
    parser.add_argument("--gi-python", default="/usr/bin/python3")
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--work", required=True)
    parser.add_argument("--tools", default="overlayd,ffmpeg,opencv,gst-cairo,gst-overlay")
    args = parser.parse_args()
    work = os.path.abspath(args.work)
    os.makedirs(work, exist_ok=True)

    make_frames(args, work)
    frames = os.path.join(work, "frames.yuv")
    for name, with_scene in (("overlayd.toml", True), ("overlayd-empty.toml", False)):
        with open(os.path.join(work, name), "w") as f:
            f.write(overlayd_config(frames, with_scene))
    texts = write_scene(args.overlayd, os.path.join(work, "overlayd.toml"), os.path.join(work, "scene.txt"))
    subprocess.run([args.opencv_peer, "png", os.path.join(work, "scene.txt"), os.path.join(work, "scene.png"),
                    str(WIDTH), str(HEIGHT)], check=True)
    wanted = args.tools.split(",")
    everything = make_tools(args, work, texts)
    tools = [t for t in everything if t.name in wanted]
    check_drawings(everything[0], tools, work)

    # overlayd's render picks its output's format by the extension; /dev/null under a .yuv name.
    null = os.path.join(work, "null.yuv")
    if not os.path.islink(null):
        os.symlink("/dev/null", null)
    raw = {t.name: [] for t in tools}
    base = {t.name: [] for t in tools}
    for run in range(args.runs):
        for tool in tools:  # interleaved, so that a slower spell of the machine spreads over all the tools
            base[tool.name].append(cpu_seconds(tool.command(args.frames, null, False)) / args.frames)
            raw[tool.name].append(cpu_seconds(tool.command(args.frames, null, True)) / args.frames)
        print(f"compare.py: run {run + 1} of {args.runs} done", file=sys.stderr)

    def ms(values):
        return 1000 * statistics.median(values)

    def drawing(name):  # each run's own difference, so that a slow spell between runs does not leak in
        return [r - b for r, b in zip(raw[name], base[name])]

    ours = "overlayd" in raw
    print(f"\n{args.frames} frames {WIDTH}x{HEIGHT} YUYV, CPU ms per frame (user + system of the tool's process, "
          f"start-up included), median of {args.runs} run(s); {time.strftime('%Y-%m-%d')}, {os.uname().machine}\n")
    print("| tool | what it does | with drawing | without (read + write) | drawing only | x overlayd, with drawing "
          "| x overlayd, drawing only |")
    print("|---|---|---|---|---|---|---|")
    for tool in tools:
        r, b, d = ms(raw[tool.name]), ms(base[tool.name]), ms(drawing(tool.name))
        ratio_raw = f"{r / ms(raw['overlayd']):.1f}x" if ours else "-"
        ours_draw = ms(drawing("overlayd")) if ours else 0.0
        ratio = f"{d / ours_draw:.0f}x" if ours_draw > 0 else "-"
        print(f"| {tool.name} | {tool.what} | {r:.2f} | {b:.2f} | {d:.2f} | {ratio_raw} | {ratio} |")
    if ours:
        print(f"\noverlayd's own blend timer (wall clock around each frame's blend, in the process): "
              f"{blend_timer(next(t for t in tools if t.name == 'overlayd'), args.frames, null)} ms per frame")
    if args.runs > 1:
        print("\nranges over the runs, ms (with drawing / without / drawing only): " + "; ".join(
            f"{t.name} {1000 * min(raw[t.name]):.2f}-{1000 * max(raw[t.name]):.2f} / "
            f"{1000 * min(base[t.name]):.2f}-{1000 * max(base[t.name]):.2f} / "
            f"{1000 * min(drawing(t.name)):.2f}-{1000 * max(drawing(t.name)):.2f}" for t in tools))

if __name__ == "__main__":
    main()
