# Filament (profile filament): its surface shading files as C++, for the direct light and the
# image-based light.
import os
import re
from .common import CheckError, REPO
from .glsl import FLOAT_LITERAL, compile_variants, glsl_to_cpp, hook


FILAMENT_FILES = ["common_math.glsl", "common_material.fs", "surface_lighting.fs", "surface_brdf.fs",
                  "surface_shading_model_standard.fs", "surface_shading_lit.fs"]


FILAMENT_EXTENSIONS = [["MATERIAL_HAS_SHEEN_COLOR", "MATERIAL_HAS_SHEEN_ROUGHNESS"],
                       ["MATERIAL_HAS_CLEAR_COAT", "MATERIAL_HAS_CLEAR_COAT_ROUGHNESS"],
                       ["MATERIAL_HAS_ANISOTROPY"], ["MATERIAL_HAS_IOR"]]


def filament_defines(v):
    """One bit of the variant number per extension present."""
    return [(n, "") for bit, names in enumerate(FILAMENT_EXTENSIONS) if v >> bit & 1 for n in names]


def filament_text(src, files, float64):
    """shaders/src/<files> pasted in order, as C++."""
    shaders = os.path.join(src, "shaders", "src")
    parts = []
    for name in files:
        p = os.path.join(shaders, name)
        if not os.path.exists(p):
            raise CheckError("%s has no shaders/src/%s" % (src, name))
        with open(p, encoding="utf-8") as f:
            parts.append(f.read())
    text = "\n".join(parts)
    # Filament's #define constants (PI, MIN_PERCEPTUAL_ROUGHNESS, saturate's bounds) are GLSL float
    # literals too; in C++ they would be double and pull the arithmetic around them into double.
    if not float64:
        text = "\n".join(FLOAT_LITERAL.sub(lambda m: m.group(1) + "f", ln) if ln.lstrip().startswith("#define")
                         else ln for ln in text.split("\n"))
    # A refraction-only field that PixelParams declares only under MATERIAL_HAS_REFRACTION at some
    # commits; nothing the check runs reads it.
    text = re.sub(r"(?m)^\s*pixel\.perceptualRoughnessUnclamped = perceptualRoughness;$", "", text)
    return glsl_to_cpp(text, float64)


def build_filament(src, workdir, float64=False):
    text = filament_text(src, FILAMENT_FILES, float64)
    for fn, lobe, macro in [("diffuseLobe", "ec::DIFFUSE", "EC_LOBE_HOOK"),
                            ("specularLobe", "ec::SPECULAR", "EC_LOBE_HOOK"),
                            ("sheenLobe", "ec::SHEEN", "EC_LOBE_HOOK"),
                            ("clearCoatLobe", "ec::CLEARCOAT", "EC_LOBE_HOOK_LAYER")]:
        text, ok = hook(text, fn, lobe, macro)
        if not ok:
            raise CheckError("no definition of %s in %s's shaders" % (fn, src))
    lut = os.path.join(REPO, "host", "src", "model", "threejs_dfg_lut.inc")
    extra = ("static const unsigned short ec_dfg_bits[] = {\n#include \"%s\"\n};\n"
             "static float ec_half(unsigned short h) { int e = (h >> 10) & 0x1f, mant = h & 0x3ff;\n"
             "  float s = (h & 0x8000) ? -1.0f : 1.0f;\n"
             "  return e == 0 ? s * std::ldexp(float(mant), -24) : s * std::ldexp(float(mant | 0x400), e - 25); }\n"
             "static const std::vector<float> ec_dfg = [] { std::vector<float> t;\n"
             "  for (unsigned short b : ec_dfg_bits) t.push_back(ec_half(b)); return t; }();\n" % lut)
    macros = [n for names in FILAMENT_EXTENSIONS for n in names]
    exe = compile_variants("filament", text, "filament.inc", "filament.inc", filament_defines, macros, workdir,
                           extra=extra, float64=float64)
    return [exe], ["shaders/src/" + n for n in FILAMENT_FILES]


FILAMENT_IBL_FILES = FILAMENT_FILES[:-1] + ["surface_light_indirect.fs", FILAMENT_FILES[-1]]


def build_filament_ibl(src, workdir, float64=False):
    text = filament_text(src, FILAMENT_IBL_FILES, float64)
    macros = [n for names in FILAMENT_EXTENSIONS for n in names] + [
        "MATERIAL_FEATURE_LEVEL", "CONFIG_SH_BANDS_COUNT", "CONFIG_STATIC_TEXTURE_TARGET_WORKAROUND",
        "IBL_INTEGRATION", "IBL_INTEGRATION_PREFILTERED_CUBEMAP", "IBL_INTEGRATION_IMPORTANCE_SAMPLING",
        "IBL_INTEGRATION_IMPORTANCE_SAMPLING_COUNT"]
    exe = compile_variants("filament_ibl", text, "filament_ibl.inc", "filament_ibl.inc", filament_defines, macros,
                           workdir, extra='#include "ibl.hpp"', float64=float64)
    return [exe], ["shaders/src/" + n for n in FILAMENT_IBL_FILES]
