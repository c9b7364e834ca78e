# SPDX-License-Identifier: Apache-2.0
# Unplug: vivid disappears while `overlayd run` streams (unbind from the driver, then rmmod), and comes back
# (modprobe). The daemon must stay up, keep writing frames that are the NO SIGNAL frame (grey 48 = Y 57 in
# BT.601 limited) while the device is gone, and show vivid's pattern again once it is back.
. /vm/lib.sh

have_overlayd || { fail unplug "no overlayd binary was staged (build the overlayd target)"; exit 0; }
vivid_load n_devs=1 node_types=0x1 multiplanar=1 || { fail unplug "modprobe vivid failed"; exit 0; }
OUT=/tmp/unplug.y4m
rm -f $OUT
overlayd run --config /vm/configs/unplug.toml >/tmp/unplug.log 2>&1 &
pid=$!

PROBE_X=10 PROBE_Y=170 # the bottom of vivid's leftmost colour bar

wait_for 30 is_live
verdict unplug-streaming $? "before: $(frames) frames, last pixel ($(probe))"

# Unbind first: the device vanishes under the open fd (ENODEV), as a USB camera does; rmmod alone would just
# fail with "in use". Once overlayd has closed it, the module itself goes.
echo "-- unbinding vivid at $(uptime_s)s"
timeout 20 sh -c 'echo vivid.0 >/sys/bus/platform/drivers/vivid/unbind' || echo "-- unbind failed or hung"
n0=$(frames)
echo "-- unbound at $(uptime_s)s, $n0 frames"
wait_for 10 is_nosignal
ns=$?
sleep 2
n1=$(frames)
rm_ok=0
wait_for 5 timeout 10 rmmod vivid 2>/dev/null || rm_ok=1
kill -0 $pid 2>/dev/null && [ $ns = 0 ] && [ "$n1" -gt "$n0" ]
verdict unplug-no-signal $? "device unbound at frame $n0; $n1 frames 2+ s later, last pixel ($(probe)); rmmod vivid: $([ $rm_ok = 0 ] && echo ok || echo failed)"

sleep 1
echo "-- modprobe vivid at $(uptime_s)s"
vivid_load n_devs=1 node_types=0x1 multiplanar=1
wait_for 30 is_live
ok=$?
kill -0 $pid 2>/dev/null || ok=1
verdict unplug-recovered $ok "after modprobe vivid: $(frames) frames, last pixel ($(probe))"

stop_overlayd $pid
rc=$?
[ $rc = 0 ]
verdict unplug-exit $rc "overlayd run exited with $rc after SIGTERM"
grep -i -E 'signal|lost|retry|device' /tmp/unplug.log | head -8
rmmod vivid
exit 0
