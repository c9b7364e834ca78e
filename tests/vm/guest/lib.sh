# SPDX-License-Identifier: Apache-2.0
# Helpers for the guest checks (busybox sh): result lines, vivid set-up, overlayd, and pixel reads from Y4M and
# raw YUYV files. Every check prints "PASS <name>: ..." or "FAIL <name>: ..."; the host counts those lines.

ART=/mnt/out # artifacts the host verifies independently (ffprobe) or a person can look at

pass() { echo "PASS $1: $2"; }
fail() { echo "FAIL $1: $2"; }
# verdict NAME OK DETAIL: OK is a shell status (0 = pass)
verdict() { if [ "$2" = 0 ]; then pass "$1" "$3"; else fail "$1" "$3"; fi; }
uptime_s() { cut -d' ' -f1 /proc/uptime; }

have_overlayd() { [ -x /usr/bin/overlayd ]; }

# vivid_load ARGS...: a fresh vivid (controls back to their defaults) with the given module parameters.
vivid_load() {
    rmmod vivid 2>/dev/null
    modprobe vivid "$@" || return 1
    for _ in 1 2 3 4 5 6 7 8 9 10; do [ -e /dev/video0 ] && return 0; sleep 0.2; done
    return 1
}

# node NAME: the /dev/video* whose sysfs name is NAME (vivid-000-vid-cap, vivid-001-vid-out, ...)
node() {
    for n in /sys/class/video4linux/video*; do
        [ "$(cat "$n/name")" = "$1" ] && echo "/dev/${n##*/}" && return 0
    done
    return 1
}

# config_for TEMPLATE OUT key=value...: copies a test config, replacing the first `key = ...` line of each key.
config_for() {
    _template=$1 _out=$2
    shift 2
    awk -v pairs="$*" 'BEGIN { n = split(pairs, kv, " "); for (i = 1; i <= n; i++) { split(kv[i], p, "="); want[p[1]] = p[2] } }
        { key = $1 } $2 == "=" && (key in want) && !(key in done) { print key " = " want[key]; done[key] = 1; next } { print }' \
        "/vm/configs/$_template" >"$_out"
}

# axes_points CONFIG: three lines "u v" (rounded pixel, top-left origin, or "none" if not visible) where the points
# 0.6 m along X, Y and Z land according to `overlayd project`. One process for the three: under TCG every overlayd
# start costs seconds (it links ~150 libraries).
axes_points() {
    overlayd project --config "$1" 0.6 0 0 0 0.6 0 0 0 0.6 2>/dev/null |
        sed -n 's/.*pixel (\([-0-9.]*\), \([-0-9.]*\)),.*, visible$/\1 \2/p; t; s/.*->.*/none/p' |
        awk '$1 == "none" { print; next } { printf "%d %d\n", $1 + 0.5, $2 + 0.5 }'
}

bytes_at() { od -An -tu1 -j "$2" -N "$3" "$1" | tr -s ' \n' '  ' | sed 's/^ //; s/ $//'; }

# y4m_geometry FILE: "W H CHROMA HEADERBYTES FRAMEBYTES" from the stream header.
y4m_geometry() {
    head -n1 "$1" | awk '{
        for (i = 2; i <= NF; i++) {
            if ($i ~ /^W/) w = substr($i, 2); if ($i ~ /^H/) h = substr($i, 2); if ($i ~ /^C/) c = substr($i, 2)
        }
        if (c == "") c = "420jpeg"
        cw = int((w + 1) / 2); ch = (c ~ /^420/) ? int((h + 1) / 2) : h
        if (c == "444") { cw = w; ch = h }
        if (c == "mono") { cw = 0; ch = 0 }
        printf "%d %d %s %d %d\n", w, h, c, length($0) + 1, w * h + 2 * cw * ch
    }'
}

# y4m_pixel FILE K X Y: "Y Cb Cr" of pixel (X, Y) in frame K (0-based).
y4m_pixel() {
    set -- "$1" "$2" "$3" "$4" $(y4m_geometry "$1")
    f=$1 k=$2 x=$3 y=$4 w=$5 h=$6 c=$7 hdr=$8 fb=$9
    base=$((hdr + k * (fb + 6) + 6))
    case $c in 444) cx=$x cy=$y cw=$w ch=$h ;; 422) cx=$((x / 2)) cy=$y cw=$(((w + 1) / 2)) ch=$h ;;
    *) cx=$((x / 2)) cy=$((y / 2)) cw=$(((w + 1) / 2)) ch=$(((h + 1) / 2)) ;; esac
    echo "$(bytes_at "$f" $((base + y * w + x)) 1) $(bytes_at "$f" $((base + w * h + cy * cw + cx)) 1)" \
        "$(bytes_at "$f" $((base + w * h + cw * ch + cy * cw + cx)) 1)"
}

# yuyv_pixel FILE K W H X Y: "Y Cb Cr" of a pixel of frame K in a file of packed YUYV frames (stride 2W).
yuyv_pixel() {
    set -- $(bytes_at "$1" $(($2 * $3 * $4 * 2 + $6 * $3 * 2 + ($5 / 2) * 4)) 4) "$5"
    if [ $(($5 % 2)) = 0 ]; then echo "$1 $2 $4"; else echo "$3 $2 $4"; fi
}

# near "A B C" "A' B' C'" TOL: every component within TOL
near() {
    echo "$1 $2" | awk -v t="$3" '{ for (i = 1; i <= 3; i++) { d = $i - $(i + 3); if (d < -t || d > t) exit 1 } }'
}

# The axis colours of the test configs in BT.601 limited range, computed by hand from Y = 16 + 219 (0.299 R +
# 0.587 G + 0.114 B) / 255, Cb = 128 + 224 (B - Y') / (1.772 * 255), Cr = 128 + 224 (R - Y') / (1.402 * 255).
RED_YCC="81 90 240"
GREEN_YCC="145 54 34"
BLUE_YCC="41 240 110"
BLACK_YCC="16 128 128"
NOSIGNAL_YCC="57 128 128" # the NO SIGNAL frame's grey 48, 48, 48

# mask_check FILE CONFIG: the privacy masks of loopback.toml and zerocopy.toml in a looped YUYV frame of W x H:
# white inside the screen mask, grey (128) where `overlayd project` puts the ground mask's centre (1.5, 1.5, 0), black
# beside them. Appends to $summary; returns non-zero on any mismatch.
WHITE_YCC="235 128 128"
GREY_YCC="126 128 128"
mask_check() {
    _r=0 _mask=$(overlayd project --config "$2" 1.5 1.5 0 2>/dev/null |
        sed -n 's/.*pixel (\([-0-9.]*\), \([-0-9.]*\)),.*, visible$/\1 \2/p' | awk '{ printf "%d %d", $1 + 0.5, $2 + 0.5 }')
    [ -n "$_mask" ] || { summary="$summary ground mask centre not visible" && return 1; }
    for probe in "1042 42:$WHITE_YCC:screen-mask" "1140 100:$WHITE_YCC:screen-mask" "1238 158:$WHITE_YCC:screen-mask" \
        "1020 100:$BLACK_YCC:beside" "$_mask:$GREY_YCC:ground-mask"; do
        _at=${probe%%:*} _rest=${probe#*:}
        _got=$(yuyv_pixel "$1" 3 $W $H $_at)
        summary="$summary ${_rest#*:}@${_at% *},${_at#* }=($_got)"
        near "$_got" "${_rest%%:*}" 8 || _r=1
    done
    return $_r
}

# axes_check "POINTS": the axis colours at the three axes_points lines, and black (the source pattern) at the
# top-left corner. $PIXEL is a command that, given "X Y", prints "Y Cb Cr". Sets $summary; returns non-zero on
# any mismatch (or if the points are not three visible ones).
axes_check() {
    summary='' _r=0
    [ "$(echo "$1" | grep -c '^[0-9]* [0-9]*$')" = 3 ] || { summary="projected points: $1" && return 1; }
    axis_probe "$(echo "$1" | sed -n 1p)" "$RED_YCC" X || _r=1
    axis_probe "$(echo "$1" | sed -n 2p)" "$GREEN_YCC" Y || _r=1
    axis_probe "$(echo "$1" | sed -n 3p)" "$BLUE_YCC" Z || _r=1
    _got=$($PIXEL 3 3)
    summary="$summary corner=($_got)"
    near "$_got" "$BLACK_YCC" 12 || _r=1
    return $_r
}

# Reads the looped capture node CAP into FILE until the overlay of CONFIG shows at its projected axes (overlayd needs
# a few seconds to start streaming under TCG: 6 tries, 2 s apart). Sets $try and $summary; 0 when it shows.
await_loop_overlay() { # CAP FILE CONFIG W H
    points=$(axes_points "$3")
    PIXEL="yuyv_pixel $2 3 $4 $5"
    for try in 1 2 3 4 5 6; do
        sleep 2
        v4l2-ctl -d "$1" --stream-mmap=4 --stream-count=4 --stream-to="$2" >/dev/null 2>&1
        axes_check "$points" && return 0
    done
    return 1
}

axis_probe() { # "U V" WANT NAME
    _got=$($PIXEL $1)
    summary="$summary $3@${1% *},${1#* }=($_got)"
    near "$_got" "$2" 12
}

# vivid_hdmi_loop: two vivid instances, instance 1's HDMI output looped back (loop_video=1) to its HDMI capture
# input at 1280x720 YUYV, instance 0 a black source; sets SRC, CAP, OUT, W and H. Same type, size, fourcc and field
# on both ends, as vivid's loop requires; no OSD text on the looped frames.
vivid_hdmi_loop() {
    vivid_load n_devs=2 node_types=0x1,0x101 multiplanar=1,1 || return 1
    SRC=$(node vivid-000-vid-cap) CAP=$(node vivid-001-vid-cap) OUT=$(node vivid-001-vid-out)
    W=1280 H=720
    black_pattern "$SRC"
    v4l2-ctl -d "$CAP" -i 3 >/dev/null && v4l2-ctl -d "$OUT" -o 1 >/dev/null
    v4l2-ctl -d "$CAP" --set-fmt-video=width=$W,height=$H,pixelformat=YUYV
    v4l2-ctl -d "$CAP" -c loop_video=1 -c osd_text_mode=2
}

# loop_overlay_run NAME TEMPLATE DETAIL: overlayd on TEMPLATE (device SRC, path OUT) in the background ($pid, log
# /tmp/NAME-run.log), then the verdict NAME-overlay on its overlay read back from the looped CAP; the frame is kept
# as $ART/NAME-WxH.yuyv.
loop_overlay_run() {
    config_for "$2" "/tmp/$1.toml" "device=\"$SRC\"" "path=\"$OUT\""
    overlayd run --config "/tmp/$1.toml" >"/tmp/$1-run.log" 2>&1 &
    pid=$!
    await_loop_overlay "$CAP" "/tmp/$1.yuv" "/tmp/$1.toml" $W $H
    _ok=$?
    kill -0 $pid 2>/dev/null || _ok=1
    verdict "$1-overlay" $_ok "$OUT -> $CAP ${W}x$H YUYV$3, try $try, looped frame:$summary"
    cp "/tmp/$1.yuv" "$ART/$1-${W}x$H.yuyv" 2>/dev/null
}

# stop_overlayd PID: SIGTERM, SIGKILL after 20 s (a daemon that does not stop must not hang the tier); returns its
# exit status.
stop_overlayd() {
    kill -TERM "$1" 2>/dev/null
    (sleep 20 && kill -KILL "$1" 2>/dev/null) &
    wait "$1"
}

# black_pattern DEVICE: vivid's "100% Black" test pattern and no OSD text, so that only overlay pixels have colour.
black_pattern() {
    black=$(v4l2-ctl -d "$1" --list-ctrls-menus | sed -n 's/^[[:space:]]*\([0-9]*\): 100% Black.*/\1/p' | head -1)
    v4l2-ctl -d "$1" -c "test_pattern=${black:-5}" -c osd_text_mode=2
}

# Following the Y4M file $OUT that `overlayd run` writes while its camera goes and comes back. The probe pixel
# ($PROBE_X, $PROBE_Y) lies on the source's leftmost colour bar (75% white, Y about 180), clear of the axes and of
# the NO SIGNAL text.
frames() { [ -s $OUT ] && set -- $(y4m_geometry $OUT) && echo $((($(wc -c <$OUT) - $4) / ($5 + 6))) || echo 0; }
probe() { n=$(frames) && [ "$n" -gt 0 ] && y4m_pixel $OUT $((n - 1)) $PROBE_X $PROBE_Y; }
is_live() { p=$(probe) && ! near "$p" "$NOSIGNAL_YCC" 10 && [ "$(echo $p | cut -d' ' -f1)" -gt 120 ]; }
is_nosignal() { p=$(probe) && near "$p" "$NOSIGNAL_YCC" 6; }
# wait_for SECONDS CONDITION...: polls every 0.5 s
wait_for() {
    t=$(($1 * 2))
    shift
    while [ $t -gt 0 ]; do "$@" && return 0; sleep 0.5; t=$((t - 1)); done
    return 1
}

# watched SECONDS COMMAND...: a command that may hang in the kernel (an unbind or an rmmod in a slow guest has
# stayed in D state, where `timeout` cannot kill it and waits for ever) runs in the background and is only watched.
# 0: done; 1: it failed; 2: still not done after SECONDS (it is left behind).
watched() {
    _r=/tmp/watched.$$.rc
    _t=$(($1 * 10))
    shift
    rm -f $_r
    # The command reports through a file: whether a finished background child still "exists" (a zombie until the
    # shell reaps it) is not a question kill -0 answers.
    ("$@" 2>/dev/null; echo $? >$_r.tmp && mv $_r.tmp $_r) &
    while [ $_t -gt 0 ]; do
        if [ -s $_r ]; then
            _rc=$(cat $_r)
            rm -f $_r
            [ "$_rc" = 0 ] && return 0
            return 1
        fi
        sleep 0.1
        _t=$((_t - 1))
    done
    return 2
}
# sysfs_write FILE VALUE SECONDS: echo VALUE >FILE, watched.
sysfs_write() { watched "$3" sh -c 'echo "$1" >"$2"' sysfs_write "$2" "$1"; }

# The guest has no network device, only lo, and it is down after boot: the checks that talk HTTP bring it up.
loopback_up() { ip link set lo up 2>/dev/null || ifconfig lo 127.0.0.1 up; }

# libcamera only enumerates devices udev has initialised, and hears of unplugs only from udevd: udev_start runs
# Debian's udevd (staged by the harness) once per boot, as a real system does, and sets UDEVD=1; without it,
# udev_initialise writes udev's database by hand (no hot-plug then).
udev_start() {
    UDEVD=0
    [ -x /usr/lib/systemd/systemd-udevd ] || return 0
    mkdir -p /run/udev
    if pidof systemd-udevd >/dev/null || /usr/lib/systemd/systemd-udevd --daemon 2>/tmp/udevd.log; then UDEVD=1; fi
}
udev_initialise() {
    if [ "$UDEVD" = 1 ]; then
        udevadm trigger --action=add && udevadm settle --timeout=30
        return
    fi
    mkdir -p /run/udev/data
    for d in /sys/bus/media/devices/* /sys/class/video4linux/*; do echo "I:1" >"/run/udev/data/c$(cat "$d/dev")"; done
}

# gpio-sim (built out of tree by the harness): a simulated GPIO chip made through configfs. One bank, labelled NAME;
# the outside world drives a line the way a switch would, by its simulated pull, and reads what a program drives.
# gpiosim_chip NAME LINES "OFFSET:LINENAME ...": makes and brings live the chip, prints the /dev/gpiochipN it became.
gpiosim_chip() {
    modprobe gpio-sim || return 1
    [ -d /sys/kernel/config/gpio-sim ] || mount -t configfs none /sys/kernel/config 2>/dev/null
    [ -d /sys/kernel/config/gpio-sim ] || return 1
    _d=/sys/kernel/config/gpio-sim/$1
    mkdir "$_d" "$_d/bank0" && echo "$2" >"$_d/bank0/num_lines" && echo "$1" >"$_d/bank0/label" || return 1
    for _l in $3; do
        mkdir "$_d/bank0/line${_l%%:*}" && echo "${_l#*:}" >"$_d/bank0/line${_l%%:*}/name" || return 1
    done
    echo 1 >"$_d/live" || return 1
    _c=$(cat "$_d/bank0/chip_name") # gpiochipN, once live
    for _ in 1 2 3 4 5 6 7 8 9 10; do
        [ -e "/sys/bus/gpio/devices/$_c" ] && [ -c "/dev/$_c" ] && echo "/dev/$_c" && return 0
        sleep 0.2
    done
    return 1
}
# gpiosim_sys NAME: the chip's sysfs folder, /sys/devices/platform/gpio-sim.N/gpiochipM, with sim_gpioK/{pull,value}
gpiosim_sys() {
    _d=/sys/kernel/config/gpio-sim/$1
    echo "/sys/devices/platform/$(cat "$_d/dev_name")/$(cat "$_d/bank0/chip_name")"
}
# gpiosim_pull NAME OFFSET pull-up|pull-down: what an input line reads while no one drives it (an edge for a
# program that watches it). A program that requests the line with a bias changes this pull itself.
gpiosim_pull() { echo "$3" >"$(gpiosim_sys "$1")/sim_gpio$2/pull"; }
# gpiosim_value NAME OFFSET: the line's level, 0 or 1 (what a program drives on an output). On release gpio-sim
# sets the line back to its pull, whatever was driven last.
gpiosim_value() { cat "$(gpiosim_sys "$1")/sim_gpio$2/value"; }
# gpiosim_remove NAME: takes the chip down and removes it from configfs (every line folder first).
gpiosim_remove() {
    _d=/sys/kernel/config/gpio-sim/$1
    [ -d "$_d" ] || return 0
    echo 0 >"$_d/live"
    for _l in "$_d"/bank*/line*/hog "$_d"/bank*/line* "$_d"/bank*; do [ -d "$_l" ] && rmdir "$_l"; done
    rmdir "$_d"
}
