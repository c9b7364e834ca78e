# SPDX-License-Identifier: Apache-2.0
# Out-of-tree kernel modules the Debian image lacks: vimc (a media-controller camera for libcamera), gpio-sim,
# gpio-mockup and irq_sim (CONFIG_GPIO_SIM and CONFIG_IRQ_SIM are off in Debian), and vicodec (the virtual stateful
# M2M codec; CONFIG_VIDEO_VICODEC is off in Debian 12, and so is CONFIG_V4L2_MEM2MEM_DEV, so v4l2-mem2mem is built
# beside it), from linux-source against the matching headers. vivid itself ships in the image, signed, and is used
# as is.
# shellcheck shell=bash

VM_MODULE_DIRS="gpio vimc vicodec"

# Builds into $VM_KCACHE/extra once per kernel version; sets VM_MODULES_OK=0 (and keeps going) if the build
# fails, so that a kernel that changed under the patches below fails one check rather than the whole tier.
vmBuildModules() {
    local out=$VM_KCACHE/extra work=$VM_KCACHE/modbuild
    VM_MODULES_OK=1
    # .done names the module folders built: a cache from before a folder was added is rebuilt.
    [ "$(cat "$out/.done" 2>/dev/null)" = "$VM_MODULE_DIRS" ] && return 0
    rm -rf "$work" "$out" && mkdir -p "$work/src" "$work/gpio" "$work/vimc" "$work/vicodec" "$out"
    vmUnpackHeaders "$work/hdr"
    vmExtractSources "$work/src"
    vmPrepareGpio "$work/src" "$work/gpio"
    cp "$work"/src/drivers/media/test-drivers/vimc/*.[ch] "$work/vimc/"
    echo "vimc-y := $(cd "$work/vimc" && ls ./*.c | sed 's|^\./||; s|\.c$|.o|' | tr '\n' ' ')" >"$work/vimc/Kbuild"
    echo 'obj-m += vimc.o' >>"$work/vimc/Kbuild"
    cp "$work"/src/drivers/media/test-drivers/vicodec/*.[ch] "$work"/src/drivers/media/v4l2-core/v4l2-mem2mem.c \
        "$work/vicodec/"
    printf '%s\n' 'vicodec-y := vicodec-core.o codec-fwht.o codec-v4l2-fwht.o' 'obj-m += v4l2-mem2mem.o vicodec.o' \
        >"$work/vicodec/Kbuild"
    local dir
    for dir in $VM_MODULE_DIRS; do
        if ! make -s -C "$work/hdr/usr/src/linux-headers-$VM_KVER" M="$work/$dir" -j"$(nproc)" modules \
            >"$work/$dir.log" 2>&1; then
            vmLog "module build in $dir failed: $(tail -5 "$work/$dir.log")"
            VM_MODULES_OK=0
        fi
        # Our own modules only: Debian's carry an appended signature that strip would drop.
        for ko in "$work/$dir"/*.ko; do [ -e "$ko" ] && strip --strip-debug -o "$out/${ko##*/}" "$ko"; done
    done
    [ "$VM_MODULES_OK" = 1 ] && echo "$VM_MODULE_DIRS" >"$out/.done"
    rm -rf "$work"
}

# Streams the source tarball out of the .deb and extracts only the files the modules need.
vmExtractSources() {
    local dest=$1 top=linux-source-$VM_KSERIES
    dpkg-deb --fsys-tarfile "$VM_KCACHE/debs/linux-source-$VM_KSERIES.deb" |
        tar -xO "./usr/src/$top.tar.xz" | xz -dc |
        tar -x -C "$dest" --strip-components=1 --wildcards "$top/drivers/gpio/gpio-sim.c" \
            "$top/drivers/gpio/gpio-mockup.c" "$top/drivers/gpio/gpiolib.h" "$top/kernel/irq/irq_sim.c" \
            "$top/drivers/media/test-drivers/vimc/*" "$top/drivers/media/test-drivers/vicodec/*" \
            "$top/drivers/media/v4l2-core/v4l2-mem2mem.c"
}

# irq_sim.c as a module: irq_to_desc() is not exported, generic_handle_irq() does the same for us.
vmPrepareGpio() {
    local src=$1 dest=$2
    cp "$src"/drivers/gpio/{gpio-sim.c,gpio-mockup.c,gpiolib.h} "$dest/"
    {
        echo '#include <linux/module.h>'
        sed 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$src/kernel/irq/irq_sim.c"
        echo 'MODULE_LICENSE("GPL");'
    } >"$dest/irq_sim.c"
    echo 'obj-m += irq_sim.o gpio-sim.o gpio-mockup.o' >"$dest/Kbuild"
}
