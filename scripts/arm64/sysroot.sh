#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Makes the arm64 sysroot the cross build links against and qemu-aarch64 runs in: Debian 12's own arm64 packages
# (the -dev packages overlayd builds with and every library they pull in), downloaded by a private apt whose state
# lives in the cache folder and unpacked with dpkg-deb. The host's dpkg is never touched: on Debian 12 installing
# libopencv-dev:arm64 beside the amd64 one would remove amd64 packages.
#
# Usage: scripts/arm64/sysroot.sh [CACHE]   (default .cache/arm64). Prints the sysroot's path. The download
# (about 240 MB) is kept in CACHE/apt; the sysroot is rebuilt only when the package list below changes. libcamera
# (0.3.2) comes from bookworm-backports with the host's pin (scripts/backports.sh): only libcamera from that suite.
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=scripts/backports.sh
. scripts/backports.sh
cache=$(realpath -m "${1:-.cache/arm64}")

packages=(
    libc6-dev libstdc++-12-dev
    libglm-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libyaml-cpp-dev libtinyxml2-dev
    libgtest-dev libgmock-dev libbenchmark-dev libpng-dev libfreetype-dev
    libopencv-dev libopencv-contrib-dev # OpenCVConfig.cmake is in libopencv-dev (which costs no more: contrib needs every module)
    libsystemd-dev libturbojpeg0-dev libcamera-dev libmicrohttpd-dev libgpiod-dev
)
sysroot=$cache/sysroot
stamp=$(printf '%s\n' "${packages[@]}" "$OVERLAYD_BACKPORTS_SUITE $OVERLAYD_BACKPORTS_PACKAGES" | sha256sum | cut -c1-16)
if [ -f "$sysroot/.overlayd-sysroot" ] && [ "$(cat "$sysroot/.overlayd-sysroot")" = "$stamp" ]; then
    echo "$sysroot"
    exit 0
fi

apt_dir=$cache/apt
mkdir -p "$apt_dir/state/lists/partial" "$apt_dir/archives/partial" "$apt_dir/sources.list.d" "$apt_dir/preferences.d"
: > "$apt_dir/state/status" # nothing installed: apt resolves the packages' whole closure
# The host's own Debian sources, for arm64.
for sources in /etc/apt/sources.list.d/*.sources; do
    [ -f "$sources" ] || continue
    grep -q "debian" "$sources" || continue
    grep -q "$OVERLAYD_BACKPORTS_SUITE" "$sources" && continue # written below, for arm64
    sed 's/^Types: deb$/Types: deb\nArchitectures: arm64/' "$sources" > "$apt_dir/sources.list.d/$(basename "$sources")"
done
if [ -f /etc/apt/sources.list ]; then
    sed -n 's/^deb \(\[[^]]*\] \)\?/deb [arch=arm64] /p' /etc/apt/sources.list > "$apt_dir/sources.list.d/main.list"
fi
overlaydBackportsSources "Architectures: arm64" > "$apt_dir/sources.list.d/overlayd-backports.sources"
overlaydBackportsPin > "$apt_dir/preferences.d/overlayd-libcamera"
apt=(apt-get -q -o APT::Architecture=arm64 -o APT::Architectures::=arm64 -o Debug::NoLocking=1
     -o Dir::State="$apt_dir/state" -o Dir::State::status="$apt_dir/state/status"
     -o Dir::Cache="$apt_dir" -o Dir::Cache::archives="$apt_dir/archives"
     -o Dir::Etc::SourceList=/dev/null -o Dir::Etc::SourceParts="$apt_dir/sources.list.d"
     -o Dir::Etc::Preferences=/dev/null -o Dir::Etc::PreferencesParts="$apt_dir/preferences.d")
echo "arm64 sysroot: downloading ${#packages[@]} packages and their dependencies into $apt_dir" >&2
"${apt[@]}" update >&2
"${apt[@]}" install -y --download-only --no-install-recommends "${packages[@]}" >&2
# The packages this resolution chose, by version: the archive folder keeps older downloads too (libcamera 0.0.3
# beside 0.3.2), and unpacking both would mix two libcameras.
"${apt[@]}" install -s --no-install-recommends "${packages[@]}" 2>/dev/null |
    sed -n 's/^Inst \([^ ]*\) (\([^ ]*\) .*/\1 \2/p' >"$apt_dir/selected"

rm -rf "$sysroot.new"
mkdir -p "$sysroot.new/usr/lib" "$sysroot.new/usr/bin" "$sysroot.new/usr/sbin"
# Debian 12 is merged-/usr: /lib is usr/lib (the loader's path /lib/ld-linux-aarch64.so.1 must resolve).
ln -s usr/lib "$sysroot.new/lib"
ln -s usr/bin "$sysroot.new/bin"
ln -s usr/sbin "$sysroot.new/sbin"
count=0
while read -r name version; do
    for deb in "$apt_dir/archives/${name%%:*}_${version/:/%3a}_"*.deb; do
        [ -f "$deb" ] || { echo "arm64 sysroot: $name $version was not downloaded" >&2; exit 1; }
        dpkg-deb -x "$deb" "$sysroot.new"
        count=$((count + 1))
    done
done <"$apt_dir/selected"
# Absolute symlinks point into the host; make them relative so they stay inside the sysroot.
find "$sysroot.new" -type l -lname '/*' | while read -r link; do
    target=$(readlink "$link")
    ln -sfn "$(realpath -m --relative-to="$(dirname "$link")" "$sysroot.new$target")" "$link"
done
# What update-alternatives would link in a postinst that never runs here: the reference BLAS and LAPACK that
# OpenCV's core is linked against.
multiarch=$sysroot.new/usr/lib/aarch64-linux-gnu
for alternative in blas/libblas.so.3 lapack/liblapack.so.3; do
    [ -e "$multiarch/$alternative" ] && ln -sfn "$alternative" "$multiarch/$(basename "$alternative")"
done
echo "$stamp" > "$sysroot.new/.overlayd-sysroot"
rm -rf "$sysroot"
mv "$sysroot.new" "$sysroot"
echo "arm64 sysroot: $count packages unpacked into $sysroot" >&2
echo "$sysroot"
