#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Guest side of install_deb.sh, run by vmcheck.service once multi-user.target is up: the package installed with
# dpkg -i (its dependencies are the guest's own packages), overlayd.service started by the postinst and READY, /state
# answered by a daemon running as overlayd, a config change applied by systemctl reload, a clean stop, and
# dpkg --purge leaving nothing of it behind.
say() { echo "VMCHECK $*"; }
field() { grep -o "\"$1\":[^,}]*" | head -1; }
state() { curl -s --max-time 5 --unix-socket /run/overlayd/http.sock http://localhost/state; }

dpkg -i /root/overlayd.deb > /root/dpkg.log 2>&1
say "installed: rc=$? $(tail -n 3 /root/dpkg.log | tr '\n' ' ')"
say "user: $(id overlayd)"
for i in $(seq 60); do [ "$(systemctl show -p SubState --value overlayd)" = running ] && break; sleep 1; done
say "started: $(systemctl show -p ActiveState -p SubState -p StatusText overlayd | tr '\n' ' ') enabled=$(systemctl is-enabled overlayd)"
pid=$(systemctl show -p MainPID --value overlayd)
say "owner: process=$(stat -c %U /proc/"$pid") $(state | field version) $(state | field yaw)"
say "page: $(curl -s -o /dev/null -w 'status=%{http_code}' --unix-socket /run/overlayd/http.sock http://localhost/)"

sed -i 's/^yaw = 90.0$/yaw = 45.0/' /etc/overlayd/overlayd.toml
systemctl reload overlayd
say "reload: rc=$?"
for i in $(seq 20); do state | field yaw | grep -q '45' && break; sleep 1; done
say "reloaded: $(state | field yaw) pid-kept=$([ "$(systemctl show -p MainPID --value overlayd)" = "$pid" ] && echo yes)"
journalctl --no-pager -o cat -u overlayd | grep -E 'reload|refused|error|Control process' | tail -n 5 | sed 's/^/VMCHECK journal: /'

systemctl stop overlayd
say "stopped: rc=$? $(systemctl show -p Result -p ExecMainStatus -p ActiveState overlayd | tr '\n' ' ')"

dpkg --purge overlayd > /root/purge.log 2>&1
say "purged: rc=$?"
left=$(ls -d /usr/bin/overlayd /etc/overlayd /var/lib/overlayd /usr/share/overlayd /usr/share/doc/overlayd \
    /lib/systemd/system/overlayd*.service /usr/lib/sysusers.d/overlayd.conf \
    /etc/systemd/system/multi-user.target.wants/overlayd.service 2>/dev/null | tr '\n' ' ')
say "left: [${left}]"
say "done"
systemctl poweroff
