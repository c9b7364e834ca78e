// SPDX-License-Identifier: Apache-2.0
// The alignment page's logic: pose sliders -> PUT /api/camera, layer toggles, click-to-ground, save, and a /state
// poll that never overwrites what the user is editing. Plain browser JS: the daemon serves only its four files
// (live_view.js, loaded first, holds the picture: WebRTC or MJPEG).
'use strict';

const POSE_KEYS = ['x', 'y', 'z', 'yaw', 'pitch', 'roll'];
const POSITION_KEYS = ['x', 'y', 'z'];
const POSITION_SPAN_M = 20; // a position slider reaches this far either side of the value it was centred on
const FINE_SPAN_M = 1; // ... and this far in fine mode: a 20 px drag moves centimetres, not metres
const FINE_SPAN_DEG = 5; // an angle slider's reach in fine mode, either side of the value it was centred on
const STEP_M = 0.01; // an arrow key's step; Shift multiplies it by COARSE_FACTOR
const STEP_DEG = 0.1;
const COARSE_FACTOR = 10;
const POSE_SEND_DELAY_MS = 100; // a slider drag becomes ten requests a second, not one per pixel
const STATE_PERIOD_MS = 2000;
const RECENT_INPUT_MS = 1500; // a control touched this recently still counts as being edited
const STREAM_RETRY_MS = 2000;
const MAX_CLICKS = 32; // enough points for solve-pose (it needs 4 or more)
const TOKEN_KEY = 'overlayd.token';

const $ = (id) => document.getElementById(id);

// ---- HTTP ----------------------------------------------------------------------------------------------------

class ApiError extends Error {
    constructor(status, message) {
        super(message);
        this.status = status;
    }
}

async function api(method, path, body) {
    const headers = {};
    const token = sessionStorage.getItem(TOKEN_KEY);
    if (token) headers.Authorization = `Bearer ${token}`;
    if (body !== undefined) headers['Content-Type'] = 'application/json';
    let response;
    try {
        response = await fetch(path, {
            method, headers, cache: 'no-store', body: body === undefined ? undefined : JSON.stringify(body),
        });
    } catch (error) {
        throw new ApiError(0, 'the server is unreachable');
    }
    const text = await response.text();
    let data = null;
    try {
        data = text ? JSON.parse(text) : null;
    } catch (error) {
        data = null; // an error page from a proxy, say: the status line below still explains it
    }
    if (!response.ok) {
        const message = data && typeof data.error === 'string' ? data.error : `${response.status} ${response.statusText}`;
        throw new ApiError(response.status, message);
    }
    return data;
}

// A control request: a 401 asks for the token and tries again with it, so no edit is lost while the user types it.
async function control(method, path, body) {
    for (let attempt = 0; ; ++attempt) {
        try {
            const answer = await api(method, path, body);
            if (attempt > 0) $('token-form').hidden = true; // the token worked: the form goes away
            return answer;
        } catch (error) {
            if (error.status !== 401) throw error;
            await askForToken(attempt > 0 || sessionStorage.getItem(TOKEN_KEY) !== null);
        }
    }
}

// ---- Token ---------------------------------------------------------------------------------------------------

const tokenWaiters = [];

function askForToken(refused) {
    const form = $('token-form');
    form.hidden = false;
    $('token-hint').textContent = refused
        ? 'The server refused this token; enter the control token again.'
        : 'The server needs its control token for changes.';
    $('token').focus();
    return new Promise((resolve) => tokenWaiters.push(resolve));
}

function setUpToken() {
    const form = $('token-form');
    form.hidden = true; // shown when a change needs the token (a 401), hidden again once the token works
    form.addEventListener('submit', (event) => {
        event.preventDefault();
        const token = $('token').value.trim();
        if (!token) return;
        sessionStorage.setItem(TOKEN_KEY, token);
        $('token').value = '';
        $('token-hint').textContent = 'Token kept for this tab.';
        tokenWaiters.splice(0).forEach((resolve) => resolve());
    });
    $('token-forget').addEventListener('click', () => {
        sessionStorage.removeItem(TOKEN_KEY);
        $('token').value = '';
        $('token-hint').textContent = 'Token forgotten.';
    });
}

// ---- Sending the newest value --------------------------------------------------------------------------------

// At most one request in flight; edits made meanwhile collapse into one follow-up carrying the newest value. The
// delay starts at the first edit and is not restarted by later ones, so a long slider drag still moves the overlay
// every delayMs instead of only when the hand stops.
class LatestSender {
    constructor(delayMs, send) {
        this.delayMs = delayMs;
        this.send = send;
        this.timer = null;
        this.inFlight = false;
        this.again = false;
    }

    get busy() { return this.timer !== null || this.inFlight || this.again; }

    // A newer value exists than the one the request in flight carries: its answer is stale.
    get superseded() { return this.timer !== null || this.again; }

    // Resolves once the newest value has been answered: Save must write what the user set last.
    async settled() {
        while (this.busy) await new Promise((resolve) => setTimeout(resolve, 50));
    }

    touch() {
        if (this.timer === null) this.timer = setTimeout(() => this.fire(), this.delayMs);
    }

    async fire() {
        this.timer = null;
        if (this.inFlight) {
            this.again = true;
            return;
        }
        this.inFlight = true;
        try {
            await this.send();
        } finally {
            this.inFlight = false;
            if (this.again) {
                this.again = false;
                if (this.timer === null) this.fire();
            }
        }
    }
}

function setStatus(id, text, isError = false) {
    const element = $(id);
    element.textContent = text;
    element.classList.toggle('error', isError);
}

// ---- Camera pose ---------------------------------------------------------------------------------------------

const lastInputAt = new Map();
const poseSender = new LatestSender(POSE_SEND_DELAY_MS, sendPose);

const number = (key) => $(key);
const slider = (key) => $(`${key}-slider`);
const round = (value, digits) => String(Number(value.toFixed(digits)));

function isBeingEdited(element, key) {
    return document.activeElement === element || Date.now() - (lastInputAt.get(key) || 0) < RECENT_INPUT_MS;
}

const fine = () => $('fine').checked;

// A slider's reach around `value`: +-20 m for a position (+-1 m fine); an angle's whole range, or +-5 degrees fine,
// kept inside the field's own limits.
function centreSlider(key, value) {
    const range = slider(key);
    if (POSITION_KEYS.includes(key)) {
        const span = fine() ? FINE_SPAN_M : POSITION_SPAN_M;
        range.min = round(value - span, 2);
        range.max = round(value + span, 2);
        return;
    }
    const field = number(key);
    const low = Number(field.min), high = Number(field.max);
    range.min = fine() ? round(Math.max(low, value - FINE_SPAN_DEG), 1) : field.min;
    range.max = fine() ? round(Math.min(high, value + FINE_SPAN_DEG), 1) : field.max;
}

// Sliders re-centre only when the value leaves their reach, so the thumb does not jump after a drag.
function placeSlider(key, value) {
    const range = slider(key);
    const outside = range.min === '' || value < Number(range.min) || value > Number(range.max);
    if (outside) centreSlider(key, value);
    range.value = String(value);
}

function recentreSliders() {
    for (const key of POSE_KEYS) {
        const value = number(key).valueAsNumber;
        if (!Number.isFinite(value)) continue;
        centreSlider(key, value);
        slider(key).value = String(value);
    }
}

// Up/Down (and Left/Right on a slider) step by 0.01 m or 0.1 degree, Shift by ten times that: the same on the
// field and the slider, whatever the slider's reach.
function onPoseKey(key, event) {
    const direction = {ArrowUp: 1, ArrowRight: 1, ArrowDown: -1, ArrowLeft: -1}[event.key];
    if (!direction || event.altKey || event.ctrlKey || event.metaKey) return;
    if (event.target.type === 'number' && (event.key === 'ArrowLeft' || event.key === 'ArrowRight')) return; // the caret
    const field = number(key);
    if (!Number.isFinite(field.valueAsNumber)) return;
    event.preventDefault();
    const position = POSITION_KEYS.includes(key);
    const step = (position ? STEP_M : STEP_DEG) * (event.shiftKey ? COARSE_FACTOR : 1);
    let value = field.valueAsNumber + direction * step;
    if (field.min !== '') value = Math.max(Number(field.min), value);
    if (field.max !== '') value = Math.min(Number(field.max), value);
    field.value = round(value, position ? 4 : 3);
    onPoseInput(key, false);
}

// The pose in the fields, or why it is not sent: a value outside its field's range is refused here, named, rather
// than sent and come back as another pose (pitch 120 is the same camera as yaw - 180, pitch 60, roll 180).
function readPose() {
    const values = POSE_KEYS.map((key) => number(key).valueAsNumber);
    if (values.some((value) => !Number.isFinite(value))) return {error: 'Every pose field needs a number.'};
    for (const key of POSE_KEYS) {
        const field = number(key), value = field.valueAsNumber;
        const min = field.min === '' ? -Infinity : Number(field.min), max = field.max === '' ? Infinity : Number(field.max);
        if (value < min || value > max) {
            const name = key.length === 1 ? key : key[0].toUpperCase() + key.slice(1);
            return {error: `${name} ${value} is outside ${field.min}..${field.max}: not sent.`};
        }
    }
    const [x, y, z, yaw, pitch, roll] = values;
    return {pose: {position: [x, y, z], yaw, pitch, roll}};
}

async function sendPose() {
    const {pose: body, error} = readPose();
    if (error) {
        setStatus('pose-status', error, true);
        return;
    }
    try {
        const camera = await control('PUT', '/api/camera', body);
        setStatus('pose-status', 'Pose applied.');
        if (!poseSender.superseded) showCamera(camera, false);
    } catch (error) {
        setStatus('pose-status', error.message, true);
    }
}

function onPoseInput(key, fromSlider) {
    lastInputAt.set(key, Date.now());
    if (fromSlider) {
        number(key).value = slider(key).value;
    } else if (Number.isFinite(number(key).valueAsNumber)) {
        placeSlider(key, number(key).valueAsNumber);
    }
    poseSender.touch();
}

function setUpPose() {
    for (const key of POSE_KEYS) {
        slider(key).addEventListener('input', () => onPoseInput(key, true));
        number(key).addEventListener('input', () => onPoseInput(key, false));
        number(key).addEventListener('change', () => onPoseInput(key, false));
        number(key).addEventListener('keydown', (event) => onPoseKey(key, event));
        slider(key).addEventListener('keydown', (event) => onPoseKey(key, event));
    }
    $('fine').addEventListener('change', recentreSliders);
    $('revert').addEventListener('click', revertPose);
    $('pose').addEventListener('submit', (event) => event.preventDefault()); // Enter in a field must not reload
}

// The pose the config file gave (with its saved live pose, if any), as /state reports it; null before the first poll.
let configuredPose = null;

// Back to the config's pose: the fields take it and it is sent like any edit (Save then writes it).
function revertPose() {
    if (!configuredPose) {
        setStatus('pose-status', 'The config\'s pose is not known yet.', true);
        return;
    }
    const values = {
        x: configuredPose.position[0], y: configuredPose.position[1], z: configuredPose.position[2],
        yaw: configuredPose.yaw, pitch: configuredPose.pitch, roll: configuredPose.roll,
    };
    for (const key of POSE_KEYS) {
        number(key).value = round(values[key], POSITION_KEYS.includes(key) ? 4 : 3);
        lastInputAt.set(key, Date.now());
        placeSlider(key, values[key]);
    }
    poseSender.touch();
}

// fromPoll: a /state poll must not undo edits still on their way to the server.
function showCamera(camera, fromPoll) {
    if (!camera || !Array.isArray(camera.position)) return;
    if (camera.configured && Array.isArray(camera.configured.position)) configuredPose = camera.configured;
    if (fromPoll && poseSender.busy) return;
    const values = {
        x: camera.position[0], y: camera.position[1], z: camera.position[2],
        yaw: camera.yaw, pitch: camera.pitch, roll: camera.roll,
    };
    for (const key of POSE_KEYS) {
        if (typeof values[key] !== 'number' || isBeingEdited(number(key), key)) continue;
        number(key).value = round(values[key], POSITION_KEYS.includes(key) ? 4 : 3);
        placeSlider(key, values[key]);
    }
    showIntrinsics(camera.intrinsics);
}

// The lens field edits the intrinsics key the camera has: its field of view (along its fov_axis) for `fov`, the
// focal length in pixels for `pinhole` (fy keeps its ratio to fx; the principal point and skew stay).
let lensForm = null;
let shownIntrinsics = null;

function showLens(intrinsics) {
    shownIntrinsics = intrinsics;
    lensForm = intrinsics.form === 'fov' || intrinsics.form === 'pinhole' ? intrinsics.form : null;
    $('lens-form').hidden = lensForm === null;
    if (lensForm === null) return;
    $('lens-label').textContent = lensForm === 'fov' ? `Field of view (°, ${intrinsics.fov_axis})` : 'Focal length fx (px)';
    const field = $('lens');
    field.max = lensForm === 'fov' ? '179' : '';
    if (isBeingEdited(field, 'lens')) return;
    field.value = round(lensForm === 'fov' ? intrinsics.fov : intrinsics.fx, 3);
}

async function sendLens() {
    const value = $('lens').valueAsNumber;
    const k = shownIntrinsics;
    if (!Number.isFinite(value) || value <= 0 || !k || lensForm === null) {
        setStatus('lens-status', 'The lens needs a number above 0.', true);
        return;
    }
    const body = lensForm === 'fov' ? {fov: value}
        : {pinhole: {fx: value, fy: value * k.fy / k.fx, cx: k.cx, cy: k.cy, skew: k.skew}};
    try {
        const camera = await control('PUT', '/api/camera', body);
        setStatus('lens-status', 'Lens applied.');
        showIntrinsics(camera.intrinsics);
    } catch (error) {
        setStatus('lens-status', error.message, true);
    }
}

function setUpLens() {
    $('lens').addEventListener('change', () => {
        lastInputAt.set('lens', Date.now());
        sendLens();
    });
    $('lens-form').addEventListener('submit', (event) => event.preventDefault());
}

function showIntrinsics(intrinsics) {
    if (!intrinsics) return;
    showLens(intrinsics);
    for (const key of ['fx', 'fy', 'cx', 'cy']) {
        if (typeof intrinsics[key] === 'number') $(key).textContent = intrinsics[key].toFixed(2);
    }
    if (typeof intrinsics.hfov === 'number') $('hfov').textContent = `${intrinsics.hfov.toFixed(2)}°`;
}

// ---- Save ----------------------------------------------------------------------------------------------------

function describeSave(answer) {
    const file = answer && (answer.saved || answer.path);
    if (typeof file === 'string') return `Saved to ${file}`;
    return answer ? `Saved: ${JSON.stringify(answer)}` : 'Saved.';
}

function setUpSave() {
    $('save').addEventListener('click', async () => {
        $('save').disabled = true;
        setStatus('save-status', 'Saving…');
        try {
            await poseSender.settled();
            setStatus('save-status', describeSave(await control('POST', '/api/save', {})));
        } catch (error) {
            setStatus('save-status', error.message, true);
        } finally {
            $('save').disabled = false;
        }
    });
}

// ---- Layers --------------------------------------------------------------------------------------------------

const layerSenders = new Map();

function layerSender(name, checkbox) {
    if (!layerSenders.has(name)) {
        layerSenders.set(name, new LatestSender(0, async () => {
            const visible = checkbox.checked;
            try {
                await control('PUT', `/api/layers/${encodeURIComponent(name)}`, {visible});
                setStatus('layers-status', `${name}: ${visible ? 'shown' : 'hidden'}.`);
            } catch (error) {
                setStatus('layers-status', `${name}: ${error.message}`, true);
            }
        }));
    }
    return layerSenders.get(name);
}

function buildLayers(box, layers) {
    box.replaceChildren();
    layerSenders.clear();
    layers.forEach((layer, index) => {
        const checkbox = document.createElement('input');
        checkbox.type = 'checkbox';
        checkbox.id = `layer-${index}`;
        checkbox.dataset.layer = layer.name;
        checkbox.addEventListener('change', () => {
            lastInputAt.set(`layer:${layer.name}`, Date.now());
            layerSender(layer.name, checkbox).touch();
        });
        const label = document.createElement('label');
        label.htmlFor = checkbox.id;
        label.textContent = layer.name;
        const row = document.createElement('div');
        row.className = 'layer';
        row.append(checkbox, label);
        box.append(row);
    });
}

function showLayers(layers) {
    if (!Array.isArray(layers)) return;
    const box = $('layers');
    const names = layers.map((layer) => layer.name).join('\n');
    if (box.dataset.names !== names) {
        buildLayers(box, layers);
        box.dataset.names = names;
    }
    for (const layer of layers) {
        const checkbox = box.querySelector(`input[data-layer="${CSS.escape(layer.name)}"]`);
        const sender = layerSenders.get(layer.name);
        if ((sender && sender.busy) || isBeingEdited(null, `layer:${layer.name}`)) continue;
        checkbox.checked = Boolean(layer.visible);
    }
}

// ---- Clicking the image: pixel -> ground ---------------------------------------------------------------------

const clicks = []; // {n, cornerX, cornerY}: corner-based image coordinates, so marks survive a resize
let clickCount = 0;
let frameSize = {width: 0, height: 0, origin: 'top-left'};

const liveView = new LiveView($('stream'), $('video'), $('transport'));

// The stream's own pixels: the <img>'s natural size or the <video>'s videoWidth x videoHeight.
function imageSize() {
    const size = liveView.size();
    if (size.width > 0 && size.height > 0) return size;
    return frameSize; // no frame decoded yet: /state knows the source's size
}

// Where the picture is drawn inside the element: its content box, letterboxed by object-fit: contain.
function pictureRect(img) {
    const rect = img.getBoundingClientRect();
    const style = getComputedStyle(img);
    const px = (name) => parseFloat(style[name]) || 0;
    const left = rect.left + px('borderLeftWidth') + px('paddingLeft');
    const top = rect.top + px('borderTopWidth') + px('paddingTop');
    const width = rect.width - px('borderLeftWidth') - px('paddingLeft') - px('borderRightWidth') - px('paddingRight');
    const height = rect.height - px('borderTopWidth') - px('paddingTop') - px('borderBottomWidth') - px('paddingBottom');
    const size = imageSize();
    if (!size.width || !size.height || width <= 0 || height <= 0) return null;
    const scale = Math.min(width / size.width, height / size.height);
    return {
        left: left + (width - size.width * scale) / 2, top: top + (height - size.height * scale) / 2,
        scale, width: size.width, height: size.height,
    };
}

// Pixel centres sit at integers (projection/viewport.h), so the corner-based position is the pixel + 0.5.
function toPixel(cornerX, cornerY, height) {
    const u = cornerX - 0.5;
    const fromTop = cornerY - 0.5;
    return [u, frameSize.origin === 'bottom-left' ? height - 1 - fromTop : fromTop];
}

function describeHit(result) {
    if (!result) return 'no answer';
    if (Array.isArray(result.hit)) {
        const [x, y] = result.hit;
        return `ground x ${x.toFixed(2)} m, y ${y.toFixed(2)} m`;
    }
    return `no ground point${result.reason ? ` (${result.reason})` : ''}`;
}

// The world point a click is of: its ground point to start with, corrected by the user to the mark they clicked.
function worldInputs(n, hit) {
    const box = document.createElement('span');
    box.className = 'world';
    ['x', 'y', 'z'].forEach((axis, i) => {
        const input = document.createElement('input');
        input.type = 'number';
        input.step = '0.01';
        input.dataset.axis = axis;
        input.setAttribute('aria-label', `point ${n} world ${axis} (m)`);
        input.value = hit ? String(Number(hit[i].toFixed(3))) : '';
        input.addEventListener('input', updatePointsFile);
        box.append(` ${axis} `, input);
    });
    return box;
}

// The clicked points as solve-pose reads them (alignment/points_file.h): a header row, then x,y,z,u,v per point.
function pointsCsv() {
    const rows = ['x,y,z,u,v'];
    for (const item of [...$('click-results').children].reverse()) {
        const world = [...item.querySelectorAll('input[data-axis]')].map((input) => input.valueAsNumber);
        if (world.length !== 3 || !world.every(Number.isFinite)) continue;
        rows.push([...world, ...item.dataset.pixel.split(',').map(Number)].join(','));
    }
    return rows.join('\n') + '\n';
}

function updatePointsFile() {
    const csv = pointsCsv();
    const link = $('points-download');
    link.href = `data:text/csv;charset=utf-8,${encodeURIComponent(csv)}`;
    link.dataset.points = String(csv.split('\n').length - 2);
}

function addClickResult(n, pixel, result, text, isError) {
    const item = document.createElement('li');
    item.value = n;
    item.className = isError ? 'error' : 'hit';
    item.dataset.pixel = pixel.join(','); // machine-readable twins of the text, for tests and scripts
    const hit = !isError && result && Array.isArray(result.hit) ? result.hit : null;
    if (hit) item.dataset.hit = hit.join(',');
    item.append(`pixel (${pixel[0].toFixed(1)}, ${pixel[1].toFixed(1)}): ${text}; world`, worldInputs(n, hit));
    const list = $('click-results');
    list.prepend(item);
    while (list.children.length > MAX_CLICKS) list.lastElementChild.remove();
    updatePointsFile();
}

async function onImageClick(event) {
    const img = liveView.element();
    const picture = pictureRect(img);
    if (!picture) return;
    // Whole mouse coordinates name the CSS pixel under the pointer: its centre is half a pixel on (in the 1:1 view,
    // the image pixel's centre).
    const centre = (value) => (Number.isInteger(value) ? value + 0.5 : value);
    const cornerX = (centre(event.clientX) - picture.left) / picture.scale;
    const cornerY = (centre(event.clientY) - picture.top) / picture.scale;
    if (cornerX < 0 || cornerY < 0 || cornerX > picture.width || cornerY > picture.height) return; // letterbox
    const n = ++clickCount;
    clicks.unshift({n, cornerX, cornerY});
    clicks.length = Math.min(clicks.length, MAX_CLICKS);
    drawMarks();
    const pixel = toPixel(cornerX, cornerY, picture.height).map((value) => Number(value.toFixed(2)));
    try {
        const answer = await control('POST', '/api/unproject', {pixels: [pixel]});
        const result = Array.isArray(answer) ? answer[0] : null;
        addClickResult(n, pixel, result, describeHit(result), false);
    } catch (error) {
        addClickResult(n, pixel, null, error.message, true);
    }
}

function drawMarks() {
    const img = liveView.element();
    const canvas = $('marks');
    const ratio = window.devicePixelRatio || 1;
    canvas.style.width = `${img.clientWidth}px`; // the image's size in either view
    canvas.style.height = `${img.clientHeight}px`;
    canvas.width = Math.round(img.clientWidth * ratio);
    canvas.height = Math.round(img.clientHeight * ratio);
    const context = canvas.getContext('2d');
    context.clearRect(0, 0, canvas.width, canvas.height);
    const picture = pictureRect(img);
    if (!picture) return;
    const box = img.getBoundingClientRect();
    context.scale(ratio, ratio);
    context.lineWidth = 2;
    context.font = '14px system-ui, sans-serif';
    for (const click of clicks) {
        const x = picture.left - box.left + click.cornerX * picture.scale;
        const y = picture.top - box.top + click.cornerY * picture.scale;
        context.strokeStyle = context.fillStyle = click.n === clickCount ? '#ff3b30' : '#ffcc00';
        context.beginPath();
        context.arc(x, y, 7, 0, 2 * Math.PI);
        context.moveTo(x - 12, y); context.lineTo(x + 12, y);
        context.moveTo(x, y - 12); context.lineTo(x, y + 12);
        context.stroke();
        context.fillText(String(click.n), x + 10, y - 10);
    }
}

// 1:1: the frame shows the image at its own size, scrolled, so one CSS pixel is one image pixel.
function toggleZoom() {
    const actual = $('frame').classList.toggle('actual-size');
    $('zoom').setAttribute('aria-pressed', String(actual));
    $('zoom').textContent = actual ? 'Fit view' : '1:1 view';
    drawMarks();
}

function setUpImage() {
    const img = $('stream');
    for (const element of [img, $('video')]) {
        element.addEventListener('click', onImageClick);
        element.addEventListener('picture', drawMarks); // the picture moved between the two
        new ResizeObserver(drawMarks).observe(element);
    }
    $('zoom').addEventListener('click', toggleZoom);
    $('points-clear').addEventListener('click', () => {
        $('click-results').replaceChildren();
        clicks.length = 0;
        drawMarks();
        updatePointsFile();
    });
    updatePointsFile();
    // "load" never fires for an MJPEG stream; "error" does when the connection drops, so reconnect.
    img.addEventListener('error', () => setTimeout(() => {
        if (liveView.kind !== 'mjpeg') return;
        img.removeAttribute('src');
        img.src = '/stream';
    }, STREAM_RETRY_MS));
}

// ---- State poll ----------------------------------------------------------------------------------------------

function formatUptime(seconds) {
    const s = Math.floor(seconds);
    const h = Math.floor(s / 3600);
    const m = Math.floor((s % 3600) / 60);
    return h ? `${h} h ${m} min` : m ? `${m} min ${s % 60} s` : `${s} s`;
}

function showSource(source) {
    if (!source) return;
    frameSize = {...frameSize, width: source.width || 0, height: source.height || 0};
    if (source.width && source.height) $('frame').style.aspectRatio = `${source.width} / ${source.height}`;
    $('source-state').textContent = `${source.kind} ${source.state}, ${source.width}×${source.height} ${source.format}`;
    const measured = typeof source.fps_measured === 'number' ? source.fps_measured.toFixed(2) : '–';
    $('source-fps').textContent = `${measured} (nominal ${source.fps})`;
    $('source-frames').textContent = String(source.frames);
}

function showHttp(http) {
    const connections = http.connections ?? http.clients;
    if (typeof connections !== 'number') return;
    const watching = typeof http.stream_clients === 'number' ? ` (${http.stream_clients} watching the stream)` : '';
    $('http-clients').textContent = `${connections} connections${watching}`;
}

function showState(state) {
    showSource(state.source);
    const origin = (state.camera && state.camera.origin) || (state.viewport && state.viewport.origin);
    if (origin) frameSize.origin = origin;
    showCamera(state.camera, true);
    showLayers(state.layers);
    if (state.http) showHttp(state.http);
    if (typeof state.uptime_s === 'number') $('uptime').textContent = formatUptime(state.uptime_s);
}

async function pollState() {
    try {
        const state = await api('GET', '/state');
        liveView.choose(state);
        showState(state);
        setStatus('connection', 'Connected.');
        document.body.dataset.ready = 'true'; // what tests wait for: the controls hold the server's values
    } catch (error) {
        setStatus('connection', `No state: ${error.message}`, true);
        liveView.choose({}); // no word of a WebRTC sink: MJPEG, which retries by itself
    }
    setTimeout(pollState, STATE_PERIOD_MS);
}

setUpToken();
setUpPose();
setUpLens();
setUpSave();
setUpImage();
pollState();
