#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The delay from capture to the browser's decoded frame over WebRTC: `overlayd run` at 1280x720 30 fps (the synthetic
scene with a demo-like overlay), openh264 at 4 Mbit/s, [webrtc] on, and Debian's headless Chromium (DevTools,
tests/http/devtools.py) playing the stream in a <video> on loopback for SECONDS. Two halves, each per frame:
- the daemon's, from its own histograms (/metrics): `blended` (capture to the overlay blended) and `webrtc_sent`
  (from the blend to the access unit handed to the peers' feeds: encode included);
- the browser's, from requestVideoFrameCallback's metadata: `receiveTime` (the frame's last packet arrived) to
  `presentationTime` (the decoded frame handed to the compositor): jitter buffer, decode and the hand-over; and
  `processingDuration` (decode) alone. getStats()' jitter-buffer delay and decode time per frame are printed beside.
Between the two halves, unmeasured: the peer's feed queue, RTP packetization, DTLS-SRTP and loopback. p99 of the whole
is at most the sum of the halves' p99s plus that. A figure for docs/streaming.md, not a timed test.

    webrtc_latency_run.py build/daemon/overlayd [SECONDS] [--chromium /usr/bin/chromium]   (run in a scratch folder)"""
import argparse
import os
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "http"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts", "peers"))
sys.path.insert(0, HERE)
import daemon_fixture  # noqa: E402
from cpu_per_frame import CONFIG_720P30  # noqa: E402
from devtools import Chromium, Page  # noqa: E402
from encoded import ANNOTATIONS  # noqa: E402
from latency_run import histograms, quantile  # noqa: E402
from whep_browser_test import CONNECT, STATS, close_all  # noqa: E402

# The receiver's track into a <video>; each presented frame's metadata kept (ms, the page's clock).
PLAY = """(() => {
  const video = document.createElement('video');
  video.muted = true;
  document.body.appendChild(video);
  video.srcObject = new MediaStream([pc.getReceivers()[0].track]);
  window.presented = [];
  const each = (now, m) => {
    if (m.receiveTime !== undefined)
      window.presented.push([m.presentationTime - m.receiveTime, m.processingDuration * 1000, m.width, m.height]);
    video.requestVideoFrameCallback(each);
  };
  video.requestVideoFrameCallback(each);
  return video.play().then(() => 'playing', error => String(error));
})()"""


def percentile(values, q):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))] if ordered else float("nan")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("overlayd")
    parser.add_argument("seconds", nargs="?", type=float, default=30.0)
    parser.add_argument("--chromium", default="/usr/bin/chromium")
    args = parser.parse_args()
    port = daemon_fixture.free_port()
    with open("webrtc-latency.toml", "w", encoding="utf-8") as file:
        file.write(CONFIG_720P30 + ANNOTATIONS + "[webrtc]\nenabled = true\n" +
                   daemon_fixture.http_section(port, control="off"))
    shutil.rmtree("chrome", ignore_errors=True)
    daemon = daemon_fixture.Daemon(args.overlayd, "webrtc-latency.toml", ".", port, log_path="webrtc-latency.log")
    browser = page = None
    try:
        daemon.wait_ready()
        browser = Chromium(args.chromium, os.path.abspath("chrome"), os.path.abspath("chromium.log"))
        page = Page(browser.browser_url(20), timeout=15)
        page.call("Page.navigate", url=daemon.base + "/state")
        page.wait_for("document.readyState === 'complete'", 10, "the page")
        answered = page.evaluate(CONNECT)
        if answered.get("status") != 201:
            sys.exit(f"POST /whep: {answered}")
        played = page.evaluate(PLAY)
        page.wait_for("window.presented.length >= 30", 20, "30 presented frames")
        time.sleep(2)  # past the first keyframe's start-up
        page.evaluate("window.presented.length = 0")
        before = page.evaluate(STATS)
        with daemon_fixture.loopback_opener.open(daemon.base + "/metrics", timeout=5) as response:
            metrics_before = histograms(response.read().decode())
        time.sleep(args.seconds)
        presented = page.evaluate("window.presented")
        after = page.evaluate(STATS)
        with daemon_fixture.loopback_opener.open(daemon.base + "/metrics", timeout=5) as response:
            metrics_after = histograms(response.read().decode())
        load = open("/proc/loadavg").read().split()[:3]
    finally:
        status = close_all(page, browser, daemon)
    print(f"{args.seconds:.0f} s, video {played}, overlayd exit {status}, load average {' '.join(load)}")
    p99s = {}
    for stage in ("blended", "webrtc_sent"):
        # The window's own counts: the histograms after, less before.
        old = dict(metrics_before.get(stage, []))
        buckets = [(bound, count - old.get(bound, 0.0)) for bound, count in metrics_after.get(stage, [])]
        frames = buckets[-1][1] if buckets else 0
        if not frames:
            print(f"{stage:>12}: no frames")
            continue
        (p50, _), (p99, bound) = quantile(buckets, 0.5), quantile(buckets, 0.99)
        p99s[stage] = p99 * 1000
        print(f"{stage:>12}: {frames:.0f} frames, p50 {p50 * 1000:.1f} ms, p99 {p99 * 1000:.1f} ms (<= {bound * 1000:g})")
    shown = [p for p in presented if (p[2], p[3]) == (1280, 720)]
    delays, decodes = [p[0] for p in shown], [p[1] for p in shown]
    p99s["browser"] = percentile(delays, 0.99)
    print(f"{'browser':>12}: {len(shown)} frames presented ({len(shown) / args.seconds:.1f} a second) at 1280x720, "
          f"receive to presentation p50 {percentile(delays, 0.5):.1f} ms, p99 {p99s['browser']:.1f} ms; "
          f"decode p50 {percentile(decodes, 0.5):.1f} ms, p99 {percentile(decodes, 0.99):.1f} ms")
    emitted = after["emitted"] - before["emitted"]
    if emitted:
        print(f"{'getStats':>12}: jitter buffer {1000 * (after['jitterBufferDelay'] - before['jitterBufferDelay']) / emitted:.1f}"
              f" ms a frame, decode {1000 * (after['decodeTime'] - before['decodeTime']) / max(1, after['frames'] - before['frames']):.2f}"
              " ms a frame")
    print(f"capture to presented, p99 at most {sum(p99s.values()):.1f} ms (the sum of the p99s above) plus the feed "
          "queue, packetization, DTLS-SRTP and loopback")


if __name__ == "__main__":
    main()
