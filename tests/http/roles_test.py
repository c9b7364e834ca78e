#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd's viewer and control credentials through the real binary:

    tests/http/roles_test.py --overlayd build/daemon/overlayd --workdir /tmp/roles

[http] with a control token (token_file), a viewer token (viewer_token_file) and users (users_file: a viewer and a
controller, by Basic or, through curl, by Digest). Every credential against every kind of request, with raw requests on loopback:
  watching (the page, /state, /metrics, /snapshot, /stream, /api/project, POST /api/unproject): 401 without a
  credential or with a wrong one, 200 with any right one;
  changing (PUT /api/camera, PUT /api/layers/NAME): 401 without or with a wrong one, 403 with a viewer's, 200 with
  a controller's.
Then guessing from one address: the first refusal is logged with the address, the next ones are not, and after 10
within a minute that address gets 429 even with the right credential while another address is served; no secret
is ever in the log. Bounded: about 10 s.
"""
import base64
import os
import subprocess
import sys
import time

import daemon_fixture
import raw_client

CONTROL_TOKEN = "control-token-7f3a9c"
VIEWER_TOKEN = "viewer-token-1b2e44"
USERS = "# the test's users\nalice:viewer:alice-password\nbob:control:bob:password with colon\n"


check = raw_client.check
POSE = '{"position": [0.0, -6.0, 3.0], "yaw": 90.0, "pitch": 25.0, "roll": 0.0}'


def basic(name, password):
    return "Basic " + base64.b64encode(f"{name}:{password}".encode()).decode()


WATCH = [("GET", "/", ""), ("GET", "/state", ""), ("GET", "/metrics", ""), ("GET", "/snapshot", ""),
         ("GET", "/stream", ""), ("GET", "/api/project?points=0,0,0", ""),
         ("POST", "/api/unproject", '{"pixels": [[640, 500]]}')]
CHANGE = [("PUT", "/api/camera", POSE), ("PUT", "/api/layers/grid", '{"visible": true}')]
CREDENTIALS = {  # name: (Authorization, may watch, may change)
    "none": (None, False, False),
    "wrong token": ("Bearer not-the-token", False, False),
    "viewer token": (f"Bearer {VIEWER_TOKEN}", True, False),
    "control token": (f"Bearer {CONTROL_TOKEN}", True, True),
    "viewer user": (basic("alice", "alice-password"), True, False),
    "control user": (basic("bob", "bob:password with colon"), True, True),
    "wrong password": (basic("bob", "alice-password"), False, False),
}


def request(port, method, path, body, authorization, source="127.0.0.1"):
    head = f"{method} {path} HTTP/1.1\r\nHost: t\r\nConnection: close\r\n"
    if authorization:
        head += f"Authorization: {authorization}\r\n"
    if body:
        head += f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n"
    if path == "/stream":  # the status line is enough: do not read the endless stream
        with raw_client.connect(port, source) as s:
            s.sendall((head + "\r\n").encode())
            first = s.recv(64)
        return int(first.split()[1]) if first.startswith(b"HTTP/1.1 ") else None
    status, _, _ = raw_client.exchange(port, (head + "\r\n" + body).encode(), source, timeout=5.0)
    return status


def matrix(port):
    # Each credential from its own address, so that the wrong ones do not reach the guessing limit.
    for n, (name, (authorization, watch, change)) in enumerate(CREDENTIALS.items()):
        source = f"127.0.2.{n + 1}"
        for method, path, body in WATCH:
            status = request(port, method, path, body, authorization, source)
            check(status == (200 if watch else 401), f"{name}: {method} {path} answered {status}")
        for method, path, body in CHANGE:
            status = request(port, method, path, body, authorization, source)
            expected = 200 if change else 403 if watch else 401
            check(status == expected, f"{name}: {method} {path} answered {status}, not {expected}")
        print(f"matrix: {name}: watch {watch}, change {change}: as expected")


def digest(port):
    """curl answering the Digest challenge (MD5) with a users_file user's password, which it never sends."""
    def curl(method, path, user, body=None):
        done = subprocess.run(["curl", "-s", "-o", "/dev/null", "-w", "%{http_code}", "--digest", "-u", user, "-X",
                               method, f"http://127.0.0.1:{port}{path}"] + (["-d", body] if body else []),
                              capture_output=True, text=True, timeout=20)
        return int(done.stdout or 0)
    _, _, answer = raw_client.get(port, "/state", "127.0.4.1", timeout=5.0)
    challenges = [line.split(":", 1)[1].strip() for line in answer.split(b"\r\n\r\n")[0].decode().split("\r\n")
                  if line.lower().startswith("www-authenticate:")]
    check(any("Digest" in str(c) for c in challenges) and any("Basic" in str(c) for c in challenges),
          f"the 401 offers Digest beside Basic and Bearer: {challenges}")
    results = {"viewer /state": curl("GET", "/state", "alice:alice-password"),
               "viewer PUT /api/camera": curl("PUT", "/api/camera", "alice:alice-password", POSE),
               "control PUT /api/camera": curl("PUT", "/api/camera", "bob:bob:password with colon", POSE),
               "wrong password /state": curl("GET", "/state", "alice:bob:password with colon")}
    check(results == {"viewer /state": 200, "viewer PUT /api/camera": 403, "control PUT /api/camera": 200,
                      "wrong password /state": 401}, f"curl --digest: {results}")
    print(f"digest: challenged with {[c.split()[0] for c in challenges]}; curl --digest: {results}")


def guessing(port, daemon):
    guesser, other = "127.0.3.1", "127.0.3.2"
    statuses = [request(port, "PUT", "/api/camera", POSE, f"Bearer guess-{i}", guesser) for i in range(10)]
    check(statuses == [401] * 10, f"10 wrong tokens: {statuses}")
    right = request(port, "PUT", "/api/camera", POSE, f"Bearer {CONTROL_TOKEN}", guesser)
    check(right == 429, f"the right token after 10 wrong ones from the same address: {right}, not 429")
    elsewhere = request(port, "PUT", "/api/camera", POSE, f"Bearer {CONTROL_TOKEN}", other)
    check(elsewhere == 200, f"the right token from another address: {elsewhere}")
    lines = [line for line in daemon.log_text().splitlines() if guesser in line]
    print("guessing: " + " | ".join(lines))
    check(len(lines) == 2, f"the guesser's address in {len(lines)} log lines, not 2 (the first and the limit)")
    log = daemon.log_text()
    for secret in (CONTROL_TOKEN, VIEWER_TOKEN, "guess-", "alice-password", "bob:password"):
        check(secret not in log, f"'{secret}' is in the log")
    limited = raw_client.metric(port, "overlayd_http_limit_total", 'limit="auth_rate_limited"',
                                f"Authorization: Bearer {VIEWER_TOKEN}\r\n")
    check(limited is not None and limited >= 1, f"/metrics auth_rate_limited: {limited}")


def run(overlayd, workdir, args):
    port = daemon_fixture.free_port()
    for name, text in (("control.token", CONTROL_TOKEN + "\n"), ("viewer.token", VIEWER_TOKEN + "\n"),
                       ("users", USERS)):
        with open(os.path.join(workdir, name), "w") as file:
            file.write(text)
    config = os.path.join(workdir, "roles.toml")
    with open(config, "w") as file:
        file.write(daemon_fixture.demo_without_sinks() + daemon_fixture.http_section(
            port, control="token", token_file="control.token", viewer_token_file="viewer.token", users_file="users"))
    with raw_client.serving(daemon_fixture.Daemon(overlayd, config, workdir, port)) as daemon:
        deadline = time.monotonic() + 20
        while request(port, "GET", "/state", "", f"Bearer {VIEWER_TOKEN}") != 200:
            check(daemon.process.poll() is None and time.monotonic() < deadline,
                  f"overlayd did not serve /state:\n{daemon.log_tail()}")
            time.sleep(0.2)
        matrix(port)
        digest(port)
        guessing(port, daemon)


def main():
    return raw_client.test_main("roles_test", __doc__, run)


if __name__ == "__main__":
    sys.exit(main())
