#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Puts the licence's SPDX identifier on the first comment line of every source file of the repository that lacks
# it, in the file's own comment syntax; a file that has one is left as it is, so running it twice changes nothing.
# After a shebang (#!) or an HTML doctype the identifier goes on the next line, so scripts still run.
# tests/architecture/spdx_test.py fails for a source without it.
#
# Usage: scripts/spdx.sh [--check]   (--check: change nothing, list the files without it, exit 1 if there are any)
set -euo pipefail
cd "$(dirname "$0")/.."
check=false
[ "${1:-}" = --check ] && check=true
id="SPDX-License-Identifier: Apache-2.0"

# The comment that carries the identifier for a path; empty for files that are not sources (data, images, seeds).
comment_for() {
    case "$1" in
    tests/data/* | tests/fuzz/*_seeds/*) ;;
    *.cpp | *.h | *.c | *.js) echo "// $id" ;;
    *.css) echo "/* $id */" ;;
    *.html) echo "<!-- $id -->" ;;
    *.sh | *.py | *.cmake | */CMakeLists.txt | CMakeLists.txt | *.service | *.sysusers) echo "# $id" ;;
    *)
        # A script without an extension (.ci/run, debian/postinst): a shebang says it is one.
        case "$(basename "$1")" in *.*) ;; *) [ "$(head -c 2 "$1")" != "#!" ] || echo "# $id" ;; esac
        ;;
    esac
}

missing=0
while IFS= read -r -d '' path; do
    line=$(comment_for "$path")
    [ -n "$line" ] && [ -f "$path" ] || continue
    head -n 3 "$path" | grep -q "SPDX-License-Identifier:" && continue
    if $check; then
        echo "$path: no '$id' in its first lines"
        missing=1
        continue
    fi
    first=$(head -n 1 "$path")
    case "$first" in
    '#!'* | '<!doctype'* | '<!DOCTYPE'*) at=1 ;; # the interpreter line and the doctype must stay first
    *) at=0 ;;
    esac
    tmp=$(mktemp "$path.spdx.XXXXXX")
    { head -n "$at" "$path"; echo "$line"; tail -n "+$((at + 1))" "$path"; } > "$tmp"
    chmod --reference="$path" "$tmp"
    mv "$tmp" "$path"
done < <(git ls-files -z)
exit $missing
