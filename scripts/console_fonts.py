#!/usr/bin/env python3
"""The characters the Linux console can show: the intersection of the Unicode tables of the
Debian console fonts a student is likely to have (console-setup-linux, /usr/share/consolefonts).

Writes tests/fixtures/console/glyphs.txt (one code point per line, hex), which the test
`ecosystem::the_linux_console_gets_no_glyph_its_fonts_lack` reads: under TERM=linux the
explorer may send only these. Run after `apt-get install console-setup-linux`:

    python3 scripts/console_fonts.py /usr/share/consolefonts > tests/fixtures/console/glyphs.txt
"""
import gzip
import struct
import sys
from pathlib import Path

FONTS = ["Lat15-Fixed16", "Lat2-Terminus16", "Uni2-Fixed16", "Uni3-Terminus16"]


def psf1(data):
    mode, size = data[2], data[3]
    glyphs = 512 if mode & 0x01 else 256
    if not mode & 0x06:
        raise ValueError("no Unicode table")
    table = data[4 + glyphs * size:]
    cps, i, seq = set(), 0, False
    while i + 1 < len(table):
        (v,) = struct.unpack_from("<H", table, i)
        i += 2
        if v == 0xFFFF:
            seq = False
        elif v == 0xFFFE:
            seq = True
        elif not seq:
            cps.add(v)
    return cps


def psf2(data):
    _, _, hsize, flags, length, charsize, _, _ = struct.unpack_from("<8I", data, 0)
    if not flags & 1:
        raise ValueError("no Unicode table")
    table = data[hsize + length * charsize:]
    cps = set()
    for entry in table.split(b"\xff"):
        single = entry.split(b"\xfe")[0]
        cps.update(ord(c) for c in single.decode("utf-8", "replace") if c != "\ufffd")
    return cps


def coverage(path):
    data = gzip.decompress(path.read_bytes())
    if data[:2] == b"\x36\x04":
        return psf1(data)
    if data[:4] == b"\x72\xb5\x4a\x86":
        return psf2(data)
    raise ValueError(f"{path}: not a PSF font")


def main():
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else "/usr/share/consolefonts")
    sets = [coverage(folder / f"{name}.psf.gz") for name in FONTS]
    common = set.intersection(*sets)
    print(f"# code points every one of {', '.join(FONTS)} has (Debian console-setup-linux)")
    print("# made by scripts/console_fonts.py; one hex code point per line")
    for cp in sorted(common):
        print(f"{cp:04x}")


if __name__ == "__main__":
    main()
