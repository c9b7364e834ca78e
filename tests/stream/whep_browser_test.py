#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""WebRTC in a real browser: Debian's headless Chromium, driven through its DevTools protocol (tests/http/devtools.py),
opens overlayd's own page origin, makes an RTCPeerConnection (receive-only video, the browser's own host candidates
hidden behind mDNS names), POSTs its offer to /whep and plays the answer:
- getStats() shows at least 60 frames decoded at the stream's size (640x360), with host candidates only on both
  sides (no ice_servers, no internet);
- a DELETE of the Location from the page frees the peer (/state lists none).

    whep_browser_test.py --overlayd build/daemon/overlayd --workdir /tmp/whep-browser [--chromium /usr/bin/chromium]
Exit 0 when every check passed, 1 when any failed, 77 (skipped) without chromium or python3-websocket."""
import argparse
import json
import os
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "http"))
sys.path.insert(0, HERE)
import daemon_fixture  # noqa: E402
from rtsp_test import HEIGHT, SCENE, WIDTH, check, failures  # noqa: E402

try:
    from devtools import Chromium, Page  # noqa: E402
except ImportError as error:
    print(f"SKIP: no python3-websocket ({error})")
    sys.exit(77)

FRAMES = 60
# Everything from the offer to the answer set, in the page: the result is what the POST answered.
CONNECT = """(async () => {
  const pc = new RTCPeerConnection();
  pc.addTransceiver('video', {direction: 'recvonly'});
  await pc.setLocalDescription(await pc.createOffer());
  await new Promise(done => {
    if (pc.iceGatheringState === 'complete') done();
    pc.onicegatheringstatechange = () => pc.iceGatheringState === 'complete' && done();
    setTimeout(done, 3000);
  });
  const started = performance.now();
  const answer = await fetch('/whep', {method: 'POST', headers: {'Content-Type': 'application/sdp'},
                                      body: pc.localDescription.sdp});
  const text = await answer.text();
  const took = performance.now() - started;
  if (answer.status !== 201)
    return {status: answer.status, body: text};
  await pc.setRemoteDescription({type: 'answer', sdp: text});
  window.pc = pc;
  window.whep = answer.headers.get('Location');
  window.connectedAt = null;
  pc.onconnectionstatechange = () => { if (pc.connectionState === 'connected') window.connectedAt = performance.now(); };
  window.answeredAt = performance.now();
  return {status: 201, location: window.whep, took: took,
          nack: text.split(String.fromCharCode(10)).map(line => line.trim())
                .filter(line => / nack$/.test(line) || /rtx[/]/.test(line))};
})()"""
STATS = """(async () => {
  let video = null;
  (await pc.getStats()).forEach(s => {
    if (s.type === 'inbound-rtp' && s.kind === 'video')
      video = {frames: s.framesDecoded || 0, width: s.frameWidth, height: s.frameHeight,
               jitterBufferDelay: s.jitterBufferDelay, emitted: s.jitterBufferEmittedCount,
               decodeTime: s.totalDecodeTime};
  });
  return video;
})()"""


def peers(daemon):
    for sink in daemon.state().get("encoder", {}).get("sinks", []):
        if sink.get("kind") == "webrtc":
            return len(sink.get("peers", []))
    return None


def close_all(page, browser, daemon):
    """Closes the tab and the browser when they were opened, then stops the daemon: its exit status."""
    if page:
        page.close()
    if browser:
        browser.stop()
    return daemon.stop()


def browser_arguments():
    """(the arguments, the work folder made with no old browser profile); exits 77 without chromium."""
    parser = argparse.ArgumentParser()
    for option in ("--overlayd", "--workdir"):
        parser.add_argument(option, required=True)
    parser.add_argument("--chromium", default="/usr/bin/chromium")
    args = parser.parse_args()
    if not os.access(args.chromium, os.X_OK):
        print(f"SKIP: no {args.chromium}")
        sys.exit(77)
    workdir = os.path.abspath(args.workdir)
    shutil.rmtree(os.path.join(workdir, "chrome"), ignore_errors=True)
    os.makedirs(workdir, exist_ok=True)
    return args, workdir


def main():
    args, workdir = browser_arguments()
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, "whep.toml")
    with open(config, "w", encoding="utf-8") as file:
        file.write(SCENE + "\n[webrtc]\nenabled = true\n" + daemon_fixture.http_section(port, control="off"))
    daemon = daemon_fixture.Daemon(args.overlayd, config, workdir, port)
    browser = page = None
    try:
        daemon.wait_ready()
        browser = Chromium(args.chromium, os.path.join(workdir, "chrome"), os.path.join(workdir, "chromium.log"))
        page = Page(browser.browser_url(20), timeout=15)
        # The daemon's origin, but not its page: the page makes a peer of its own (whep_page_test.py tests that one).
        page.call("Page.navigate", url=daemon.base + "/state")
        page.wait_for("document.readyState === 'complete'", 10, "the page")
        answered = page.evaluate(CONNECT)
        check(answered.get("status") == 201, f"the browser's POST /whep: 201 ({json.dumps(answered)[:300]})")
        if answered.get("status") != 201:
            return
        check(any(line.endswith(" nack") for line in answered.get("nack", [])),
              f"the answer takes the browser's NACKs ({answered.get('nack')})")
        started = time.monotonic()
        stats = None
        while time.monotonic() - started < 15:
            stats = page.evaluate(STATS)
            if stats and stats["frames"] >= FRAMES:
                break
            time.sleep(0.2)
        seconds = time.monotonic() - started
        connected = page.evaluate("window.connectedAt && window.connectedAt - window.answeredAt")
        frames = stats["frames"] if stats else 0
        check(frames >= FRAMES and (stats["width"], stats["height"]) == (WIDTH, HEIGHT),
              f"getStats(): {frames} frames decoded (>= {FRAMES}) at {stats and stats['width']}x"
              f"{stats and stats['height']} ({WIDTH}x{HEIGHT}) {seconds:.1f} s after the answer (connected after "
              f"{connected and round(connected)} ms)")
        if stats and stats.get("emitted"):
            print(f"jitter buffer delay {1000 * stats['jitterBufferDelay'] / stats['emitted']:.1f} ms a frame, "
                  f"decode {1000 * stats['decodeTime'] / max(1, frames):.2f} ms a frame (Chromium's own stats)")
        check(peers(daemon) == 1, f"/state lists the browser as a peer ({peers(daemon)})")
        status = page.evaluate("fetch(window.whep, {method: 'DELETE'}).then(r => r.status)")
        deadline = time.monotonic() + 5
        while peers(daemon) != 0 and time.monotonic() < deadline:
            time.sleep(0.1)
        check(status == 200 and peers(daemon) == 0, f"DELETE from the page: {status}, then {peers(daemon)} peers")
        check(not page.problems, f"no error in the page ({page.problems[:3]})")
    finally:
        code = close_all(page, browser, daemon)
        check(code == 0, f"overlayd stopped cleanly (exit {code})")
        if failures:
            print(daemon.log_tail(30))
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
