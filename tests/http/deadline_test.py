#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd's HTTP request deadlines through the real binary: bytes that trickle in do not extend them.

    tests/http/deadline_test.py --overlayd build/daemon/overlayd --workdir /tmp/deadline

Three clients on a loopback port (the demo scene, control "open"), each sending one byte every 0.5 s so that the
connection is never idle: one never finishes its headers, one sends complete headers announcing a 1000-byte body
and trickles it (a Content-Length that lies for as long as the client likes), one sends a well-formed request a byte
every 0.1 s that completes before the header deadline (it must be answered). The first must be closed within 10 s
(kHeaderDeadlineSec) plus the one-second check, the second within 20 s (kBodyDeadlineSec) of its headers, and
/metrics must count both. Bounded: about 25 s.
"""
import sys
import time

import raw_client

HEADER_DEADLINE = 10.0
BODY_DEADLINE = 20.0
SLACK = 2.5         # the server checks once a second; the client looks every 0.5 s
INTERVAL = 0.5
TICK = 0.1          # the polite client sends a byte this often (its 52 bytes take 5.2 s)


check = raw_client.check


def run(overlayd, workdir, args):
    with raw_client.serving(raw_client.start_daemon(overlayd, workdir, "deadline", control="open")) as daemon:
        port = daemon.port
        daemon.wait_ready()
        headers = raw_client.connect(port, "127.0.0.2")
        headers.sendall(b"GET /state HTTP/1.1\r\nHost: t\r\n")
        body = raw_client.connect(port, "127.0.0.2")
        body.sendall(b"PUT /api/camera HTTP/1.1\r\nHost: t\r\nContent-Length: 1000\r\n\r\n")
        polite = raw_client.connect(port, "127.0.0.4")
        request = iter(b"GET /state HTTP/1.1\r\nHost: t\r\nConnection: close\r\n\r\n")
        start = time.monotonic()
        closed = {}
        answered = b""
        tick = 0
        while time.monotonic() - start < BODY_DEADLINE + SLACK + 1 and len(closed) < 2:
            time.sleep(TICK)
            tick += 1
            for name, client in (("headers", headers), ("body", body)):
                if name in closed or tick % round(INTERVAL / TICK):
                    continue
                if raw_client.closed_by_peer(client):
                    closed[name] = time.monotonic() - start
                    continue
                try:
                    client.send(b"a")
                except OSError:
                    closed[name] = time.monotonic() - start
            byte = next(request, None)
            if byte is not None:
                polite.send(bytes([byte]))
            elif not answered:
                polite.settimeout(2.0)
                answered = polite.recv(65536)
        print(f"closed after (s): {closed}; the polite client got {answered[:15]!r}")
        check(answered.startswith(b"HTTP/1.1 200"), f"a request sent a byte every {INTERVAL} s that completes in "
                                                     f"time was not answered: {answered[:100]!r}")
        check("headers" in closed and HEADER_DEADLINE - 1 <= closed["headers"] <= HEADER_DEADLINE + SLACK,
              f"headers trickled: closed after {closed.get('headers')} s, not within {HEADER_DEADLINE} s")
        check("body" in closed and BODY_DEADLINE - 1 <= closed["body"] <= BODY_DEADLINE + SLACK,
              f"a body trickled: closed after {closed.get('body')} s, not within {BODY_DEADLINE} s")
        for limit in ("header_deadline", "body_deadline"):
            count = raw_client.metric(port, "overlayd_http_limit_total", f'limit="{limit}"')
            check(count is not None and count >= 1, f"/metrics: overlayd_http_limit_total{{limit=\"{limit}\"}} is "
                                                    f"{count}")


def main():
    return raw_client.test_main("deadline_test", __doc__, run)


if __name__ == "__main__":
    sys.exit(main())
