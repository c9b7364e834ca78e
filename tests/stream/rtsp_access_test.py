#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Who may watch an RTSP sink, through the real binary read by ffprobe (FFmpeg's RTSP client, independent of
gst-rtsp-server):
- [http] viewer = "credential" with a users_file: a viewer user, a control user and the viewer token (user name
  "token") each read h264; no credential, a wrong password and an unknown user are refused (401: ffprobe fails);
  the refusal is logged with the client's address and never the password; after 10 refusals within a minute the
  address is refused even the right password;
- auth = "none" on the sink: open beside that [http]; auth = "credential" with no credential in [http] is refused
  by check-config;
- [http] with tls_cert/tls_key (a test CA made by openssl): the sink is RTSPS with that certificate (openssl
  s_client verifies it against the CA), ffmpeg decodes frames from rtsps:// with a viewer user, a wrong password is
  refused, plain rtsp:// to it fails; tls = "off" keeps it plain.

    rtsp_access_test.py --overlayd build/daemon/overlayd --workdir /tmp/rtsp-access-test
Exit 0 when every check passed, 1 when any failed."""
import hashlib
import json
import os
import re
import socket
import ssl
import subprocess
import sys
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rtsp_test  # noqa: E402
import tls_test  # noqa: E402  (tests/http, on the path through rtsp_test)
from rtsp_test import check, daemon_fixture, write  # noqa: E402

USERS = "# name:role:password\nwatcher:viewer:see-it:all\nboss:control:c0ntrol\n"
VIEWER_TOKEN = "viewer-token-123"
WRONG = "wrong-secret-xyz"


class WatchedDaemon(daemon_fixture.Daemon):
    """A daemon whose /state needs a viewer credential (and over HTTPS, with tls): the fixture's readiness check
    asks with one."""

    def __init__(self, *args, tls=False):
        super().__init__(*args)
        if tls:
            self.base = self.base.replace("http:", "https:")
        self.context = ssl._create_unverified_context() if tls else None

    def state(self):
        request = urllib.request.Request(self.base + "/state", headers={
            "Authorization": "Bearer " + VIEWER_TOKEN})
        with urllib.request.urlopen(request, timeout=5, context=self.context) as response:
            return json.load(response)


def probe(url, *extra):
    """ffprobe over TCP: the codec it found, or its error's last line."""
    done = subprocess.run(["ffprobe", "-v", "error", *extra, "-rtsp_transport", "tcp", "-select_streams", "v:0",
                           "-show_entries", "stream=codec_name", "-of", "csv=p=0", url],
                          capture_output=True, text=True, timeout=30)
    return done.stdout.strip() if done.returncode == 0 else "error: " + done.stderr.strip()[-120:]


def sink(rtsp_port, extra=""):
    return f'\n[[sink]]\nkind = "rtsp"\nlisten = "127.0.0.1:{rtsp_port}"\npath = "/cam"\n{extra}\n'


def serve(overlayd, workdir, name, http_options, sink_extra="", tls=False):
    """A daemon with [http] (users, viewer token) and an RTSP sink: (daemon, its RTSP port)."""
    write(workdir, "users", USERS)
    write(workdir, "viewer.token", VIEWER_TOKEN + "\n")
    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    config = write(workdir, name, rtsp_test.SCENE + daemon_fixture.http_section(
        http_port, control="off", users_file="users", viewer_token_file="viewer.token", **http_options) +
        '[encoder]\nencoder = "openh264"\n' + sink(rtsp_port, sink_extra))
    checked = subprocess.run([overlayd, "check-config", config], capture_output=True, text=True, timeout=30)
    check(checked.returncode == 0, f"check-config accepts {name}: {checked.stderr.strip()[-200:]}")
    daemon = WatchedDaemon(overlayd, config, workdir, http_port, tls=tls)
    daemon.wait_ready()
    return daemon, rtsp_port


def digest_describe(port, path, user, password):
    """A DESCRIBE without a credential, then with RFC 2617's digest answer to the server's challenge (MD5, no qop):
    (the WWW-Authenticate challenges of the first reply, the status of the second)."""
    url = f"rtsp://127.0.0.1:{port}{path}"

    def exchange(sock, cseq, authorization=""):
        sock.sendall(f"DESCRIBE {url} RTSP/1.0\r\nCSeq: {cseq}\r\nAccept: application/sdp\r\n{authorization}\r\n"
                     .encode())
        reply = b""
        while b"\r\n\r\n" not in reply:
            chunk = sock.recv(4096)
            if not chunk:
                break
            reply += chunk
        head = reply.split(b"\r\n\r\n")[0].decode(errors="replace").split("\r\n")
        return int(head[0].split()[1]), [line.split(":", 1)[1].strip() for line in head[1:]
                                          if line.lower().startswith("www-authenticate:")]

    with socket.create_connection(("127.0.0.1", port), timeout=10) as sock:
        status, challenges = exchange(sock, 1)
        digest = next((c for c in challenges if c.startswith("Digest ")), "")
        fields = dict(re.findall(r'(\w+)="([^"]*)"', digest))
        if status != 401 or "nonce" not in fields:
            return challenges, status
        def md5(text):
            return hashlib.md5(text.encode()).hexdigest()
        realm, nonce = fields["realm"], fields["nonce"]
        answer = md5(f"{md5(f'{user}:{realm}:{password}')}:{nonce}:{md5(f'DESCRIBE:{url}')}")
        status, _ = exchange(sock, 2, f'Authorization: Digest username="{user}", realm="{realm}", nonce="{nonce}", '
                                      f'uri="{url}", response="{answer}"\r\n')
        return challenges, status


def credentials(overlayd, workdir):
    daemon, port = serve(overlayd, workdir, "credential.toml", {"viewer": "credential"})
    try:
        url = f"127.0.0.1:{port}/cam"
        for who in ("watcher:see-it:all", "boss:c0ntrol", f"token:{VIEWER_TOKEN}"):
            name = who.split(":")[0]
            got = probe(f"rtsp://{who}@{url}")
            check(got == "h264", f"{name} (users_file or token) reads h264: {got}")
        challenges, status = digest_describe(port, "/cam", "watcher", "see-it:all")
        check(any(c.startswith("Digest ") for c in challenges) and any(c.startswith("Basic ") for c in challenges)
              and status == 200, f"a digest client (RFC 2617, its response computed here) reads the stream: "
              f"challenged with {[c.split()[0] for c in challenges]}, DESCRIBE answered {status}")
        _, status = digest_describe(port, "/cam", "watcher", WRONG)
        check(status == 401, f"digest with a wrong password: {status}")
        for who, what in (("", "no credential"), (f"watcher:{WRONG}@", "a wrong password"),
                          (f"nobody:{WRONG}@", "an unknown user")):
            got = probe(f"rtsp://{who}{url}")
            check(got.startswith("error") and "401" in got, f"{what} is refused (401): {got}")
        # Guessing is slow: once an address has been refused kMaxAuthFailures (10) times within the window, even
        # the right password is refused from it (last: it blocks this test's address for a minute).
        for _ in range(10):
            probe(f"rtsp://watcher:{WRONG}@{url}")
        got = probe(f"rtsp://watcher:see-it:all@{url}")
        check(got.startswith("error") and "401" in got, f"after 10 refusals the right password is refused: {got}")
    finally:
        daemon.stop()
    log = open(daemon.log_path, encoding="utf-8", errors="replace").read()
    check("RTSP: refused a credential from 127.0.0.1 (RTSP basic)" in log, "the refusal is logged with the address")
    check("RTSP: 10 refused credentials from 127.0.0.1" in log, "and the block, once")
    check(WRONG not in log and "see-it" not in log, "and no password is")


def two_tokens(overlayd, workdir):
    """A viewer and a control token both go by the user name "token": gst-rtsp-server keeps one digest entry per
    name, so the sink offers basic alone, and a client that would pick digest (ffmpeg) reads with either token."""
    write(workdir, "viewer.token", VIEWER_TOKEN + "\n")
    write(workdir, "control.token", "control-token-456\n")
    http_port, rtsp_port = daemon_fixture.free_port(), daemon_fixture.free_port()
    config = write(workdir, "tokens.toml", rtsp_test.SCENE + daemon_fixture.http_section(
        http_port, control="token", token_file="control.token", viewer="credential",
        viewer_token_file="viewer.token") + '[encoder]\nencoder = "openh264"\n' + sink(rtsp_port))
    daemon = WatchedDaemon(overlayd, config, workdir, http_port)
    try:
        daemon.wait_ready()
        challenges, _ = digest_describe(rtsp_port, "/cam", "token", VIEWER_TOKEN)
        check([c.split()[0] for c in challenges] == ["Basic"], f"with two tokens the 401 offers basic alone: "
              f"{challenges}")
        for secret in (VIEWER_TOKEN, "control-token-456"):
            got = probe(f"rtsp://token:{secret}@127.0.0.1:{rtsp_port}/cam")
            check(got == "h264", f"ffmpeg reads with the token {secret[:7]}...: {got}")
    finally:
        daemon.stop()


def open_sink(overlayd, workdir):
    daemon, port = serve(overlayd, workdir, "none.toml", {"viewer": "credential"}, 'auth = "none"')
    try:
        got = probe(f"rtsp://127.0.0.1:{port}/cam")
        check(got == "h264", f"auth = \"none\": no credential reads h264: {got}")
    finally:
        daemon.stop()


def refused(overlayd, workdir):
    """auth = "credential" with no credential in [http]: nobody could watch, so check-config refuses it."""
    config = write(workdir, "nobody.toml", rtsp_test.SCENE + daemon_fixture.http_section(
        daemon_fixture.free_port(), control="off") + sink(daemon_fixture.free_port(), 'auth = "credential"'))
    done = subprocess.run([overlayd, "check-config", config], capture_output=True, text=True, timeout=30)
    said = done.stdout + done.stderr
    check(done.returncode != 0 and "sink[0].auth" in said and "nobody could watch" in said,
          f"auth = \"credential\" without a credential in [http] is refused: {said.strip()[-160:]}")


def decode(url, frames):
    """How many frames ffmpeg decodes over TCP (TLS unverified: the test CA is not ffmpeg's)."""
    done = subprocess.run(["ffmpeg", "-v", "error", "-rtsp_transport", "tcp", "-i", url, "-frames:v", str(frames),
                           "-f", "rawvideo", "-pix_fmt", "gray", "-"], capture_output=True, timeout=30)
    return len(done.stdout) // (rtsp_test.WIDTH * rtsp_test.HEIGHT)


def no_tls_backend(overlayd, workdir, files):
    """Without a GLib TLS backend (glib-networking's module hidden) RTSPS cannot start: check-config and run both
    refuse the sink at its `tls` key with the same line, rather than run failing when the server opens."""
    empty = os.path.join(workdir, "no-gio-modules")
    os.makedirs(empty, exist_ok=True)
    config = write(workdir, "no-backend.toml", rtsp_test.SCENE + daemon_fixture.http_section(
        daemon_fixture.free_port(), control="off", **files) + '[encoder]\nencoder = "openh264"\n' +
        sink(daemon_fixture.free_port(), ""))
    hidden = dict(os.environ, GIO_MODULE_DIR=empty, GIO_EXTRA_MODULES=empty)
    checked = subprocess.run([overlayd, "check-config", config], capture_output=True, text=True, timeout=30,
                             env=hidden)
    line = next((l for l in checked.stdout.splitlines() if "sink[0].tls: GLib has no TLS backend" in l), "")
    ran = subprocess.run([overlayd, "run", "--config", config, "--frames", "1"], capture_output=True, text=True,
                         timeout=30, env=hidden)
    check(checked.returncode == 2 and ran.returncode == 2 and line and line in ran.stderr,
          f"no GLib TLS backend: check-config exit {checked.returncode}, run exit {ran.returncode}, both at the "
          f"sink's tls key: {line or checked.stdout.strip()[-300:]}")
    checked = subprocess.run([overlayd, "check-config", config], capture_output=True, text=True, timeout=30)
    check(checked.returncode == 0, f"with glib-networking the same config passes: {checked.stdout.strip()[-200:]}")


def rtsps(overlayd, workdir):
    """[http] with tls_cert and tls_key: the RTSP sink is RTSPS with the same certificate (tls = "http")."""
    folder = os.path.join(workdir, "tls")
    os.makedirs(folder, exist_ok=True)
    tls_test.make_certificates(folder)
    files = {"tls_cert": "tls/server.pem", "tls_key": "tls/server.key"}
    no_tls_backend(overlayd, workdir, files)
    daemon, port = serve(overlayd, workdir, "rtsps.toml", {"viewer": "credential", **files}, tls=True)
    try:
        url = f"127.0.0.1:{port}/cam"
        count = decode(f"rtsps://watcher:see-it:all@{url}", 10)
        check(count == 10, f"rtsps:// with a viewer user: ffmpeg decodes {count} of 10 frames")
        got = probe(f"rtsps://watcher:{WRONG}@{url}")
        check(got.startswith("error") and "401" in got, f"over TLS a wrong password is refused: {got}")
        got = probe(f"rtsp://watcher:see-it:all@{url}", "-timeout", "3000000")
        check(got.startswith("error"), f"plain rtsp:// to it fails: {got}")
        served = subprocess.run(["openssl", "s_client", "-connect", f"127.0.0.1:{port}", "-CAfile",
                                 os.path.join(folder, "ca.pem"), "-verify_return_error"], input="",
                                capture_output=True, text=True, timeout=20)
        check("overlayd server" in served.stdout and "Verify return code: 0" in served.stdout,
              "the certificate served is [http]'s, verified against the test CA")
        sinks = daemon.state()["encoder"]["sinks"]
        check(sinks[0]["url"] == f"rtsps://{url}", f"/state gives the sink's url as RTSPS: {sinks[0]['url']}")
    finally:
        daemon.stop()
    log = open(daemon.log_path, encoding="utf-8", errors="replace").read()
    check(f"RTSP at rtsps://{url}, a credential asked" in log, "the log says RTSPS, and that a credential is asked")
    daemon, port = serve(overlayd, workdir, "rtsp-off.toml", {"viewer": "credential", **files}, 'tls = "off"',
                         tls=True)
    try:
        got = probe(f"rtsp://watcher:see-it:all@127.0.0.1:{port}/cam")
        check(got == "h264", f"tls = \"off\": plain rtsp:// beside HTTPS: {got}")
    finally:
        daemon.stop()


def main():
    overlayd, workdir = rtsp_test.arguments(__doc__)
    refused(overlayd, workdir)
    rtsps(overlayd, workdir)
    credentials(overlayd, workdir)
    two_tokens(overlayd, workdir)
    open_sink(overlayd, workdir)
    return 1 if rtsp_test.failures else 0


if __name__ == "__main__":
    sys.exit(main())
