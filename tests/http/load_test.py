#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd's HTTP server under load: 100 MJPEG viewers, 10 stalled ones, then a storm of 2000 short connections.

    tests/http/load_test.py --overlayd build/daemon/overlayd --workdir /tmp/lt [--seconds 60]

The test writes config/examples/demo.toml (a synthetic 1280x720 30 fps camera) without its [[sink]]s into WORKDIR,
adds [http] on a free loopback port (control = "open", max_clients = 128, stream_fps = 15) and runs
`overlayd run` there (its log: WORKDIR/overlayd.log). Phases:

  baseline  one /stream client for 3 s (so the JPEG encoder runs): fps, frames, sink counters, VmRSS, open fds
  load      --seconds of 100 clients reading /stream as fast as they can (each part's framing and JPEG markers
            checked) and 10 that read one byte a second through a small SO_RCVBUF; /proc sampled every second,
            /state every 3 s
  drain     every client closed: the fds must come back to the baseline
  storm     2000 short connections from 8 threads (/state, /snapshot, /stream closed at once, connect-and-close,
            half a request line; half of the last three closed with RST): every /state and /snapshot must answer within 3 s,
            and the fds must come back to the baseline within 5 s (before the 10 s idle timeout could hide a leak)
  idle      8 connections that send nothing or half a request and wait: the idle timeout must close them
  stop      SIGTERM: exit status 0 within 5 s

Thresholds are loose on purpose (2 cores, noisy neighbours) but each names the fault it catches: the camera's
rate may not drop by more than 10% (median of the /state samples and the frame counter's average; up to a quarter
of the samples may dip further on a busy machine, but none below half), fds may not exceed the baseline plus one per client plus a little, and
must come back to the baseline +-2 after each phase (one leaked fd per connection fails), RSS may grow by at most
64 MiB (a server queueing frames for stalled clients grows by ~15 MB/s), no viewer may go 5 s without a part and
each must get at least a third of stream_fps. The test runs its clients at nice 10 (they stand for viewers on other
machines); the CPU line shows whether neighbours left the machine any idle time.
Exit 0: pass; 1: a check failed (each failure is listed after the summary); 2: set-up failed.
Bounded: --seconds + about 60 s.
"""
import argparse
import json
import os
import selectors
import signal
import socket
import statistics
import subprocess
import sys
import threading
import time
import urllib.request

FAST_CLIENTS = 100
SLOW_CLIENTS = 10
STREAM_FPS = 15.0
MAX_CLIENTS = 128
STORM_REQUESTS = 2000
STORM_THREADS = 8
IDLE_HOLDERS = 8
IDLE_TIMEOUT = 10.0         # the server's idle connection timeout
FPS_TOLERANCE = 0.10        # the camera's rate under load, relative to the baseline
RSS_GROWTH = 64 << 20       # bytes of VmRSS over the baseline
FD_SLACK = 8                # fds over baseline + clients during the load (monitoring requests, encoder, ...)
FD_RETURN = 2               # fds off the baseline after a phase
SETTLE = IDLE_TIMEOUT / 2   # seconds for the fds to come back after the clients closed: less than the idle timeout
STORM_LATENCY = 3.0         # seconds a /state or /snapshot may take in the storm (normally well under 0.5 s)
SLOW_LIFETIME = IDLE_TIMEOUT + 5   # seconds a slow reader stays before it dials again
MAX_GAP = 5.0               # seconds a fast viewer may go without a part
MIN_CLIENT_FPS = STREAM_FPS / 3
BOUNDARY = b'--overlaydframe'
HEAD_LIMIT = 4096
RECV_SIZE = 1 << 18


class Failure(Exception):
    pass


class SetupError(Exception):
    pass


class ProtocolError(Exception):
    pass


# No proxy: an http_proxy in the environment must not swallow requests to 127.0.0.1.
opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))


def free_port():
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


def without_sinks(toml):
    """Drops every [[sink]] table: the test must not write the demo's outputs (tables end at the next header)."""
    kept, in_sink = [], False
    for line in toml.splitlines():
        header = line.strip()
        if header.startswith('['):
            in_sink = header == '[[sink]]'
        if not in_sink:
            kept.append(line)
    return '\n'.join(kept)


def write_config(workdir, port):
    source = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'config', 'examples', 'demo.toml')
    with open(source) as file:
        text = without_sinks(file.read())
    path = os.path.join(workdir, 'overlayd.toml')
    with open(path, 'w') as file:
        file.write(f'{text}\n\n[http]\nlisten = "127.0.0.1:{port}"\ncontrol = "open"\n'
                   f'max_clients = {MAX_CLIENTS}\nstream_fps = {STREAM_FPS}\n')
    return path


def tail(path, lines=15):
    try:
        with open(path, errors='replace') as file:
            return ''.join(file.readlines()[-lines:])
    except OSError:
        return '(no log)'


def mib(size):
    return f'{size / (1 << 20):.1f}'


# ---- The daemon ----------------------------------------------------------------------------------------------

class Daemon:
    def __init__(self, overlayd, workdir):
        self.port = free_port()
        self.address = ('127.0.0.1', self.port)
        self.base = f'http://127.0.0.1:{self.port}'
        self.log = os.path.join(workdir, 'overlayd.log')
        config = write_config(workdir, self.port)
        with open(self.log, 'wb') as log:
            self.process = subprocess.Popen([overlayd, 'run', '--config', config], cwd=workdir,
                                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=log)

    def check_alive(self, during):
        if self.process.poll() is not None:
            code = self.process.returncode
            how = f'signal {-code}' if code < 0 else f'status {code}'
            raise Failure(f'overlayd died ({how}) during {during}:\n{tail(self.log)}')

    def state(self, timeout=5):
        with opener.open(self.base + '/state', timeout=timeout) as response:
            return json.loads(response.read())

    def wait_for_state(self, timeout):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise SetupError(f'overlayd exited with {self.process.returncode} before serving /state:\n'
                                 f'{tail(self.log)}')
            try:
                return self.state()
            except (OSError, ValueError):
                time.sleep(0.1)
        raise SetupError(f'GET /state did not answer within {timeout} s:\n{tail(self.log)}')

    def rss(self):
        with open(f'/proc/{self.process.pid}/status') as file:
            for line in file:
                if line.startswith('VmRSS:'):
                    return int(line.split()[1]) * 1024
        raise Failure('no VmRSS in /proc/PID/status')

    def fds(self):
        return len(os.listdir(f'/proc/{self.process.pid}/fd'))

    def settle_fds(self, target, timeout):
        """The fd count once it is within FD_RETURN of target, or the last count after timeout."""
        deadline = time.monotonic() + timeout
        while True:
            count = self.fds()
            if abs(count - target) <= FD_RETURN or time.monotonic() > deadline:
                return count
            time.sleep(0.25)

    def thread_cpu(self):
        """CPU seconds (user + system) per thread, named 'main' (the event loop) or NAME/TID."""
        seconds = {}
        task = f'/proc/{self.process.pid}/task'
        for tid in os.listdir(task):
            try:
                with open(f'{task}/{tid}/stat') as file:
                    stat = file.read()
            except OSError:
                continue
            name = 'main' if int(tid) == self.process.pid else f'{stat[stat.index("(") + 1:stat.rindex(")")]}/{tid}'
            fields = stat[stat.rindex(')') + 2:].split()
            seconds[name] = (int(fields[11]) + int(fields[12])) / CLOCK_TICKS
        return seconds

    def stop(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


CLOCK_TICKS = os.sysconf('SC_CLK_TCK')


def machine_idle():
    """Idle and total CPU ticks of the whole machine (all cores), from /proc/stat."""
    with open('/proc/stat') as file:
        ticks = [int(value) for value in file.readline().split()[1:]]
    return ticks[3] + ticks[4], sum(ticks)


def cpu_usage(before, after, seconds):
    """'overlayd 85% of a core (main 60%, ...), machine idle 10% of 2 cores' between two cpu_snapshot()s."""
    threads = {name: after[0].get(name, 0) - before[0].get(name, 0) for name in after[0]}
    total = sum(threads.values())
    busiest = sorted(threads.items(), key=lambda item: -item[1])[:4]
    idle = (after[1][0] - before[1][0]) / max(1, after[1][1] - before[1][1])
    return (f'overlayd {total / seconds:.0%} of a core (' + ', '.join(f'{name} {value / seconds:.0%}'
                                                                   for name, value in busiest) +
            f'); machine idle {idle:.0%} of {os.cpu_count()} cores')


def cpu_snapshot(daemon):
    return daemon.thread_cpu(), machine_idle()


def source_figures(state):
    sinks = state.get('sinks', [])
    return {'fps': state['source']['fps_measured'], 'frames': state['source']['frames'],
            'dropped': {sink['name']: sink['dropped'] for sink in sinks},
            'written': {sink['name']: sink['written'] for sink in sinks}}


# ---- The stream parser: chunked transfer -> multipart parts, counting parts without keeping their bodies ---------

class PartCounter:
    """Counts the parts of multipart/x-mixed-replace; each must be an image/jpeg of Content-Length bytes, FFD8..FFD9."""

    def __init__(self):
        self.head = bytearray()
        self.left = None        # body bytes still to come, None while reading a part's headers
        self.edges = b''       # a body's first two bytes
        self.last = b''        # and its last two
        self.parts = 0
        self.part_times = []

    def feed(self, data, pos, end):
        while pos < end:
            if self.left is None:
                pos = self._feed_head(data, pos, end)
                continue
            take = min(self.left, end - pos)
            if len(self.edges) < 2:
                self.edges += data[pos:pos + min(take, 2 - len(self.edges))]
            pos += take
            self.last = (self.last + data[max(pos - 2, pos - take):pos])[-2:]
            self.left -= take
            if self.left == 0:
                self._end_part()

    def _end_part(self):
        if self.edges != b'\xff\xd8' or self.last != b'\xff\xd9':
            raise ProtocolError(f'part {self.parts + 1} is not a whole JPEG (starts {self.edges.hex()}, '
                                f'ends {self.last.hex()})')
        self.parts += 1
        self.part_times.append(time.monotonic())
        self.left, self.edges, self.last = None, b'', b''

    def _feed_head(self, data, pos, end):
        room = HEAD_LIMIT - len(self.head)
        piece = data[pos:min(end, pos + room)]
        before = len(self.head)
        self.head += piece
        start = 0
        while self.head.startswith(b'\r\n', start):  # the CRLF that ends the previous part
            start += 2
        found = self.head.find(b'\r\n\r\n', start)
        if found < 0:
            if len(self.head) >= HEAD_LIMIT:
                raise ProtocolError(f'no end of part headers in {HEAD_LIMIT} bytes')
            return pos + len(piece)
        lines = bytes(self.head[start:found]).split(b'\r\n')
        consumed = found + 4 - before
        self.head = bytearray()
        if lines[0] != BOUNDARY:
            raise ProtocolError(f'part {self.parts + 1} starts with {lines[0][:40]!r}, not the boundary')
        headers = dict(line.split(b':', 1) for line in lines[1:] if b':' in line)
        headers = {key.strip().lower(): value.strip() for key, value in headers.items()}
        if headers.get(b'content-type') != b'image/jpeg':
            raise ProtocolError(f'part {self.parts + 1} has Content-Type {headers.get(b"content-type")!r}')
        try:
            self.left = int(headers[b'content-length'])
        except (KeyError, ValueError):
            raise ProtocolError(f'part {self.parts + 1} has no usable Content-Length') from None
        if self.left < 4:
            raise ProtocolError(f'part {self.parts + 1} has Content-Length {self.left}')
        return pos + consumed


class Dechunker:
    def __init__(self, sink):
        self.sink = sink
        self.line = b''
        self.left = None        # chunk bytes still to come, None while reading a size line
        self.crlf = 0           # bytes of the CRLF after a chunk still to come

    def feed(self, data, pos, end):
        while pos < end:
            if self.crlf:
                take = min(self.crlf, end - pos)
                if data[pos:pos + take] != b'\r\n'[2 - self.crlf:2 - self.crlf + take]:
                    raise ProtocolError('a chunk is not followed by CRLF')
                self.crlf -= take
                pos += take
            elif self.left is None:
                newline = data.find(b'\n', pos, min(end, pos + 64))
                if newline < 0:
                    self.line += data[pos:min(end, pos + 64)]
                    if len(self.line) > 64:
                        raise ProtocolError('a chunk size line over 64 bytes')
                    return
                line, self.line = self.line + data[pos:newline], b''
                pos = newline + 1
                try:
                    self.left = int(line.split(b';')[0].strip(), 16)
                except ValueError:
                    raise ProtocolError(f'bad chunk size line {line[:40]!r}') from None
                if self.left == 0:
                    raise ProtocolError('the server ended the stream (last chunk)')
            else:
                take = min(self.left, end - pos)
                self.sink.feed(data, pos, pos + take)
                pos += take
                self.left -= take
                if self.left == 0:
                    self.left, self.crlf = None, 2


class StreamReader:
    """One /stream response fed in pieces: the status and headers, then the (chunked) multipart body."""

    def __init__(self):
        self.head = b''
        self.parts = PartCounter()
        self.body = None

    def feed(self, data):
        pos = 0
        if self.body is None:
            before = len(self.head)
            self.head += data[:HEAD_LIMIT]
            found = self.head.find(b'\r\n\r\n')
            if found < 0:
                if len(self.head) >= HEAD_LIMIT:
                    raise ProtocolError('no end of the response headers')
                return
            pos = found + 4 - before
            self.body = self._check_head(self.head[:found])
        self.body.feed(data, pos, len(data))

    def _check_head(self, head):
        lines = head.split(b'\r\n')
        if not lines[0].startswith(b'HTTP/1.1 200'):
            raise ProtocolError(f'/stream answered {lines[0][:60]!r}')
        headers = {key.strip().lower(): value.strip()
                   for key, value in (line.split(b':', 1) for line in lines[1:] if b':' in line)}
        content_type = headers.get(b'content-type', b'').replace(b' ', b'')
        if content_type != b'multipart/x-mixed-replace;boundary=overlaydframe':
            raise ProtocolError(f'/stream has Content-Type {content_type!r}')
        chunked = headers.get(b'transfer-encoding', b'').lower() == b'chunked'
        return Dechunker(self.parts) if chunked else self.parts


# ---- The clients --------------------------------------------------------------------------------------------------

def stream_request(port):
    return f'GET /stream HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n'.encode()


class FastClient:
    def __init__(self, address):
        self.sock = socket.create_connection(address, timeout=5)
        self.sock.sendall(stream_request(address[1]))
        self.sock.setblocking(False)
        self.reader = StreamReader()
        self.received = 0
        self.started = time.monotonic()
        self.ended = None
        self.error = None

    def close(self, error=None):
        if self.ended is None:
            self.ended = time.monotonic()
            self.error = error
            self.sock.close()

    def fps(self):
        return self.reader.parts.parts / ((self.ended or time.monotonic()) - self.started)

    def max_gap(self):
        times = [self.started] + self.reader.parts.part_times + [self.ended or time.monotonic()]
        return max(b - a for a, b in zip(times, times[1:]))


class FastClients(threading.Thread):
    """Viewers that read /stream as fast as they can, all on one epoll selector."""

    def __init__(self, address, count):
        super().__init__(name='fast-clients', daemon=True)
        self.clients = [FastClient(address) for _ in range(count)]
        self.stopping = threading.Event()

    def run(self):
        selector = selectors.DefaultSelector()
        for client in self.clients:
            selector.register(client.sock, selectors.EVENT_READ, client)
        while not self.stopping.is_set():
            for key, _ in selector.select(timeout=0.2):
                self._receive(selector, key.data)
        for client in self.clients:
            if client.ended is None:
                selector.unregister(client.sock)
                client.close()
        selector.close()

    def _receive(self, selector, client):
        try:
            data = client.sock.recv(RECV_SIZE)
            if not data:
                raise ProtocolError('the server closed the connection')
            client.received += len(data)
            client.reader.feed(data)
        except BlockingIOError:
            pass
        except (OSError, ProtocolError) as error:
            selector.unregister(client.sock)
            client.close(str(error))

    def stop(self):
        self.stopping.set()
        self.join(10)


def tcp_state(sock):
    try:
        return sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_INFO, 8)[0]
    except OSError:
        return 0


TCP_ESTABLISHED = 1


class SlowReaders(threading.Thread):
    """Viewers that read one byte a second through a small receive buffer, so the server's writes to them back up.

    The server may drop a stream whose writes make no progress for its idle timeout, and the client cannot see that
    behind its closed window; so each reader hangs up after SLOW_LIFETIME (with unread data: an RST) and dials again,
    staggered, to keep stalled streams on the server through the whole load."""

    def __init__(self, address, count):
        super().__init__(name='slow-readers', daemon=True)
        self.address = address
        now = time.monotonic()
        self.readers = [[self._connect(), now - index * SLOW_LIFETIME / count] for index in range(count)]
        self.received = 0
        self.redials = 0
        self.seen_closed = 0
        self.errors = []
        self.stopping = threading.Event()

    def _connect(self):
        sock = socket.socket()
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 2048)  # before connect: it sets the window scale
        sock.settimeout(5)
        sock.connect(self.address)
        sock.sendall(stream_request(self.address[1]))
        return sock

    def run(self):
        while not self.stopping.wait(1.0):
            for reader in self.readers:
                alive = self._read_one(reader[0])
                self.seen_closed += not alive
                if alive and time.monotonic() - reader[1] < SLOW_LIFETIME:
                    continue
                reader[0].close()
                self.redials += 1
                try:
                    reader[:] = [self._connect(), time.monotonic()]
                except OSError as error:
                    self.errors.append(f'a slow reader could not connect again: {error}')
                    return
        for reader in self.readers:
            reader[0].close()

    def _read_one(self, sock):
        try:
            data = sock.recv(1, socket.MSG_DONTWAIT)
        except BlockingIOError:
            return tcp_state(sock) == TCP_ESTABLISHED
        except OSError:
            return False
        self.received += len(data)
        return bool(data) and tcp_state(sock) == TCP_ESTABLISHED

    def stop(self):
        self.stopping.set()
        self.join(10)


# ---- Sampling during the load -------------------------------------------------------------------------------------

class Monitor(threading.Thread):
    """Samples the daemon's RSS and fds every second and /state every 3 s; records what went wrong."""

    def __init__(self, daemon):
        super().__init__(name='monitor', daemon=True)
        self.daemon = daemon
        self.max_rss = 0
        self.max_fds = 0
        self.states = []        # (time, state)
        self.slowest_state = 0.0
        self.problems = []
        self.stopping = threading.Event()

    def run(self):
        tick = 0
        while not self.stopping.wait(1.0):
            if self.daemon.process.poll() is not None:
                return
            try:
                self.max_rss = max(self.max_rss, self.daemon.rss())
                self.max_fds = max(self.max_fds, self.daemon.fds())
            except OSError:
                return
            tick += 1
            if tick % 3 == 0:
                self._sample_state()

    def _sample_state(self):
        asked = time.monotonic()
        try:
            self.states.append((time.monotonic(), self.daemon.state(timeout=5)))
            self.slowest_state = max(self.slowest_state, time.monotonic() - asked)
        except (OSError, ValueError) as error:
            self.problems.append(f'GET /state failed during the load after {time.monotonic() - asked:.1f} s: '
                                 f'{error}')

    def stop(self):
        self.stopping.set()
        self.join(10)


# ---- The storm ----------------------------------------------------------------------------------------------------

def read_response(sock):
    """Status code, headers and body of a Connection: close response."""
    data = b''
    while True:
        piece = sock.recv(RECV_SIZE)
        if not piece:
            break
        data += piece
    head, _, body = data.partition(b'\r\n\r\n')
    lines = head.split(b'\r\n')
    status = int(lines[0].split()[1]) if lines[0].startswith(b'HTTP/1.') else 0
    headers = {key.strip().lower(): value.strip()
               for key, value in (line.split(b':', 1) for line in lines[1:] if b':' in line)}
    return status, headers, body


def get(address, path):
    with socket.create_connection(address, timeout=15) as sock:
        sock.sendall(f'GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n'.encode())
        return read_response(sock)


def reset_on_close(sock):
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, b'\x01\x00\x00\x00\x00\x00\x00\x00')


def storm_state(address, index):
    status, _, body = get(address, '/state')
    if status != 200 or 'source' not in json.loads(body):
        raise ProtocolError(f'/state answered {status}')


def storm_snapshot(address, index):
    status, headers, body = get(address, '/snapshot')
    if status != 200 or headers.get(b'content-type') != b'image/jpeg':
        raise ProtocolError(f'/snapshot answered {status} {headers.get(b"content-type")!r}')
    if int(headers.get(b'content-length', -1)) != len(body) or body[:2] != b'\xff\xd8' or body[-2:] != b'\xff\xd9':
        raise ProtocolError(f'/snapshot sent {len(body)} bytes that are not a whole JPEG')


def storm_stream(address, index):
    with socket.create_connection(address, timeout=10) as sock:
        if index % 2:
            reset_on_close(sock)
        sock.sendall(stream_request(address[1]))
        if index % 3 == 0:
            sock.recv(1024)


def storm_silent(address, index):
    with socket.create_connection(address, timeout=10) as sock:
        if index % 2:
            reset_on_close(sock)


def storm_half_request(address, index):
    with socket.create_connection(address, timeout=10) as sock:
        if index % 2:
            reset_on_close(sock)
        sock.sendall(b'GET /sta')


STORM_KINDS = [('GET /state', storm_state), ('GET /snapshot', storm_snapshot),
               ('/stream closed at once', storm_stream), ('connect and close', storm_silent),
               ('half a request line', storm_half_request)]


def storm(address):
    """STORM_REQUESTS short connections in STORM_THREADS threads; per kind: [done, failed, first error, seconds]."""
    results = {name: [0, 0, None, []] for name, _ in STORM_KINDS}
    lock = threading.Lock()
    next_index = iter(range(STORM_REQUESTS))

    def worker():
        while True:
            with lock:
                index = next(next_index, None)
            if index is None:
                return
            name, request = STORM_KINDS[index % len(STORM_KINDS)]
            error = None
            began = time.monotonic()
            try:
                request(address, index // len(STORM_KINDS))
            except (OSError, ValueError, ProtocolError) as caught:
                error = f'{type(caught).__name__}: {caught}'
            with lock:
                results[name][3].append(time.monotonic() - began)
                results[name][0] += 1
                if error:
                    results[name][1] += 1
                    results[name][2] = results[name][2] or error

    threads = [threading.Thread(target=worker, daemon=True) for _ in range(STORM_THREADS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(60)
    return results


class IdleHolders(threading.Thread):
    """Connections that send nothing or half a request line and wait: the server's idle timeout must close them."""

    def __init__(self, address, count, timeout):
        super().__init__(name='idle-holders', daemon=True)
        self.opened = time.monotonic()
        self.timeout = timeout
        self.sockets = []
        for index in range(count):
            sock = socket.create_connection(address, timeout=5)
            if index % 2:
                sock.sendall(b'GET /state HTTP/1.1\r\nHost: 127.0.0.1\r\n')
            self.sockets.append(sock)
        self.closed_at = [None] * count

    def run(self):
        while time.monotonic() < self.opened + self.timeout and None in self.closed_at:
            for index, sock in enumerate(self.sockets):
                if self.closed_at[index] is None and self._closed(sock):
                    self.closed_at[index] = time.monotonic() - self.opened
            time.sleep(0.1)
        for sock in self.sockets:
            sock.close()

    def last_closed(self):
        """Seconds from opening until the server closed the last one; None if some stayed open until the timeout."""
        self.join(self.timeout + 5)
        return None if None in self.closed_at else max(self.closed_at)

    @staticmethod
    def _closed(sock):
        try:
            return sock.recv(4096, socket.MSG_DONTWAIT) == b''
        except BlockingIOError:
            return False
        except OSError:
            return True


# ---- The phases ---------------------------------------------------------------------------------------------------

class Figures:
    def __init__(self):
        self.lines = []
        self.failures = []
        self.busy_note = ''

    def line(self, text):
        self.lines.append(text)

    def check(self, ok, message):
        if not ok:
            self.failures.append(message)
        return ok


def warm_up(daemon, timeout):
    """Waits until the camera's measured rate settles near its nominal one (it starts low after start-up)."""
    deadline = time.monotonic() + timeout
    while True:
        source = daemon.state()['source']
        if abs(source['fps_measured'] - source['fps']) <= FPS_TOLERANCE * source['fps']:
            return
        if time.monotonic() > deadline:
            raise SetupError(f'the camera runs at {source["fps_measured"]:.1f} fps {timeout} s after start-up, '
                             f'not {source["fps"]}: the machine is too busy to judge the server')
        time.sleep(0.5)


def baseline(daemon, figures):
    daemon.wait_for_state(20)
    warm_up(daemon, 15)
    idle_fds = daemon.fds()
    viewer = FastClients(daemon.address, 1)
    viewer.start()
    time.sleep(3)
    state = daemon.state()
    base = {'rss': daemon.rss(), 'fds': daemon.fds(), 'idle_fds': idle_fds, **source_figures(state),
            'nominal_fps': state['source']['fps'], 'time': time.monotonic()}
    viewer.stop()
    daemon.check_alive('the baseline')
    if viewer.clients[0].error or viewer.clients[0].reader.parts.parts == 0:
        raise SetupError(f'the baseline viewer got no parts: {viewer.clients[0].error}')
    if base['fps'] < 0.75 * base['nominal_fps']:
        raise SetupError(f'the camera runs at {base["fps"]:.1f} fps before any load, not {base["nominal_fps"]}: '
                         'the machine is too busy to judge the server')
    return base


def load(daemon, base, seconds, figures):
    fast = FastClients(daemon.address, FAST_CLIENTS)
    slow = SlowReaders(daemon.address, SLOW_CLIENTS)
    monitor = Monitor(daemon)
    begin = time.monotonic()
    first = daemon.state()
    cpu_before = cpu_snapshot(daemon)
    for thread in (fast, slow, monitor):
        thread.start()
    try:
        while time.monotonic() - begin < seconds:
            daemon.check_alive('the load')
            time.sleep(0.5)
        last = daemon.state(timeout=10)
        end = time.monotonic()
        cpu_after = cpu_snapshot(daemon)
        figures.line('CPU under load: ' + cpu_usage(cpu_before, cpu_after, end - begin))
        idle = (cpu_after[1][0] - cpu_before[1][0]) / max(1, cpu_after[1][1] - cpu_before[1][1])
        figures.busy_note = (f' (the machine was {1 - idle:.0%} busy during the load: if near 100%, neighbours may '
                             'have starved the camera; rerun on a quieter machine)' if idle < 0.1 else '')
    finally:
        monitor.stop()
        fast.stop()
        slow.stop()
    daemon.check_alive('the load')
    judge_load(base, first, last, end - begin, monitor, figures)
    judge_viewers(fast, slow, figures)
    return monitor


def judge_load(base, first, last, seconds, monitor, figures):
    figures.failures += monitor.problems
    fps = [state['source']['fps_measured'] for _, state in monitor.states]
    low = base['fps'] * (1 - FPS_TOLERANCE)
    if figures.check(fps, 'no /state sample answered during the load'):
        median = statistics.median(fps)
        figures.line(f'source fps under load: min {min(fps):.2f} / median {median:.2f} / max {max(fps):.2f} '
                     f'({len(fps)} /state samples; baseline {base["fps"]:.2f}): ' + ' '.join(f'{v:.1f}' for v in fps))
        figures.check(median >= low, f'the camera ran at a median {median:.2f} fps under load, more than '
                                     f'{FPS_TOLERANCE:.0%} below the baseline {base["fps"]:.2f}{figures.busy_note}')
        figures.check(min(fps) >= base['fps'] / 2,
                      f'the camera fell to {min(fps):.2f} fps under load{figures.busy_note}')
        outside = sum(value < low for value in fps)
        figures.check(outside <= max(1, len(fps) // 4),
                      f'{outside} of {len(fps)} fps samples were more than {FPS_TOLERANCE:.0%} below the baseline'
                      f'{figures.busy_note}')
    start, stop = source_figures(first), source_figures(last)
    rate = (stop['frames'] - start['frames']) / seconds
    figures.line(f'frames under load: +{stop["frames"] - start["frames"]} in {seconds:.1f} s = {rate:.2f} fps')
    figures.check(rate >= low, f'the frame counter advanced at {rate:.2f} fps under load '
                               f'(baseline {base["fps"]:.2f}){figures.busy_note}')
    frames = stop['frames'] - start['frames']
    for name in stop['dropped']:
        dropped = stop['dropped'][name] - start['dropped'].get(name, 0)
        written = stop['written'][name] - start['written'].get(name, 0)
        figures.line(f'sink {name!r} under load: written +{written}, dropped +{dropped}')
        figures.check(dropped <= FPS_TOLERANCE * frames, f'sink {name!r} dropped {dropped} of {frames} frames')
        figures.check(written >= (1 - FPS_TOLERANCE) * frames, f'sink {name!r} wrote {written} of {frames} frames')
    clients = [state.get('http', {}) for _, state in monitor.states]
    if clients:
        figures.line(f'server-side under load: /state answered within {monitor.slowest_state * 1000:.0f} ms, '
                     f'connections max {max(c.get("connections", 0) for c in clients)}, stream clients per sample '
                     + ' '.join(str(c.get('stream_clients', '?')) for c in clients))
        per_client = [value for value in clients[-1].get('stream_fps', []) if isinstance(value, (int, float))]
        if per_client:
            figures.line(f'server-side per-client fps at the end (slow readers included): min {min(per_client):.2f} / '
                         f'median {statistics.median(per_client):.2f} / max {max(per_client):.2f}')


def judge_viewers(fast, slow, figures):
    clients = fast.clients
    errors = [client.error for client in clients if client.error]
    parts = sum(client.reader.parts.parts for client in clients)
    received = sum(client.received for client in clients)
    fps = sorted(client.fps() for client in clients)
    gap = max(client.max_gap() for client in clients)
    figures.line(f'fast clients: {len(clients)}, {parts} parts, {mib(received)} MiB; per-client fps min '
                 f'{fps[0]:.2f} / median {statistics.median(fps):.2f} / max {fps[-1]:.2f} '
                 f'(cap {STREAM_FPS}); longest gap between parts {gap:.2f} s')
    figures.check(not errors, f'{len(errors)} fast clients failed, the first: {errors[0] if errors else ""}')
    figures.check(fps[0] >= MIN_CLIENT_FPS, f'a fast client got only {fps[0]:.2f} fps (at least {MIN_CLIENT_FPS})')
    figures.check(fps[-1] <= STREAM_FPS * 1.1, f'a fast client got {fps[-1]:.2f} fps, over the {STREAM_FPS} cap')
    figures.check(gap <= MAX_GAP, f'a fast client waited {gap:.2f} s for a part (at most {MAX_GAP})')
    figures.line(f'slow readers: {SLOW_CLIENTS}, {slow.received} bytes read, {slow.redials} hang-ups and new '
                 f'connections, {slow.seen_closed} closes seen from the server')
    figures.failures += slow.errors


def drain(daemon, base, monitor, figures):
    after_fds = daemon.settle_fds(base['fds'], SETTLE)
    after_rss = daemon.rss()
    limit = base['fds'] + FAST_CLIENTS + SLOW_CLIENTS + FD_SLACK
    figures.check(monitor.max_fds <= limit, f'{monitor.max_fds} fds open under load (at most {limit})')
    figures.check(monitor.max_rss < base['rss'] + RSS_GROWTH,
                  f'RSS reached {mib(monitor.max_rss)} MiB under load (baseline {mib(base["rss"])} MiB)')
    figures.check(abs(after_fds - base['fds']) <= FD_RETURN,
                  f'{after_fds} fds open {SETTLE:.0f} s after the load ended (baseline {base["fds"]})')
    figures.check(after_rss < base['rss'] + RSS_GROWTH, f'RSS {mib(after_rss)} MiB after the load')
    return after_fds, after_rss


def storm_phase(daemon, base, figures):
    began = time.monotonic()
    results = storm(daemon.address)
    took = time.monotonic() - began
    daemon.check_alive('the connection storm')
    for name, (done, failed, error, latencies) in results.items():
        figures.line(f'storm {name}: {done} done, {failed} failed, {statistics.mean(latencies) * 1000:.0f} ms mean, '
                     f'{max(latencies) * 1000:.0f} ms max' + (f' (first failure: {error})' if error else ''))
        figures.check(failed == 0, f'storm: {failed} of {done} "{name}" failed, the first: {error}')
        if name in ('GET /state', 'GET /snapshot'):
            figures.check(max(latencies) <= STORM_LATENCY, f'storm: a "{name}" took {max(latencies):.1f} s '
                                                           f'(at most {STORM_LATENCY} s)')
    figures.line(f'storm: {STORM_REQUESTS} connections from {STORM_THREADS} threads in {took:.1f} s')
    try:
        figures.check('source' in daemon.state(), '/state after the storm has no source')
    except (OSError, ValueError) as error:
        figures.check(False, f'GET /state failed after the storm: {error}')
    after_fds = daemon.settle_fds(base['fds'], SETTLE)
    after_rss = daemon.rss()
    figures.check(abs(after_fds - base['fds']) <= FD_RETURN,
                  f'{after_fds} fds open {SETTLE:.0f} s after the storm (baseline {base["fds"]}): the server holds '
                  'connections its clients closed')
    figures.check(after_rss < base['rss'] + RSS_GROWTH, f'RSS {mib(after_rss)} MiB after the storm')
    return after_fds, after_rss


def idle_phase(daemon, base, figures):
    holders = IdleHolders(daemon.address, IDLE_HOLDERS, IDLE_TIMEOUT * 2)
    holders.start()
    closed = holders.last_closed()
    figures.line(f'idle connections ({IDLE_HOLDERS}, half with half a request): '
                 + (f'all closed by the server within {closed:.1f} s' if closed else
                    f'still open after {IDLE_TIMEOUT * 2:.0f} s'))
    figures.check(closed is not None, f'the server kept idle connections open over {IDLE_TIMEOUT * 2:.0f} s '
                                      f'(idle timeout {IDLE_TIMEOUT:.0f} s)')
    after_fds = daemon.settle_fds(base['fds'], SETTLE)
    figures.check(abs(after_fds - base['fds']) <= FD_RETURN,
                  f'{after_fds} fds open after the idle connections closed (baseline {base["fds"]})')
    return after_fds


def terminate(daemon, figures):
    began = time.monotonic()
    daemon.process.send_signal(signal.SIGTERM)
    try:
        code = daemon.process.wait(5)
    except subprocess.TimeoutExpired:
        figures.check(False, f'overlayd did not exit within 5 s of SIGTERM:\n{tail(daemon.log)}')
        return
    figures.line(f'SIGTERM: exit status {code} after {time.monotonic() - began:.2f} s')
    figures.check(code == 0, f'overlayd exited with {code} on SIGTERM:\n{tail(daemon.log)}')


def run(args, workdir, figures):
    daemon = Daemon(args.overlayd, workdir)
    # The clients stand for viewers on other machines: on this one they should not take the camera's CPU.
    os.nice(10)
    try:
        base = baseline(daemon, figures)
        figures.line(f'baseline (one viewer): {base["fps"]:.2f} fps, frames {base["frames"]}, sinks dropped '
                     f'{base["dropped"]}; fds {base["fds"]} ({base["idle_fds"]} without the viewer)')
        monitor = load(daemon, base, args.seconds, figures)
        after_load = drain(daemon, base, monitor, figures)
        after_storm = storm_phase(daemon, base, figures)
        after_idle = idle_phase(daemon, base, figures)
        figures.line(f'RSS MiB: baseline {mib(base["rss"])}, max under load {mib(monitor.max_rss)}, '
                     f'after load {mib(after_load[1])}, after storm {mib(after_storm[1])}')
        figures.line(f'fds: baseline {base["fds"]}, max under load {monitor.max_fds} '
                     f'({FAST_CLIENTS + SLOW_CLIENTS} clients), after load {after_load[0]}, '
                     f'after storm {after_storm[0]}, after the idle connections {after_idle}')
        terminate(daemon, figures)
    finally:
        daemon.stop()


def on_alarm(signum, frame):
    raise Failure('the test ran out of time')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--overlayd', required=True)
    parser.add_argument('--workdir', required=True)
    parser.add_argument('--seconds', type=float, default=60.0)
    args = parser.parse_args()
    if not os.access(args.overlayd, os.X_OK):
        print(f'load_test: set-up: {args.overlayd} is not an executable', file=sys.stderr)
        return 2
    workdir = os.path.abspath(args.workdir)
    os.makedirs(workdir, exist_ok=True)
    args.overlayd = os.path.abspath(args.overlayd)

    figures = Figures()
    signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(int(args.seconds) + 90)
    try:
        run(args, workdir, figures)
    except SetupError as error:
        print(f'load_test: set-up: {error}', file=sys.stderr)
        return 2
    except Failure as error:
        figures.failures.append(str(error))
    except Exception as error:  # the test itself broke: still a failure, named by its type
        figures.failures.append(f'{type(error).__name__}: {error}')
    finally:
        signal.alarm(0)
    print('\n'.join(['load_test summary:'] + [f'  {line}' for line in figures.lines]))
    if figures.failures:
        print('\n'.join(['load_test: FAIL:'] + [f'  - {failure}' for failure in figures.failures]))
        return 1
    print(f'load_test: PASS (log in {workdir}/overlayd.log)')
    return 0


if __name__ == '__main__':
    sys.exit(main())
