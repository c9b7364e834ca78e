#!/bin/bash
# SPDX-License-Identifier: Apache-2.0
# Opt-in (not in CTest): the amd64 package installed the way a board gets it. Boots Debian 12 with systemd as PID 1
# in QEMU (KVM where tests/vm/run.sh found it working, else TCG) from a minbase rootfs holding the package's Depends (so dpkg -i resolves
# them from the guest's own packages) and curl; the guest (deb_check.sh) installs, starts, queries, reloads, stops
# and purges it. Needs root, mmdebstrap, cpio, qemu-system-x86 and the guest kernel cached by tests/vm/run.sh.
# Usage: tests/systemd/vm/install_deb.sh out/deb/overlayd_VERSION_amd64.deb
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
deb=$(realpath "$1")
cache=${OVERLAYD_VM_CACHE:-$HOME/.cache/overlayd-vm}
work=${OVERLAYD_VM_WORK:-$PWD/vm-deb}
vmlinux=$(find "$cache" -mindepth 2 -maxdepth 2 -name vmlinux 2>/dev/null | head -1)
[ -n "$vmlinux" ] || { echo "no guest kernel in $cache: run tests/vm/run.sh once" >&2; exit 2; }
mkdir -p "$work" && cd "$work"
start=$SECONDS

# The rootfs: minbase + systemd + curl + the package's Depends (names only: bookworm's versions satisfy them, and
# bookworm-backports' for libcamera0.3: guest.sh),
# cached per package list (about 6 min and 400 MB the first time).
source "$here/guest.sh"
depends=$(dpkg-deb -f "$deb" Depends | tr ',' '\n' | sed 's/|.*//; s/(.*)//; s/ //g' | grep . | sort -u | paste -sd,)
rootfs=$(guestRootfs "systemd-sysv,curl,$depends" deb-rootfs '/usr/share/locale/*')
echo "install_deb: rootfs ready after $((SECONDS - start)) s"

rm -rf root && mkdir root && tar -C root -xf "$rootfs"
install -m 644 "$deb" root/root/overlayd.deb
guestImage "$here/deb_check.sh"
guestBoot "$vmlinux"
echo "install_deb: guest done after $((SECONDS - start)) s"

version=$(dpkg-deb -f "$deb" Version)
expect installed: 'rc=0'
expect user: '(video)' '(gpio)'
expect started: ActiveState=active SubState=running StatusText=streaming enabled=enabled
expect owner: process=overlayd "\"version\":\"$version\"" '"yaw":90'
expect page: status=200
expect reload: rc=0
expect reloaded: '"yaw":45' pid-kept=yes
expect stopped: rc=0 Result=success ActiveState=inactive
expect purged: rc=0
expect left: '\[\]'
[ $fail = 0 ] && echo "install_deb: all guest checks passed in $((SECONDS - start)) s (log: $work/guest.log)"
exit $fail
