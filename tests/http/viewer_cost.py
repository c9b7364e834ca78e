#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""What watching costs: the daemon's CPU seconds per second at 1280x720 YUYV 30 fps (the demo scene, overlay on)
with 0, 1 and 10 /stream viewers, measured from /proc/PID/stat over the same interval for each. A measurement for
docs/speed.md, not a pass/fail test (these machines are noisy; compare the rows of one run, not runs).

    viewer_cost.py --overlayd build/daemon/overlayd --workdir /tmp/viewer-cost [--seconds 20]"""
import argparse
import os
import socket
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402


def cpu_seconds(pid):
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def viewer(port, stop, received):
    with socket.create_connection(("127.0.0.1", port)) as s:
        s.sendall(b"GET /stream HTTP/1.1\r\nHost: x\r\n\r\n")
        s.settimeout(2)
        while not stop.is_set():
            try:
                chunk = s.recv(1 << 16)
            except socket.timeout:
                continue
            if not chunk:
                break
            received[0] += chunk.count(b"\xff\xd8\xff")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    parser.add_argument("--seconds", type=float, default=20.0)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    port = daemon_fixture.free_port()
    config = os.path.join(args.workdir, "viewers.toml")
    open(config, "w").write(daemon_fixture.demo_without_sinks() +
                            daemon_fixture.http_section(port, control="off", stream_fps=30.0))
    daemon = daemon_fixture.Daemon(os.path.abspath(args.overlayd), config, args.workdir, port)
    try:
        daemon.wait_ready()
        print(f"{'viewers':>8} {'cpu-s/s':>8} {'source fps':>10} {'fps per viewer':>15}")
        for count in (0, 1, 10):
            stop = threading.Event()
            counters = [[0] for _ in range(count)]
            threads = [threading.Thread(target=viewer, args=(port, stop, c)) for c in counters]
            for t in threads:
                t.start()
            time.sleep(2.0)  # the encoder starts with the first viewer
            frames0, cpu0, t0 = daemon.state()["source"]["frames"], cpu_seconds(daemon.process.pid), time.monotonic()
            parts0 = [c[0] for c in counters]
            time.sleep(args.seconds)
            frames1, cpu1, t1 = daemon.state()["source"]["frames"], cpu_seconds(daemon.process.pid), time.monotonic()
            parts = [c[0] - p for c, p in zip(counters, parts0)]
            stop.set()
            for t in threads:
                t.join()
            elapsed = t1 - t0
            per_viewer = sum(parts) / len(parts) / elapsed if parts else 0.0
            print(f"{count:>8} {(cpu1 - cpu0) / elapsed:>8.3f} {(frames1 - frames0) / elapsed:>10.1f} "
                  f"{per_viewer:>15.1f}")
    finally:
        daemon.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
