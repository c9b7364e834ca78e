# SPDX-License-Identifier: Apache-2.0
# Booting the guest: KVM when it really works (on many CI machines /dev/kvm exists but nested virtualization
# fails on MSRs or cmpxchg16b), else TCG software emulation. 2 vCPUs at most: the build machines are shared.
# shellcheck shell=bash

# Sets VM_ACCEL_ARGS. OVERLAYD_VM_ACCEL=kvm|tcg forces a choice; auto probes KVM with a short boot once and
# remembers the answer per host kernel and QEMU version.
vmChooseAccel() {
    local tcg=(-accel tcg,thread=multi -cpu max) kvm=(-accel kvm -cpu host)
    case ${OVERLAYD_VM_ACCEL:-auto} in
    tcg) VM_ACCEL_ARGS=("${tcg[@]}") && return 0 ;;
    kvm) VM_ACCEL_ARGS=("${kvm[@]}") && return 0 ;;
    esac
    VM_ACCEL_ARGS=("${tcg[@]}")
    [ -r /dev/kvm ] && [ -w /dev/kvm ] || return 0
    local memo
    memo=$VM_CACHE/kvm-works-$(uname -r)-$(qemu-system-x86_64 --version | head -1 | tr -dc '0-9.')
    if [ ! -e "$memo" ]; then
        local log=$VM_WORK/kvm-probe.log
        # In a subshell: a QEMU that aborts must not make bash print a job report.
        (timeout 30 qemu-system-x86_64 "${kvm[@]}" -m 256 -smp 1 -nographic -nic none -no-reboot \
            -kernel "$VM_KCACHE/vmlinux" -initrd "$VM_WORK/initramfs.cpio" \
            -append "console=ttyS0 quiet loglevel=3 panic=-1 vm.probe=1" >"$log" 2>&1) 2>/dev/null || true
        grep -q "== probe ok" "$log" && echo yes >"$memo" || echo no >"$memo"
    fi
    [ "$(cat "$memo")" = yes ] && VM_ACCEL_ARGS=("${kvm[@]}")
    return 0
}

# $1: the comma-separated checks to run ("" = all), $2: the guest log to write. The guest powers off when done;
# the timeout only catches a hung guest.
vmBoot() {
    local checks=$1 log=$2
    timeout "${OVERLAYD_VM_TIMEOUT:-1200}" qemu-system-x86_64 "${VM_ACCEL_ARGS[@]}" -m 1536 -smp 2 \
        -nographic -nic none -no-reboot -kernel "$VM_KCACHE/vmlinux" -initrd "$VM_WORK/initramfs.cpio" \
        -append "console=ttyS0 quiet loglevel=3 panic=-1 vm.checks=$checks" \
        -virtfs "local,path=$VM_WORK/share,mount_tag=share,security_model=none,id=share" >"$log" 2>&1 </dev/null
}
