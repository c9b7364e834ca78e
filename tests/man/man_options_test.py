#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd(1) and the binary's --help agree: the commands `overlayd --help` lists are the page's COMMANDS
subsections, and each command's options and arguments (`overlayd COMMAND --help`) are the entries of its subsection,
the global ones those of GLOBAL OPTIONS; an option in one and not the other fails, either way.

    man_options_test.py OVERLAYD overlayd.1.scd [--plant stale]
--plant stale adds an option the binary does not have to the page's run section, to show that the check sees it."""
import re
import subprocess
import sys


def help_text(overlayd, *command):
    done = subprocess.run([overlayd, *command, '--help'], capture_output=True, text=True, timeout=30)
    if done.returncode != 0:
        raise SystemExit(f'{overlayd} {" ".join(command)} --help exited {done.returncode}: {done.stderr}')
    return done.stdout


def sections(text):
    """CLI11's help: {'Options': [lines], 'Positionals': [...], 'Subcommands': [...], group title: [...]}."""
    found, current = {}, None
    for line in text.splitlines():
        header = re.match(r'^(\S[^:]*):\s*$', line)
        if header:
            current = header.group(1)
            found[current] = []
        elif current and re.match(r'^  \S', line):  # an entry; deeper lines continue its description
            found[current].append(line.strip())
    return found


def help_entries(text):
    """Every option name (-c, --config) and positional argument a --help output lists (help and version too)."""
    entries = set()
    for title, lines in sections(text).items():
        if title in ('Subcommands', 'Examples', 'Example', 'Signals', 'Exit status'):
            continue
        for line in lines:
            head = line.split()[0]
            if title == 'Positionals':
                entries.add(head)
            elif head.startswith('-'):
                entries.update(name for name in head.split(',') if name)
    return entries


def help_commands(text):
    return {line.split()[0] for line in sections(text).get('Subcommands', [])}


def page_sections(page):
    """{'GLOBAL OPTIONS': text, 'run': text, ...}: the page's sections and its COMMANDS subsections."""
    parts, name = {}, None
    for line in page.splitlines():
        heading = re.match(r'^(#{1,2}) (.*)$', line)
        if heading:
            name = heading.group(2)
            parts[name] = []
        elif name:
            parts[name].append(line)
    return {name: '\n'.join(lines) for name, lines in parts.items()}


def page_entries(text):
    """The entries of a section: the lines just before an indented description, their *-x*, *--x* and _arg_."""
    entries = set()
    for line in re.findall(r'^(\S.*)\n\t', text, re.M):
        entries.update(re.findall(r'\*(--?[a-z][a-z-]*)\*', line))
        if line.startswith('_'):
            entries.add(re.match(r'_([a-z]+)_', line).group(1))
    return entries


def main():
    overlayd, page_path = sys.argv[1], sys.argv[2]
    page = open(page_path, encoding='utf-8').read()
    if sys.argv[3:] == ['--plant', 'stale']:
        page = page.replace('## run\n', '## run\n\n*--dry-run*\n\tCheck and exit.\n', 1)
    parts = page_sections(page)
    failures = []

    def compare(where, binary, documented):
        failures.extend(f'{where}: `{name}` is in --help but not in overlayd(1)' for name in sorted(binary - documented))
        failures.extend(f'{where}: overlayd(1) documents `{name}`, which --help does not list'
                        for name in sorted(documented - binary))

    top = help_text(overlayd)
    compare('overlayd', help_entries(top), page_entries(parts.get('GLOBAL OPTIONS', '')))
    commands = help_commands(top)
    documented = {name for name in parts if re.fullmatch(r'[a-z][a-z-]*', name)}
    compare('commands', commands, documented)
    for command in sorted(commands & documented):
        # --help is global: every command's help lists it, the page says so once under GLOBAL OPTIONS.
        compare(f'overlayd {command}', help_entries(help_text(overlayd, command)) - {'-h', '--help'},
                page_entries(parts[command]))
    for failure in failures:
        print(failure)
    print(f'{len(commands)} commands compared')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
