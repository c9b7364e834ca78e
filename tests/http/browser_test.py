#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The alignment page in a real browser against a real `overlayd run`: pose edit, click-to-ground, layer toggle.

    tests/http/browser_test.py --overlayd build/daemon/overlayd --workdir /tmp/bt [--config config/examples/demo.toml]

--config (default: the repository's config/examples/demo.toml) is the scene to serve: the test copies it into WORKDIR
without its [[sink]]s and adds an [http] section on a free loopback port with control = "open". Needs /usr/bin/chromium (or --chromium), ffmpeg (the stdlib has no JPEG
decoder) and Debian's python3-websocket. WORKDIR keeps overlayd.log, chromium.log, the config and page.png.
Exit 0: pass; 1: a check failed (the message says which); 2: set-up failed. Bounded by --timeout (90 s).
"""
import argparse
import json
import math
import os
import re
import shutil
import signal
import sys
import subprocess
import time
import urllib.parse
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import daemon_fixture  # noqa: E402
from devtools import Chromium, Page  # noqa: E402

HUD_ROWS = 100  # demo.toml's timestamp and frame counter change every frame; the overlay check looks below them
OVERLAY_THRESHOLD = 40  # grey levels between overlaid and raw that count as overlay, well above JPEG noise


class Failure(AssertionError):
    """A failed check. An AssertionError, as daemon_fixture raises when overlayd dies or never serves /state, so that
    main() reports both the same way."""



def http(base, path, method='GET', body=None):
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(base + path, data=data, method=method,
                                     headers={'Content-Type': 'application/json'} if data else {})
    with daemon_fixture.loopback_opener.open(request, timeout=5) as response:
        return response.read(), response.headers


def get_state(base):
    return json.loads(http(base, '/state')[0])


def write_config(source, workdir, port):
    """WORKDIR/overlayd.toml: the scene to serve without its [[sink]]s, and control open, as the page needs to edit."""
    path = os.path.join(workdir, 'overlayd.toml')
    with open(path, 'w') as file:
        file.write(daemon_fixture.config_without_sinks(source) + daemon_fixture.http_section(port, control='open'))
    return path


def start_daemon(args, workdir, cleanup):
    """overlayd serving the scene on a free loopback port, once it streams. It runs in WORKDIR, so that nothing lands
    where the test was started, and logs to WORKDIR/overlayd.log, where the usage above says to look."""
    port = daemon_fixture.free_port()
    daemon = daemon_fixture.Daemon(args.overlayd, write_config(args.config, workdir, port), workdir, port,
                                   log_path=os.path.join(workdir, 'overlayd.log'), cwd=workdir)
    cleanup.append(daemon.stop)
    daemon.wait_ready(20)
    return daemon


def poll(check, timeout, what):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = check()
        if value:
            return value
        time.sleep(0.1)
    raise Failure(f'timed out after {timeout} s waiting for {what}')


# ---- Snapshots: the overlay is where the overlaid frame differs from the raw one --------------------------------

def checked_grey(image, workdir, name):
    """daemon_fixture.grey_pixels, failing unless ffmpeg gave one byte per pixel of the size ffprobe read."""
    width, height, pixels = daemon_fixture.grey_pixels(image, workdir, name)
    if len(pixels) != width * height:
        raise Failure(f'{name}: ffmpeg gave {len(pixels)} bytes for {width}x{height}')
    return width, height, pixels


def overlay_mask(base, workdir, name):
    """Marks the overlay's pixels: where the overlaid snapshot differs from the raw one. They are two frames (each
    request waits for the next), alike below the HUD while the scene stands still; change_yaw measures the rest."""
    overlaid = http(base, '/snapshot')[0]
    raw = http(base, '/snapshot?raw=1')[0]
    width, height, top = checked_grey(overlaid, workdir, f'{name}.jpg')
    _, _, bottom = checked_grey(raw, workdir, f'{name}-raw.jpg')
    start = HUD_ROWS * width
    return bytes(abs(a - b) > OVERLAY_THRESHOLD for a, b in zip(top[start:], bottom[start:]))


def mask_change(a, b):
    return sum(x != y for x, y in zip(a, b))


def shown_change(before_png, after_png, box, frame_width, workdir):
    """Pixels of the page's <img> that changed between two screenshots, below the HUD (scaled to the display)."""
    width, _, before = checked_grey(before_png, workdir, 'page-before.png')
    _, _, after = checked_grey(after_png, workdir, 'page-after.png')
    left, top, right, bottom = (round(box[key]) for key in ('left', 'top', 'right', 'bottom'))
    top += round(HUD_ROWS * (right - left) / frame_width)
    return sum(abs(before[row * width + col] - after[row * width + col]) > OVERLAY_THRESHOLD
               for row in range(top, bottom) for col in range(left, right))


# ---- The steps ---------------------------------------------------------------------------------------------------

def open_page(page, base):
    page.call('Page.navigate', url=base + '/')
    # Not the MJPEG <img>'s load event, which never fires: app.js marks the page ready once /state filled it in.
    page.wait_for("document.body && document.body.dataset.ready === 'true'", 15, 'the page to load /state')


def set_yaw(page, base):
    """Types yaw + 10 into the yaw field as a user would and waits for the server to take it."""
    yaw = float(page.evaluate("document.getElementById('yaw').value"))
    target = round(yaw + 10, 3)
    page.evaluate(f"""(() => {{
        const field = document.getElementById('yaw');
        field.value = '{target}';
        field.dispatchEvent(new Event('input', {{bubbles: true}}));
        field.dispatchEvent(new Event('change', {{bubbles: true}}));
    }})()""")
    poll(lambda: abs(get_state(base)['camera']['yaw'] - target) < 1e-3, 5, f'/state camera yaw to become {target}')
    return yaw, target


def sequence(base):
    value = http(base, '/snapshot')[1].get('X-Sequence')
    return int(value) if value is not None else None


def stream_box(page, frame_width):
    """The <img>'s box once it shows the stream; its naturalWidth is the only sign, MJPEG never fires "load"."""
    page.wait_for(f"document.getElementById('stream').naturalWidth === {frame_width}", 10, 'the stream on the page')
    return page.evaluate("document.getElementById('stream').getBoundingClientRect().toJSON()")


def change_yaw(page, base, workdir):
    frame_width = get_state(base)['source']['width']
    box = stream_box(page, frame_width)
    screen_before = page.screenshot(os.path.join(workdir, 'page-before.png'))
    before = overlay_mask(base, workdir, 'before')
    noise = mask_change(before, overlay_mask(base, workdir, 'before-again'))
    if sum(before) == 0:
        raise Failure('the overlaid and raw snapshots are the same: no overlay to compare')
    yaw, target = set_yaw(page, base)
    # The frame that carries the new overlay comes a few frames after the request was answered.
    applied_at = sequence(base)
    if applied_at is None:
        time.sleep(0.5)
    else:
        poll(lambda: sequence(base) >= applied_at + 3, 5, 'frames after the pose change')
    after = overlay_mask(base, workdir, 'after')
    moved = mask_change(before, after)
    print(f'yaw {yaw} -> {target}: {moved} overlay pixels changed in /snapshot (same-pose noise {noise})')
    if moved < max(2000, 5 * noise):
        raise Failure(f'the overlay barely changed after yaw {yaw} -> {target}: {moved} pixels, noise {noise}')
    time.sleep(0.5)  # a few /stream parts (stream_fps 15) for the browser to show
    shown = shown_change(screen_before, page.screenshot(os.path.join(workdir, 'page.png')), box, frame_width, workdir)
    print(f'{shown} pixels of the page\'s stream changed')
    if shown < 1000:
        raise Failure(f'the stream on the page barely changed after the yaw edit ({shown} pixels): see page.png')


def click_centre(page, base):
    rect = page.evaluate("""(() => {
        const image = document.getElementById('stream');
        image.scrollIntoView({block: 'center'});
        const r = image.getBoundingClientRect();
        return {x: r.left + r.width / 2, y: r.top + r.height / 2, width: r.width};
    })()""")
    page.click(rect['x'], rect['y'])
    found = page.wait_for("(() => { const li = document.querySelector('#click-results li');"
                          " return li && {className: li.className, text: li.textContent,"
                          " pixel: li.dataset.pixel, hit: li.dataset.hit}; })()", 5, 'a ground point on the page')
    if found['className'] != 'hit' or not found.get('hit'):
        raise Failure(f'the click gave no ground point: {found["text"]!r}')
    state = get_state(base)
    width, height = state['source']['width'], state['source']['height']
    u, v = map(float, found['pixel'].split(','))
    # One CSS pixel of the scaled-down image covers about width / displayed width image pixels.
    slack = 1.5 * width / rect['width'] + 0.5
    if abs(u - (width - 1) / 2) > slack or abs(v - (height - 1) / 2) > slack:
        raise Failure(f'clicking the image centre gave pixel ({u}, {v}), not about ({(width - 1) / 2}, '
                      f'{(height - 1) / 2}): the CSS scaling is not accounted for')
    expected = json.loads(http(base, '/api/unproject', 'POST', {'pixels': [[u, v]]})[0])[0]['hit']
    shown = [float(value) for value in found['hit'].split(',')]
    if any(abs(a - b) > 1e-6 for a, b in zip(shown[:2], expected[:2])):
        raise Failure(f'the page shows ground point {shown}, the server says {expected}')
    print(f'clicked pixel ({u}, {v}): page shows {found["text"]!r}')


def hide_layer(page, base):
    name = next(layer['name'] for layer in get_state(base)['layers'] if layer['visible'])
    selector = f'input[data-layer={json.dumps(name)}]'
    clicked = page.evaluate(f"(() => {{ const box = document.querySelector({json.dumps(selector)});"
                            " if (!box) return false; box.click(); return true; })()")
    if not clicked:
        raise Failure(f'no checkbox for layer {name!r} on the page')
    poll(lambda: any(layer['name'] == name and not layer['visible'] for layer in get_state(base)['layers']), 5,
         f'/state to report layer {name!r} hidden')
    print(f'layer {name!r} hidden through its checkbox')


def out_of_range_pitch(page, base):
    """Pitch 120 typed into the field (range -90..90) is refused on the page, naming the field, and never sent: the
    camera stays as it was (the server would take it as another pose)."""
    before = get_state(base)['camera']
    page.evaluate("""(() => {
        const field = document.getElementById('pitch');
        field.value = '120';
        field.dispatchEvent(new Event('input', {bubbles: true}));
        field.dispatchEvent(new Event('change', {bubbles: true}));
    })()""")
    said = page.wait_for("(() => { const s = document.getElementById('pose-status');"
                         " return s.classList.contains('error') && s.textContent; })()", 5, 'the page to refuse pitch 120')
    if 'Pitch' not in said or '120' not in said:
        raise Failure(f'the page refused pitch 120 without naming it: {said!r}')
    time.sleep(1.0)  # longer than the page's send delay
    after = get_state(base)['camera']
    if any(abs(after[key] - before[key]) > 1e-9 for key in ('yaw', 'pitch', 'roll')):
        raise Failure(f'pitch 120 was sent anyway: {before} became {after}')
    page.evaluate(f"""(() => {{
        const field = document.getElementById('pitch');
        field.value = '{before['pitch']}';
        field.dispatchEvent(new Event('change', {{bubbles: true}}));
    }})()""")
    print(f'pitch 120 refused on the page: {said!r}')


def shown_intrinsics(page, base, centred):
    """The page shows /state's intrinsics, those the camera draws with: cx, cy in [camera.pinhole]'s convention."""
    k = get_state(base)['camera']['intrinsics']
    shown = page.wait_for("(() => { const cx = document.getElementById('cx').textContent;"
                          " return cx && cx !== '–' && {cx, cy: document.getElementById('cy').textContent}; })()",
                          5, 'the intrinsics on the page')
    if abs(float(shown['cx']) - k['cx']) > 0.006 or abs(float(shown['cy']) - k['cy']) > 0.006:
        raise Failure(f'the page shows cx {shown["cx"]}, cy {shown["cy"]}; the camera uses {k["cx"]}, {k["cy"]}')
    width, height = get_state(base)['source']['width'], get_state(base)['source']['height']
    if centred and (abs(k['cx'] - (width - 1) / 2) > 1e-6 or abs(k['cy'] - (height - 1) / 2) > 1e-6):
        raise Failure(f'a centred camera shows cx {k["cx"]}, cy {k["cy"]}, not the image centre '
                      f'({(width - 1) / 2}, {(height - 1) / 2}) with pixel centres at integers')


def pose_value(base, key):
    camera = get_state(base)['camera']
    return camera['position']['xyz'.index(key)] if key in 'xyz' else camera[key]


def step_by_key(page, base, element, key, press, shift, expected_step):
    """Focuses `element` (a pose field or slider), presses an arrow key and waits for /state's `key` to move by
    expected_step: the page's own step (0.01 m, 0.1 degree; Shift ten times that), not the element's native one."""
    before = pose_value(base, key)
    page.evaluate(f"document.getElementById({json.dumps(element)}).focus()")
    page.press(press, shift=shift)
    target = round(before + expected_step, 6)
    poll(lambda: abs(pose_value(base, key) - target) < 1e-6, 5,
         f'{press}{" with Shift" if shift else ""} on #{element} to move {key} {before} -> {target}')


def fine_control(page, base):
    """Arrow keys step fields and sliders by 0.01 m / 0.1 degree, Shift by ten times that; "Fine sliders" narrows a
    position slider to +-1 m, so that a 20 px drag moves centimetres (it moved metres over +-20 m)."""
    step_by_key(page, base, 'x', 'x', 'ArrowUp', True, 0.1)
    step_by_key(page, base, 'x', 'x', 'ArrowDown', False, -0.01)
    step_by_key(page, base, 'yaw-slider', 'yaw', 'ArrowRight', True, 1.0)
    step_by_key(page, base, 'yaw-slider', 'yaw', 'ArrowLeft', False, -0.1)
    page.evaluate("document.getElementById('fine').click()")
    spans = page.evaluate("""(() => Object.fromEntries(['x', 'yaw'].map((key) => {
        const range = document.getElementById(key + '-slider');
        return [key, Number(range.max) - Number(range.min)]; })))()""")
    if abs(spans['x'] - 2) > 1e-9 or spans['yaw'] > 10 + 1e-9:
        raise Failure(f'fine sliders span {spans}, not x 2 m and yaw at most 10 degrees')
    time.sleep(1.6)  # the page's "being edited" window after the key presses: the drag below starts from the server's x
    before = pose_value(base, 'x')
    box = page.evaluate("""(() => { const r = document.getElementById('x-slider');
        r.scrollIntoView({block: 'center'}); return r.getBoundingClientRect().toJSON(); })()""")
    thumb = box['left'] + box['width'] * (before - float(page.evaluate("document.getElementById('x-slider').min"))) / 2
    page.drag(thumb, box['top'] + box['height'] / 2, 20)
    poll(lambda: abs(pose_value(base, 'x') - before) > 1e-9, 5, 'the fine x slider drag to move the camera')
    time.sleep(0.5)
    moved = abs(pose_value(base, 'x') - before)
    if moved > 0.5:  # 20 px of +-1 m, plus the thumb's half width if the press missed its centre
        raise Failure(f'a 20 px drag of the fine x slider ({box["width"]} px wide) moved x by {moved} m')
    page.evaluate("document.getElementById('fine').click()")
    print(f'keys: 0.01 m / 0.1 degree, Shift 10x; a 20 px fine drag moved x {moved:.3f} m')


def revert(page, base):
    """"Revert to the config" puts back the config's pose (/state camera.configured) after edits."""
    configured = get_state(base)['camera']['configured']
    if abs(get_state(base)['camera']['yaw'] - configured['yaw']) < 1e-6:
        set_yaw(page, base)
    page.evaluate("document.getElementById('revert').click()")
    poll(lambda: all(abs(get_state(base)['camera'][key] - configured[key]) < 1e-6 for key in ('yaw', 'pitch', 'roll'))
         and math.dist(get_state(base)['camera']['position'], configured['position']) < 1e-6, 5,
         f'the pose to go back to the config\'s {configured}')
    print(f'reverted to the config\'s pose {configured}')


def edit_lens(page, base):
    """The lens field edits the camera's own intrinsics key: a `fov` camera's field of view along its axis (the
    demo's vfov 50, then back), a `pinhole` camera's focal length (fx 10% longer with fy in proportion and the
    principal point kept, then back)."""
    label = page.wait_for("!document.getElementById('lens-form').hidden &&"
                          " document.getElementById('lens-label').textContent", 5, 'the lens field')
    k = get_state(base)['camera']['intrinsics']
    if k['form'] == 'fov':
        if 'Field of view' not in label or k['fov_axis'] not in label:
            raise Failure(f'the fov camera\'s lens field is labelled {label!r}')
        key = 'vfov' if k['fov_axis'] == 'vertical' else 'hfov'
        steps = [(50.0, lambda now: abs(now[key] - 50.0) < 1e-6), (k['fov'], lambda now: abs(now[key] - k[key]) < 1e-6)]
    else:
        if 'Focal length' not in label:
            raise Failure(f'the pinhole camera\'s lens field is labelled {label!r}')
        longer = round(k['fx'] * 1.1, 3)
        steps = [(longer, lambda now: abs(now['fx'] - longer) < 1e-6 and abs(now['fy'] / now['fx'] - k['fy'] / k['fx'])
                  < 1e-6 and abs(now['cx'] - k['cx']) < 1e-6 and abs(now['cy'] - k['cy']) < 1e-6),
                 (k['fx'], lambda now: abs(now['fx'] - k['fx']) < 1e-3)]
    for value, reached in steps:
        page.evaluate(f"""(() => {{
            const field = document.getElementById('lens');
            field.value = '{value}';
            field.dispatchEvent(new Event('change', {{bubbles: true}}));
        }})()""")
        poll(lambda: reached(get_state(base)['camera']['intrinsics']), 5, f'the lens field\'s {value} to apply')
    print(f'lens field {label!r}: {steps[0][0]} applied, then {steps[1][0]}')


GROUND_MARKS = [(-2.0, 0.0, 0.0), (2.0, 0.0, 0.0), (-3.0, 6.0, 0.0), (3.0, 6.0, 0.0), (0.0, 12.0, 0.0),
                (1.0, 3.0, 0.0)]


def click_pixel_actual_size(page, u, v):
    """In the 1:1 view: scrolls the frame to image pixel (u, v) and clicks that pixel's centre."""
    box = page.evaluate(f"""(() => {{
        const frame = document.getElementById('frame');
        frame.scrollIntoView({{block: 'start'}});
        frame.scrollLeft = {u} - frame.clientWidth / 2;
        frame.scrollTop = {v} - frame.clientHeight / 2;
        return document.getElementById('stream').getBoundingClientRect().toJSON(); }})()""")
    page.click(box['left'] + u + 0.5, box['top'] + v + 0.5)


def collect_points(page, base, overlayd, config, workdir):
    """The 1:1 view shows one image pixel per CSS pixel, so clicks land on the pixels meant; the clicked points,
    given their world coordinates, download as a CSV that `overlayd solve-pose` reads and solves back to the live
    pose."""
    page.evaluate("document.getElementById('points-clear').click()")
    page.evaluate("document.getElementById('zoom').click()")
    width = page.evaluate("document.getElementById('stream').getBoundingClientRect().width")
    natural = page.evaluate("document.getElementById('stream').naturalWidth")
    if abs(width - natural) > 0.5:
        raise Failure(f'the 1:1 view shows the {natural} px image {width} px wide')
    query = ';'.join(','.join(str(c) for c in p) for p in GROUND_MARKS)
    state = get_state(base)['source']
    projected = [p for p in json.loads(http(base, '/api/project?points=' + query)[0])
                 if p['visible'] and 0 <= p['pixel'][0] <= state['width'] - 1 and 0 <= p['pixel'][1] <= state['height'] - 1]
    if len(projected) < 4:
        raise Failure(f'only {len(projected)} of the ground marks {GROUND_MARKS} are in the frame: too few to solve')
    for n, point in enumerate(projected, 1):
        u, v = (round(c) for c in point['pixel'])
        click_pixel_actual_size(page, u, v)
        shown = page.wait_for(f"document.querySelectorAll('#click-results li').length === {n} &&"
                              " document.querySelector('#click-results li').dataset.pixel", 5, f'click {n}')
        got = [float(c) for c in shown.split(',')]
        if math.dist(got, (u, v)) > 0.05:
            raise Failure(f'in the 1:1 view a click on pixel ({u}, {v}) gave {got}')
        world = point['world']
        page.evaluate(f"""(() => {{
            const inputs = document.querySelectorAll('#click-results li:first-child input[data-axis]');
            {json.dumps(world)}.forEach((value, i) => {{
                inputs[i].value = String(value);
                inputs[i].dispatchEvent(new Event('input', {{bubbles: true}}));
            }}); }})()""")
    page.evaluate("document.getElementById('zoom').click()")
    href = page.evaluate("document.getElementById('points-download').href")
    prefix = 'data:text/csv;charset=utf-8,'
    if not href.startswith(prefix):
        raise Failure(f'the points link is {href[:80]!r}, not a CSV')
    csv_text = urllib.parse.unquote(href[len(prefix):])
    points = os.path.join(workdir, 'points.csv')
    open(points, 'w').write(csv_text)
    if csv_text.count('\n') != len(projected) + 1:
        raise Failure(f'the points file has not a header and {len(projected)} rows:\n{csv_text}')
    solved = subprocess.run([overlayd, 'solve-pose', '--config', config, '--points', points],
                            capture_output=True, text=True, timeout=60)
    if solved.returncode != 0:
        raise Failure(f'solve-pose refused the page\'s points ({solved.returncode}): {solved.stderr}\n{csv_text}')
    found = re.search(r'# position = \[([^\]]*)\]\s*# yaw = (\S+)\s*# pitch = (\S+)', solved.stdout)
    if not found:
        raise Failure(f'no pose in solve-pose\'s output:\n{solved.stdout}')
    position = [float(c) for c in found.group(1).split(',')]
    camera = get_state(base)['camera']
    if math.dist(position, camera['position']) > 0.05 or abs(float(found.group(2)) - camera['yaw']) > 0.2 or \
            abs(float(found.group(3)) - camera['pitch']) > 0.2:
        raise Failure(f'solve-pose on the page\'s points gave {found.group(0)!r}; the camera is {camera}')
    print(f'{len(projected)} points clicked in the 1:1 view solve back to the pose: {found.group(0)!r}')


def token_flow(args, workdir, cleanup, browser):
    """With control = "token": a click on the image gives its ground point without the token (it changes nothing);
    a pose edit asks for the token over the page, moving none of the controls, and the form goes once it worked."""
    port = daemon_fixture.free_port()
    token_file = os.path.join(workdir, 'token')
    open(token_file, 'w').write('browser-token\n')
    path = os.path.join(workdir, 'overlayd-token.toml')
    with open(path, 'w') as file:
        file.write(daemon_fixture.config_without_sinks(args.config) +
                   daemon_fixture.http_section(port, control='token', token_file=token_file))
    daemon = daemon_fixture.Daemon(args.overlayd, path, workdir, port, cwd=workdir)
    cleanup.append(daemon.stop)
    daemon.wait_ready(20)
    page = Page(browser.browser_url(20), timeout=10)
    cleanup.append(page.close)
    open_page(page, daemon.base)
    page.evaluate("sessionStorage.clear()")
    click_centre(page, daemon.base)
    if not page.evaluate("document.getElementById('token-form').hidden"):
        raise Failure('a click on the image asked for the control token')
    top = page.evaluate("document.getElementById('pose-title').getBoundingClientRect().top")
    set_field = """(() => {
        const field = document.getElementById('yaw');
        field.value = '95';
        field.dispatchEvent(new Event('input', {bubbles: true}));
        field.dispatchEvent(new Event('change', {bubbles: true}));
    })()"""
    page.evaluate(set_field)
    page.wait_for("!document.getElementById('token-form').hidden", 5, 'the page to ask for the token')
    moved = page.evaluate("document.getElementById('pose-title').getBoundingClientRect().top") - top
    if abs(moved) > 1:
        raise Failure(f'the token form pushed the pose controls {moved} px down')
    page.evaluate("""(() => {
        document.getElementById('token').value = 'browser-token';
        document.getElementById('token-form').requestSubmit();
    })()""")
    poll(lambda: abs(get_state(daemon.base)['camera']['yaw'] - 95) < 1e-6, 5, 'the pose edit sent with the token')
    page.wait_for("document.getElementById('token-form').hidden", 5, 'the token form to go once the token worked')
    if page.problems:
        raise Failure('the page with control = "token" ran into errors:\n' + '\n'.join(map(str, page.problems)))
    print('token: a click needs none; an edit asked for it over the page, and the form went once it worked')


def check_narrow(page, workdir):
    page.call('Emulation.setDeviceMetricsOverride', width=360, height=800, deviceScaleFactor=1, mobile=True)
    overflow = page.wait_for('(() => { void document.body.offsetWidth;'
                             ' return {scroll: document.documentElement.scrollWidth, view: innerWidth}; })()',
                             5, 'the narrow layout')
    page.screenshot(os.path.join(workdir, 'page-narrow.png'))
    if overflow['scroll'] > overflow['view'] + 1:
        raise Failure(f'at 360 px wide the page scrolls sideways ({overflow["scroll"]} px of content)')


def run(args, workdir, cleanup):
    daemon = start_daemon(args, workdir, cleanup)
    base = daemon.base

    browser = Chromium(args.chromium, os.path.join(workdir, 'chrome'), os.path.join(workdir, 'chromium.log'))
    cleanup.append(browser.stop)
    page = Page(browser.browser_url(20), timeout=10)
    cleanup.append(page.close)

    open_page(page, base)
    change_yaw(page, base, workdir)
    click_centre(page, base)
    hide_layer(page, base)
    out_of_range_pitch(page, base)
    fine_control(page, base)
    revert(page, base)
    edit_lens(page, base)
    collect_points(page, base, args.overlayd, os.path.join(workdir, 'overlayd.toml'), workdir)
    shown_intrinsics(page, base, args.config == os.path.abspath(daemon_fixture.DEMO))
    check_narrow(page, workdir)
    if page.problems:
        raise Failure('the page ran into errors:\n' + '\n'.join(map(str, page.problems)))
    token_flow(args, workdir, cleanup, browser)
    if page.problems:
        raise Failure('the page ran into errors:\n' + '\n'.join(map(str, page.problems)))
    if daemon.process.poll() is not None:
        raise Failure(f'overlayd exited with {daemon.process.returncode} during the test:\n{daemon.log_tail()}')


def on_alarm(signum, frame):
    raise Failure('the test ran out of time')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--overlayd', required=True)
    parser.add_argument('--config', default=daemon_fixture.DEMO)
    parser.add_argument('--workdir', required=True)
    parser.add_argument('--chromium', default='/usr/bin/chromium')
    parser.add_argument('--timeout', type=int, default=90)
    args = parser.parse_args()
    for tool in (args.overlayd, args.chromium, shutil.which('ffmpeg'), shutil.which('ffprobe')):
        if not tool or not os.access(tool, os.X_OK):
            print(f'browser_test: set-up: {tool or "ffmpeg/ffprobe"} is not an executable', file=sys.stderr)
            return 2
    workdir = os.path.abspath(args.workdir)
    shutil.rmtree(os.path.join(workdir, 'chrome'), ignore_errors=True)  # a stale profile from an earlier run
    os.makedirs(workdir, exist_ok=True)
    args.overlayd, args.config = os.path.abspath(args.overlayd), os.path.abspath(args.config)

    cleanup = []
    signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(args.timeout)
    try:
        run(args, workdir, cleanup)
    except AssertionError as error:  # a Failure, or daemon_fixture's: overlayd died or never served /state
        print(f'browser_test: FAIL: {error}', file=sys.stderr)
        return 1
    except Exception as error:  # the browser, HTTP or ffmpeg broke: still a failure, named by its type
        print(f'browser_test: FAIL: {type(error).__name__}: {error}', file=sys.stderr)
        return 1
    finally:
        signal.alarm(0)
        for step in reversed(cleanup):
            step()
    print(f'browser_test: PASS (screenshots in {workdir})')
    return 0


if __name__ == '__main__':
    sys.exit(main())
