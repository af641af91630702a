// checkMaterialKeys (material_keys.hpp): the key tables of the glTF 2.0 material schema and of
// the KHR_materials_* extensions, the registry of real KHR_/EXT_ names, and the walk that reports
// what the readers would otherwise skip without a word.
#include "model/material_keys.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "brdfcl/error.hpp"
#include "io/messages.hpp"
#include "io/option_style.hpp"

namespace brdfcl::detail {
namespace {

using json = nlohmann::json;
using Names = std::vector<std::string_view>;
using Report = std::function<void(const std::string&)>;

const Names kMaterialKeys = {"name",           "extensions",       "extras",          "pbrMetallicRoughness",
                             "normalTexture",  "occlusionTexture", "emissiveTexture", "emissiveFactor",
                             "alphaMode",      "alphaCutoff",      "doubleSided"};
const Names kMaterialTextures = {"normalTexture", "occlusionTexture", "emissiveTexture"};
const Names kPbrKeys = {"baseColorFactor", "baseColorTexture", "metallicFactor",      "roughnessFactor",
                        "metallicRoughnessTexture", "extensions", "extras"};
const Names kPbrTextures = {"baseColorTexture", "metallicRoughnessTexture"};
// textureInfo, normalTextureInfo (scale) and occlusionTextureInfo (strength) as one set: a scale
// on the wrong slot is harmless, and the readers look only where the schema puts them.
const Names kTextureInfoKeys = {"index", "texCoord", "scale", "strength", "extensions", "extras"};

struct Extension {
  std::string_view name;
  Names keys;      // besides extensions and extras
  Names textures;  // the keys among them that hold a textureInfo
};

const Extension kSheen{"KHR_materials_sheen",
                       {"sheenColorFactor", "sheenColorTexture", "sheenRoughnessFactor", "sheenRoughnessTexture"},
                       {"sheenColorTexture", "sheenRoughnessTexture"}};
// The experimental draft's keys, sheenFactor included: the materials reader takes it for intensityFactor.
const Extension kDraftSheen{"KHR_materials_sheen",
                            {"sheenColorFactor", "sheenColorTexture", "sheenRoughnessFactor", "sheenRoughnessTexture",
                             "intensityFactor", "sheenFactor", "colorFactor", "colorIntensityTexture"},
                            {"sheenColorTexture", "sheenRoughnessTexture", "colorIntensityTexture"}};
const Extension kClearcoat{"KHR_materials_clearcoat",
                           {"clearcoatFactor", "clearcoatTexture", "clearcoatRoughnessFactor",
                            "clearcoatRoughnessTexture", "clearcoatNormalTexture"},
                           {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"}};
const Extension kAnisotropy{"KHR_materials_anisotropy",
                            {"anisotropyStrength", "anisotropyRotation", "anisotropyTexture"},
                            {"anisotropyTexture"}};
const Extension kEmissiveStrength{"KHR_materials_emissive_strength", {"emissiveStrength"}, {}};
// Read from materials files for the engine profiles (docs/profiles.md; spec's f has no IOR input).
const Extension kIor{"KHR_materials_ior", {"ior"}, {}};

// Ratified material extensions that f has no input for, with what each would change. Only the
// materials file reports them: the glTF loader already names them once from extensionsUsed.
struct LeftOut {
  std::string_view name, why;
};
const LeftOut kLeftOut[] = {
    {"KHR_materials_specular",
     "brdfcl's f has no specular strength or color input (dielectric F0 stays 0.04, F90 stays 1)"},
    {"KHR_materials_transmission", "brdfcl's f is a reflection BRDF; transmitted light is not modelled"},
    {"KHR_materials_volume", "brdfcl's f is a surface BRDF; volume thickness and attenuation are not modelled"},
    {"KHR_materials_iridescence", "brdfcl's f has no thin-film iridescence term"},
    {"KHR_materials_emissive_strength", "emission is not part of f; emissiveFactor is kept as written"},
    {"KHR_materials_dispersion", "dispersion acts on transmission, which brdfcl's f does not model"},
    {"KHR_materials_diffuse_transmission",
     "brdfcl's f is a reflection BRDF; diffuse transmission is not modelled"},
    {"KHR_materials_unlit", "brdfcl's f is the lit metallic-roughness BRDF; the material is evaluated as lit"},
    {"KHR_materials_pbrSpecularGlossiness",
     "the archived specular-glossiness model is not read; f uses pbrMetallicRoughness (defaults if absent)"},
    {"KHR_materials_variants",
     "KHR_materials_variants belongs at the document's top level and in mesh primitives, not in a material"},
};

// Real KHR_/EXT_ extensions (Khronos registry: ratified, archived and multi-vendor): a name
// among these is never taken for a typo, wherever it appears.
const Names kRegistry = {
    "KHR_materials_sheen", "KHR_materials_clearcoat", "KHR_materials_anisotropy", "KHR_materials_ior",
    "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_iridescence",
    "KHR_materials_emissive_strength", "KHR_materials_dispersion", "KHR_materials_diffuse_transmission",
    "KHR_materials_unlit", "KHR_materials_pbrSpecularGlossiness", "KHR_materials_variants",
    "KHR_texture_transform", "KHR_texture_basisu", "KHR_draco_mesh_compression", "KHR_mesh_quantization",
    "KHR_meshopt_compression", "KHR_lights_punctual", "KHR_animation_pointer", "KHR_xmp_json_ld", "KHR_xmp",
    "KHR_techniques_webgl", "KHR_node_visibility", "KHR_node_selectability", "KHR_node_hoverability",
    "KHR_interactivity", "KHR_accessor_float64", "EXT_meshopt_compression", "EXT_mesh_gpu_instancing",
    "EXT_lights_image_based", "EXT_lights_ies", "EXT_texture_webp", "EXT_texture_avif", "EXT_mesh_manifold",
    "EXT_texture_video"};

bool contains(const Names& names, std::string_view s) { return std::find(names.begin(), names.end(), s) != names.end(); }

// Vendors other than Khronos and EXT own their prefixes: brdfcl cannot tell their typos.
bool khronosPrefix(std::string_view name) {
  auto upper = [&](std::size_t n) {
    std::string s(name.substr(0, n));
    for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
  };
  return upper(4) == "KHR_" || upper(4) == "EXT_";
}

std::string suggestion(std::string_view word, const Names& candidates) {
  const std::string near = closestName(word, candidates);
  return near.empty() ? std::string() : "; did you mean " + near + "?";
}

std::string join(const Names& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

class Checker {
 public:
  Checker(MaterialKeyReader reader, const Report& report) : reader_(reader), report_(report) {}

  void material(const json& m, const std::string& path) const {
    if (!m.is_object()) return;
    keys(m, path, kMaterialKeys, kMaterialTextures, false);
    if (const auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end() && pbr->is_object())
      keys(*pbr, path + ".pbrMetallicRoughness", kPbrKeys, kPbrTextures);
    if (const auto ext = m.find("extensions"); ext != m.end() && ext->is_object())
      materialExtensions(*ext, path + ".extensions");
  }

 private:
  static std::string at(const std::string& path, const std::string& key) { return path + "." + printable(key, 80); }

  // Every glTF object may have extensions and extras; a material's own extensions are
  // materialExtensions' business (nested = false).
  void keys(const json& obj, const std::string& path, const Names& known, const Names& textures,
            bool nested = true) const {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      const std::string& key = it.key();
      if (key == "extras") continue;
      if (key == "extensions") {
        if (nested) nestedExtensions(*it, at(path, key));
      } else if (contains(textures, key)) {
        if (it->is_object()) keys(*it, at(path, key), kTextureInfoKeys, {});
      } else if (!contains(known, key)) {
        const std::string near = suggestion(key, known);
        Names listed;
        for (const auto& k : known)
          if (k != "extensions" && k != "extras") listed.push_back(k);
        report_(at(path, key) + ": unknown key, ignored" +
                (near.empty() ? " (known here: " + join(listed) + ", extensions, extras)" : near));
      }
    }
  }

  // An "extensions" object below the material's own: only a misspelt Khronos name is reported.
  void nestedExtensions(const json& ext, const std::string& path) const {
    if (!ext.is_object()) return;
    for (auto it = ext.begin(); it != ext.end(); ++it)
      if (khronosPrefix(it.key()) && !contains(kRegistry, it.key()))
        report_(at(path, it.key()) + ": unknown extension, ignored" + suggestion(it.key(), kRegistry));
  }

  void materialExtensions(const json& ext, const std::string& path) const {
    const bool file = reader_ == MaterialKeyReader::MaterialsFile;
    std::vector<const Extension*> evaluated{file ? &kDraftSheen : &kSheen, &kClearcoat, &kAnisotropy};
    if (!file) evaluated.push_back(&kEmissiveStrength);
    if (file) evaluated.push_back(&kIor);
    for (auto it = ext.begin(); it != ext.end(); ++it) {
      const std::string& name = it.key();
      const std::string p = at(path, name);
      const auto e = std::find_if(evaluated.begin(), evaluated.end(), [&](const Extension* x) { return x->name == name; });
      if (e != evaluated.end()) {
        if (it->is_object()) {
          Names known = (*e)->keys;
          known.insert(known.end(), {"extensions", "extras"});
          keys(*it, p, known, (*e)->textures);
        }
        continue;
      }
      const auto left = std::find_if(std::begin(kLeftOut), std::end(kLeftOut), [&](const LeftOut& l) { return l.name == name; });
      if (file && left != std::end(kLeftOut)) {
        report_(p + ": ignored: " + std::string(left->why));
        continue;
      }
      if (khronosPrefix(name) && !contains(kRegistry, name)) {
        std::string near = suggestion(name, kRegistry);
        if (near.empty()) {
          Names names;
          for (const Extension* x : evaluated) names.push_back(x->name);
          near = " (brdfcl reads " + join(names) + ")";
        }
        report_(p + ": unknown extension, ignored" + near);
      }
    }
  }

  MaterialKeyReader reader_;
  const Report& report_;
};

}  // namespace

void checkMaterialKeys(const json& material, const std::string& path, MaterialKeyReader reader, const Report& report) {
  Checker(reader, report).material(material, path);
}

std::string strictError(std::string finding) {
  if (const auto at = finding.find(", ignored"); at != std::string::npos) finding.erase(at, 9);
  if (const auto at = finding.find(": ignored: "); at != std::string::npos) finding.replace(at, 11, ": not evaluated: ");
  return finding + " (an error under " + flagName("--strict") + ")";
}

}  // namespace brdfcl::detail
