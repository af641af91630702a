#!/usr/bin/env python3
# Helpers of bench/gpu/run-gpu-bench on the GPU machine: the peer's pairs and indices written once,
# the host<->device copy bandwidth (pageable and pinned, through PyTorch's CUDA runtime) that
# bounds the row paths, and counts of the division, sqrt and special-function instructions in PTX/SASS.
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def pairs(out, n, seed, ks):
    from peer_pairs import make_pairs
    # As drjit_peer.py's timing(): one pair draw, one index draw per K from seed + K.
    make_pairs(n, seed).astype(np.float32).tofile(os.path.join(out, "pairs.f32"))
    for k in ks:
        idx = np.random.default_rng(seed + k).integers(0, k, n).astype("<u4")
        idx.tofile(os.path.join(out, f"indices-{k}.u32"))


def copy_bandwidth(mib):
    import torch
    n = mib << 20
    dev = torch.empty(n, dtype=torch.uint8, device="cuda")
    dev2 = torch.empty(n, dtype=torch.uint8, device="cuda")
    rows = {}
    for pinned in (False, True):
        host = torch.empty(n, dtype=torch.uint8, pin_memory=pinned)
        host.fill_(1)
        for what, (dst, src) in {"host_to_device": (dev, host), "device_to_host": (host, dev)}.items():
            t = []
            for _ in range(6):
                a, b = torch.cuda.Event(enable_timing=True), torch.cuda.Event(enable_timing=True)
                torch.cuda.synchronize()
                a.record()
                dst.copy_(src)
                b.record()
                torch.cuda.synchronize()
                t.append(a.elapsed_time(b) * 1e-3)
            rows[f"{what}_{'pinned' if pinned else 'pageable'}_GBps"] = n / statistics.median(t[1:]) / 1e9
    t = []
    for _ in range(6):
        a, b = torch.cuda.Event(enable_timing=True), torch.cuda.Event(enable_timing=True)
        a.record()
        dev2.copy_(dev)
        b.record()
        torch.cuda.synchronize()
        t.append(a.elapsed_time(b) * 1e-3)
    rows["device_to_device_read_plus_write_GBps"] = 2 * n / statistics.median(t[1:]) / 1e9
    rows["gpu"] = torch.cuda.get_device_name(0)
    print(json.dumps(rows, indent=1))


PTX_OPS = ["div.rn.f32", "div.full.f32", "div.approx", "rcp.rn.f32", "rcp.approx", "sqrt.rn.f32", "sqrt.approx",
           "rsqrt.approx", "ex2.approx", "lg2.approx", "ld.global", "st.global", "ld.local", "st.local", "fma.rn.f32",
           ".ftz"]


def count(paths):
    """Per file: PTX operation counts, then ptxas's resource report and SASS counts of the cubin."""
    ptxas = os.environ.get("PTXAS", "ptxas")
    for p in paths:
        raw = open(p, "rb").read()
        # brdfcl's disk cache puts a header before the binary, and NVIDIA's PTX ends in NULs.
        start = raw.find(b"//\n// Generated")
        raw = (raw[start:] if start > 0 else raw).rstrip(b"\0")
        text = raw.decode("latin-1")
        if ".entry" not in text:
            continue
        with open(p, "wb") as f:
            f.write(raw)
        entries = re.findall(r"\.entry\s+(\w+)", text)
        ops = {o: text.count(o) for o in PTX_OPS}
        print(f"== {os.path.basename(p)}: entries {entries}")
        print("   PTX " + ", ".join(f"{k} {v}" for k, v in ops.items()))
        cubin = p + ".cubin"
        r = subprocess.run([ptxas, "-arch=sm_90", "-O3", "-v", p, "-o", cubin], capture_output=True, text=True)
        for line in (r.stderr + r.stdout).splitlines():
            if "registers" in line or "spill" in line or "Compiling entry" in line or "error" in line:
                print("   ptxas " + line.strip())
        if r.returncode != 0 or not os.path.exists(cubin) or not shutil.which("cuobjdump"):
            continue
        s = subprocess.run(["cuobjdump", "-sass", cubin], capture_output=True, text=True).stdout
        ins = re.findall(r"/\*[0-9a-f]{4,6}\*/\s+(?:@!?U?P\w+\s+)?([A-Z][A-Z0-9_.]*)", s)
        mufu = {}
        for i in ins:
            if i.startswith("MUFU") or i in ("CALL.REL.NOINC", "CALL.REL", "BSSY", "BRA", "LDL", "STL") or \
                    i.startswith(("LDG", "STG", "LDL", "STL", "CALL")):
                mufu[i] = mufu.get(i, 0) + 1
        print(f"   SASS {len(ins)} instructions; " + ", ".join(f"{k} {v}" for k, v in sorted(mufu.items())))


WORKLOADS = ["all:256", "all:1", "sheen:256", "sheen:1", "specular:256", "specular:1"]


def variants(work, spec, rounds, runs, peer_json, out_json):
    """brdfcl bench --pairs on each line of `spec` ("label build [VAR=VALUE ...] [@lobe:k,...]"),
    alternating lines within each round; each line keeps its own brdfcl disk cache, whose new
    program binaries (PTX on NVIDIA) are kept as ptx/brdfcl-<label>-<lobe>-k<k>.ptx."""
    lines = []
    for raw in open(spec):
        f = raw.split("#", 1)[0].split()
        if not f:
            continue
        env = {k: v.replace("~", " ") for k, v in (x.split("=", 1) for x in f[2:] if "=" in x and not x.startswith("@"))}
        loads = next((x[1:].split(",") for x in f[2:] if x.startswith("@")), WORKLOADS)
        lines.append((f[0], f[1], env, loads))
    drjit = {}
    if os.path.exists(peer_json):
        for r in json.load(open(peer_json))["results"]:
            drjit[f"{r['lobe']}:{r['materials']}"] = r["drjit_samples_per_second"]
    os.makedirs(os.path.join(work, "ptx"), exist_ok=True)
    got = {}
    for rnd in range(rounds):
        for w in WORKLOADS:
            lobe, k = w.split(":")
            for label, build, env, loads in lines:
                if w not in loads:
                    continue
                cache = os.path.join(work, f"xc-{label}")
                before = set(glob.glob(os.path.join(cache, "brdfcl", "program_*.bin")))
                e = dict(os.environ, XDG_CACHE_HOME=cache, **env)
                cmd = [os.path.join(work, build, "brdfcl"), "bench", "--pairs", os.path.join(work, "pairs.f32"),
                       "--indices", os.path.join(work, f"indices-{k}.u32"), "--materials", k, "--lobe", lobe,
                       "--runs", str(runs), "--json"]
                r = subprocess.run(cmd, capture_output=True, text=True, env=e)
                if r.returncode != 0:
                    print(f"  {label} {w}: failed: {r.stderr.strip()[:300]}")
                    continue
                j = json.loads(r.stdout)
                got.setdefault((label, w), []).append(j["launch_samples_per_second"])
                print(f"    round {rnd + 1} {label:<8}{w:>14}{j['launch_samples_per_second'] / 1e9:>8.2f} G/s", flush=True)
                for p in sorted(set(glob.glob(os.path.join(cache, "brdfcl", "program_*.bin"))) - before):
                    if b"eval_samples" in open(p, "rb").read():
                        with open(p, "rb") as src, open(os.path.join(work, "ptx", f"brdfcl-{label}-{lobe}-k{k}.ptx"), "wb") as dst:
                            dst.write(src.read())
    print(f"  {'build/setting':<14}{'workload':>14}{'brdfcl G/s':>12}{'Dr.Jit G/s':>12}{'ratio':>8}  rounds")
    rows = []
    for (label, w), v in got.items():
        med = statistics.median(v)
        d = drjit.get(w)
        rows.append({"label": label, "workload": w, "launch_samples_per_second": med, "rounds": v,
                     "drjit_samples_per_second": d, "ratio": med / d if d else None})
        print(f"  {label:<14}{w:>14}{med / 1e9:>12.1f}{(d or 0) / 1e9:>12.1f}{(med / d if d else 0):>8.2f}  "
              + ", ".join(f"{x / 1e9:.1f}" for x in v))
    json.dump({"variants": [l[:3] for l in lines], "results": rows}, open(out_json, "w"), indent=1)


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "pairs":
        pairs(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), [int(k) for k in sys.argv[5].split(",")])
    elif cmd == "copy":
        copy_bandwidth(int(sys.argv[2]))
    elif cmd == "variants":
        variants(sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5]), sys.argv[6], sys.argv[7])
    elif cmd == "count":
        count(sorted(p for a in sys.argv[2:] for p in glob.glob(a)))
    else:
        sys.exit(f"gpu_probe: unknown command {cmd}")
