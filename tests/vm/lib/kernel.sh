# SPDX-License-Identifier: Apache-2.0
# The guest kernel: the ABI Debian's linux-image-amd64 points at today, fetched with `apt-get download` (never
# installed on the host), unpacked into the cache and kept there per kernel package version.
# shellcheck shell=bash

# Sets VM_KVER (6.1.0-56-amd64), VM_KDEBVER (6.1.192-2) and VM_KSERIES (6.1). Debian moves to a new ABI now and
# then and old ones leave the archive, so the version is read from the metapackage, never pinned.
vmDiscoverKernel() {
    local image
    image=$(vmKernelImagePackage)
    if [ -z "$image" ] && [ "$(id -u)" -eq 0 ]; then
        apt-get -o DPkg::Lock::Timeout=900 update -qq
        image=$(vmKernelImagePackage)
    fi
    [ -n "$image" ] || vmDie "apt-cache knows no linux-image-amd64 dependency (run apt-get update?)"
    VM_KVER=${image#linux-image-}
    VM_KDEBVER=$(apt-cache policy "$image" | awk '$1 == "Candidate:" { print $2 }')
    VM_KSERIES=$(echo "$VM_KVER" | cut -d. -f1,2)
    [ -n "$VM_KDEBVER" ] && [ "$VM_KDEBVER" != "(none)" ] || vmDie "no candidate version for $image"
    VM_KCACHE=$VM_CACHE/$VM_KVER-$VM_KDEBVER
    mkdir -p "$VM_KCACHE"
}

vmKernelImagePackage() {
    apt-cache depends linux-image-amd64 2>/dev/null |
        awk '$1 == "Depends:" && $2 ~ /^linux-image-[0-9]/ { print $2; exit }'
}

# Downloads one package into $VM_KCACHE/debs/<name>.deb unless it is there; $2 pins the version (may be empty).
vmDownload() {
    local name=$1 version=$2 dir=$VM_KCACHE/debs
    [ -s "$dir/$name.deb" ] && return 0
    mkdir -p "$dir/partial"
    # As root, apt's sandbox user could not write into a cache under $HOME: download as root instead.
    local sandbox=()
    [ "$(id -u)" -eq 0 ] && sandbox=(-o APT::Sandbox::User=root)
    (cd "$dir/partial" && rm -f ./*.deb && apt-get download -qq "${sandbox[@]}" "$name${version:+=$version}") ||
        vmDie "apt-get download $name${version:+=$version} failed (apt-get update, or the ABI left the archive)"
    mv "$dir"/partial/"${name}"_*.deb "$dir/$name.deb"
}

vmDownloadKernel() {
    local abi=${VM_KVER%-amd64}
    vmDownload "linux-image-$VM_KVER" "$VM_KDEBVER"
    vmDownload "linux-headers-$VM_KVER" "$VM_KDEBVER"
    vmDownload "linux-headers-$abi-common" "$VM_KDEBVER"
    vmDownload "linux-kbuild-$VM_KSERIES" "" # the headers accept any kbuild >= their version
    vmDownload "linux-source-$VM_KSERIES" "$VM_KDEBVER"
}

# An ELF vmlinux: Debian's bzImage is XZ-compressed, and booting the decompressed ELF through its PVH entry saves
# about 5 s per boot under TCG.
vmUnpackKernel() {
    [ -s "$VM_KCACHE/vmlinux" ] && return 0
    local tmp=$VM_KCACHE/vmlinuz-unpack
    rm -rf "$tmp" && mkdir -p "$tmp"
    dpkg-deb --fsys-tarfile "$VM_KCACHE/debs/linux-image-$VM_KVER.deb" | tar -x -C "$tmp" "./boot/vmlinuz-$VM_KVER"
    python3 - "$tmp/boot/vmlinuz-$VM_KVER" "$VM_KCACHE/vmlinux.tmp" <<'PY'
import lzma, sys
data = open(sys.argv[1], 'rb').read()
start = data.find(b'\xfd7zXZ\x00')
if start < 0:
    sys.exit('vmlinuz has no XZ stream')
open(sys.argv[2], 'wb').write(lzma.LZMADecompressor().decompress(data[start:]))
PY
    mv "$VM_KCACHE/vmlinux.tmp" "$VM_KCACHE/vmlinux"
    rm -rf "$tmp"
}

# The image's module tree (400 MB), for depmod/modprobe to resolve what the guest needs; removed again after use.
vmUnpackModules() {
    rm -rf "$1" && mkdir -p "$1"
    dpkg-deb --fsys-tarfile "$VM_KCACHE/debs/linux-image-$VM_KVER.deb" | tar -x -C "$1" ./lib
}

# Headers unpacked into a private root: the arch Makefile includes the common one by absolute path, so point it
# at our copy; the scripts/ and tools/ links are relative and resolve inside the root.
vmUnpackHeaders() {
    local root=$1 abi=${VM_KVER%-amd64} deb
    for deb in "linux-headers-$VM_KVER" "linux-headers-$abi-common" "linux-kbuild-$VM_KSERIES"; do
        dpkg -x "$VM_KCACHE/debs/$deb.deb" "$root"
    done
    sed -i "s|/usr/src/|$root/usr/src/|" "$root/usr/src/linux-headers-$VM_KVER/Makefile"
}
