# SPDX-License-Identifier: Apache-2.0
# The guest's initramfs, in concatenated cpio archives (the kernel unpacks them in order): a base with busybox
# and the kernel modules, cached per kernel version, and a per-run archive with the V4L2 tools, overlayd, all
# their libraries, the guest /init and the checks. overlayd's ~150 libraries (OpenCV's closure, 190 MB) are in
# the initramfs rather than on the 9p share: under TCG, loading them over 9p took a minute per process.
# shellcheck shell=bash

# Debian's modules the checks load, with their dependencies (modprobe --show-depends): SocketCAN's core, raw
# sockets and the virtual CAN bus for checks/90-can-steering.sh.
VM_GUEST_MODULES="vivid vimc vicodec gpio-sim gpio-mockup configfs 9p 9pnet_virtio virtio_pci can can-raw vcan"

vmBaseInitramfs() {
    local out=$VM_KCACHE/base.cpio root=$VM_KCACHE/base-root kimg=$VM_KCACHE/kimg
    # Rebuilt when the out-of-tree modules are newer or the module list changed (base.modules records it).
    [ -s "$out" ] && [ "$out" -nt "$VM_KCACHE/extra" ] &&
        [ "$(cat "$VM_KCACHE/base.modules" 2>/dev/null)" = "$VM_GUEST_MODULES" ] && return 0
    vmUnpackModules "$kimg"
    rm -rf "$root" && mkdir -p "$root"/usr/{bin,sbin,lib64,lib/x86_64-linux-gnu} "$root"/{proc,sys,dev,tmp,run,etc,mnt}
    ln -s usr/bin "$root/bin" && ln -s usr/sbin "$root/sbin" && ln -s usr/lib "$root/lib" && ln -s usr/lib64 "$root/lib64"
    cp /bin/busybox "$root/usr/bin/busybox"
    local applet ko rel
    for applet in $(/bin/busybox --list-full); do [ -e "$root/$applet" ] || ln -s /usr/bin/busybox "$root/$applet"; done
    local mods=$kimg/lib/modules/$VM_KVER
    mkdir -p "$mods/extra"
    cp "$VM_KCACHE"/extra/*.ko "$mods/extra/" 2>/dev/null || true # a failed module build is reported elsewhere
    depmod -b "$kimg" "$VM_KVER"
    for m in $VM_GUEST_MODULES; do
        modprobe -d "$kimg" -S "$VM_KVER" --show-depends "$m" 2>/dev/null | awk '$1 == "insmod" { print $2 }'
    done | sort -u | while read -r ko; do
        rel=${ko#"$kimg"/}
        install -D -m644 "$ko" "$root/usr/$rel"
    done
    cp "$mods"/modules.{order,builtin,builtin.modinfo} "$root/usr/lib/modules/$VM_KVER/"
    depmod -b "$root" "$VM_KVER"
    (cd "$root" && find . -print0 | cpio --null -o -H newc --quiet) >"$out.tmp" && mv "$out.tmp" "$out"
    echo "$VM_GUEST_MODULES" >"$VM_KCACHE/base.modules"
    rm -rf "$root" "$kimg"
}

# $1: work folder. Writes $1/initramfs.cpio = base + tools + guest scripts and configs.
vmRunInitramfs() {
    local work=$1 root=$1/run-root
    rm -rf "$root" && mkdir -p "$root/vm"
    vmCopyWithLibraries "$root" /usr/bin/v4l2-ctl /usr/bin/v4l2-compliance /usr/bin/media-ctl
    vmStageLibcamera "$root"
    vmStageGpiod "$root"
    vmStageUdev "$root"
    vmStageHttp "$root"
    vmStageCan "$root"
    cp -a "$work/sysroot/." "$root/"
    install -m755 "$VM_HERE/guest/init" "$root/init"
    cp -r "$VM_HERE/guest/lib.sh" "$VM_HERE/guest/checks" "$VM_HERE/configs" "$root/vm/"
    (cd "$root" && find . -print0 | cpio --null -o -H newc --quiet) >"$work/run.cpio"
    cat "$VM_KCACHE/base.cpio" "$work/run.cpio" >"$work/initramfs.cpio"
    rm -rf "$root" "$work/run.cpio"
}

# libcamera's vimc pipeline at run time: the IPA module is loaded with dlopen (ldd of overlayd does not list it)
# and only with its signature file beside it (so it is copied as it is, never stripped), its proxy, its data, and
# `cam` as a baseline client. From VM_LIBCAMERA_ROOT (run.sh: OVERLAYD_LIBCAMERA_ROOT) when set, into the guest's
# standard paths, where that libcamera looks for its IPA modules and data.
vmStageLibcamera() {
    local root=$1 from=${VM_LIBCAMERA_ROOT:-} lib=/usr/lib/x86_64-linux-gnu/libcamera file
    [ -e "$from$lib/ipa_vimc.so" ] || return 0
    for file in /usr/bin/cam "$lib/ipa_vimc.so" "$lib/vimc_ipa_proxy"; do
        vmCopyIfChanged "$from$file" "$root$file"
        vmCopyLibraries "$root" "$from$file"
    done
    cp "$from$lib/ipa_vimc.so.sign" "$root$lib/"
    mkdir -p "$root/usr/share/libcamera/ipa" && cp -r "$from/usr/share/libcamera/ipa/vimc" "$root/usr/share/libcamera/ipa/"
}

# Debian's gpiod tools (libgpiod 1.6): the independent client of gpio-sim in checks/70-gpio.sh.
vmStageGpiod() {
    local root=$1 tool tools=()
    for tool in gpiodetect gpioinfo gpioget gpioset gpiomon gpiofind; do
        [ -x "/usr/bin/$tool" ] && tools+=("/usr/bin/$tool")
    done
    [ ${#tools[@]} -gt 0 ] || { vmLog "no gpiod tools (package gpiod) on the host: the GPIO checks will fail"; return 0; }
    vmCopyWithLibraries "$root" "${tools[@]}"
}

# The HTTP checks (checks/80-http-ustreamer.sh): curl as the client, Debian's µStreamer as the baseline server, and
# the font overlayd draws text with (without it, OpenCV's Hershey font: a different cost than a real system's).
vmStageHttp() {
    local root=$1 tool font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
    for tool in /usr/bin/curl /usr/bin/ustreamer; do
        if [ -x "$tool" ]; then vmCopyWithLibraries "$root" "$tool"; else vmLog "no $tool on the host: the HTTP check will fail"; fi
    done
    [ -e "$font" ] && install -D -m644 "$font" "$root$font"
    return 0
}

# can-utils' cansend, cangen and candump (checks/90-can-steering.sh): the bus's other end, an independent sender and
# reader of the frames overlayd decodes. The guest's `ip` (busybox) makes the vcan interface.
vmStageCan() {
    local root=$1 tool tools=()
    for tool in cansend cangen candump; do [ -x "/usr/bin/$tool" ] && tools+=("/usr/bin/$tool"); done
    [ ${#tools[@]} -gt 0 ] || { vmLog "no can-utils on the host: the CAN check will fail"; return 0; }
    vmCopyWithLibraries "$root" "${tools[@]}"
}

# udevd, so that the guest has what a real system has: libcamera enumerates only devices udev has initialised, and
# learns of a camera going away or coming back only from udevd's events. Debian's udev package is downloaded (not
# installed on the host) once per version; its udevadm is also systemd-udevd (by the name it is called with). No
# rules: the database entries and events are all libcamera needs.
vmStageUdev() {
    local root=$1 version dir
    version=$(apt-cache policy udev 2>/dev/null | sed -n 's/^ *Candidate: //p')
    [ -n "$version" ] && [ "$version" != "(none)" ] || { vmLog "no udev package known to apt: the guest runs without udevd"; return 0; }
    dir=$VM_CACHE/udev-$version
    if [ ! -x "$dir/bin/udevadm" ]; then
        rm -rf "$dir.tmp" && mkdir -p "$dir.tmp"
        (cd "$dir.tmp" && apt-get download "udev=$version" >/dev/null 2>&1 && dpkg -x udev_*.deb x) ||
            { vmLog "downloading udev $version failed: the guest runs without udevd"; return 0; }
        rm -rf "$dir" && mv "$dir.tmp/x" "$dir" && rm -rf "$dir.tmp"
    fi
    install -D -m755 "$dir/bin/udevadm" "$root/usr/bin/udevadm"
    mkdir -p "$root/usr/lib/systemd" && ln -sf /usr/bin/udevadm "$root/usr/lib/systemd/systemd-udevd"
    vmCopyLibraries "$root" "$dir/bin/udevadm"
}

# The overlayd binary (without debug info: 39 MB -> 2 MB) and its ldd closure under $1/sysroot, kept between runs
# so that unchanged libraries are not copied again. A missing binary leaves no overlayd in the guest: its checks
# then fail, loudly.
vmStageOverlayd() {
    local work=$1 binary=$2
    mkdir -p "$work/sysroot/usr/bin"
    rm -f "$work/sysroot/usr/bin/overlayd"
    [ -x "$binary" ] || return 0
    strip --strip-debug -o "$work/sysroot/usr/bin/overlayd" "$binary"
    vmCopyLibraries "$work/sysroot" "$binary"
    vmStageStreamModule "$work/sysroot" "$(dirname "$binary")/overlayd-stream.so"
}

# The encoded outputs (checks/47-m2m-encode.sh): overlayd's GStreamer module beside the binary (where it looks
# first), and the GStreamer plugins that pipeline uses: appsrc/appsink (app), identity, tee, queue and filesink
# (coreelements), and the v4l2 plugin, which registers v4l2fwhtenc when it finds vicodec's encoder node. The
# plugin scanner lets GStreamer build its registry in a child process, as on a real system. A build without the
# module (-DOVERLAYD_STREAM=OFF) stages none of it: that check then fails, saying so.
vmStageStreamModule() {
    local root=$1 module=$2 gst=/usr/lib/x86_64-linux-gnu/gstreamer-1.0 plugin
    rm -f "$root/usr/bin/overlayd-stream.so"
    [ -e "$module" ] || return 0
    strip --strip-debug -o "$root/usr/bin/overlayd-stream.so" "$module"
    vmCopyLibraries "$root" "$module"
    for plugin in app coreelements video4linux2; do
        [ -e "$gst/libgst$plugin.so" ] && vmCopyWithLibraries "$root" "$gst/libgst$plugin.so"
    done
    vmCopyWithLibraries "$root" /usr/lib/x86_64-linux-gnu/gstreamer1.0/gstreamer-1.0/gst-plugin-scanner
}
