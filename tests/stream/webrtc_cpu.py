#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The daemon's CPU with 0, 1 and 8 WebRTC peers (WHEP receivers of whep_test.py's own, in this process) at
1280x720 30 fps, synthetic scene, openh264 at 4 Mbit/s: what each added peer costs (packetization and encryption;
the one encode is shared). A measurement, not a test: it prints the figures.

    webrtc_cpu.py --overlayd build/daemon/overlayd --workdir /tmp/webrtc-cpu [--seconds 10]"""
import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "http"))
sys.path.insert(0, HERE)
from rtsp_test import SCENE  # noqa: E402
from whep_test import Receiver, arguments, peers, request, start  # noqa: E402

# rtsp_test's scene at 720p, openh264 at 4 Mbit/s, WebRTC
CONFIG = SCENE.replace("width = 640", "width = 1280").replace("height = 360", "height = 720") + """
[encoder]
encoder = "openh264"
bitrate_kbps = 4000
[webrtc]
enabled = true
"""


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as file:
        fields = file.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=10)
    args = arguments(parser)
    daemon = start(args.overlayd, args.workdir, "cpu", CONFIG)
    receivers = []
    try:
        daemon.wait_ready()
        results = {}
        for count in (0, 1, 8):
            while len(receivers) < count:
                receiver = Receiver()
                status, _, answer = request("POST", daemon.base + "/whep", receiver.offer())
                assert status == 201, (status, answer)
                receiver.answer(answer)
                receivers.append(receiver)
            for receiver in receivers:
                receiver.frames(10, 10)  # flowing
            time.sleep(1)
            state = daemon.state()
            frames0, cpu0, t0 = state["encoder"]["frames_encoded"], cpu_seconds(daemon.process.pid), time.monotonic()
            time.sleep(args.seconds)
            state = daemon.state()
            frames = state["encoder"]["frames_encoded"] - frames0
            cpu, wall = cpu_seconds(daemon.process.pid) - cpu0, time.monotonic() - t0
            results[count] = cpu / wall
            print(f"{count} peers ({peers(daemon)} in /state): {100 * cpu / wall:.1f} % of a core, "
                  f"{frames / wall:.1f} frames encoded/s, {1000 * cpu / max(1, frames):.2f} ms CPU a frame", flush=True)
        print(f"per added peer: {100 * (results[8] - results[1]) / 7:.1f} % of a core "
              f"(the first: {100 * (results[1] - results[0]):.1f} %)")
    finally:
        for receiver in receivers:
            receiver.stop()
        daemon.stop()


if __name__ == "__main__":
    main()
