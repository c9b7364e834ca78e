#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Heap by pool from a massif output (docs/footprint.md): valgrind --tool=massif --massif-out-file=OUT overlayd run ...;
then tests/footprint/heap_pools.py OUT. Each allocation tree's bytes at the last detailed snapshot go to the first frame that
names a known pool (the synthetic source's frames, sink slots, layer canvases, native layers, text, ...)."""
import re, sys
POOLS = [('source frame pool', 'FramePool::'), ('sink copy slots', 'SinkWorker::'),
         ('source still frame', 'SyntheticSource::start'), ('layer RGBA canvases', 'OverlayLayer::OverlayLayer'),
         ('native layers (runs)', 'NativeLayer::'), ('text coverage cache', 'TextRenderer::'),
         ('config / scene', 'loadConfig'), ('logger / misc daemon', 'overlayd::')]
text = open(sys.argv[1]).read()
snaps = re.split(r'(?m)^snapshot=', text)[1:]
detailed = [s for s in snaps if 'heap_tree=detailed' in s or 'heap_tree=peak' in s]
snap = detailed[-1]
total = int(re.search(r'mem_heap_B=(\d+)', snap).group(1))
# massif.out tree: lines "n<children>: <bytes> <where>" with indentation = depth
lines = [l for l in snap.splitlines() if re.match(r'^\s*n\d+:', l)]
nodes = []
for l in lines:
    depth = len(l) - len(l.lstrip(' '))
    m = re.match(r'\s*n(\d+): (\d+) (.*)', l)
    nodes.append((depth, int(m.group(1)), int(m.group(2)), m.group(3)))
# walk: attribute each leaf (children == 0) to the first pool whose marker appears in its path
pools = {}
stack = []
for depth, children, size, where in nodes:
    while stack and stack[-1][0] >= depth:
        stack.pop()
    stack.append((depth, where))
    if children == 0 and depth > 0:
        path = [w for _, w in stack]
        name = 'other'
        for pool, marker in POOLS:
            if any(marker in w for w in path):
                name = pool
                break
        pools[name] = pools.get(name, 0) + size
print('massif heap at the last detailed snapshot: %.1f MiB' % (total / 2**20))
for name, size in sorted(pools.items(), key=lambda kv: -kv[1]):
    print('  %-24s %7.2f MiB' % (name, size / 2**20))
