# Comparison: the error metric rel_err (|a - b| / max(|a|, |b|, floor)), the line that states it,
# and how a worst pair is described in the report.
import math


# ---------------------------------------------------------------------------------------------
# Comparison

def describe(at, pairs, mats):
    k, e, o = at
    i, L, V = pairs[k]
    return "%s; L=(%s); V=(%s); (%s) -> (%s)" % (
        mats[i].short(), ",".join("%.6g" % c for c in L), ",".join("%.6g" % c for c in V),
        ",".join("%.6g" % c for c in e), ",".join("%.6g" % c for c in o))


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
