#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A dpkg database of the arm64 sysroot's packages, for dpkg-shlibdeps --admindir (scripts/package.sh arm64): the
# host's own database knows no arm64 package, and the sysroot was unpacked with dpkg-deb, which records nothing.
# Each .deb of the sysroot's download becomes a status entry, its file list (with the sysroot's path in front, as
# dpkg-shlibdeps finds the libraries there) and its shlibs and symbols files. Kept in DIR until the sysroot
# changes (the stamp is the sysroot's).
#
# Usage: scripts/arm64/deb_admindir.sh CACHE DIR   (CACHE: the folder scripts/arm64/sysroot.sh made; DIR: where
# the database goes). Prints DIR.
set -euo pipefail
cache=$(realpath "$1")
admindir=$(realpath -m "$2")
stamp=$(cat "$cache/sysroot/.overlayd-sysroot")
if [ -f "$admindir/.stamp" ] && [ "$(cat "$admindir/.stamp")" = "$stamp" ]; then
    echo "$admindir"
    exit 0
fi
rm -rf "$admindir.new" && mkdir -p "$admindir.new/info" "$admindir.new/updates"
# Database format 1 (arch-qualified names for Multi-Arch: same); arm64 one of its architectures.
echo 1 > "$admindir.new/info/format"
printf 'amd64\narm64\n' > "$admindir.new/arch"
control=$(mktemp -d)
for deb in "$cache"/apt/archives/*.deb; do
    read -r package multiarch < <(dpkg-deb -f "$deb" Package Multi-Arch | awk '{ print $2 }' | paste -sd' ')
    # dpkg names the files of a Multi-Arch: same package with its architecture, every other one without.
    name=$package && [ "${multiarch:-}" != same ] || name=$package:arm64
    { dpkg-deb -f "$deb" Package Version Architecture Multi-Arch Source Depends Provides
      printf 'Maintainer: unknown\nDescription: unknown\nStatus: install ok installed\n\n'; } >> "$admindir.new/status"
    dpkg-deb -c "$deb" | awk '{ print $6 }' | sed -e 's|^\./|/|' -e 's|/$||' -e "s|^|$cache/sysroot|" \
        > "$admindir.new/info/$name.list"
    rm -rf "$control" && mkdir -p "$control" && dpkg-deb -e "$deb" "$control"
    for file in shlibs symbols; do
        [ -f "$control/$file" ] && cp "$control/$file" "$admindir.new/info/$name.$file"
    done
done
rm -rf "$control"
echo "$stamp" > "$admindir.new/.stamp"
rm -rf "$admindir" && mv "$admindir.new" "$admindir"
echo "$admindir"
