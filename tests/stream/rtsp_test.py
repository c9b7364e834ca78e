#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""kind = "rtsp" through the real path: `overlayd run` (synthetic source, an overlay, [encoder] openh264, an RTSP
sink on a free port) read by real clients:
- ffprobe over UDP and over TCP interleaved reports h264 at the stream's size and rate;
- ffmpeg decodes 60 frames, and the overlay's magenta line lies where `overlayd project` (the binary's projection,
  not the renderer) puts it, and not where a line never drawn would be (a tolerance for compression: a thick line);
- ten clients at once (five UDP, five TCP) each decode frames while /state lists ten clients and /metrics shows
  one encoder, whose frame count follows the source's (one encode, not ten);
- the footprint: the binary does not link GStreamer, a run without encoded sinks maps none of it (/proc/PID/maps),
  a run with one does (the check can see it);
- a port already taken stops `run` with the address in the message.

    rtsp_test.py --overlayd build/daemon/overlayd --workdir /tmp/rtsp-test
Exit 0 when every check passed, 1 when any failed (each check prints PASS or FAIL with its numbers)."""
import argparse
import json
import math
import os
import re
import socket
import subprocess
import sys
import threading
import time
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "http"))
import daemon_fixture  # noqa: E402

WIDTH, HEIGHT, FPS = 640, 360, 30
SCENE = """
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
name = "left rail"
type = "polyline"
points = [[-1.5, 1.0, 0.0], [-1.5, 8.0, 0.0]]
style = { colour = "#ff00ff", width = 8.0 }
"""
LINE = [(-1.5, 1.0, 0.0), (-1.5, 8.0, 0.0)]
DECOY = [(1.5, 1.0, 0.0), (1.5, 8.0, 0.0)]  # never drawn: magenta must not be there
RADIUS = 3
failures = []


def check(ok, what):
    print(("PASS " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def arguments(doc):
    """(the binary, the work folder, made) from --overlayd and --workdir."""
    parser = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    return os.path.abspath(args.overlayd), args.workdir


def verdict(log_path, lines=15):
    """The exit status: 1 with the failed checks and the daemon's last log lines when any failed."""
    if failures:
        print(f"{len(failures)} check(s) failed:\n" + "\n".join(failures))
        print("".join(open(log_path, encoding="utf-8", errors="replace").readlines()[-lines:]))
        return 1
    return 0


def rtsp_config(http_port, rtsp_port, keyframe_interval=1.0):
    return SCENE + daemon_fixture.http_section(http_port, control="off") + f"""
[encoder]
encoder = "openh264"
bitrate_kbps = 3000
keyframe_interval_s = {keyframe_interval}
[[sink]]
kind = "rtsp"
listen = "127.0.0.1:{rtsp_port}"
path = "/cam"
"""


def write(workdir, name, text):
    path = os.path.join(workdir, name)
    with open(path, "w", encoding="utf-8") as file:
        file.write(text)
    return path


def project(overlayd, config, world):
    coordinates = [f"{c:.6f}" for point in world for c in point]
    done = subprocess.run([overlayd, "project", "--config", config, "--json", "--"] + coordinates,
                          capture_output=True, text=True, timeout=30, check=True)
    return [p["pixel"] for p in json.loads(done.stdout) if p["visible"] and p["pixel"]
            and RADIUS <= p["pixel"][0] < WIDTH - RADIUS and RADIUS <= p["pixel"][1] < HEIGHT - RADIUS]


def along(line, count=24):
    (a, b) = line
    return [tuple(a[c] + (b[c] - a[c]) * i / (count - 1) for c in range(3)) for i in range(count)]


def magenta(rgb, x, y):
    """#ff00ff through I420 and H.264 at 3 Mbit/s: generous against colour noise; the grey checkerboard never
    passes."""
    i = (y * WIDTH + x) * 3
    r, g, b = rgb[i], rgb[i + 1], rgb[i + 2]
    return r > 140 and g < 120 and b > 140


def share_near(rgb, pixels):
    hits = 0
    for u, v in pixels:
        u, v = int(round(u)), int(round(v))
        if any(magenta(rgb, x, y) for y in range(v - RADIUS, v + RADIUS + 1) for x in range(u - RADIUS, u + RADIUS + 1)):
            hits += 1
    return hits / max(1, len(pixels))


def probe(url, transport):
    done = subprocess.run(["ffprobe", "-v", "error", "-rtsp_transport", transport, "-select_streams", "v:0",
                           "-show_entries", "stream=codec_name,width,height,r_frame_rate", "-of", "json", url],
                          capture_output=True, text=True, timeout=60)
    streams = json.loads(done.stdout or "{}").get("streams", [])
    return streams[0] if streams else {"error": done.stderr.strip()[-300:]}


def frame_rate(stream, url, transport):
    """The stream's rate: ffprobe's r_frame_rate is its guess from the first packets' timestamps (openh264 writes no
    timing into the SPS), which a loaded machine skews (359/12) or leaves at the timebase (90000/1); then the rate is
    measured from 45 frames' presentation times."""
    try:
        numerator, denominator = (int(x) for x in stream.get("r_frame_rate", "0/1").split("/"))
        guessed = numerator / denominator
    except (ValueError, ZeroDivisionError):
        guessed = 0.0
    if abs(guessed - FPS) <= 0.1 * FPS:
        return guessed
    done = subprocess.run(["ffprobe", "-v", "error", "-rtsp_transport", transport, "-select_streams", "v:0",
                           "-read_intervals", "%+#45", "-show_entries", "frame=pts_time", "-of", "csv=p=0", url],
                          capture_output=True, text=True, timeout=60)
    times = [float(t) for t in done.stdout.split() if t.replace(".", "", 1).isdigit()]
    return (len(times) - 1) / (times[-1] - times[0]) if len(times) > 2 and times[-1] > times[0] else 0.0


def decode(url, transport, frames):
    """(frames decoded, the last frame as rgb24): ffmpeg, independent of our encoder and of GStreamer."""
    done = subprocess.run(["ffmpeg", "-v", "error", "-rtsp_transport", transport, "-i", url, "-frames:v",
                           str(frames), "-f", "rawvideo", "-pix_fmt", "rgb24", "-"], capture_output=True, timeout=90)
    size = WIDTH * HEIGHT * 3
    count = len(done.stdout) // size
    return count, done.stdout[(count - 1) * size:count * size] if count else b""


def metrics(base):
    with daemon_fixture.loopback_opener.open(base + "/metrics", timeout=5) as response:
        return response.read().decode()


def gstreamer_mapped(pid):
    with open(f"/proc/{pid}/maps", encoding="utf-8") as maps:
        return sorted({line.split()[-1] for line in maps if "libgst" in line})


def footprint(overlayd, workdir):
    linked = subprocess.run(["ldd", overlayd], capture_output=True, text=True, timeout=30).stdout
    check("libgst" not in linked, "the binary does not link GStreamer (ldd): " +
          (", ".join(l.split()[0] for l in linked.splitlines() if "libgst" in l) or "none"))
    version = subprocess.Popen([overlayd, "--version"], stdout=subprocess.PIPE)
    version.communicate(timeout=10)
    port = daemon_fixture.free_port()
    plain = write(workdir, "camera-only.toml", SCENE + daemon_fixture.http_section(port, control="off"))
    daemon = daemon_fixture.Daemon(overlayd, plain, workdir, port)
    try:
        daemon.wait_ready()
        mapped = gstreamer_mapped(daemon.process.pid)
        check(not mapped, f"a run without encoded sinks maps no GStreamer library: {mapped or 'none'}")
    finally:
        daemon.stop()


def late_joiner(overlayd, workdir):
    """Keyframes every 30 s: a client that joins a running media still decodes its first frame at once, because its
    PLAY asks the encoder for a keyframe."""
    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    config = write(workdir, "late-joiner.toml", rtsp_config(http_port, rtsp_port, keyframe_interval=30.0))
    url = f"rtsp://127.0.0.1:{rtsp_port}/cam"
    daemon = daemon_fixture.Daemon(overlayd, config, workdir, http_port)
    try:
        daemon.wait_ready()
        first = subprocess.Popen(["ffmpeg", "-v", "error", "-rtsp_transport", "tcp", "-i", url, "-frames:v", "300",
                                  "-f", "null", "-"], stdin=subprocess.DEVNULL)
        time.sleep(4)  # the shared media runs, its first keyframe long gone
        started = time.monotonic()
        count, _ = decode(url, "udp", 1)
        elapsed = time.monotonic() - started
        check(count == 1 and elapsed < 5.0, f"a late joiner decodes its first frame in {elapsed:.1f} s with keyframes "
              "every 30 s (its PLAY asks for one)")
        first.kill()
        first.wait()
    finally:
        daemon.stop()


def module_missing(overlayd, workdir):
    """The binary alone, without the module beside it: run stops at start saying where it looked."""
    folder = os.path.join(workdir, "alone")
    os.makedirs(folder, exist_ok=True)
    alone = os.path.join(folder, "overlayd")
    subprocess.run(["cp", overlayd, alone], check=True)
    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    config = write(workdir, "alone.toml", rtsp_config(http_port, rtsp_port))
    done = subprocess.run([alone, "run", "--config", config], capture_output=True, text=True, timeout=30)
    check(done.returncode != 0 and "overlayd-stream.so is not installed" in done.stderr,
          f"without its module run stops: exit {done.returncode}, {done.stderr.strip().splitlines()[-1:]}")


def main():
    overlayd, workdir = arguments(__doc__)

    footprint(overlayd, workdir)
    module_missing(overlayd, workdir)
    late_joiner(overlayd, workdir)

    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    config = write(workdir, "rtsp.toml", rtsp_config(http_port, rtsp_port))
    checked = subprocess.run([overlayd, "check-config", config], capture_output=True, text=True)
    check(checked.returncode == 0, f"check-config accepts the RTSP config: {checked.stderr.strip()[-200:]}")
    url = f"rtsp://127.0.0.1:{rtsp_port}/cam"
    daemon = daemon_fixture.Daemon(overlayd, config, workdir, http_port)
    try:
        daemon.wait_ready()
        mapped = gstreamer_mapped(daemon.process.pid)
        check(any("libgstreamer-1.0" in m for m in mapped), f"with an RTSP sink GStreamer is mapped ({len(mapped)} "
              "libraries): the footprint check sees it when it is there")

        for transport in ("udp", "tcp"):
            stream = probe(url, transport)
            check(stream.get("codec_name") == "h264" and stream.get("width") == WIDTH and
                  stream.get("height") == HEIGHT and abs(frame_rate(stream, url, transport) - FPS) <= 0.1 * FPS,
                  f"ffprobe over {transport}: {stream}, {frame_rate(stream, url, transport):.2f} fps")

        count, rgb = decode(url, "tcp", 60)
        check(count == 60, f"ffmpeg decodes 60 frames over TCP: {count}")
        if rgb:
            with open(os.path.join(workdir, "last-frame.rgb"), "wb") as file:
                file.write(rgb)
            line = share_near(rgb, project(overlayd, config, along(LINE)))
            decoy = share_near(rgb, project(overlayd, config, along(DECOY)))
            check(line >= 0.9, f"the magenta line is where `overlayd project` puts it: {line:.0%} of 24 points")
            check(decoy <= 0.1, f"and not where no line was drawn: {decoy:.0%}")

        # Ten clients at once on the one encoder.
        results, clients_seen = [None] * 10, []
        before = daemon.state()["encoder"]
        threads = [threading.Thread(target=lambda i=i: results.__setitem__(
            i, decode(url, "udp" if i % 2 else "tcp", 90)[0])) for i in range(10)]
        for thread in threads:
            thread.start()
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and any(t.is_alive() for t in threads):
            clients = sum(len(s["clients"]) for s in daemon.state()["encoder"]["sinks"])
            clients_seen.append(clients)
            if clients == 10:
                text = metrics(daemon.base)
                encoders = re.findall(r"^overlayd_encoders\{[^}]*\} (\S+)$", text, re.M)
                rtsp = re.findall(r"^overlayd_rtsp_clients\{[^}]*\} (\S+)$", text, re.M)
                check([float(e) for e in encoders] == [1] and [float(r) for r in rtsp] == [10],
                      f"/metrics with ten clients: encoders {encoders}, rtsp clients {rtsp}")
                break
            time.sleep(0.2)
        check(max(clients_seen or [0]) == 10, f"/state lists ten clients at once (most seen: {max(clients_seen or [0])})")
        for thread in threads:
            thread.join(120)
        check(all(r == 90 for r in results), f"each of the ten decodes 90 frames: {results}")
        after = daemon.state()
        encoded = after["encoder"]["frames_encoded"] - before["frames_encoded"]
        check(encoded <= after["source"]["frames"] - before["frames_in"] + 5,
              f"one encode: {encoded} frames encoded while ten clients watched (not ten times the source's)")
        latency = after["encoder"]["latency"]
        stages = ["blended", "encoder_in", "encoded", "sent"]
        check(all(latency[s]["frames"] > 0 for s in stages) and latency["sent"]["p99_s"] < 1.0,
              "the latency of every stage (blended from capture, the others from the blend): " +
              ", ".join(f"{s} p50 {latency[s]['p50_s'] * 1000:g} ms p99 {latency[s]['p99_s'] * 1000:g} ms"
                        for s in stages))
        text = metrics(daemon.base)
        counts = dict(re.findall(r'^overlayd_stage_latency_seconds_count\{stage="(\w+)"\} (\d+(?:\.0)?)$', text, re.M))
        check(sorted(counts) == sorted(stages) and all(float(c) > 0 for c in counts.values()),
              f"/metrics has overlayd_stage_latency_seconds for every stage: {counts}")
        check(after["encoder"]["keyframes"] > 0 and after["encoder"]["bitrate_kbps"] > 0,
              f"the encoder reports keyframes {after['encoder']['keyframes']}, "
              f"{after['encoder']['bitrate_kbps']:.0f} kbit/s, element {after['encoder']['element']}")

        # The port is taken now: a second daemon on it stops at start, naming the address.
        second_http = daemon_fixture.free_port()
        taken = write(workdir, "taken.toml", rtsp_config(second_http, rtsp_port))
        done = subprocess.run([overlayd, "run", "--config", taken], capture_output=True, text=True, timeout=30)
        check(done.returncode != 0 and f"127.0.0.1:{rtsp_port}" in done.stderr,
              f"a taken port stops run: exit {done.returncode}, {done.stderr.strip().splitlines()[-1:]}")
    finally:
        status = daemon.stop()
        check(status == 0, f"overlayd stops cleanly on SIGTERM: exit {status}")
    return verdict(daemon.log_path)


if __name__ == "__main__":
    sys.exit(main())
