#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd.toml(5) in scdoc, made from docs/config.md: the one description of every key, its range, default and
meaning, so that the manual page cannot say something else. Each "## " section of the document becomes a section of
the page; a table becomes a list of entries (the first column is the entry, the others follow as "column: value");
prose stays prose, Markdown spans become the page's bold and underline.

    config_page.py docs/config.md overlayd.toml.5.scd [VERSION]"""
import re
import sys

INLINE = re.compile(r'`([^`]+)`|\*\*(.+?)\*\*|(?<![\w*])\*([^*\s][^*]*?)\*(?![\w*])|!?\[([^\]]*)\]\([^)]*\)')


def escape(text):
    """scdoc's markup characters taken literally."""
    return re.sub(r'([\\*_])', r'\\\1', text)


def inline(text):
    """Markdown spans to scdoc: code and strong as bold, emphasis as underline, a link as its text."""
    out, at = [], 0
    text = text.replace('\\|', '|')
    for match in INLINE.finditer(text):
        out.append(escape(text[at:match.start()]))
        code, strong, emphasis, link = match.groups()
        if code is not None:
            out.append('*' + escape(code) + '*')
        elif strong is not None:
            out.append('*' + escape(strong.replace('`', '')) + '*')
        elif emphasis is not None:
            out.append('_' + escape(emphasis) + '_')
        else:
            out.append(inline(link))
        at = match.end()
    out.append(escape(text[at:]))
    return ''.join(out)


def cells(row):
    """The cells of a Markdown table row; an escaped \\| stays inside its cell."""
    parts = re.split(r'(?<!\\)\|', row.strip().strip('|'))
    return [part.strip() for part in parts]


def table(rows):
    """A Markdown table as scdoc entries: the first cell is the entry, the others are lines indented beneath it."""
    header = cells(rows[0])
    lines = []
    for row in rows[2:]:
        values = cells(row)
        lines.append(inline(values[0]))
        details = [f'{name}: {value}' for name, value in zip(header[1:], values[1:]) if value]
        for index, detail in enumerate(details):  # ++ ends a line inside one paragraph
            lines.append(('\t' if index == 0 else '') + inline(detail) + (' ++' if index + 1 < len(details) else ''))
        lines.append('')
    return lines


def heading(text, level):
    title = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', text).replace('`', '')
    return ('# ' + title) if level == 2 else ('## ' + title)


def convert(markdown, version):
    lines = markdown.splitlines()
    page = [f'overlayd.toml(5) "overlayd {version}" "overlayd manual"', '', '# NAME', '',
            'overlayd.toml - configuration file of the overlayd camera-overlay daemon', '', '# SYNOPSIS', '',
            '*/etc/overlayd/overlayd.toml*, */etc/overlayd/*_NAME_*.toml*', '', '# DESCRIPTION', '']
    paragraph, rows = [], []

    def flush():
        if paragraph:
            page.extend([inline(' '.join(paragraph)), ''])
            paragraph.clear()
        if rows:
            page.extend(table(rows))
            rows.clear()

    for line in lines[1:]:  # the document's title is the page's NAME
        if line.startswith('|'):
            if paragraph:
                flush()
            rows.append(line)
            continue
        if rows:
            flush()
        match = re.match(r'^(#{2,3}) (.*)$', line)
        if match:
            flush()
            page.extend([heading(match.group(2), len(match.group(1))), ''])
        elif not line.strip():
            flush()
        else:
            paragraph.append(line.strip())
    flush()
    page += ['# SEE ALSO', '', '*overlayd*(1), *systemd.service*(5); /usr/share/doc/overlayd/ for the documents',
             'this page names (config.md is this page).', '']
    return '\n'.join(page)


def main():
    version = sys.argv[3] if len(sys.argv) > 3 else 'unknown'
    with open(sys.argv[1], encoding='utf-8') as source:
        text = convert(source.read(), version)
    with open(sys.argv[2], 'w', encoding='utf-8') as out:
        out.write(text)


if __name__ == '__main__':
    main()
