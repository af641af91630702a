# The Dr.Jit peer's side of brdfcl itself (bench/peers/drjit_peer.py): the one-line failure, the
# --device every brdfcl command gets, `brdfcl bench` runs (figures, materials, the sheen E table)
# and the pair and index files both sides read.
import json
import math
import os
import subprocess
import sys

import numpy as np

from peer_pairs import make_pairs

BRDFCL_DEVICE = []  # --device DEV for every brdfcl command, from --device (set in place by main)


def fail(message):
    print(f"drjit_peer: {message}", file=sys.stderr)
    sys.exit(2)


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


def write_inputs(tmp, name, planes, index):
    pairs, indices = os.path.join(tmp, f"{name}.f32"), os.path.join(tmp, f"{name}.u32")
    planes.astype(np.float32).tofile(pairs)
    index.astype("<u4").tofile(indices)
    return pairs, indices
