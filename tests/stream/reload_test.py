#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""SIGHUP with an RTSP sink, through the real binary and a real client (ffmpeg over TCP):
- a reload that keeps [encoder] and the encoded sinks as they were (another sink added) keeps the engine: the
  client that watched before goes on decoding through the reload, still the server's one client (same address, same
  start); and when the source's size changes too, the kept engine is opened again for it;
- a reload that changes the encoder (bitrate) and the mount (/cam to /cam2) on the same port is accepted: the old
  server closes before the new one binds, and a client of the new mount decodes;
- a reload whose RTSP port another program holds is refused at the file's listen key; one whose port another
  overlayd holds (which the loader lets pass) is refused when its engine cannot bind, and the previous engine
  streams on: a client of the previous mount decodes after it.

    reload_test.py --overlayd build/daemon/overlayd --workdir /tmp/reload-test
Exit 0 when every check passed, 1 when any failed (each check prints PASS or FAIL with its numbers)."""
import os
import re
import signal
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "http"))
import daemon_fixture  # noqa: E402
from rtsp_test import SCENE, arguments, check, decode, probe, verdict, write  # noqa: E402

def config(http_port, rtsp_port, path="/cam", bitrate=2000, extra="", small=False):
    scene = SCENE.replace("width = 640", "width = 320").replace("height = 360", "height = 240") if small else SCENE
    return scene + daemon_fixture.http_section(http_port, control="off") + f"""
[encoder]
encoder = "openh264"
bitrate_kbps = {bitrate}
keyframe_interval_s = 1.0
[[sink]]
kind = "rtsp"
listen = "127.0.0.1:{rtsp_port}"
path = "{path}"
""" + extra


class Watcher:
    """One ffmpeg client decoding over TCP into nothing, its progress read from -progress: the frames it has
    decoded so far, and whether it still runs."""

    def __init__(self, url, workdir, name):
        self.path = os.path.join(workdir, name + ".progress")
        if os.path.exists(self.path):  # ffmpeg appends: a previous run's progress must not count
            os.remove(self.path)
        self.process = subprocess.Popen(["ffmpeg", "-v", "error", "-rtsp_transport", "tcp", "-i", url, "-f", "null",
                                         "-progress", self.path, "-"], stdin=subprocess.DEVNULL,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    def frames(self):
        try:
            text = open(self.path, encoding="utf-8").read()
        except OSError:
            return 0
        found = re.findall(r"^frame=(\d+)$", text, re.M)
        return int(found[-1]) if found else 0

    def wait_frames(self, count, timeout=20.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and self.frames() < count and self.process.poll() is None:
            time.sleep(0.2)
        return self.frames()

    def stop(self):
        if self.process.poll() is None:
            self.process.kill()
        _, err = self.process.communicate(timeout=10)
        return err.decode(errors="replace").strip()[-300:]


def reload(daemon, text, path, marker_count):
    """Writes the config, sends SIGHUP and waits for the daemon to say what it made of it: "reloaded" or
    "reload refused" (the log lines after the previous reloads)."""
    with open(path, "w", encoding="utf-8") as file:
        file.write(text)
    daemon.process.send_signal(signal.SIGHUP)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        lines = [l for l in daemon.log_text().splitlines() if re.search(r"reloaded |reload refused", l)]
        if len(lines) > marker_count:
            return lines[marker_count]
        time.sleep(0.1)
    return "no answer to SIGHUP in 20 s"


def main():
    overlayd, workdir = arguments(__doc__)

    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    path = write(workdir, "reload.toml", config(http_port, rtsp_port))
    url = f"rtsp://127.0.0.1:{rtsp_port}/cam"
    daemon = daemon_fixture.Daemon(overlayd, path, workdir, http_port)
    watcher = None
    try:
        daemon.wait_ready()
        watcher = Watcher(url, workdir, "before")
        before = watcher.wait_frames(30)
        clients_before = daemon.state()["encoder"]["sinks"][0]["clients"]

        # 1. The encoded outputs unchanged, another sink added: the engine runs on, its client with it.
        answer = reload(daemon, config(http_port, rtsp_port, extra='[[sink]]\nkind = "null"\n'), path, 0)
        check(answer.find("reloaded ") >= 0, f"a reload that adds a null sink and keeps the RTSP sink: {answer}")
        after = watcher.wait_frames(before + 60)
        check(watcher.process.poll() is None and after >= before + 60,
              f"the client that watched before goes on through the reload: {before} frames before, {after} after")
        clients_after = daemon.state()["encoder"]["sinks"][0]["clients"]
        check(len(clients_before) == 1 and clients_after == clients_before,
              f"the same RTSP session on the same server: clients {clients_before} before, {clients_after} after")
        why = watcher.stop()
        watcher = None
        if why:
            print("  the first client said: " + why)

        # The same encoded outputs while the source's size changes and a sink goes: the kept engine is opened again
        # for the new size.
        answer = reload(daemon, config(http_port, rtsp_port, small=True), path, 1)
        check(answer.find("reloaded ") >= 0, f"a reload that changes the source's size and keeps the RTSP sink: {answer}")
        stream = probe(url, "tcp")
        check((stream.get("width"), stream.get("height")) == (320, 240), f"ffprobe sees the new size: {stream}")

        # 2. The encoder and the mount changed, the port the same: the old server goes before the new one binds.
        answer = reload(daemon, config(http_port, rtsp_port, path="/cam2", bitrate=1500), path, 2)
        check(answer.find("reloaded ") >= 0, f"a reload that changes bitrate and mount on the same port: {answer}")
        count, _ = decode(f"rtsp://127.0.0.1:{rtsp_port}/cam2", "tcp", 30)
        check(count == 30, f"a client of the new mount decodes 30 frames: {count}")

        # 3. A reload onto a port another program holds: refused at the file's listen key, as check-config would.
        with socket.socket() as holder:
            holder.bind(("127.0.0.1", 0))
            holder.listen(1)
            held = holder.getsockname()[1]
            answer = reload(daemon, config(http_port, held, path="/cam3"), path, 3)
            check(re.search(rf"reload refused.*reload.toml:\d+:\d+: sink\[0\].listen: 127.0.0.1:{held} is in use by ",
                            answer) is not None, f"a reload onto a port another program holds is refused at its key: {answer}")
        # 4. One the file cannot tell is taken (another overlayd holds it: the loader lets a running daemon's port
        # pass, for check-config before its reload): the new engine fails to bind once the running one has closed,
        # the reload is refused, and the previous engine opens again.
        other_http, other_rtsp = daemon_fixture.free_port(), daemon_fixture.free_port()
        other = daemon_fixture.Daemon(overlayd, write(workdir, "other.toml", config(other_http, other_rtsp)),
                                      workdir, other_http)
        try:
            other.wait_ready()
            answer = reload(daemon, config(http_port, other_rtsp, path="/cam3"), path, 4)
            check("reload refused" in answer and f"127.0.0.1:{other_rtsp}" in answer,
                  f"a reload onto a port another overlayd holds is refused when its engine cannot bind: {answer}")
        finally:
            other.stop()
        count, _ = decode(f"rtsp://127.0.0.1:{rtsp_port}/cam2", "tcp", 30)
        check(count == 30, f"the previous config streams on: a client of /cam2 decodes 30 frames: {count}")
    finally:
        if watcher:
            watcher.stop()
        status = daemon.stop()
        check(status == 0, f"overlayd stops cleanly on SIGTERM: exit {status}")
    return verdict(daemon.log_path, 20)


if __name__ == "__main__":
    sys.exit(main())
