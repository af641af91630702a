# What both outside peers (mitsuba_peer.py, drjit_peer.py) share: the direction pairs they time
# and check, the domain of brdfcl's own workload (bench/peers/workload.cpp: N.L and N.V in [0.01, 1)
# with uniform azimuths, from a fixed seed so that every run sees the same pairs), and the timing.
import statistics
import time

import numpy as np


def make_pairs(n, seed):
    rng = np.random.default_rng(seed)
    planes = []
    for _ in range(2):  # L, then V
        z = rng.uniform(0.01, 1.0, n).astype(np.float32)
        phi = rng.uniform(0.0, 2 * np.pi, n).astype(np.float32)
        s = np.sqrt(1.0 - z * z)
        planes += [s * np.cos(phi), s * np.sin(phi), z]
    return np.stack(planes).astype(np.float32)  # 6 x n: L.xyz, V.xyz


def median_seconds(run, runs):
    """The median wall time of `runs` calls of `run` (which waits for its own results)."""
    t = []
    for _ in range(runs):
        t0 = time.perf_counter()
        run()
        t.append(time.perf_counter() - t0)
    return statistics.median(t)
