# MaterialX (profile materialx): its genglsl libraries composed as gltf_pbr.mtlx's nodegraph and
# compiled as C++, for the direct light and the image-based light.
import os
import re
import subprocess
from .common import CXX_FLAGS, CheckError, GLUE, progress
from .glsl import FLOAT_LITERAL, find_function, glsl_to_cpp


MATERIALX_FILES = ["libraries/stdlib/genglsl/lib/mx_math.glsl",
                   "libraries/pbrlib/genglsl/lib/mx_closure_type.glsl",
                   "libraries/pbrlib/genglsl/lib/mx_microfacet.glsl",
                   "libraries/pbrlib/genglsl/lib/mx_microfacet_specular.glsl",
                   "libraries/pbrlib/genglsl/lib/mx_microfacet_sheen.glsl",
                   "libraries/pbrlib/genglsl/lib/mx_microfacet_diffuse.glsl",
                   "libraries/pbrlib/genglsl/mx_oren_nayar_diffuse_bsdf.glsl",
                   "libraries/pbrlib/genglsl/mx_generalized_schlick_bsdf.glsl",
                   "libraries/pbrlib/genglsl/mx_dielectric_bsdf.glsl",
                   "libraries/pbrlib/genglsl/mx_sheen_bsdf.glsl",
                   "libraries/pbrlib/genglsl/mx_layer_bsdf.glsl",
                   "libraries/pbrlib/genglsl/mx_mix_bsdf.glsl",
                   "libraries/pbrlib/genglsl/mx_roughness_anisotropy.glsl",
                   "libraries/stdlib/genglsl/mx_rotate_vector3.glsl"]
MATERIALX_GRAPH = "libraries/bxdf/gltf_pbr.mtlx"

# The BSDF part of gltf_pbr.mtlx's nodegraph as scripts/engine_check/materialx.inc composes it:
# node -> (category, {input: source}); a source is "=value", "@interface" or "node".
MATERIALX_NODES = {
    "one_minus_ior": ("subtract", {"in1": "=1", "in2": "@ior"}),
    "one_plus_ior": ("add", {"in1": "=1", "in2": "@ior"}),
    "ior_div": ("divide", {"in1": "one_minus_ior", "in2": "one_plus_ior"}),
    "dielectric_f0_from_ior": ("multiply", {"in1": "ior_div", "in2": "ior_div"}),
    "dielectric_f0_from_ior_specular_color": ("multiply", {"in1": "@specular_color", "in2": "dielectric_f0_from_ior"}),
    "clamped_dielectric_f0_from_ior_specular_color": ("min", {"in1": "dielectric_f0_from_ior_specular_color",
                                                              "in2": "=1"}),
    "dielectric_f0": ("multiply", {"in1": "clamped_dielectric_f0_from_ior_specular_color", "in2": "@specular"}),
    "dielectric_f90": ("multiply", {"in1": "=1, 1, 1", "in2": "@specular"}),
    "roughness_uv": ("combine2", {"in1": "clamped_at", "in2": "clamped_ab"}),
    "clamped_at": ("clamp", {"in": "at", "low": "=0.00001", "high": "=1.0"}),
    "clamped_ab": ("clamp", {"in": "alpha_roughness", "low": "=0.00001", "high": "=1.0"}),
    "alpha_roughness": ("multiply", {"in1": "@roughness", "in2": "@roughness"}),
    "strength_2": ("multiply", {"in1": "@anisotropy_strength", "in2": "@anisotropy_strength"}),
    "at": ("mix", {"fg": "=1", "bg": "alpha_roughness", "mix": "strength_2"}),
    "diffuse_bsdf": ("oren_nayar_diffuse_bsdf", {"color": "@base_color", "normal": "@normal"}),
    "transmission_bsdf": ("dielectric_bsdf", {"weight": "=1", "tint": "@base_color", "ior": "@ior",
                                              "roughness": "roughness_uv", "normal": "@normal",
                                              "tangent": "selected_tangent", "scatter_mode": "=T"}),
    "reflection_bsdf": ("generalized_schlick_bsdf", {"color0": "dielectric_f0", "color90": "dielectric_f90",
                                                     "roughness": "roughness_uv", "normal": "@normal",
                                                     "tangent": "selected_tangent", "scatter_mode": "=R"}),
    "transmission_mix": ("mix", {"bg": "diffuse_bsdf", "fg": "transmission_bsdf", "mix": "@transmission"}),
    "tf_reflection_bsdf": ("generalized_schlick_bsdf", {"color0": "dielectric_f0", "color90": "dielectric_f90",
                                                        "roughness": "roughness_uv", "normal": "@normal",
                                                        "tangent": "selected_tangent", "scatter_mode": "=R",
                                                        "thinfilm_thickness": "@iridescence_thickness",
                                                        "thinfilm_ior": "@iridescence_ior"}),
    "mix_iridescent_dielectric_reflection": ("mix", {"bg": "reflection_bsdf", "fg": "tf_reflection_bsdf",
                                                     "mix": "@iridescence"}),
    "iridescent_dielectric_bsdf": ("layer", {"top": "mix_iridescent_dielectric_reflection",
                                             "base": "transmission_mix"}),
    "metal_bsdf": ("generalized_schlick_bsdf", {"color0": "@base_color", "color90": "=1, 1, 1",
                                                "roughness": "roughness_uv", "normal": "@normal",
                                                "tangent": "selected_tangent"}),
    "tf_metal_bsdf": ("generalized_schlick_bsdf", {"color0": "@base_color", "color90": "=1, 1, 1",
                                                   "roughness": "roughness_uv", "normal": "@normal",
                                                   "tangent": "selected_tangent",
                                                   "thinfilm_thickness": "@iridescence_thickness",
                                                   "thinfilm_ior": "@iridescence_ior"}),
    "mix_iridescent_metal_bsdf": ("mix", {"bg": "metal_bsdf", "fg": "tf_metal_bsdf", "mix": "@iridescence"}),
    "base_mix": ("mix", {"bg": "iridescent_dielectric_bsdf", "fg": "mix_iridescent_metal_bsdf", "mix": "@metallic"}),
    "sheen_intensity": ("maxcomponent", {"in": "@sheen_color"}),
    "sheen_roughness_sq": ("multiply", {"in1": "@sheen_roughness", "in2": "@sheen_roughness"}),
    "sheen_color_normalized": ("divide", {"in1": "@sheen_color", "in2": "sheen_intensity"}),
    "sheen_bsdf": ("sheen_bsdf", {"weight": "sheen_intensity", "color": "sheen_color_normalized",
                                  "roughness": "sheen_roughness_sq", "normal": "@normal"}),
    "sheen_layer": ("layer", {"top": "sheen_bsdf", "base": "base_mix"}),
    "clearcoat_roughness_uv": ("roughness_anisotropy", {"roughness": "@clearcoat_roughness"}),
    "clearcoat_bsdf": ("dielectric_bsdf", {"weight": "@clearcoat", "roughness": "clearcoat_roughness_uv",
                                           "ior": "=1.5", "normal": "@clearcoat_normal", "tangent": "@tangent"}),
    "clearcoat_layer": ("layer", {"top": "clearcoat_bsdf", "base": "sheen_layer"}),
    "rad_2_deg": ("multiply", {"in1": "@anisotropy_rotation", "in2": "=-57.295780"}),
    "rotate_tangent": ("rotate3d", {"in": "@tangent", "amount": "rad_2_deg", "axis": "@normal"}),
    "normalize_tangent": ("normalize", {"in": "rotate_tangent"}),
    "abs_anisotropy_rotation": ("absval", {"in": "@anisotropy_rotation"}),
    "selected_tangent": ("ifgreater", {"value1": "abs_anisotropy_rotation", "value2": "=0.0",
                                       "in1": "normalize_tangent", "in2": "@tangent"}),
    "shader_constructor": ("surface", {"bsdf": "clearcoat_layer", "edf": "emission", "opacity": "opacity"}),
}
# Nodedef defaults the glue relies on (input -> value); a glTF material without the extension
# leaves these inputs at them.
MATERIALX_DEFAULTS = {"specular": "1", "specular_color": "1, 1, 1", "transmission": "0", "iridescence": "0",
                      "iridescence_ior": "1.3", "iridescence_thickness": "100", "ior": "1.5"}


def materialx_graph_drift(path):
    """Where gltf_pbr.mtlx's nodegraph differs from the one materialx.inc composes (empty: none)."""
    import xml.etree.ElementTree as ET
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        return ["cannot read %s: %s" % (path, e)]
    nd = root.find("nodedef[@name='ND_gltf_pbr_surfaceshader']")
    ng = root.find("nodegraph[@name='IMPL_gltf_pbr_surfaceshader']")
    if nd is None or ng is None:
        return ["no ND_gltf_pbr_surfaceshader nodedef or IMPL_gltf_pbr_surfaceshader nodegraph"]
    out = []
    defaults = {i.get("name"): i.get("value") for i in nd.findall("input")}
    for k, v in MATERIALX_DEFAULTS.items():
        if defaults.get(k) != v:
            out.append("input %s defaults to %s, not %s" % (k, defaults.get(k), v))
    nodes = {n.get("name"): n for n in ng if n.get("name")}
    for name, (cat, inputs) in MATERIALX_NODES.items():
        n = nodes.get(name)
        if n is None:
            out.append("no node %s" % name)
            continue
        if n.tag != cat:
            out.append("%s is a <%s>, not a <%s>" % (name, n.tag, cat))
        have = {}
        for i in n.findall("input"):
            src = i.get("nodename") or ("@" + i.get("interfacename") if i.get("interfacename") else
                                        "=" + str(i.get("value")))
            have[i.get("name")] = src
        if have != inputs:
            out.append("%s's inputs are %s" % (name, ", ".join("%s=%s" % kv for kv in sorted(have.items()))))
    return out


MATERIALX_IBL_FILES = ["libraries/pbrlib/genglsl/lib/mx_environment_prefilter.glsl"]
# The environment uniforms the generator binds (HwConstants); the glue's lookup answers them all.
MATERIALX_ENV_TOKENS = {"envMatrix": "mat4(1.0)", "envRadianceMips": "10", "envRadiance": "ec_env_radiance",
                        "envIrradiance": "ec_env_irradiance", "envLightIntensity": "1.0"}


def materialx_text(src, files, float64):
    parts = []
    for name in files:
        p = os.path.join(src, name)
        if not os.path.exists(p):
            raise CheckError("%s has no %s" % (src, name))
        with open(p, encoding="utf-8") as f:
            # The files are pasted in dependency order, so their own #includes go.
            parts.append(re.sub(r'(?m)^[ \t]*#include\s*[<"][^>"]+[>"].*$', "", f.read()))
    text = "\n".join(parts)
    # Tokens the shader generator substitutes (GlslShaderGenerator, HwConstants).
    text = text.replace("$closureDataConstructor", "ClosureData{closureType, L, V, N, P, occlusion}")
    text = text.replace("$texSamplerSignature", "sampler2D_stub tex_sampler").replace(
        "$texSamplerSampler2D", "tex_sampler").replace("$albedoTable", "ec_albedo_table")
    text = re.sub(r"\$(\w+)", lambda m: MATERIALX_ENV_TOKENS.get(m.group(1), m.group(0)), text)
    if not float64:
        text = "\n".join(FLOAT_LITERAL.sub(lambda m: m.group(1) + "f", ln) if ln.lstrip().startswith("#define")
                         else ln for ln in text.split("\n"))
    text = glsl_to_cpp(text, float64)
    # The glue answers the texture read itself (a uniform environment, or nothing).
    f = find_function(text, "mx_latlong_map_lookup")
    if f:
        text = text[:f[0]] + text[f[2]:]
    return text


def materialx_compile(name, text, workdir, float64, defines=()):
    cpp = ["#define EC_FLOAT64" if float64 else ""] + ["#define %s" % d for d in defines] + [
        '#include <cstring>', '#include "glsl.hpp"', '#include "driver.hpp"', "namespace mx {", "#undef M_PI",
        '#include "materialx.inc"', "#define float double" if float64 else "", text,
        "#undef float" if float64 else "", '#define EC_MATERIALX_AFTER\n#include "materialx.inc"',
        "}  // namespace mx", "static ec::RunFn const ec_variants[16] = {%s};" % ", ".join(["mx::ec_run"] * 16),
        "int main(int argc, char** argv) { return ec::run(ec_variants, argc, argv); }"]
    path = os.path.join(workdir, name + ".cpp")
    with open(path, "w") as fh:
        fh.write("\n".join(cpp) + "\n")
    exe = os.path.join(workdir, name)
    progress("compiling %s" % name)
    r = subprocess.run(["g++"] + CXX_FLAGS + ["-I", GLUE, path, "-o", exe], capture_output=True, text=True)
    if r.returncode != 0:
        raise CheckError("g++ failed on materialx's code (%s):\n%s" % (path, r.stderr[-4000:]))
    return exe


def build_materialx(src, workdir, float64=False):
    """The direct light: CLOSURE_TYPE_REFLECTION under one directional light."""
    for d in materialx_graph_drift(os.path.join(src, MATERIALX_GRAPH)):
        print("materialx: gltf_pbr.mtlx differs from the nodegraph the glue composes: %s" % d)
    exe = materialx_compile("materialx", materialx_text(src, MATERIALX_FILES, float64), workdir, float64)
    return [exe], MATERIALX_FILES + [MATERIALX_GRAPH]


def build_materialx_ibl(src, workdir, float64=False):
    """The environment term: CLOSURE_TYPE_INDIRECT through mx_environment_prefilter, which the
    generator emits after the microfacet library, before the BSDFs."""
    for d in materialx_graph_drift(os.path.join(src, MATERIALX_GRAPH)):
        print("materialx: gltf_pbr.mtlx differs from the nodegraph the glue composes: %s" % d)
    k = MATERIALX_FILES.index("libraries/pbrlib/genglsl/lib/mx_microfacet_specular.glsl") + 1
    files = MATERIALX_FILES[:k] + MATERIALX_IBL_FILES + MATERIALX_FILES[k:]
    exe = materialx_compile("materialx-ibl", materialx_text(src, files, float64), workdir, float64, ["EC_MX_INDIRECT"])
    return [exe], files + [MATERIALX_GRAPH]
