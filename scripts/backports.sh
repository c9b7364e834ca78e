# SPDX-License-Identifier: Apache-2.0
# libcamera 0.3 from Debian 12's bookworm-backports, shared by scripts/install-deps.sh (the host) and
# scripts/arm64/sysroot.sh (the arm64 sysroot's private apt): the suite on the mirror the machine already uses, and
# a pin that lets only libcamera's packages come from it, so that nothing else on the machine moves.
# shellcheck shell=bash

OVERLAYD_BACKPORTS_SUITE=bookworm-backports
# What comes from the suite: libcamera's own packages (libcamera-dev, libcamera0.3, libcamera-ipa, libcamera-tools,
# libcamera-base) and nothing else; their other dependencies are bookworm's.
OVERLAYD_BACKPORTS_PACKAGES="libcamera*"

# The Debian mirror of the bookworm entry already configured (deb822 .sources or a one-line sources.list).
overlaydDebianMirror() {
    local file uri
    for file in /etc/apt/sources.list.d/*.sources; do
        [ -f "$file" ] || continue
        uri=$(awk 'BEGIN { RS = ""; FS = "\n" }
            /(^|\n)Suites:[^\n]*bookworm([ \n]|$)/ && !/-security/ {
                for (i = 1; i <= NF; i++) if ($i ~ /^URIs:/) { sub(/^URIs: */, "", $i); split($i, u, " "); print u[1]; exit }
            }' "$file")
        [ -n "$uri" ] && { echo "$uri"; return; }
    done
    if [ -f /etc/apt/sources.list ]; then
        uri=$(sed -n 's/^deb \(\[[^]]*\] \)\?\([^ ]*\) bookworm .*/\2/p' /etc/apt/sources.list | head -n1)
        [ -n "$uri" ] && { echo "$uri"; return; }
    fi
    echo http://deb.debian.org/debian
}

# $1: an optional "Architectures: arm64" line. The deb822 entry of the suite.
overlaydBackportsSources() {
    echo "# overlayd: libcamera 0.3 (only libcamera may come from here: see preferences.d/overlayd-libcamera)"
    echo "Types: deb"
    [ -n "${1:-}" ] && echo "$1"
    echo "URIs: $(overlaydDebianMirror)"
    echo "Suites: $OVERLAYD_BACKPORTS_SUITE"
    echo "Components: main"
    echo "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg"
}

# The pin: nothing from the suite (-1) except libcamera's packages, which win over bookworm's 0.0.3 (990).
overlaydBackportsPin() {
    cat <<PIN
# overlayd: from $OVERLAYD_BACKPORTS_SUITE only libcamera; everything else stays on bookworm.
Package: *
Pin: release n=$OVERLAYD_BACKPORTS_SUITE
Pin-Priority: -1

Package: $OVERLAYD_BACKPORTS_PACKAGES
Pin: release n=$OVERLAYD_BACKPORTS_SUITE
Pin-Priority: 990
PIN
}
