#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The alignment page as a person sees it: overlayd serving the demo scene on a free loopback port, Debian's headless
Chromium opening http://127.0.0.1:PORT/, one screenshot once the page has filled itself in from /state.

Usage: scripts/alignment_picture.py --overlayd build/daemon/overlayd --output docs/alignment-page.png
Reuses the HTTP tier's daemon fixture and DevTools client (tests/http/), so the picture comes from the same code
the browser test drives."""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "http"))
import daemon_fixture  # noqa: E402
from devtools import Chromium, Page  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--overlayd", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--chromium", default="/usr/bin/chromium")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="overlayd-picture-") as workdir:
        port = daemon_fixture.free_port()
        config = os.path.join(workdir, "demo.toml")
        with open(config, "w", encoding="utf-8") as file:
            file.write(daemon_fixture.demo_without_sinks() + daemon_fixture.http_section(port, control="open"))
        daemon = daemon_fixture.Daemon(os.path.abspath(args.overlayd), config, workdir, port, cwd=workdir)
        browser = None
        try:
            daemon.wait_ready(20)
            browser = Chromium(args.chromium, os.path.join(workdir, "chrome"), os.path.join(workdir, "chromium.log"),
                               width=1280, height=757)
            page = Page(browser.browser_url(20), timeout=10)
            page.call("Page.navigate", url=daemon.base + "/")
            page.wait_for("document.body && document.body.dataset.ready === 'true'", 15, "the page to load /state")
            width = daemon.state()["source"]["width"]
            page.wait_for(f"document.getElementById('stream').naturalWidth === {width}", 10, "the stream on the page")
            page.screenshot(os.path.abspath(args.output))
            page.close()
        finally:
            if browser:
                browser.stop()
            daemon.stop()
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
