# The Dr.Jit peer's kernel dump (bench/peers/drjit_peer.py --print-ir): the LLVM IR and machine code
# or the PTX of each timed workload, with the machine-code figures the kernels are compared by.
import json
import os
import sys

import numpy as np

from drjit_brdfcl import brdfcl_bench, write_inputs
from drjit_maths import Peer
from drjit_timing import Side
from peer_pairs import make_pairs


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
