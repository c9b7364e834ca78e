#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""check-config refuses what run would of the encoded outputs, through the real binary, with the one located line
("FILE:LINE:COLUMN: KEY: reason") from check-config and from run, both exit 2, in the cases a static refusal row
(tests/data/config/refusals) cannot set up:
- encoder = "x264" where x264enc is not installed (GStreamer given an empty plugin folder: no element at all);
- encoder = "auto" (no [encoder]) where openh264enc is not installed;
- an RTSP port another program listens on (named, with its pid);
- encoded sinks where the module overlayd-stream.so cannot be found (the binary alone in a folder, and
  OVERLAYD_STREAM_MODULE_DIR naming an empty one): run cannot start them, so check-config refuses them;
and accepts an RTSP port that an overlayd holds (the running daemon, whose reload takes it over).

    check_config_test.py --overlayd build/daemon/overlayd --workdir /tmp/check-config-test
Exit 0 when every check passed, 1 when any failed."""
import os
import re
import shutil
import socket
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "http"))
import daemon_fixture  # noqa: E402
from rtsp_test import arguments, check, failures, write  # noqa: E402

SOURCE = """[source]
kind = "synthetic"
format = "NV12"
width = 320
height = 240
"""


def rtsp(port):
    return f'[[sink]]\nkind = "rtsp"\nlisten = "127.0.0.1:{port}"\npath = "/cam"\n'


def refused_alike(overlayd, config, where, env=None):
    """check-config and run: exit 2 both, and run's log holds the very line check-config printed at `where`."""
    checked = subprocess.run([overlayd, "check-config", config], capture_output=True, text=True, timeout=60, env=env)
    line = next((l for l in checked.stdout.splitlines() if re.search(where, l)), "")
    ran = subprocess.run([overlayd, "run", "--config", config, "--frames", "1"], capture_output=True, text=True,
                         timeout=60, env=env)
    return checked.returncode == 2 and ran.returncode == 2 and line != "" and line in ran.stderr, \
        f"check-config exit {checked.returncode}, run exit {ran.returncode}: {line or checked.stdout.strip()}"


def main():
    overlayd, workdir = arguments(__doc__)

    empty = os.path.join(workdir, "no-plugins")
    os.makedirs(empty, exist_ok=True)
    without = dict(os.environ, GST_PLUGIN_SYSTEM_PATH_1_0=empty, GST_PLUGIN_PATH_1_0=empty,
                   GST_REGISTRY_1_0=os.path.join(workdir, "registry.bin"))
    port = daemon_fixture.free_port()
    config = write(workdir, "x264.toml", SOURCE + '[encoder]\nencoder = "x264"\n' + rtsp(port))
    ok, said = refused_alike(overlayd, config, r"x264\.toml:7:11: encoder\.encoder: encoder = \"x264\": the x264enc "
                             r"element is not installed", without)
    check(ok, f"x264 not installed: {said}")
    config = write(workdir, "auto.toml", SOURCE + rtsp(port))
    ok, said = refused_alike(overlayd, config, r"auto\.toml:7:8: sink\[0\]\.kind: no \[encoder\], so encoder = \"auto\": "
                             r"the openh264enc element is not installed", without)
    check(ok, f"openh264 not installed, encoder = \"auto\": {said}")

    alone = os.path.join(workdir, "alone")
    os.makedirs(alone, exist_ok=True)
    lonely = os.path.join(alone, "overlayd")  # no overlayd-stream.so beside it, nor in ../lib/overlayd
    if os.path.exists(lonely):
        os.remove(lonely)
    try:
        os.link(overlayd, lonely)  # /proc/self/exe names the link, so the module is looked for beside it
    except OSError:
        shutil.copy2(overlayd, lonely)
    no_module = dict(os.environ, OVERLAYD_STREAM_MODULE_DIR=empty)
    config = write(workdir, "module.toml", SOURCE + '[encoder]\nencoder = "openh264"\n' + rtsp(port))
    ok, said = refused_alike(lonely, config, r"module\.toml:7:11: encoder\.encoder: the encoded outputs' module "
                             r"overlayd-stream\.so is not installed \(looked in " + re.escape(empty), no_module)
    check(ok, f"the stream module missing: {said}")

    with socket.socket() as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen(1)
        held = holder.getsockname()[1]
        config = write(workdir, "taken.toml", SOURCE + rtsp(held))
        ok, said = refused_alike(overlayd, config, rf"taken\.toml:8:10: sink\[0\]\.listen: 127\.0\.0\.1:{held} is in "
                                 rf"use by \S+ \(pid {os.getpid()}\)")
        check(ok, f"an RTSP port another program listens on: {said}")

    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    running = write(workdir, "running.toml", SOURCE + daemon_fixture.http_section(http_port, control="off") +
                    '[encoder]\nencoder = "openh264"\n' + rtsp(rtsp_port))
    daemon = daemon_fixture.Daemon(overlayd, running, workdir, http_port)
    try:
        daemon.wait_ready()
        checked = subprocess.run([overlayd, "check-config", running], capture_output=True, text=True, timeout=60)
        check(checked.returncode == 0, "check-config before a reload accepts the port the running overlayd holds: "
              f"exit {checked.returncode}, {checked.stdout.strip()}")
    finally:
        daemon.stop()
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
