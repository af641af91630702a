# The glTF Sample Renderer (profile khronos): its pbr.frag and includes as C++, for the direct
# light and the image-based light, with the checkout's sheen E table.
import json
import os
import re
import zlib
import khronos_luts  # scripts/khronos_luts.py: the PNG reader the table came from
from .common import CheckError
from .glsl import compile_variants, glsl_to_cpp, hook, resolve_includes


def debug_macros(text):
    names = sorted(set(re.findall(r"\b(DEBUG_\w+|ALPHAMODE_\w+)\b", text)))
    out = [("DEBUG", "DEBUG_NONE"), ("ALPHAMODE", "ALPHAMODE_OPAQUE")]
    out += [(n, str(i + 1)) for i, n in enumerate(names)]
    return out


KHRONOS_EXTENSIONS = ["MATERIAL_SHEEN", "MATERIAL_CLEARCOAT", "MATERIAL_ANISOTROPY", "MATERIAL_IOR"]


def khronos_text(src, skip):
    """pbr.frag with its includes (but `skip`) as C++."""
    frag = os.path.join(src, "source", "Renderer", "shaders", "pbr.frag")
    if not os.path.exists(frag):
        raise CheckError("%s has no source/Renderer/shaders/pbr.frag" % src)
    return resolve_includes(frag, skip)


def khronos_defines(text, light):
    """The variant's #defines: the metallic-roughness material lit by `light` (USE_PUNCTUAL or
    USE_IBL), and one bit of the variant number per extension present."""
    dbg = debug_macros(text)

    def defines(v):
        d = [("MATERIAL_METALLICROUGHNESS", ""), (light, ""), ("LIGHT_COUNT", "1"), ("LINEAR_OUTPUT", "")]
        d += dbg
        d += [(name, "") for bit, name in enumerate(KHRONOS_EXTENSIONS) if v >> bit & 1]
        return d
    return defines


def khronos_sheen_e_lut(src, workdir):
    """C++ defining ec_sheen_e_lut: the checkout's own lut_sheen_E.png as the 8-bit texels of its
    WebGL upload (the renderer's u_SheenELUT, in the direct and the image-based light alike)."""
    png = os.path.join(src, khronos_luts.PNG_PATH)
    if not os.path.exists(png):
        raise CheckError("%s has no %s" % (src, khronos_luts.PNG_PATH))
    try:
        w, h, texels = khronos_luts.read_texels(png)
    except khronos_luts.PngError as e:
        raise CheckError(str(e))
    except (OSError, zlib.error) as e:
        raise CheckError("cannot read %s: %s" % (png, e))
    raw = os.path.join(workdir, "lut_sheen_E.u8")
    with open(raw, "wb") as f:
        f.write(texels)
    return ("static sampler2D ec_load_unorm8(const char* path, int w, int h) {\n"
            "  sampler2D s; s.w = w; s.h = h;\n"
            "  std::vector<unsigned char> b(size_t(w) * size_t(h));\n"
            "  FILE* f = std::fopen(path, \"rb\");\n"
            "  if (!f || std::fread(b.data(), 1, b.size(), f) != b.size()) {\n"
            "    std::fprintf(stderr, \"cannot read %%s\\n\", path); std::exit(2); }\n"
            "  std::fclose(f);\n"
            "  for (unsigned char t : b) s.texels.push_back(float(t) / 255.0f);  // unorm8 as a GPU converts it\n"
            "  return s; }\n"
            "static const sampler2D ec_sheen_e_lut = ec_load_unorm8(%s, %d, %d);\n" % (json.dumps(raw), w, h))


def build_khronos(src, workdir, float64=False):
    text = khronos_text(src, {"tonemapping.glsl", "textures.glsl", "ibl.glsl", "iridescence.glsl"})
    text = glsl_to_cpp(text, float64)
    for fn, lobe in [("BRDF_lambertian", "ec::DIFFUSE"), ("BRDF_specularGGX", "ec::SPECULAR"),
                     ("BRDF_specularGGXAnisotropy", "ec::SPECULAR"), ("getPunctualRadianceSheen", "ec::SHEEN"),
                     ("getPunctualRadianceClearCoat", "ec::CLEARCOAT")]:
        text, ok = hook(text, fn, lobe)
        if not ok and fn != "BRDF_specularGGXAnisotropy":
            raise CheckError("no definition of %s in %s's shaders" % (fn, src))
    exe = compile_variants("khronos", text, "khronos.inc", "khronos.inc", khronos_defines(text, "USE_PUNCTUAL"),
                           KHRONOS_EXTENSIONS, workdir, extra=khronos_sheen_e_lut(src, workdir), float64=float64)
    files = ["source/Renderer/shaders/" + n for n in
             ["pbr.frag", "brdf.glsl", "material_info.glsl", "functions.glsl", "punctual.glsl"]]
    return [exe], files + [khronos_luts.PNG_PATH]


def build_khronos_ibl(src, workdir, float64=False):
    text = khronos_text(src, {"tonemapping.glsl", "textures.glsl", "iridescence.glsl"})
    if "USE_IBL" not in text or "getIBLRadianceGGX" not in text:
        raise CheckError("%s's pbr.frag has no USE_IBL block (or ibl.glsl is missing)" % src)
    text = glsl_to_cpp(text, float64)
    exe = compile_variants("khronos_ibl", text, "khronos_ibl.inc", "khronos_ibl.inc", khronos_defines(text, "USE_IBL"),
                           KHRONOS_EXTENSIONS, workdir, extra='#include "ibl.hpp"\n' + khronos_sheen_e_lut(src, workdir),
                           float64=float64)
    files = ["source/Renderer/shaders/" + n for n in
             ["pbr.frag", "ibl.glsl", "brdf.glsl", "material_info.glsl", "functions.glsl"]]
    return [exe], files + [khronos_luts.PNG_PATH]
