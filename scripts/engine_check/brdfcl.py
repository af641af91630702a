# Running brdfcl: the materials and pairs it reads, `brdfcl eval` per lobe, the sheen albedo
# tables the engines look up, and running an engine evaluator with brdfcl's look-ups.
import json
import math
import os
import re
import subprocess
from .common import CheckError, LOBES, fmt
from .sets import Mat


# ---------------------------------------------------------------------------------------------
# brdfcl

def write_inputs(d, tag, mats, pairs):
    mj = os.path.join(d, tag + ".json")
    with open(mj, "w") as f:
        json.dump({"materials": [m.gltf() for m in mats]}, f)
    # fmt() strings went in as JSON strings: turn them into numbers.
    with open(mj) as f:
        txt = f.read()
    with open(mj, "w") as f:
        f.write(re.sub(r'"(-?[0-9][0-9.e+-]*)"', r"\1", txt))
    sc = os.path.join(d, tag + ".csv")
    with open(sc, "w") as f:
        f.write("material,Lx,Ly,Lz,Vx,Vy,Vz\n")
        for i, L, V in pairs:
            f.write("%d,%s,%s\n" % (i, ",".join(fmt(c) for c in L), ",".join(fmt(c) for c in V)))
    return mj, sc


def brdfcl_eval(exe, args, mj, sc, out):
    cmd = [exe, "eval", "--materials", mj, "--samples", sc, "--out", out] + args
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise CheckError("%s failed: %s" % (" ".join(cmd), r.stderr.strip()))
    with open(out) as f:
        next(f)
        return [tuple(float(x) for x in line.split(",")) for line in f]


def sheen_albedo(exe, d, tag, mats, pairs):
    """E(N·V) and E(N·L) per pair for both sheen tables, read back from brdfcl's spec profile:
    with view-only scaling its diffuse lobe is (1 − E(N·V) max3(c)) times that of the same
    material without sheen."""
    probes = [Mat(base=[1.0, 1.0, 1.0], metallic=0.0, roughness=0.5)]
    for m in mats:
        rs = m.sheen[1] if m.sheen is not None else 0.5
        probes.append(Mat(base=[1.0, 1.0, 1.0], metallic=0.0, roughness=0.5, sheen=([1.0, 1.0, 1.0], rs)))
    rows = []
    for i, L, V in pairs:
        rows += [(i + 1, L, V), (0, L, V), (i + 1, V, L), (0, V, L)]
    mj, sc = write_inputs(d, tag + "-sheen-probe", probes, rows)
    out = {}
    for vis in ["charlie", "ashikhmin"]:
        res = brdfcl_eval(exe, ["--profile", "spec", "--lobe", "diffuse", "--sheen-scaling", "view",
                                "--sheen-visibility", vis], mj, sc, os.path.join(d, tag + "-sheen-" + vis + ".csv"))
        e = []
        for k in range(len(pairs)):
            a, b, c, dd = res[4 * k][0], res[4 * k + 1][0], res[4 * k + 2][0], res[4 * k + 3][0]
            e.append((1.0 - a / b if b else 0.0, 1.0 - c / dd if dd else 0.0))
        out[vis] = e
    return out


def sheen_table(exe, d, tag, coords):
    """brdfcl's sheen E at each (table, μ, r) of `coords` (table 0: E_CC, 1: E_CN), read back as
    sheen_albedo() does, with V at N·V = μ and L = N."""
    coords = sorted(coords)
    rough = sorted({r for _, _, r in coords})
    probes = [Mat(base=[1.0, 1.0, 1.0], metallic=0.0, roughness=0.5)]
    probes += [Mat(base=[1.0, 1.0, 1.0], metallic=0.0, roughness=0.5, sheen=([1.0, 1.0, 1.0], r)) for r in rough]
    index = {r: k + 1 for k, r in enumerate(rough)}
    rows = []
    for _, mu, r in coords:
        mu = min(max(mu, 0.0), 1.0)
        V = (math.sqrt(max(0.0, 1.0 - mu * mu)), 0.0, mu)
        rows += [(index[r], (0.0, 0.0, 1.0), V), (0, (0.0, 0.0, 1.0), V)]
    mj, sc = write_inputs(d, tag + "-table-probe", probes, rows)
    out = {}
    for table, vis in [(0, "charlie"), (1, "ashikhmin")]:
        wanted = [k for k, c in enumerate(coords) if c[0] == table]
        if not wanted:
            continue
        res = brdfcl_eval(exe, ["--profile", "spec", "--lobe", "diffuse", "--sheen-scaling", "view",
                                "--sheen-visibility", vis], mj, sc, os.path.join(d, tag + "-table-" + vis + ".csv"))
        for k in wanted:
            a, b = res[2 * k][0], res[2 * k + 1][0]
            out[coords[k]] = 1.0 - a / b if b else 0.0
    return out


def run_with_lookups(exe, args, d, tag, brdfcl, extra_env=None):
    """Runs an engine evaluator twice: once to learn the table coordinates it reads, once with
    brdfcl's values there (driver.hpp, table_lookup)."""
    rec = os.path.join(d, tag + ".lookups.txt")
    env = dict(os.environ, EC_LOOKUPS_OUT=rec, **(extra_env or {}))
    env.pop("EC_LOOKUPS", None)
    r = subprocess.run([exe] + args, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        raise CheckError("%s failed: %s" % (exe, r.stderr.strip()[-2000:]))
    if not os.path.exists(rec):
        return r  # an evaluator that reads no brdfcl table (three.js's) records none: one run is all
    coords = set()
    with open(rec) as f:
        for line in f:
            t, u, v = line.split()
            coords.add((int(t), float.fromhex(u), float.fromhex(v)))
    env = dict(os.environ, **(extra_env or {}))
    env.pop("EC_LOOKUPS_OUT", None)
    if coords:
        values = sheen_table(brdfcl, d, tag, coords)
        ans = os.path.join(d, tag + ".answers.txt")
        with open(ans, "w") as f:
            for (t, u, v), e in sorted(values.items()):
                f.write("%d %s %s %s\n" % (t, u.hex(), v.hex(), e.hex()))
        env["EC_LOOKUPS"] = ans
    r = subprocess.run([exe] + args, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        raise CheckError("%s failed: %s" % (exe, r.stderr.strip()[-2000:]))
    return r


def run_engine_exe(exe, d, tag, mats, pairs, albedo, brdfcl, env=None):
    mf = os.path.join(d, tag + ".mat.txt")
    with open(mf, "w") as f:
        for m in mats:
            f.write(m.line() + "\n")
    pf = os.path.join(d, tag + ".pairs.txt")
    with open(pf, "w") as f:
        for k, (i, L, V) in enumerate(pairs):
            ecc, ecn = (albedo["charlie"][k], albedo["ashikhmin"][k]) if albedo else ((0.0, 0.0), (0.0, 0.0))
            f.write("%d %s %s %s %s %s %s\n" % (i, " ".join(fmt(c) for c in L), " ".join(fmt(c) for c in V),
                                                 repr(ecc[0]), repr(ecc[1]), repr(ecn[0]), repr(ecn[1])))
    r = run_with_lookups(exe, [mf, pf], d, tag, brdfcl, env)
    rows = []
    for line in r.stdout.split("\n"):
        if line.strip():
            v = [float(x) for x in line.split()]
            rows.append({lobe: tuple(v[3 * k:3 * k + 3]) for k, lobe in enumerate(LOBES)})
    if len(rows) != len(pairs):
        raise CheckError("%s wrote %d rows for %d pairs" % (exe, len(rows), len(pairs)))
    return rows
