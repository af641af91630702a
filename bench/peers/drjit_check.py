# The Dr.Jit peer's check (bench/peers/drjit_peer.py): `brdfcl eval` against the peer on the same
# pairs and materials, with the same maths in float64 as referee.
import json
import os
import subprocess

import numpy as np

from drjit_brdfcl import BRDFCL_DEVICE, brdfcl_bench, fail, write_inputs
from drjit_maths import LOBES, Peer, pack
from drjit_timing import Side
from peer_pairs import make_pairs


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
