#!/bin/bash
# SPDX-License-Identifier: Apache-2.0
# Opt-in (not in CTest): boots Debian 12 with systemd as PID 1 in QEMU (TCG) and proves that the installed
# overlayd@.service reaches active (running) under its hardening and that the watchdog restarts a stalled instance.
# Needs root, mmdebstrap, cpio, qemu-system-x86 and the guest kernel cached by tests/vm/run.sh.
# Usage: tests/systemd/vm/boot_systemd.sh [BUILD_DIR]   (BUILD_DIR default: build; it must have built overlayd)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../../build}" && pwd)
cache=${OVERLAYD_VM_CACHE:-$HOME/.cache/overlayd-vm}
work=${OVERLAYD_VM_WORK:-$PWD/vm-systemd}
vmlinux=$(find "$cache" -mindepth 2 -maxdepth 2 -name vmlinux 2>/dev/null | head -1)
[ -n "$vmlinux" ] || { echo "no guest kernel in $cache: run tests/vm/run.sh once" >&2; exit 2; }
mkdir -p "$work" && cd "$work"

# The rootfs: minbase + systemd + the daemon's runtime libraries, cached (about 5 min and 600 MB the first time).
source "$here/guest.sh"
# libcamera (0.3, from bookworm-backports: guest.sh), libgpiod and libmicrohttpd are linked since the binary gained
# those parts; procps holds the /bin/kill that ExecReload= runs (without it a reload fails with 203/EXEC and the
# daemon never sees SIGHUP).
packages=systemd-sysv,libopencv-imgcodecs406,libopencv-contrib406,libopencv-imgproc406,libtomlplusplus3
packages+=,libturbojpeg0,libyaml-cpp0.7,libtinyxml2-9,libcamera0.3,libgpiod2,libmicrohttpd12,procps
rootfs=$(guestRootfs "$packages" systemd-rootfs '/usr/share/doc/*' '/usr/share/man/*' '/usr/share/locale/*')

# What `cmake --install` would put there, plus two configs and the check unit.
rm -rf root && mkdir root && tar -C root -xf "$rootfs"
install -D -m 755 "$build/daemon/overlayd" root/usr/local/bin/overlayd
strip root/usr/local/bin/overlayd
sed "s|^ExecStart=[^ ]*|ExecStart=/usr/local/bin/overlayd|" "$build/systemd/overlayd@.service" \
    > root/etc/systemd/system/overlayd@.service
install -D -m 644 "$here/../../../systemd/overlayd.sysusers" root/usr/lib/sysusers.d/overlayd.conf
mkdir -p root/etc/overlayd
for name in demo stall; do
    stall=0 && [ $name = stall ] && stall=30
    printf '[source]\nkind = "synthetic"\nformat = "YUYV"\nwidth = 320\nheight = 240\nfps = 30.0\n' \
        > root/etc/overlayd/$name.toml
    printf '[source.synthetic]\npattern = "colour-bars"\nstall_after_frames = %s\n[[sink]]\nkind = "null"\n' \
        $stall >> root/etc/overlayd/$name.toml
done
guestImage "$here/vmcheck.sh"
guestBoot "$vmlinux"

expect user '(video)' '(gpio)'
expect demo: ActiveState=active SubState=running StatusText=streaming
expect stall: 'NRestarts=[1-9]'
expect reloaded: ActiveState=active SubState=running
expect stopped: Result=success
[ $fail = 0 ] && echo "boot_systemd: all guest checks passed (log: $work/guest.log)"
exit $fail
