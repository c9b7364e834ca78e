#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""What `overlayd --version` costs in resident memory, and the floor under it (docs/footprint.md).

  tests/footprint/startup_rss.py --overlayd build/daemon/overlayd [--runs 5] [--by-library 25]

- peak RSS of `overlayd --version`: ru_maxrss of the child (what `/usr/bin/time -v` reports as "Maximum resident set
  size"), the median of --runs. The child is forked by a small C launcher built here, as time(1) forks it: the
  maximum survives exec, so a child forked from Python would report Python's own resident size;
- the floor: the same figure for a C++ program that prints one line and does nothing else, linked (c++, no
  --as-needed) against exactly the shared libraries overlayd names (its DT_NEEDED): what loading those libraries
  costs before overlayd runs a line of its own; and the same program with no library but the C++ runtime;
- with --by-library N: /proc/self/smaps of `overlayd --version` as it exits (copied by a destructor in a small
  LD_PRELOAD library built here), the N largest mappings grouped by file (private dirty = relocations, GOT, .data,
  heap; the rest = text and read-only data paged in, with the kernel's fault-around of up to 64 KiB per fault).

A file written moments ago (a binary just linked) shows its pages as private dirty until they are written back;
measure a build that has settled. RSS counts a library's clean pages even when other processes share them: it is
the figure `time -v` and the issue give. Nothing here is a pass/fail threshold (RSS depends on the machine's
libraries and page cache).
"""
import argparse
import collections
import os
import re
import statistics
import subprocess
import sys
import tempfile

PROGRAM = '#include <cstdio>\nint main() { std::puts("overlayd 0.1.0"); return 0; }\n'
# Forks and execs argv[1...], waits, prints the child's ru_maxrss (KiB): time(1)'s figure.
LAUNCHER = r"""
#include <stdio.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
int main(int argc, char **argv) {
    (void)argc;
    pid_t pid = fork();
    if (pid == 0) { execv(argv[1], argv + 1); _exit(127); }
    int status; struct rusage usage;
    if (wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return 1;
    printf("%ld\n", usage.ru_maxrss);
    return 0;
}
"""
# Copies /proc/self/smaps to $OVERLAYD_SMAPS_OUT as the process exits (a destructor of a preloaded library runs after
# the program's own).
DUMPER = r"""
#include <stdio.h>
#include <stdlib.h>
__attribute__((destructor)) static void dumpSmaps(void) {
    const char *path = getenv("OVERLAYD_SMAPS_OUT");
    FILE *in = fopen("/proc/self/smaps", "r"), *out = path ? fopen(path, "w") : NULL;
    char buffer[65536]; size_t n;
    while (in && out && (n = fread(buffer, 1, sizeof buffer, in)) > 0) fwrite(buffer, 1, n, out);
    if (in) fclose(in);
    if (out) fclose(out);
}
"""


def compile_c(folder, name, text, *flags):
    source, output = os.path.join(folder, name + '.c'), os.path.join(folder, name)
    with open(source, 'w') as f:
        f.write(text)
    subprocess.run(['cc', '-O2', source, '-o', output, *flags], check=True)
    return output


def peak_rss_kib(launcher, argv, runs):
    values = []
    for _ in range(runs):
        out = subprocess.run([launcher] + argv, capture_output=True, text=True)
        if out.returncode != 0:
            sys.exit(f'{argv[0]} failed')
        values.append(int(out.stdout.split()[-1]))
    return int(statistics.median(values))


def needed_libraries(binary):
    out = subprocess.run(['readelf', '-d', binary], capture_output=True, text=True, check=True).stdout
    return re.findall(r'\(NEEDED\)\s+Shared library: \[(.+)\]', out)


def library_count(binary):
    out = subprocess.run(['ldd', binary], capture_output=True, text=True, check=True).stdout
    return len([line for line in out.splitlines() if line.strip()])


def build_floor(folder, libraries):
    source = os.path.join(folder, 'floor.cpp')
    with open(source, 'w') as f:
        f.write(PROGRAM)
    plain, same = os.path.join(folder, 'plain'), os.path.join(folder, 'same_libraries')
    subprocess.run(['c++', '-O2', source, '-o', plain], check=True)
    # The C++ runtime and libc are linked anyway; the others by file name, each kept even if unused.
    runtime = re.compile(r'^lib(c|m|gcc_s|stdc\+\+)\.so')
    extra = [f'-l:{name}' for name in libraries if not runtime.match(name)]
    subprocess.run(['c++', '-O2', source, '-o', same, '-Wl,--no-as-needed'] + extra, check=True)
    return plain, same


def smaps_at_exit(folder, binary):
    """/proc/self/smaps of `binary --version` as it exits: everything start-up and the command touched."""
    dumper = compile_c(folder, 'dump_smaps.so', DUMPER, '-shared', '-fPIC')
    out = os.path.join(folder, 'smaps')
    environment = dict(os.environ, LD_PRELOAD=dumper, OVERLAYD_SMAPS_OUT=out)
    subprocess.run([binary, '--version'], stdout=subprocess.DEVNULL, env=environment, check=True)
    with open(out) as f:
        return f.read()


def by_mapping(smaps):
    groups = collections.defaultdict(collections.Counter)
    current = None
    for line in smaps.splitlines():
        header = re.match(r'^[0-9a-f]+-[0-9a-f]+ \S+ \S+ \S+ \d+\s*(.*)$', line)
        if header:
            current = groups[os.path.basename(header.group(1).strip()) or '[anonymous]']
            continue
        key, _, value = line.partition(':')
        if current is not None and key in ('Rss', 'Private_Dirty'):
            current[key] += int(value.split()[0])
    return groups


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--overlayd', required=True)
    parser.add_argument('--runs', type=int, default=5)
    parser.add_argument('--by-library', type=int, default=0, metavar='N')
    args = parser.parse_args()
    binary = os.path.abspath(args.overlayd)

    with tempfile.TemporaryDirectory(prefix=f'overlayd-floor-{os.getpid()}-') as folder:
        launcher = compile_c(folder, 'launcher', LAUNCHER)
        plain, same = build_floor(folder, needed_libraries(binary))
        rows = [('overlayd --version', binary, [binary, '--version']),
                ('floor: puts() + the same libraries', same, [same]),
                ('floor: puts(), C++ runtime only', plain, [plain])]
        print(f'| program | shared libraries (ldd) | peak RSS (median of {args.runs}) |')
        print('|---|---|---|')
        for name, path, argv in rows:
            print(f'| {name} | {library_count(path)} | {peak_rss_kib(launcher, argv, args.runs) / 1024:.1f} MiB |')
        groups = by_mapping(smaps_at_exit(folder, binary)) if args.by_library else None

    if groups:
        total = sum(g['Rss'] for g in groups.values())
        print(f'\nAt exit(): {total / 1024:.1f} MiB resident in {len(groups)} files and anonymous mappings')
        print('| mapping | RSS KiB | of it private dirty |')
        print('|---|---|---|')
        for name, g in sorted(groups.items(), key=lambda item: -item[1]['Rss'])[:args.by_library]:
            print(f'| {name} | {g["Rss"]} | {g["Private_Dirty"]} |')


if __name__ == '__main__':
    main()
