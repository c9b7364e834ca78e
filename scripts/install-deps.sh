#!/usr/bin/env bash
# Installs the Debian 12 packages overlayd needs to build and test, only those that are missing.
set -euo pipefail

packages=(
    build-essential clang cmake ninja-build pkg-config
    libglm-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    libopencv-dev fonts-dejavu-core
    libtomlplusplus-dev libcli11-dev libsystemd-dev libturbojpeg0-dev libyaml-cpp-dev
    libcamera-dev libcamera-ipa # the libcamera source; the IPA modules are what a real (or vimc) camera needs
    libmicrohttpd-dev nlohmann-json3-dev # the HTTP server; JSON request bodies
    libgpiod-dev gpiod # GPIO lines (libgpiod 1.6, the v1 API); the tools are the independent client in tests/vm
    # Independent clients the tests check our output with.
    ffmpeg v4l-utils systemd
    curl chromium python3-websocket # the HTTP tier: a real client and a real headless browser
    qemu-system-x86 busybox-static cpio kmod xz-utils python3 binutils make ustreamer # tests/vm: the real-driver tier
    can-utils # tests/vm: cansend and candump, the CAN check's other end of the bus
)

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
