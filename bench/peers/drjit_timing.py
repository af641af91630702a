# The Dr.Jit peer's timing (bench/peers/drjit_peer.py): one workload resident on the device, and
# alternating rounds of `brdfcl bench --pairs --indices` and the peer on the same inputs.
import gc
import statistics
import time

import numpy as np

from drjit_brdfcl import brdfcl_bench, write_inputs
from drjit_maths import Peer, pack
from peer_pairs import make_pairs, median_seconds


class Side:
    """One workload on the device: inputs resident, materials gathered by index (K > 1) or read
    once for all lanes (K = 1, as brdfcl's one-material program does)."""

    def __init__(self, peer, lobe, materials, planes, index, freeze=True, features=None):
        dr, t = peer.dr, peer.t
        self.peer, self.dr, self.lobe = peer, dr, lobe
        packed, self.features = pack(materials)
        if features is not None:
            self.features = features
        Float = peer.Float
        self.L = [Float(planes[i]) for i in range(3)]
        self.V = [Float(planes[3 + i]) for i in range(3)]
        self.k = len(materials)
        self.table = {k: Float(v) for k, v in packed.items()}
        self.index = t.UInt32(np.ascontiguousarray(index, dtype=np.uint32))
        self.sheen_e = peer.sheen_e
        dr.eval(self.L, self.V, self.index, self.table)
        dr.sync_thread()

        def body(L, V, index, table, sheen_e):
            peer.sheen_e = sheen_e  # an input of the frozen function, as every array it reads
            if self.k == 1:
                m = table  # size-1 arrays: one load, broadcast over the lanes
            else:
                m = {k: dr.gather(Float, v, index) for k, v in table.items()}
            return peer.evaluate(self.lobe, self.features, m, L, V)

        # A frozen function replays the recorded kernel without tracing again: the kernel alone
        # is timed, as brdfcl's side times its kernel alone.
        self.fn = dr.freeze(body) if freeze else body

    def run(self):
        f = self.fn(self.L, self.V, self.index, self.table, self.sheen_e)
        self.dr.eval(f)
        self.dr.sync_thread()
        return f

    def median_seconds(self, runs):
        return median_seconds(self.run, runs)

    def kernel_seconds(self, runs):
        """CUDA: the kernels' own time from Dr.Jit's history (launch to completion on the device)."""
        dr = self.dr
        dr.set_flag(dr.JitFlag.KernelHistory, True)
        t = []
        for _ in range(runs):
            dr.kernel_history_clear()
            t0 = time.perf_counter()
            self.run()
            wall = time.perf_counter() - t0
            hist = [h for h in dr.kernel_history() if h.get("type") == dr.KernelType.JIT]
            kernel = sum(h.get("execution_time", 0.0) for h in hist) * 1e-3  # ms in the history
            t.append(kernel if kernel > 0 else wall)  # a history without times: the wall clock
        dr.set_flag(dr.JitFlag.KernelHistory, False)
        return statistics.median(t)


def timing(a, dr, mod, sheen_e, tmp):
    n = a.pairs
    planes = make_pairs(n, a.seed)
    peer = Peer(dr, mod, sheen_e)
    cuda = a.backend == "cuda"
    results = []
    threads = f", {dr.thread_count()} threads" if not cuda else ""
    print(f"brdfcl vs Dr.Jit {dr.__version__} ({a.backend}{threads}{', frozen' if not a.no_freeze else ', traced'}), "
          f"{n} pairs, median of {a.runs} runs, {a.rounds} alternating rounds")
    print(f"  {'lobe':<10}{'materials':>10}{'brdfcl':>10}{'Dr.Jit':>10}  brdfcl/Dr.Jit (rounds)")
    for k in a.materials:
        # One index draw per K, shared by both sides and every lobe.
        index = np.random.default_rng(a.seed + k).integers(0, k, n).astype(np.uint32)
        pairs, indices = write_inputs(tmp, f"pairs-{k}", planes, index)
        for lobe in a.lobes:
            first = brdfcl_bench(a.brdfcl, lobe, k, pairs, indices, a.runs)
            side = Side(peer, lobe, first["material_params"], planes, index, freeze=not a.no_freeze)
            side.run()  # traces and compiles; the frozen function records here
            side.run()
            # On a GPU, brdfcl's launch (profiling event) against Dr.Jit's kernel time; on the CPU
            # both sides' wall time of the evaluation with inputs and results in memory.
            key = "launch_samples_per_second" if cuda else "samples_per_second"
            ours, theirs = [], []
            for _ in range(a.rounds):
                ours.append(brdfcl_bench(a.brdfcl, lobe, k, pairs, indices, a.runs)[key])
                theirs.append(n / (side.kernel_seconds(a.runs) if cuda else side.median_seconds(a.runs)))
            ratios = [o / t for o, t in zip(ours, theirs)]
            row = {"lobe": lobe, "materials": k, "pairs": n, "device": first["device"],
                   "brdfcl_samples_per_second": statistics.median(ours),
                   "drjit_samples_per_second": statistics.median(theirs),
                   "ratio_median": statistics.median(ratios), "ratios": ratios}
            results.append(row)
            print(f"  {lobe:<10}{k:>10}{row['brdfcl_samples_per_second'] / 1e6:>10.1f}"
                  f"{row['drjit_samples_per_second'] / 1e6:>10.1f}  {row['ratio_median']:.2f}x "
                  f"({', '.join(f'{r:.2f}' for r in ratios)})", flush=True)
            # The Side and its frozen function hold each other (the body reads self), so only the
            # cycle collector frees them: collected here, their arrays are freed before the next
            # workload records, where a free (a host function on the LLVM backend) cannot be recorded.
            del side
            gc.collect()
            dr.sync_thread()
    what = "launch (profiling event) vs kernel time" if cuda else "OpenCL kernel vs Dr.Jit evaluation, inputs resident"
    print(f"  (Msamples/s; {what})")
    return results
