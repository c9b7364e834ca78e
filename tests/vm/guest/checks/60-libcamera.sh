# SPDX-License-Identifier: Apache-2.0
# libcamera: vimc's camera through Debian's libcamera 0.0.3 (vimc pipeline handler and IPA) into the real overlayd.
# list-cameras lists the sensor; render writes a Y4M at the asked size (the host's ffprobe reads it) with the axes
# where `overlayd project` puts them over Sensor B's black test pattern; a format vimc lacks is adjusted and logged
# once; unbinding vimc while `run` streams gives NO SIGNAL frames and the daemon stays up (libcamera 0.0.3 does not
# let it pick the camera up again: see the end).
. /vm/lib.sh

have_overlayd || { fail libcamera "no overlayd binary was staged (build the overlayd target)"; exit 0; }
[ -e /usr/lib/x86_64-linux-gnu/libcamera/ipa_vimc.so ] || { fail libcamera "libcamera's vimc IPA was not staged"; exit 0; }
mkdir -p "$ART"

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
    if ! timeout 120 overlayd render --config "$cfg" --frames $FRAMES --output "$out" >/tmp/$name.log 2>&1; then
        fail "$name" "overlayd render exited non-zero: $(tail -3 /tmp/$name.log | tr '\n' ' ')"
        continue
    fi
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
rmmod vivid

# Unplug: unbind vimc under a running overlayd, then bind it again.
rmmod vimc && modprobe vimc && sleep 1 && udev_initialise # the default colour bars again
OUT=/tmp/lc-unplug.y4m
rm -f $OUT
overlayd run --config /vm/configs/libcamera-unplug.toml >/tmp/lc-unplug.log 2>&1 &
pid=$!
PROBE_X=10 PROBE_Y=340 # low on vimc's leftmost colour bar

wait_for 60 is_live
verdict libcamera-unplug-streaming $? "before: $(frames) frames, last pixel ($(probe))"
echo "-- unbinding vimc at $(uptime_s)s"
timeout 20 sh -c 'echo vimc.0 >/sys/bus/platform/drivers/vimc/unbind' || echo "-- unbind failed or hung"
n0=$(frames)
wait_for 20 is_nosignal
ns=$?
sleep 2
n1=$(frames)
kill -0 $pid 2>/dev/null && [ $ns = 0 ] && [ "$n1" -gt "$n0" ]
verdict libcamera-unplug-no-signal $? "vimc unbound at frame $n0; $n1 frames 2+ s later, last pixel ($(probe))"

kill -0 $pid 2>/dev/null
verdict libcamera-unplug-still-running $? "overlayd still runs (NO SIGNAL) while the camera is gone"
grep -q 'stopped answering: it is left as it is' /tmp/lc-unplug.log
verdict libcamera-unplug-parked $? "the log says why: $(grep -m1 'stopped answering' /tmp/lc-unplug.log | cut -c1-120)"

# What this libcamera cannot do: libcamera 0.0.3 neither notices vimc going away (no cameraRemoved, even with
# udevd's events) nor survives being asked to stop it (PipelineHandler::stop asserts), and binding vimc again under
# the process that holds the parked camera has crashed it (SIGSEGV in libcamera's thread) or hung the bind. So the
# recovery proven here is the one a unit gets from systemd's Restart=: the old process stops on SIGTERM, vimc is
# bound again, and a new overlayd finds the camera and streams.
stop_overlayd $pid
rc=$?
[ $rc = 0 ]
verdict libcamera-unplug-stops $? "overlayd with the parked camera exited $rc after SIGTERM"
echo "-- binding vimc at $(uptime_s)s"
timeout 20 sh -c 'echo vimc.0 >/sys/bus/platform/drivers/vimc/bind' || echo "-- bind failed or hung"
sleep 1 && timeout 40 sh -c '. /vm/lib.sh; UDEVD='"$UDEVD"' udev_initialise'
rm -f $OUT
overlayd run --config /vm/configs/libcamera-unplug.toml >/tmp/lc-replug.log 2>&1 &
pid=$!
wait_for 60 is_live
verdict libcamera-replug-new-process $? "a new overlayd after the re-bind: $(frames) frames, last pixel ($(probe))"
stop_overlayd $pid
grep -i -E 'signal|lost|retry|back|libcamera' /tmp/lc-unplug.log | head -10
timeout 20 rmmod vimc || echo "-- rmmod vimc failed"
exit 0
