#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The encoded row of scripts/compare-peers.sh: CPU time per encoded overlaid frame, overlayd against FFmpeg, on
the same raw frames (ffmpeg's testsrc2, 1280x720 YUYV) with the same encoder (x264: veryfast, zerolatency, the same
bitrate and keyframe interval; Debian's FFmpeg has libx264 and no libopenh264), each also without its overlay
(the encode alone), each run as its own process, CPU from wait4 (user + system, every thread).
- overlayd: `run` replaying the frames, a ground grid, a thick polyline and a clock text, [encoder] x264, a
  record sink (Matroska) in the work folder;
- FFmpeg: drawgrid + drawbox + drawtext, libx264, the same container.
Every output is read back with ffprobe and the CPU time divided by the frames in it: a run that lost more than
a tenth is not a figure. Prints a Markdown table.

    encoded.py --overlayd build-release/daemon/overlayd [--frames 150] [--runs 3] [--work out/peers-encoded]"""
import argparse
import glob
import os
import shutil
import statistics
import subprocess
import sys

WIDTH, HEIGHT, FPS, BITRATE_KBPS, KEYFRAME_S = 1280, 720, 30, 4000, 2.0
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

CAMERA = """
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
"""
# A ground grid, a thick polyline and a clock text (also tests/stream/cpu_per_frame.py's).
ANNOTATIONS = """
[[annotation]]
type = "grid"
spacing = 1.0
extent = 20.0
major_every = 5
style = { colour = "#ffffffb0", width = 1.0 }
major_style = { colour = "#ffff00", width = 2.0 }
[[annotation]]
type = "polyline"
points = [[-1.5, 1.0, 0.0], [-1.5, 8.0, 0.0]]
style = { colour = "#ff00ff", width = 8.0 }
[[annotation]]
type = "text"
text = "{time:%Y-%m-%d %H:%M:%S}"
position = [10.0, 10.0]
size_px = 24.0
background = "#00000080"
style = { colour = "white" }
"""


def overlayd_config(frames, directory, draw):
    return f"""# Written by scripts/peers/encoded.py.
[daemon]
stats_interval = 0.0
[source]
kind = "replay"
format = "YUYV"
width = {WIDTH}
height = {HEIGHT}
fps = {FPS}
[source.replay]
path = "{frames}"
format = "raw"
[encoder]
encoder = "x264"
bitrate_kbps = {BITRATE_KBPS}
keyframe_interval_s = {KEYFRAME_S}
queue = 8
[[sink]]
kind = "record"
directory = "{directory}"
segment_s = 3600
container = "matroska"
""" + (CAMERA + ANNOTATIONS if draw else "")


def ffmpeg_command(frames, n, out, draw):
    cmd = ["ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-f", "rawvideo", "-pix_fmt", "yuyv422", "-s",
           f"{WIDTH}x{HEIGHT}", "-framerate", str(FPS), "-i", frames]
    if draw:
        cmd += ["-vf", "drawgrid=w=64:h=64:t=1:c=white@0.7,drawbox=x=600:y=200:w=8:h=400:t=fill:c=magenta,"
                f"drawtext=fontfile={FONT}:text='%{{localtime}}':x=10:y=10:fontsize=24:fontcolor=white:"
                "box=1:boxcolor=black@0.5"]
    return cmd + ["-frames:v", str(n), "-c:v", "libx264", "-preset", "veryfast", "-tune", "zerolatency", "-b:v",
                  f"{BITRATE_KBPS}k", "-g", str(int(KEYFRAME_S * FPS * 2)), "-pix_fmt", "yuv420p", "-f", "matroska",
                  "-y", out]


def cpu_seconds(argv):
    child = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(child.pid, 0)
    err = child.stderr.read().decode(errors="replace")
    if status != 0:
        sys.exit(f"encoded.py: failed (status {status}): {' '.join(argv)}\n{err[-800:]}")
    return usage.ru_utime + usage.ru_stime


def frames_in(path):
    done = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                           "stream=nb_read_frames", "-of", "csv=p=0", path], capture_output=True, text=True)
    return int(done.stdout.strip() or 0) if done.stdout.strip().isdigit() else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--frames", type=int, default=150)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--work", default="out/peers-encoded")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    frames = os.path.join(args.work, "frames.yuv")
    if not os.path.exists(frames) or os.path.getsize(frames) != WIDTH * HEIGHT * 2 * args.frames:
        subprocess.run(["ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-f", "lavfi", "-i",
                        f"testsrc2=size={WIDTH}x{HEIGHT}:rate={FPS}", "-frames:v", str(args.frames), "-f", "rawvideo",
                        "-pix_fmt", "yuyv422", "-y", frames], check=True)

    def overlayd(draw, run):
        directory = os.path.join(args.work, f"overlayd-{'draw' if draw else 'plain'}-{run}")
        shutil.rmtree(directory, ignore_errors=True)
        os.makedirs(directory)
        config = os.path.join(args.work, f"overlayd-{'draw' if draw else 'plain'}.toml")
        with open(config, "w") as file:
            file.write(overlayd_config(os.path.abspath(frames), os.path.abspath(directory), draw))
        seconds = cpu_seconds([args.overlayd, "run", "--config", config, "--frames", str(args.frames), "--log-level",
                               "warning"])
        files = glob.glob(os.path.join(directory, "*.mkv"))
        return seconds, sum(frames_in(f) for f in files)

    def ffmpeg(draw, run):
        out = os.path.join(args.work, f"ffmpeg-{'draw' if draw else 'plain'}-{run}.mkv")
        return cpu_seconds(ffmpeg_command(frames, args.frames, out, draw)), frames_in(out)

    results, least = {}, {}
    for run in range(args.runs):  # interleaved, so that the machine's load falls on every tool alike
        for name, tool in (("overlayd", overlayd), ("ffmpeg", ffmpeg)):
            for draw in (False, True):
                seconds, encoded = tool(draw, run)
                # overlayd's stop at --frames N loses the last frame or two still inside the encoder, and a busy
                # machine makes its feed drop frames rather than stall the source (counted, not encoded): the CPU
                # time is divided by the frames that came out, which counts those against overlayd.
                least[name] = min(least.get(name, encoded), encoded)
                if encoded < args.frames * 0.9:
                    sys.exit(f"encoded.py: {name} {'with' if draw else 'without'} its overlay encoded {encoded} of "
                             f"{args.frames} frames: not a figure")
                results.setdefault((name, draw), []).append(1000 * seconds / encoded)
    print(f"| {WIDTH}x{HEIGHT} YUYV, x264 veryfast zerolatency {BITRATE_KBPS} kbit/s, {args.frames} frames, "
          f"{args.runs} runs | encode alone, ms CPU/frame | overlay + encode | the overlay adds |")
    print("|---|---|---|---|")
    best = min(statistics.median(results[(n, True)]) for n in ("overlayd", "ffmpeg"))
    for name, what in (("overlayd", "run: replay, grid + polyline + clock text, record sink"),
                       ("ffmpeg", "drawgrid + drawbox + drawtext, libx264")):
        plain, drawn = statistics.median(results[(name, False)]), statistics.median(results[(name, True)])
        print(f"| {name} ({what}; at least {least[name]} frames out) | {plain:.2f} | {drawn:.2f} "
              f"({drawn / best:.2f}x the best) | {100 * (drawn - plain) / plain:+.1f} % |")


if __name__ == "__main__":
    sys.exit(main())
