#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The alignment page plays WebRTC itself, in Debian's headless Chromium driven through DevTools (tests/http/devtools.py),
against `overlayd run` (rtsp_test's scene: a magenta rail on a checkerboard, [webrtc] enabled):
- the page's badge says WebRTC, its <video> plays, the browser's getStats() shows frames decoded;
- a frame drawn from the <video> into a canvas is magenta where `overlayd project` puts the rail, and not where it
  puts the undrawn decoy;
- a click on the <video>'s centre names the stream's centre pixel and the ground point /api/unproject gives for it;
- 8 tabs at once are all served (8 peers in /state) by one encoder (/metrics overlayd_encoders 1); closing the tabs
  hangs up (the page's DELETE on pagehide) and /state lists no peer within 30 s;
- with [webrtc] off the page plays MJPEG and the badge says so; so does a tab whose POST /whep is refused (past
  max_peers = 1), and one whose connection never comes up (within 3 s, hanging its peer up).

    whep_page_test.py --overlayd build/daemon/overlayd --workdir /tmp/whep-page [--chromium /usr/bin/chromium]
Exit 0 when every check passed, 1 when any failed, 77 (skipped) without chromium or python3-websocket."""
import json
import os
import sys
import time
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "http"))
sys.path.insert(0, HERE)
import daemon_fixture  # noqa: E402
from rtsp_test import (DECOY, HEIGHT, LINE, RADIUS, SCENE, WIDTH, along, check, failures, magenta,  # noqa: E402
                       project)

try:
    from devtools import BrowserError, Chromium, Page  # noqa: E402
    from whep_browser_test import browser_arguments  # noqa: E402
except ImportError as error:
    print(f"SKIP: no python3-websocket ({error})")
    sys.exit(77)

TABS = 8
FRAMES = 30
# WebRTC chosen and a frame decoded (the badge's delay is measured from then on); a tab in the background decodes
# without rendering, so only the tab in front is asked for the <video>'s own size.
PLAYING = "document.body.dataset.transport === 'webrtc' && liveView.timer !== null"
SHOWN = PLAYING + " && liveView.video.videoWidth > 0"
# MJPEG playing: the badge's text.
ON_MJPEG = ("document.body.dataset.transport === 'mjpeg' && liveView.img.naturalWidth > 0 && "
            "document.getElementById('transport').textContent")
# The browser's own count of what it decoded, from the page's peer connection.
DECODED = """(async () => {
  let frames = 0;
  (await liveView.pc.getStats()).forEach(s => {
    if (s.type === 'inbound-rtp' && s.kind === 'video') frames = s.framesDecoded || 0;
  });
  return frames;
})()"""
# The <video>'s current frame drawn at its own size; the RGB of the square around each pixel asked for.
SAMPLE = """((points, radius) => {
  const video = liveView.video;
  const canvas = document.createElement('canvas');
  canvas.width = video.videoWidth;
  canvas.height = video.videoHeight;
  const context = canvas.getContext('2d');
  context.drawImage(video, 0, 0);
  const data = context.getImageData(0, 0, canvas.width, canvas.height).data;
  return {width: canvas.width, height: canvas.height, squares: points.map(([u, v]) => {
    const rgb = [];
    for (let y = Math.round(v) - radius; y <= Math.round(v) + radius; ++y)
      for (let x = Math.round(u) - radius; x <= Math.round(u) + radius; ++x) {
        const i = 4 * (y * canvas.width + x);
        rgb.push([data[i], data[i + 1], data[i + 2]]);
      }
    return rgb;
  })};
})"""


def http_json(url, method="GET", body=None):
    data = json.dumps(body).encode() if body is not None else None
    request = urllib.request.Request(url, data=data, method=method, headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(request, timeout=10) as answer:
        text = answer.read().decode()
    return json.loads(text) if text.lstrip().startswith(("{", "[")) else text


def peers(daemon):
    for sink in daemon.state().get("encoder", {}).get("sinks", []):
        if sink.get("kind") == "webrtc":
            return len(sink.get("peers", []))
    return None


def metric(base, name):
    for line in http_json(base + "/metrics").splitlines():
        if line.startswith(name + " ") or line.startswith(name + "{"):
            return float(line.rsplit(" ", 1)[1])
    return None


def share_magenta(page, pixels):
    sample = page.evaluate(f"{SAMPLE}({json.dumps(pixels)}, {RADIUS})")
    # rtsp_test's magenta() reads one pixel at (0, 0) of the buffer it is given
    hits = sum(any(magenta(rgb, 0, 0) for rgb in square) for square in sample["squares"])
    return hits / max(1, len(pixels)), (sample["width"], sample["height"])


def start(overlayd, workdir, name, webrtc, max_peers=8):
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, name + ".toml")
    with open(config, "w", encoding="utf-8") as file:
        file.write(SCENE + (f"\n[webrtc]\nenabled = true\nmax_peers = {max_peers}\n" if webrtc else "") +
                   daemon_fixture.http_section(port, control="open"))
    daemon = daemon_fixture.Daemon(overlayd, config, workdir, port, log_path=os.path.join(workdir, name + ".log"))
    daemon.wait_ready()
    return daemon, config


def click_centre(page, base):
    box = page.evaluate("""(() => { const v = liveView.element(); v.scrollIntoView({block: 'center'});
        const r = v.getBoundingClientRect(); return {x: r.left + r.width / 2, y: r.top + r.height / 2,
        width: r.width, tag: v.tagName}; })()""")
    page.click(box["x"], box["y"])
    found = page.wait_for("(() => { const li = document.querySelector('#click-results li');"
                          " return li && {pixel: li.dataset.pixel, hit: li.dataset.hit}; })()", 5, "a ground point")
    u, v = map(float, found["pixel"].split(","))
    slack = 1.5 * WIDTH / box["width"] + 0.5  # one CSS pixel of the scaled picture, in stream pixels
    expected = http_json(base + "/api/unproject", "POST", {"pixels": [[u, v]]})[0]["hit"]
    shown = [float(value) for value in (found.get("hit") or "nan,nan").split(",")]
    check(box["tag"] == "VIDEO" and abs(u - (WIDTH - 1) / 2) <= slack and abs(v - (HEIGHT - 1) / 2) <= slack and
          all(abs(a - b) < 1e-6 for a, b in zip(shown[:2], expected[:2])),
          f"a click on the <{box['tag'].lower()}>'s centre: pixel ({u}, {v}) (about {(WIDTH - 1) / 2}, "
          f"{(HEIGHT - 1) / 2}), ground {shown[:2]} = /api/unproject's {expected[:2]}")


def webrtc_page(overlayd, workdir, browser):
    daemon, config = start(overlayd, workdir, "webrtc", True)
    tabs = []
    try:
        page = Page(browser.browser_url(20), timeout=20, url=daemon.base + "/")
        tabs.append(page)
        page.call("Page.bringToFront")
        try:
            page.wait_for(SHOWN, 20, "the page's <video> playing WebRTC")
        except BrowserError:
            print("the badge says " + repr(page.evaluate("document.getElementById('transport').textContent")))
            raise
        deadline = time.monotonic() + 15
        while page.evaluate(DECODED) < FRAMES and time.monotonic() < deadline:
            time.sleep(0.2)
        badge = page.wait_for("liveView.delay && document.getElementById('transport').textContent", 5, "a delay")
        decoded = page.evaluate(DECODED)
        check(badge.startswith("WebRTC") and decoded >= FRAMES,
              f"the badge says {badge!r}; getStats(): {decoded} frames decoded (>= {FRAMES})")
        line, size = share_magenta(page, project(overlayd, config, along(LINE)))
        decoy, _ = share_magenta(page, project(overlayd, config, along(DECOY)))
        check(size == (WIDTH, HEIGHT) and line >= 0.9 and decoy <= 0.1,
              f"the <video>'s frame ({size[0]}x{size[1]}) is magenta where `overlayd project` puts the rail at "
              f"{line:.0%} of 24 points, at the decoy {decoy:.0%}")
        click_centre(page, daemon.base)

        for _ in range(TABS - 1):
            tabs.append(Page(browser.browser_url(20), timeout=20, url=daemon.base + "/"))
        started = time.monotonic()
        playing = 0
        while time.monotonic() - started < 40:
            playing = sum(1 for tab in tabs if tab.evaluate(f"Boolean({PLAYING})"))
            if playing == TABS:
                break
            time.sleep(0.5)
        encoders = metric(daemon.base, "overlayd_encoders")
        check(playing == TABS and peers(daemon) == TABS and encoders == 1,
              f"{TABS} tabs: {playing} play WebRTC ({time.monotonic() - started:.1f} s), /state lists "
              f"{peers(daemon)} peers, /metrics overlayd_encoders {encoders}")
        check(metric(daemon.base, "overlayd_webrtc_peers") == TABS,
              f"/metrics overlayd_webrtc_peers {metric(daemon.base, 'overlayd_webrtc_peers')}")
        problems = [problem for tab in tabs for problem in tab.problems]
        for tab in tabs:
            tab.close_tab()
        tabs.clear()
        started = time.monotonic()
        while peers(daemon) != 0 and time.monotonic() - started < 30:
            time.sleep(0.25)
        check(peers(daemon) == 0, f"closing the tabs hangs up: {peers(daemon)} peers "
              f"{time.monotonic() - started:.1f} s later")
        check(not problems, f"no error in the pages ({problems[:3]})")
    finally:
        for tab in tabs:
            tab.close()
        code = daemon.stop()
        check(code == 0, f"overlayd stopped cleanly (exit {code})")
        if failures:
            print(daemon.log_tail(30))


def mjpeg_page(overlayd, workdir, browser):
    daemon, _ = start(overlayd, workdir, "mjpeg", False)
    page = None
    try:
        page = Page(browser.browser_url(20), timeout=20, url=daemon.base + "/")
        shown = page.wait_for(ON_MJPEG, 15, "the page playing MJPEG")
        check(shown.startswith("MJPEG") and page.evaluate("liveView.video.hidden && !liveView.pc"),
              f"with [webrtc] off the page plays MJPEG: the badge says {shown!r}")
    finally:
        if page:
            page.close_tab()
        code = daemon.stop()
        check(code == 0, f"overlayd (no WebRTC) stopped cleanly (exit {code})")


def full_page(overlayd, workdir, browser):
    """max_peers = 1: the second tab's POST /whep is refused (503) and that tab plays MJPEG instead."""
    daemon, _ = start(overlayd, workdir, "full", True, max_peers=1)
    tabs = []
    try:
        tabs.append(Page(browser.browser_url(20), timeout=20, url=daemon.base + "/"))
        tabs[0].wait_for(PLAYING, 20, "the first tab playing WebRTC")
        tabs.append(Page(browser.browser_url(20), timeout=20, url=daemon.base + "/"))
        shown = tabs[1].wait_for(ON_MJPEG, 15, "the second tab on MJPEG")
        check(shown.startswith("MJPEG") and "503" in shown and peers(daemon) == 1,
              f"past max_peers the page falls back to MJPEG: the badge says {shown!r}; {peers(daemon)} peer")
        tabs.pop().close_tab()
        tabs[0].close_tab()  # its DELETE frees the one place
        tabs.clear()
        stalled(daemon, browser)
    finally:
        for tab in tabs:
            tab.close_tab()
        code = daemon.stop()
        check(code == 0, f"overlayd (max_peers = 1) stopped cleanly (exit {code})")


def stalled(daemon, browser):
    """A connection that never comes up (the answer is never applied, in this tab only): MJPEG after 3 s, and the
    peer the daemon made is hung up."""
    deadline = time.monotonic() + 10
    while peers(daemon) != 0 and time.monotonic() < deadline:
        time.sleep(0.1)
    tab = Page(browser.browser_url(20), timeout=20, url="about:blank")
    try:
        tab.call("Page.addScriptToEvaluateOnNewDocument",
                 source="RTCPeerConnection.prototype.setRemoteDescription = () => new Promise(() => {});")
        tab.call("Page.navigate", url=daemon.base + "/")
        tab.wait_for("liveView.location", 10, "the stalled tab's POST /whep answered")
        asked = time.monotonic()
        shown = tab.wait_for(ON_MJPEG, 10, "the stalled tab on MJPEG")
        took = time.monotonic() - asked
        while peers(daemon) != 0 and time.monotonic() - asked < 10:
            time.sleep(0.1)
        check(shown == "MJPEG · no WebRTC picture within 3 s" and took < 3.5 and peers(daemon) == 0,
              f"a WebRTC connection that never comes up: {shown!r} {took:.1f} s after the answer, then "
              f"{peers(daemon)} peers (the page hung up)")
    finally:
        tab.close_tab()


def main():
    args, workdir = browser_arguments()
    overlayd = os.path.abspath(args.overlayd)
    browser = Chromium(args.chromium, os.path.join(workdir, "chrome"), os.path.join(workdir, "chromium.log"))
    try:
        for run in (mjpeg_page, full_page, webrtc_page):
            try:
                run(overlayd, workdir, browser)
            except BrowserError as error:
                check(False, f"{run.__name__}: {error}")
    finally:
        browser.stop()
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
