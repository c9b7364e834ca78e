# SPDX-License-Identifier: Apache-2.0
# Shared helpers of the VM harness: logging, timing, the cache and work folders, host package installation.
# Sourced by run.sh; every function here is quiet unless something needs the user's attention.
# shellcheck shell=bash

vmLog() { echo "vm: $*" >&2; }
vmDie() {
    echo "vm: error: $*" >&2
    exit 2
}

vmNow() { date +%s.%N; }
# Seconds since $1 (a vmNow value), one decimal: stage timings go to the log so that a slow cold run is explained.
vmSince() { awk -v a="$1" -v b="$(vmNow)" 'BEGIN { printf "%.1f", b - a }'; }

# Runs a stage and logs how long it took: vmStage "name" command args...
vmStage() {
    local name=$1 start status=0
    shift
    start=$(vmNow)
    "$@" || status=$?
    vmLog "$name: $(vmSince "$start") s"
    return $status
}

# The host commands the harness needs and the Debian packages that provide them. scripts/install-deps.sh lists
# the same packages; this is the fallback for someone running tests/vm/run.sh directly.
VM_HOST_TOOLS=(
    "qemu-system-x86_64 qemu-system-x86" "cpio cpio" "depmod kmod" "xz xz-utils"
    "python3 python3" "strip binutils" "gcc-12 gcc-12" "make make" "v4l2-ctl v4l-utils" "v4l2-compliance v4l-utils"
    "ffprobe ffmpeg" "cam libcamera-tools" "gpioinfo gpiod" "curl curl" "ustreamer ustreamer" "cansend can-utils"
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf fonts-dejavu-core"
    "/usr/lib/x86_64-linux-gnu/libcamera/ipa_vimc.so libcamera-ipa"
)

vmInstallHostTools() {
    local missing=() entry tool package
    for entry in "${VM_HOST_TOOLS[@]}"; do
        read -r tool package <<<"$entry"
        # A path (a library such as the vimc IPA) is checked for existence: command -v wants the execute bit.
        case $tool in
        /*) [ -e "$tool" ] || missing+=("$package") ;;
        *) command -v "$tool" >/dev/null 2>&1 || missing+=("$package") ;;
        esac
    done
    # busybox must be the static build (ldd fails on it): it runs inside the guest with no libraries.
    if [ ! -x /bin/busybox ] || ldd /bin/busybox >/dev/null 2>&1; then missing+=(busybox-static); fi
    [ ${#missing[@]} -eq 0 ] && return 0
    local sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        sudo -n true 2>/dev/null || vmDie "missing packages: ${missing[*]} (install them, or run as root / with sudo)"
        sudo="sudo -n"
    fi
    vmLog "installing ${missing[*]}"
    $sudo apt-get -o DPkg::Lock::Timeout=900 update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends \
        $(printf '%s\n' "${missing[@]}" | sort -u)
}

# Copies executables with their ldd closure into a root folder, keeping /usr/lib/x86_64-linux-gnu and /lib64 (the
# dynamic loader) where the guest's loader looks for them.
vmCopyWithLibraries() {
    local root=$1 file
    shift
    for file in "$@"; do
        vmCopyIfChanged "$file" "$root/usr/${file#/usr/}"
        vmCopyLibraries "$root" "$file"
    done
}

vmCopyLibraries() {
    local root=$1 file=$2 lib
    ldd "$file" 2>/dev/null | grep -o '/[^ ]*' | while read -r lib; do
        case $lib in
        /lib64/*) vmCopyIfChanged "$lib" "$root/usr/lib64/${lib##*/}" ;;
        *) vmCopyIfChanged "$lib" "$root/usr/lib/x86_64-linux-gnu/${lib##*/}" ;;
        esac
    done
}

# Copies (following links, keeping the time stamp) unless $2 already has $1's size and time stamp: the staged
# closure of overlayd is 190 MB and mostly unchanged between runs.
vmCopyIfChanged() {
    local src dst=$2
    src=$(readlink -f "$1")
    [ -e "$dst" ] && [ "$(stat -c '%s %Y' "$src")" = "$(stat -c '%s %Y' "$dst")" ] && return 0
    mkdir -p "$(dirname "$dst")"
    cp -p "$src" "$dst.tmp" && mv -f "$dst.tmp" "$dst"
}
