# brdfcl's spec material written in Dr.Jit (bench/peers/drjit_peer.py): the material packed as the
# host packs it, and every lobe, its clamps and its sheen E table lookup over one backend's arrays.
import math

import numpy as np

# kernels/common/material_layout.h and kernels/brdf/material.h
MIN_ALPHA = 1.0e-3
MIN_SHEEN_ALPHA = 1.0e-3
MIN_COS = 1.0e-4
INV_PI = 1.0 / math.pi
LOBES = ("all", "diffuse", "specular", "sheen", "clearcoat")


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
