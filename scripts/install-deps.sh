#!/usr/bin/env bash
# Installs the Debian 12 packages overlayd needs to build and test, only those that are missing. On x86-64 and arm64
# (a Raspberry Pi OS / Debian 12 board) alike.
set -euo pipefail

packages=(
    build-essential clang cmake ninja-build pkg-config
    libglm-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    libopencv-dev fonts-dejavu-core libfreetype-dev # text: FreeType renders each glyph once (the cache is ours)
    libtomlplusplus-dev libcli11-dev libsystemd-dev libturbojpeg0-dev libyaml-cpp-dev
    libpng-dev # PNG files (media/codec): images, replay, snapshots
    libcamera-dev libcamera-ipa # the libcamera source; the IPA modules are what a real (or vimc) camera needs
    libmicrohttpd-dev nlohmann-json3-dev # the HTTP server; JSON request bodies
    libgpiod-dev gpiod # GPIO lines (libgpiod 1.6, the v1 API); the tools are the independent client in tests/vm
    # Independent clients the tests check our output with.
    ffmpeg v4l-utils systemd
    curl chromium python3-websocket # the HTTP tier: a real client and a real headless browser
    python3
)
# tests/vm, the real-driver tier, boots Debian's x86-64 kernel in QEMU: on x86-64 hosts only (on an arm64 board the
# tier reports itself skipped, and these are not installed).
vm_packages=(
    qemu-system-x86 busybox-static cpio kmod xz-utils binutils make ustreamer
    can-utils # cansend and candump, the CAN check's other end of the bus
)
if [ "$(dpkg --print-architecture)" = amd64 ]; then
    packages+=("${vm_packages[@]}")
fi
# --arm64: what scripts/test-arm64.sh needs on the x86-64 host (the cross compiler and qemu-user; its sysroot is
# unpacked from Debian's arm64 packages into a cache folder, not installed).
if [ "${1:-}" = "--arm64" ]; then
    packages+=(crossbuild-essential-arm64 qemu-user)
fi

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
