#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd over a long run: reloads good and bad, a sink reader that leaves and comes back, RSS, fds and threads flat.

    tests/soak/soak_test.py --overlayd build/daemon/overlayd --workdir /tmp/soak [--seconds 180]

CI runs it for 180 s (CTest `soak`, in the g++ tier and again under ASan + UBSan); the hour the issue asks for is
`--seconds 3600` (or OVERLAYD_SOAK_SECONDS=3600 through CTest). The daemon runs the README's demo scene (a timestamp
and a frame counter change every frame) over a synthetic 640x360 checkerboard at 30 fps (a pattern
that does not depend on the camera, so that a reload rebuilds the scene, not the source), with:

  reloads   a SIGHUP every RELOAD_PERIOD seconds, cycling through two good configs (the camera moved between them)
            and bad ones (a TOML syntax error, an out-of-range value, a source that cannot be opened together with a
            new camera and a new sink): after each, the log must say "reloaded" or "reload refused" within 10 s and
            /state's camera must be the new good one, or the one before a refused reload
  sink      a Y4M sink on a FIFO whose reader reads for READER_ON seconds, closes, stays away READER_OFF seconds and
            comes back: every visit must start with a Y4M header and receive frames
  /proc     VmRSS, open fds and threads sampled every second

Checks, after a warm-up of WARM_UP seconds: the least-squares slope of VmRSS under RSS_SLOPE MiB/min (a leaked
640x360 frame per reload is ~4 MiB/min, 1 KiB per frame ~1.8 MiB/min), fds and threads back within FD_SLACK /
THREAD_SLACK of their warm-up values at the end, the frame rate of every 10 s window at least FPS_KEPT of the
first window's (relative: under the sanitizers the absolute rate is the build's, not the daemon's), and exit status 0
after SIGTERM (under ASan a leak report makes it non-zero). The slopes are printed either way.
Exit 0: pass; 1: a check failed (each failure listed); 2: set-up failed.
"""
import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import threading
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "tests", "http"))
from daemon_fixture import DEMO, free_port, loopback_opener  # noqa: E402  (the HTTP tier's helpers)

RELOAD_PERIOD = 4.0    # seconds between SIGHUPs
READER_ON = 9.0        # seconds the FIFO's reader reads on each visit
READER_OFF = 4.0       # seconds it stays away
WARM_UP = 60.0         # seconds before the flatness baselines are taken (allocator caches and pools fill first)
RSS_SLOPE = 2.0        # MiB per minute of VmRSS growth allowed after the warm-up
FD_SLACK = 3           # fds over the warm-up value allowed at the end (a reload or a reader visit in flight)
THREAD_SLACK = 1
FPS_KEPT = 0.85        # each 10 s window's frame rate relative to the first one
FPS_WINDOW = 10.0

def demo_scene():
    """demo.toml from its first [camera] on: the scene the README shows, without its source, daemon and sinks."""
    text = open(DEMO, encoding="utf-8").read()
    scene, keep = [], False
    for line in text.splitlines():
        header = line.strip()
        if header.startswith("["):
            keep = header not in ("[[sink]]", "[daemon]", "[source]", "[source.synthetic]")
        if keep:
            scene.append(line)
    return "\n".join(scene) + "\n"


def config_text(port, fifo, camera_y, source=None, extra_sink=None):
    source = source or ('[source]\nkind = "synthetic"\nformat = "YUYV"\nwidth = 640\nheight = 360\nfps = 30.0\n'
                        '[source.synthetic]\npattern = "checkerboard"\n')
    scene = demo_scene().replace("position = [1.5, -6.0, 3.0]", f"position = [1.5, {camera_y}, 3.0]", 1)
    sinks = f'[[sink]]\nkind = "y4m"\npath = "{fifo}"\n'
    if extra_sink:
        sinks += f'[[sink]]\nkind = "y4m"\npath = "{extra_sink}"\n'
    return (f'[daemon]\nlog_level = "info"\nstats_interval = 5.0\n\n{source}\n{scene}\n{sinks}\n'
            f'[http]\nlisten = "127.0.0.1:{port}"\ncontrol = "off"\n')


class Variants:
    """The configs the reloads cycle through: (name, text, camera y it leaves /state with or None if refused)."""

    def __init__(self, port, fifo, workdir):
        good_a = config_text(port, fifo, -6.0)
        good_b = config_text(port, fifo, -5.0)
        v4l2 = ('[source]\nkind = "v4l2"\nwidth = 640\nheight = 360\nfps = 30.0\n'
                '[source.v4l2]\ndevice = "/dev/video-soak-absent"\n')
        self.initial = good_a
        self.cycle = [
            ("good, camera moved", good_b, -5.0),
            ("bad: a TOML syntax error", good_a.replace("[camera]", "[camera", 1), None),
            ("good, camera back", good_a, -6.0),
            ("bad: fov out of range", good_b.replace("fov = 60.0", "fov = 400.0", 1), None),
            ("good, camera moved", good_b, -5.0),
            ("bad: a source that cannot be opened, a new camera and a new sink at once",
             config_text(port, fifo, -9.0, source=v4l2, extra_sink=os.path.join(workdir, "never.y4m")), None),
            ("good, camera back", good_a, -6.0),
        ]


def proc_sample(pid):
    with open(f"/proc/{pid}/status") as status:
        fields = dict(line.split(":", 1) for line in status if ":" in line)
    rss = int(fields["VmRSS"].split()[0]) * 1024
    threads = int(fields["Threads"])
    fds = len(os.listdir(f"/proc/{pid}/fd"))
    return rss, fds, threads


def slope_per_minute(samples):
    """Least-squares slope of (t, value) samples, in value per minute."""
    ts = [t for t, _ in samples]
    vs = [v for _, v in samples]
    mt, mv = statistics.fmean(ts), statistics.fmean(vs)
    denominator = sum((t - mt) ** 2 for t in ts)
    return 60.0 * sum((t - mt) * (v - mv) for t, v in zip(ts, vs)) / denominator if denominator else 0.0


class FifoReader(threading.Thread):
    """Reads the sink's FIFO for READER_ON s, leaves for READER_OFF s, comes back; records each visit."""

    def __init__(self, path, stop):
        super().__init__(daemon=True)
        self.path, self.stop = path, stop
        self.visits = []   # (header_ok, bytes)

    def run(self):
        while not self.stop.is_set():
            fd = os.open(self.path, os.O_RDONLY | os.O_NONBLOCK)
            received, head, until = 0, b"", time.monotonic() + READER_ON
            try:
                while time.monotonic() < until and not self.stop.is_set():
                    try:
                        chunk = os.read(fd, 1 << 20)
                    except BlockingIOError:
                        chunk = None
                    if not chunk:
                        time.sleep(0.01)
                        continue
                    if len(head) < 9:
                        head += chunk[:9 - len(head)]
                    received += len(chunk)
            finally:
                os.close(fd)
            self.visits.append((head.startswith(b"YUV4MPEG2") if head else None, received))
            self.stop.wait(READER_OFF)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    parser.add_argument("--seconds", type=float, default=float(os.environ.get("OVERLAYD_SOAK_SECONDS", "180")))
    args = parser.parse_args()
    if args.seconds < 2 * WARM_UP:
        print(f"--seconds must be at least {2 * WARM_UP:.0f}", file=sys.stderr)
        return 2
    shutil.rmtree(args.workdir, ignore_errors=True)
    os.makedirs(args.workdir)
    port, fifo = free_port(), os.path.join(args.workdir, "soak.y4m")
    os.mkfifo(fifo)
    variants = Variants(port, fifo, args.workdir)
    config = os.path.join(args.workdir, "soak.toml")

    def write_config(text):
        with open(config + ".new", "w", encoding="utf-8") as file:
            file.write(text)
        os.replace(config + ".new", config)

    write_config(variants.initial)
    log_path = os.path.join(args.workdir, "overlayd.log")
    log = open(log_path, "w")
    env = dict(os.environ)
    # Under ASan a freed block waits in a 256 MiB quarantine by default (16 MiB still showed as ~2 MiB/min for minutes): RSS would climb for minutes and look like a
    # leak. A small one keeps the check meaningful; the option is ignored by a build without ASan.
    env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS", ""), "quarantine_size_mb=4"]))
    daemon = subprocess.Popen([args.overlayd, "run", "--config", config], stdin=subprocess.DEVNULL,
                              stdout=subprocess.DEVNULL, stderr=log, env=env)
    failures = []

    def log_text():
        log.flush()
        return open(log_path, encoding="utf-8", errors="replace").read()

    def state():
        with loopback_opener.open(f"http://127.0.0.1:{port}/state", timeout=5) as response:
            return json.load(response)

    deadline = time.monotonic() + 30
    while True:
        try:
            if state()["source"]["frames"] > 0:
                break
        except (OSError, ValueError, KeyError):
            pass
        if daemon.poll() is not None or time.monotonic() > deadline:
            print(f"set-up: overlayd did not stream (exit {daemon.poll()}):\n{log_text()[-3000:]}", file=sys.stderr)
            daemon.kill()
            return 2
        time.sleep(0.2)

    stop = threading.Event()
    reader = FifoReader(fifo, stop)
    reader.start()
    start = time.monotonic()
    samples, frames = [], []    # (t, (rss, fds, threads)), (t, frames)
    reloads, expected_y, next_reload, index = 0, -6.0, start + RELOAD_PERIOD, 0
    while time.monotonic() - start < args.seconds:
        now = time.monotonic()
        if daemon.poll() is not None:
            failures.append(f"overlayd exited with {daemon.returncode} after {now - start:.0f} s")
            break
        samples.append((now - start, proc_sample(daemon.pid)))
        frames.append((now - start, state()["source"]["frames"]))
        if now >= next_reload:
            name, text, camera_y = variants.cycle[index % len(variants.cycle)]
            index += 1
            before = log_text().count("reloaded ") + log_text().count("reload refused")
            write_config(text)
            daemon.send_signal(signal.SIGHUP)
            answered = time.monotonic() + 10
            while log_text().count("reloaded ") + log_text().count("reload refused") == before:
                if time.monotonic() > answered:
                    failures.append(f"reload {index} ({name}): no 'reloaded' or 'reload refused' in the log in 10 s")
                    break
                time.sleep(0.05)
            refused = log_text().count("reload refused")
            expected_y = camera_y if camera_y is not None else expected_y
            seen_y = state()["camera"]["position"][1]
            if abs(seen_y - expected_y) > 1e-9:
                failures.append(f"reload {index} ({name}): /state camera y {seen_y}, expected {expected_y}")
            if (camera_y is None) != (refused > reloads):
                failures.append(f"reload {index} ({name}): {'not ' if camera_y is None else ''}refused")
            reloads = refused
            next_reload = time.monotonic() + RELOAD_PERIOD
        time.sleep(max(0.0, 1.0 - (time.monotonic() - now)))
    stop.set()
    reader.join(READER_ON + READER_OFF + 5)
    status = None
    if daemon.poll() is None:
        daemon.send_signal(signal.SIGTERM)
        try:
            status = daemon.wait(30)
        except subprocess.TimeoutExpired:
            daemon.kill()
            failures.append("overlayd did not stop within 30 s of SIGTERM")
    else:
        status = daemon.returncode
    if status != 0:
        failures.append(f"exit status {status} after SIGTERM (a sanitizer report is in {log_path})")

    steady = [(t, s) for t, s in samples if t >= WARM_UP]
    rss_slope = slope_per_minute([(t, s[0] / (1 << 20)) for t, s in steady])
    fd_slope = slope_per_minute([(t, s[1]) for t, s in steady])
    thread_slope = slope_per_minute([(t, s[2]) for t, s in steady])
    warm = steady[0][1]
    last = steady[-1][1]
    windows = []
    for t0 in range(0, int(frames[-1][0] - FPS_WINDOW) + 1, int(FPS_WINDOW)):
        inside = [(t, f) for t, f in frames if t0 <= t <= t0 + FPS_WINDOW]
        if len(inside) >= 2 and inside[-1][0] > inside[0][0]:
            windows.append((inside[-1][1] - inside[0][1]) / (inside[-1][0] - inside[0][0]))
    print(f"soak: {frames[-1][0]:.0f} s, {index} reloads ({reloads} refused), {len(reader.visits)} reader visits")
    print(f"soak: VmRSS {warm[0] / (1 << 20):.1f} MiB after warm-up -> {last[0] / (1 << 20):.1f} MiB, "
          f"slope {rss_slope:+.3f} MiB/min; fds {warm[1]} -> {last[1]} ({fd_slope:+.3f}/min); "
          f"threads {warm[2]} -> {last[2]} ({thread_slope:+.3f}/min)")
    print(f"soak: frame rate per {FPS_WINDOW:.0f} s window: first {windows[0]:.2f}, min {min(windows):.2f}, "
          f"median {statistics.median(windows):.2f}")

    if rss_slope > RSS_SLOPE:
        failures.append(f"VmRSS grows {rss_slope:.2f} MiB/min after the warm-up (limit {RSS_SLOPE})")
    if last[1] > warm[1] + FD_SLACK:
        failures.append(f"open fds {warm[1]} after the warm-up, {last[1]} at the end")
    if last[2] > warm[2] + THREAD_SLACK:
        failures.append(f"threads {warm[2]} after the warm-up, {last[2]} at the end")
    if min(windows) < FPS_KEPT * windows[0]:
        failures.append(f"the frame rate fell to {min(windows):.2f} fps from {windows[0]:.2f}")
    if len(reader.visits) < 2:
        failures.append(f"the FIFO reader came back {len(reader.visits)} times (at least 2 visits expected)")
    for number, (header_ok, received) in enumerate(reader.visits, 1):
        if not header_ok or received == 0:
            failures.append(f"reader visit {number}: {received} bytes, Y4M header {'seen' if header_ok else 'missing'}")
    for failure in failures:
        print(f"FAIL: {failure}")
    if failures:
        print(f"log: {log_path}\n{log_text()[-2000:]}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
