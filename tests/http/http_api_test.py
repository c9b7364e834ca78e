#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The HTTP API through the real path: `overlayd run` with [http] on loopback, every endpoint and every refusal
checked with curl (a real client), the stream read by ffprobe, the overlay in snapshots found where /api/project
says, a pose change seen in the next snapshot, save then restart, and a SIGHUP reload of [http].

    http_api_test.py --overlayd build/daemon/overlayd --workdir /tmp/http-api
Exit 0 when every check passed, 1 with the failed check's message."""
import argparse
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402

TOKEN = "s3cret-token-for-tests"
WIDTH, HEIGHT = 1280, 720
SLOT_TEXT = """
[[annotation]]
name = "status line"
type = "text"
text = "status: {slot:status}"
position = [10.0, 80.0]
size_px = 20.0
style = { colour = "white", layer = "hud" }
"""


class Check:
    def __init__(self):
        self.count = 0

    def __call__(self, condition, message):
        self.count += 1
        if not condition:
            raise AssertionError(message)


check = Check()


def curl(base, path, method="GET", body=None, token=None, extra=()):
    """(status, body bytes, headers text) from curl; --path-as-is so that '..' reaches the server as typed."""
    command = ["curl", "-sS", "--path-as-is", "-o", "-", "-D", "/dev/stderr", "-X", method, "--max-time", "10"]
    if token:
        command += ["-H", f"Authorization: Bearer {token}"]
    if body is not None:
        command += ["--data-binary", "@-", "-H", "Content-Type: application/json"]
    command += list(extra) + [base + path]
    done = subprocess.run(command, input=body.encode() if isinstance(body, str) else body, capture_output=True,
                          timeout=20)
    headers = done.stderr.decode(errors="replace")
    status = int(headers.split()[1]) if headers.startswith("HTTP/") else 0
    return status, done.stdout, headers


def curl_json(*args, **kwargs):
    status, body, _ = curl(*args, **kwargs)
    return status, json.loads(body) if body else None


def gray(jpeg_bytes, workdir, name):
    """The JPEG decoded by ffmpeg (independent of our encoder) to 8-bit grey, row-major, at the stream's size."""
    _, _, pixels = daemon_fixture.grey_pixels(jpeg_bytes, workdir, name)
    check(len(pixels) == WIDTH * HEIGHT, f"{name}: decoded {len(pixels)} bytes, not {WIDTH}x{HEIGHT}")
    return pixels


def snapshot(base, raw=False):
    status, body, headers = curl(base, "/snapshot" + ("?raw=1" if raw else ""))
    check(status == 200, f"/snapshot{'?raw=1' if raw else ''}: {status}")
    check("image/jpeg" in headers and "X-Timestamp-Us" in headers and "no-store" in headers,
          f"/snapshot headers: {headers}")
    return body


def overlay_near(overlaid, raw, pixel, radius=2, threshold=40):
    """Whether the overlay changed the grey level by at least `threshold` within `radius` px of `pixel`."""
    u, v = int(round(pixel[0])), int(round(pixel[1]))
    best = 0
    for y in range(max(v - radius, 0), min(v + radius + 1, HEIGHT)):
        for x in range(max(u - radius, 0), min(u + radius + 1, WIDTH)):
            best = max(best, abs(overlaid[y * WIDTH + x] - raw[y * WIDTH + x]))
    return best >= threshold


def project(base, points):
    query = ";".join(",".join(str(c) for c in p) for p in points)
    status, result = curl_json(base, "/api/project?points=" + query)
    check(status == 200, f"/api/project: {status} {result}")
    return result


def grid_points():
    """Grid line crossings on the ground in front of the camera, away from the axes triad and the labels."""
    return [(x, y, 0.0) for x in (-3, -2, 2, 3) for y in (1, 2, 3)]


def check_overlay_where_projected(base, workdir, tag):
    """Every visible grid crossing /api/project gives has overlay pixels in the next snapshot (raw vs overlaid)."""
    projected = project(base, grid_points())
    raw = gray(snapshot(base, raw=True), workdir, f"{tag}-raw.jpg")
    overlaid = gray(snapshot(base), workdir, f"{tag}-overlaid.jpg")
    visible = [p for p in projected if p["visible"]]
    check(len(visible) >= 6, f"{tag}: only {len(visible)} grid crossings visible: {projected}")
    missing = [p["pixel"] for p in visible if not overlay_near(overlaid, raw, p["pixel"])]
    check(not missing, f"{tag}: no overlay at the projected grid crossings {missing}")
    return {tuple(p["world"]): p["pixel"] for p in visible}


# Numbers no config file may hold (a denormal, the largest doubles) and what a JSON parser makes of overflow.
EXTREMES = (5e-324, -5e-324, 1e-300, 1e308, -1e308, "1e400")
HOME = {"position": [1.5, -6.0, 3.0], "yaw": 90.0, "pitch": 25.0, "roll": 0.0, "fov": 60.0, "near": 0.1,
        "far": 200.0, "distortion": {"model": "none"}}


def camera_bodies(value):
    """A [camera] request for each numeric key of the camera request, with `value` in that key."""
    pose = {"position": [0.0, -6.0, 3.0], "yaw": 90.0, "pitch": 25.0, "roll": 0.0}
    pinhole = {"fx": 900.0, "fy": 900.0, "cx": 640.0, "cy": 360.0, "skew": 0.0}
    bounds = {"left": -1.0, "right": 1.0, "bottom": -1.0, "top": 1.0, "near": 0.1, "far": 100.0}
    window = {"focal": 1.0, "half_width": 1.0, "half_height": 0.6, "centre": [0.0, 0.0]}
    bodies = [{"fov": value}, {"near": value}, {"far": value}]
    bodies += [{"pinhole": pinhole, "distortion": {"model": "plumb_bob", "coefficients": [value if i == at else 0.0
                                                                                        for i in range(5)]}}
               for at in range(5)]
    bodies += [dict(pose, **{key: value}) for key in ("yaw", "pitch", "roll")]
    bodies += [dict(pose, position=[value if i == axis else c for i, c in enumerate(pose["position"])])
               for axis in range(3)]
    bodies += [{"pinhole": dict(pinhole, **{key: value})} for key in pinhole]
    bodies += [{"frustum": dict(bounds, **{key: value})} for key in bounds]
    bodies += [{"window": dict(window, **{key: value})} for key in ("focal", "half_width", "half_height")]
    return [json.dumps(body).replace('"1e400"', "1e400") for body in bodies]


def finite_numbers(value):
    """Every number in a JSON document is finite (nlohmann writes inf and nan as null)."""
    if isinstance(value, dict):
        return all(finite_numbers(v) for v in value.values())
    if isinstance(value, list):
        return all(finite_numbers(v) for v in value)
    return value is not None and (not isinstance(value, float) or math.isfinite(value))


def check_numbers_and_names(base, daemon):
    """Every number the API takes is finite and in the config file's range, and a path segment is a whole name."""
    for value in EXTREMES:
        for body in camera_bodies(value):
            status, result = curl_json(base, "/api/camera", "PUT", body, token=TOKEN)
            camera = daemon.state()["camera"]
            check(status in (200, 400) and finite_numbers(camera), f"PUT /api/camera {body}: {status} {camera}")
            check(status == 200 or "camera." in result["error"] or "number overflow" in result["error"],
                  f"PUT /api/camera {body}: {result}")
            if status == 200:  # a value in range: back to the config's camera
                status, result = curl_json(base, "/api/camera", "PUT", json.dumps(HOME), token=TOKEN)
                check(status == 200, f"PUT /api/camera back home: {status} {result}")
    status, result = curl_json(base, "/api/camera", "PUT", '{"fov": 5e-324}', token=TOKEN)
    check(status == 400 and "camera.fov" in result["error"], f"PUT a fov of 5e-324: {status} {result}")

    for query in ("nan,0,0", "1e308,0,0", "0,-1e300,0", "0,0,1e400"):
        status, result = curl_json(base, "/api/project?points=" + query)
        check(status == 400 and "point" in result["error"], f"/api/project?points={query}: {status} {result}")
    for pixels in ("[[1e308, 0]]", "[[0, -1e300]]", "[[640, 360], [0, 1e7]]"):
        status, result = curl_json(base, "/api/unproject", "POST", '{"pixels": %s}' % pixels, token=TOKEN)
        check(status == 400 and "pixel" in result["error"], f"/api/unproject {pixels}: {status} {result}")

    # A %-escaped NUL or control character in a name is refused, not cut short to another layer's name.
    for path in ("/api/layers/grid%00x", "/api/layers/grid%00", "/api/layers/gr%0aid", "/api/layers/grid%7f",
                 "/api/layers/grid%1", "/api/text/status%00x"):
        status, result = curl_json(base, path, "PUT", '{"visible": false}', token=TOKEN)
        check(status == 400, f"PUT {path}: {status} {result}")
        check(all(layer["visible"] for layer in daemon.state()["layers"]), f"PUT {path} hid a layer")
    status, result = curl_json(base, "/api/project?points=1,2,3%00", "GET")
    check(status == 400, f"/api/project with a NUL in the query: {status} {result}")
    status, result = curl_json(base, "/api/project?points=2%2C4%2C0", "GET")
    check(status == 200 and result[0]["world"] == [2, 4, 0], f"/api/project with %-escaped commas: {status} {result}")


def run(overlayd, workdir):
    port = daemon_fixture.free_port()
    token_file = os.path.join(workdir, "token")
    open(token_file, "w").write(TOKEN + "\n")
    config_path = os.path.join(workdir, "http.toml")
    config_text = daemon_fixture.demo_without_sinks() + SLOT_TEXT
    open(config_path, "w").write(
        config_text + daemon_fixture.http_section(port, control="token", token_file=token_file, stream_fps=30.0))
    dropin = os.path.join(workdir, "http.live.toml")
    if os.path.exists(dropin):
        os.remove(dropin)

    # check-config accepts it; it refuses an open control API on every interface, naming the key.
    done = subprocess.run([overlayd, "check-config", config_path], capture_output=True, text=True)
    check(done.returncode == 0, f"check-config: {done.returncode} {done.stderr}")
    bad_path = os.path.join(workdir, "bad.toml")
    open(bad_path, "w").write(config_text + daemon_fixture.http_section(port, control="open", listen_also="x")
                              .replace('listen = "127.0.0.1', 'listen = "0.0.0.0'))
    done = subprocess.run([overlayd, "check-config", bad_path], capture_output=True, text=True)
    check(done.returncode == 2 and "http.control" in done.stdout + done.stderr and "http.listen_also" in done.stdout + done.stderr,
          f"check-config of an open API on 0.0.0.0: {done.returncode} {done.stderr}")

    daemon = daemon_fixture.Daemon(overlayd, config_path, workdir, port)
    base = daemon.base
    try:
        state = daemon.wait_ready()
        check(state["source"]["width"] == WIDTH and state["source"]["format"] == "YUYV", f"/state source: {state}")
        check([layer["name"] for layer in state["layers"]] == ["grid", "axes", "labels", "hud"], f"layers: {state}")
        # The version /state reports is the one the binary prints (the package's too), from git or VERSION.
        printed = subprocess.run([overlayd, "--version"], capture_output=True, text=True).stdout.split()
        check(printed[:1] == ["overlayd"] and state.get("version") == printed[-1] and state["version"][0].isdigit(),
              f"/state version {state.get('version')!r} against --version {printed}")
        check(abs(state["camera"]["yaw"] - 90.0) < 1e-9 and abs(state["camera"]["pitch"] - 25.0) < 1e-9,
              f"/state camera in yaw/pitch/roll: {state['camera']}")

        status, body, headers = curl(base, "/metrics")
        check(status == 200 and b"overlayd_source_frames_total " in body and "text/plain" in headers,
              f"/metrics: {status} {body[:200]}")

        # The page and nothing else from its folder.
        status, body, _ = curl(base, "/")
        check(status == 200 and b"<html" in body.lower(), f"GET /: {status}")
        for path in ("/../CMakeLists.txt", "/%2e%2e/CMakeLists.txt", "/..%2fCMakeLists.txt", "/www/", "/.hidden.js",
                     "/nope", "/api/nope"):
            status, body, _ = curl(base, path)
            check(status == 404, f"GET {path}: {status} (expected 404) {body[:100]}")
        status, _, _ = curl(base, "/state", method="DELETE")
        check(status == 405, f"DELETE /state: {status}")

        # The stream: ffprobe reads it as MJPEG at the stream's size and counts frames.
        done = subprocess.run(["ffprobe", "-v", "error", "-read_intervals", "%+#20", "-count_frames", "-show_entries",
                               "stream=codec_name,width,height,nb_read_frames:format=format_name", "-of", "json",
                               base + "/stream"], capture_output=True, text=True, timeout=60)
        probed = json.loads(done.stdout or "{}")
        stream = (probed.get("streams") or [{}])[0]
        check(done.returncode == 0 and stream.get("codec_name") == "mjpeg" and stream.get("width") == WIDTH and
              stream.get("height") == HEIGHT and int(stream.get("nb_read_frames", 0)) >= 20 and
              probed["format"]["format_name"] == "mpjpeg", f"ffprobe /stream: {done.returncode} {probed} {done.stderr}")

        # Control needs the token: refused without it, or with a wrong one, and nothing changes.
        pose = json.dumps({"position": [0.0, -6.0, 3.0], "yaw": 95.0, "pitch": 25.0, "roll": 0.0})
        for token in (None, "wrong"):
            status, result = curl_json(base, "/api/camera", "PUT", pose, token=token)
            check(status == 401 and "token" in result["error"], f"PUT /api/camera, token {token}: {status} {result}")
        check(abs(daemon.state()["camera"]["yaw"] - 90.0) < 1e-9, "a refused change changed the camera")

        # Bad input: 400 naming the field, nothing changed.
        refusals = [
            ("{not json", "not JSON"),
            ('{"eye": [0, -6, 3], "gaze": [0, 0, 1], "up": [0, 0, 1]}', "camera.up"),
            ('{"position": [0, -6, 3], "yaw": 95, "pich": 25}', "did you mean 'pitch'"),
            ('{"position": [0, -6], "yaw": 95}', "camera.position"),
            ('{"position": [0, -6, 3], "yaw": 900}', "camera.yaw"),
            ('{"fov": 200}', "camera.fov"),
            ('{"calibration": "/etc/passwd"}', "camera.calibration"),
            ("[1, 2]", "JSON object"),
            ('{"position": [0, -6, 3], "yaw": null}', "null"),
        ]
        for body, expected in refusals:
            status, result = curl_json(base, "/api/camera", "PUT", body, token=TOKEN)
            check(status == 400 and expected in result["error"], f"PUT /api/camera {body}: {status} {result}")
        check(abs(daemon.state()["camera"]["yaw"] - 90.0) < 1e-9, "a refused change changed the camera")

        status, result = curl_json(base, "/api/layers/nope", "PUT", '{"visible": false}', token=TOKEN)
        check(status == 404 and "nope" in result["error"], f"PUT unknown layer: {status} {result}")
        status, result = curl_json(base, "/api/layers/grid", "PUT", '{"visible": "no"}', token=TOKEN)
        check(status == 400 and "visible" in result["error"], f"PUT layer with a string: {status} {result}")
        status, result = curl_json(base, "/api/text/nope", "PUT", '{"text": "x"}', token=TOKEN)
        check(status == 404, f"PUT unknown slot: {status} {result}")
        status, result = curl_json(base, "/api/text/status", "PUT", '{"text": "two\\nlines"}', token=TOKEN)
        check(status == 400, f"PUT a two-line text: {status} {result}")
        status, result = curl_json(base, "/api/project?points=1,2", "GET")
        check(status == 400 and "points" in result["error"], f"/api/project with 2 numbers: {status} {result}")
        status, result = curl_json(base, "/api/unproject", "POST", '{"pixels": [[1]]}', token=TOKEN)
        check(status == 400 and "pixels" in result["error"], f"/api/unproject with 1 number: {status} {result}")
        check_numbers_and_names(base, daemon)

        # Limits: a 10 MB body is refused before it is read; so is a URL over 8 KiB.
        status, result = curl_json(base, "/api/camera", "PUT", b"x" * (10 * 1024 * 1024), token=TOKEN)
        check(status == 413, f"a 10 MB body: {status} {result}")
        status, _, _ = curl(base, "/api/project?points=" + "1," * 5000)
        check(status in (413, 414, 431), f"a 10 kB URL: {status}")

        # Text slots from other programs.
        status, result = curl_json(base, "/api/text/status", "PUT", '{"text": "reversing"}', token=TOKEN)
        check(status == 200 and daemon.state()["text_slots"]["status"] == "reversing", f"PUT text: {status} {result}")

        # The overlay lies where /api/project says; a pose change moves it by what /api/project then says.
        before = check_overlay_where_projected(base, workdir, "before")
        status, result = curl_json(base, "/api/camera", "PUT", pose, token=TOKEN)
        check(status == 200 and abs(result["yaw"] - 95.0) < 1e-9, f"PUT /api/camera: {status} {result}")
        after = check_overlay_where_projected(base, workdir, "after")
        moved = [w for w in after if w in before and math.dist(after[w], before[w]) > 10.0]
        check(len(moved) >= 6, f"a 5 degree yaw moved only {len(moved)} crossings by more than 10 px")

        # A hidden layer leaves the frame untouched there.
        status, _ = curl_json(base, "/api/layers/grid", "PUT", '{"visible": false}', token=TOKEN)
        check(status == 200 and not daemon.state()["layers"][0]["visible"], "PUT /api/layers/grid")
        raw = gray(snapshot(base, raw=True), workdir, "hidden-raw.jpg")
        overlaid = gray(snapshot(base), workdir, "hidden-overlaid.jpg")
        drawn = [p for p in after.values() if overlay_near(overlaid, raw, p)]
        check(not drawn, f"the hidden grid still drawn at {drawn}")
        curl_json(base, "/api/layers/grid", "PUT", '{"visible": true}', token=TOKEN)

        # unproject -> the ground point -> project gives the pixel back.
        status, result = curl_json(base, "/api/unproject", "POST", '{"pixels": [[640, 500]]}', token=TOKEN)
        hit = result[0]["hit"]
        check(status == 200 and hit is not None and abs(hit[2]) < 1e-9, f"/api/unproject: {status} {result}")
        back = project(base, [hit])[0]["pixel"]
        check(math.dist(back, [640, 500]) < 1e-6, f"unproject then project: {back}, not [640, 500]")

        # Save writes the drop-in beside the config; a restart comes up with the live pose.
        status, result = curl_json(base, "/api/save", "POST", "", token=TOKEN)
        check(status == 200 and os.path.exists(dropin), f"/api/save: {status} {result}")
        live = daemon.state()["camera"]
        check(daemon.stop() == 0, "overlayd did not exit 0 on SIGTERM")
        daemon = daemon_fixture.Daemon(overlayd, config_path, workdir, port)
        restarted = daemon.wait_ready()["camera"]
        check(all(abs(restarted[k] - live[k]) < 1e-9 for k in ("yaw", "pitch", "roll")) and
              math.dist(restarted["position"], live["position"]) < 1e-9, f"after restart {restarted}, saved {live}")
        check(open(config_path).read().endswith(daemon_fixture.http_section(
            port, control="token", token_file=token_file, stream_fps=30.0)), "the user's config file was rewritten")

        # A reload that turns control off answers 403; one whose listen address is bad keeps the server serving.
        open(config_path, "w").write(config_text + daemon_fixture.http_section(port, control="off"))
        daemon.process.send_signal(signal.SIGHUP)
        deadline = time.monotonic() + 10
        status = 0
        while time.monotonic() < deadline and status != 403:
            time.sleep(0.2)
            status, _ = curl_json(base, "/api/camera", "PUT", pose, token=TOKEN)
        check(status == 403, f"after reloading control = \"off\": {status}")
        open(config_path, "w").write(config_text + daemon_fixture.http_section(port, control="off")
                                     .replace("127.0.0.1:", "127.0.0.1:x"))
        daemon.process.send_signal(signal.SIGHUP)
        time.sleep(1.0)
        check("reload refused" in daemon.log_text() and daemon.state()["source"]["state"] == "streaming",
              "a bad [http] reload was not refused, or the server stopped serving")
    except Exception:
        print(daemon.log_text()[-4000:], file=sys.stderr)
        raise
    finally:
        status = daemon.stop()
    check(status == 0, f"overlayd exited {status}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    for tool in ("curl", "ffprobe", "ffmpeg"):
        if not shutil.which(tool):
            print(f"http_api_test: {tool} is missing (scripts/install-deps.sh installs it)", file=sys.stderr)
            return 1
    os.makedirs(args.workdir, exist_ok=True)
    try:
        run(os.path.abspath(args.overlayd), args.workdir)
    except AssertionError as failure:
        print(f"http_api_test: FAILED after {check.count} checks: {failure}", file=sys.stderr)
        return 1
    print(f"http_api_test: {check.count} checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
