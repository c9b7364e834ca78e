# SPDX-License-Identifier: Apache-2.0
# The systemd guests' shared steps (boot_systemd.sh, install_deb.sh): a cached Debian 12 rootfs, the rootfs booted
# as the initramfs with a check script run once multi-user.target is up, and the checks of its VMCHECK lines.
# shellcheck shell=bash
# shellcheck source=scripts/backports.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../../scripts/backports.sh"

# guestRootfs PACKAGES NAME [EXCLUDE...]: prints the path of a minbase bookworm rootfs tarball with PACKAGES
# (comma-separated), made by mmdebstrap once per package list and kept in $cache as NAME-HASH.tar (minutes and
# hundreds of MB the first time). Each EXCLUDE is a dpkg path-exclude glob (it stays in the guest's dpkg config).
# bookworm-backports is a second source, as on the host (scripts/backports.sh): libcamera0.3 is only there; apt's
# default priority for a backports suite (100) keeps every package bookworm has on bookworm.
guestRootfs() {
    local packages=$1 name=$2 rootfs options=() exclude mirror && shift 2
    for exclude in "$@"; do options+=("--dpkgopt=path-exclude=$exclude"); done
    mirror=$(overlaydDebianMirror)
    rootfs=$cache/$name-$(echo "$packages $OVERLAYD_BACKPORTS_SUITE" | md5sum | cut -c1-8).tar
    if [ ! -s "$rootfs" ]; then
        # The name must end in .tar: mmdebstrap picks its output's format from it.
        mmdebstrap --variant=minbase --include="$packages" "${options[@]}" bookworm "${rootfs%.tar}.tmp.tar" \
            "deb $mirror bookworm main" "deb $mirror $OVERLAYD_BACKPORTS_SUITE main" >&2 &&
            mv "${rootfs%.tar}.tmp.tar" "$rootfs"
    fi
    echo "$rootfs"
}

# guestImage CHECK: installs CHECK as the guest's vmcheck.service into ./root and packs ./root as ./root.cpio.
guestImage() {
    install -m 755 "$1" root/usr/local/bin/vmcheck.sh
    printf '[Unit]\nAfter=multi-user.target\n[Service]\nType=oneshot\nExecStart=/usr/local/bin/vmcheck.sh\n%s\n' \
        'StandardOutput=journal+console' > root/etc/systemd/system/vmcheck.service
    mkdir -p root/etc/systemd/system/multi-user.target.wants
    ln -sf ../vmcheck.service root/etc/systemd/system/multi-user.target.wants/vmcheck.service
    ln -sf /lib/systemd/systemd root/init # the whole rootfs is the initramfs: no block or 9p modules needed
    (cd root && find . | cpio -o -H newc --quiet) > root.cpio
}

# guestBoot VMLINUX: boots ./root.cpio until the check script powers off (10 min at most), the console in
# ./guest.log, and prints the VMCHECK lines. KVM only where tests/vm/run.sh's probe found it working (nested KVM
# often fails on MSRs), else TCG.
guestBoot() {
    local accel=(-accel tcg,thread=multi -cpu max) memo
    memo=$cache/kvm-works-$(uname -r)-$(qemu-system-x86_64 --version | head -1 | tr -dc '0-9.')
    [ "$(cat "$memo" 2>/dev/null)" = yes ] && accel=(-accel kvm -cpu host)
    timeout 600 qemu-system-x86_64 "${accel[@]}" -m 2048 -smp 2 -nographic -nic none -no-reboot -kernel "$1" \
        -initrd root.cpio -append "console=ttyS0 panic=-1 loglevel=3 systemd.show_status=0" \
        > guest.log 2>&1 < /dev/null || true
    grep -a -o 'VMCHECK.*' guest.log || true
}

# expect WHAT PATTERN...: every pattern must occur on the first VMCHECK line starting with WHAT; sets fail=1 if
# not. (systemctl show prints properties in its own order, so each one is looked for on its own.)
fail=0
expect() {
    local what=$1 line && shift
    line=$(grep -a -o "VMCHECK $what.*" guest.log | head -1)
    for pattern in "$@"; do
        echo "$line" | grep -q -- "$pattern" || { echo "FAIL: $what: no '$pattern' in '$line'"; fail=1; }
    done
}
