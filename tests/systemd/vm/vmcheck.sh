#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Guest side of boot_systemd.sh, run by vmcheck.service once multi-user.target is up: overlayd@demo reaches active
# (running), a reload keeps it active, and a stalled instance is killed by the watchdog and restarted.
say() { echo "VMCHECK $*"; }
say "user: $(id overlayd)"
systemctl start overlayd@demo
say "demo: $(systemctl show -p ActiveState -p SubState -p StatusText overlayd@demo | tr '\n' ' ')"
systemctl start overlayd@stall
sleep 30 # READY, about 1 s of frames, then WatchdogSec=10s, RestartSec=3s and a new start
say "stall: $(systemctl show -p NRestarts -p ActiveState overlayd@stall | tr '\n' ' ')"
journalctl --no-pager -u overlayd@stall | grep -E 'Watchdog timeout|Scheduled restart' | sed 's/^/VMCHECK journal: /'
systemctl reload overlayd@demo
sleep 2
say "reloaded: $(systemctl show -p ActiveState -p SubState overlayd@demo | tr '\n' ' ')"
systemctl stop overlayd@demo overlayd@stall
say "stopped: $(systemctl show -p Result -p ActiveState overlayd@demo | tr '\n' ' ')"
say "done"
systemctl poweroff
