#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""WebRTC over WHEP through the real path: `overlayd run` (synthetic source, [webrtc] enabled, no [encoder] table:
the defaults) watched by an independent receiver built here with GStreamer's webrtcbin (through python3-gi):
- POST /whep with the receiver's offer answers 201, application/sdp, a Location /whep/ID, and an answer whose ICE
  candidates are host candidates only (no ice_servers);
- the receiver decodes at least 60 frames of the stream's size, while /state lists one peer;
- /state's peer shows webrtcbin's RTCP figures: packets sent (at least the receiver's own count of packets
  received), the PLIs the receiver sent (it asks for keyframes here), a loopback round trip; /metrics the totals;
- a second offer past max_peers = 1 is 503; DELETE of the Location hangs up (/state: no peers), DELETE again 404;
- a receiver that stops without DELETE is reaped within REAP_BOUND_S (its RTCP reports stop);
- bad offers are 400 naming what is wrong (not SDP; no video; no H.264), a wrong Content-Type is 415;
- /stream's credential rules: with a viewer token configured, no credential is 401, the viewer's token passes.

    whep_test.py --overlayd build/daemon/overlayd --workdir /tmp/whep-test
Exit 0 when every check passed, 1 when any failed, 77 (skipped) without python3-gi's GStreamer WebRTC bindings."""
import argparse
import os
import sys
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "http"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402
from rtsp_test import HEIGHT, SCENE, WIDTH, check, failures  # noqa: E402

try:
    import gi
    gi.require_version("Gst", "1.0")
    gi.require_version("GstWebRTC", "1.0")
    gi.require_version("GstSdp", "1.0")
    gi.require_version("GstVideo", "1.0")
    from gi.repository import Gst, GstSdp, GstVideo, GstWebRTC  # noqa: E402
except (ImportError, ValueError) as error:
    # python3-gi is Debian's: only the system interpreter has it (CMake may have found another, a pyenv one).
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    print(f"SKIP: no GStreamer WebRTC bindings ({error}; Debian: python3-gi gir1.2-gst-plugins-bad-1.0)")
    sys.exit(77)

FRAMES = 60
# rtsp_test's scene (640x360 at 30 fps, a magenta rail) and checks, with WebRTC instead of an RTSP sink; no
# [encoder] table: [webrtc] enabled alone runs the encoder with its defaults.
CONFIG = SCENE + """
[webrtc]
enabled = true
max_peers = 1
"""


def request(method, url, body=None, content_type="application/sdp", token=None):
    """(status, headers, body text) of one request, errors included."""
    data = body.encode() if body is not None else None
    req = urllib.request.Request(url, data=data, method=method)
    if token:
        req.add_header("Authorization", f"Bearer {token}")
    if data is not None:
        req.add_header("Content-Type", content_type)
    try:
        with urllib.request.urlopen(req, timeout=15) as answer:
            return answer.status, answer.headers, answer.read().decode()
    except urllib.error.HTTPError as error:
        return error.code, error.headers, error.read().decode()
    except urllib.error.URLError as error:  # not listening yet
        return 0, None, str(error)


class Receiver:
    """webrtcbin receiving H.264 only (recvonly), decoding with openh264dec into an appsink."""

    def __init__(self):
        self.pipeline = Gst.Pipeline.new("receiver")
        self.webrtc = Gst.ElementFactory.make("webrtcbin", "receiver")
        self.webrtc.set_property("bundle-policy", GstWebRTC.WebRTCBundlePolicy.MAX_BUNDLE)
        self.pipeline.add(self.webrtc)
        self.sink = None
        self.source = None  # webrtcbin's src pad: where a keyframe request goes upstream, as a PLI
        caps = Gst.Caps.from_string("application/x-rtp,media=video,encoding-name=H264,payload=102,clock-rate=90000,"
                                    "packetization-mode=(string)1,profile-level-id=(string)42e01f")
        self.webrtc.emit("add-transceiver", GstWebRTC.WebRTCRTPTransceiverDirection.RECVONLY, caps)
        self.webrtc.connect("pad-added", self.on_pad)
        self.pipeline.set_state(Gst.State.PLAYING)

    def on_pad(self, _, pad):
        if pad.direction != Gst.PadDirection.SRC:
            return
        decode = Gst.parse_bin_from_description(
            "rtph264depay ! h264parse ! openh264dec ! videoconvert ! video/x-raw,format=I420 "
            "! appsink name=frames sync=false max-buffers=1000", True)
        self.pipeline.add(decode)
        decode.sync_state_with_parent()
        pad.link(decode.get_static_pad("sink"))
        self.source = pad
        self.sink = decode.get_by_name("frames")

    def offer(self):
        promise = Gst.Promise.new()
        self.webrtc.emit("create-offer", None, promise)
        promise.wait()
        reply = promise.get_reply()
        offer = reply.get_value("offer")  # owned by the reply, which the promise owns: both kept until it is set
        done = Gst.Promise.new()
        self.webrtc.emit("set-local-description", offer, done)
        done.wait()
        deadline = time.monotonic() + 10
        while (self.webrtc.get_property("ice-gathering-state") != GstWebRTC.WebRTCICEGatheringState.COMPLETE
               and time.monotonic() < deadline):
            time.sleep(0.05)
        return self.webrtc.get_property("local-description").sdp.as_text()

    def answer(self, text):
        result, message = GstSdp.SDPMessage.new_from_text(text)
        assert result == GstSdp.SDPResult.OK
        answer = GstWebRTC.WebRTCSessionDescription.new(GstWebRTC.WebRTCSDPType.ANSWER, message)
        promise = Gst.Promise.new()
        self.webrtc.emit("set-remote-description", answer, promise)
        promise.wait()

    def frames(self, count, timeout):
        """(frames decoded, (width, height) of the last) within timeout seconds."""
        decoded, size = 0, None
        deadline = time.monotonic() + timeout
        while decoded < count and time.monotonic() < deadline:
            sample = self.sink.emit("try-pull-sample", Gst.SECOND // 10) if self.sink else None
            if sample is None:
                time.sleep(0.01 if self.sink is None else 0)
                continue
            decoded += 1
            structure = sample.get_caps().get_structure(0)
            size = (structure.get_value("width"), structure.get_value("height"))
        return decoded, size

    def ask_keyframe(self):
        """What a decoder does after a loss: webrtcbin's RTP session sends it as a PLI."""
        event = GstVideo.video_event_new_upstream_force_key_unit(Gst.CLOCK_TIME_NONE, False, 0)
        return bool(self.source and self.source.send_event(event))

    def packets_received(self):
        """The receiver's own count, from its webrtcbin's inbound-rtp statistics."""
        promise = Gst.Promise.new()
        self.webrtc.emit("get-stats", None, promise)
        promise.wait()
        reply = promise.get_reply()
        received = [0]

        def add(_, value):
            if isinstance(value, Gst.Structure) and value.get_name() == "inbound-rtp":
                found, count = value.get_uint64("packets-received")
                received[0] += count if found else 0
            return True
        reply.foreach(add)
        return received[0]

    def stop(self):
        self.pipeline.set_state(Gst.State.NULL)


def peers(daemon):
    for sink in daemon.state().get("encoder", {}).get("sinks", []):
        if sink.get("kind") == "webrtc":
            return len(sink.get("peers", []))
    return None


def webrtc_sink(daemon):
    return next((s for s in daemon.state().get("encoder", {}).get("sinks", []) if s.get("kind") == "webrtc"), {})


def metric(base, name):
    with urllib.request.urlopen(base + "/metrics", timeout=10) as answer:
        for line in answer.read().decode().splitlines():
            if line.startswith(name + " "):
                return float(line.split()[-1])
    return None


def peer_stats(daemon, receiver):
    """The peer's figures in /state against the receiver's own: polled every 2 s, RTCP every second or more."""
    asked = 0
    for _ in range(3):  # apart: the receiver's RTP session holds back PLIs that come too close together
        asked += receiver.ask_keyframe()
        time.sleep(1.2)
    peer = {}
    deadline = time.monotonic() + 15
    while time.monotonic() < deadline:
        peer = (webrtc_sink(daemon).get("peers") or [{}])[0]
        if peer.get("rtt_s") is not None and peer.get("plis", 0) >= 1:
            break
        time.sleep(0.5)
    received = receiver.packets_received()
    time.sleep(2.5)  # one more poll: the daemon's count is from after the receiver's
    peer = (webrtc_sink(daemon).get("peers") or [{}])[0]
    sent = peer.get("packets_sent", 0)
    check(received > 0 and sent >= received and peer.get("address", "").startswith("127.0.0.1")
          and peer.get("since"), f"/state's peer {peer.get('id')} ({peer.get('address')}, since {peer.get('since')}):"
          f" {sent} packets sent >= the {received} the receiver counted")
    rtt = peer.get("rtt_s")
    check(rtt is not None and 0 <= rtt < 0.5, f"its RTCP round trip on loopback: {rtt} s")
    check(asked >= 1 and peer.get("plis", 0) >= 1 and peer.get("nacks", -1) >= 0,
          f"the receiver asked for {asked} keyframes: {peer.get('plis')} PLIs, {peer.get('nacks')} NACKs in /state")
    totals = {name: metric(daemon.base, f"overlayd_webrtc_{name}_total") for name in ("packets_sent", "plis")}
    check(totals["packets_sent"] is not None and totals["packets_sent"] >= sent and
          totals["plis"] is not None and totals["plis"] >= peer.get("plis", 0), f"/metrics totals {totals}")


# A vanished viewer is found by its RTCP reports stopping: reaped kWebrtcSilenceMs (15 s) after its last one, on
# the next look (every second). The bound is what ICE consent freshness gives (RFC 7675: 30 s).
REAP_BOUND_S = 30


def vanished(daemon, whep):
    """A receiver that goes without DELETE (its pipeline stopped: no more RTCP) is reaped when its reports stop."""
    receiver = Receiver()
    status, _, answer = request("POST", whep, receiver.offer())
    if status != 201:
        check(False, f"a second receiver after DELETE: 201 ({status})")
        return
    receiver.answer(answer)
    decoded, _ = receiver.frames(10, 10)
    receiver.stop()  # no DELETE; its RTCP stops
    started = time.monotonic()
    while peers(daemon) != 0 and time.monotonic() - started < REAP_BOUND_S:
        time.sleep(0.5)
    check(decoded >= 10 and peers(daemon) == 0,
          f"a receiver gone without DELETE is reaped: {peers(daemon)} peers {time.monotonic() - started:.1f} s later")


def credentials(overlayd, workdir):
    """The rules of /stream: with a viewer token configured, no credential is 401 and the viewer's reaches WHEP."""
    token = "whep-viewer-token-0123456789"
    with open(os.path.join(workdir, "viewer.token"), "w", encoding="utf-8") as file:
        file.write(token + "\n")
    daemon = start(overlayd, workdir, "whep-viewer", CONFIG, viewer_token_file="viewer.token")
    try:
        deadline = time.monotonic() + 20
        while request("GET", daemon.base + "/state", token=token)[0] != 200 and time.monotonic() < deadline:
            time.sleep(0.2)
        status, _, _ = request("POST", daemon.base + "/whep", "hello")
        check(status == 401, f"with a viewer token configured, POST /whep without a credential: 401 ({status})")
        status, _, body = request("POST", daemon.base + "/whep", "hello", token=token)
        check(status == 400, f"the viewer's token reaches WHEP (400 for the bad offer: {status} {body.strip()[:80]})")
    finally:
        daemon.stop()


def arguments(parser=None):
    """--overlayd and --workdir (made), GStreamer started."""
    parser = parser or argparse.ArgumentParser()
    for option in ("--overlayd", "--workdir"):
        parser.add_argument(option, required=True)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    Gst.init(None)
    return args


def start(overlayd, workdir, name, text, **http):
    """overlayd run on `text` (NAME.toml in workdir) with [http] on a free port, control off, and `http`'s keys."""
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, name + ".toml")
    with open(config, "w", encoding="utf-8") as file:
        file.write(text + daemon_fixture.http_section(port, control="off", **http))
    return daemon_fixture.Daemon(overlayd, config, workdir, port)


def main():
    args = arguments()
    daemon = start(args.overlayd, args.workdir, "whep", CONFIG)
    receiver = None
    try:
        daemon.wait_ready()
        whep = daemon.base + "/whep"
        receiver = Receiver()
        offer = receiver.offer()
        started = time.monotonic()
        status, headers, answer = request("POST", whep, offer)
        took = time.monotonic() - started
        location = headers.get("Location", "") if headers else ""
        check(status == 201 and headers.get("Content-Type", "").startswith("application/sdp")
              and location.startswith("/whep/"),
              f"POST /whep: 201 application/sdp with a Location (got {status}, {location!r}, {took * 1000:.0f} ms)"
              + ("" if status == 201 else f": {answer[:300]}"))
        candidates = [line for line in answer.splitlines() if line.startswith("a=candidate:")]
        check(candidates and all(" typ host" in line for line in candidates),
              f"the answer carries its candidates, host only ({len(candidates)} candidates)")
        if status != 201:
            return
        receiver.answer(answer)
        decoded, size = receiver.frames(FRAMES, 20)
        check(decoded >= FRAMES and size == (WIDTH, HEIGHT),
              f"the receiver decoded {decoded} frames (>= {FRAMES}) of {size} ({WIDTH}x{HEIGHT})")
        check(peers(daemon) == 1, f"/state lists one WebRTC peer ({peers(daemon)})")
        peer_stats(daemon, receiver)
        latency = daemon.state()["encoder"]["latency"].get("webrtc_sent", {})
        counted = metric(daemon.base, 'overlayd_stage_latency_seconds_count{stage="webrtc_sent"}')
        check(latency.get("frames", 0) >= FRAMES and 0 < latency.get("p99_s", 0) < 1.0 and counted
              and counted >= latency["frames"], f"the WebRTC stage in the latency figures (from the blend to the "
              f"peers' feeds): /state {latency}, /metrics count {counted}")

        status, _, body = request("POST", whep, offer)
        check(status == 503 and "max_peers" in body, f"an offer past max_peers = 1 is 503 ({status}: {body.strip()})")

        status, _, _ = request("DELETE", daemon.base + location)
        check(status == 200, f"DELETE {location}: 200 ({status})")
        deadline = time.monotonic() + 5
        while peers(daemon) != 0 and time.monotonic() < deadline:
            time.sleep(0.1)
        check(peers(daemon) == 0, f"after DELETE /state lists no peer ({peers(daemon)})")
        status, _, body = request("DELETE", daemon.base + location)
        check(status == 404, f"DELETE {location} again: 404 ({status}: {body.strip()})")

        for bad, named, what in [("hello", "not SDP", "not SDP"),
                                 ("v=0\r\no=- 1 1 IN IP4 0.0.0.0\r\ns=-\r\nt=0 0\r\n"
                                  "m=audio 9 UDP/TLS/RTP/SAVPF 111\r\na=rtpmap:111 opus/48000/2\r\n",
                                  "m=video", "audio only"),
                                 (offer.replace("H264", "VP8"), "H.264", "VP8 only")]:
            status, _, body = request("POST", whep, bad)
            check(status == 400 and named in body, f"a bad offer ({what}) is 400 naming '{named}' ({status}: "
                  f"{body.strip()[:200]})")
        status, _, body = request("POST", whep, offer, content_type="application/json")
        check(status == 415, f"an offer sent as application/json is 415 ({status}: {body.strip()[:120]})")
        vanished(daemon, whep)
        credentials(args.overlayd, args.workdir)
    finally:
        if receiver:
            receiver.stop()
        code = daemon.stop()
        check(code == 0, f"overlayd stopped cleanly (exit {code})")
        if failures:
            print(daemon.log_tail(30))
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
