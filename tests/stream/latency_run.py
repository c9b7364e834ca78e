#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The encoded path's latency over a long run: `overlayd run` at 1280x720 30 fps (the synthetic scene with a demo-like
overlay), openh264 at 4 Mbit/s, an RTSP sink with one real client (ffmpeg over TCP, decoding to null) for SECONDS,
then the daemon's own histograms from /metrics: for each stage the frames counted, the share within one frame
interval (33 ms), p50 and p99 (interpolated inside the histogram's bucket, and the bucket's upper bound) and the
mean. A figure for docs/streaming.md, not a timed test.

    latency_run.py build/daemon/overlayd [SECONDS]   (run in a scratch folder: it writes its config and log there)"""
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "http"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts", "peers"))
import daemon_fixture  # noqa: E402
from cpu_per_frame import CONFIG_720P30  # noqa: E402
from encoded import ANNOTATIONS  # noqa: E402


def histograms(text):
    """{stage: [(upper bound, cumulative count), ...]} from overlayd_stage_latency_seconds_bucket samples."""
    stages = {}
    pattern = r'overlayd_stage_latency_seconds_bucket\{stage="([^"]+)",le="([^"]+)"\} ([0-9.e+]+)'
    for stage, bound, count in re.findall(pattern, text):
        stages.setdefault(stage, []).append((float("inf") if bound == "+Inf" else float(bound), float(count)))
    return stages


def quantile(buckets, q):
    """(interpolated, bucket upper bound) of quantile q: linear inside the bucket that holds it, as Prometheus's
    histogram_quantile does."""
    total = buckets[-1][1]
    rank, lower, below = q * total, 0.0, 0.0
    for bound, cumulative in buckets:
        if cumulative >= rank:
            if bound == float("inf"):
                return lower, bound
            inside = cumulative - below
            return lower + (bound - lower) * ((rank - below) / inside if inside else 1.0), bound
        lower, below = bound, cumulative
    return lower, float("inf")


def main():
    overlayd, seconds = sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 60.0
    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    with open("latency.toml", "w", encoding="utf-8") as file:
        file.write(CONFIG_720P30 + ANNOTATIONS + daemon_fixture.http_section(http_port, control="off") +
                   f'[[sink]]\nkind = "rtsp"\nlisten = "127.0.0.1:{rtsp_port}"\npath = "/cam"\n')
    daemon = daemon_fixture.Daemon(overlayd, "latency.toml", ".", http_port, log_path="latency.log")
    try:
        daemon.wait_ready()
        client = subprocess.run(["ffmpeg", "-v", "error", "-rtsp_transport", "tcp", "-i",
                                 f"rtsp://127.0.0.1:{rtsp_port}/cam", "-t", str(seconds), "-f", "null", "-"],
                                stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=seconds + 60)
        with daemon_fixture.loopback_opener.open(daemon.base + "/metrics", timeout=5) as response:
            text = response.read().decode()
        load = open("/proc/loadavg").read().split()[:3]
    finally:
        status = daemon.stop()
    print(f"{seconds:.0f} s, ffmpeg exit {client.returncode}, overlayd exit {status}, load average {' '.join(load)}")
    for stage, buckets in histograms(text).items():
        frames = buckets[-1][1]
        if not frames:
            continue
        within = next(c for b, c in buckets if b == 0.033) / frames
        (p50, p50_bound), (p99, p99_bound) = quantile(buckets, 0.5), quantile(buckets, 0.99)
        total = float(re.search(rf'overlayd_stage_latency_seconds_sum\{{stage="{stage}"\}} ([0-9.e+-]+)', text)[1])
        print(f"{stage:>10}: {frames:.0f} frames, {within * 100:.2f} % within 33 ms, p50 {p50 * 1000:.1f} ms "
              f"(<= {p50_bound * 1000:g}), p99 {p99 * 1000:.1f} ms (<= {p99_bound * 1000:g}), "
              f"mean {total / frames * 1000:.2f} ms")
    print(next((line.strip() for line in open("latency.log", encoding="utf-8") if "stopped after" in line), ""))


if __name__ == "__main__":
    main()
