#!/usr/bin/env python3
# Mitsuba 3 (llvm_ad_rgb, 2 threads) as a throughput peer of `brdfcl bench`: both evaluate the
# same direction pairs (--op sample: both sample directions at the same views), interleaved round
# by round in one run, and the ratios are printed.
# Run through `make bench-peers` (bench/peers/run-mitsuba-peer sets up the venv and libLLVM).
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

from peer_pairs import make_pairs, median_seconds


def fail(message):
    print(f"mitsuba_peer: {message}", file=sys.stderr)
    sys.exit(2)


def run_brdfcl(brdfcl, lobe, pairs_path, runs, op="eval"):
    cmd = [brdfcl, "bench", "--op", op, "--lobe", lobe, "--materials", "1", "--pairs", pairs_path, "--runs", str(runs),
           "--json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def schlick_f0(m):
    return [0.04 + (c - 0.04) * m["metallic"] for c in m["base_color"]]


def mitsuba_bsdf(mi, lobe, m):
    alpha = m["roughness"] ** 2
    s = m["anisotropy_strength"]
    if lobe == "specular":
        # glTF anisotropy stretches the tangent roughness towards 1: alpha_t = mix(alpha, 1, s^2).
        # The conductor's normal-incidence reflectance is made brdfcl's F0 (eta = 1, k from F0);
        # Mitsuba still evaluates the full complex Fresnel, brdfcl Schlick's.
        f0 = [min(c, 0.999) for c in schlick_f0(m)]
        k = [2.0 * (c / (1.0 - c)) ** 0.5 for c in f0]
        return mi.load_dict({
            "type": "roughconductor",
            "distribution": "ggx",
            "alpha_u": alpha + (1.0 - alpha) * s * s,
            "alpha_v": alpha,
            "eta": {"type": "rgb", "value": [1.0, 1.0, 1.0]},
            "k": {"type": "rgb", "value": k},
        })
    # Disney's parameters, not glTF's: the closest knobs (see docs/performance.md for what differs).
    return mi.load_dict({
        "type": "principled",
        "base_color": {"type": "rgb", "value": m["base_color"]},
        "metallic": m["metallic"],
        "roughness": m["roughness"],
        "anisotropic": s,
        "sheen": max(m["sheen_color"]),
        "sheen_tint": 0.0,
        "clearcoat": m["clearcoat"],
        "clearcoat_gloss": 1.0 - m["clearcoat_roughness"],
        "specular": 0.5,  # F0 = 0.08 * specular = 0.04, glTF's dielectric F0
        "spec_trans": 0.0,
    })


def specular_agreement(mi, dr, brdfcl, m, planes, tmp):
    # Not a timing: how close the two specular lobes are on the same pairs, f * N.L against
    # Mitsuba's f (which carries the cosine), with Mitsuba's frame turned to brdfcl's rotated
    # tangent. Left apart: Schlick against conductor Fresnel, and the two Smith G's.
    n = planes.shape[1]
    material = {"pbrMetallicRoughness": {"baseColorFactor": m["base_color"] + [1.0], "metallicFactor": m["metallic"],
                                         "roughnessFactor": m["roughness"]},
                "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": m["anisotropy_strength"],
                                                            "anisotropyRotation": m["anisotropy_rotation"]}}}
    gltf = os.path.join(tmp, "material.gltf")
    with open(gltf, "w") as f:
        json.dump({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_anisotropy"], "materials": [material]}, f)
    samples = os.path.join(tmp, "samples.npy")
    np.save(samples, np.concatenate([np.zeros((1, n), np.float32), planes]).T.copy())
    out = os.path.join(tmp, "out.npy")
    subprocess.run([brdfcl, "eval", "--materials", gltf, "--samples", samples, "--out", out, "--lobe", "specular"],
                   check=True, capture_output=True)
    ours = np.load(out) * planes[2][:, None]
    c, s = np.cos(m["anisotropy_rotation"]), np.sin(m["anisotropy_rotation"])
    turned = np.stack([c * planes[0] + s * planes[1], -s * planes[0] + c * planes[1], planes[2],
                       c * planes[3] + s * planes[4], -s * planes[3] + c * planes[4], planes[5]]).astype(np.float32)
    theirs = np.array(MitsubaSide(mi, dr, mitsuba_bsdf(mi, "specular", m), turned).run()).T
    # Weighted by the value: most pairs of a sharp lobe are near 0 in both and would say nothing.
    significant = theirs > 0.01 * theirs.max()
    rel = np.abs(ours - theirs)[significant] / theirs[significant]
    return float(np.abs(ours - theirs).sum() / np.abs(theirs).sum()), float(np.median(rel))


class MitsubaSide:
    def __init__(self, mi, dr, bsdf, planes):
        self.mi, self.dr, self.bsdf = mi, dr, bsdf
        n = planes.shape[1]
        self.ctx = mi.BSDFContext()
        si = dr.zeros(mi.SurfaceInteraction3f, n)
        si.wi = mi.Vector3f(planes[3], planes[4], planes[5])  # V: brdfcl's view direction
        si.sh_frame = mi.Frame3f(mi.Normal3f(0, 0, 1))
        si.n = mi.Normal3f(0, 0, 1)
        self.si = si
        self.wo = mi.Vector3f(planes[0], planes[1], planes[2])  # L
        dr.eval(self.si, self.wo)  # the inputs are in memory before the clock, as brdfcl's are
        dr.sync_thread()

    def run(self):
        # Tracing and the kernel-cache lookup are part of every Mitsuba evaluation, so they are
        # timed; the first call (the LLVM compilation) is the warm-up.
        f = self.bsdf.eval(self.ctx, self.si, self.wo)
        self.dr.eval(f)
        self.dr.sync_thread()
        return f

    def median_seconds(self, runs):
        return median_seconds(self.run, runs)


class MitsubaSampleSide(MitsubaSide):
    """bsdf.sample at the pairs' views (their V planes), with uniform numbers drawn once: the
    sampled direction, its pdf and the weight f cos / pdf, as `brdfcl bench --op sample` computes."""

    def __init__(self, mi, dr, bsdf, planes, seed):
        super().__init__(mi, dr, bsdf, planes)
        rng = np.random.default_rng(seed)
        u = rng.random((3, planes.shape[1]), dtype=np.float32)
        self.s1 = mi.Float(u[2])
        self.s2 = mi.Point2f(u[0], u[1])
        dr.eval(self.s1, self.s2)
        dr.sync_thread()

    def run(self):
        bs, weight = self.bsdf.sample(self.ctx, self.si, self.s1, self.s2)
        self.dr.eval(bs.wo, bs.pdf, weight)
        self.dr.sync_thread()
        return bs, weight


def main():
    ap = argparse.ArgumentParser(description="brdfcl against Mitsuba 3 on the same direction pairs")
    ap.add_argument("--brdfcl", default="build/bin/brdfcl")
    ap.add_argument("--sizes", default="262144,4194304", help="pairs per run, comma-separated")
    ap.add_argument("--runs", type=int, default=7, help="timed runs per side per round; median reported")
    ap.add_argument("--rounds", type=int, default=5, help="interleaved rounds (brdfcl, Mitsuba, brdfcl, ...)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", help="also write the figures to this file")
    ap.add_argument("--check", action="store_true", help="first compare the specular lobes' values on 65,536 pairs")
    ap.add_argument("--op", default="eval", choices=("eval", "sample"),
                    help="eval: f at given pairs (bsdf.eval); sample: directions, pdfs and weights (bsdf.sample)")
    a = ap.parse_args()

    try:
        import drjit as dr
        import mitsuba as mi
        mi.set_variant("llvm_ad_rgb")
    except Exception as e:  # a libLLVM Dr.Jit cannot use shows up here, whatever its type
        fail(f"cannot start Mitsuba's llvm_ad_rgb variant ({type(e).__name__}: no usable libLLVM?); "
             "set DRJIT_LIBLLVM_PATH to libLLVM-19.so (apt-get install libllvm19)")
    dr.set_thread_count(a.threads)
    if not os.access(a.brdfcl, os.X_OK):
        fail(f"{a.brdfcl} is not built; run cmake --build --preset release --target brdfcl")

    workloads = [("specular", "roughconductor (ggx, anisotropic, conductor Fresnel)"),
                 ("all", "principled (sheen, clearcoat, anisotropic)")]
    results = []
    print(f"brdfcl vs Mitsuba {mi.__version__} (llvm_ad_rgb, {dr.thread_count()} threads), {a.op}, one material, "
          f"median of {a.runs} runs, {a.rounds} interleaved rounds")
    with tempfile.TemporaryDirectory() as tmp:
        if a.check:
            planes = make_pairs(65536, a.seed)
            planes.tofile(os.path.join(tmp, "check.f32"))
            m = run_brdfcl(a.brdfcl, "specular", os.path.join(tmp, "check.f32"), 1)["material0"]
            total, med = specular_agreement(mi, dr, a.brdfcl, m, planes, tmp)
            print(f"  specular values, brdfcl f*N.L vs roughconductor: sum|difference|/sum|f| {total:.3f}, "
                  f"median relative difference where f > 1% of its peak {med:.3f}")
        print(f"  {'lobe':<10}{'Mitsuba bsdf':<54}{'pairs':>9}{'brdfcl':>10}{'Mitsuba':>10}  brdfcl/Mitsuba (rounds)")
        for n in [int(x) for x in a.sizes.split(",")]:
            planes = make_pairs(n, a.seed)
            path = os.path.join(tmp, f"pairs-{n}.f32")
            planes.tofile(path)
            for lobe, label in workloads:
                first = run_brdfcl(a.brdfcl, lobe, path, a.runs, a.op)
                bsdf = mitsuba_bsdf(mi, lobe, first["material0"])
                side = (MitsubaSampleSide(mi, dr, bsdf, planes, a.seed) if a.op == "sample"
                        else MitsubaSide(mi, dr, bsdf, planes))
                side.run()  # warm-up: traces and compiles the kernel
                side.run()
                ours, theirs = [], []
                for _ in range(a.rounds):
                    ours.append(run_brdfcl(a.brdfcl, lobe, path, a.runs, a.op)["samples_per_second"])
                    theirs.append(n / side.median_seconds(a.runs))
                ratios = [o / t for o, t in zip(ours, theirs)]
                row = {"op": a.op, "lobe": lobe, "mitsuba_bsdf": label, "pairs": n,
                       "brdfcl_samples_per_second": statistics.median(ours),
                       "mitsuba_samples_per_second": statistics.median(theirs),
                       "ratio_median": statistics.median(ratios), "ratios": ratios, "material": first["material0"]}
                results.append(row)
                print(f"  {lobe:<10}{label:<54}{n:>9}{row['brdfcl_samples_per_second'] / 1e6:>10.1f}"
                      f"{row['mitsuba_samples_per_second'] / 1e6:>10.1f}  {row['ratio_median']:.2f}x "
                      f"({', '.join(f'{r:.2f}' for r in ratios)})", flush=True)
                del side
    print(f"  (Msamples/s; brdfcl: OpenCL kernel only; Mitsuba: bsdf.{a.op} with dr.eval, inputs resident)")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"mitsuba": mi.__version__, "drjit": dr.__version__, "threads": dr.thread_count(),
                       "runs": a.runs, "rounds": a.rounds, "results": results}, f, indent=2)


if __name__ == "__main__":
    main()
