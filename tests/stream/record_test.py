#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""kind = "record" and kind = "push" through the real path: `overlayd run` (synthetic source, [encoder] openh264)
writing segments read back by ffprobe, and pushing into ffmpeg listeners:
- segments: 2 s segments for 9 s give 4 complete files (named by their UTC start) whose durations ffprobe reads
  within 10% of 2 s, and no partial file once the daemon has stopped;
- retention: old segments (by name) go at start with keep_days, and keep_bytes deletes the oldest of the new ones,
  never a newer one before an older;
- kill -9 in the middle of a segment: every finished file reads as 2 s and the partial one reads (up to its last
  fragment); the next start finishes it under its final name;
- a full filesystem (a 3 MiB tmpfs): the recording stops with a log line while the stream goes on, and records
  again once space is freed; every file on it reads (skipped, and said so, where mount is not permitted);
- push: into `ffmpeg -listen 1` over RTMP and an SRT listener frames arrive; an RTMP server down at start and up
  later is reached; into an RTSP server in RECORD mode (gst-rtsp-server, rtsp_record_server.py) what arrives decodes
  in ffmpeg (SKIP, with the reason, where python3-gi or its RTSP server typelib is missing).

    record_test.py --overlayd build/daemon/overlayd --workdir /tmp/record-test
Exit 0 when every check passed, 1 when any failed (each check prints PASS, FAIL or SKIP with its numbers)."""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "http"))
import daemon_fixture  # noqa: E402

SEGMENT_NAME = re.compile(r"^\d{8}T\d{6}Z(-\d+)?\.(mp4|mkv)$")
failures = []


def check(ok, what):
    print(("PASS " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def config(sinks, keyframe_s=1.0, bitrate=1000, http_port=None, pattern="checkerboard-scene"):
    """The synthetic source encoded by openh264; `noise` makes the encoder use its whole bitrate (big segments)."""
    text = f"""
[source]
kind = "synthetic"
format = "NV12"
width = 320
height = 240
fps = 30.0
[source.synthetic]
pattern = "{pattern}"
[encoder]
encoder = "openh264"
bitrate_kbps = {bitrate}
keyframe_interval_s = {keyframe_s}
""" + sinks
    if http_port:
        text += daemon_fixture.http_section(http_port, control="off")
    return text


def record_sink(directory, segment_s, extra=""):
    return f'[[sink]]\nkind = "record"\ndirectory = "{directory}"\nsegment_s = {segment_s}\n{extra}\n'


class Run:
    """overlayd run on a config, its log kept; no HTTP needed: the files and the log are what is checked."""

    def __init__(self, overlayd, workdir, name, text):
        self.path = os.path.join(workdir, name + ".toml")
        with open(self.path, "w", encoding="utf-8") as file:
            file.write(text)
        self.log_path = os.path.join(workdir, name + f"-{int(time.time() * 1000)}.log")
        self.log = open(self.log_path, "w")
        self.process = subprocess.Popen([overlayd, "run", "--config", self.path], stdin=subprocess.DEVNULL,
                                        stdout=subprocess.DEVNULL, stderr=self.log)

    def log_text(self):
        if not self.log.closed:
            self.log.flush()
        return open(self.log_path, encoding="utf-8", errors="replace").read()

    def wait_log(self, pattern, timeout):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if re.search(pattern, self.log_text()):
                return True
            if self.process.poll() is not None:
                return False
            time.sleep(0.1)
        return False

    def stop(self, sig=signal.SIGTERM):
        if self.process.poll() is None:
            self.process.send_signal(sig)
            try:
                self.process.wait(15)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.log.close()
        return self.process.returncode


def probe(path):
    """(duration in s or None, decoded frame count) as ffprobe reads the file."""
    result = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                             "format=duration:stream=nb_read_frames", "-of", "default=nw=1", path],
                            capture_output=True, text=True, timeout=30)
    fields = dict(line.split("=", 1) for line in result.stdout.split() if "=" in line)
    duration = fields.get("duration", "N/A")
    frames = fields.get("nb_read_frames", "N/A")
    return (float(duration) if duration not in ("N/A", "") else None,
            int(frames) if frames.isdigit() and result.returncode == 0 else 0)


def segments(directory):
    return sorted(name for name in os.listdir(directory) if SEGMENT_NAME.match(name))


def fresh(workdir, name):
    path = os.path.join(workdir, name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def test_segments(overlayd, workdir):
    directory = fresh(workdir, "segments")
    run = Run(overlayd, workdir, "segments", config(record_sink(directory, 2)))
    started = run.wait_log(r"recording to", 20)
    time.sleep(9.0)
    status = run.stop()
    check(started and status == 0, f"segments: the daemon ran 9 s and stopped cleanly (exit {status})")
    names = segments(directory)
    leftovers = [n for n in os.listdir(directory) if n.endswith(".partial")]
    durations = [probe(os.path.join(directory, n))[0] for n in names]
    full = [d for d in durations[:4] if d is not None and abs(d - 2.0) <= 0.2]
    check(len(names) >= 4 and len(full) == 4,
          f"segments: 4 complete 2 s files ({len(names)} files, durations {durations})")
    check(all(d is not None for d in durations), "segments: ffprobe reads every file, the last one too")
    check(not leftovers, f"segments: no partial file after a clean stop ({leftovers})")
    if len(names) >= 2:
        first = time.mktime(time.strptime(names[0][:15], "%Y%m%dT%H%M%S"))
        second = time.mktime(time.strptime(names[1][:15], "%Y%m%dT%H%M%S"))
        check(1 <= second - first <= 3, f"segments: names are the UTC start times, 2 s apart ({names[:2]})")
        check(abs(time.mktime(time.gmtime()) - first) < 60, f"segments: the first name is UTC now ({names[0]})")


def test_retention(overlayd, workdir):
    directory = fresh(workdir, "retention")
    old = ["20200101T000000Z.mp4", "20200101T000100Z.mp4"]
    for name in old:
        with open(os.path.join(directory, name), "wb") as file:
            file.write(b"\0" * 1000)
    with open(os.path.join(directory, "notes.txt"), "w") as file:
        file.write("not a segment")
    keep = 1_500_000  # two or three 1 s segments of noise
    run = Run(overlayd, workdir, "retention",
              config(record_sink(directory, 1, f"keep_bytes = {keep}\nkeep_days = 1"), pattern="noise"))
    seen = []
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        for name in segments(directory):
            if name not in seen:
                seen.append(name)
        time.sleep(0.1)
    run.stop()
    left = segments(directory)
    seen += [name for name in left if name not in seen]  # the one finished at stop
    check(not any(name in left for name in old), f"retention: segments older than keep_days deleted at start ({left[:3]})")
    check(os.path.exists(os.path.join(directory, "notes.txt")), "retention: a file that is not a segment is kept")
    new = [n for n in seen if n not in old]  # in the order they appeared
    total = sum(os.path.getsize(os.path.join(directory, n)) for n in left)
    check(len(new) > len(left) > 0 and set(left) == set(new[-len(left):]),
          f"retention: the oldest go first ({len(new)} written, the newest {len(left)} kept)")
    # The budget holds for the finished segments; the last one, finished at stop, may add its own bytes.
    last = os.path.getsize(os.path.join(directory, left[-1])) if left else 0
    check(total - last <= keep, f"retention: within keep_bytes ({total - last} <= {keep}, plus the last {last})")


def test_kill(overlayd, workdir, pattern="noise", fragment_bytes=20000):
    """`fragment_bytes`: a partial file larger than this holds a fragment (its header alone is under 1 KB)."""
    directory = fresh(workdir, "kill-" + pattern)
    run = Run(overlayd, workdir, "kill", config(record_sink(directory, 2), keyframe_s=0.5, pattern=pattern))
    run.wait_log(r"recording to", 20)
    # Killed once the segment being written has its first fragment (a picture group held, then 1 s: before it, the
    # file holds its header only, docs/streaming.md) and before its end.
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and len(segments(directory)) < 2:
        time.sleep(0.05)
    while time.monotonic() < deadline and not any(n.endswith(".partial") and os.path.getsize(
            os.path.join(directory, n)) > fragment_bytes for n in os.listdir(directory)):
        time.sleep(0.02)
    run.stop(signal.SIGKILL)
    files = sorted(os.listdir(directory))
    read = {name: probe(os.path.join(directory, name)) for name in files}
    finished = [n for n in files if SEGMENT_NAME.match(n)]
    partial = [n for n in files if n.endswith(".partial")]
    check(len(finished) >= 2 and all(read[n][0] and abs(read[n][0] - 2.0) <= 0.2 for n in finished),
          f"kill -9 ({pattern}): every finished segment is complete ({[(n, read[n][0]) for n in finished]})")
    check(len(partial) == 1 and all(read[n][1] > 0 for n in partial),
          f"kill -9 ({pattern}): the segment being written reads up to its last fragment "
          f"({[(n, os.path.getsize(os.path.join(directory, n)), read[n]) for n in partial]})")
    rerun = Run(overlayd, workdir, "kill-again", config(record_sink(directory, 2), keyframe_s=0.5, pattern=pattern))
    recovered = rerun.wait_log(r"left partial by a crash kept", 20)
    rerun.stop()
    after = os.listdir(directory)
    check(recovered and all(n[:-len(".partial")] in after for n in partial) and
          not any(n.endswith(".partial") for n in after),
          f"kill -9 ({pattern}): the next start finishes the partial segment under its final name")


def test_kill_quiet(overlayd, workdir):
    """A quiet scene: segments of a few KB, which a buffered filesink would hold in memory until killed."""
    test_kill(overlayd, workdir, pattern="checkerboard-scene", fragment_bytes=1200)


def test_full_disk(overlayd, workdir):
    mount = fresh(workdir, "full")
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=3m", "tmpfs", mount],
                             capture_output=True, text=True)
    if mounted.returncode != 0:
        print(f"SKIP full disk: cannot mount a tmpfs here ({mounted.stderr.strip()}): not counted as a pass",
              flush=True)
        return
    try:
        http_port = daemon_fixture.free_port()
        run = Run(overlayd, workdir, "full", config(record_sink(mount, 1), bitrate=3000, http_port=http_port, pattern="noise"))
        stopped = run.wait_log(r"is full: recording stopped", 40)
        check(stopped, "full disk: a log line says the recording stopped")
        frames = []
        for _ in range(2):
            try:
                with daemon_fixture.loopback_opener.open(f"http://127.0.0.1:{http_port}/state", timeout=5) as r:
                    import json
                    frames.append(json.load(r)["source"]["frames"])
            except OSError:
                frames.append(None)
            time.sleep(1.0)
        check(None not in frames and frames[1] > frames[0] and run.process.poll() is None,
              f"full disk: the stream goes on (frames {frames})")
        import json
        with daemon_fixture.loopback_opener.open(f"http://127.0.0.1:{http_port}/state", timeout=5) as r:
            recording = [s for s in json.load(r)["encoder"]["sinks"] if s["kind"] == "record"]
        check(len(recording) == 1 and recording[0]["disk_full"] and recording[0]["disk_full_stops"] >= 1,
              f"full disk: /state says the recording waits for space ({recording})")
        with daemon_fixture.loopback_opener.open(f"http://127.0.0.1:{http_port}/metrics", timeout=5) as r:
            metrics = r.read().decode()
        check(re.search(r'^overlayd_record_disk_full\{sink="sink\[0\]",url="[^"]*"\} 1(\.0)?$', metrics, re.M) is not None,
              "full disk: /metrics overlayd_record_disk_full is 1")
        for name in os.listdir(mount):
            if SEGMENT_NAME.match(name):
                os.remove(os.path.join(mount, name))
        resumed = run.wait_log(r"space is back", 10)
        time.sleep(1.5)
        check(resumed and any(SEGMENT_NAME.match(n) or n.endswith(".partial") for n in os.listdir(mount)),
              f"full disk: recording again once space is freed ({sorted(os.listdir(mount))})")
        run.stop()
        unreadable = [n for n in os.listdir(mount) if probe(os.path.join(mount, n))[1] == 0]
        check(not unreadable, f"full disk: every file on the full filesystem reads ({unreadable})")
    finally:
        subprocess.run(["umount", mount])


def record_server_python():
    """A python that has GStreamer's introspection (python3-gi): this one, else Debian's."""
    for python in (sys.executable, "/usr/bin/python3"):
        if os.path.exists(python) and subprocess.run([python, "-c", "import gi"], capture_output=True).returncode == 0:
            return python
    return None


def test_rtsp_push(overlayd, workdir):
    """Into a real RTSP RECORD server (gst-rtsp-server in record mode, rtsp_record_server.py): what it receives,
    written as an H.264 byte stream, is decoded by ffmpeg at the stream's size."""
    python = record_server_python()
    if python is None:
        print("SKIP push: RTSP into a RECORD server: python3-gi and gir1.2-gst-rtsp-server-1.0 are not installed "
              "(scripts/install-deps.sh)", flush=True)
        return
    port = daemon_fixture.free_port()
    out = os.path.join(workdir, "rtsp-push.h264")
    if os.path.exists(out):
        os.remove(out)
    server = subprocess.Popen([python, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                     "rtsp_record_server.py"), str(port), "/cam", out, "30"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    said = server.stdout.readline().strip()
    if said.startswith("missing"):
        server.wait()
        print(f"SKIP push: RTSP into a RECORD server: {said} (python3-gi, gir1.2-gst-rtsp-server-1.0)", flush=True)
        return
    try:
        check(said == "listening", f"push: the RTSP RECORD server listens: {said}")
        run = Run(overlayd, workdir, "push-rtsp",
                  config(f'[[sink]]\nkind = "push"\nurl = "rtsp://127.0.0.1:{port}/cam"\n'))
        connected = run.wait_log(r"pushing to rtsp://", 15)
        time.sleep(4)
        run.stop()
        time.sleep(0.5)
    finally:
        server.kill()
        server.wait()
    read = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                           "stream=codec_name,width,height,nb_read_frames", "-of", "default=nw=1", out],
                          capture_output=True, text=True, timeout=30)
    fields = dict(line.split("=", 1) for line in read.stdout.split() if "=" in line)
    frames = int(fields["nb_read_frames"]) if fields.get("nb_read_frames", "").isdigit() else 0
    check(connected and fields.get("codec_name") == "h264" and fields.get("width") == "320" and
          fields.get("height") == "240" and frames >= 60,
          f"push: a gst-rtsp-server RECORD server takes ANNOUNCE/SETUP/RECORD and ffmpeg decodes what it received: "
          f"{frames} frames, {fields.get('width')}x{fields.get('height')} {fields.get('codec_name')} "
          f"(the push logged that it pushes: {connected})")


def listener(args, workdir, name):
    log = open(os.path.join(workdir, name + ".ffmpeg.log"), "w")
    process = subprocess.Popen(["ffmpeg", "-hide_banner", "-nostdin", "-loglevel", "warning", "-stats"] + args +
                               ["-f", "null", "-"], stdout=subprocess.DEVNULL, stderr=log)
    return process, log


def frames_received(workdir, name):
    text = open(os.path.join(workdir, name + ".ffmpeg.log"), encoding="utf-8", errors="replace").read()
    counts = re.findall(r"frame=\s*(\d+)", text)
    return int(counts[-1]) if counts else 0


def push_case(overlayd, workdir, name, url, ffmpeg_args, delay_server=0.0, wait=6.0):
    run = Run(overlayd, workdir, "push-" + name, config(f'[[sink]]\nkind = "push"\nurl = "{url}"\n'))
    time.sleep(delay_server)
    process, log = listener(ffmpeg_args, workdir, name)
    time.sleep(wait)
    run.stop()
    time.sleep(0.5)
    process.send_signal(signal.SIGINT)
    try:
        process.wait(5)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
    log.close()
    return frames_received(workdir, name), run


def test_push(overlayd, workdir):
    port = daemon_fixture.free_port()
    frames, _ = push_case(overlayd, workdir, "rtmp", f"rtmp://127.0.0.1:{port}/live/cam",
                          ["-listen", "1", "-i", f"rtmp://127.0.0.1:{port}/live/cam"], wait=6.0)
    check(frames >= 60, f"push: an RTMP listener (ffmpeg -listen 1) decodes the pushed stream ({frames} frames)")
    port = daemon_fixture.free_port()
    frames, _ = push_case(overlayd, workdir, "srt", f"srt://127.0.0.1:{port}",
                          ["-i", f"srt://127.0.0.1:{port}?mode=listener"], wait=6.0)
    check(frames >= 60, f"push: an SRT listener decodes the pushed stream ({frames} frames)")
    test_rtsp_push(overlayd, workdir)
    port = daemon_fixture.free_port()
    frames, run = push_case(overlayd, workdir, "late", f"rtmp://127.0.0.1:{port}/live/cam",
                            ["-listen", "1", "-i", f"rtmp://127.0.0.1:{port}/live/cam"], delay_server=3.0, wait=8.0)
    log = run.log_text()
    check(frames >= 30 and "retrying with back-off" in log,
          f"push: a server down at start is reached once it is up ({frames} frames; the failure logged once: "
          f"{log.count('retrying with back-off')} line)")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    overlayd = os.path.abspath(args.overlayd)
    for name, test in [("segments", test_segments), ("retention", test_retention), ("kill", test_kill), ("kill", test_kill_quiet),
                       ("full", test_full_disk), ("push", test_push)]:
        if not args.only or name in args.only.split(","):
            test(overlayd, args.workdir)
    print(f"{len(failures)} failed" if failures else "all passed", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
