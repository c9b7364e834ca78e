#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Every source of the repository names its licence: an `SPDX-License-Identifier: Apache-2.0` comment among its
first three lines (after a shebang or a doctype). Sources are the tracked C++, C, JavaScript, CSS, HTML, shell,
Python and CMake files, the units and the extension-less scripts that start with a shebang; test data and fuzz seeds
are not. Exit status 1 lists every file without it. scripts/spdx.sh adds the missing lines."""
import os
import subprocess
import sys

IDENTIFIER = "SPDX-License-Identifier: Apache-2.0"
SOURCE_SUFFIXES = (".cpp", ".h", ".c", ".js", ".css", ".html", ".sh", ".py", ".cmake", ".service", ".sysusers")
NOT_SOURCES = ("tests/data/", "tests/fuzz/")


def tracked(root):
    listing = subprocess.run(["git", "ls-files", "-z"], cwd=root, check=True, capture_output=True).stdout
    return [name for name in listing.decode().split("\0") if name]


def is_source(root, name):
    if name.startswith(NOT_SOURCES) or not os.path.isfile(os.path.join(root, name)):
        return False
    if name.endswith(SOURCE_SUFFIXES) or os.path.basename(name) == "CMakeLists.txt":
        return True
    if "." in os.path.basename(name):
        return False
    with open(os.path.join(root, name), "rb") as file:
        return file.read(2) == b"#!"


def main():
    root = sys.argv[1]
    missing = []
    for name in tracked(root):
        if not is_source(root, name):
            continue
        with open(os.path.join(root, name), encoding="utf-8", errors="replace") as file:
            head = [file.readline() for _ in range(3)]
        if not any(IDENTIFIER in line for line in head):
            missing.append(name)
    for name in missing:
        print(f"{name}:1: no '{IDENTIFIER}' in its first three lines (scripts/spdx.sh adds it)")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
