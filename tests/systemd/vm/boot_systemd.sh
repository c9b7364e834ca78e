#!/bin/bash
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
packages=systemd-sysv,libopencv-imgcodecs406,libopencv-contrib406,libopencv-imgproc406,libtomlplusplus3
packages+=,libturbojpeg0,libyaml-cpp0.7,libtinyxml2-9
rootfs=$cache/systemd-rootfs-$(echo "$packages" | md5sum | cut -c1-8).tar
if [ ! -s "$rootfs" ]; then
    mmdebstrap --variant=minbase --include="$packages" --dpkgopt='path-exclude=/usr/share/doc/*' \
        --dpkgopt='path-exclude=/usr/share/man/*' --dpkgopt='path-exclude=/usr/share/locale/*' \
        bookworm "$rootfs.tmp" && mv "$rootfs.tmp" "$rootfs"
fi

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
install -m 755 "$here/vmcheck.sh" root/usr/local/bin/vmcheck.sh
printf '[Unit]\nAfter=multi-user.target\n[Service]\nType=oneshot\nExecStart=/usr/local/bin/vmcheck.sh\n%s\n' \
    'StandardOutput=journal+console' > root/etc/systemd/system/vmcheck.service
mkdir -p root/etc/systemd/system/multi-user.target.wants
ln -sf ../vmcheck.service root/etc/systemd/system/multi-user.target.wants/vmcheck.service
ln -sf /lib/systemd/systemd root/init # the whole rootfs is the initramfs: no block or 9p modules needed
(cd root && find . | cpio -o -H newc --quiet) > root.cpio

timeout 600 qemu-system-x86_64 -accel tcg,thread=multi -cpu max -m 2048 -smp 2 -nographic -nic none -no-reboot \
    -kernel "$vmlinux" -initrd root.cpio -append "console=ttyS0 panic=-1 loglevel=3 systemd.show_status=0" \
    > guest.log 2>&1 < /dev/null || true
grep -a -o 'VMCHECK.*' guest.log || true

# systemctl show prints properties in its own order, so each one is looked for on its own.
fail=0
expect() { # expect WHAT PATTERN...: every pattern must occur on one VMCHECK line starting with WHAT
    local what=$1 line && shift
    line=$(grep -a -o "VMCHECK $what.*" guest.log | head -1)
    for pattern in "$@"; do
        echo "$line" | grep -q -- "$pattern" || { echo "FAIL: $what: no '$pattern' in '$line'"; fail=1; }
    done
}
expect user '(video)' '(gpio)'
expect demo: ActiveState=active SubState=running StatusText=streaming
expect stall: 'NRestarts=[1-9]'
expect reloaded: ActiveState=active SubState=running
expect stopped: Result=success
[ $fail = 0 ] && echo "boot_systemd: all guest checks passed (log: $work/guest.log)"
exit $fail
