# What a frame costs in CPU through the libcamera source (vimc, Debian's libcamera 0.0.3) against the V4L2 source
# (vivid's webcam input) at the same size, format and overlay: `overlayd render` of 5 and of 20 frames under
# `time`, the difference over 15 frames, so that start-up (libraries, the camera manager, the IPA) cancels out.
# Reported, not asserted: TCG times are for function, and these machines drift; the line is for docs/libcamera.md.
. /vm/lib.sh

have_overlayd || { fail source-cost "no overlayd binary was staged (build the overlayd target)"; exit 0; }

cpu_seconds() { # CONFIG FRAMES: user + sys seconds of one render
    time -p overlayd render --config "$1" --frames "$2" --output /tmp/cost.y4m 2>&1 >/dev/null |
        awk '$1 == "user" || $1 == "sys" { s += $2 } END { print s + 0 }'
    rm -f /tmp/cost.y4m
}
per_frame_ms() { # CONFIG
    a=$(cpu_seconds "$1" 5) b=$(cpu_seconds "$1" 20)
    awk -v a="$a" -v b="$b" 'BEGIN { printf "%.1f", (b - a) / 15 * 1000 }'
}

modprobe vimc && sleep 1 || { fail source-cost "modprobe vimc failed"; exit 0; }
udev_start
udev_initialise
config_for libcamera.toml /tmp/cost-lc.toml 'format="RGB24"'
lc=$(per_frame_ms /tmp/cost-lc.toml)
rmmod vimc

vivid_load n_devs=1 node_types=0x1 multiplanar=1 || { fail source-cost "modprobe vivid failed"; exit 0; }
DEV=$(node vivid-000-vid-cap)
config_for capture.toml /tmp/cost-v4l2.toml 'format="RGB24"' width=1280 height=720 "device=\"$DEV\""
v4=$(per_frame_ms /tmp/cost-v4l2.toml)
rmmod vivid

echo "MEASURE source-cost: CPU per frame, RGB24 with grid and axes into Y4M: libcamera (vimc 1278x720) $lc ms," \
    "V4L2 (vivid 1280x720) $v4 ms, ratio $(awk -v a="$lc" -v b="$v4" 'BEGIN { if (b > 0) printf "%.2f", a / b }')"
exit 0
