# Babylon.js (profile babylon): its PBR .fx includes as C++, for the direct light and the
# image-based light, with the checkout's BRDF texture.
import json
import os
import re
import struct
import khronos_luts
from .common import CheckError
from .glsl import FLOAT_LITERAL, compile_variants, glsl_to_cpp


BABYLON_SHADERS = "packages/dev/core/src/Shaders/ShadersInclude"
# The function libraries pbr.fragment.fx includes, in its order, then the blocks the glue runs as
# its body: pbrBlockReflectance0, one lightFragment (light 0), pbrBlockFinalLitComponents.
BABYLON_FUNCTION_FILES = ["helperFunctions.fx", "pbrHelperFunctions.fx", "pbrBRDFFunctions.fx",
                          "pbrDirectLightingSetupFunctions.fx", "pbrDirectLightingFunctions.fx",
                          "pbrBlockReflectivity.fx"]
BABYLON_BODY_FILES = ["pbrBlockReflectance0.fx", "lightFragment.fx", "pbrBlockFinalLitComponents.fx"]
# The defines PBRMaterial sets for a glTF metallic-roughness material under one directional light
# (docs/profiles.md "babylon"): PBRBRDFConfiguration's defaults, the BRDF texture expanded to half
# floats (no ENVIRONMENTBRDF_RGBD), no SPECULARAA factors on a flat surface.
BABYLON_DEFINES = [("PBR", ""), ("LIGHT0", ""), ("DIRLIGHT0", ""), ("SPECULARTERM", ""), ("METALLICWORKFLOW", ""),
                   ("BRDF_V_HEIGHT_CORRELATED", ""), ("MS_BRDF_ENERGY_CONSERVATION", ""), ("ENVIRONMENTBRDF", ""),
                   ("LEGACY_SPECULAR_ENERGY_CONSERVATION", ""), ("SPECULAR_GLOSSINESS_ENERGY_CONSERVATION", ""),
                   ("BASE_DIFFUSE_MODEL", "BRDF_DIFFUSE_MODEL_EON"),
                   ("DIELECTRIC_SPECULAR_MODEL", "DIELECTRIC_SPECULAR_MODEL_GLTF"),
                   ("CONDUCTOR_SPECULAR_MODEL", "CONDUCTOR_SPECULAR_MODEL_GLTF"), ("DEBUGMODE", "0")]
# One bit of the variant number per extension present: KHR_materials_sheen, _clearcoat,
# _anisotropy, _ior (which sets only indexOfRefraction).
BABYLON_EXTENSIONS = [["SHEEN", "SHEEN_ROUGHNESS", "SHEEN_ALBEDOSCALING"], ["CLEARCOAT"], ["ANISOTROPIC"], []]


def babylon_defines(v):
    return BABYLON_DEFINES + [(n, "") for bit, names in enumerate(BABYLON_EXTENSIONS) if v >> bit & 1 for n in names]


def babylon_read(src, name, seen=None):
    """ShadersInclude/name as Babylon's shader processor sees it: `#include<x>` (with its optional
    (...) or [...] tail) replaced by x.fx where the checkout has it, `{X}` read as light 0."""
    seen = set() if seen is None else seen
    p = os.path.join(src, BABYLON_SHADERS, name)
    if not os.path.exists(p):
        raise CheckError("%s has no %s/%s" % (src, BABYLON_SHADERS, name))
    with open(p, encoding="utf-8") as f:
        text = f.read().replace("\r\n", "\n")

    def repl(m):
        inc = m.group(1) + ".fx"
        if inc in seen or not os.path.exists(os.path.join(src, BABYLON_SHADERS, inc)):
            # Only inside branches the check's defines leave out (area lights, clustered lights).
            return "// (#include<%s> not compiled)" % m.group(1)
        seen.add(inc)
        return babylon_read(src, inc, seen)

    text = re.sub(r"(?m)^[ \t]*#include\s*<(\w+)>.*$", repl, text)
    return text.replace("{X}", "0")


def babylon_cpp(text, float64):
    # An `out` parameter on a line of its own (Babylon writes long parameter lists one to a line)
    # would read as a global `out` declaration to glsl_to_cpp: spell it as a reference first.
    text = re.sub(r"(?m)^([ \t]*)(?:inout|out)\s+(\w+)\s+(\w+)(?=\s*\)?\s*,?\s*$)", r"\1\2& \3", text)
    # #define constants are GLSL float literals too (MINIMUMVARIANCE, saturate's bounds).
    if not float64:
        text = "\n".join(FLOAT_LITERAL.sub(lambda m: m.group(1) + "f", ln) if ln.lstrip().startswith("#define")
                         else ln for ln in text.split("\n"))
    return glsl_to_cpp(text, float64)


def babylon_brdf_texture(src, workdir):
    """C++ defining ec_brdf_texture: the checkout's brdfTextureTools.ts PNG, RGBD-decoded and rounded
    to half float per texel as RGBDTextureTools.ExpandRGBDTexture leaves it (scripts/babylon_luts.py)."""
    import babylon_luts
    ts = os.path.join(src, babylon_luts.TS_PATH)
    if not os.path.exists(ts):
        raise CheckError("%s has no %s" % (src, babylon_luts.TS_PATH))
    try:
        _, w, h, texels = babylon_luts.decoded_texels(ts)
    except (babylon_luts.LutError, khronos_luts.PngError) as e:
        raise CheckError(str(e))
    raw = os.path.join(workdir, "babylon_brdf.f32")
    with open(raw, "wb") as f:
        for t in texels:
            f.write(struct.pack("<3f", *(struct.unpack("<e", struct.pack("<H", b))[0] for b in t)))
    return ("struct ec_rgb_texture {\n"
            "  int w = 0, h = 0;\n"
            "  std::vector<float> t;  // row-major rgb, row 0 = v 0 (invertY = false)\n"
            "  vec3 at(int x, int y) const {\n"
            "    x = x < 0 ? 0 : (x >= w ? w - 1 : x); y = y < 0 ? 0 : (y >= h ? h - 1 : y);\n"
            "    const float* q = &t[(size_t(y) * size_t(w) + size_t(x)) * 3]; return vec3(q[0], q[1], q[2]); }\n"
            "  vec4 sample(vec2 uv) const {  // BILINEAR, CLAMP\n"
            "    real x = uv.x * real(w) - real(0.5), y = uv.y * real(h) - real(0.5);\n"
            "    real x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;\n"
            "    int i = int(x0), j = int(y0);\n"
            "    vec3 a = glm::mix(at(i, j), at(i + 1, j), fx), b = glm::mix(at(i, j + 1), at(i + 1, j + 1), fx);\n"
            "    return vec4(glm::mix(a, b, fy), real(1)); }\n"
            "};\n"
            "static ec_rgb_texture ec_load_rgb(const char* path, int w, int h) {\n"
            "  ec_rgb_texture s; s.w = w; s.h = h; s.t.resize(size_t(w) * size_t(h) * 3);\n"
            "  FILE* f = std::fopen(path, \"rb\");\n"
            "  if (!f || std::fread(s.t.data(), 4, s.t.size(), f) != s.t.size()) {\n"
            "    std::fprintf(stderr, \"cannot read %%s\\n\", path); std::exit(2); }\n"
            "  std::fclose(f); return s; }\n"
            "static const ec_rgb_texture ec_brdf_texture = ec_load_rgb(%s, %d, %d);\n" % (json.dumps(raw), w, h))


def babylon_text(src, float64):
    """The function libraries, then ec_babylon_body(): the glue's stages around the body blocks."""
    funcs = "\n".join(babylon_read(src, n) for n in BABYLON_FUNCTION_FILES)
    body = [babylon_read(src, n) for n in BABYLON_BODY_FILES]

    def stage(k):
        return '#define EC_BABYLON_STAGE %d\n#include "babylon.inc"\n#undef EC_BABYLON_STAGE\n' % k
    text = (babylon_cpp(funcs, float64) + "\nstatic void ec_babylon_body() {\n" + stage(1) +
            babylon_cpp(body[0], float64) + "\n" + stage(2) + babylon_cpp(body[1], float64) + "\n" +
            babylon_cpp(body[2], float64) + "\n" + stage(3) + "}\n")
    macros = sorted(set(re.findall(r"(?m)^[ \t]*#define\s+(\w+)", text)) - {"EC_BABYLON_STAGE"})
    return text, macros


def build_babylon(src, workdir, float64=False):
    text, macros = babylon_text(src, float64)
    macros += [k for k, _ in BABYLON_DEFINES] + [n for names in BABYLON_EXTENSIONS for n in names]
    exe = compile_variants("babylon", text, "babylon.inc", "babylon.inc", babylon_defines, macros, workdir,
                           extra=babylon_brdf_texture(src, workdir), float64=float64)
    import babylon_luts
    return [exe], [BABYLON_SHADERS + "/" + n for n in BABYLON_FUNCTION_FILES + BABYLON_BODY_FILES] + [
        babylon_luts.TS_PATH]


# Babylon's image-based light: the function files of the direct check, then the blocks that read
# the environment (pbrBlockReflection's reflectionBlock, sheenBlock, clearcoatBlock), and as the
# body pbr.fragment.fx's order from pbrBlockReflectance0 to pbrBlockFinalColorComposition, with no
# light in the loop (docs/profiles.md, "Checked against the engines' IBL code").
BABYLON_IBL_FUNCTION_FILES = BABYLON_FUNCTION_FILES + ["pbrBlockReflection.fx", "pbrBlockSheen.fx",
                                                       "pbrBlockClearcoat.fx"]
BABYLON_IBL_BODY_FILES = ["pbrBlockReflectance0.fx", "pbrBlockReflectance.fx", "pbrBlockFinalLitComponents.fx",
                          "pbrBlockFinalColorComposition.fx"]
# The defines PBRMaterial adds for a scene environment: a prefiltered float cube (no RGBD, no
# lod in alpha), irradiance from its spherical harmonics in the fragment, and
# PBRBRDFConfiguration's MIX_IBL_RADIANCE_WITH_IRRADIANCE.
BABYLON_IBL_DEFINES = [("REFLECTION", ""), ("REFLECTIONMAP_3D", ""), ("REFLECTIONMAP_CUBIC", ""),
                       ("USESPHERICALFROMREFLECTIONMAP", ""), ("SPHERICAL_HARMONICS", ""), ("LODBASEDMICROSFURACE", ""),
                       ("NORMAL", ""), ("MIX_IBL_RADIANCE_WITH_IRRADIANCE", "")]


def babylon_ibl_defines(v):
    """The direct check's defines less the light, plus the environment's; ANISOTROPIC left out (its
    bent normal only turns the reflection vector, which a uniform environment cannot show)."""
    direct = [d for d in babylon_defines(v) if d[0] not in ("LIGHT0", "DIRLIGHT0", "ANISOTROPIC")]
    return direct + BABYLON_IBL_DEFINES


def babylon_ibl_text(src, float64):
    funcs = "\n".join(babylon_read(src, n) for n in BABYLON_IBL_FUNCTION_FILES)
    body = [babylon_read(src, n) for n in BABYLON_IBL_BODY_FILES]
    # Functions of files the check does not compile (pbrIBLFunctions, reflectionFunction,
    # harmonicsFunctions): the glue answers them unless the checkout's compiled files define them.
    have = ["#define EC_BABYLON_HAS_%s" % n.upper() for n in ["getLodFromAlphaG", "computeReflectionCoords"]
            if re.search(r"\b%s\s*\(\s*(?:in\s+)?float\s" % n if n == "getLodFromAlphaG" else
                         r"\bvec3\s+%s\s*\(" % n, funcs)]

    def stage(k):
        return '#define EC_BABYLON_IBL_STAGE %d\n#include "babylon_ibl.inc"\n#undef EC_BABYLON_IBL_STAGE\n' % k
    parts = ["\n".join(have), stage(0), babylon_cpp(funcs, float64),
             "static vec3 ec_babylon_ibl_body() {", stage(1), babylon_cpp(body[0], float64), stage(2),
             babylon_cpp(body[1], float64), stage(3), babylon_cpp(body[2], float64), stage(4),
             babylon_cpp(body[3], float64), stage(5), "}"]
    text = "\n".join(parts) + "\n"
    macros = sorted(set(re.findall(r"(?m)^[ \t]*#define\s+(\w+)", text)) - {"EC_BABYLON_IBL_STAGE"})
    return text, macros


def build_babylon_ibl(src, workdir, float64=False):
    text, macros = babylon_ibl_text(src, float64)
    macros += [k for k, _ in BABYLON_DEFINES + BABYLON_IBL_DEFINES] + [n for names in BABYLON_EXTENSIONS for n in names]
    exe = compile_variants("babylon_ibl", text, "babylon_ibl.inc", "babylon_ibl.inc", babylon_ibl_defines, macros,
                           workdir, extra='#include "ibl.hpp"\n' + babylon_brdf_texture(src, workdir), float64=float64)
    import babylon_luts
    return [exe], [BABYLON_SHADERS + "/" + n for n in BABYLON_IBL_FUNCTION_FILES + BABYLON_IBL_BODY_FILES] + [
        babylon_luts.TS_PATH]
