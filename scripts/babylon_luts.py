#!/usr/bin/env python3
# Carries Babylon.js's environment BRDF texture (the RGBD PNG inlined in brdfTextureTools.ts) into
# host/src/model/babylon_brdf_lut.inc as the half-float texels Babylon expands it to
# (docs/profiles.md "Tables"); scripts/engine-check reads the same texture through
# decoded_texels() (engine_check/babylon.py).
import argparse
import base64
import hashlib
import math
import os
import re
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import khronos_luts  # noqa: E402  (the PNG reader)

TS_PATH = os.path.join("packages", "dev", "core", "src", "Misc", "brdfTextureTools.ts")
SIZE = 256  # BRDFCL_BABYLON_BRDF_SIZE in kernels/common/material_layout.h
OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "host", "src", "model",
                   "babylon_brdf_lut.inc")


class LutError(Exception):
    pass


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def png_bytes(ts_path):
    """The PNG that brdfTextureTools.ts inlines as _environmentBRDFBase64Texture's data URI."""
    with open(ts_path, encoding="utf-8") as f:
        text = f.read()
    m = re.search(r"_environmentBRDFBase64Texture\s*=\s*[\"']data:image/png;base64,([A-Za-z0-9+/=\s]+)[\"']", text)
    if not m:
        raise LutError("%s has no _environmentBRDFBase64Texture PNG data URI" % ts_path)
    try:
        return base64.b64decode(re.sub(r"\s", "", m.group(1)), validate=True)
    except ValueError as e:
        raise LutError("%s: the base64 PNG does not decode: %s" % (ts_path, e))


def from_rgbd(r, g, b, a):
    """helperFunctions.fx fromRGBD on 8-bit unorm texels, in float: pow(rgb, 2.2) / a
    (LinearEncodePowerApprox; the engine does not set USE_EXACT_SRGB_CONVERSIONS by default)."""
    if a == 0:
        raise LutError("a texel has alpha 0, which RGBD cannot divide by")
    d = f32(a / 255.0)
    return tuple(f32(f32(math.pow(f32(c / 255.0), f32(2.2))) / d) for c in (r, g, b))


def half_bits(x):
    """x rounded to IEEE binary16 (round to nearest even), as its bits: what a RGBA16F render target
    stores when rgbdDecode.fragment writes the float."""
    return struct.unpack("<H", struct.pack("<e", x))[0]


def decoded_texels(ts_path):
    """(png sha256, width, height, [(r, g, b) half-float bits per texel]), row-major, first PNG row
    first (v = 0 with invertY = false)."""
    data = png_bytes(ts_path)
    try:
        w, h, bpp, rows = khronos_luts.png_rows(data, ts_path)
    except zlib.error as e:
        raise LutError("%s: the PNG's image data does not inflate: %s" % (ts_path, e))
    if bpp != 4:
        raise LutError("%s: the BRDF PNG is not 8-bit RGBA" % ts_path)
    out = []
    for line in rows:
        for x in range(w):
            r, g, b, a = line[4 * x:4 * x + 4]
            out.append(tuple(half_bits(c) for c in from_rgbd(r, g, b, a)))
    return hashlib.sha256(data).hexdigest(), w, h, out


def main():
    ap = argparse.ArgumentParser(description="Writes host/src/model/babylon_brdf_lut.inc from a Babylon.js checkout.")
    ap.add_argument("--sources", required=True, help="a Babylon.js checkout (holds %s)" % TS_PATH)
    args = ap.parse_args()
    try:
        sha, w, h, texels = decoded_texels(os.path.join(args.sources, TS_PATH))
    except (OSError, LutError, khronos_luts.PngError) as e:
        sys.exit("babylon_luts: %s" % e)
    if (w, h) != (SIZE, SIZE):
        sys.exit("babylon_luts: the BRDF PNG is %dx%d, brdfcl's layout expects %dx%d" % (w, h, SIZE, SIZE))
    raw = b"".join(struct.pack("<3H", *t) for t in texels)
    packed = zlib.compress(raw, 9)
    lines = ["// Babylon.js's environment BRDF texture, carried over as data: BabylonJS/Babylon.js",
             "// %s, the inlined RGBD PNG (sha256 %s, 256x256)," % (TS_PATH.replace(os.sep, "/"), sha[:16]),
             "// each texel decoded as rgbdDecode does (pow(rgb, 2.2) / a in float) and rounded to half float;",
             "// (r, g, b) bits little-endian per texel, row j = perceptual roughness, column i = N.V; zlib-compressed.",
             "// Written by scripts/babylon_luts.py; data only."]
    for i in range(0, len(packed), 24):
        lines.append("    " + ", ".join(str(b) for b in packed[i:i + 24]) + ",")
    with open(OUT + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(OUT + ".tmp", OUT)
    print("babylon_luts: wrote %s (%d texels, %d bytes compressed)" % (OUT, len(texels), len(packed)))


if __name__ == "__main__":
    main()
