#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# cmake/overlayd_version.cmake in a scratch git repository: the VERSION file without a tag, a tag as it is, later
# commits and uncommitted changes after it in Debian's spelling, a release candidate before its release, and the
# order dpkg gives them (the package's upgrades depend on it).
#   version_test.sh SOURCE_DIR
set -euo pipefail
script=$(realpath "$1")/cmake/overlayd_version.cmake
repo=$(mktemp -d) && trap 'rm -rf "$repo"' EXIT
git() { command git -C "$repo" -c user.email=test@example.org -c user.name=test "$@"; }
version() {
    cmake -DSOURCE_DIR="$repo" -DOUTPUT="$repo.h" -P "$script"
    sed -n 's/^#define OVERLAYD_VERSION "\(.*\)"$/\1/p' "$repo.h"
}
fail=0
expect() { # expect WANT: the version now
    local got && got=$(version)
    [ "$got" = "$1" ] || { echo "FAIL: expected '$1', got '$got'"; fail=1; }
}
git init -q && echo 0.4.0 > "$repo/VERSION" && git add VERSION && git commit -qm first
expect 0.4.0
git tag v0.5.0 && expect 0.5.0
git commit -qm second --allow-empty && hash=$(git rev-parse --short=7 HEAD) && expect "0.5.0+1.g$hash"
echo 0.5.1 > "$repo/VERSION" && expect "0.5.0+1.g$hash.dirty"
git commit -qam third && git tag v0.6.0-rc1 && expect 0.6.0~rc1
dpkg --compare-versions 0.5.0 lt "0.5.0+1.g$hash" && dpkg --compare-versions "0.5.0+1.g$hash" lt 0.6.0~rc1 &&
    dpkg --compare-versions 0.6.0~rc1 lt 0.6.0 || { echo "FAIL: dpkg orders the versions otherwise"; fail=1; }
rm -f "$repo.h"
[ $fail = 0 ] && echo "version: git describe and VERSION give Debian versions in release order"
exit $fail
