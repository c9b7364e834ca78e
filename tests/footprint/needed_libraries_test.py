#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The shared libraries overlayd must not name (DT_NEEDED): each one loaded at every start, `overlayd --version`
included, costs resident memory (docs/footprint.md) for something the daemon does without it.

  needed_libraries_test.py OVERLAYD [--deny PREFIX ...]

Exit 1 naming each denied library the binary needs. The default list and why:
- libopencv_freetype: text is drawn from overlayd's own glyph cache on FreeType (overlay/raster/text_renderer.cpp);
  the module brought HarfBuzz and GLib;
- libopencv_imgcodecs, libopencv_highgui, libopencv_videoio: image files go through media/codec (libpng,
  libjpeg-turbo); imgcodecs alone brought about a hundred libraries (GDAL, poppler, HDF5, ...).
"""
import argparse
import re
import subprocess
import sys

DENIED = ['libopencv_freetype.so', 'libopencv_imgcodecs.so', 'libopencv_highgui.so', 'libopencv_videoio.so']


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('binary')
    parser.add_argument('--deny', nargs='+', default=DENIED, metavar='PREFIX')
    args = parser.parse_args()
    out = subprocess.run(['readelf', '-d', args.binary], capture_output=True, text=True, check=True).stdout
    needed = re.findall(r'\(NEEDED\)\s+Shared library: \[(.+)\]', out)
    if not needed:
        sys.exit(f'{args.binary}: no DT_NEEDED entries found (not a dynamically linked ELF?)')
    found = [name for name in needed if any(name.startswith(prefix) for prefix in args.deny)]
    for name in found:
        print(f'{args.binary} needs {name}, which it must not (see {__file__})')
    print(f'{len(needed)} libraries needed; denied: {", ".join(found) or "none"}')
    return 1 if found else 0


if __name__ == '__main__':
    sys.exit(main())
