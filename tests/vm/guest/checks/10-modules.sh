# SPDX-License-Identifier: Apache-2.0
# The kernel modules the harness builds out of tree load in Debian's kernel: vimc registers a media device,
# gpio-mockup a GPIO chip (gpio-sim needs configfs set-up; loading it proves the irq_sim patch links), vicodec (with
# the v4l2-mem2mem it needs) its encoder and decoder nodes.
. /vm/lib.sh

ok=0
modprobe vimc && sleep 1 && [ -e /dev/media0 ] || ok=1
verdict modules-vimc $ok "vimc loads and registers $(ls /dev/media* 2>/dev/null | tr '\n' ' ')"
rmmod vimc 2>/dev/null

ok=0
modprobe gpio-sim && modprobe gpio-mockup gpio_mockup_ranges=-1,8 && [ -e /dev/gpiochip0 ] || ok=1
verdict modules-gpio $ok "gpio-sim, irq_sim and gpio-mockup load; $(ls /dev/gpiochip* 2>/dev/null | tr '\n' ' ')"
rmmod gpio-mockup gpio-sim irq_sim 2>/dev/null
ok=0
modprobe vicodec && sleep 1 && node stateful-encoder >/dev/null && node stateful-decoder >/dev/null || ok=1
verdict modules-vicodec $ok "vicodec loads: encoder $(node stateful-encoder), decoder $(node stateful-decoder); \
$(v4l2-ctl -d "$(node stateful-encoder)" --list-formats-out 2>/dev/null | grep -c "'") output formats"
rmmod vicodec v4l2-mem2mem 2>/dev/null
exit 0
