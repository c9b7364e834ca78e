#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""CPU per frame of overlay + encode against the encode alone, same source, same encoder, same run: `overlayd run`
at 720p30 NV12 (synthetic scene) with an RTSP sink and openh264, with and without a demo-like overlay (a grid, a
thick polyline, a clock text), each for 20 s after 3 s of warm-up, CPU time read from /proc/PID/stat. Two rounds,
interleaved. A figure for docs/streaming.md, not a timed test.

    cpu_per_frame.py build/daemon/overlayd   (run in a scratch folder: it writes its configs and logs there)"""
import os, subprocess, sys, time
# 720p30 NV12 from the synthetic scene into openh264 (4 Mbit/s, a keyframe every 2 s: the defaults); latency_run.py
# measures the same.
CONFIG_720P30 = """
[daemon]
stats_interval = 0
[source]
kind = "synthetic"
format = "NV12"
width = 1280
height = 720
fps = 30.0
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
[encoder]
encoder = "openh264"
"""
# The demo-like overlay the encoded row of scripts/compare-peers.sh draws too.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "peers"))
from encoded import ANNOTATIONS as overlay  # noqa: E402
def run(overlayd, name, extra, port, seconds=20):
    path = f"{name}.toml"
    open(path, "w").write(CONFIG_720P30 + extra + f'[[sink]]\nkind = "rtsp"\nlisten = "127.0.0.1:{port}"\npath = "/c"\n')
    p = subprocess.Popen([overlayd, "run", "--config", path], stderr=open(f"{name}.log", "w"))
    time.sleep(3)
    def cpu():
        f = open(f"/proc/{p.pid}/stat").read().split(")")[1].split()
        return (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")
    c0, t0 = cpu(), time.monotonic()
    time.sleep(seconds)
    c1, t1 = cpu(), time.monotonic()
    p.terminate(); p.wait()
    frames = 30 * (t1 - t0)
    return (c1 - c0) / frames * 1000
if __name__ == "__main__":
    for i in range(2):
        a = run(sys.argv[1], "encode-only", "", 19554 + i)
        b = run(sys.argv[1], "overlay-encode", overlay, 19564 + i)
        print(f"round {i}: encode alone {a:.2f} ms CPU/frame, overlay+encode {b:.2f} ms CPU/frame, +{(b/a-1)*100:.1f}%")
