# SPDX-License-Identifier: Apache-2.0
# [[input.can]]: the reverse camera's guide lines follow a steering-wheel angle read from SocketCAN. Debian's can,
# can-raw and vcan modules give a virtual bus, vcan0; can-utils' cangen plays the steering-angle sensor (one fixed
# frame every 50 ms, as an ECU repeats it), cansend sends single frames, and candump, on the same bus for the whole
# check, is the independent record of what was sent. overlayd runs configs/can-steering.toml (the synthetic checkerboard scene, [http] on
# 127.0.0.1:8090): started before vcan0 exists (an interface that appears later is opened by the retry); then angle A
# and angle B, a malformed frame (one data byte for a 16-bit signal), silence past the 500 ms timeout, a value
# outside min..max, and vcan0 going down and up again. /state (curl) must say what happened; the /snapshot JPEGs of each step (and one ?raw=1) go to $ART,
# where the host (tests/vm/host/can_steering.py, run by report.sh) finds the wheel tracks where its own Ackermann
# geometry, projected by `overlayd project`, puts them.
. /vm/lib.sh

NAME=can-steering
PORT=8090 # configs/can-steering.toml's [http] listen
URL=http://127.0.0.1:$PORT
A=400.0 A_DATA=0FA0         # raw 4000 * 0.1 deg: road-wheel angle 400 / 15 = 26.67 deg, turning left
B=-300.0 B_DATA=F448        # raw -3000 (two's complement 0xF448): -20 deg, turning right
RANGE=600.1 RANGE_DATA=1771 # raw 6001: above max = 540
PERIOD_MS=50                # the sender's period

have_overlayd || { fail $NAME "no overlayd binary was staged (build the overlayd target)"; exit 0; }
for tool in cansend cangen candump curl; do
    command -v $tool >/dev/null ||
        { fail $NAME "no $tool in the guest (the host package is missing: scripts/install-deps.sh)"; exit 0; }
done
mkdir -p "$ART"
rm -f "$ART"/can-steering-*

pid='' spid='' dpid=''
cleanup() {
    [ -n "$spid" ] && kill "$spid" 2>/dev/null
    [ -n "$dpid" ] && kill "$dpid" 2>/dev/null
    [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null && stop_overlayd "$pid"
    ip link del vcan0 2>/dev/null
    rmmod vcan can-raw can can-dev 2>/dev/null
}

# The modules, and lo for curl (the guest has no other network device).
ok=0 loaded=''
for m in can can-raw vcan; do modprobe $m && loaded="$loaded $m" || ok=1; done
loopback_up
mods=$(grep -E '^(can|can_raw|vcan|can_dev) ' /proc/modules | cut -d' ' -f1 | tr '\n' ' ')
verdict can-modules $ok "modprobe:$loaded (/proc/modules: $mods)"
[ $ok = 0 ] || { cleanup; exit 0; }

# can_entry: the "kind":"can" object of /state's "inputs" (flat, compact JSON, keys sorted: "interface" before
# "kind"; "input_health" has "kind":"can" objects too, without "interface"); field ENTRY KEY: its value, unquoted.
can_entry() { curl -s --max-time 5 "$URL/state" | grep -o '{[^{}]*"interface":[^{}]*"kind":"can"[^{}]*}' | head -1; }
field() { echo "$1" | sed -n "s/.*\"$2\":\"\{0,1\}\([^\",}]*\).*/\1/p"; }
same() { # VALUE WANT: within 0.05
    [ -n "$1" ] && [ "$1" != null ] && awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; exit !(d < 0.05 && d > -0.05) }'
}
brief() {
    echo "state=$(field "$1" state) value=$(field "$1" value) age_s=$(field "$1" age_s) frames=$(field "$1" frames)" \
        "malformed=$(field "$1" malformed) out_of_range=$(field "$1" out_of_range) connected=$(field "$1" connected)"
}
# await SECONDS TEST...: polls /state every 0.3 s until TEST "$E" holds; $E is the last entry read
await() {
    _n=$(($1 * 10 / 3))
    shift
    while [ $_n -gt 0 ]; do
        E=$(can_entry)
        "$@" && return 0
        sleep 0.3
        _n=$((_n - 1))
    done
    return 1
}
is_state() { [ "$(field "$E" state)" = "$1" ] && same "$(field "$E" value)" "$2"; }
is_connected() { [ "$(field "$E" connected)" = "$1" ]; }
snapshot() { curl -s -f --max-time 10 -o "$ART/$NAME-$1.jpg" "$URL/snapshot$2" && [ -s "$ART/$NAME-$1.jpg" ]; }

# overlayd first: vcan0 does not exist yet, and must not stop it.
cp /vm/configs/can-steering.toml "$ART/$NAME.toml"
overlayd run --config /vm/configs/can-steering.toml >/tmp/can-run.log 2>&1 &
pid=$!
_t=0
until E=$(can_entry) && [ -n "$E" ]; do
    _t=$((_t + 1))
    kill -0 $pid 2>/dev/null && [ $_t -le 90 ] || break
    sleep 1
done
if [ -z "$E" ]; then
    fail $NAME "overlayd run never answered /state (${_t} s): $(tail -5 /tmp/can-run.log | tr '\n' ' ')"
    cleanup
    exit 0
fi
before=$E
ip link add vcan0 type vcan && ip link set vcan0 up
made=$?
candump -L vcan0 >/tmp/candump.log 2>&1 &
dpid=$!
await 10 is_connected true
late=$?
[ -n "$before" ] && [ "$(field "$before" connected)" = false ] && [ "$(field "$before" state)" = no-data ] &&
    [ $made = 0 ] && [ $late = 0 ]
verdict $NAME-interface-late $? "before vcan0 existed (after ${_t} s of start-up): $(brief "$before") \
error='$(echo "$before" | sed -n 's/.*"error":"\([^"]*\)".*/\1/p')'; after ip link add/up (status $made): $(brief "$E")"

# The bus itself, through can-utils alone: what cansend puts on vcan0, candump reads. An id overlayd does not read.
sleep 1 # candump's start-up
cansend vcan0 123#DEADBEEF
sleep 0.5
grep -q 'vcan0 123#DEADBEEF' /tmp/candump.log
verdict can-vcan $? "cansend vcan0 123#DEADBEEF; candump -L: $(grep -m1 '123#' /tmp/candump.log)"

# step LABEL VALUE DATA: cangen repeats frame 025#DATA until /state shows VALUE ok, then the next overlaid frame is
# kept.
step() {
    cangen vcan0 -g $PERIOD_MS -I 025 -L 2 -D "$3" &
    spid=$!
    await 15 is_state ok "$2"
    _ok=$?
    snapshot "$1" && _snap=ok || { _snap=failed && _ok=1; }
    E=$(can_entry)
    is_state ok "$2" || _ok=1 # still fresh after the snapshot: the frame was drawn with it
    kill $spid
    wait $spid 2>/dev/null
    spid=''
    verdict $NAME-value-$1 $_ok "cangen vcan0 -g $PERIOD_MS -I 025 -L 2 -D $3: /state $(brief "$E") \
(want ok, $2 deg); snapshot $_snap"
}
printf 'A %s\nB %s\n' "$A" "$B" >"$ART/$NAME-angles.txt" # for the host
step a $A $A_DATA
snapshot raw "?raw=1" || echo "-- the raw snapshot failed"
step b $B $B_DATA

# A malformed frame: one data byte for a signal in bytes 0 and 1. Counted, and the value stays.
E=$(can_entry)
m0=$(field "$E" malformed) v0=$(field "$E" value)
cansend vcan0 025#0F
has_malformed() { [ "$(field "$E" malformed)" = $((m0 + 1)) ]; }
await 5 has_malformed
_ok=$?
same "$(field "$E" value)" "$B" && same "$v0" "$B" || _ok=1
verdict $NAME-malformed $_ok "cansend vcan0 025#0F (DLC 1): malformed $m0 -> $(field "$E" malformed) (want +1), \
value $v0 -> $(field "$E" value) (want $B); $(brief "$E")"

# Silence: 500 ms after the last valid frame the value is stale; the snapshot must show no wheel tracks.
sleep 1.2
await 5 is_state stale "$B"
_ok=$?
snapshot stale || _ok=1
E2=$(can_entry)
age=$(field "$E2" age_s)
[ "$(field "$E2" state)" = stale ] && awk -v a="$age" 'BEGIN { exit !(a > 0.5) }' || _ok=1
verdict $NAME-stale $_ok "no frame for > 500 ms: /state $(brief "$E2") (want stale, the last value $B, age_s > 0.5)"

# Out of range: decoded, kept in /state, counted, never drawn.
r0=$(field "$(can_entry)" out_of_range)
cansend vcan0 "025#$RANGE_DATA"
await 5 is_state out-of-range "$RANGE"
_ok=$?
[ "$(field "$E" out_of_range)" = $((r0 + 1)) ] || _ok=1
snapshot range || _ok=1
verdict $NAME-out-of-range $_ok "cansend vcan0 025#$RANGE_DATA ($RANGE deg, max 540): out_of_range $r0 -> \
$(field "$E" out_of_range) (want +1); /state $(brief "$E")"

# What overlayd counted against what candump saw of id 0x025 (the 0x123 frame is not its signal).
sleep 0.5
kill $dpid 2>/dev/null
wait $dpid 2>/dev/null
dpid=''
sent=$(grep -c 'vcan0 025#' /tmp/candump.log)
short=$(grep -c 'vcan0 025#[0-9A-F][0-9A-F]$' /tmp/candump.log)
E=$(can_entry)
[ "$(field "$E" frames)" = "$sent" ] && [ "$(field "$E" malformed)" = "$short" ] && [ "$short" = 1 ]
verdict $NAME-counts $? "candump saw $sent frames with id 025 ($short with one data byte); /state frames \
$(field "$E" frames), malformed $(field "$E" malformed)"

# The interface goes down under the daemon and comes back: the socket is closed (connected false) and reopened by
# the retry, and a frame after that is read.
ip link set vcan0 down
await 5 is_connected false
down=$?
down_entry=$E
sleep 2 # two retries: a down interface is not opened (its health waits)
E=$(can_entry)
is_connected false || down=1
[ "$(curl -s --max-time 5 "$URL/metrics" | sed -n 's/^overlayd_input_following{kind="can",[^}]*} //p')" = 0.0 ] || down=1
ip link set vcan0 up
await 10 is_connected true
up=$?
cansend vcan0 "025#$A_DATA"
await 5 is_state ok "$A"
again=$?
[ $down = 0 ] && [ $up = 0 ] && [ $again = 0 ]
verdict $NAME-interface-down-up $? "ip link set vcan0 down: $(brief "$down_entry") \
error='$(echo "$down_entry" | sed -n 's/.*"error":"\([^"]*\)".*/\1/p')'; up, then cansend 025#$A_DATA: $(brief "$E")"

stop_overlayd $pid
rc=$?
pid=''
[ $rc = 0 ]
verdict $NAME-exit $? "overlayd run exited $rc after SIGTERM"
grep -E 'input\.can|warning|error' /tmp/can-run.log | grep -v 'stats: ' | head -20
cp /tmp/can-run.log "$ART/$NAME-run.log" 2>/dev/null
cp /tmp/candump.log "$ART/$NAME-candump.log" 2>/dev/null
cleanup
exit 0
