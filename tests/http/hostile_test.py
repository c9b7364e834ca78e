#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd's HTTP server against hostile clients on loopback, through the real binary:

    tests/http/hostile_test.py --overlayd build/daemon/overlayd --workdir /tmp/hostile

The demo scene without its sinks, [http] on a free loopback port with the default max_clients (32), control "open".
Phases, each bounded:
  few       20 clients from one address trickle request headers (they fit in max_clients): a /state from that
            address is answered within 1 s, shedding all but 7 of them (max_pending_per_address, counted)
  flood     200 clients from one address trickle request headers a byte at a time (and dial again when closed)
            for 6 s: they fill every slot; /state from another address answers within 1 s throughout, a /stream
            viewer never waits 2 s for a part, and /metrics counts max_clients
  spread    the same 200 from 200 addresses (127.0.1.x): every slot is taken, the slowest incomplete request is
            shed for each newcomer; same checks, max_clients counted
  storm     2,000 short connections (8 threads; half /state, half closed at once or after half a request line,
            some with a reset) complete in under 5 s, every /state answered 200; the daemon's fds come back to the
            count before, its RSS grows by less than 8 MiB
  lies      oversized and lying requests get the right status: a Content-Length over the body limit 413, a
            chunked body over it 413, a URL over 8 KiB 414, headers over the connection's memory 431, a
            Content-Length that is not a number 400
Exit 0: pass, 1: a check failed.
"""
import sys
import threading
import time

import raw_client

PER_ADDRESS = 8          # max_pending_per_address's default
STATE_LATENCY = 1.0     # s: /state while the flood runs
STREAM_GAP = 2.0        # s: the longest a viewer may wait for a part
STORM = 2000
STORM_THREADS = 8
STORM_SECONDS = 5.0
RSS_GROWTH = 8 << 20
FD_RETURN = 2


check = raw_client.check


def watch_state(port, seconds):
    """The slowest /state (and the failures) from 127.0.0.1 over `seconds`, one request every 0.1 s."""
    worst, failures, deadline = 0.0, [], time.monotonic() + seconds
    while time.monotonic() < deadline:
        status, elapsed, _ = raw_client.get(port, "/state", timeout=STATE_LATENCY + 1)
        if elapsed > STATE_LATENCY / 2:
            print(f"slow /state: {elapsed:.3f} s at {time.monotonic():.2f}")
        worst = max(worst, elapsed)
        if status != 200:
            failures.append(status)
        time.sleep(0.1)
    return worst, failures


def shed_count(port, limit):
    return raw_client.metric(port, "overlayd_http_limit_total", f'limit="{limit}"') or 0


def flood(port, sources, label, limit, seconds=5.0):
    """len(sources) tricklers for `seconds`: /state, the stream and the limit that must have shed them."""
    before = shed_count(port, limit)
    with raw_client.StreamWatch(port) as viewer:
        time.sleep(1.0)
        with raw_client.Tricklers(port, sources, prefix=b"GET /state HTTP/1.1\r\nHost: t\r\nX-Slow: ") as tricklers:
            time.sleep(1.0)
            worst, failures = watch_state(port, seconds)
        print(f"{label}: /state worst {worst:.3f} s, failures {failures[:5]} ({len(failures)}), tricklers closed "
              f"{tricklers.closed}, refused {tricklers.refused}; stream parts {viewer.parts}, longest gap "
              f"{viewer.longest_gap:.2f} s")
    check(not failures, f"{label}: /state failed {len(failures)} times under the flood: {failures[:5]}")
    check(worst < STATE_LATENCY, f"{label}: /state took {worst:.2f} s under the flood (limit {STATE_LATENCY} s)")
    check(viewer.longest_gap < STREAM_GAP, f"{label}: the stream stalled {viewer.longest_gap:.2f} s")
    after = shed_count(port, limit)
    check(after > before, f"{label}: /metrics did not count {limit} ({before} -> {after})")


def few(port):
    before = shed_count(port, "max_pending_per_address")
    with raw_client.Tricklers(port, ["127.0.0.5"] * 20, interval=0.5, prefix=b"GET /state HTTP/1.1\r\nX: "):
        time.sleep(2.0)
        status, elapsed, _ = raw_client.get(port, "/state", source="127.0.0.5")
    shed = shed_count(port, "max_pending_per_address") - before
    print(f"few: /state from the tricklers' address {status} in {elapsed:.3f} s; {shed} of theirs shed")
    check(status == 200 and elapsed < STATE_LATENCY, f"few: /state from the tricklers' address: {status}, {elapsed} s")
    check(shed >= 20 - PER_ADDRESS + 1, f"few: {shed} requests shed for max_pending_per_address, not at least "
                                        f"{20 - PER_ADDRESS + 1}")


def storm(port, pid):
    time.sleep(1.0)
    fds_before, rss_before = raw_client.fds(pid), raw_client.rss(pid)
    results, lock = [], threading.Lock()

    def worker(n):
        # Every other connection is a /state that must be answered; the rest connect and close at once, or send
        # half a request line and close (with a reset for half of them): what a port scanner or a flaky client does.
        local = []
        for i in range(n):
            if i % 2 == 0:
                status, elapsed, _ = raw_client.get(port, "/state")
                local.append(status)
            else:
                raw_client.hang_up(port, b"GET /sta" if i % 4 == 1 else b"", reset=i % 8 >= 5)
                local.append(200)
        with lock:
            results.extend(local)

    start = time.monotonic()
    threads = [threading.Thread(target=worker, args=(STORM // STORM_THREADS,)) for _ in range(STORM_THREADS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(60)
    seconds = time.monotonic() - start
    bad = [s for s in results if s != 200]
    deadline = time.monotonic() + 3.0
    while raw_client.fds(pid) > fds_before + FD_RETURN and time.monotonic() < deadline:
        time.sleep(0.1)
    fds_after, rss_after = raw_client.fds(pid), raw_client.rss(pid)
    print(f"storm: {len(results)} connections in {seconds:.2f} s ({len(results) / seconds:.0f}/s), {len(bad)} not "
          f"200; fds {fds_before} -> {fds_after}; RSS {rss_before >> 10} -> {rss_after >> 10} KiB")
    check(len(results) == STORM and not bad, f"storm: {len(bad)} of {len(results)} not answered 200: {bad[:5]}")
    check(seconds < STORM_SECONDS, f"storm: {STORM} connections took {seconds:.2f} s (limit {STORM_SECONDS} s)")
    check(abs(fds_after - fds_before) <= FD_RETURN, f"storm: fds {fds_before} -> {fds_after}")
    check(rss_after - rss_before < RSS_GROWTH, f"storm: RSS grew {(rss_after - rss_before) >> 10} KiB")


def lies(port):
    put = "PUT /api/camera HTTP/1.1\r\nHost: t\r\nConnection: close\r\n"
    cases = [
        ("a Content-Length over the limit", put + "Content-Length: 10000000\r\n\r\n", 413),
        ("a chunked body over the limit",
         put + "Transfer-Encoding: chunked\r\n\r\n" + ("8000\r\n" + "a" * 0x8000 + "\r\n") * 3 + "0\r\n\r\n", 413),
        ("a URL over 8 KiB", "GET /state?x=" + "a" * 9000 + " HTTP/1.1\r\nHost: t\r\nConnection: close\r\n\r\n", 414),
        ("headers over the connection's memory",
         "GET /state HTTP/1.1\r\nHost: t\r\n" + "".join(f"X-{i}: {'b' * 1000}\r\n" for i in range(40)) + "\r\n",
         431),
        ("a Content-Length that is not a number", put + "Content-Length: lots\r\n\r\n", 400),
    ]
    for label, raw, expected in cases:
        status, elapsed, answer = raw_client.exchange(port, raw.encode(), timeout=5.0)
        print(f"lies: {label}: {status} in {elapsed:.2f} s")
        check(status == expected, f"lies: {label}: answered {status}, not {expected}: {answer[:200]!r}")


def run(overlayd, workdir, args):
    phases = args.phases.split(",")
    with raw_client.serving(raw_client.start_daemon(overlayd, workdir, "hostile", control="open")) as daemon:
        port = daemon.port
        daemon.wait_ready()
        if "few" in phases:
            few(port)
        if "flood" in phases:
            flood(port, ["127.0.0.3"] * 200, "flood", "max_clients")
        if "spread" in phases:
            flood(port, [f"127.0.1.{i}" for i in range(1, 201)], "spread", "max_clients")
        if "storm" in phases:
            storm(port, daemon.process.pid)
        if "lies" in phases:
            lies(port)


def add_phases(parser):
    parser.add_argument("--phases", default="few,flood,spread,storm,lies", help="which phases, comma-separated")


def main():
    return raw_client.test_main("hostile_test", __doc__, run, add_arguments=add_phases)


if __name__ == "__main__":
    sys.exit(main())
