#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the Debian 12 packages overlayd needs, only those that are missing. On x86-64 and arm64 (a Raspberry Pi OS /
# Debian 12 board) alike.
#
# Usage: scripts/install-deps.sh [--demo] [--arm64]
#   (none)   everything the test suite needs: the daemon's build, GoogleTest, Google Benchmark and the independent
#            clients the tests check our output with (scripts/test.sh)
#   --demo   only what building and running the daemon needs (scripts/run.sh): about 60% of the download
#   --arm64  adds what scripts/test-arm64.sh needs on the x86-64 host
#
# libcamera must be 0.3 or later (the configure refuses Debian 12's own 0.0.3): where the installed or candidate
# libcamera is older, Debian's bookworm-backports suite (libcamera 0.3.2) is added on the mirror already in use, with
# a pin that lets only libcamera's packages come from it (scripts/backports.sh), and libcamera is installed from it.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/backports.sh
. scripts/backports.sh

demo=false
arm64=false
for arg in "$@"; do
    case "$arg" in
    --demo) demo=true ;;
    --arm64) arm64=true ;;
    *)
        echo "usage: $0 [--demo] [--arm64]" >&2
        exit 2
        ;;
    esac
done

# The daemon: the compiler and build tools, and every library `overlayd` links, optional ones included (HTTP, GPIO,
# libcamera, systemd notify), so that the demo's binary is the one scripts/test.sh tests, and its build is reused.
packages=(
    build-essential cmake ninja-build pkg-config
    libglm-dev
    libopencv-dev fonts-dejavu-core # OpenCV's Debian package pulls in all its modules: most of the download
    libfreetype-dev # text: FreeType renders each glyph once (the cache is ours)
    libtomlplusplus-dev libcli11-dev libsystemd-dev libturbojpeg0-dev libyaml-cpp-dev
    libtinyxml2-dev # OpenCV's XML calibration files
    libpng-dev # PNG files (media/codec): images, replay, snapshots
    libcamera-dev libcamera-ipa # the libcamera source (0.3 or later, see above); the IPA modules a camera needs
    libmicrohttpd-dev nlohmann-json3-dev # the HTTP server; JSON request bodies
    libgpiod-dev # GPIO lines (libgpiod 1.6, the v1 API)
    # the encoded outputs' module (overlayd-stream.so, loaded only when an encoded sink is configured)
    libgstreamer1.0-dev libgstreamer-plugins-base1.0-dev libgstrtspserver-1.0-dev
    libgstreamer-plugins-bad1.0-dev # webrtcbin's library and headers (gstreamer-webrtc-1.0): WebRTC
    systemd # on every booted Debian already; its systemd.pc says where the units install (systemd/CMakeLists.txt)
)
# The test suite: the test frameworks, and independent clients the tests check our output with.
test_packages=(
    clang # the second compiler, the sanitizers and libFuzzer (.ci/run)
    libgtest-dev libgmock-dev libbenchmark-dev
    gpiod # the gpiod tools: the independent GPIO client in tests/vm
    ffmpeg v4l-utils
    libjpeg-turbo-progs # cjpeg: libjpeg's own defaults, what the stream's JPEG size is compared with
    # the encoded outputs' elements at run time: appsrc/tee (base), rtph264pay (good), h264parse and openh264enc
    # (bad, with libopenh264), x264enc (ugly); splitmuxsink, mp4mux, matroskamux, flvmux (good), rtmp2sink, srtsink,
    # mpegtsmux (bad), rtspclientsink (gstreamer1.0-rtsp); tests/stream reads the RTSP stream, the recordings and the
    # pushes with ffprobe and ffmpeg
    gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-plugins-bad gstreamer1.0-plugins-ugly
    glib-networking # GLib's TLS backend: RTSPS (GTlsCertificate)
    gstreamer1.0-rtsp
    gstreamer1.0-nice # webrtcbin's ICE (libnice)
    python3-gi gir1.2-gstreamer-1.0 gir1.2-gst-plugins-base-1.0 gir1.2-gst-plugins-bad-1.0 # tests/stream's WHEP receiver
    python3-gi-cairo # scripts/compare-peers.sh's GStreamer + cairo peer (the peers.smoke test)
    libopenh264-7
    python3-gi gir1.2-gst-rtsp-server-1.0 # tests/stream's RTSP RECORD server, which the push is proven against
    curl chromium python3-websocket # the HTTP tier: a real client and a real headless browser
    python3
    scdoc man-db # the manual pages (man/) and man's check of them (tests/man)
    dpkg-dev lintian # the package: dpkg-shlibdeps for its Depends, lintian on it (scripts/package.sh)
)
# tests/vm, the real-driver tier, boots Debian's x86-64 kernel in QEMU: on x86-64 hosts only (on an arm64 board the
# tier reports itself skipped, and these are not installed).
vm_packages=(
    qemu-system-x86 busybox-static cpio kmod xz-utils binutils make ustreamer
    can-utils # cansend and candump, the CAN check's other end of the bus
    libcamera-tools # `cam`, the guest's baseline libcamera client: the same libcamera as overlayd's
    mmdebstrap # the systemd guests' Debian 12 rootfs (tests/systemd/vm)
)
if ! $demo; then
    packages+=("${test_packages[@]}")
    if [ "$(dpkg --print-architecture)" = amd64 ]; then
        packages+=("${vm_packages[@]}")
    fi
fi
# --arm64: what scripts/test-arm64.sh needs on the x86-64 host (the cross compiler and qemu-user; its sysroot is
# unpacked from Debian's arm64 packages into a cache folder, not installed).
if $arm64; then
    packages+=(crossbuild-essential-arm64 qemu-user)
fi

# libcamera older than 0.3 (Debian 12's 0.0.3) counts as missing: it is replaced from bookworm-backports.
libcamera_min=0.3
old_libcamera=false
missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    elif [[ $p == libcamera* ]] && dpkg --compare-versions "$(dpkg-query -W -f='${Version}' "$p")" lt "$libcamera_min"; then
        missing+=("$p")
        old_libcamera=true
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
# Where apt itself offers no libcamera >= 0.3 (a plain Debian 12), the backports suite and its pin are added.
candidate=$(apt-cache policy libcamera-dev 2>/dev/null | sed -n 's/^ *Candidate: //p')
if $old_libcamera || [ -z "$candidate" ] || [ "$candidate" = "(none)" ] ||
    dpkg --compare-versions "$candidate" lt "$libcamera_min"; then
    echo "install-deps: libcamera $libcamera_min or later comes from $OVERLAYD_BACKPORTS_SUITE: adding it (libcamera only)"
    overlaydBackportsSources "" | $sudo tee /etc/apt/sources.list.d/overlayd-backports.sources >/dev/null
    overlaydBackportsPin | $sudo tee /etc/apt/preferences.d/overlayd-libcamera >/dev/null
    $sudo apt-get update -qq
    # Anything else the suite would move is a broken pin: stop before installing.
    if apt-get -s dist-upgrade 2>/dev/null | grep '^Inst' | grep '~bpo' | grep -v '^Inst libcamera'; then
        echo "install-deps: the pin would let the packages above come from $OVERLAYD_BACKPORTS_SUITE: not installing" >&2
        exit 1
    fi
fi
echo "install-deps: installing ${missing[*]}"
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
