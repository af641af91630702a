#!/usr/bin/env python3
# brdfcl's spec material (every lobe, its clamps and its sheen E table) written in Dr.Jit, gathering
# K materials by index, on the LLVM or CUDA backend: checked against `brdfcl eval`, and timed side by
# side with `brdfcl bench --pairs --indices` on the same pairs, indices and materials.
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

from peer_pairs import make_pairs, median_seconds

# kernels/common/material_layout.h and kernels/brdf/material.h
MIN_ALPHA = 1.0e-3
MIN_SHEEN_ALPHA = 1.0e-3
MIN_COS = 1.0e-4
INV_PI = 1.0 / math.pi
LOBES = ("all", "diffuse", "specular", "sheen", "clearcoat")
BRDFCL_DEVICE = []  # --device DEV for every brdfcl command, from --device


def fail(message):
    print(f"drjit_peer: {message}", file=sys.stderr)
    sys.exit(2)


def check_pairs(n, seed):
    # The check also reaches past the timing domain: grazing and below-horizon directions (f = 0
    # there), L = V (H = V) and mirrored pairs (N.H -> 1), where clamps and select()s decide.
    planes = make_pairs(n, seed)
    rng = np.random.default_rng(seed + 1)
    k = n // 8
    z = rng.uniform(-0.05, 0.02, (2, k)).astype(np.float32)
    phi = rng.uniform(0.0, 2 * np.pi, (2, k)).astype(np.float32)
    s = np.sqrt(1.0 - z * z)
    planes[0, :k], planes[1, :k], planes[2, :k] = s[0] * np.cos(phi[0]), s[0] * np.sin(phi[0]), z[0]
    planes[3:, k:2 * k] = planes[:3, k:2 * k]  # L = V
    planes[3, 2 * k:3 * k], planes[4, 2 * k:3 * k] = -planes[0, 2 * k:3 * k], -planes[1, 2 * k:3 * k]
    planes[5, 2 * k:3 * k] = planes[2, 2 * k:3 * k]  # mirrored about N
    return planes


def pack(materials):
    # host/src/model/pack.cpp -> kernels/common/material_pack.h (ratified sheen; the bench
    # workloads have no draft sheen), in float32 as the host packs it.
    f = np.float32
    cols = {k: [] for k in ("base_r", "base_g", "base_b", "metallic", "alpha", "alpha_t", "aniso_cos", "aniso_sin",
                            "sheen_r", "sheen_g", "sheen_b", "sheen_max", "sheen_alpha", "sheen_roughness",
                            "clearcoat", "clearcoat_alpha")}
    for m in materials:
        r, s = f(m["roughness"]), f(m["anisotropy_strength"])
        alpha, s2 = r * r, s * s
        rot = f(m["anisotropy_rotation"])
        sheen = [f(c) for c in m["sheen_color"]]
        sr, cr = f(m["sheen_roughness"]), f(m["clearcoat_roughness"])
        values = {"base_r": f(m["base_color"][0]), "base_g": f(m["base_color"][1]), "base_b": f(m["base_color"][2]),
                  "metallic": f(m["metallic"]), "alpha": max(alpha, f(MIN_ALPHA)),
                  "alpha_t": max(alpha * (f(1) - s2) + s2, f(MIN_ALPHA)),
                  "aniso_cos": np.cos(rot), "aniso_sin": np.sin(rot),
                  "sheen_r": sheen[0], "sheen_g": sheen[1], "sheen_b": sheen[2], "sheen_max": max(sheen),
                  "sheen_alpha": max(sr * sr, f(MIN_SHEEN_ALPHA)), "sheen_roughness": sr,
                  "clearcoat": f(m["clearcoat"]), "clearcoat_alpha": max(cr * cr, f(MIN_ALPHA))}
        for k, v in values.items():
            cols[k].append(v)
    packed = {k: np.array(v, dtype=np.float32) for k, v in cols.items()}
    # The batch's feature set (pack.cpp featuresOf): a layer no material uses is compiled out, and
    # without anisotropy the specular takes the isotropic forms.
    features = {"sheen": bool((packed["sheen_max"] > 0).any()),
                "clearcoat": bool((packed["clearcoat"] > 0).any()),
                "anisotropy": any(m["anisotropy_strength"] > 0 for m in materials)}
    return packed, features


class Peer:
    """The spec material over one backend's arrays (drjit.llvm or drjit.cuda)."""

    def __init__(self, dr, mod, sheen_e, double=False):
        # double: the same maths on the same float32 inputs in float64, the check's referee.
        self.dr, self.t = dr, mod
        self.Float = mod.Float64 if double else mod.Float
        self.sheen_e = self.Float(np.ascontiguousarray(sheen_e, dtype=np.float32).ravel())
        self.e_size = sheen_e.shape[0]

    # --- kernels/common/lanes.h, fastmath.h: Dr.Jit's own exp, exp2, log, log2 stand in. Where clang
    # contracts an OpenCL C expression a * b + c into one fma (-ffp-contract=on, the OpenCL default),
    # dr.fma does it here, so that both round alike where the maths is ill-conditioned (sharp GGX peaks).
    @staticmethod
    def pow5(x):
        x2 = x * x
        return x2 * x2 * x

    def log1p(self, u):
        # Goldberg 1991, as brdf_log1p: exact for small u, inf stays inf.
        dr = self.dr
        w = 1.0 + u
        r = dr.log(w) * (u / (w - 1.0))
        r = dr.select(w == 1.0, u, r)
        return dr.select(dr.isinf(u), u, r)

    def mix(self, a, b, t):
        return self.dr.fma(b - a, t, a)

    # --- kernels/brdf/lobes.h -------------------------------------------------------------------
    def half_vector(self, L, V):
        dr, Float, fma = self.dr, self.Float, self.dr.fma
        hx, hy, hz = L[0] + V[0], L[1] + V[1], L[2] + V[2]
        h2 = fma(hz, hz, fma(hx, hx, hy * hy))
        degenerate = h2 < 1.0e-30
        scale = dr.select(h2 < 1.0e-12, Float(1099511627776.0), Float(1.0))
        return (dr.select(degenerate, 0.0, hx * scale), dr.select(degenerate, 0.0, hy * scale),
                dr.select(degenerate, 1.0, hz * scale))

    def geometry(self, L, V):
        dr, fma = self.dr, self.dr.fma
        g = {"L": L, "V": V, "NdotL": dr.maximum(L[2], MIN_COS), "NdotV": dr.maximum(V[2], MIN_COS)}
        h = self.half_vector(L, V)
        g["h"] = h
        g["hxy2"] = fma(h[0], h[0], h[1] * h[1])
        g["hn2"] = h[2] * h[2]
        g["h2"] = g["hxy2"] + g["hn2"]
        inv_h = dr.rsqrt(g["h2"])
        dx, dy, dz = fma(-h[0], inv_h, V[0]), fma(-h[1], inv_h, V[1]), fma(-h[2], inv_h, V[2])
        g["w"] = self.pow5(0.5 * fma(dz, dz, fma(dx, dx, dy * dy)))
        return g

    # --- kernels/brdf/terms.h -------------------------------------------------------------------
    def D_GGX_Anisotropic(self, ht, hb, hn, h2, at, ab):
        fma = self.dr.fma
        t, b = ht / at, hb / ab
        d = fma(hn, hn, fma(t, t, b * b))
        return (h2 * h2) / (math.pi * at * ab * d * d)

    def D_GGX(self, hxy2, hn2, alpha):
        a2 = alpha * alpha
        d = self.dr.fma(hn2, a2, hxy2)
        h2 = hxy2 + hn2
        return a2 * h2 * h2 / (math.pi * d * d)

    def V_GGX_Anisotropic(self, NdotL, NdotV, TdotV, BdotV, TdotL, BdotL, at, ab):
        sqrt, fma = self.dr.sqrt, self.dr.fma
        tv, bv, tl, bl = at * TdotV, ab * BdotV, at * TdotL, ab * BdotL
        ggxv = NdotL * sqrt(fma(NdotV, NdotV, fma(tv, tv, bv * bv)))
        ggxl = NdotV * sqrt(fma(NdotL, NdotL, fma(tl, tl, bl * bl)))
        return 0.5 / (ggxv + ggxl)

    def V_SmithGGXCorrelated(self, NdotL, NdotV, alpha):
        sqrt, fma = self.dr.sqrt, self.dr.fma
        a2 = alpha * alpha
        ggxv = NdotL * sqrt(fma(NdotV * NdotV, 1.0 - a2, a2))
        ggxl = NdotV * sqrt(fma(NdotL * NdotL, 1.0 - a2, a2))
        return 0.5 / (ggxv + ggxl)

    def F_Schlick(self, f0, w):
        return self.dr.fma(1.0 - f0, w, f0)

    def D_Charlie(self, hxy2, hn2, alpha):
        inv_r = 1.0 / alpha
        log_sin2 = -self.log1p(hn2 / hxy2)
        return (2.0 + inv_r) * self.dr.exp(0.5 * inv_r * log_sin2) * (0.5 / math.pi)

    def V_Charlie(self, NdotL, NdotV, alpha):
        dr, mix, fma = self.dr, self.mix, self.dr.fma
        t = (1.0 - alpha) * (1.0 - alpha)
        a = mix(21.5473, 25.3245, t)
        b = mix(3.82987, 3.32435, t)
        c = mix(0.19823, 0.16801, t)
        d = mix(-1.97760, -1.27393, t)
        e = mix(-4.32054, -4.85967, t)
        l_half = fma(0.5, d, a / fma(b, dr.exp2(-c), 1.0)) + e

        def lam(cos_theta):
            low = cos_theta < 0.5
            x = dr.select(low, cos_theta, 1.0 - cos_theta)
            l = fma(d, x, a / fma(b, dr.exp2(c * dr.log2(x)), 1.0)) + e
            return dr.exp(dr.select(low, l, fma(2.0, l_half, -l)))

        return 1.0 / ((1.0 + lam(NdotV) + lam(NdotL)) * (4.0 * NdotV * NdotL))

    # --- kernels/brdf/sheen_albedo.h ------------------------------------------------------------
    def sheen_albedo_row(self, r):
        dr, Int32 = self.dr, self.t.Int32
        n = self.e_size
        y = dr.sqrt(dr.clip(r, 0.0, 1.0)) * float(n - 1)
        y0 = dr.minimum(Int32(y), n - 2)
        return y0 * n, y - self.Float(y0)

    def sheen_albedo(self, row, mu):
        dr, Int32, Float = self.dr, self.t.Int32, self.Float
        n = self.e_size
        x = dr.sqrt(dr.clip(mu, 0.0, 1.0)) * float(n - 1)
        x0 = dr.minimum(Int32(x), n - 2)
        fx = x - Float(x0)
        i00 = self.t.UInt32(row[0] + x0)
        t00, t01 = dr.gather(Float, self.sheen_e, i00), dr.gather(Float, self.sheen_e, i00 + 1)
        t10, t11 = dr.gather(Float, self.sheen_e, i00 + n), dr.gather(Float, self.sheen_e, i00 + n + 1)
        return self.mix(self.mix(t00, t01, fx), self.mix(t10, t11, fx), row[1])

    # --- the lobes and the layering (lobes.h, profiles/spec.h, material.h) -------------------
    def specular(self, m, g, anisotropy):
        L, V, h = g["L"], g["V"], g["h"]
        if anisotropy:
            c, s = m["aniso_cos"], m["aniso_sin"]
            fma = self.dr.fma
            ht, hb = fma(h[0], c, h[1] * s), fma(h[1], c, -(h[0] * s))
            TdotV, BdotV = fma(V[0], c, V[1] * s), fma(V[1], c, -(V[0] * s))
            TdotL, BdotL = fma(L[0], c, L[1] * s), fma(L[1], c, -(L[0] * s))
            spec = (self.D_GGX_Anisotropic(ht, hb, h[2], g["h2"], m["alpha_t"], m["alpha"]) *
                    self.V_GGX_Anisotropic(g["NdotL"], g["NdotV"], TdotV, BdotV, TdotL, BdotL, m["alpha_t"], m["alpha"]))
        else:
            spec = self.D_GGX(g["hxy2"], g["hn2"], m["alpha"]) * self.V_SmithGGXCorrelated(g["NdotL"], g["NdotV"], m["alpha"])
        F = self.F_Schlick(0.04, g["w"])
        ks = (1.0 - m["metallic"]) * F
        return [self.dr.fma(m["metallic"], self.F_Schlick(m[k], g["w"]), ks) for k in ("base_r", "base_g", "base_b")], spec

    def diffuse(self, m, g):
        F = self.F_Schlick(0.04, g["w"])
        return [m["base_r"], m["base_g"], m["base_b"]], (1.0 - m["metallic"]) * (1.0 - F) * INV_PI

    def evaluate(self, lobe, features, m, L, V):
        """f(L, V) in 1/sr without the cosine, as brdf_material; m: field name -> Float lanes."""
        dr, Float = self.dr, self.Float
        g = self.geometry(L, V)
        result = [Float(0.0)] * 3
        add = lambda below, colour, weight: [dr.fma(c, weight, b) for b, c in zip(below, colour)]
        if lobe in ("all", "diffuse", "specular"):
            base = [Float(0.0)] * 3
            if lobe != "specular":
                base = add(base, *self.diffuse(m, g))
            if lobe != "diffuse":
                base = add(base, *self.specular(m, g, features["anisotropy"]))
            if features["sheen"]:  # min albedo scaling, the default
                row = self.sheen_albedo_row(m["sheen_roughness"])
                s_view = dr.fma(-m["sheen_max"], self.sheen_albedo(row, g["NdotV"]), 1.0)
                s_light = dr.fma(-m["sheen_max"], self.sheen_albedo(row, g["NdotL"]), 1.0)
                scale = dr.minimum(s_view, s_light)
                base = [b * scale for b in base]
            result = base
        if features["sheen"] and lobe in ("all", "sheen"):
            dv = self.D_Charlie(g["hxy2"], g["hn2"], m["sheen_alpha"]) * self.V_Charlie(g["NdotL"], g["NdotV"], m["sheen_alpha"])
            result = add(result, [m["sheen_r"], m["sheen_g"], m["sheen_b"]], dv)
        if features["clearcoat"]:
            coat = m["clearcoat"] * self.F_Schlick(0.04, self.pow5(1.0 - V[2]))
            result = [Float(0.0)] * 3 if lobe == "clearcoat" else [r * (1.0 - coat) for r in result]
            if lobe in ("all", "clearcoat"):
                # In batch evaluation the clearcoat normal is N: the same half vector.
                h = g["h"]
                alpha = m["clearcoat_alpha"]
                cc = self.D_GGX(dr.fma(h[0], h[0], h[1] * h[1]), h[2] * h[2], alpha) * \
                    self.V_SmithGGXCorrelated(g["NdotL"], g["NdotV"], alpha)
                result = [r + coat * cc for r in result]
        valid = (L[2] > 0.0) & (V[2] > 0.0)
        return [dr.select(valid, r, 0.0) for r in result]


class Side:
    """One workload on the device: inputs resident, materials gathered by index (K > 1) or read
    once for all lanes (K = 1, as brdfcl's one-material program does)."""

    def __init__(self, peer, lobe, materials, planes, index, freeze=True, features=None):
        dr, t = peer.dr, peer.t
        self.peer, self.dr, self.lobe = peer, dr, lobe
        packed, self.features = pack(materials)
        if features is not None:
            self.features = features
        Float = peer.Float
        self.L = [Float(planes[i]) for i in range(3)]
        self.V = [Float(planes[3 + i]) for i in range(3)]
        self.k = len(materials)
        self.table = {k: Float(v) for k, v in packed.items()}
        self.index = t.UInt32(np.ascontiguousarray(index, dtype=np.uint32))
        self.sheen_e = peer.sheen_e
        dr.eval(self.L, self.V, self.index, self.table)
        dr.sync_thread()

        def body(L, V, index, table, sheen_e):
            peer.sheen_e = sheen_e  # an input of the frozen function, as every array it reads
            if self.k == 1:
                m = table  # size-1 arrays: one load, broadcast over the lanes
            else:
                m = {k: dr.gather(Float, v, index) for k, v in table.items()}
            return peer.evaluate(self.lobe, self.features, m, L, V)

        # A frozen function replays the recorded kernel without tracing again: the kernel alone
        # is timed, as brdfcl's side times its kernel alone.
        self.fn = dr.freeze(body) if freeze else body

    def run(self):
        f = self.fn(self.L, self.V, self.index, self.table, self.sheen_e)
        self.dr.eval(f)
        self.dr.sync_thread()
        return f

    def median_seconds(self, runs):
        return median_seconds(self.run, runs)

    def kernel_seconds(self, runs):
        """CUDA: the kernels' own time from Dr.Jit's history (launch to completion on the device)."""
        dr = self.dr
        dr.set_flag(dr.JitFlag.KernelHistory, True)
        t = []
        for _ in range(runs):
            dr.kernel_history_clear()
            t0 = time.perf_counter()
            self.run()
            wall = time.perf_counter() - t0
            hist = [h for h in dr.kernel_history() if h.get("type") == dr.KernelType.JIT]
            kernel = sum(h.get("execution_time", 0.0) for h in hist) * 1e-3  # ms in the history
            t.append(kernel if kernel > 0 else wall)  # a history without times: the wall clock
        dr.set_flag(dr.JitFlag.KernelHistory, False)
        return statistics.median(t)


def brdfcl_bench(brdfcl, lobe, materials, pairs_path, indices_path, runs):
    cmd = [brdfcl, "bench", "--lobe", lobe, "--materials", str(materials), "--pairs", pairs_path,
           "--indices", indices_path, "--runs", str(runs), "--json"] + BRDFCL_DEVICE
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)} failed: {r.stderr.strip() or r.returncode}")
    return json.loads(r.stdout)


def sheen_e_table(brdfcl, tmp):
    # The E table from brdfcl itself: the one its kernel reads (`brdfcl bench --sheen-e-out`).
    pairs, indices = write_inputs(tmp, "e", make_pairs(16, 0), np.zeros(16, np.uint32))
    out = os.path.join(tmp, "sheen_e.f32")
    cmd = [brdfcl, "bench", "--lobe", "all", "--materials", "1", "--pairs", pairs, "--runs", "1",
           "--sheen-e-out", out, "--json"] + BRDFCL_DEVICE
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)} failed: {r.stderr.strip() or r.returncode}")
    e = np.fromfile(out, dtype="<f4")
    size = int(round(math.sqrt(e.size)))
    if size * size != e.size or size < 2:
        fail(f"brdfcl bench --sheen-e-out wrote {e.size} floats; expected a square table")
    return e.reshape(size, size)


def gltf_materials(materials):
    out = []
    for m in materials:
        out.append({"pbrMetallicRoughness": {"baseColorFactor": list(m["base_color"]) + [1.0],
                                             "metallicFactor": m["metallic"], "roughnessFactor": m["roughness"]},
                    "extensions": {
                        "KHR_materials_sheen": {"sheenColorFactor": m["sheen_color"],
                                                "sheenRoughnessFactor": m["sheen_roughness"]},
                        "KHR_materials_clearcoat": {"clearcoatFactor": m["clearcoat"],
                                                    "clearcoatRoughnessFactor": m["clearcoat_roughness"]},
                        "KHR_materials_anisotropy": {"anisotropyStrength": m["anisotropy_strength"],
                                                     "anisotropyRotation": m["anisotropy_rotation"]}}})
    return {"asset": {"version": "2.0"},
            "extensionsUsed": ["KHR_materials_sheen", "KHR_materials_clearcoat", "KHR_materials_anisotropy"],
            "materials": out}


def write_inputs(tmp, name, planes, index):
    pairs, indices = os.path.join(tmp, f"{name}.f32"), os.path.join(tmp, f"{name}.u32")
    planes.astype(np.float32).tofile(pairs)
    index.astype("<u4").tofile(indices)
    return pairs, indices


def check(a, dr, mod, sheen_e, tmp):
    """`brdfcl eval` (NPY in, NPY out) against the peer on the same pairs and material indices.
    Errors are relative to the f that brdfcl returns, floored at --abs-floor; where the sheen's albedo
    scaling multiplies the base, to the unscaled base as tests/unit/test_accuracy.cpp takes it (the
    table's error is one in the factor). The same maths in float64 on the same inputs referees
    pairs where the two disagree by more than the tolerance: where brdfcl's own float32 result is
    that far from it too, the difference is float32 rounding of an ill-conditioned value (a sharp
    GGX peak, 1 - sheenColor E near 0), not different maths."""
    n = a.check_pairs
    planes = check_pairs(n, a.seed + 100)
    peer, referee = Peer(dr, mod, sheen_e), Peer(dr, mod, sheen_e, double=True)
    worst_all, unexplained_all, own_all, peer_all = 0.0, 0, 0.0, 0.0
    print(f"check: {n} pairs, |Dr.Jit - brdfcl eval| / max(|f|, {a.abs_floor:g}), "
          f"per workload and lobe (target <= {a.tolerance:g})")
    # The layered workload's materials carry every layer: each lobe by itself; the sheen and
    # specular workloads compile other feature sets (no anisotropy, no sheen), checked as timed.
    # One material too: the peer then reads it once for all lanes instead of gathering.
    k = a.materials_max
    cases = [("all", lobe, k) for lobe in LOBES] + [("sheen", "sheen", k), ("specular", "specular", k), ("all", "all", 1)]
    for workload, lobe, k in cases:
        index = np.random.default_rng(a.seed + 2).integers(0, k, n).astype(np.uint32)
        pairs, indices = write_inputs(tmp, "check", planes, index)
        samples = os.path.join(tmp, "samples.npy")
        np.save(samples, np.concatenate([index[None, :].astype(np.float32), planes]).T.copy())
        mats = brdfcl_bench(a.brdfcl, workload, k, pairs, indices, 1)["material_params"]
        gltf = os.path.join(tmp, f"{workload}.gltf")
        with open(gltf, "w") as f:
            json.dump(gltf_materials(mats), f)
        out = os.path.join(tmp, "out.npy")
        r = subprocess.run([a.brdfcl, "eval", "--materials", gltf, "--samples", samples, "--out", out, "--lobe", lobe]
                           + BRDFCL_DEVICE, capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"brdfcl eval --lobe {lobe} failed: {r.stderr.strip()}")
        ours = np.load(out).astype(np.float64)
        run = lambda p, features=None: np.stack([np.array(c, dtype=np.float64) for c in
                                                 Side(p, lobe, mats, planes, index, freeze=False, features=features).run()], axis=1)
        theirs, exact = run(peer), run(referee)
        scale = np.abs(ours)
        features = pack(mats)[1]
        if features["sheen"] and lobe in ("all", "diffuse", "specular"):
            scale = np.maximum(scale, np.abs(run(referee, dict(features, sheen=False))))
        scale = np.maximum(scale, a.abs_floor)
        err = np.abs(theirs - ours) / scale
        own = np.abs(ours - exact) / scale  # brdfcl's float32 rounding, against the maths in float64
        excess = err > a.tolerance
        unexplained = excess & (own < 0.5 * a.tolerance)
        i, c = np.unravel_index(int(np.argmax(err)), err.shape)
        worst = float(err[i, c])
        worst_all = max(worst_all, worst)
        unexplained_all += int(unexplained.sum())
        own_all = max(own_all, float(own.max()))
        peer_all = max(peer_all, float((np.abs(theirs - exact) / scale).max()))
        print(f"  {workload:<9}{lobe:<10}K {k:<4} worst {worst:.2e} at pair {i} ({'rgb'[c]}): material {index[i]}, "
              f"L ({planes[0, i]:.9g}, {planes[1, i]:.9g}, {planes[2, i]:.9g}), "
              f"V ({planes[3, i]:.9g}, {planes[4, i]:.9g}, {planes[5, i]:.9g}); "
              f"brdfcl {ours[i, c]:.9g}, Dr.Jit {theirs[i, c]:.9g}, float64 {exact[i, c]:.9g}", flush=True)
        if excess.any():
            print(f"    {int(excess.sum())} of {err.size} values above {a.tolerance:g}; at all of them but "
                  f"{int(unexplained.sum())} brdfcl's own float32 result is as far from the float64 maths "
                  f"(>= {0.5 * a.tolerance:g}; its worst there {float(own[excess].max()):.1e})")
    print(f"  against the same maths in float64: brdfcl worst {own_all:.1e}, Dr.Jit worst {peer_all:.1e}")
    if unexplained_all == 0:
        verdict = (f"met" if worst_all <= a.tolerance else
                   f"met where the maths is well conditioned (every larger difference is brdfcl's own float32 rounding)")
    else:
        verdict = f"NOT met ({unexplained_all} values differ more than float32 rounding explains)"
    print(f"  worst relative difference {worst_all:.2e}; target <= {a.tolerance:g}: {verdict}")
    return worst_all, unexplained_all


def asm_counts(lines):
    # The figures the kernels are compared by: divisions, square roots, stack traffic (spills and
    # their reloads), non-temporal stores, per loop body of 16 lanes (the whole kernel, in fact).
    text = [l.split("\t", 1) for l in lines]
    ops = [(t[0].split()[-1] if t else "", t[1] if len(t) > 1 else "") for t in text]
    stack = lambda args: "[rsp" in args or "[rbp" in args
    return {"instructions": len(ops),
            "div": sum(o.startswith("vdiv") for o, _ in ops),
            "sqrt": sum(o.startswith("vsqrt") for o, _ in ops),
            "rsqrt": sum(o.startswith("vrsqrt") for o, _ in ops),
            "gathers": sum(o.startswith("vgather") or o.startswith("vpgather") for o, _ in ops),
            "stack_stores": sum(o.startswith("vmov") and stack(args.split(",")[0]) for o, args in ops),
            "stack_loads": sum(stack(args.split(",", 1)[1]) for o, args in ops if "," in args),
            "nontemporal_stores": sum(o.startswith("vmovnt") and "[" in args.split(",")[0] for o, args in ops)}


def print_ir(a, dr, mod, sheen_e, tmp):
    """Dr.Jit's kernels for each timed workload into a folder: the LLVM IR and the machine code
    that Dr.Jit's LLVM backend made of it (its own disassembly, logged at LogLevel.Trace on a
    kernel-cache miss: the caller points HOME at an empty folder) on the CPU, the PTX on CUDA, for
    comparison with brdfcl's program binaries."""
    n = 1 << 16
    planes = make_pairs(n, a.seed)
    peer = Peer(dr, mod, sheen_e)
    os.makedirs(a.print_ir, exist_ok=True)
    summary = []
    for lobe in a.lobes:
        for k in a.materials:
            index = np.random.default_rng(a.seed).integers(0, k, n).astype(np.uint32)
            pairs, indices = write_inputs(tmp, "ir", planes, index)
            mats = brdfcl_bench(a.brdfcl, lobe, k, pairs, indices, 1)["material_params"]
            side = Side(peer, lobe, mats, planes, index, freeze=False)
            dr.set_flag(dr.JitFlag.KernelHistory, True)
            dr.kernel_history_clear()
            trace = os.path.join(tmp, "trace.txt")
            # Dr.Jit's log reaches stdout or stderr depending on how it was started: catch both.
            saved = [os.dup(1), os.dup(2)]
            with open(trace, "w") as f:
                sys.stdout.flush()
                sys.stderr.flush()
                os.dup2(f.fileno(), 1)
                os.dup2(f.fileno(), 2)
                try:
                    dr.set_log_level(dr.LogLevel.Trace)
                    side.run()
                finally:
                    dr.set_log_level(dr.LogLevel.Warn)
                    sys.stdout.flush()
                    sys.stderr.flush()
                    for fd, old in zip((1, 2), saved):
                        os.dup2(old, fd)
                        os.close(old)
            hist = [h for h in dr.kernel_history() if h.get("type") == dr.KernelType.JIT]
            dr.set_flag(dr.JitFlag.KernelHistory, False)
            base = os.path.join(a.print_ir, f"drjit-{a.backend}-{lobe}-k{k}")
            ir = "\n".join(h["ir"].getvalue() if hasattr(h["ir"], "getvalue") else str(h["ir"]) for h in hist)
            with open(base + (".ptx" if a.backend == "cuda" else ".ll"), "w") as f:
                f.write(ir)
            row = {"lobe": lobe, "materials": k, "kernels": len(hist),
                   "operations": sum(h.get("operation_count", 0) for h in hist)}
            if a.backend == "llvm":
                with open(trace) as f:
                    asm = [l.split("jit_llvm_disasm(): ", 1)[1].rstrip("\n") for l in f if "jit_llvm_disasm(): " in l]
                asm = [l for l in asm if not l.startswith("=")]
                with open(base + ".s", "w") as f:
                    f.write("\n".join(asm) + "\n")
                if not asm:
                    print(f"  {base}.s: empty (the kernel came from Dr.Jit's cache; run with HOME at an empty folder)")
                row.update(asm_counts(asm))
            summary.append(row)
            print(f"  {base}.*: " + ", ".join(f"{k2} {v}" for k2, v in row.items() if k2 not in ("lobe", "materials")))
    with open(os.path.join(a.print_ir, f"drjit-{a.backend}-summary.json"), "w") as f:
        json.dump(summary, f, indent=2)


def main():
    ap = argparse.ArgumentParser(description="brdfcl against the same maths in Dr.Jit")
    ap.add_argument("--brdfcl", default="build/bin/brdfcl")
    ap.add_argument("--backend", choices=["llvm", "cuda"], default="llvm")
    ap.add_argument("--pairs", type=int, help="pairs per timed run (default 4194304 on llvm, 16777216 on cuda)")
    ap.add_argument("--device", help="brdfcl's OpenCL device, index or name substring "
                                     "(default $BRDFCL_DEVICE, else 'NVIDIA' on cuda and brdfcl's default on llvm)")
    ap.add_argument("--lobes", default="all,sheen,specular", help="workloads to time, comma-separated")
    ap.add_argument("--materials", default="1,256", help="material counts to time, comma-separated")
    ap.add_argument("--runs", type=int, default=7, help="timed runs per side per round; median reported")
    ap.add_argument("--rounds", type=int, default=5, help="alternating rounds (brdfcl, Dr.Jit, brdfcl, ...)")
    ap.add_argument("--threads", type=int, default=0, help="Dr.Jit LLVM threads (default: as many as brdfcl's PoCL)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", help="also write the figures to this file")
    ap.add_argument("--mitsuba-json", help="the Mitsuba peer's JSON, whose ratios are printed beside these")
    ap.add_argument("--check", action="store_true", help="first compare every lobe with `brdfcl eval`")
    ap.add_argument("--check-only", action="store_true", help="the comparison alone, no timing")
    ap.add_argument("--check-pairs", type=int, default=1 << 16)
    ap.add_argument("--materials-max", type=int, default=256, help="materials in the check")
    ap.add_argument("--tolerance", type=float, default=1e-5)
    ap.add_argument("--abs-floor", type=float, default=1e-6, help="relative errors are taken against max(|f|, this)")
    ap.add_argument("--print-ir", metavar="DIR",
                    help="write Dr.Jit's kernels (LLVM IR and machine code, or PTX) of the timed workloads to DIR and stop")
    ap.add_argument("--no-freeze", action="store_true", help="time tracing too (dr.freeze off)")
    a = ap.parse_args()
    a.lobes = a.lobes.split(",")
    if a.pairs is None:
        a.pairs = 1 << 24 if a.backend == "cuda" else 1 << 22
    if a.device is None and a.backend == "cuda" and not os.environ.get("BRDFCL_DEVICE"):
        a.device = "NVIDIA"
    global BRDFCL_DEVICE
    BRDFCL_DEVICE = ["--device", a.device] if a.device else []
    a.materials = [int(x) for x in a.materials.split(",")]
    for lobe in a.lobes:
        if lobe not in ("all", "sheen", "specular", "clearcoat"):
            fail(f"unknown --lobes value '{lobe}'; use all, sheen, specular or clearcoat")

    if a.print_ir and a.backend == "llvm" and not os.environ.get("DRJIT_PEER_KEEP_HOME"):
        # Dr.Jit logs a kernel's machine code only when it compiles it: an empty kernel cache.
        os.environ["HOME"] = tempfile.mkdtemp(prefix="drjit-home-")
    try:
        import drjit as dr
    except Exception as e:
        fail(f"cannot import drjit ({type(e).__name__}: {e}); run through bench/peers/run-drjit-peer")
    backend = dr.JitBackend.CUDA if a.backend == "cuda" else dr.JitBackend.LLVM
    if not dr.has_backend(backend):
        what = "no CUDA device or driver" if a.backend == "cuda" else \
            "no usable libLLVM; set DRJIT_LIBLLVM_PATH to libLLVM-19.so (apt-get install libllvm19)"
        print(f"drjit_peer: Dr.Jit's {a.backend} backend is unavailable here ({what})", file=sys.stderr)
        sys.exit(3)
    mod = __import__(f"drjit.{a.backend}", fromlist=["Float"])
    if a.backend == "llvm":
        dr.set_thread_count(a.threads or os.cpu_count())
    if not os.access(a.brdfcl, os.X_OK):
        fail(f"{a.brdfcl} is not built; run cmake --build --preset release --target brdfcl")

    with tempfile.TemporaryDirectory() as tmp:
        sheen_e = sheen_e_table(a.brdfcl, tmp)
        if a.print_ir:
            print_ir(a, dr, mod, sheen_e, tmp)
            return
        worst = None
        if a.check or a.check_only:
            worst, unexplained = check(a, dr, mod, sheen_e, tmp)
            if a.check_only:
                sys.exit(0 if unexplained == 0 else 1)
        results = timing(a, dr, mod, sheen_e, tmp)
    mitsuba = {}
    if a.mitsuba_json and os.path.exists(a.mitsuba_json):
        with open(a.mitsuba_json) as f:
            for row in json.load(f).get("results", []):
                if row["pairs"] == a.pairs:
                    mitsuba[row["lobe"]] = row["ratio_median"]
    if mitsuba:
        print("  beside the Mitsuba peer (brdfcl / Mitsuba, one material, same pair count; not the same maths):")
        for lobe, ratio in mitsuba.items():
            ours = [r["ratio_median"] for r in results if r["lobe"] == lobe and r["materials"] == 1]
            print(f"    {lobe:<10} / Dr.Jit {ours[0]:.2f}x   / Mitsuba {ratio:.2f}x" if ours else
                  f"    {lobe:<10} / Mitsuba {ratio:.2f}x")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"drjit": dr.__version__, "backend": a.backend,
                       "threads": dr.thread_count() if a.backend == "llvm" else None,
                       "pairs": a.pairs, "runs": a.runs, "rounds": a.rounds, "frozen": not a.no_freeze,
                       "check_worst_relative_difference": worst, "check_tolerance": a.tolerance,
                       "mitsuba_ratios": mitsuba, "results": results}, f, indent=2)


def timing(a, dr, mod, sheen_e, tmp):
    n = a.pairs
    planes = make_pairs(n, a.seed)
    peer = Peer(dr, mod, sheen_e)
    cuda = a.backend == "cuda"
    results = []
    threads = f", {dr.thread_count()} threads" if not cuda else ""
    print(f"brdfcl vs Dr.Jit {dr.__version__} ({a.backend}{threads}{', frozen' if not a.no_freeze else ', traced'}), "
          f"{n} pairs, median of {a.runs} runs, {a.rounds} alternating rounds")
    print(f"  {'lobe':<10}{'materials':>10}{'brdfcl':>10}{'Dr.Jit':>10}  brdfcl/Dr.Jit (rounds)")
    for k in a.materials:
        # One index draw per K, shared by both sides and every lobe.
        index = np.random.default_rng(a.seed + k).integers(0, k, n).astype(np.uint32)
        pairs, indices = write_inputs(tmp, f"pairs-{k}", planes, index)
        for lobe in a.lobes:
            first = brdfcl_bench(a.brdfcl, lobe, k, pairs, indices, a.runs)
            side = Side(peer, lobe, first["material_params"], planes, index, freeze=not a.no_freeze)
            side.run()  # traces and compiles; the frozen function records here
            side.run()
            # On a GPU, brdfcl's launch (profiling event) against Dr.Jit's kernel time; on the CPU
            # both sides' wall time of the evaluation with inputs and results in memory.
            key = "launch_samples_per_second" if cuda else "samples_per_second"
            ours, theirs = [], []
            for _ in range(a.rounds):
                ours.append(brdfcl_bench(a.brdfcl, lobe, k, pairs, indices, a.runs)[key])
                theirs.append(n / (side.kernel_seconds(a.runs) if cuda else side.median_seconds(a.runs)))
            ratios = [o / t for o, t in zip(ours, theirs)]
            row = {"lobe": lobe, "materials": k, "pairs": n, "device": first["device"],
                   "brdfcl_samples_per_second": statistics.median(ours),
                   "drjit_samples_per_second": statistics.median(theirs),
                   "ratio_median": statistics.median(ratios), "ratios": ratios}
            results.append(row)
            print(f"  {lobe:<10}{k:>10}{row['brdfcl_samples_per_second'] / 1e6:>10.1f}"
                  f"{row['drjit_samples_per_second'] / 1e6:>10.1f}  {row['ratio_median']:.2f}x "
                  f"({', '.join(f'{r:.2f}' for r in ratios)})", flush=True)
            del side
    what = "launch (profiling event) vs kernel time" if cuda else "OpenCL kernel vs Dr.Jit evaluation, inputs resident"
    print(f"  (Msamples/s; {what})")
    return results


if __name__ == "__main__":
    main()
