# SPDX-License-Identifier: Apache-2.0
# The kernel modules the harness builds out of tree load in Debian's kernel: vimc registers a media device,
# gpio-mockup a GPIO chip (gpio-sim needs configfs set-up; loading it proves the irq_sim patch links).
. /vm/lib.sh

ok=0
modprobe vimc && sleep 1 && [ -e /dev/media0 ] || ok=1
verdict modules-vimc $ok "vimc loads and registers $(ls /dev/media* 2>/dev/null | tr '\n' ' ')"
rmmod vimc 2>/dev/null

ok=0
modprobe gpio-sim && modprobe gpio-mockup gpio_mockup_ranges=-1,8 && [ -e /dev/gpiochip0 ] || ok=1
verdict modules-gpio $ok "gpio-sim, irq_sim and gpio-mockup load; $(ls /dev/gpiochip* 2>/dev/null | tr '\n' ' ')"
rmmod gpio-mockup gpio-sim irq_sim 2>/dev/null
exit 0
