#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Makes out/deb/overlayd_VERSION_ARCH.deb from a build CI has already made: build/ for amd64, build-arm64/ (the
# arm64 tier's cross build, scripts/test-arm64.sh) for arm64. A staged tree packed with dpkg-deb, no rebuild:
# the binary stripped, the units configured for /usr, the default config as a conffile, the page, man pages,
# documents and examples, maintainer scripts that create the user and enable the service as debhelper's would,
# and Depends from dpkg-shlibdeps (for arm64 against the arm64 sysroot's packages). docs/packaging.md explains it.
#
# Usage: scripts/package.sh [amd64|arm64]   (default: this machine's architecture)
# Environment: BUILD_DIR (default build, or build-arm64), OVERLAYD_ARM64_CACHE (default .cache/arm64),
# OVERLAYD_ARM64_ADMINDIR (default CACHE/admindir: kept with the sysroot, 4 min to make), OUT_DIR (default out/deb).
# Prints the .deb's path.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
arch=${1:-$(dpkg --print-architecture)}
case "$arch" in
amd64) build=${BUILD_DIR:-build} strip=strip ;;
arm64) build=${BUILD_DIR:-build-arm64} strip=aarch64-linux-gnu-strip ;;
*) echo "usage: $0 [amd64|arm64]" >&2 && exit 2 ;;
esac
build=$(realpath "$build")
out=$(realpath -m "${OUT_DIR:-out/deb}")
binary=$build/daemon/overlayd
[ -x "$binary" ] || { echo "package: no $binary: build it first" >&2 && exit 1; }
version=$(sed -n 's/^#define OVERLAYD_VERSION "\(.*\)"$/\1/p' "$build/base/generated/overlayd_version.h" 2>/dev/null || true)
[ -n "$version" ] || version=$(head -n 1 VERSION) # a build from before the version header: the release
stage=$out/stage-$arch
rm -rf "$stage" && mkdir -p "$stage/DEBIAN"

# The program and what it reads.
install -D -m 755 "$binary" "$stage/usr/bin/overlayd"
"$strip" --remove-section=.comment --remove-section=.note --strip-unneeded "$stage/usr/bin/overlayd"
# The encoded outputs' GStreamer module, where the binary looks for it (kPackagedModuleDir), when the build has one
# (the arm64 sysroot has no GStreamer). Its libraries and GStreamer's plugins are Recommends: a camera-only
# install needs none of them, and the daemon names what is missing when an encoded sink is configured.
module=$build/daemon/overlayd-stream.so
if [ -f "$module" ]; then
    install -D -m 644 "$module" "$stage/usr/lib/overlayd/overlayd-stream.so"
    "$strip" --remove-section=.comment --remove-section=.note --strip-unneeded "$stage/usr/lib/overlayd/overlayd-stream.so"
fi
mkdir -p "$stage/lib/systemd/system"
for unit in systemd/overlayd.service systemd/overlayd@.service "$build/systemd/overlayd-http@.service.in"; do
    sed -e 's|@OVERLAYD_BINDIR@|/usr/bin|g' -e 's|@OVERLAYD_CONFDIR@|/etc/overlayd|g' \
        -e 's|@OVERLAYD_DOCDIR@|/usr/share/doc/overlayd|g' "$unit" > "$stage/lib/systemd/system/$(basename "$unit" .in)"
done
install -D -m 644 systemd/overlayd.sysusers "$stage/usr/lib/sysusers.d/overlayd.conf"
install -D -m 644 debian/overlayd.toml "$stage/etc/overlayd/overlayd.toml"
install -D -m 644 -t "$stage/usr/share/overlayd/www" http/www/*

# Documentation: the manual pages (made by the build when scdoc is installed, else here), the documents the units
# and pages name, the examples, the licence and a change log.
doc=$stage/usr/share/doc/overlayd
mkdir -p "$doc/examples" "$stage/usr/share/man/man1" "$stage/usr/share/man/man5"
cp config/examples/* "$doc/examples/"
cp docs/*.md "$doc/"
sed -e "s/@VERSION@/$version/" man/overlayd.1.scd | scdoc > "$stage/usr/share/man/man1/overlayd.1"
python3 man/config_page.py docs/config.md "$out/overlayd.toml.5.scd" "$version"
scdoc < "$out/overlayd.toml.5.scd" > "$stage/usr/share/man/man5/overlayd.toml.5"
# The Maintainer field and the change log's signature: Debian's own variables (as dch reads them), so whoever ships
# the package names themselves; without them, the project's placeholder address.
maintainer="${DEBFULLNAME:-The overlayd authors} <${DEBEMAIL:-overlayd@example.org}>"
sed -e "s/@VERSION@/$version/" -e "s|@MAINTAINER@|$maintainer|" -e "s/@DATE@/$(date -R -u -d "@${SOURCE_DATE_EPOCH:-$(git log -1 --format=%ct 2>/dev/null || date +%s)}")/" \
    debian/changelog.in > "$doc/changelog"
gzip -9n "$stage"/usr/share/man/man*/* "$doc/changelog"
find "$doc" -name '*.md' -size +4k -exec gzip -9n {} +
install -m 644 debian/copyright "$doc/copyright"
chmod -R u=rwX,go=rX "$stage/usr" "$stage/lib" "$stage/etc"

# Depends: dpkg-shlibdeps in a scratch source tree. For arm64 the libraries are the sysroot's, and the package
# database it asks which package holds each one is made from the sysroot's .debs (scripts/arm64/deb_admindir.sh).
scratch=$out/shlibdeps-$arch
rm -rf "$scratch" && mkdir -p "$scratch/debian"
printf 'Source: overlayd\n\nPackage: overlayd\nArchitecture: any\n' > "$scratch/debian/control"
shlibdeps=(dpkg-shlibdeps -O "-e$stage/usr/bin/overlayd")
[ -f "$module" ] && shlibdeps+=(-dRecommends "-e$stage/usr/lib/overlayd/overlayd-stream.so")
if [ "$arch" = arm64 ]; then
    cache=$(realpath "${OVERLAYD_ARM64_CACHE:-.cache/arm64}")
    admindir=$(scripts/arm64/deb_admindir.sh "$cache" "${OVERLAYD_ARM64_ADMINDIR:-$cache/admindir}")
    shlibdeps+=("--admindir=$admindir" "-l$cache/sysroot/usr/lib/aarch64-linux-gnu"
        "-l$cache/sysroot/lib/aarch64-linux-gnu")
    export DEB_HOST_ARCH=arm64 DEB_HOST_MULTIARCH=aarch64-linux-gnu DEB_HOST_GNU_TYPE=aarch64-linux-gnu
fi
fields=$(cd "$scratch" && "${shlibdeps[@]}" 2>"$scratch/warnings")
depends=$(echo "$fields" | sed -n 's/^shlibs:Depends=//p')
recommends=$(echo "$fields" | sed -n 's/^shlibs:Recommends=//p')
[ -z "$recommends" ] || recommends="Recommends: $recommends, gstreamer1.0-plugins-base, gstreamer1.0-plugins-good, gstreamer1.0-plugins-bad, gstreamer1.0-nice, glib-networking"
[ -n "$depends" ] || { cat "$scratch/warnings" >&2 && echo "package: dpkg-shlibdeps found no Depends" >&2 && exit 1; }

install -m 755 debian/postinst debian/prerm debian/postrm "$stage/DEBIAN/"
echo /etc/overlayd/overlayd.toml > "$stage/DEBIAN/conffiles"
size=$(du -sk --exclude=DEBIAN "$stage" | cut -f1)
sed -e "s/@VERSION@/$version/" -e "s|@MAINTAINER@|$maintainer|" -e "s/@ARCH@/$arch/" -e "s/@SIZE@/$size/" -e "s/@SHLIBS@/$depends/" -e "s/@RECOMMENDS@/$recommends/" -e '/^$/d' \
    debian/control.in > "$stage/DEBIAN/control"
(cd "$stage" && find . -path ./DEBIAN -prune -o -type f -printf '%P\0' | LC_ALL=C sort -z | xargs -0 md5sum) \
    > "$stage/DEBIAN/md5sums"
deb=$out/overlayd_${version}_$arch.deb
dpkg-deb --root-owner-group -Zxz --build "$stage" "$deb" >/dev/null
echo "$deb"
