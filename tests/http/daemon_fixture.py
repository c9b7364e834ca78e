# SPDX-License-Identifier: Apache-2.0
"""A real `overlayd run` with an [http] section, for the HTTP tier's tests: the demo scene (config/examples/demo.toml
without its file sinks), a free loopback port, helpers to wait for it and stop it, and a JPEG decoder for snapshots."""
import json
import os
import re
import signal
import socket
import subprocess
import time
import urllib.error
import urllib.request

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEMO = os.path.join(REPO, "config", "examples", "demo.toml")

# No proxy: an http_proxy in the environment must not swallow requests to 127.0.0.1.
loopback_opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def demo_without_sinks():
    """demo.toml without its [[sink]]s: the scene, camera and source a person sees in the README."""
    return config_without_sinks(DEMO)


def config_without_sinks(path):
    """The config's text without its [[sink]] tables: a test must not write the scene's outputs. A table ends at
    the next header, wherever it is in the file (browser_test.py takes any --config, not only the demo)."""
    kept, in_sink = [], False
    for line in open(path, encoding="utf-8").read().splitlines():
        header = line.strip()
        if header.startswith("["):
            in_sink = header == "[[sink]]"
        if not in_sink:
            kept.append(line)
    return "\n".join(kept) + "\n"


def http_section(port, **options):
    lines = ["", "[http]", f'listen = "127.0.0.1:{port}"']
    for key, value in options.items():
        lines.append(f"{key} = {json.dumps(value)}")
    return "\n".join(lines) + "\n"


class Daemon:
    """overlayd run --config PATH, its log in workdir; stop() sends SIGTERM and returns the exit status.

    log_path names the log when a test documents where it is (the default is new per start, so a restart keeps the
    first run's log); cwd is where the daemon runs, for anything it writes relative to its working directory."""

    def __init__(self, overlayd, config_path, workdir, port, log_path=None, cwd=None):
        self.port = port
        self.base = f"http://127.0.0.1:{port}"
        self.log_path = log_path or os.path.join(workdir, f"overlayd-{port}-{int(time.time() * 1000)}.log")
        self.log = open(self.log_path, "w")
        self.process = subprocess.Popen([overlayd, "run", "--config", config_path], cwd=cwd,
                                        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=self.log)

    def wait_ready(self, timeout=20.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise AssertionError(f"overlayd exited with {self.process.returncode}:\n{self.log_text()}")
            try:
                state = self.state()
                if state["source"]["state"] == "streaming" and state["source"]["frames"] > 0:
                    return state
            except (OSError, urllib.error.URLError, ValueError, KeyError):
                pass
            time.sleep(0.1)
        raise AssertionError(f"overlayd did not serve /state within {timeout} s:\n{self.log_text()}")

    def state(self):
        with loopback_opener.open(self.base + "/state", timeout=5) as response:
            return json.load(response)

    def log_text(self):
        self.log.flush()
        return open(self.log_path, encoding="utf-8", errors="replace").read()

    def log_tail(self, lines=15):
        """The log's last lines: enough to say why the daemon died without burying the failure message."""
        return "".join(self.log_text().splitlines(keepends=True)[-lines:])

    def stop(self, timeout=10.0):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
                raise AssertionError("overlayd did not stop within 10 s of SIGTERM")
        self.log.close()
        return self.process.returncode


def grey_pixels(image, workdir, name):
    """(width, height, pixels): the image (a snapshot's JPEG, a screenshot's PNG) saved as workdir/name for a person
    to look at, then decoded by ffmpeg, independent of our encoder, to 8-bit grey, row-major. The size comes from
    ffprobe so that each test can check the decoded length against it or against the size it expects."""
    path = os.path.join(workdir, name)
    with open(path, "wb") as file:
        file.write(image)
    probe = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-show_entries", "stream=width,height",
                            "-of", "csv=p=0", path], capture_output=True, text=True, timeout=30, check=True)
    width, height = map(int, probe.stdout.strip().split(","))
    decoded = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt", "gray", "-"],
                             capture_output=True, timeout=30, check=True)
    return width, height, decoded.stdout
