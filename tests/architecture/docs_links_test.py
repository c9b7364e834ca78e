#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The documents stay true to the tree: every relative link in README.md and docs/*.md resolves (to a file, or to a
heading of a Markdown file when it names an anchor), and every repository path they name in backticks
(`daemon/pipeline.cpp`, `tests/http/`, `config/*_config.cpp`) exists. Exit status 1 lists every broken one as
file:line. A path in prose is checked when it names a file (folder/name.ext). Paths inside fenced code blocks are
commands' arguments (build/..., out/...), not checked."""
import glob
import os
import re
import sys

LINK = re.compile(r'!?\[[^\]]*\]\(([^)\s]+)(?:\s+"[^"]*")?\)')
CODE_SPAN = re.compile(r'`([^`]+)`')
HEADING = re.compile(r'^(#{1,6})\s+(.*?)\s*#*\s*$')
# Folders that exist only after a build or a run: a path under them is an output, not a file of the repository.
GENERATED = {"build", "out", ".git", ".cache"}


def documents(root):
    found = [os.path.join(root, "README.md")] if os.path.exists(os.path.join(root, "README.md")) else []
    found += sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
    return found


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r'`|\*\*|\*|_(?=\W)|\[([^\]]*)\]\([^)]*\)', lambda m: m.group(1) or "", heading.strip()).lower()
    return re.sub(r'[^\w\- ]', '', text).replace(' ', '-')


def anchors(path, cache={}):
    if path not in cache:
        found, seen, fenced = set(), {}, False
        with open(path, encoding="utf-8") as document:
            for line in document:
                if line.startswith("```"):
                    fenced = not fenced
                match = None if fenced else HEADING.match(line)
                if match:
                    base = slug(match.group(2))
                    count = seen.get(base, 0)
                    seen[base] = count + 1
                    found.add(base if count == 0 else f"{base}-{count}")
        cache[path] = found
    return cache[path]


def check_link(root, path, target):
    if re.match(r'^[a-z][a-z0-9+.-]*:', target):  # http:, https:, mailto:
        return None
    file_part, _, anchor = target.partition("#")
    resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
    if not os.path.exists(resolved):
        return f"link to {target}: {os.path.relpath(resolved, root)} does not exist"
    if anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
        return f"link to {target}: no heading with the anchor #{anchor} in {os.path.relpath(resolved, root)}"
    return None


def repository_paths(root, span):
    folders = {name for name in os.listdir(root) if os.path.isdir(os.path.join(root, name)) and
               name not in GENERATED and not name.startswith(".")}
    pattern = re.compile(r'(?<![\w./-])((?:' + "|".join(map(re.escape, sorted(folders))) + r')/[\w./*@-]*)')
    for match in pattern.finditer(span):
        candidate = match.group(1).rstrip(".,:;")
        if re.search(r'[<>{}$%]|NAME|DATE|\.\.\.', span[match.start():match.end() + 1]):
            continue  # a pattern a person fills in (tests/fuzz/<target>, out/bench-DATE.json), not a path
        yield candidate


def problems(root):
    found = []
    for path in documents(root):
        relative = os.path.relpath(path, root)
        fenced = False
        with open(path, encoding="utf-8") as document:
            for number, line in enumerate(document, 1):
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                    continue
                if fenced:
                    continue
                for match in LINK.finditer(line):
                    problem = check_link(root, path, match.group(1))
                    if problem:
                        found.append(f"{relative}:{number}: {problem}")
                prose = CODE_SPAN.sub(" ", LINK.sub(" ", line))
                named = [path for span in CODE_SPAN.findall(line) for path in repository_paths(root, span)]
                named += [path for path in repository_paths(root, prose) if re.search(r'\.[a-z]+$', path)]
                for candidate in named:
                    if not glob.glob(os.path.join(root, candidate)):
                        found.append(f"{relative}:{number}: names `{candidate}`, which does not exist")
    return found


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    found = problems(root)
    for problem in found:
        print(problem)
    if found:
        print(f"{len(found)} broken link(s) or path(s) in the documents")
        return 1
    print(f"docs links ok: {len(documents(root))} documents")
    return 0


if __name__ == "__main__":
    sys.exit(main())
