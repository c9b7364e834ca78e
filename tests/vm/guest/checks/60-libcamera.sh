# SPDX-License-Identifier: Apache-2.0
# libcamera: vimc's camera through libcamera 0.3.2 (Debian bookworm-backports: vimc pipeline handler and IPA) into
# the real overlayd. list-cameras lists the sensor; render writes a Y4M at the asked size (the host's ffprobe reads
# it) with the axes where `overlayd project` puts them over Sensor B's black test pattern; a format vimc lacks is
# adjusted and logged once; vimc unbound and bound again five times while `run` streams: NO SIGNAL after each unbind
# and the unplugged camera stopped with its device nodes closed before the bind,
# the overlaid camera again after each bind, in the same process, with no fd or thread growth; SIGTERM during a
# re-plug exits 0.
. /vm/lib.sh

have_overlayd || { fail libcamera "no overlayd binary was staged (build the overlayd target)"; exit 0; }
[ -e /usr/lib/x86_64-linux-gnu/libcamera/ipa_vimc.so ] || { fail libcamera "libcamera's vimc IPA was not staged"; exit 0; }
mkdir -p "$ART"
# The libcamera overlayd was built against (0.3, libcamera.so.0.3), staged with its IPA modules.
ls /usr/lib/x86_64-linux-gnu/libcamera.so.0.3 >/dev/null 2>&1
verdict libcamera-version $? "the guest's libcamera: $(ls /usr/lib/x86_64-linux-gnu/ | grep '^libcamera.*\.so' | tr '\n' ' ')"

udev_start
echo "-- udevd running: $UDEVD"
subdev() { # NAME: the /dev/v4l-subdev* whose sysfs name is NAME
    for n in /sys/class/video4linux/v4l-subdev*; do
        [ "$(cat "$n/name")" = "$1" ] && echo "/dev/${n##*/}" && return 0
    done
    return 1
}

modprobe vimc && sleep 1 || { fail libcamera "modprobe vimc failed"; exit 0; }
udev_initialise

overlayd list-cameras >/tmp/lc-list.txt 2>&1
overlayd list-cameras --json >/tmp/lc-list.json 2>/dev/null
grep -q "^libcamera .*'Sensor B'" /tmp/lc-list.txt && grep -q '"api": "libcamera"' /tmp/lc-list.json &&
    grep -q 'RGB24' /tmp/lc-list.txt
verdict libcamera-list $? "$(grep -A3 '^libcamera' /tmp/lc-list.txt | tr '\n' ';' | cut -c1-300)"
cp /tmp/lc-list.txt /tmp/lc-list.json "$ART/" 2>/dev/null

# A known picture: Sensor B's test pattern set to "100% Black" (libcamera's vimc pipeline leaves it alone).
SENSOR=$(subdev "Sensor B")
black=$(v4l2-ctl -d "$SENSOR" --list-ctrls-menus | sed -n 's/^[[:space:]]*\([0-9]*\): 100% Black.*/\1/p' | head -1)
v4l2-ctl -d "$SENSOR" -c "test_pattern=${black:-5}"
echo "-- Sensor B ($SENSOR) test_pattern=$(v4l2-ctl -d "$SENSOR" -C test_pattern)"

FRAMES=3
for FMT in RGB24 BGR24; do
    name=capture-libcamera-$FMT-1278x720 cfg=/tmp/lc-$FMT.toml out=/tmp/lc-$FMT.y4m
    config_for libcamera.toml "$cfg" "format=\"$FMT\""
    t0=$(uptime_s)
    if ! timeout 120 overlayd render --config "$cfg" --frames $FRAMES --output "$out" >/tmp/$name.log 2>&1; then
        fail "$name" "overlayd render exited non-zero: $(tail -3 /tmp/$name.log | tr '\n' ' ')"
        continue
    fi
    echo "-- render of $FRAMES frames: $t0 s to $(uptime_s) s"
    set -- $(y4m_geometry "$out")
    want=$(($4 + FRAMES * ($5 + 6)))
    size=$(wc -c <"$out")
    [ -s /tmp/lc-points ] || axes_points "$cfg" >/tmp/lc-points
    PIXEL="y4m_pixel $out $((FRAMES - 1))"
    axes_check "$(cat /tmp/lc-points)"
    axes=$?
    [ "$1x$2" = "1278x720" ] && [ "$3" = 444 ] && [ "$size" = "$want" ] && [ $axes = 0 ]
    verdict "$name" $? "Y4M ${1}x$2 C$3 $size bytes (want 1278x720 C444 $want); axes:$summary"
    cp "$out" "$ART/$name.y4m" 2>/dev/null
    rm -f "$out"
done

# vimc offers RGB formats only: NV12 is adjusted by libcamera's validate(), and the source says so once.
config_for libcamera.toml /tmp/lc-nv12.toml 'format="NV12"'
timeout 120 overlayd render --config /tmp/lc-nv12.toml --frames 2 --output /tmp/lc-nv12.y4m >/tmp/lc-nv12.log 2>&1
rc=$?
line=$(grep 'asked 1278x720 NV12, got 1278x720 ' /tmp/lc-nv12.log)
[ $rc = 0 ] && [ "$(echo "$line" | grep -c .)" = 1 ]
verdict libcamera-adjusted $? "exit $rc; log: $line"

# An unknown control is refused at start, naming file, line and key (the range comes from the opened camera).
cat /vm/configs/libcamera.toml >/tmp/lc-ctrl.toml
sed -i 's/^no_signal_timeout = 3.0$/no_signal_timeout = 3.0\ncontrols = { Brightness = 7.5 }/' /tmp/lc-ctrl.toml
timeout 60 overlayd render --config /tmp/lc-ctrl.toml --frames 1 --output /tmp/lc-ctrl.y4m >/tmp/lc-ctrl.log 2>&1
rc=$?
[ $rc != 0 ] && grep -q '/tmp/lc-ctrl.toml:[0-9]*:[0-9]*: source.libcamera.controls.Brightness: ' /tmp/lc-ctrl.log
verdict libcamera-control-range $? "exit $rc: $(grep -m1 Brightness /tmp/lc-ctrl.log)"

# The daemon streams from libcamera into vivid's output node with zero_copy = "auto" and stops cleanly on SIGTERM
# (the camera stopped, released, exit 0). Zero copy: libcamera's buffers (exported by vimc) queued on vivid's output
# by DMABUF; if the kernel refuses, the sink says why and copies, and the check says which path it proved.
vivid_load n_devs=1 node_types=0x101 multiplanar=1 || fail libcamera-run "modprobe vivid failed"
VOUT=$(node vivid-000-vid-out)
cp /tmp/lc-RGB24.toml /tmp/lc-run.toml
printf '\n[[sink]]\nkind = "v4l2"\npath = "%s"\nbuffers = 4\nzero_copy = "auto"\n' "$VOUT" >>/tmp/lc-run.toml
overlayd run --config /tmp/lc-run.toml >/tmp/lc-run.log 2>&1 &
pid=$!
sleep 10
grep -q 'notice: streaming from libcamera' /tmp/lc-run.log
streaming=$?
stop_overlayd $pid
rc=$?
[ $streaming = 0 ] && [ $rc = 0 ]
verdict libcamera-run-exit $? "streaming: $(grep -c 'streaming from libcamera' /tmp/lc-run.log) line(s); exit $rc after SIGTERM"
# The sink's own account at close: "<device>: N frames out: Z zero-copy, C copied, D dropped".
set -- $(sed -n 's/.*: \([0-9]*\) frames out: \([0-9]*\) zero-copy, \([0-9]*\) copied, \([0-9]*\) dropped.*/\1 \2 \3 \4/p' \
    /tmp/lc-run.log | tail -1) 0 0 0 0
if grep -q 'zero copy: the capture buffers are queued by DMABUF' /tmp/lc-run.log; then
    [ "$1" -gt 0 ] && [ "$2" = "$1" ] && [ "$3" = 0 ]
    verdict libcamera-zerocopy $? "$VOUT took libcamera's buffers by DMABUF: $1 frames out, $2 zero-copy, $3 copied"
else
    [ "$1" -gt 0 ] && [ "$3" = "$1" ]
    verdict libcamera-zerocopy-refused-copied $? "no zero copy ($(grep -m1 -o 'no zero copy: [^)]*' /tmp/lc-run.log)):" \
        "the copy path instead, $1 frames out, $3 copied"
fi
grep -E 'v4l2|zero|frames out' /tmp/lc-run.log | tail -3
cp /tmp/lc-run.log "$ART/libcamera-run.log"
watched 20 rmmod vivid || echo "-- rmmod vivid failed or hung"

# Unplug and re-plug, five times, under one running overlayd. libcamera 0.3.2's vimc pipeline never reports an
# unplug: overlayd sees no frame, shows NO SIGNAL within the stall timeout (no_signal_timeout = 2 s, plus the first
# NO SIGNAL frame's pacing), stops and releases the camera (its device fds closed) and lets libcamera's camera
# manager go before vimc is bound again (a manager that still lists the camera aborts on its return); the same
# process then finds Sensor B in a fresh manager, configures and starts it again.
# Each sysfs write is watched, not waited for (sysfs_write): a write stuck in the kernel is a FAIL, never a hang.
# vimc again, for its default colour bars.
watched 30 rmmod vimc || { fail libcamera-unplug-streaming "rmmod vimc failed or hung in the kernel"; exit 0; }
watched 30 modprobe vimc && sleep 1 && udev_initialise
OUT=/tmp/lc-unplug.y4m
rm -f $OUT
overlayd run --config /vm/configs/libcamera-unplug.toml >/tmp/lc-unplug.log 2>&1 &
pid=$!
PROBE_X=10 PROBE_Y=340 # low on vimc's leftmost colour bar
UNBIND=/sys/bus/platform/drivers/vimc/unbind BIND=/sys/bus/platform/drivers/vimc/bind
# Alive: not exited and not a zombie (this shell has not reaped it yet, so kill -0 still succeeds on a dead one).
running() { [ -r /proc/$pid/status ] && ! grep -q '^State:[[:space:]]*Z' /proc/$pid/status; }
fds() { ls /proc/$pid/fd 2>/dev/null | wc -l; }
threads() { ls /proc/$pid/task 2>/dev/null | wc -l; }
# The camera's device nodes overlayd holds open: after an unplug, 0 once it let the old camera go.
devfds() { ls -l /proc/$pid/fd 2>/dev/null | grep -c -E '/dev/(video|media|v4l-subdev)'; }
released() { [ "$(devfds)" = 0 ]; }
# A kernel hang in vimc's unbind or bind is reported on the console (hung-task warnings after 20 s).
dmesg -n 7 2>/dev/null
echo 20 >/proc/sys/kernel/hung_task_timeout_secs 2>/dev/null

wait_for 60 is_live
verdict libcamera-unplug-streaming $? "before: $(frames) frames, last pixel ($(probe)); $(fds) fds, $(threads) threads"
cycles=0 stuck="" detail="" http=0 http_back=0
URL=http://127.0.0.1:8091
loopback_up # for curl
for i in 1 2 3 4 5; do
    echo "-- cycle $i: unbinding vimc at $(uptime_s)s"
    sysfs_write $UNBIND vimc.0 20
    w=$?
    [ $w = 0 ] || { stuck="unbind $i: $([ $w = 2 ] && echo 'still in the kernel after 20 s' || echo failed)"; break; }
    n0=$(frames)
    wait_for 8 is_nosignal
    ns=$?
    n1=$(frames)
    # The old instance's nodes, closed once overlayd stopped and released the camera and let its manager go:
    # required before the bind (a manager still listing the camera aborts when it comes back).
    wait_for 10 released
    rel=$?
    # The HTTP surface stays up while the camera is gone (configs/libcamera-unplug.toml's [http]).
    http_gone=$(curl -sf -m 5 $URL/state | grep -o '"source":{[^}]*"state":"[a-z]*"' | grep -o '"state":"[a-z]*"')
    snap=$(curl -sf -m 5 -o /tmp/lc-snap.jpg -w '%{content_type} %{size_download}' $URL/snapshot)
    [ "$http_gone" = '"state":"waiting"' ] && [ "${snap%% *}" = image/jpeg ] && http=$((http + 1))
    echo "-- cycle $i: NO SIGNAL $ns, frames $n0 -> $n1, device fds $(devfds) (released $rel); /state $http_gone," \
        "/snapshot $snap; overlayd says:"
    tail -n 4 /tmp/lc-unplug.log | cut -c1-200
    echo "-- cycle $i: binding vimc at $(uptime_s)s"
    sysfs_write $BIND vimc.0 20
    w=$?
    [ $w = 0 ] || { stuck="bind $i: $([ $w = 2 ] && echo 'still in the kernel after 20 s' || echo failed)"; break; }
    [ "$UDEVD" = 1 ] || udev_initialise
    wait_for 60 is_live
    live=$?
    running
    alive=$?
    curl -sf -m 5 $URL/state | grep -q '"source":{[^}]*"state":"streaming"' && http_back=$((http_back + 1))
    [ $i = 1 ] && fd1=$(fds) th1=$(threads)
    detail="$detail [$i: nosignal=$ns frames $n0->$n1 released=$rel live=$live alive=$alive fds=$(fds) threads=$(threads)]"
    echo "-- cycle $i: live $live at $(uptime_s)s"
    [ $ns = 0 ] && [ "$n1" -gt "$n0" ] && [ $rel = 0 ] && [ $live = 0 ] && [ $alive = 0 ] && cycles=$((cycles + 1))
done
[ -z "$stuck" ]
verdict libcamera-replug-sysfs $? "${stuck:-every unbind and bind returned}"
[ $cycles = 5 ]
verdict libcamera-replug-5-cycles $? "$cycles of 5 cycles NO SIGNAL, released, then live in pid $pid:$detail"
[ $http = 5 ] && [ $http_back = 5 ]
verdict libcamera-replug-http $? "camera gone: /state \"waiting\" and a /snapshot JPEG in $http of 5 cycles;" \
    "back: /state \"streaming\" in $http_back of 5"
fd5=$(fds) th5=$(threads)
running && [ "${fd1:-0}" -gt 0 ] && [ "$fd5" -le "$fd1" ] && [ "$th5" -le "$th1" ]
verdict libcamera-replug-no-growth $? "after cycle 1: ${fd1:-?} fds, ${th1:-?} threads; after cycle 5: $fd5 fds, $th5 threads"
grep -q 'was disconnected\|was removed\|was unplugged' /tmp/lc-unplug.log && grep -q 'is streaming again' /tmp/lc-unplug.log
verdict libcamera-replug-logged $? "$(grep -c 'streaming again' /tmp/lc-unplug.log) re-acquisitions logged;" \
    "$(grep -m1 'disconnected\|removed\|unplugged' /tmp/lc-unplug.log | cut -c1-160)"
# How many stops reached a capture node already gone (libcamera's STREAMOFF answered ENODEV, the ioctl shim let the
# stop complete): it depends on how far vimc's unbind got when the removal uevent was read, so it is reported only.
echo "-- $(grep -c 'was unplugged (its device is gone): stopped' /tmp/lc-unplug.log) of the stops found the node gone"
# Each loss came from the kernel's removal of the camera's node (its uevent), not from the stall timeout.
prompt=$(grep -c 'was unplugged (its device node went away)' /tmp/lc-unplug.log)
[ "$prompt" -ge 5 ]
verdict libcamera-replug-uevent $? "$prompt losses reported on the node's removal uevent, $(grep -c 'no frame for' \
    /tmp/lc-unplug.log) on the stall timeout (5 and 0 wanted)"

# SIGTERM while the camera is being picked up again: unbind, bind, and the signal at once.
if [ -z "$stuck" ]; then
    sysfs_write $UNBIND vimc.0 20 && wait_for 8 is_nosignal && sysfs_write $BIND vimc.0 20
    [ "$UDEVD" = 1 ] || udev_initialise
fi
stop_overlayd $pid
rc=$?
[ $rc = 0 ]
verdict libcamera-replug-sigterm $? "overlayd exited $rc after SIGTERM during a re-plug"
grep -i -E 'signal|lost|retry|back|libcamera|disconnect' /tmp/lc-unplug.log | head -20
cp /tmp/lc-unplug.log "$ART/libcamera-unplug.log"
[ -z "$stuck" ] && { watched 20 rmmod vimc || echo "-- rmmod vimc failed or hung"; }
exit 0
