#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd's HTTPS through the real binary, with a test CA that `openssl` makes in WORKDIR:

    tests/http/tls_test.py --overlayd build/daemon/overlayd --workdir /tmp/tls

  serve    [http] tls_cert/tls_key (relative to the config's folder): `curl --cacert ca.pem` gets the page, /state
           and a change with the control token; plain HTTP to the same port fails cleanly (no answer, the
           connection closed within 5 s) and HTTPS goes on
  renew    a /stream viewer over TLS; the certificate and key renamed over by a renewed pair and SIGHUP sent: the
           next client is served the renewed certificate while the viewer's parts keep coming (no gap over 2 s)
  check    `overlayd check-config` refuses a key that is not the certificate's, and an unreadable certificate, at
           http.tls_cert (exit 2)
  warn     a listen address other than loopback without TLS starts with a warning that names the risk
Bounded: about 20 s.
"""
import os
import shutil
import signal
import ssl
import subprocess
import sys
import time

import daemon_fixture
import raw_client

TOKEN = "tls-test-control-token"
STREAM_GAP = 2.0


check = raw_client.check
POSE = '{"position": [0.0, -6.0, 3.0], "yaw": 90.0, "pitch": 25.0, "roll": 0.0}'


def openssl(*args, cwd):
    subprocess.run(["openssl", *args], cwd=cwd, check=True, capture_output=True, timeout=30)


def make_certificates(folder):
    """ca.pem, then server.pem/server.key and renewed.pem/renewed.key signed by it (for 127.0.0.1), and other.key."""
    openssl("req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:P-256", "-nodes", "-keyout", "ca.key",
            "-out", "ca.pem", "-days", "2", "-subj", "/CN=overlayd test CA", cwd=folder)
    with open(os.path.join(folder, "san.ext"), "w") as file:
        file.write("subjectAltName=IP:127.0.0.1,DNS:localhost\n")
    for name in ("server", "renewed"):
        openssl("req", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:P-256", "-nodes", "-keyout", f"{name}.key",
                "-out", f"{name}.csr", "-subj", f"/CN=overlayd {name}", cwd=folder)
        openssl("x509", "-req", "-in", f"{name}.csr", "-CA", "ca.pem", "-CAkey", "ca.key", "-CAcreateserial",
                "-days", "2", "-extfile", "san.ext", "-out", f"{name}.pem", cwd=folder)
    openssl("genpkey", "-algorithm", "ec", "-pkeyopt", "ec_paramgen_curve:P-256", "-out", "other.key", cwd=folder)


def curl(url, ca, *extra):
    result = subprocess.run(["curl", "-sS", "--noproxy", "*", "--max-time", "5", "--cacert", ca, "-o", "-", "-w",
                             "\n%{http_code}", *extra, url], capture_output=True, text=True, timeout=15)
    body, _, code = result.stdout.rpartition("\n")
    return result.returncode, int(code or 0), body, result.stderr


def served_certificate(port):
    return ssl.get_server_certificate(("127.0.0.1", port), timeout=5)


def pem_of(path):
    return ssl.DER_cert_to_PEM_cert(ssl.PEM_cert_to_DER_cert(open(path).read()))


def wait_https(base, ca, daemon, timeout=20.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if daemon.process.poll() is not None:
            raise AssertionError(f"overlayd exited {daemon.process.returncode}:\n{daemon.log_tail()}")
        code, status, body, _ = curl(base + "/state", ca)
        if code == 0 and status == 200 and '"frames"' in body:
            return
        time.sleep(0.2)
    raise AssertionError(f"no HTTPS /state within {timeout} s:\n{daemon.log_tail()}")


def serve_and_renew(overlayd, workdir, ca):
    port = daemon_fixture.free_port()
    shutil.copy(os.path.join(workdir, "server.pem"), os.path.join(workdir, "live.pem"))
    shutil.copy(os.path.join(workdir, "server.key"), os.path.join(workdir, "live.key"))
    with open(os.path.join(workdir, "token"), "w") as file:
        file.write(TOKEN + "\n")
    config = os.path.join(workdir, "tls.toml")
    with open(config, "w") as file:
        file.write(daemon_fixture.demo_without_sinks() + daemon_fixture.http_section(
            port, control="token", token_file="token", tls_cert="live.pem", tls_key="live.key"))
    base = f"https://127.0.0.1:{port}"
    with raw_client.serving(daemon_fixture.Daemon(overlayd, config, workdir, port)) as daemon:
        wait_https(base, ca, daemon)
        code, status, body, err = curl(base + "/", ca)
        check(code == 0 and status == 200 and "<html" in body.lower(), f"the page over HTTPS: {code} {status} {err}")
        code, status, body, err = curl(base + "/api/camera", ca, "-X", "PUT", "-H", f"Authorization: Bearer {TOKEN}",
                                       "--data", POSE)
        check(code == 0 and status == 200, f"PUT /api/camera over HTTPS: {code} {status} {body} {err}")
        # Plain HTTP to the TLS port: no HTTP answer, the connection ends quickly, HTTPS still served.
        status, elapsed, answer = raw_client.get(port, "/state", timeout=5.0)
        print(f"plain HTTP to the TLS port: {answer[:40]!r} after {elapsed:.2f} s")
        check(status is None and elapsed < 5.0, f"plain HTTP to the TLS port: {status} after {elapsed:.2f} s")
        check(curl(base + "/state", ca)[1] == 200, "HTTPS after a plain HTTP request")

        check(served_certificate(port) == pem_of(os.path.join(workdir, "server.pem")), "the first certificate")
        with raw_client.StreamWatch(port, ssl.create_default_context(cafile=ca)) as viewer:
            time.sleep(1.5)
            before = viewer.parts
            # Renewed as certbot does: new files renamed over the old ones, then a reload.
            for source, target in (("renewed.pem", "live.pem"), ("renewed.key", "live.key")):
                shutil.copy(os.path.join(workdir, source), os.path.join(workdir, target + ".new"))
                os.replace(os.path.join(workdir, target + ".new"), os.path.join(workdir, target))
            daemon.process.send_signal(signal.SIGHUP)
            renewed, deadline = False, time.monotonic() + 10
            while not renewed and time.monotonic() < deadline:
                time.sleep(0.3)
                renewed = served_certificate(port) == pem_of(os.path.join(workdir, "renewed.pem"))
            time.sleep(1.5)
            print(f"renew: renewed served {renewed}; stream parts {before} before, {viewer.parts} in all, longest "
                  f"gap {viewer.longest_gap:.2f} s")
            check(renewed, f"the renewed certificate was not served within 10 s of SIGHUP:\n{daemon.log_tail()}")
            check(viewer.thread.is_alive() and viewer.parts > before + 10,
                  f"the TLS stream stopped at the reload ({before} -> {viewer.parts} parts)")
            check(viewer.longest_gap < STREAM_GAP, f"the TLS stream stalled {viewer.longest_gap:.2f} s")
        code, status, _, err = curl(base + "/state", ca)
        check(code == 0 and status == 200, f"HTTPS after the renewal: {code} {status} {err}")
        check(TOKEN not in daemon.log_text(), "the control token is in the log")


def check_config(overlayd, workdir):
    port = daemon_fixture.free_port()
    for label, cert, key, words in (("a key that is not the certificate's", "server.pem", "other.key", "do not match"),
                                    ("an unreadable certificate", "absent.pem", "server.key", "cannot read")):
        config = os.path.join(workdir, "check.toml")
        with open(config, "w") as file:
            file.write(daemon_fixture.demo_without_sinks() +
                       daemon_fixture.http_section(port, control="off", tls_cert=cert, tls_key=key))
        result = subprocess.run([overlayd, "check-config", config], capture_output=True, text=True,
                                timeout=30)
        said = result.stdout + result.stderr
        print(f"check-config, {label}: exit {result.returncode}: {said.strip()[:300]}")
        check(result.returncode == 2 and "http.tls_cert" in said and words in said,
              f"check-config with {label}: exit {result.returncode}: {said}")


def warn(overlayd, workdir):
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, "wide.toml")
    with open(config, "w") as file:
        file.write(daemon_fixture.demo_without_sinks() + daemon_fixture.http_section(port, control="off")
                   .replace("127.0.0.1:", "0.0.0.0:"))
    with raw_client.serving(daemon_fixture.Daemon(overlayd, config, workdir, port)) as daemon:
        daemon.wait_ready()
        lines = [line for line in daemon.log_text().splitlines() if "without TLS" in line]
        print(f"warn: {lines}")
        check(lines and "warning" in lines[0] and "clear text" in lines[0], "no warning about plain HTTP on 0.0.0.0")


def run(overlayd, workdir, args):
    make_certificates(workdir)
    check_config(overlayd, workdir)
    warn(overlayd, workdir)
    serve_and_renew(overlayd, workdir, os.path.join(workdir, "ca.pem"))


def main():
    return raw_client.test_main("tls_test", __doc__, run, tools=("curl", "openssl"))


if __name__ == "__main__":
    sys.exit(main())
