// SPDX-License-Identifier: Apache-2.0
// The page's picture: WebRTC in a <video> (the browser's own RTCPeerConnection, WHEP on the daemon's /whep) when
// /state lists a WebRTC sink, the MJPEG /stream in an <img> otherwise, or when WebRTC does not play within
// WEBRTC_START_MS or fails later. A badge names which one plays and, for WebRTC, the delay the browser measures.
'use strict';

const WEBRTC_START_MS = 3000; // no decoded frame by then: MJPEG instead
const DELAY_PERIOD_MS = 1000; // how often the badge's delay is measured from getStats()
const DECODED_POLL_MS = 200; // how often getStats() is asked for the first decoded frame

class LiveView {
    constructor(img, video, badge) {
        this.img = img;
        this.video = video;
        this.badge = badge;
        this.kind = null; // 'webrtc' or 'mjpeg' once chosen
        this.pc = null;
        this.location = null; // the peer's /whep/ID, for the DELETE that hangs up
        this.delay = null; // {totalMs, jitterMs, rttMs} of the last measurement
        this.last = null; // the previous inbound-rtp figures: the delay is over the last period, not since the start
        this.timer = null;
        window.addEventListener('pagehide', () => this.hangUp());
    }

    // The element the picture is in, and the stream's own size in pixels (0 x 0 before the first frame).
    element() { return this.kind === 'webrtc' ? this.video : this.img; }

    size() {
        if (this.kind === 'webrtc') return {width: this.video.videoWidth, height: this.video.videoHeight};
        return {width: this.img.naturalWidth, height: this.img.naturalHeight};
    }

    // From the first /state: WebRTC when the daemon has a WebRTC sink, else MJPEG. Later states change nothing.
    choose(state) {
        if (this.kind !== null) return;
        const sinks = (state.encoder && state.encoder.sinks) || [];
        if (sinks.some((sink) => sink.kind === 'webrtc')) this.startWebrtc();
        else this.useMjpeg('WebRTC is off');
    }

    async startWebrtc() {
        this.kind = 'webrtc';
        this.show('WebRTC', 'connecting…');
        this.img.removeAttribute('src'); // one stream at a time: MJPEG would cost the daemon a JPEG encode
        // Shown at once: a <video> that is not rendered (display: none) may never decode its first frame.
        this.video.hidden = false;
        this.img.hidden = true;
        const giveUp = setTimeout(() => this.fallBack('no WebRTC picture within 3 s'), WEBRTC_START_MS);
        try {
            await this.connect();
            // The browser's own count, not the element's events: a tab in the background decodes but does not
            // render, so its <video> may have no frame to show yet while the connection works.
            while (this.pc && (await this.inbound()).framesDecoded === undefined) {
                if (this.pc.connectionState === 'failed') throw new Error('the connection failed');
                await new Promise((resolve) => setTimeout(resolve, DECODED_POLL_MS));
            }
            clearTimeout(giveUp);
            if (this.kind !== 'webrtc') return; // fell back meanwhile
            this.pc.addEventListener('connectionstatechange', () => {
                if (this.pc && this.pc.connectionState === 'failed') this.fallBack('the WebRTC connection failed');
            });
            this.timer = setInterval(() => this.measure(), DELAY_PERIOD_MS);
            this.video.dispatchEvent(new Event('picture'));
        } catch (error) {
            clearTimeout(giveUp);
            this.fallBack(error.message);
        }
    }

    // WHEP: one offer with every candidate (no trickle), answered by the daemon's 201 and its Location.
    async connect() {
        const pc = new RTCPeerConnection();
        this.pc = pc;
        pc.addTransceiver('video', {direction: 'recvonly'});
        pc.addEventListener('track', (event) => {
            this.video.srcObject = event.streams[0] || new MediaStream([event.track]);
            this.video.play().catch(() => {}); // muted: autoplay is allowed; a refusal shows as no frame in 3 s
        });
        await pc.setLocalDescription(await pc.createOffer());
        await new Promise((resolve) => {
            if (pc.iceGatheringState === 'complete') resolve();
            pc.addEventListener('icegatheringstatechange', () => pc.iceGatheringState === 'complete' && resolve());
            setTimeout(resolve, WEBRTC_START_MS / 3); // host candidates come at once; a slow STUN is not waited for
        });
        const response = await fetch('/whep', {
            method: 'POST', headers: {'Content-Type': 'application/sdp'}, body: pc.localDescription.sdp,
        });
        const answer = await response.text();
        if (response.status !== 201) throw new Error(`POST /whep: ${response.status} ${answer.trim()}`);
        this.location = response.headers.get('Location');
        if (this.pc !== pc) { // fell back while the daemon answered
            this.hangUp();
            return;
        }
        await pc.setRemoteDescription({type: 'answer', sdp: answer});
    }

    fallBack(reason) {
        if (this.kind !== 'webrtc') return;
        this.hangUp();
        this.useMjpeg(reason);
    }

    useMjpeg(reason) {
        this.kind = 'mjpeg';
        this.video.hidden = true;
        this.img.hidden = false;
        if (!this.img.getAttribute('src')) this.img.src = '/stream';
        this.show('MJPEG', reason);
        this.img.dispatchEvent(new Event('picture'));
    }

    // Closes the connection and DELETEs the peer; keepalive lets the request outlive a closing tab.
    hangUp() {
        clearInterval(this.timer);
        this.timer = null;
        if (this.pc) this.pc.close();
        this.pc = null;
        this.video.srcObject = null;
        if (this.location) fetch(this.location, {method: 'DELETE', keepalive: true}).catch(() => {});
        this.location = null;
    }

    // The delay a frame spends from the daemon to the screen, as far as the browser can tell: the jitter buffer's
    // mean wait over the last period (jitterBufferDelay / jitterBufferEmittedCount) plus half the ICE pair's round
    // trip (the network's one way). The daemon's own capture-to-send time is in its /state (encoder.latency).
    async measure() {
        const inbound = await this.inbound();
        const rtt = inbound.rtt;
        if (!inbound.jitterBufferEmittedCount) return;
        const previous = this.last || {jitterBufferDelay: 0, jitterBufferEmittedCount: 0};
        this.last = inbound;
        const emitted = inbound.jitterBufferEmittedCount - previous.jitterBufferEmittedCount;
        if (emitted <= 0) return;
        const jitterMs = (1000 * (inbound.jitterBufferDelay - previous.jitterBufferDelay)) / emitted;
        const rttMs = rtt === null ? 0 : 1000 * rtt;
        this.delay = {totalMs: jitterMs + rttMs / 2, jitterMs, rttMs, framesDecoded: inbound.framesDecoded};
        this.show('WebRTC', `${Math.round(this.delay.totalMs)} ms`,
            `jitter buffer ${jitterMs.toFixed(1)} ms + half the round trip ${(rttMs / 2).toFixed(1)} ms`);
    }

    // The video's inbound-rtp statistics ({} before the first frame decoded), with the ICE pair's round trip (s).
    async inbound() {
        const pc = this.pc;
        let inbound = {}, rtt = null;
        if (!pc) return inbound;
        (await pc.getStats()).forEach((stats) => {
            if (stats.type === 'inbound-rtp' && stats.kind === 'video' && stats.framesDecoded > 0) inbound = stats;
            if (stats.type === 'candidate-pair' && stats.nominated && typeof stats.currentRoundTripTime === 'number') {
                rtt = stats.currentRoundTripTime;
            }
        });
        return {...inbound, rtt};
    }

    show(kind, detail, title = '') {
        this.badge.textContent = `${kind} · ${detail}`;
        this.badge.title = title || detail;
        this.badge.dataset.kind = kind.toLowerCase();
        document.body.dataset.transport = kind.toLowerCase(); // what tests read
    }
}
