# The image-based-light check (--ibl): the EXR writer and reader, the G-buffer `brdfcl shade`
# reads, and check_ibl, which runs each engine's IBL code against it and prints the report.
import json
import os
import random
import struct
import subprocess
import zlib
from .common import CheckError, progress
from .sets import edge_set, random_set
from .compare import print_report, worst_pair
from .sources import build_engine
from .brdfcl import run_engine_exe
from .engines import ENGINES, IBL_ENGINES


# ---------------------------------------------------------------------------------------------
# Image-based light: each engine's IBL shader code under a constant environment (its samplers
# answer one radiance), its split-sum tables answered with brdfcl's where the engine computes
# them at run time, against `brdfcl shade`.


def exr_zip(raw):
    """OpenEXR's ZIP block encoding: the two-halves interleave, the byte predictor, zlib."""
    half = (len(raw) + 1) // 2
    t = bytearray(len(raw))
    t[:half] = raw[0::2]
    t[half:] = raw[1::2]
    p = bytearray(t)
    for i in range(1, len(t)):
        p[i] = (t[i] - t[i - 1] + 128) & 0xFF
    return zlib.compress(bytes(p))


EXR_LINES = {0: 1, 2: 1, 3: 16}  # compression (none, ZIPS, ZIP) -> scan lines per block


def exr_write(path, width, height, channels, compression=0):
    """A single-part scan-line OpenEXR file, FLOAT channels ({name: [w*h values]}), uncompressed
    (0), ZIPS (2, one line per block) or ZIP (3, blocks of 16 lines)."""
    names = sorted(channels)

    def attr(name, typ, data):
        return name.encode() + b"\0" + typ.encode() + b"\0" + struct.pack("<i", len(data)) + data

    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for n in names) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (struct.pack("<ii", 20000630, 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", bytes([compression])) + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    per = EXR_LINES[compression]
    chunks = []
    for y in range(0, height, per):
        raw = b"".join(struct.pack("<%df" % width, *channels[n][ln * width:(ln + 1) * width])
                       for ln in range(y, min(y + per, height)) for n in names)
        data = exr_zip(raw) if compression else raw
        data = data if len(data) < len(raw) else raw  # OpenEXR keeps a block that does not shrink raw
        chunks.append(struct.pack("<ii", y, len(data)) + data)
    offsets, pos = [], len(header) + 8 * len(chunks)
    for c in chunks:
        offsets.append(pos)
        pos += len(c)
    with open(path, "wb") as f:
        f.write(header + b"".join(struct.pack("<Q", o) for o in offsets) + b"".join(chunks))


def exr_unzip(data, raw_size):
    """OpenEXR's ZIP/ZIPS block: zlib, then the byte predictor and the two-halves interleave undone."""
    t = bytearray(zlib.decompress(data))
    if len(t) != raw_size:
        raise CheckError("an EXR block inflates to %d bytes, not %d" % (len(t), raw_size))
    for i in range(1, len(t)):
        t[i] = (t[i - 1] + t[i] - 128) & 0xFF
    half = (len(t) + 1) // 2
    out = bytearray(len(t))
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return bytes(out)


def exr_read(path):
    """(width, height, {channel: values}) of a single-part scan-line EXR with FLOAT channels,
    uncompressed, ZIPS or ZIP (what brdfcl writes)."""
    with open(path, "rb") as f:
        data = f.read()
    if struct.unpack_from("<i", data, 0)[0] != 20000630:
        raise CheckError("%s is not an OpenEXR file" % path)
    pos, attrs = 8, {}
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        tend = data.index(b"\0", end + 1)
        size = struct.unpack_from("<i", data, tend + 1)[0]
        attrs[name] = data[tend + 5:tend + 5 + size]
        pos = tend + 5 + size
    pos += 1
    chans, c = [], attrs["channels"]
    k = 0
    while c[k] != 0:
        end = c.index(b"\0", k)
        ptype = struct.unpack_from("<i", c, end + 1)[0]
        if ptype != 2:
            raise CheckError("%s: channel %s is not FLOAT" % (path, c[k:end].decode()))
        chans.append(c[k:end].decode())
        k = end + 17
    comp = attrs["compression"][0]
    if comp not in EXR_LINES:
        raise CheckError("%s: compression %d is not read here (only none, ZIPS, ZIP)" % (path, comp))
    x0, y0, x1, y1 = struct.unpack("<iiii", attrs["dataWindow"])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    per = EXR_LINES[comp]
    nblocks = (h + per - 1) // per
    offsets = struct.unpack_from("<%dQ" % nblocks, data, pos)
    out = {n: [0.0] * (w * h) for n in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        lines = min(per, y0 + h - y)
        raw = 4 * w * len(chans) * lines
        block = data[off + 8:off + 8 + size]
        if size < raw:
            block = exr_unzip(block, raw)
        for ln in range(lines):
            for ci, n in enumerate(chans):
                vals = struct.unpack_from("<%df" % w, block, 4 * w * (ln * len(chans) + ci))
                row = (y - y0 + ln) * w
                out[n][row:row + w] = vals
    return w, h, out


def write_gbuffer(path, mats, pairs):
    """One pixel per (material, V): N = clearcoatN = +Z, T = +X, at the origin, covered."""
    n = len(pairs)
    w = min(n, 256)
    h = (n + w - 1) // w
    ch = {name: [0.0] * (w * h) for name in
          ["P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "T.X", "T.Y", "T.Z", "baseColor.R", "baseColor.G", "baseColor.B",
           "metallic", "roughness", "mask", "sheenColor.R", "sheenColor.G", "sheenColor.B", "sheenRoughness",
           "clearcoat", "clearcoatRoughness", "clearcoatN.X", "clearcoatN.Y", "clearcoatN.Z", "anisotropyStrength",
           "anisotropyRotation", "V.X", "V.Y", "V.Z"]}
    for k in range(w * h):
        ch["N.Z"][k] = ch["clearcoatN.Z"][k] = ch["T.X"][k] = ch["V.Z"][k] = 1.0
    for k, (i, _, V) in enumerate(pairs):
        m = mats[i]
        ch["mask"][k] = 1.0
        for c, name in enumerate("RGB"):
            ch["baseColor." + name][k] = m.base[c]
            if m.sheen is not None:
                ch["sheenColor." + name][k] = m.sheen[0][c]
        ch["metallic"][k], ch["roughness"][k] = m.metallic, m.roughness
        if m.sheen is not None:
            ch["sheenRoughness"][k] = m.sheen[1]
        if m.clearcoat is not None:
            ch["clearcoat"][k], ch["clearcoatRoughness"][k] = m.clearcoat
        if m.anisotropy is not None:
            ch["anisotropyStrength"][k], ch["anisotropyRotation"][k] = m.anisotropy
        ch["V.X"][k], ch["V.Y"][k], ch["V.Z"][k] = V
    exr_write(path, w, h, ch)


def brdfcl_shade_ibl(exe, d, tag, profile, mats, pairs):
    """brdfcl's image-based light per pair under a uniform environment of radiance 1."""
    g = os.path.join(d, tag + ".gbuffer.exr")
    write_gbuffer(g, mats, pairs)
    scene = os.path.join(d, tag + ".scene.json")
    with open(scene, "w") as f:
        json.dump({"lights": [], "environment": {"builtin": "uniform", "intensity": 1}}, f)
    out = os.path.join(d, "%s-%s.shade.exr" % (tag, profile))
    cmd = [exe, "shade", "--gbuffer", g, "--scene", scene, "--out", out, "--profile", profile]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise CheckError("%s failed: %s" % (" ".join(cmd), r.stderr.strip()))
    w, h, ch = exr_read(out)
    return [(ch["R"][k], ch["G"][k], ch["B"][k]) for k in range(len(pairs))]


def ibl_sets(rng, n_mats, per):
    """The direct check's sets without KHR_materials_ior (a G-buffer carries no IOR: shade uses 1.5)."""
    sets = {"random": random_set(rng, n_mats, per), "edge": edge_set(rng)}
    for mats, _ in sets.values():
        for m in mats:
            m.ior = None
    return sets


IBL_COMPONENTS = ["all", "base", "sheen", "clearcoat", "anisotropy"]


def ibl_component(m, comp):
    if comp == "all":
        return True
    if comp == "base":
        return m.sheen is None and m.clearcoat is None and m.anisotropy is None
    return getattr(m, comp) is not None


def check_ibl(a, work, wanted):
    rng = random.Random(a.seed)
    sets = ibl_sets(rng, a.materials, a.pairs)
    dfg = os.path.join(work, "ggx-dfg-64.csv")
    cmd = [a.brdfcl, "lut", "--kind", "ggx-dfg", "--size", "64", "--out", dfg]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise CheckError("%s failed: %s" % (" ".join(cmd), r.stderr.strip()))
    results = []
    for prof in wanted:
        if prof not in IBL_ENGINES:
            print("%s: no image-based-light glue in this harness yet, not checked" % prof)
            continue
        folder, builder = ENGINES[prof][0], IBL_ENGINES[prof]
        built = build_engine(a, work, prof, folder, builder, prof + " (image-based light)")
        if built is None:
            continue
        exes, files, per_file = built
        for p in files:
            print("  %-58s last changed %s" % (p, per_file[p]))
        for tag, (mats, pairs) in sets.items():
            progress("%s image-based light: %s set" % (prof, tag))
            eng = run_engine_exe(exes[0], work, "%s-ibl-%s" % (prof, tag), mats, pairs, None, a.brdfcl,
                                 {"EC_GGX_DFG": dfg})
            ours = brdfcl_shade_ibl(a.brdfcl, work, "ibl-" + tag, prof, mats, pairs)
            for comp in IBL_COMPONENTS:
                worst, at, nan_bad, nan_at = worst_pair(pairs, [r["all"] for r in eng], ours, a.floor,
                                                        lambda i: ibl_component(mats[i], comp))
                results.append((prof, comp, tag, worst, nan_bad, at, nan_at, pairs, mats))
    print_report(a, results, "component", 10, "at (material; V; engine -> brdfcl)", False)
    return 0
