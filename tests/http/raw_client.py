# SPDX-License-Identifier: Apache-2.0
"""Raw-socket clients for the hostile-client tests: a request with any bytes (lies included), a client that trickles,
the daemon's fds and memory from /proc, and a counter of /stream parts. Sources may be any 127.x.y.z address: Linux
routes all of 127/8 to loopback, so one machine can stand for many client addresses."""
import argparse
import contextlib
import os
import re
import select
import shutil
import socket
import struct
import sys
import threading
import time

import daemon_fixture


def connect(port, source="127.0.0.1", timeout=3.0):
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    s.settimeout(timeout)
    s.bind((source, 0))
    s.connect(("127.0.0.1", port))
    return s


def exchange(port, raw, source="127.0.0.1", timeout=3.0):
    """(status or None, seconds, answer bytes): raw sent at once, the answer read until the server closes."""
    start = time.monotonic()
    answer = b""
    try:
        with connect(port, source, timeout) as s:
            s.sendall(raw)
            while True:
                chunk = s.recv(65536)
                if not chunk:
                    break
                answer += chunk
    except OSError:
        pass
    match = re.match(rb"HTTP/1\.[01] (\d{3})", answer)
    return (int(match.group(1)) if match else None), time.monotonic() - start, answer


def get(port, path, source="127.0.0.1", timeout=3.0, headers=""):
    return exchange(port, f"GET {path} HTTP/1.1\r\nHost: t\r\nConnection: close\r\n{headers}\r\n".encode(), source,
                    timeout)


def hang_up(port, sent=b"", reset=False):
    """Connect, send `sent`, close at once (with a reset when `reset`: SO_LINGER 0)."""
    try:
        s = connect(port)
        if sent:
            s.sendall(sent)
        if reset:
            s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        s.close()
    except OSError:
        pass


def closed_by_peer(s):
    """Whether the server has ended the request (closed, reset or answered it), without waiting."""
    readable, _, _ = select.select([s], [], [], 0)
    return bool(readable)


class Background:
    """A client running in a thread for the time of a `with` block (its run() looks at stop_event)."""

    def __init__(self):
        self.stop_event = threading.Event()
        self.thread = threading.Thread(target=self.run, daemon=True)

    def run(self):
        raise NotImplementedError

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.stop_event.set()
        self.thread.join(10)


class Tricklers(Background):
    """count clients that send one byte of a request every `interval` seconds and never finish it; a client the
    server closes dials again at once (an attacker keeps the pressure). prefix: what each sends first in one go."""

    def __init__(self, port, sources, interval=0.2, prefix=b""):
        self.port, self.sources, self.interval, self.prefix = port, sources, interval, prefix
        self.closed = 0       # connections the server closed
        self.refused = 0      # connects that failed
        super().__init__()

    def dial(self, source):
        try:
            s = connect(self.port, source, timeout=1.0)
            s.sendall(self.prefix)
            s.setblocking(False)
            return s
        except OSError:
            self.refused += 1
            return None

    def run(self):
        clients = [self.dial(source) for source in self.sources]
        while not self.stop_event.wait(self.interval):
            for i, s in enumerate(clients):
                alive = s is not None and not closed_by_peer(s)
                if alive:
                    try:
                        s.send(b"a")
                    except OSError:
                        alive = False
                if not alive:
                    if s is not None:
                        self.closed += 1
                        s.close()
                    clients[i] = self.dial(self.sources[i])
        for s in clients:
            if s is not None:
                s.close()


class StreamWatch(Background):
    """A /stream viewer that counts parts and remembers the longest gap between two; over TLS with `context`."""

    def __init__(self, port, context=None):
        self.port, self.context = port, context
        self.parts, self.longest_gap = 0, 0.0
        super().__init__()

    def run(self):
        raw = connect(self.port, timeout=5.0)
        with self.context.wrap_socket(raw, server_hostname="127.0.0.1") if self.context else raw as s:
            s.sendall(b"GET /stream HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            last, tail = time.monotonic(), b""
            while not self.stop_event.is_set():
                chunk = s.recv(65536)
                if not chunk:
                    break
                marker = b"Content-Type: image/jpeg"
                seen = (tail + chunk).count(marker) - tail.count(marker)
                tail = (tail + chunk)[-32:]
                if seen:
                    now = time.monotonic()
                    self.longest_gap = max(self.longest_gap, now - last)
                    self.parts, last = self.parts + seen, now


def fds(pid):
    return len(os.listdir(f"/proc/{pid}/fd"))


def rss(pid):
    for line in open(f"/proc/{pid}/status"):
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) * 1024
    return 0


def metric(port, name, labels="", headers=""):
    status, _, answer = get(port, "/metrics", headers=headers)
    pattern = re.escape(name) + (r"\{" + re.escape(labels) + r"\}" if labels else "") + r" (\S+)"
    match = re.search(pattern.encode(), answer)
    return float(match.group(1)) if match else None


def start_daemon(overlayd, workdir, name, **http):
    """overlayd run on the demo scene without its sinks, [http] on a free loopback port with `http`'s keys."""
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, name + ".toml")
    with open(config, "w") as file:
        file.write(daemon_fixture.demo_without_sinks() + daemon_fixture.http_section(port, **http))
    return daemon_fixture.Daemon(overlayd, config, workdir, port)


def check(condition, message):
    check.count += 1
    if not condition:
        raise AssertionError(message)


check.count = 0


@contextlib.contextmanager
def serving(daemon):
    """The daemon for a block of checks: its log's tail printed when one fails; stopped after, exit status 0."""
    try:
        yield daemon
    except AssertionError:
        print(daemon.log_tail(), file=sys.stderr)
        raise
    finally:
        status = daemon.stop()
    check(status == 0, f"overlayd exited {status}")


def test_main(name, doc, run, tools=(), add_arguments=None):
    """--overlayd and --workdir (and the test's own options), then run(overlayd, workdir, args): exit 0 or 1."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    if add_arguments:
        add_arguments(parser)
    args = parser.parse_args()
    for tool in tools:
        if not shutil.which(tool):
            print(f"{name}: {tool} is missing (scripts/install-deps.sh installs it)", file=sys.stderr)
            return 1
    os.makedirs(args.workdir, exist_ok=True)
    try:
        run(os.path.abspath(args.overlayd), args.workdir, args)
    except AssertionError as failure:
        print(f"{name}: FAILED after {check.count} checks: {failure}", file=sys.stderr)
        return 1
    print(f"{name}: {check.count} checks passed")
    return 0
