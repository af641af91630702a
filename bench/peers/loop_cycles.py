#!/usr/bin/env python3
# The loop over samples of a compiled batch kernel, counted and timed statically: PoCL's eval_samples
# or another kernel (--kernel sample_rows; from a POCL_CACHE_DIR) or Dr.Jit's LLVM kernel (a .s of
# run-drjit-peer --print-ir). Prints its instruction counts and llvm-mca's cycles per iteration (16 lanes).
import argparse
import glob
import re
import subprocess
import sys
import tempfile


def pocl_loop(cache, kernel="eval_samples", variant="*"):
    """The work-item loop (the largest backward jump) of _pocl_kernel_<kernel>_workgroup, from the
    compiled variant (local size and grid, PoCL's directory name) that `variant` matches: PoCL keeps
    one a launch shape, and a small grid's differs from a large one's."""
    found = sorted(glob.glob(f"{cache}/*/*/{kernel}/{variant}/{kernel}.so"))
    found = [f for f in found if "/0-0-0/" not in f] or found  # 0-0-0: the generic, unspecialized build
    if not found:
        sys.exit(f"loop_cycles: no {kernel}.so matching {variant} under {cache}")
    if len(found) > 1:
        print(f"loop_cycles: {len(found)} variants; counting {found[0].split('/')[-2]} (choose with --variant)",
              file=sys.stderr)
    text = subprocess.run(["objdump", "-d", "--no-show-raw-insn", found[0]], capture_output=True, text=True,
                          check=True).stdout
    fn = text.split(f"<_pocl_kernel_{kernel}_workgroup>:")[1].split("\n\n")[0].split("\n")
    ins = []
    for line in fn:
        m = re.match(r"\s*([0-9a-f]+):\s+(\S+)\s*(.*)", line)
        if m:
            ins.append((int(m.group(1), 16), m.group(2), re.sub(r"#.*", "", m.group(3)).strip()))
    jumps = [(int(re.match(r"([0-9a-f]+)", a).group(1), 16), at) for at, op, a in ins
             if op.startswith("j") and re.match(r"[0-9a-f]+ ", a)]
    head, tail = max(((t, at) for t, at in jumps if t < at), key=lambda j: j[1] - j[0])
    body = [(op, a) for at, op, a in ins if head <= at <= tail]
    stack_store = lambda op, a: op.startswith("vmov") and re.search(r",\s*-?(0x[0-9a-f]+)?\(%r[sb]p", a)
    stack_load = lambda op, a: re.search(r"\(%r[sb]p[^,]*\),", a)
    return body, "att", stack_store, stack_load


def drjit_loop(path):
    """The loop (the largest backward jump) of Dr.Jit's disassembly, Intel syntax with relative targets."""
    ins = []
    for line in open(path):
        m = re.match(r"0x([0-9a-f]+)\s+(\S+)\s*(.*)", line.strip())
        if m:
            ins.append((int(m.group(1), 16), m.group(2), m.group(3).strip()))
    jumps = [(at + int(a), at) for at, op, a in ins if op.startswith("j") and re.fullmatch(r"-?[0-9]+", a)]
    head, tail = max(((t, at) for t, at in jumps if t < at), key=lambda j: j[1] - j[0])
    body = [(op, a) for at, op, a in ins if head <= at <= tail]
    stack = lambda s: "[rsp" in s or "[rbp" in s
    stack_store = lambda op, a: op.startswith("vmov") and stack(a.split(",")[0])
    stack_load = lambda op, a: "," in a and stack(a.split(",", 1)[1])
    return body, "intel", stack_store, stack_load


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("source", help="a POCL_CACHE_DIR holding eval_samples, or Dr.Jit's .s")
    ap.add_argument("--mcpu", default="icelake-server", help="llvm-mca's CPU model (LLVM 14 has no sapphirerapids)")
    ap.add_argument("--kernel", default="eval_samples", help="PoCL: the kernel's name (sample_rows, pdf_rows, ...)")
    ap.add_argument("--variant", default="*", help="PoCL: a glob of the compiled variant's directory (4096-1-1-goffs0)")
    ap.add_argument("--mca-out", help="also write llvm-mca's whole report (timeline, bottlenecks) to this file")
    a = ap.parse_args()
    body, syntax, stack_store, stack_load = (drjit_loop(a.source) if a.source.endswith(".s")
                                             else pocl_loop(a.source, a.kernel, a.variant))
    count = lambda p: sum(1 for op, _ in body if p(op))
    row = {"instructions": len(body), "vdivps": count(lambda o: o.startswith("vdiv")),
           "vsqrtps": count(lambda o: o.startswith("vsqrt")), "gathers": count(lambda o: "gather" in o),
           "stack_stores": sum(1 for op, x in body if stack_store(op, x)),
           "stack_loads": sum(1 for op, x in body if stack_load(op, x)),
           "nontemporal_stores": count(lambda o: o.startswith("vmovnt"))}
    # Branches and calls out: llvm-mca runs the block as a straight loop body.
    lines = [f"{op} {x}" for op, x in body if not op.startswith(("j", "call"))]
    with tempfile.NamedTemporaryFile("w", suffix=".s") as f:
        f.write((".intel_syntax noprefix\n" if syntax == "intel" else "") + "\n".join(lines) + "\n")
        f.flush()
        out = subprocess.run(["llvm-mca", f"-mcpu={a.mcpu}", "-iterations=200", "-bottleneck-analysis", f.name],
                             capture_output=True, text=True).stdout
        if a.mca_out:
            timeline = subprocess.run(["llvm-mca", f"-mcpu={a.mcpu}", "-iterations=2", "-timeline",
                                       "-timeline-max-iterations=2", "-timeline-max-cycles=2000", f.name],
                                      capture_output=True, text=True).stdout
            with open(a.mca_out, "w") as o:
                o.write(out + "\n" + timeline)
    cycles = re.search(r"Total Cycles:\s+(\d+)", out)
    bound = re.search(r"Block RThroughput:\s+([\d.]+)", out)
    deps = re.search(r"- Register Dependencies \[\s*([\d.]+)%", out)
    row["mca_cycles_per_iteration"] = round(int(cycles.group(1)) / 200, 1) if cycles else None
    row["mca_throughput_bound"] = float(bound.group(1)) if bound else None
    row["mca_register_dependency_stalls_pct"] = float(deps.group(1)) if deps else None
    print(", ".join(f"{k} {v}" for k, v in row.items()))


if __name__ == "__main__":
    main()
