# three.js (profile threejs): its TSL node functions run in node through an eager stand-in
# (tsl-run.mjs), for the direct light and the image-based light.
import json
import os
import re
import shutil
from .common import CheckError, GLUE


THREEJS_FILES = ["src/nodes/functions/" + n for n in
                 ["PhysicalLightingModel.js", "BSDF/BRDF_Lambert.js", "BSDF/BRDF_GGX.js", "BSDF/F_Schlick.js",
                  "BSDF/D_GGX.js", "BSDF/V_GGX_SmithCorrelated.js", "BSDF/D_GGX_Anisotropic.js",
                  "BSDF/V_GGX_SmithCorrelated_Anisotropic.js", "BSDF/BRDF_Sheen.js", "BSDF/DFGLUT.js",
                  "material/getRoughness.js", "material/getGeometryRoughness.js"]] + ["src/nodes/core/LightingModel.js"]
THREEJS_MATERIAL_NODE = "src/nodes/accessors/MaterialNode.js"


def threejs_sheen_clamp(src):
    """MaterialNode.js's clamp of the sheen roughness ([lo, hi]), or None where the file has none."""
    p = os.path.join(src, THREEJS_MATERIAL_NODE)
    if not os.path.exists(p):
        raise CheckError("%s has no %s" % (src, THREEJS_MATERIAL_NODE))
    with open(p, encoding="utf-8") as f:
        text = f.read()
    m = re.search(r"scope === MaterialNode\.SHEEN_ROUGHNESS \)(.*?)\} else if", text, re.S)
    if not m:
        raise CheckError("no SHEEN_ROUGHNESS branch in %s" % p)
    c = re.search(r"node\s*=\s*node\.clamp\(\s*([0-9.eE+-]+)\s*,\s*([0-9.eE+-]+)\s*\)", m.group(1))
    return [float(c.group(1)), float(c.group(2))] if c else None


THREEJS_ENV_BRDF = "src/nodes/functions/BSDF/EnvironmentBRDF.js"


def threejs_local_imports(src, path):
    """The files `path` imports by a relative path that exist in the checkout (EnvironmentBRDF's
    DFG source: DFGLUT.js, or DFGApprox.js in older trees)."""
    with open(os.path.join(src, path), encoding="utf-8") as f:
        text = f.read()
    out = []
    for spec in re.findall(r"import\s[^;]*?from\s*['\"](\.[^'\"]+)['\"]", text):
        q = os.path.normpath(os.path.join(os.path.dirname(path), spec))
        if os.path.exists(os.path.join(src, q)):
            out.append(q)
    return out


def threejs_runner(src, workdir, name, driver, files, float64):
    """An evaluator script that runs three.js's TSL `files` in node through the stand-in, driven by
    scripts/engine_check/`driver` (which may import threejs.mjs, the direct-light driver)."""
    import shlex
    if not shutil.which("node"):
        raise CheckError("node is not installed (scripts/install-deps installs nodejs)")
    for p in files + [THREEJS_MATERIAL_NODE]:
        if not os.path.exists(os.path.join(src, p)):
            raise CheckError("%s has no %s" % (src, p))
    clamp = threejs_sheen_clamp(src)
    cmd = ["node", os.path.join(GLUE, "tsl-run.mjs"), "f64" if float64 else "f32", os.path.join(GLUE, driver)]
    # The hooks load the direct-light driver as it is when another driver imports it.
    cmd += [os.path.join(GLUE, "threejs.mjs")] if driver != "threejs.mjs" else []
    cmd += [os.path.join(src, p) for p in files]
    exe = os.path.join(workdir, name)
    with open(exe, "w") as f:
        f.write("#!/bin/sh\nEC_MATERIALS=\"$1\" EC_PAIRS=\"$2\" EC_THREEJS_SRC=%s EC_THREEJS_SHEEN_CLAMP=%s exec %s\n"
                % (shlex.quote(os.path.abspath(src)), shlex.quote(json.dumps(clamp)), " ".join(map(shlex.quote, cmd))))
    os.chmod(exe, 0o755)
    return [exe], files + [THREEJS_MATERIAL_NODE]


def build_threejs(src, workdir, float64=False):
    return threejs_runner(src, workdir, "threejs-run", "threejs.mjs", THREEJS_FILES, float64)


def build_threejs_ibl(src, workdir, float64=False):
    """PhysicalLightingModel's indirect() and finish(), with EnvironmentBRDF.js for the coat."""
    files = THREEJS_FILES + [THREEJS_ENV_BRDF]
    if not os.path.exists(os.path.join(src, THREEJS_ENV_BRDF)):
        raise CheckError("%s has no %s" % (src, THREEJS_ENV_BRDF))
    files += [q for q in threejs_local_imports(src, THREEJS_ENV_BRDF) if q not in files]
    return threejs_runner(src, workdir, "threejs-ibl-run", "threejs-ibl.mjs", files, float64)
