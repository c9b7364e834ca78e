#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Checks an arm64 overlayd package without an arm64 machine (the arm64 tier calls it after scripts/package.sh
# arm64): its files are the package's (dpkg-deb -c), its program is an AArch64 ELF, and every Depends is satisfied
# by a package of the arm64 sysroot's download (Debian 12's arm64 archive), version constraint included.
#
# Usage: scripts/arm64/check_deb.sh DEB [CACHE]   (CACHE default .cache/arm64: scripts/arm64/sysroot.sh's folder)
set -euo pipefail
deb=$(realpath "$1")
cache=$(realpath "${2:-$(dirname "$0")/../../.cache/arm64}")
fail=0
bad() { echo "check_deb: $*" >&2; fail=1; }

[ "$(dpkg-deb -f "$deb" Architecture)" = arm64 ] || bad "Architecture is $(dpkg-deb -f "$deb" Architecture), not arm64"
contents=$(dpkg-deb -c "$deb" | awk '{ print $6 }')
for path in ./usr/bin/overlayd ./lib/systemd/system/overlayd.service ./lib/systemd/system/overlayd@.service \
    ./lib/systemd/system/overlayd-http@.service ./usr/lib/sysusers.d/overlayd.conf ./etc/overlayd/overlayd.toml \
    ./usr/share/overlayd/www/index.html ./usr/share/man/man1/overlayd.1.gz ./usr/share/man/man5/overlayd.toml.5.gz \
    ./usr/share/doc/overlayd/copyright ./usr/share/doc/overlayd/examples/demo.toml; do
    grep -qx -- "$path" <<< "$contents" || bad "no $path in the package"
done
scratch=$(mktemp -d) && trap 'rm -rf "$scratch"' EXIT
dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$scratch" ./usr/bin/overlayd
machine=$(readelf -h "$scratch/usr/bin/overlayd" | sed -n 's/^ *Machine: *//p')
[ "$machine" = AArch64 ] || bad "usr/bin/overlayd is for '$machine', not AArch64"

# The version of a package in the arm64 archive index the sysroot's private apt downloaded (nothing written).
archive_version() {
    apt-cache -o APT::Architecture=arm64 -o APT::Architectures::=arm64 -o Dir::State="$cache/apt/state" \
        -o Dir::State::status="$cache/apt/state/status" -o Dir::Cache="$cache/apt" -o Dir::Cache::pkgcache= \
        -o Dir::Cache::srcpkgcache= -o Dir::Etc::SourceList=/dev/null -o Dir::Etc::SourceParts="$cache/apt/sources.list.d" \
        show --no-all-versions "$1" 2>/dev/null | sed -n 's/^Version: //p' | head -1
}

# Every package of the sysroot's download, with its version: what an arm64 Debian 12 would install from.
declare -A available
for file in "$cache"/apt/archives/*.deb; do
    read -r name version < <(dpkg-deb -f "$file" Package Version | awk '{ print $2 }' | paste -sd' ')
    available[$name]=$version
done
depends=$(dpkg-deb -f "$deb" Depends)
count=0
while IFS= read -r clause; do
    clause=$(echo "$clause" | sed 's/^ *//; s/ *$//')
    [ -n "$clause" ] || continue
    count=$((count + 1))
    ok=false
    while IFS= read -r alternative; do # "libfoo (>= 1.2)" or "bar"
        name=$(echo "$alternative" | awk '{ print $1 }')
        relation=$(echo "$alternative" | sed -n 's/.*(\([<>=]*\) *\([^)]*\)).*/\1 \2/p')
        # A package the sysroot does not download because no -dev package pulls it in (fonts, systemd) is in
        # Debian 12 for arm64 all the same: it is looked up in the arm64 archive index of that download.
        have=${available[$name]:-$(archive_version "$name")}
        [ -n "$have" ] || continue
        if [ -z "$relation" ] || dpkg --compare-versions "$have" "${relation% *}" "${relation#* }"; then
            ok=true
        fi
    done < <(echo "$clause" | tr '|' '\n')
    $ok || bad "Depends '$clause' is not satisfied by the arm64 sysroot's packages"
done < <(echo "$depends" | tr ',' '\n')
[ $fail = 0 ] && echo "check_deb: $(basename "$deb"): contents, AArch64 program and $count Depends resolved"
exit $fail
