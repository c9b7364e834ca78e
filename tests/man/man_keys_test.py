#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""overlayd.toml(5) and the config schema name the same keys. The schema is what the loader reads: every key a
TableReader call in config/*.cpp asks for by name ("reader.integer("buffers", 2, 32)"), plus the keys it reads
through its tables of names (the pose forms, the intrinsics forms, frustum sides, loops over key lists). The page is the scdoc source
man/config_page.py makes from docs/config.md.

Both ways: a schema key the page never names in bold (a new key nobody documented) fails, and so does an entry of
one of the page's key tables that the loader does not read (a removed or misspelt key still documented).

    man_keys_test.py SOURCE_DIR PAGE.scd [--plant undocumented|unknown]
--plant puts a fault into the page first, to show that the check catches it: `log_level` no longer in bold
(undocumented), or an entry for a key the loader does not have (unknown)."""
import glob
import os
import re
import sys

READER_CALL = re.compile(r'(?:\.|->)\s*(?:node|has|number|positive|integer|boolean|string|choice(?:<[^>]*>)?|vec2|vec3|'
                         r'quaternion|numbers|points|strings|colour|colours|table|tables|problem)\(\s*"([a-z_][a-z0-9_]*)"')
NAME_TABLE = re.compile(r'(kPoseForms|kIntrinsicsForms)\[\]\s*=\s*\{(.*?)\n\};', re.S)
SIDE_PAIR = re.compile(r'\{"([a-z_]+)",\s*&')
KEY_LOOP = re.compile(r'for \(std::string_view \w+ : \{([^}]*)\}\)')
LITERAL = re.compile(r'"([a-z_][a-z0-9_]*)"')
BOLD = re.compile(r'\*((?:[^*\\]|\\.)+)\*')
# Entries of the tables whose first column is a key (header "key | type | default" or "key | default"): the
# entry line, then "\ttype: " or "\tdefault: ". Tables of forms, annotation types and limits head rows otherwise.
ENTRY = re.compile(r'^(\S.*)\n\t(?:type|default): ', re.M)


def schema_keys(root):
    keys = set()
    for path in glob.glob(os.path.join(root, 'config', '*.cpp')):
        text = open(path, encoding='utf-8').read()
        keys.update(READER_CALL.findall(text))
        keys.update(SIDE_PAIR.findall(text))
        for _, body in NAME_TABLE.findall(text):
            keys.update(LITERAL.findall(body))
        for body in KEY_LOOP.findall(text):
            keys.update(LITERAL.findall(body))
    return keys


def unescape(text):
    return re.sub(r'\\(.)', r'\1', text)


def page_words(page):
    """Every identifier the page sets in bold (keys are bold: `key` in the document), dotted paths split."""
    words = set()
    for bold in (span for line in page.splitlines() for span in BOLD.findall(line)):
        words.update(re.findall(r'[a-z_][a-z0-9_]*', unescape(bold)))
    return words


def page_entries(page):
    """The keys that head an entry of a key table ("input *bias*", "*width*, *height*"), without a qualifier."""
    entries = set()
    for line in ENTRY.findall(page):
        for bold in BOLD.findall(line):
            name = unescape(bold)
            if re.fullmatch(r'[a-z_][a-z0-9_]*', name):
                entries.add(name)
    return entries


def main():
    root, page_path = sys.argv[1], sys.argv[2]
    page = open(page_path, encoding='utf-8').read()
    plant = sys.argv[4] if len(sys.argv) > 4 and sys.argv[3] == '--plant' else None
    if plant == 'undocumented':
        page = page.replace('*log\\_level*', 'log level')
    elif plant == 'unknown':
        page += '\n*frame\\_budget*\n\tdefault: 4\n'
    schema = schema_keys(root)
    if len(schema) < 100:
        print(f'only {len(schema)} keys found in config/*.cpp: the reader calls changed shape; update this test')
        return 1
    failures = [f'{page_path}: the schema key `{key}` is not in overlayd.toml(5) (document it in docs/config.md)'
                for key in sorted(schema - page_words(page))]
    failures += [f'{page_path}: overlayd.toml(5) documents `{key}`, which config/*.cpp never reads'
                 for key in sorted(page_entries(page) - schema)]
    for failure in failures:
        print(failure)
    print(f'{len(schema)} schema keys, {len(page_entries(page))} key entries in the page')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
