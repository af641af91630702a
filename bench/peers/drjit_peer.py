#!/usr/bin/env python3
# brdfcl's spec material (every lobe, its clamps and its sheen E table) written in Dr.Jit, gathering
# K materials by index, on the LLVM or CUDA backend: checked against `brdfcl eval`, and timed side by
# side with `brdfcl bench --pairs --indices` on the same pairs, indices and materials.
# The maths is in drjit_maths.py, the check in drjit_check.py, the timing in drjit_timing.py, the
# kernel dump in drjit_ir.py and the runs of brdfcl itself in drjit_brdfcl.py.
import argparse
import json
import os
import sys
import tempfile

from drjit_brdfcl import BRDFCL_DEVICE, fail, sheen_e_table
from drjit_check import check
from drjit_ir import print_ir
from drjit_timing import timing


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
    BRDFCL_DEVICE[:] = ["--device", a.device] if a.device else []
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


if __name__ == "__main__":
    main()
