#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""An [[input.text]] whose folder is removed and made again while `overlayd run` streams, as systemd does to a
writer service's RuntimeDirectory= on every restart: three restarts in a row, the file written with `echo >` and
once replaced by rename. Each time /state must show the new text, and while the folder is gone the input's health
must say "waiting" (in /state's input_health, with the error and its time, and as overlayd_input_following 0 in
/metrics); once it is back, "following" and 1.

    input_folder_test.py --overlayd build/daemon/overlayd --workdir /tmp/input-folder
Exit 0 when every check passed, 1 with the failed check's message."""
import argparse
import datetime
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402
import text_input_test  # noqa: E402

# text_input_test.py's scene and input, the file one folder down.
CONFIG = text_input_test.CONFIG.replace('file = "status.txt"', 'file = "run/status.txt"')
FOLLOWING = 'overlayd_input_following{kind="text",input="status"}'
ERRORS = 'overlayd_input_errors_total{kind="text",input="status"}'


def metrics(daemon):
    with daemon_fixture.loopback_opener.open(daemon.base + "/metrics", timeout=5) as response:
        values = {}
        for line in response.read().decode().splitlines():
            if line and not line.startswith("#"):
                name, value = line.rsplit(" ", 1)
                values[name] = float(value)
        return values


def health(daemon):
    entries = [e for e in daemon.state().get("input_health", []) if e["kind"] == "text" and e["name"] == "status"]
    if len(entries) != 1:
        raise AssertionError(f"/state input_health: {len(entries)} entries for the text input 'status', want 1: "
                             f"{daemon.state().get('input_health')}")
    return entries[0]


def wait_until(what, check, timeout=5.0):
    deadline = time.monotonic() + timeout
    while True:
        try:
            check()
            return
        except AssertionError:
            if time.monotonic() >= deadline:
                raise AssertionError(f"{what}, within {timeout} s") from None
        time.sleep(0.05)


def expect(condition, message):
    if not condition:
        raise AssertionError(message)


def expect_text(daemon, text):
    wait_until(f"/state shows {text!r} in the slot (it shows {daemon.state()['text_slots'].get('status')!r})",
               lambda: expect(daemon.state()["text_slots"].get("status") == text, "not yet"))


def expect_waiting(daemon, folder, errors, before):
    wait_until("the input's health says waiting",
               lambda: expect(health(daemon)["state"] == "waiting" and metrics(daemon)[FOLLOWING] == 0, "not yet"))
    entry = health(daemon)
    expect(entry["errors"] == errors, f"waiting: errors {entry['errors']}, want {errors}: {entry}")
    expect(metrics(daemon)[ERRORS] == errors, f"waiting: {ERRORS} is {metrics(daemon)[ERRORS]}, want {errors}")
    expect(entry["last_error"] and folder in entry["last_error"], f"waiting: last_error names no {folder}: {entry}")
    at = datetime.datetime.strptime(entry["last_error_at"], "%Y-%m-%dT%H:%M:%S.%fZ")
    at = at.replace(tzinfo=datetime.timezone.utc)
    expect(before - datetime.timedelta(seconds=1) <= at <= datetime.datetime.now(datetime.timezone.utc),
           f"waiting: last_error_at {entry['last_error_at']} is not when the folder went ({before.isoformat()})")


def expect_following(daemon, errors):
    wait_until("the input's health says following",
               lambda: expect(health(daemon)["state"] == "following" and metrics(daemon)[FOLLOWING] == 1, "not yet"))
    entry = health(daemon)
    expect(entry["errors"] == errors, f"following: errors {entry['errors']}, want {errors}: {entry}")


def run(overlayd, workdir):
    if 'file = "run/status.txt"' not in CONFIG:
        raise AssertionError("text_input_test.CONFIG no longer names status.txt: update this test's CONFIG")
    folder = os.path.join(workdir, "run")
    status_file = os.path.join(folder, "status.txt")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    with open(status_file, "w") as f:
        f.write("BEFORE\n")
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, "input-folder.toml")
    with open(config, "w") as f:
        f.write(CONFIG + daemon_fixture.http_section(port, control="off"))
    daemon = daemon_fixture.Daemon(overlayd, config, workdir, port)
    try:
        daemon.wait_ready()
        expect_text(daemon, "BEFORE")
        expect_following(daemon, 0)
        expect(health(daemon)["source"] == status_file, f"source: {health(daemon)}")
        for restart in range(1, 4):
            before = datetime.datetime.now(datetime.timezone.utc)
            shutil.rmtree(folder)
            expect_waiting(daemon, folder, restart, before)
            expect_text(daemon, "")  # the file went with its folder
            os.makedirs(folder)
            expect_following(daemon, restart)
            text = f"AFTER RESTART {restart}"
            if restart < 3:
                subprocess.run(f"echo '{text}' > {status_file}", shell=True, check=True)
            else:  # the safe way to write it: a temporary file renamed over it
                with open(os.path.join(folder, "status.tmp"), "w") as f:
                    f.write(text + "\n")
                os.replace(os.path.join(folder, "status.tmp"), status_file)
            expect_text(daemon, text)
            print(f"restart {restart}: waiting while the folder was gone, then {text!r}")
        log = daemon.log_text()
        expect(f"the folder {folder} is gone" in log, "the log does not say the folder went")
        expect(f"following {status_file} again" in log, "the log does not say the file is followed again")
    except Exception:
        print(daemon.log_text()[-3000:], file=sys.stderr)
        raise
    finally:
        code = daemon.stop()
    if code != 0:
        raise AssertionError(f"overlayd exited {code}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    try:
        run(os.path.abspath(args.overlayd), os.path.abspath(args.workdir))
    except AssertionError as failure:
        print(f"input_folder_test: FAILED: {failure}", file=sys.stderr)
        return 1
    print("input_folder_test: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
