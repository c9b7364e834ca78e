#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The page of an installed binary: a copy of overlayd in PREFIX/bin (as the package's /usr/bin/overlayd) serves
the page of PREFIX/share/overlayd/www (the package's /usr/share/overlayd/www), not the source tree's folder the
build compiled in; and the build tree's binary, with no such folder beside it, still serves the source tree's.
Both through the real binary and a real client (urllib) on loopback.

    installed_page_test.py --overlayd build/daemon/overlayd --workdir /tmp/installed-page
Exit 0 when both pages are the expected ones, 1 with the failure."""
import argparse
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402

MARKER = "<!doctype html><title>installed page marker</title>"


def page(overlayd, workdir, name):
    port = daemon_fixture.free_port()
    config = os.path.join(workdir, f"{name}.toml")
    open(config, "w").write(daemon_fixture.demo_without_sinks() + daemon_fixture.http_section(port, control="off"))
    daemon = daemon_fixture.Daemon(overlayd, config, workdir, port)
    try:
        daemon.wait_ready()
        with daemon_fixture.loopback_opener.open(daemon.base + "/", timeout=5) as response:
            return response.read().decode(errors="replace")
    finally:
        daemon.stop()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--workdir", required=True)
    args = parser.parse_args()
    shutil.rmtree(args.workdir, ignore_errors=True)
    prefix = os.path.join(args.workdir, "usr")
    os.makedirs(os.path.join(prefix, "bin"))
    os.makedirs(os.path.join(prefix, "share", "overlayd", "www"))
    installed = os.path.join(prefix, "bin", "overlayd")
    shutil.copy2(args.overlayd, installed)
    open(os.path.join(prefix, "share", "overlayd", "www", "index.html"), "w").write(MARKER)

    served = page(installed, args.workdir, "installed")
    if served != MARKER:
        print(f"FAIL: {installed} served {served[:120]!r}, not its prefix's share/overlayd/www/index.html")
        return 1
    source_page = open(os.path.join(os.path.dirname(__file__), "..", "..", "http", "www", "index.html")).read()
    served = page(args.overlayd, args.workdir, "built")
    if served != source_page:
        print(f"FAIL: {args.overlayd} served {served[:120]!r}, not the source tree's http/www/index.html")
        return 1
    print("installed_page: the installed copy serves its prefix's page, the built binary the source tree's")
    return 0


if __name__ == "__main__":
    sys.exit(main())
