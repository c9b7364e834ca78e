#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""What overlayd costs to start and to keep running, measured on the real binary (docs/footprint.md).

  tests/footprint/measure.py --overlayd build/daemon/overlayd [--runs 10] [--seconds 10]

- first frame: time from exec to the first frame on stdout (`overlayd run` with the demo scene, its source made
  synthetic 1280x720 YUYV, one Y4M sink on stdout: the moment the first FRAME header and its bytes are read), the
  median of --runs starts;
- shared libraries: how many the running process has mapped (/proc/PID/maps), not what ldd lists;
- memory at 1080p YUYV 30 fps with the demo scene and a null sink, after --seconds: VmRSS and, from
  /proc/PID/smaps, the part of it that is shared-library mappings, the heap and anonymous mappings.

  tests/footprint/measure.py --overlayd build/daemon/overlayd --scenes [--seconds 5]

- instead, memory only, for three scenes at 720p and 1080p YUYV 30 fps with a null sink: the demo, the reverse-camera
  example (its GPIO lines and CAN input left out: they need the board) and twenty_layers.toml (20 layers); VmRSS,
  the same split, and /proc/PID/smaps_rollup's Anonymous (what the process itself allocated and touched).
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, '..', '..', 'config', 'examples')
DEMO = os.path.join(EXAMPLES, 'demo.toml')
SCENES = [('demo', DEMO), ('reverse camera', os.path.join(EXAMPLES, 'reverse_camera.toml')),
          ('20 layers', os.path.join(HERE, 'twenty_layers.toml'))]


def demo_config(width, height, sink, path=DEMO):
    """A scene (the demo's by default) with its [source] set to WIDTHxHEIGHT YUYV at 30 fps, its sinks replaced by
    SINK, and the tables that need hardware (GPIO lines, CAN inputs) left out."""
    with open(path) as f:
        text = f.read()
    for table in (r'\[\[sink\]\]', r'\[\[gpio\.\w+\]\]', r'\[\[input\.can\]\]'):
        text = re.sub(r'(?ms)^' + table + r'.*?(?=^\[|\Z)', '', text)
    text = re.sub(r'(?m)^width = \d+', 'width = %d' % width, text, count=1)
    text = re.sub(r'(?m)^height = \d+', 'height = %d' % height, text, count=1)
    text = re.sub(r'(?m)^format = "\w+"', 'format = "YUYV"', text, count=1)
    return text + '\n' + sink


def first_frame_seconds(overlayd, config, frame_bytes):
    start = time.monotonic()
    proc = subprocess.Popen([overlayd, 'run', '--config', config], stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL)
    seen = b''
    try:
        while True:
            chunk = proc.stdout.read1(1 << 20)
            if not chunk:
                raise RuntimeError('overlayd ended before its first frame')
            seen += chunk
            at = seen.find(b'FRAME\n')
            if at >= 0 and len(seen) >= at + 6 + frame_bytes:
                return time.monotonic() - start
    finally:
        proc.stdout.close()  # first: a sink blocked writing to a full pipe would hold up the stop
        proc.terminate()
        proc.wait()


def memory(pid):
    libraries = set()
    with open('/proc/%d/maps' % pid) as f:
        for line in f:
            fields = line.split()
            if len(fields) >= 6 and '.so' in fields[5]:
                libraries.add(fields[5])
    kinds = {'libraries': 0, 'heap': 0, 'anonymous': 0, 'other': 0}
    current = 'other'
    with open('/proc/%d/smaps' % pid) as f:
        for line in f:
            if re.match(r'^[0-9a-f]+-[0-9a-f]+ ', line):
                fields = line.split()
                name = fields[5] if len(fields) >= 6 else ''
                current = ('libraries' if '.so' in name else 'heap' if name == '[heap]'
                           else 'anonymous' if name == '' else 'other')
            elif line.startswith('Rss:'):
                kinds[current] += int(line.split()[1])
    with open('/proc/%d/status' % pid) as f:
        rss = int(re.search(r'VmRSS:\s+(\d+)', f.read()).group(1))
    with open('/proc/%d/smaps_rollup' % pid) as f:
        kinds['Anonymous'] = int(re.search(r'Anonymous:\s+(\d+)', f.read()).group(1))
    return len(libraries), rss, kinds


def steady_memory(overlayd, config, seconds):
    """Runs `overlayd run` on CONFIG for SECONDS and measures it (memory()) while it runs."""
    proc = subprocess.Popen([overlayd, 'run', '--config', config], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    try:
        time.sleep(seconds)
        if proc.poll() is not None:
            sys.exit('overlayd ended: ' + proc.stderr.read().decode())
        return memory(proc.pid)
    finally:
        proc.terminate()
        proc.wait()


def describe(rss, kinds):
    return ('VmRSS %.1f MiB (libraries %.1f, heap %.1f, anonymous %.1f, other %.1f; smaps_rollup Anonymous %.1f)'
            % (rss / 1024, kinds['libraries'] / 1024, kinds['heap'] / 1024, kinds['anonymous'] / 1024,
               kinds['other'] / 1024, kinds['Anonymous'] / 1024))


def scenes(overlayd, seconds, work):
    for name, path in SCENES:
        for width, height in ((1280, 720), (1920, 1080)):
            config = os.path.join(work, 'scene-%d.toml' % width)  # none of the scenes reads a relative path
            with open(config, 'w') as f:
                f.write(demo_config(width, height, '[[sink]]\nkind = "null"\n', path))
            _, rss, kinds = steady_memory(overlayd, config, seconds)
            print('%-15s %4dx%-4d YUYV 30 fps, null sink: %s' % (name, width, height, describe(rss, kinds)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--overlayd', required=True)
    parser.add_argument('--runs', type=int, default=10)
    parser.add_argument('--seconds', type=float, default=10.0)
    parser.add_argument('--scenes', action='store_true', help='memory of the three scenes at 720p and 1080p only')
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix='overlayd-footprint-')
    if args.scenes:
        scenes(args.overlayd, args.seconds, work)
        return
    startup = os.path.join(work, 'startup.toml')
    with open(startup, 'w') as f:
        f.write(demo_config(1280, 720, '[[sink]]\nkind = "y4m"\npath = "-"\n'))
    times = [first_frame_seconds(args.overlayd, startup, 1280 * 720 * 2) for _ in range(args.runs)]
    print('first frame: median %.1f ms, min %.1f, max %.1f over %d starts (720p YUYV, Y4M on stdout)'
          % (1e3 * statistics.median(times), 1e3 * min(times), 1e3 * max(times), args.runs))

    steady = os.path.join(work, 'steady.toml')
    with open(steady, 'w') as f:
        f.write(demo_config(1920, 1080, '[[sink]]\nkind = "null"\n'))
    count, rss, kinds = steady_memory(args.overlayd, steady, args.seconds)
    print('1080p YUYV 30 fps, demo scene, null sink, after %.0f s: %d shared libraries mapped, %s'
          % (args.seconds, count, describe(rss, kinds)))


if __name__ == '__main__':
    main()
