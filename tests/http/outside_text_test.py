#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Text from outside cannot kill the daemon: watched text and path files holding bytes that are not UTF-8 (invalid
sequences, binary garbage, surrogates, a refused line whose quote would cut a multi-byte character in half), and API
requests carrying such bytes, while `overlayd run` serves. After each, the daemon lives, /state is valid JSON (decoded
by Python's strict UTF-8 decoder, independent of ours), the refused text keeps the previous value and says why, and
every 400/404 body is valid JSON too.

    outside_text_test.py --overlayd build/daemon/overlayd --workdir /tmp/outside-text
Exit 0 when every check passed, 1 when any failed (each check prints PASS or FAIL)."""
import argparse
import json
import os
import random
import subprocess
import sys
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402

CONFIG = """
[source]
kind = "synthetic"
format = "NV12"
width = 320
height = 240
fps = 30.0
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
pitch = 25.0
fov = 60.0
[[annotation]]
type = "text"
text = "{slot:status}"
position = [8.0, 8.0]
[[annotation]]
name = "route"
type = "polyline"
points = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
[[input.text]]
slot = "status"
file = "status.txt"
[[input.path]]
annotation = "route"
file = "route.txt"
"""
# 31 ASCII bytes and then "é" (C3 A9): a refusal that quotes the first 32 bytes of the token cuts "é" in half.
CUT_TOKEN = "x" * 31 + "\u00e9"


def strict_json(raw, what):
    """The body as JSON after a strict UTF-8 decode (json.loads on bytes would let surrogates through)."""
    try:
        return json.loads(raw.decode("utf-8", errors="strict"))
    except (UnicodeDecodeError, ValueError) as failure:
        raise AssertionError(f"{what} is not valid UTF-8 JSON ({failure}): {raw[:200]!r}")


def request(daemon, method, path, body=None):
    """(status, raw body) of a request; an error status is an answer too."""
    req = urllib.request.Request(daemon.base + path, data=body, method=method)
    try:
        with daemon_fixture.loopback_opener.open(req, timeout=5) as response:
            return response.status, response.read()
    except urllib.error.HTTPError as refused:
        return refused.code, refused.read()


def state(daemon):
    if daemon.process.poll() is not None:
        raise AssertionError(f"overlayd died with {daemon.process.returncode}:\n{daemon.log_tail()}")
    try:
        status, raw = request(daemon, "GET", "/state")
    except OSError as failure:
        raise AssertionError(f"GET /state failed ({failure}); overlayd exit status {daemon.process.poll()}:\n"
                             f"{daemon.log_tail()}")
    if status != 200:
        raise AssertionError(f"GET /state answered {status}: {raw[:200]!r}")
    return strict_json(raw, "/state")


def entry(daemon, kind):
    return next(e for e in state(daemon)["inputs"] if e["kind"] == kind)


def wait_for(daemon, kind, accept, what, timeout=5.0):
    deadline = time.monotonic() + timeout
    last = None
    while time.monotonic() < deadline:
        last = entry(daemon, kind)
        if accept(last):
            return last
        time.sleep(0.05)
    raise AssertionError(f"/state never showed {what} within {timeout} s: {last}")


def replace_file(path, data):
    """Written whole and renamed in: the inputs never see a half-written (or truncated, empty) version."""
    with open(path + ".tmp", "wb") as f:
        f.write(data)
    os.replace(path + ".tmp", path)


class Checks:
    """Runs each check; a daemon that died in one is started again (its exit status is a failure), so that each
    check says for itself whether it kills the daemon."""

    def __init__(self, start):
        self.failed, self.deaths = [], []
        self.start = start
        self.daemon = start()

    def run(self, name, body):
        try:
            print(f"PASS {name}: {body()}")
        except (AssertionError, OSError, ValueError, StopIteration) as failure:
            print(f"FAIL {name}: {failure}")
            self.failed.append(name)
            try:
                self.daemon.process.wait(1.0)  # a daemon that is dying: its death is this check's
            except subprocess.TimeoutExpired:
                pass
        if self.daemon.process.poll() is not None:
            self.deaths.append(f"{name}: exit {self.daemon.process.returncode}")
            print(self.daemon.log_tail(20), file=sys.stderr)
            self.daemon.stop()
            self.daemon = self.start()


def run(overlayd, workdir):
    status_file, route_file = os.path.join(workdir, "status.txt"), os.path.join(workdir, "route.txt")
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, "outside.toml")
    with open(config, "w") as f:
        f.write(CONFIG + daemon_fixture.http_section(port, control="open"))

    def start():
        """A daemon over empty inputs (a file left by a check that killed the last one would kill it again)."""
        for stale in (status_file, route_file):
            if os.path.exists(stale):
                os.remove(stale)
        daemon = daemon_fixture.Daemon(overlayd, config, workdir, port)
        daemon.wait_ready()
        return daemon

    checks = Checks(start)
    try:
        def refused_text(name, data):
            def check():
                replace_file(status_file, b"before " + name.encode() + b"\n")
                wait_for(checks.daemon, "text", lambda e: e["value"] == "before " + name and "error" not in e,
                         "the good line first")
                # Renamed in: a truncating write would show an empty line first, rightly.
                replace_file(status_file, data)
                got = wait_for(checks.daemon, "text", lambda e: "UTF-8" in e.get("error", ""), "the refusal")
                slots = state(checks.daemon)["text_slots"]
                if got["value"] != "before " + name or slots.get("status") != "before " + name:
                    raise AssertionError(f"the refused text replaced the previous one: {got}, slots {slots}")
                return f"error {got['error']!r}, value {got['value']!r} kept"
            return check

        # Starts with a stray continuation byte: a first line that happened to be valid would be shown, not refused.
        garbage = b"\x80" + random.Random(20261127).randbytes(4096)
        checks.run("1a text file with invalid UTF-8", refused_text("invalid", b"speed \xff\xfe 50\n"))
        checks.run("1b text file with a surrogate", refused_text("surrogate", b"a \xed\xa0\x80 b\n"))
        checks.run("1c text file with an overlong form", refused_text("overlong", b"a \xc0\xaf b\n"))
        checks.run("1d text file of binary garbage", refused_text("garbage", garbage))

        def path_refusal(name, data, line):
            def check():
                replace_file(route_file, b"0 0 0\n0 1 0\n")
                wait_for(checks.daemon, "path", lambda e: e["points"] == 2 and "error" not in e, "2 points first")
                replace_file(route_file, data)
                got = wait_for(checks.daemon, "path", lambda e: f"route.txt:{line}" in e.get("error", ""),
                               f"an error naming route.txt:{line}")
                if got["points"] != 2:
                    raise AssertionError(f"the refused file changed the points: {got}")
                return f"error {got['error']!r}, points kept"
            return check

        checks.run("2a path refusal quoting a token cut inside a character",
                   path_refusal("cut", ("0 0 0\n1 2 " + CUT_TOKEN + "\n").encode(), 2))
        checks.run("2b path refusal quoting invalid UTF-8", path_refusal("invalid", b"0 0 0\n0 0 0\n1 \xff\xfe 2\n", 3))
        checks.run("2c path file of binary garbage",
                   path_refusal("garbage", b"1 2 3\n" + garbage.replace(b"\n", b" ").replace(b"#", b" "), 2))

        def bodies_are_json():
            answers = [
                ("PUT", "/api/text/status", b'{"text": "\xff\xfe"}'),  # nlohmann quotes the bytes it read
                ("PUT", "/api/text/status", b'{"text": "bell \\u0007"}'),
                ("PUT", "/api/text/status", b'{"text": "\xc3"}'),
                ("PUT", "/api/layers/%FF", b'{"visible": true}'),  # the 404 names the layer
                ("GET", "/no/such/%FF%C3", None),
            ]
            before = state(checks.daemon)["text_slots"].get("status")
            seen = []
            for method, path, body in answers:
                status, raw = request(checks.daemon, method, path, body)
                parsed = strict_json(raw, f"the {status} body of {method} {path!r}")
                if status < 400 or "error" not in parsed:
                    raise AssertionError(f"{method} {path!r} answered {status} {parsed} (want a refusal)")
                seen.append(status)
            slots = state(checks.daemon)["text_slots"]
            if slots.get("status") != before:
                raise AssertionError(f"a refused PUT changed the slot: {slots}")
            return f"statuses {seen}, every body valid JSON, slot unchanged"

        checks.run("3 refusals of requests carrying bad bytes are valid JSON", bodies_are_json)

        def alive():
            state(checks.daemon)
            if checks.daemon.process.poll() is not None:
                raise AssertionError(f"overlayd exited with {checks.daemon.process.returncode}")
            return "overlayd still serves /state"

        checks.run("4 the daemon lives", alive)
        if checks.failed:
            print(checks.daemon.log_tail(20), file=sys.stderr)
    finally:
        code = checks.daemon.stop()
    if checks.deaths:
        print(f"overlayd died {len(checks.deaths)} time(s): {'; '.join(checks.deaths)}", file=sys.stderr)
    if checks.failed:
        raise AssertionError(f"{len(checks.failed)} check(s) failed: {', '.join(checks.failed)}")
    if code != 0:
        raise AssertionError(f"overlayd exited {code}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    workdir = os.path.abspath(args.workdir)
    os.makedirs(workdir, exist_ok=True)
    try:
        run(os.path.abspath(args.overlayd), workdir)
    except AssertionError as failure:
        print(f"outside_text_test: FAILED: {failure}", file=sys.stderr)
        return 1
    print("outside_text_test: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
