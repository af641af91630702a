# Zero copy: evaluating 10M float32 samples must not copy L or V (peak RSS growth, measured in a
# subprocess, stays well below the 240 MB two copies would cost), and its samples/s is compared
# with `brdfcl bench --pairs` on the same pairs and material (kernel only, in memory).
import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from conftest import ROOT

SCRIPT = textwrap.dedent("""
    import json, sys, time
    import numpy as np
    import brdfcl
    sys.path.insert(0, sys.argv[2])
    from conftest import MATERIALS

    def hwm():
        for line in open("/proc/self/status"):
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    n = int(sys.argv[1])
    rng = np.random.default_rng(5)
    L = rng.random((n, 3), dtype=np.float32) + np.float32(0.01)
    V = rng.random((n, 3), dtype=np.float32) + np.float32(0.01)
    idx = rng.integers(0, len(MATERIALS), size=n)
    materials = brdfcl._materials(MATERIALS, False)
    brdfcl.evaluate(materials, L[:4096], V[:4096], idx[:4096])  # programs built, tables baked
    before = hwm()
    out = brdfcl.evaluate(materials, L, V, idx)
    growth = hwm() - before
    # A repeat call into the same array (out=) writes the same bits.
    again = np.empty_like(out)
    brdfcl.evaluate(materials, L, V, idx, out=again)
    assert np.array_equal(again.view(np.uint32), out.view(np.uint32))
    planes = np.concatenate([L.T, V.T]).astype("<f4")
    planes[:, :4194304].tofile(sys.argv[3])
    print(json.dumps({"growth": growth, "out": out.nbytes, "n": n}))
""")


@pytest.fixture(scope="module")
def measured(tmp_path_factory):
    pairs = tmp_path_factory.mktemp("z") / "pairs.f32"
    r = subprocess.run([sys.executable, "-c", SCRIPT, str(10_000_000), str(ROOT / "tests" / "python"), str(pairs)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout.strip().splitlines()[-1]), pairs


def test_no_copy_of_L_or_V(measured):
    m, _ = measured
    extra = m["growth"] - m["out"]  # the (N, 3) result itself must exist
    print(f"\n10M samples: peak RSS growth {m['growth'] / 2**20:.0f} MiB, of which the result "
          f"{m['out'] / 2**20:.0f} MiB")
    # Two float32 copies of L and V would add 240 MB; the batch planes take ~40 MB.
    assert extra < 100e6, f"{extra / 2**20:.0f} MiB beyond the result: L or V was copied"


# Times brdfcl.evaluate on the pairs file of `brdfcl bench --pairs` with the bench's own material:
# the median of 5 repeat calls into one result array (out=), as a user's loop runs them.
TIMING = textwrap.dedent("""
    import json, sys, time
    import numpy as np
    import brdfcl
    planes = np.fromfile(sys.argv[1], dtype="<f4").reshape(6, -1)
    L, V = np.ascontiguousarray(planes[:3].T), np.ascontiguousarray(planes[3:].T)
    material = json.loads(sys.argv[2])
    out = np.empty((L.shape[0], 3), dtype=np.float32)
    brdfcl.evaluate(material, L[:4096], V[:4096])  # programs built, tables baked
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        brdfcl.evaluate(material, L, V, out=out)
        times.append(time.perf_counter() - t0)
    print(json.dumps({"n": L.shape[0], "seconds": sorted(times)[2]}))
""")


def gltf_material(m):
    """A glTF material dict from the parameters `brdfcl bench --json` prints as material0."""
    return {"pbrMetallicRoughness": {"baseColorFactor": m["base_color"] + [1.0], "metallicFactor": m["metallic"],
                                     "roughnessFactor": m["roughness"]},
            "extensions": {
                "KHR_materials_sheen": {"sheenColorFactor": m["sheen_color"],
                                        "sheenRoughnessFactor": m["sheen_roughness"]},
                "KHR_materials_clearcoat": {"clearcoatFactor": m["clearcoat"],
                                            "clearcoatRoughnessFactor": m["clearcoat_roughness"]},
                "KHR_materials_anisotropy": {"anisotropyStrength": m["anisotropy_strength"],
                                             "anisotropyRotation": m["anisotropy_rotation"]}}}


def test_throughput_vs_bench(measured, cli):
    """Python's samples/s against `brdfcl bench --pairs` (the kernel alone on pre-filled,
    pre-normalized planes, in memory) on the same 4M pairs and the same material (the bench's one
    random material, all layers), both medians of repeated runs.

    The bound is within 10 %. Measured on PoCL, 2 cores, into a reused out= array: 0.91 to
    0.96 on the idle machine, 0.90 to 0.93 with a build beside it. Python's call reads L and V and writes the result
    where they lie (the row kernel, no copy); the device then does what the bench's planes had
    done before its clock started: it deinterleaves the rows, normalizes both directions and
    checks them (BM_InMemory/all/{kernel,arrays} in docs/performance.md: 0.95 on one material). The
    bound lies inside the run-to-run scatter of a shared machine, so it is asserted with
    BRDFCL_STRICT_PERF=1; otherwise the ratio must reach 0.5, a guard against the copies of before
    coming back."""
    import os
    _, pairs = measured
    bench = json.loads(cli("bench", "--pairs", pairs, "--materials", 1, "--runs", 5, "--json"))
    r = subprocess.run([sys.executable, "-c", TIMING, str(pairs), json.dumps(gltf_material(bench["material0"]))],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    m = json.loads(r.stdout.strip().splitlines()[-1])
    ratio = (m["n"] / m["seconds"]) / bench["samples_per_second"]
    print(f"\npython {m['n'] / m['seconds'] / 1e6:.2f} M samples/s into out=, brdfcl bench "
          f"{bench['samples_per_second'] / 1e6:.2f} M samples/s, ratio {ratio:.2f}")
    assert ratio >= (0.9 if os.environ.get("BRDFCL_STRICT_PERF") == "1" else 0.5)
