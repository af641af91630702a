# The command line: the options, main() (self-test, direct-light or image-based-light check) and
# run(), which exits 2 with the message on a CheckError.
import argparse
import math
import os
import shutil
import sys
import tempfile
from .common import CheckError, REPO
from .compare import DEFAULT_FLOOR
from .engines import ENGINES
from .direct import check
from .selftest import self_test


def main():
    ap = argparse.ArgumentParser(description=__doc__ or "engine-check")
    ap.add_argument("--sources", help="folder holding the engine checkouts (glTF-Sample-Renderer/, three.js/, "
                    "filament/, Babylon.js/, MaterialX/)")
    ap.add_argument("--brdfcl", default=os.path.join(REPO, "build", "bin", "brdfcl"), help="the brdfcl to check")
    ap.add_argument("--engines", default=",".join(ENGINES), help="comma-separated profiles (default: all found)")
    ap.add_argument("--materials", type=int, default=48, help="random materials (default 48)")
    ap.add_argument("--pairs", type=int, default=40, help="random direction pairs per material (default 40)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--float64", action="store_true", help="run the engines in float64 instead of float32 (GLSL compiled "
                    "with double, the TSL stand-in unrounded): tells an engine's own float rounding from a real difference")
    ap.add_argument("--floor", type=float, default=DEFAULT_FLOOR,
                    help="error metric |a - b| / max(|a|, |b|, FLOOR) (default %g); 0 gives the pure relative "
                    "difference" % DEFAULT_FLOOR)
    ap.add_argument("--work", help="scratch folder to keep (default: a temporary one, removed)")
    ap.add_argument("--self-test", action="store_true", help="run the harness on its own tiny GLSL and TSL snippets")
    ap.add_argument("--ibl", action="store_true", help="check the image-based light instead of the direct light: each "
                    "engine's IBL code under a constant environment against `brdfcl shade --profile P`")
    a = ap.parse_args()
    if not (a.floor >= 0.0 and math.isfinite(a.floor)):
        ap.error("--floor: %r is not a finite number >= 0" % a.floor)
    if a.self_test:
        return self_test()
    if not a.sources:
        ap.error("--sources DIR is required (or --self-test)")
    if not os.access(a.brdfcl, os.X_OK):
        raise CheckError("no brdfcl at %s: build it (make build) or pass --brdfcl" % a.brdfcl)
    work = a.work or tempfile.mkdtemp(prefix="engine-check-")
    os.makedirs(work, exist_ok=True)
    try:
        return check(a, work)
    finally:
        if not a.work:
            shutil.rmtree(work, ignore_errors=True)


def run():
    try:
        sys.exit(main())
    except CheckError as e:
        sys.stderr.write("engine-check: %s\n" % e)
        sys.exit(2)
