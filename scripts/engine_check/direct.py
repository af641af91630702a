# The direct-light check (the default): runs each engine's evaluator and `brdfcl eval` per lobe on
# the random and edge sets and prints the report.
import os
import random
from .common import CheckError, LOBES, progress
from .sets import edge_set, random_set
from .compare import print_report, worst_pair
from .sources import build_engine, pins
from .brdfcl import brdfcl_eval, run_engine_exe, sheen_albedo, write_inputs
from .engines import ENGINES
from .ibl import check_ibl


def check(a, work):
    wanted = [e for e in a.engines.split(",") if e]
    for e in wanted:
        if e not in ENGINES:
            raise CheckError("--engines: unknown profile %r (known: %s)" % (e, ", ".join(ENGINES)))
    if a.ibl:
        return check_ibl(a, work, wanted)
    rng = random.Random(a.seed)
    sets = {"random": random_set(rng, a.materials, a.pairs), "edge": edge_set(rng)}
    inputs, albedo = {}, {}
    for tag, (mats, pairs) in sets.items():
        inputs[tag] = write_inputs(work, tag, mats, pairs)
        progress("sheen tables for the %s set" % tag)
        albedo[tag] = sheen_albedo(a.brdfcl, work, tag, mats, pairs)
    results = []
    unchecked = [p for p in ["khronos", "threejs", "filament", "babylon", "materialx"] if p not in ENGINES]
    if unchecked:
        print("%s: no glue in this harness yet, not checked" % ", ".join(unchecked))
    for prof in wanted:
        folder, builder = ENGINES[prof]
        built = build_engine(a, work, prof, folder, builder, prof)
        if built is None:
            continue
        exes, files, per_file = built
        pinned = pins(prof)
        for p in files:
            pin = pinned.get(os.path.basename(p))
            state = "" if pin is None else (" = pinned %s" % pin if per_file[p].startswith(pin[:7]) or
                                            pin.startswith(per_file[p][:7]) else " (profile pins %s)" % pin)
            print("  %-58s last changed %s%s" % (p, per_file[p], state))
        for tag, (mats, pairs) in sets.items():
            mj, sc = inputs[tag]
            progress("%s: %s set" % (prof, tag))
            eng = run_engine_exe(exes[0], work, "%s-%s" % (prof, tag), mats, pairs, albedo[tag], a.brdfcl)
            for lobe in LOBES:
                ours = brdfcl_eval(a.brdfcl, ["--profile", prof, "--lobe", lobe], mj, sc,
                                   os.path.join(work, "%s-%s-%s.csv" % (prof, tag, lobe)))
                worst, at, nan_bad, nan_at = worst_pair(pairs, [r[lobe] for r in eng], ours, a.floor)
                results.append((prof, lobe, tag, worst, nan_bad, at, nan_at, pairs, mats))
    print_report(a, results, "lobe", 9, "at (material; L; V; engine -> brdfcl)", True,
                 ["(a second line counts the pairs where only one side is NaN or infinite)"])
    return 0
