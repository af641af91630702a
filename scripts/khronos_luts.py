#!/usr/bin/env python3
# Carries the glTF Sample Renderer's sheen albedo table (assets/images/lut_sheen_E.png) into
# host/src/model/khronos_sheen_e_lut.inc as the 8-bit texels a WebGL upload of it holds
# (docs/profiles.md "Tables"); scripts/engine-check reads the same PNG through
# read_texels() (engine_check/khronos.py).
import argparse
import hashlib
import os
import struct
import sys
import zlib

PNG_PATH = os.path.join("assets", "images", "lut_sheen_E.png")
SIZE = 1024  # BRDFCL_KHRONOS_SHEEN_E_SIZE in kernels/common/material_layout.h
OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "host", "src", "model",
                   "khronos_sheen_e_lut.inc")


class PngError(Exception):
    pass


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else (b if pb <= pc else c)


def png_rows(data, path):
    """(width, height, bytes per pixel, unfiltered rows) of a PNG file's bytes; `path` names it in errors."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise PngError("%s is not a PNG file" % path)
    pos, idat, hdr = 8, [], None
    while pos + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            hdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + n
    if hdr is None:
        raise PngError("%s has no IHDR chunk" % path)
    w, h, depth, ctype, _, _, interlace = hdr
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(ctype)
    if channels is None or depth not in (8, 16) or interlace:
        raise PngError("%s: only non-interlaced 8- or 16-bit grey/RGB(A) PNGs are read (colour type %d, depth %d)"
                       % (path, ctype, depth))
    raw = zlib.decompress(b"".join(idat))
    bpp = channels * depth // 8
    stride = w * bpp
    if len(raw) != h * (stride + 1):
        raise PngError("%s: image data is %d bytes, expected %d" % (path, len(raw), h * (stride + 1)))
    prev = bytearray(stride)
    rows = []
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:
            for x in range(bpp, stride):
                line[x] = (line[x] + line[x - bpp]) & 255
        elif f == 2:
            for x in range(stride):
                line[x] = (line[x] + prev[x]) & 255
        elif f == 3:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                line[x] = (line[x] + ((a + prev[x]) >> 1)) & 255
        elif f == 4:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                c = prev[x - bpp] if x >= bpp else 0
                line[x] = (line[x] + _paeth(a, prev[x], c)) & 255
        elif f != 0:
            raise PngError("%s: unknown row filter %d" % (path, f))
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def read_texels(path):
    """(width, height, red channel as 8-bit unorm values, row-major, first PNG row first).
    A 16-bit channel keeps its high byte: the browser decodes the PNG to 8 bits per channel
    before texImage2D(RGBA8, UNSIGNED_BYTE) (libpng's png_set_strip_16)."""
    with open(path, "rb") as f:
        data = f.read()
    w, h, bpp, rows = png_rows(data, path)
    return w, h, b"".join(line[0::bpp] for line in rows)  # the red sample's first (high) byte


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("renderer", help="a glTF-Sample-Renderer checkout (holds %s)" % PNG_PATH)
    args = ap.parse_args()
    path = os.path.join(args.renderer, PNG_PATH)
    w, h, texels = read_texels(path)
    with open(path, "rb") as f:
        data = f.read()
    blob = hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest()
    if (w, h) != (SIZE, SIZE):
        sys.exit("khronos_luts: %s is %dx%d, brdfcl's layout expects %dx%d" % (PNG_PATH, w, h, SIZE, SIZE))
    packed = zlib.compress(texels, 9)
    lines = ["// glTF Sample Renderer's sheen albedo table, carried over as data: KhronosGroup/glTF-Sample-Renderer",
             "// %s (git blob %s, 1024x1024, 16-bit RGB), red channel as the 8-bit texels of" % (PNG_PATH, blob[:12]),
             "// its WebGL upload (high byte), row j = sheen roughness, column i = N.V; zlib-compressed.",
             "// Written by scripts/khronos_luts.py; data only."]
    for i in range(0, len(packed), 24):
        lines.append("    " + ", ".join(str(b) for b in packed[i:i + 24]) + ",")
    with open(OUT + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(OUT + ".tmp", OUT)
    print("khronos_luts: wrote %s (%d texels, %d bytes compressed)" % (OUT, len(texels), len(packed)))


if __name__ == "__main__":
    main()
