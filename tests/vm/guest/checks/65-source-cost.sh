# SPDX-License-Identifier: Apache-2.0
# What a frame costs in CPU through the libcamera source (vimc, libcamera 0.3.2) against the V4L2 source
# (vivid's webcam input) at the same format and overlay and nearly the same size (vimc turns 640x480 into 636x480):
# `overlayd render` of 10 and of 40 frames under busybox `time -v`, user + system time, the difference over 30 frames
# so that start-up (libraries, the camera manager, the IPA) cancels out; the median of three such pairs, and the
# minor page faults per frame (a copy the source added would show there). Reported, not asserted: TCG times are for
# function, and these machines drift; the line is for docs/libcamera.md.
. /vm/lib.sh

have_overlayd || { fail source-cost "no overlayd binary was staged (build the overlayd target)"; exit 0; }

run_cost() { # CONFIG FRAMES: "cpu-seconds minor-faults" of one render
    time -v overlayd render --config "$1" --frames "$2" --output /tmp/cost.y4m 2>&1 >/dev/null |
        awk -F': ' '/User time|System time/ { s += $2 } /Minor/ { f = $2 } END { print s + 0, f + 0 }'
    rm -f /tmp/cost.y4m
}
per_frame() { # CONFIG: "ms-per-frame faults-per-frame", the median of three 40-minus-10 pairs
    for _ in 1 2 3; do
        set -- "$1" $(run_cost "$1" 10) $(run_cost "$1" 40)
        awk -v a="$2" -v fa="$3" -v b="$4" -v fb="$5" 'BEGIN { f = (fb - fa) / 30; printf "%.1f %d\n", (b - a) / 30 * 1000, int(f + (f < 0 ? -0.5 : 0.5)) }'
    done | sort -n | sed -n 2p
}

modprobe vimc && sleep 1 || { fail source-cost "modprobe vimc failed"; exit 0; }
udev_start
udev_initialise
config_for libcamera.toml /tmp/cost-lc.toml 'format="RGB24"' width=640 height=480
set -- $(per_frame /tmp/cost-lc.toml)
lc=$1 lc_faults=$2
rmmod vimc

vivid_load n_devs=1 node_types=0x1 multiplanar=1 || { fail source-cost "modprobe vivid failed"; exit 0; }
DEV=$(node vivid-000-vid-cap)
config_for capture.toml /tmp/cost-v4l2.toml 'format="RGB24"' width=640 height=480 "device=\"$DEV\""
set -- $(per_frame /tmp/cost-v4l2.toml)
v4=$1 v4_faults=$2
rmmod vivid

echo "MEASURE source-cost: CPU per frame, RGB24 with grid and axes into Y4M (median of 3): libcamera (vimc 636x480)" \
    "$lc ms, $lc_faults faults; V4L2 (vivid 640x480) $v4 ms, $v4_faults faults; ratio" \
    "$(awk -v a="$lc" -v b="$v4" 'BEGIN { if (b > 0) printf "%.2f", a / b }')"
exit 0
