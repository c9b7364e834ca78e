# SPDX-License-Identifier: Apache-2.0
# GPIO: a gpio-sim chip (made through configfs) with named lines, and Debian's gpiod tools (libgpiod 1.6) as the
# independent client. An input line switches the "guides" layer of `overlayd run` (the axes over vivid's black
# pattern, read back from its Y4M file where `overlayd project` puts them); an output line follows the stream (1 while
# frames flow, 0 at NO SIGNAL, released at exit); a line another process holds is refused naming that process.
# The outside world drives the input as a switch would: by the simulated pull (sim_gpioN/pull in sysfs).
. /vm/lib.sh

have_overlayd || { fail gpio "no overlayd binary was staged (build the overlayd target)"; exit 0; }
command -v gpioinfo >/dev/null || { fail gpio "Debian's gpiod tools were not staged (host package gpiod)"; exit 0; }
mkdir -p "$ART"

SIM=overlayd-sim # the chip's label; configs/gpio.toml names the output's chip by it
IN=0 LED=1       # offsets of REVERSE_IN and STREAM_OK
WHITE_YCC="235 128 128"
MARK_X=300 MARK_Y=160 # inside the white rect of configs/gpio.toml: the default layer, drawn whatever the input says

cleanup() {
    [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null && stop_overlayd "$pid"
    gpiosim_remove $SIM
    rmmod gpio-sim irq_sim 2>/dev/null
    rmmod vivid 2>/dev/null
}

# The chip, and the tools seeing it: names, and the pull driving what an input reads.
DEVGPIO=$(gpiosim_chip $SIM 8 "$IN:REVERSE_IN $LED:STREAM_OK")
if [ -z "$DEVGPIO" ]; then
    fail gpio-sim-chip "making the gpio-sim chip failed: $(ls /sys/kernel/config/gpio-sim 2>&1 | tr '\n' ' ')"
    cleanup
    exit 0
fi
CHIP=${DEVGPIO#/dev/}
gpioinfo "$CHIP" >/tmp/gpioinfo.txt 2>&1
gpiosim_pull $SIM $IN pull-up && up=$(gpioget "$CHIP" $IN)
gpiosim_pull $SIM $IN pull-down && down=$(gpioget "$CHIP" $IN)
grep -q "line *$IN: *\"REVERSE_IN\" *unused" /tmp/gpioinfo.txt && grep -q "line *$LED: *\"STREAM_OK\" *unused" /tmp/gpioinfo.txt &&
    [ "$up$down" = 10 ]
verdict gpio-sim-chip $? "$DEVGPIO '$SIM' ($(gpiosim_sys $SIM)); gpioinfo:$(grep -E "line +($IN|$LED):" /tmp/gpioinfo.txt |
    tr -s ' \t' ' ' | tr '\n' ';'); gpioget after pull-up $up, after pull-down $down"

# list-gpio: what a user reads to write [[gpio.*]].
overlayd list-gpio >/tmp/list-gpio.txt 2>&1
rc=$?
overlayd list-gpio --json >/tmp/list-gpio.json 2>&1
[ $rc = 0 ] && grep -q "^$CHIP '$SIM' ($DEVGPIO, 8 lines)" /tmp/list-gpio.txt &&
    grep -q "^ *line $IN 'REVERSE_IN' input" /tmp/list-gpio.txt && grep -q "^ *line $LED 'STREAM_OK'" /tmp/list-gpio.txt &&
    grep -q '"name": "REVERSE_IN"' /tmp/list-gpio.json
verdict gpio-list $? "exit $rc: $(grep -A2 "^$CHIP " /tmp/list-gpio.txt | tr -s ' ' | tr '\n' ';')"
cp /tmp/list-gpio.txt /tmp/list-gpio.json "$ART/" 2>/dev/null

# overlayd run on vivid (black) with the input pulled down: the guides start hidden.
vivid_load n_devs=1 node_types=0x1 multiplanar=1 || { fail gpio-run "modprobe vivid failed"; cleanup; exit 0; }
DEV=$(node vivid-000-vid-cap)
black_pattern "$DEV"
config_for gpio.toml /tmp/gpio.toml "device=\"$DEV\"" "chip=\"$CHIP\""
OUT=/tmp/gpio.y4m
rm -f $OUT
gpiosim_pull $SIM $IN pull-down
overlayd run --config /tmp/gpio.toml >/tmp/gpio-run.log 2>&1 &
pid=$!
points=$(axes_points /tmp/gpio.toml)
echo "-- overlayd run ($pid) on $DEV, input $CHIP '$SIM' line REVERSE_IN; axes at $(echo "$points" | tr '\n' ';')"

have_frames() { [ "$(frames)" -ge "$1" ]; }
newest() { _n=$(frames) && [ "$_n" -gt 0 ] && NEWEST=$((_n - 1)) && PIXEL="y4m_pixel $OUT $NEWEST"; }
marker() {
    _m=$($PIXEL $MARK_X $MARK_Y)
    summary="$summary marker=($_m)"
    near "$_m" "$WHITE_YCC" 12
}
point() { echo "$points" | sed -n "$1p"; }
# no_axes_in FRAME: none of the three projected points has its axis colour (the frame may be live or NO SIGNAL)
no_axes_in() {
    PIXEL="y4m_pixel $OUT $1" summary='' _r=0
    axis_probe "$(point 1)" "$RED_YCC" X && _r=1
    axis_probe "$(point 2)" "$GREEN_YCC" Y && _r=1
    axis_probe "$(point 3)" "$BLUE_YCC" Z && _r=1
    return $_r
}
# guides_hidden / guides_shown: the newest frame is live (black corner, the white marker) and the three points are
# black / their axis colours.
guides_hidden() {
    newest || return 1
    summary='' _r=0
    axis_probe "$(point 1)" "$BLACK_YCC" X || _r=1
    axis_probe "$(point 2)" "$BLACK_YCC" Y || _r=1
    axis_probe "$(point 3)" "$BLACK_YCC" Z || _r=1
    _c=$($PIXEL 3 3) && summary="$summary corner=($_c)" && near "$_c" "$BLACK_YCC" 12 || _r=1
    marker || _r=1
    return $_r
}
guides_shown() { newest && axes_check "$points" && marker; }

pointsok=1
[ "$(echo "$points" | grep -c '^[0-9]* [0-9]*$')" = 3 ] && pointsok=0
wait_for 60 have_frames 5
started=$?
no_axes_in 0
first=$?
first_summary=$summary
wait_for 5 guides_hidden
hidden=$?
[ $pointsok = 0 ] && [ $started = 0 ] && [ $first = 0 ] && [ $hidden = 0 ] && kill -0 $pid 2>/dev/null
verdict gpio-input-start-hidden $? "REVERSE_IN pulled down before the start: frame 0:$first_summary; frame $NEWEST:$summary"

# The edges. The sim pull is written, then the newest complete frame is polled at the X axis point (its luma only:
# two forks per poll) until it changes: the guest's wall time from the write to that poll is an upper bound of the
# edge-to-frame latency (it includes the poll's own period, a few hundred ms under TCG with overlayd busy). Then the
# frames are read back from the one being written at the write: the first that shows the change, counted in frames
# (10 fps: 100 ms each), bounds it more finely.
set -- $(y4m_geometry $OUT) 0 0 0 0 0
FW=$1 HDR=$4 FB=$5
XU=0 XV=0
[ $pointsok = 0 ] && XU=$(point 1 | cut -d' ' -f1) XV=$(point 1 | cut -d' ' -f2)
PULL=$(gpiosim_sys $SIM)/sim_gpio$IN/pull
now_cs() { read -r _u _x </proc/uptime && NOW=${_u%.*}${_u#*.}; } # centiseconds, no fork
luma_of() { od -An -tu1 -j $((HDR + $1 * (FB + 6) + 6 + XV * FW + XU)) -N1 $OUT; } # FRAME
in_range() { [ -n "$1" ] && [ $1 -ge "$2" ] && [ $1 -le "$3" ]; }                # LUMA LO HI
# edge PULL LO HI: sets $ms (empty on a 15 s time-out), $polls, $k (the first frame whose luma is in LO..HI) and
# $nth (k's number among the frames completed after the write; empty if none)
edge() {
    polls=0 ms='' k='' nth=''
    size0=$(wc -c <$OUT)
    now_cs && t0=$NOW
    echo "$1" >"$PULL"
    while now_cs && [ $((NOW - t0)) -lt 1500 ]; do
        size=$(wc -c <$OUT)
        y=$(luma_of $(((size - HDR) / (FB + 6) - 1)))
        polls=$((polls + 1))
        if in_range "$y" "$2" "$3"; then
            now_cs && ms=$(((NOW - t0) * 10))
            break
        fi
    done
    f0=$(((size0 - HDR) / (FB + 6))) # complete before the write: frame f0 was the one being written, or the next
    _f=$f0 _n=$(frames)
    while [ $_f -lt $_n ]; do
        in_range "$(luma_of $_f)" "$2" "$3" && k=$_f nth=$((_f - f0 + 1)) && break
        _f=$((_f + 1))
    done
}
edge pull-up 69 93 # red's luma, 81 +- 12
up_ms=$ms up_polls=$polls up_nth=$nth
wait_for 5 guides_shown
shown=$?
[ -n "$up_ms" ] && [ $shown = 0 ]
verdict gpio-input-shows $? "pull-up: first seen ${up_ms:-never (15 s)} ms after the write, in frame ${k:-?}\
 (#${nth:-?} of those completed after it); frame $NEWEST:$summary"
sleep 1
edge pull-down 4 28 # black's luma, 16 +- 12
down_ms=$ms down_polls=$polls down_nth=$nth
wait_for 5 guides_hidden
hidden=$?
[ -n "$down_ms" ] && [ $hidden = 0 ]
verdict gpio-input-hides $? "pull-down: first seen ${down_ms:-never (15 s)} ms after the write, in frame ${k:-?}\
 (#${nth:-?} of those completed after it); frame $NEWEST:$summary"
echo "MEASURE gpio-latency: sim pull written -> first Y4M frame seen with the guides ${up_ms:-?} ms" \
    "(polls: $up_polls), without them ${down_ms:-?} ms (polls: $down_polls): upper bounds (guest wall time, 10 ms" \
    "clock, the poll's own period included); counted in frames, each change is in frame #${up_nth:-?} / #${down_nth:-?}" \
    "of those completed after the write (100 ms each at 10 fps; includes the 20 ms debounce)"

# The output: active while frames flow, as gpio-sim (the line's level) and gpioinfo (its holder) say.
value=$(gpiosim_value $SIM $LED)
held=$(gpioinfo "$CHIP" 2>&1 | grep -E "line +($IN|$LED):" | tr -s ' \t' ' ' | tr '\n' ';')
[ "$value" = 1 ] && echo "$held" | grep -q "line $LED: \"STREAM_OK\" \"overlayd\" output" &&
    echo "$held" | grep -q "line $IN: \"REVERSE_IN\" \"overlayd\" input"
verdict gpio-output-streaming $? "STREAM_OK sim value $value while streaming; gpioinfo:$held"

# vivid unbound under the open fd (as 50-unplug.sh): the reads fail, NO SIGNAL frames follow, the output goes inactive.
PROBE_X=3 PROBE_Y=3 # black while live, grey in the NO SIGNAL frame
led_is() { [ "$(gpiosim_value $SIM $LED)" = "$1" ]; }
now_cs && t0=$NOW
timeout 20 sh -c 'echo vivid.0 >/sys/bus/platform/drivers/vivid/unbind' || echo "-- unbind failed or hung"
wait_for 10 led_is 0
led=$?
now_cs && waited=$(((NOW - t0) * 10))
wait_for 5 is_nosignal
ns=$?
[ $led = 0 ] && [ $ns = 0 ] && kill -0 $pid 2>/dev/null
verdict gpio-output-no-signal $? "vivid unbound: STREAM_OK $(gpiosim_value $SIM $LED) after $waited ms; newest frame $(frames), corner ($(probe))"
wait_for 5 timeout 10 rmmod vivid 2>/dev/null || echo "-- rmmod vivid failed"
vivid_load n_devs=1 node_types=0x1 multiplanar=1 || echo "-- modprobe vivid failed"
wait_for 30 led_is 1
verdict gpio-output-recovered $? "vivid back: STREAM_OK $(gpiosim_value $SIM $LED); newest frame $(frames), corner ($(probe))"

# A clean stop: exit 0 and both lines released. gpio-sim sets a released line back to its pull (pull-down: 0), so
# the level is 0 whether or not the daemon drove it inactive first (the unit tests prove that order).
before=$(gpiosim_value $SIM $LED)
stop_overlayd $pid
rc=$?
pid=''
value=$(gpiosim_value $SIM $LED)
held=$(gpioinfo "$CHIP" 2>&1 | grep -E "line +($IN|$LED):" | tr -s ' \t' ' ' | tr '\n' ';')
[ $rc = 0 ] && [ "$value" = 0 ] && ! echo "$held" | grep -q overlayd
verdict gpio-output-released $? "exit $rc after SIGTERM; STREAM_OK $before before, $value after; gpioinfo:$held"
grep -E "gpio: input|notice|warning|error" /tmp/gpio-run.log | head -12
grep 'gpio: ' /tmp/gpio-run.log | tail -1
cp /tmp/gpio-run.log "$ART/gpio-run.log" 2>/dev/null
rm -f $OUT

# A line held by another process: overlayd refuses to start and names the holder.
gpiomon "$CHIP" $IN >/tmp/gpiomon.log 2>&1 &
mon=$!
sleep 1
holder=$(gpioinfo "$CHIP" 2>&1 | grep -E "line +$IN:" | tr -s ' \t' ' ')
timeout 40 overlayd run --config /tmp/gpio.toml >/tmp/gpio-busy.log 2>&1
rc=$?
kill $mon 2>/dev/null
wait $mon 2>/dev/null
[ $rc != 0 ] && grep -q "REVERSE_IN.*'gpiomon'" /tmp/gpio-busy.log
verdict gpio-line-busy $? "held by gpiomon ($holder): overlayd run exited $rc: $(grep -m1 -i 'gpiomon\|error' /tmp/gpio-busy.log | cut -c1-200)"

cleanup
exit 0
