# SPDX-License-Identifier: Apache-2.0
"""Headless Chromium driven over the DevTools protocol: just enough for browser_test.py (evaluate, click, screenshot).

Uses Debian's python3-websocket; a pyenv or venv interpreter does not see Debian's dist-packages, so fall back to it.
"""
import base64
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time

try:
    import websocket
except ImportError:
    sys.path.append('/usr/lib/python3/dist-packages')
    import websocket


class BrowserError(Exception):
    pass


class Chromium:
    """A headless Chromium process; its DevTools address comes from the "DevTools listening on" line on stderr."""

    def __init__(self, binary, profile_dir, log_path, width=1280, height=900):
        self.log_path = log_path
        self.process = subprocess.Popen(
            [binary, '--headless=new', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage',
             '--no-first-run', '--no-default-browser-check', '--no-proxy-server',
             f'--window-size={width},{height}', '--remote-debugging-port=0',
             f'--user-data-dir={profile_dir}', 'about:blank'],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            start_new_session=True)  # its own process group: stop() ends the renderers and zygotes with it
        self._url = None
        self._found = threading.Event()
        # Keep draining stderr after the line we need: a full pipe would stall the browser.
        threading.Thread(target=self._drain, daemon=True).start()

    def _drain(self):
        with open(self.log_path, 'wb') as log:
            for line in self.process.stderr:
                log.write(line)
                log.flush()
                match = re.search(rb'DevTools listening on (ws://\S+)', line)
                if match and not self._found.is_set():
                    self._url = match.group(1).decode()
                    self._found.set()
        self._found.set()  # the browser exited: let browser_url() fail now instead of at its timeout

    def browser_url(self, timeout):
        self._found.wait(timeout)
        if not self._url:
            raise BrowserError(f'chromium printed no DevTools address (see {self.log_path})')
        return self._url

    def stop(self):
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(self.process.pid, sig)
            except ProcessLookupError:
                break
            try:
                self.process.wait(5)
                break
            except subprocess.TimeoutExpired:
                pass


class Page:
    """One page target, reached through the browser's endpoint with a flat session: the browser's first page, or a
    new tab opened at `url`."""

    def __init__(self, browser_ws_url, timeout, url=None):
        self.ws = websocket.create_connection(browser_ws_url, timeout=timeout, suppress_origin=True)
        self.next_id = 0
        self.session = None
        self.problems = []  # uncaught exceptions and security errors (a CSP refusal, say) the page ran into
        if url is None:
            targets = self.call('Target.getTargets')['targetInfos']
            pages = [t for t in targets if t['type'] == 'page']
            if not pages:
                raise BrowserError(f'no page target among {targets}')
            self.target = pages[0]['targetId']
        else:
            self.target = self.call('Target.createTarget', url=url)['targetId']
        self.session = self.call('Target.attachToTarget', targetId=self.target, flatten=True)['sessionId']
        self.call('Page.enable')
        self.call('Runtime.enable')
        self.call('Log.enable')

    def call(self, method, **params):
        self.next_id += 1
        message = {'id': self.next_id, 'method': method, 'params': params}
        if self.session:
            message['sessionId'] = self.session
        self.ws.send(json.dumps(message))
        while True:  # events arrive in between: only the page's problems are kept
            reply = json.loads(self.ws.recv())
            if reply.get('id') == self.next_id:
                break
            self._note_problem(reply)
        if 'error' in reply:
            raise BrowserError(f'{method}: {reply["error"]}')
        return reply['result']

    def _note_problem(self, event):
        params = event.get('params', {})
        if event.get('method') == 'Runtime.exceptionThrown':
            details = params.get('exceptionDetails', {})
            self.problems.append(details.get('exception', {}).get('description') or details.get('text'))
        elif event.get('method') == 'Log.entryAdded':
            entry = params.get('entry', {})
            if entry.get('level') == 'error' and entry.get('source') in ('security', 'javascript'):
                self.problems.append(entry.get('text'))

    def evaluate(self, expression):
        result = self.call('Runtime.evaluate', expression=expression, returnByValue=True, awaitPromise=True)
        if 'exceptionDetails' in result:
            details = result['exceptionDetails']
            raise BrowserError(f'{expression!r} threw: {details.get("exception", {}).get("description", details)}')
        return result['result'].get('value')

    def wait_for(self, expression, timeout, what):
        """Polls a JS expression until it is truthy; a navigation in progress may destroy the context meanwhile."""
        deadline = time.monotonic() + timeout
        last_error = None
        while time.monotonic() < deadline:
            try:
                value = self.evaluate(expression)
                if value:
                    return value
            except BrowserError as error:
                last_error = error
            time.sleep(0.1)
        raise BrowserError(f'timed out after {timeout} s waiting for {what}' + (f' ({last_error})' if last_error else ''))

    def click(self, x, y):
        for kind in ('mouseMoved', 'mousePressed', 'mouseReleased'):
            self.call('Input.dispatchMouseEvent', type=kind, x=x, y=y, button='left',
                      clickCount=0 if kind == 'mouseMoved' else 1)

    def press(self, key, shift=False):
        """A key pressed and released on the focused element, as a keyboard sends it (arrow keys: 'ArrowUp')."""
        codes = {'ArrowLeft': 37, 'ArrowUp': 38, 'ArrowRight': 39, 'ArrowDown': 40}
        for kind in ('rawKeyDown', 'keyUp'):
            self.call('Input.dispatchKeyEvent', type=kind, key=key, code=key, modifiers=8 if shift else 0,
                      windowsVirtualKeyCode=codes.get(key, 0))

    def drag(self, x, y, dx):
        """A left-button drag from (x, y) by dx CSS pixels across, in small moves as a hand makes them."""
        self.call('Input.dispatchMouseEvent', type='mouseMoved', x=x, y=y)
        self.call('Input.dispatchMouseEvent', type='mousePressed', x=x, y=y, button='left', clickCount=1)
        for step in range(1, 11):
            self.call('Input.dispatchMouseEvent', type='mouseMoved', x=x + dx * step / 10, y=y, button='left',
                      buttons=1)
        self.call('Input.dispatchMouseEvent', type='mouseReleased', x=x + dx, y=y, button='left', clickCount=1)

    def screenshot(self, path):
        png = base64.b64decode(self.call('Page.captureScreenshot', format='png')['data'])
        with open(path, 'wb') as file:
            file.write(png)
        return png

    def close_tab(self):
        """Closes the tab as a user does (its pagehide runs), then the connection."""
        self.session = None
        self.call('Target.closeTarget', targetId=self.target)
        self.close()

    def close(self):
        try:
            self.ws.close()
        except OSError:
            pass
