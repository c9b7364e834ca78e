# SPDX-License-Identifier: Apache-2.0
# How long overlayd takes to start in the guest, where most of this tier's time goes (it starts overlayd some 17
# times): `overlayd --version` (exec, the loader and every library's constructors) and a one-frame synthetic render,
# each the median of three runs. A measurement (docs/vm-tests.md keeps the figures); it fails only when overlayd
# cannot start.
. /vm/lib.sh

have_overlayd || { fail startup "no overlayd in the guest"; exit 0; }
cat >/tmp/startup.toml <<'TOML'
[source]
kind = "synthetic"
format = "YUYV"
width = 320
height = 240
fps = 30.0
[source.synthetic]
pattern = "colour-bars"
TOML

# median_seconds COMMAND...: the median wall time of three runs, from /proc/uptime (10 ms steps); empty on failure.
median_seconds() {
    for _ in 1 2 3; do
        _start=$(uptime_s)
        "$@" >/dev/null 2>&1 || return 1
        awk -v a="$_start" -v b="$(uptime_s)" 'BEGIN { printf "%.2f\n", b - a }'
    done | sort -n | sed -n 2p
}

version=$(median_seconds overlayd --version)
render=$(median_seconds overlayd render --config /tmp/startup.toml --frames 1 --output /tmp/startup.y4m)
echo "MEASURE startup: overlayd --version ${version:-failed} s, one-frame render ${render:-failed} s (median of 3)"
ok=0
[ -n "$version" ] && [ -n "$render" ] || ok=1
verdict startup $ok "overlayd starts in the guest: --version ${version:-failed} s, a one-frame render ${render:-failed} s"
exit 0
