#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The real-driver test tier: boots Debian's current kernel in QEMU with vivid and runs the overlayd binary against
# it (tests/vm/guest/checks/). Prints one PASS/FAIL line per check; exits 0 if all pass, 1 if any fails, 2 on a
# harness error, 77 when skipped (OVERLAYD_SKIP_VM=1). See docs/vm-tests.md.
#
#   tests/vm/run.sh [--overlayd PATH] [--work DIR] [--checks 30-capture,40-loopback]
#
# Defaults: build/daemon/overlayd and build/vm-work/ (guest.log, the staged overlayd, the guest's artifacts).
#
# Environment: OVERLAYD_LIBCAMERA_ROOT=DIR stages the libcamera unpacked in DIR (DIR/usr/...) instead of the
# installed one; OVERLAYD_SKIP_VM=1 skips; OVERLAYD_VM_CACHE (default ~/.cache/overlayd-vm) keeps downloads and
# built pieces per kernel version; OVERLAYD_VM_ACCEL=auto|kvm|tcg; OVERLAYD_VM_TIMEOUT (s, default 1200).
set -euo pipefail
VM_HERE=$(cd "$(dirname "$0")" && pwd)
. "$VM_HERE/lib/common.sh"
. "$VM_HERE/lib/kernel.sh"
. "$VM_HERE/lib/modules.sh"
. "$VM_HERE/lib/initramfs.sh"
. "$VM_HERE/lib/qemu.sh"
. "$VM_HERE/lib/report.sh"

if [ "${OVERLAYD_SKIP_VM:-0}" = 1 ]; then
    echo "SKIPPED: the VM tier (tests/vm) did not run because OVERLAYD_SKIP_VM=1"
    exit 77
fi
# The guest is Debian's x86-64 kernel and the x86-64 build of overlayd: an arm64 board reports the tier skipped.
if [ "$(uname -m)" != x86_64 ]; then
    echo "SKIPPED: the VM tier (tests/vm) boots an x86-64 guest; this host is $(uname -m)"
    exit 77
fi

overlayd=$VM_HERE/../../build/daemon/overlayd checks="" VM_WORK=${OVERLAYD_VM_WORK:-$VM_HERE/../../build/vm-work}
while [ $# -gt 0 ]; do
    case $1 in
    --overlayd) overlayd=$2 && shift 2 ;;
    --work) VM_WORK=$2 && shift 2 ;;
    --checks) checks=$2 && shift 2 ;;
    *) vmDie "unknown argument $1 (see the top of $0)" ;;
    esac
done
VM_CACHE=${OVERLAYD_VM_CACHE:-$HOME/.cache/overlayd-vm}
mkdir -p "$VM_CACHE" "$VM_WORK"
VM_WORK=$(cd "$VM_WORK" && pwd)
[ -x "$overlayd" ] && overlayd=$(readlink -f "$overlayd")
# A libcamera unpacked beside the system's (dpkg -x of bookworm-backports' packages, docs/libcamera.md): overlayd
# was built against it, so its libraries, IPA modules and `cam` are what the guest gets.
VM_LIBCAMERA_ROOT=${OVERLAYD_LIBCAMERA_ROOT:-}
if [ -n "$VM_LIBCAMERA_ROOT" ]; then
    VM_LIBCAMERA_ROOT=$(readlink -f "$VM_LIBCAMERA_ROOT")
    export LD_LIBRARY_PATH=$VM_LIBCAMERA_ROOT/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
fi

started=$(vmNow)
vmStage "host tools" vmInstallHostTools
# One preparation at a time per cache (two build folders may run the tier at once); the boots run in parallel.
exec 9>"$VM_CACHE/.lock"
flock 9
vmDiscoverKernel
vmLog "kernel $VM_KVER ($VM_KDEBVER), cache $VM_KCACHE"
vmStage "download" vmDownloadKernel
vmStage "unpack kernel" vmUnpackKernel
vmStage "modules" vmBuildModules
vmStage "base initramfs" vmBaseInitramfs
flock -u 9
rm -rf "$VM_WORK/share/out" && mkdir -p "$VM_WORK/share/out"
vmStage "stage overlayd" vmStageOverlayd "$VM_WORK" "$overlayd"
vmStage "run initramfs" vmRunInitramfs "$VM_WORK"
vmChooseAccel
vmLog "accelerator: ${VM_ACCEL_ARGS[*]}"
boot_status=0
vmStage "boot + guest checks" vmBoot "$checks" "$VM_WORK/guest.log" || boot_status=$?
vmReport "$VM_WORK/guest.log" "$boot_status" "$overlayd"
status=$?
vmLog "total $(vmSince "$started") s; guest log: $VM_WORK/guest.log"
exit $status
