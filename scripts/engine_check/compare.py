# Comparison: the error metric rel_err (|a - b| / max(|a|, |b|, floor)), the line that states it,
# the worst pair of a run and the report table that the direct-light and image-based-light checks print.
import math


# ---------------------------------------------------------------------------------------------
# Comparison

def describe(at, pairs, mats, light=True):
    """The material, L (where light), V and both sides' values of the pair at = (k, engine, brdfcl)."""
    k, e, o = at
    i, L, V = pairs[k]
    where = ("L=(%s); " % ",".join("%.6g" % c for c in L) if light else "") + \
        "V=(%s)" % ",".join("%.6g" % c for c in V)
    return "%s; %s; (%s) -> (%s)" % (mats[i].short(), where, ",".join("%.6g" % c for c in e),
                                     ",".join("%.6g" % c for c in o))


FLT_MIN = 2.0 ** -126


DEFAULT_FLOOR = 1e-4


def rel_err(a, b, floor=DEFAULT_FLOOR):
    """|a - b| / max(|a|, |b|, floor): relative where the values are above the floor, absolute in
    units of the floor below it, so two values that both round to nothing (1e-38 against 0) do not
    count as a whole relative unit. Subnormals count as 0 (GPUs and brdfcl's kernels flush them); a
    NaN or infinity on one side only is an infinite difference."""
    a = 0.0 if abs(a) < FLT_MIN else a
    b = 0.0 if abs(b) < FLT_MIN else b
    if math.isnan(a) and math.isnan(b):
        return 0.0
    if math.isnan(a) or math.isnan(b):
        return math.inf
    if a == b:
        return 0.0
    if math.isinf(a) or math.isinf(b):
        return math.inf
    return abs(a - b) / max(abs(a), abs(b), floor)


def metric_line(floor, float64):
    return ("worst = max over pairs and channels of |engine - brdfcl| / max(|engine|, |brdfcl|, %g)%s; "
            "engine run in %s" % (floor, " (pure relative)" if floor == 0 else "", "float64" if float64 else "float32"))


def worst_pair(pairs, engine, ours, floor, keep=None):
    """Over the pairs whose material index keep accepts (all without it), engine[k] against ours[k]:
    (worst, at, nan_bad, nan_at), the largest finite rel_err over the channels and its pair
    (k, engine, brdfcl), and how many pairs differ infinitely (NaN or infinity on one side) with the
    first of them; worst is -1 and at None where no pair counts."""
    worst, at, nan_bad, nan_at = -1.0, None, 0, None
    for k, (i, L, V) in enumerate(pairs):
        if keep is not None and not keep(i):
            continue
        e, o = engine[k], ours[k]
        err = max(rel_err(x, y, floor) for x, y in zip(e, o))
        if err == math.inf:
            nan_bad += 1
            nan_at = nan_at or (k, e, o)
        elif err > worst:
            worst, at = err, (k, e, o)
    return worst, at, nan_bad, nan_at


def print_report(a, results, part, width, where, light, notes=()):
    """The table after a check: the metric, a header (part names the second column, width its width,
    where the last), notes under it, then per result (profile, part, set, worst, nan_bad, at, nan_at,
    pairs, mats) its worst pair and, on a second line, the pairs that differ infinitely."""
    row = "%-9s %-" + str(width) + "s %-6s %-10s"
    print()
    print(metric_line(a.floor, a.float64))
    print((row + " %s") % ("engine", part, "set", "worst", where))
    for note in notes:
        print((row + " %s") % ("", "", "", "", note))
    for prof, name, tag, worst, nan_bad, at, nan_at, pairs, mats in results:
        if at is not None:
            print((row + " %s") % (prof, name, tag, "%.2e" % worst, describe(at, pairs, mats, light)))
        else:
            print(row % (prof, name, tag, "-"))
        if nan_bad:
            print((row + " %s") % ("", "", "", "%d x inf" % nan_bad, describe(nan_at, pairs, mats, light)))
