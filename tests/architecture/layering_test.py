#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The folder layering of docs/architecture.md, checked: every #include "folder/..." in a production folder must name
a folder that the table below lets it use, and inside a folder the includes between its files (a .cpp and its .h
counted as one) form no cycle, and every namespace opened is one that docs/architecture.md names. A new edge is a design decision: change the table and the document together. Exit
status 1 lists every offending include as file:line, and every cycle."""
import os
import re
import sys

# folder -> the project folders its files may include (its own folder is always allowed).
ALLOWED = {
    "base": set(),
    "projection": {"base"},
    "media": {"base"},
    "overlay": {"base", "media", "projection"},
    "drivers": {"base", "media", "projection"},
    "gpio": {"base"},
    "http": {"base"},
    "inputs": {"base"},
    "alignment": {"base", "projection"},
    "stream": {"base", "media", "drivers"},
    "config": {"base", "media", "projection", "overlay", "drivers", "gpio", "http", "inputs", "stream"},
    "control": {"base", "media", "projection", "overlay", "drivers", "gpio", "http", "inputs", "stream", "alignment",
                "config"},
    "daemon": {"base", "media", "projection", "overlay", "drivers", "gpio", "http", "inputs", "stream", "alignment",
               "config", "control"},
    "tools": {"base", "media", "projection", "overlay", "drivers", "gpio", "http", "inputs", "stream", "alignment",
              "config", "control", "daemon"},
}
# Within overlay/: the wings under the renderer. raster/ and blend/ share the "over" rounding (blend/div255.h) and
# the coverage row interface (raster/coverage_sink.h); shapes/ is what the others draw.
OVERLAY_WINGS = {
    "shapes": {"shapes"},
    "raster": {"raster", "shapes", "blend"},
    "blend": {"blend", "raster", "shapes"},
}
# Cycles inside a folder that are still there, each a pair that needs a design change rather than a move. A new
# cycle fails; a listed one that is gone fails too, so that the list only shrinks.
KNOWN_CYCLES = set()
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
# A member function defined at the start of a line: "Result<T> Class::name(", "Class::~Class(", "Outer::Inner::f(".
MEMBER = re.compile(r'^(?:[\w:<>,*&\s]+?\s+[*&]?)?((?:\w+::)*?\w+)::(?:~?\w+|operator\S+)\s*\(')
NAMESPACE = re.compile(r'^\s*namespace\s+([\w:]+)')
# Classes whose member functions are still defined in more than one .cpp: none. A new one fails; one that is gone
# fails too, so that the list only shrinks. (A `*_none.cpp` is the build's stand-in when an optional library is
# missing, never built beside its counterpart: not counted.)
KNOWN_SPREAD = set()
# One namespace (docs/architecture.md): `overlayd`, anonymous ones, and named inner ones for two reasons only: a
# source compiled once per instruction set, and support code that several tests share. Aliases are not counted.
OPENED = re.compile(r'^\s*namespace\s+([\w:]+)\s*\{')
PER_INSTRUCTION_SET = {"baseline", "avx2", "avx512", "OVERLAYD_LANES_NS"}
TEST_SUPPORT = {"test", "bench"}


def problems(root):
    found = []
    for folder, allowed in ALLOWED.items():
        for directory, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(directory, name)
                relative = os.path.relpath(path, root)
                parts = relative.split(os.sep)
                wing = parts[1] if folder == "overlay" and len(parts) > 2 else None
                with open(path, encoding="utf-8") as source:
                    for number, line in enumerate(source, 1):
                        match = INCLUDE.match(line)
                        if not match or "/" not in match.group(1):
                            continue
                        target = match.group(1).split("/")
                        if target[0] not in ALLOWED:
                            continue  # a sibling header of a test or a third-party path
                        if target[0] != folder and target[0] not in allowed:
                            found.append(f"{relative}:{number}: {folder}/ may not include {match.group(1)}")
                        elif wing and target[0] == "overlay" and len(target) > 2 and target[1] not in OVERLAY_WINGS[wing]:
                            found.append(f"{relative}:{number}: overlay/{wing}/ may not include {match.group(1)}")
                        elif wing and target[0] == "overlay" and len(target) == 2:
                            found.append(f"{relative}:{number}: overlay/{wing}/ may not include the renderer "
                                         f"({match.group(1)})")
    return found


def unit(path):
    """A file's unit: its path without the extension, so that a .cpp and its .h are one node."""
    return os.path.splitext(path)[0]


def cycles(root):
    """Cycles among the units of each folder, found by a depth-first search over its own includes."""
    edges = {}
    for folder in ALLOWED:
        for directory, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                relative = os.path.relpath(os.path.join(directory, name), root)
                targets = edges.setdefault(unit(relative), set())
                with open(os.path.join(root, relative), encoding="utf-8") as source:
                    for line in source:
                        match = INCLUDE.match(line)
                        if match and match.group(1).split("/")[0] == folder:
                            target = unit(match.group(1))
                            if target != unit(relative) and os.path.exists(os.path.join(root, match.group(1))):
                                targets.add(target)
    found, state, seen = [], {}, set()

    def visit(node, stack):
        state[node] = "open"
        stack.append(node)
        for target in sorted(edges.get(node, ())):
            if state.get(target) == "open":
                loop = stack[stack.index(target):] + [target]
                if tuple(sorted(set(loop))) in KNOWN_CYCLES:
                    seen.add(tuple(sorted(set(loop))))
                else:
                    found.append("cycle inside " + target.split(os.sep)[0] + "/: " + " -> ".join(loop))
            elif target not in state:
                visit(target, stack)
        stack.pop()
        state[node] = "done"

    for node in sorted(edges):
        if node not in state:
            visit(node, [])
    found += [f"the known cycle {' <-> '.join(pair)} is gone: take it off KNOWN_CYCLES" for pair in
              sorted(KNOWN_CYCLES - seen) if all(part in edges for part in pair)]
    return found


def spread(root):
    """Classes whose member functions are defined in more than one .cpp file."""
    files, namespaces = {}, set()
    for folder in ALLOWED:
        for directory, _, names in os.walk(os.path.join(root, folder)):
            for name in sorted(names):
                if not name.endswith(".cpp") or name.endswith("_none.cpp"):
                    continue
                relative = os.path.relpath(os.path.join(directory, name), root)
                with open(os.path.join(root, relative), encoding="utf-8") as source:
                    for line in source:
                        if (match := NAMESPACE.match(line)):
                            namespaces.update(match.group(1).split("::"))
                        elif line[:1].isalpha() and (match := MEMBER.match(line)):
                            files.setdefault(match.group(1), set()).add(relative)
    found, seen = [], set()
    for name, where in sorted(files.items()):
        if len(where) < 2 or name.split("::")[-1] in namespaces:
            continue
        if name in KNOWN_SPREAD:
            seen.add(name)
        else:
            found.append(f"class {name} has member functions in {len(where)} files: {', '.join(sorted(where))}")
    found += [f"the class {name} is in one file now: take it off KNOWN_SPREAD" for name in sorted(KNOWN_SPREAD - seen)
              if name in files]
    return found


def namespaces(root):
    """Namespaces other than `overlayd`, its per-instruction-set copies and (under tests/) its test support."""
    found = []
    for folder in list(ALLOWED) + ["tests"]:
        inner = PER_INSTRUCTION_SET | (TEST_SUPPORT if folder == "tests" else set())
        for directory, _, names in os.walk(os.path.join(root, folder)):
            if os.path.relpath(directory, root).startswith(os.path.join("tests", "data")):
                continue  # fixtures, planted faults among them
            for name in sorted(names):
                if not name.endswith((".h", ".cpp")):
                    continue
                relative = os.path.relpath(os.path.join(directory, name), root)
                with open(os.path.join(root, relative), encoding="utf-8") as source:
                    for number, line in enumerate(source, 1):
                        if not (match := OPENED.match(line)):
                            continue
                        parts = match.group(1).split("::")
                        if parts[0] == "overlayd":
                            parts = parts[1:]
                        if parts and (len(parts) > 1 or parts[0] not in inner) and parts != ["std"]:
                            found.append(f"{relative}:{number}: namespace {match.group(1)}: overlayd's code is in "
                                         "the one namespace overlayd (docs/architecture.md)")
    return found


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    root = os.path.abspath(root)
    found = problems(root) + cycles(root) + spread(root) + namespaces(root)
    for problem in found:
        print(problem)
    if found:
        print(f"{len(found)} include(s), cycle(s), spread class(es) or namespace(s) against docs/architecture.md")
        return 1
    print("layering ok: " + ", ".join(f"{folder} -> {{{', '.join(sorted(allowed))}}}" for folder, allowed in
                                      ALLOWED.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
