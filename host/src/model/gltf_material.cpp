// readGltfMaterial and checkMaterialFactors (gltf_material.hpp): one table of the material's
// factors (where each sits, its range, the MaterialParams field it fills) read from JSON by the
// reader and checked on a caller's MaterialParams by the evaluator.
#include "model/gltf_material.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "brdfcl/error.hpp"
#include "io/messages.hpp"
#include "model/emissive_factor.hpp"

namespace brdfcl::detail {
namespace {

using json = nlohmann::json;

// Intensity: the draft's intensityFactor, >= 0 and at most kMaxDraftIntensity. Ior:
// KHR_materials_ior's schema, 0 (F0 = 1) or at least 1.
enum class Domain { Unit, NonNegative, Intensity, Finite, Ior };

const char* expectedNumber(Domain d) {
  switch (d) {
    case Domain::Unit:
      return "a number in [0, 1]";
    case Domain::NonNegative:
    case Domain::Intensity:
      return "a number >= 0";
    case Domain::Ior:
      return "0 or a number >= 1";
    case Domain::Finite:
      break;
  }
  return "a finite number";
}

bool inDomain(double d, Domain domain) {
  if (!std::isfinite(d)) return false;
  switch (domain) {
    case Domain::Unit:
      return d >= 0.0 && d <= 1.0;
    case Domain::NonNegative:
    case Domain::Intensity:
      return d >= 0.0;
    case Domain::Ior:
      return d == 0.0 || d >= 1.0;
    case Domain::Finite:
      break;
  }
  return true;
}

// One factor: `key` in its part's object; a number (`length` 1) or a color of `length` numbers,
// of which the first three fill `at` and a fourth the base color's alpha. `field` names it in
// checkMaterialFactors' messages (null: an alias or a value outside MaterialParams, not checked there).
struct Factor {
  const char* key;
  Domain domain;
  std::size_t length;
  float* (*at)(GltfMaterial&);
  const char* field;
};

struct TextureKey {
  const char* key;
  MaterialTexture slot;
  const char* valueKey;  // the textureInfo's own number, or null
};

enum Readers { kFile = 1, kAsset = 2, kBoth = 3 };
enum class Sheen { None, Ratified, Draft };

// Where a part's keys sit: the material object (object and extension null), an object under it
// ("pbrMetallicRoughness"), or an extension object under its "extensions".
struct Part {
  const char* object;
  const char* extension;
  int readers;
  Sheen sheen;
  std::vector<TextureKey> textures;
  std::vector<Factor> factors;
};

#define FIELD(expr) [](GltfMaterial& g) { return &(expr); }

// In reading order (textures of a part first, then its factors); checkMaterialFactors' order too.
const std::vector<Part>& parts() {
  static const std::vector<Part> table = {
      {nullptr, nullptr, kBoth, Sheen::None,
       {{"normalTexture", MaterialTexture::Normal, "scale"},
        {"occlusionTexture", MaterialTexture::Occlusion, "strength"},
        {"emissiveTexture", MaterialTexture::Emissive, nullptr}},
       {}},
      {"pbrMetallicRoughness", nullptr, kBoth, Sheen::None,
       {{"baseColorTexture", MaterialTexture::BaseColor, nullptr},
        {"metallicRoughnessTexture", MaterialTexture::MetallicRoughness, nullptr}},
       {{"baseColorFactor", Domain::Unit, 4, FIELD(g.params.baseColor[0]), "baseColor"},
        {"metallicFactor", Domain::Unit, 1, FIELD(g.params.metallic), "metallic"},
        {"roughnessFactor", Domain::Unit, 1, FIELD(g.params.roughness), "roughness"}}},
      {nullptr, nullptr, kBoth, Sheen::None, {},
       {{"emissiveFactor", Domain::NonNegative, 3, FIELD(g.params.emissive[0]), "emissive"}}},
      {nullptr, "KHR_materials_sheen", kBoth, Sheen::Ratified,
       {{"sheenColorTexture", MaterialTexture::SheenColor, nullptr},
        {"sheenRoughnessTexture", MaterialTexture::SheenRoughness, nullptr}},
       {{"sheenColorFactor", Domain::Unit, 3, FIELD(g.params.sheenColor[0]), "sheenColor"},
        {"sheenRoughnessFactor", Domain::Unit, 1, FIELD(g.params.sheenRoughness), "sheenRoughness"}}},
      // "sheenFactor" is the draft's own example and disable rule for what its table calls
      // intensityFactor: read as that, so the draft's velvet example renders as velvet.
      {nullptr, "KHR_materials_sheen", kFile, Sheen::Draft,
       {{"colorIntensityTexture", MaterialTexture::DraftColorIntensity, nullptr}},
       {{"intensityFactor", Domain::Intensity, 1, FIELD(g.params.draftIntensity), "draftIntensity"},
        {"sheenFactor", Domain::Intensity, 1, FIELD(g.params.draftIntensity), nullptr},
        {"colorFactor", Domain::Unit, 3, FIELD(g.params.draftColor[0]), "draftColor"}}},
      {nullptr, "KHR_materials_clearcoat", kBoth, Sheen::None,
       {{"clearcoatTexture", MaterialTexture::Clearcoat, nullptr},
        {"clearcoatRoughnessTexture", MaterialTexture::ClearcoatRoughness, nullptr},
        {"clearcoatNormalTexture", MaterialTexture::ClearcoatNormal, "scale"}},
       {{"clearcoatFactor", Domain::Unit, 1, FIELD(g.params.clearcoat), "clearcoat"},
        {"clearcoatRoughnessFactor", Domain::Unit, 1, FIELD(g.params.clearcoatRoughness), "clearcoatRoughness"}}},
      {nullptr, "KHR_materials_anisotropy", kBoth, Sheen::None,
       {{"anisotropyTexture", MaterialTexture::Anisotropy, nullptr}},
       {{"anisotropyStrength", Domain::Unit, 1, FIELD(g.params.anisotropyStrength), "anisotropyStrength"},
        {"anisotropyRotation", Domain::Finite, 1, FIELD(g.params.anisotropyRotation), "anisotropyRotation"}}},
      // Read for the engine profiles (docs/profiles.md); the spec profile's f has no IOR input.
      {nullptr, "KHR_materials_ior", kFile, Sheen::None, {}, {{"ior", Domain::Ior, 1, FIELD(g.params.ior), "ior"}}},
      {nullptr, "KHR_materials_emissive_strength", kAsset, Sheen::None, {},
       {{"emissiveStrength", Domain::NonNegative, 1, FIELD(g.emissiveStrength), nullptr}}},
  };
  return table;
}

#undef FIELD

class Reader {
 public:
  Reader(const std::string& path, const GltfMaterialContext& c) : base_(path), c_(c) {}

  GltfMaterial read(const json& m) {
    GltfMaterial out;
    if (const auto n = m.find("name"); n != m.end()) {
      if (!n->is_string()) fail(base_ + ".name", "expected a string, got " + describeJson(*n));
      out.params.name = n->get<std::string>();
    }
    const int reader = c_.reader == MaterialKeyReader::MaterialsFile ? kFile : kAsset;
    const json* extensions = object(m, "extensions", base_ + ".extensions");
    const Sheen sheen = sheenKind(extensions, reader);
    for (const Part& part : parts()) {
      if (!(part.readers & reader) || (part.sheen != Sheen::None && part.sheen != sheen)) continue;
      std::string path = base_;
      const json* obj = &m;
      if (part.object) {
        path += std::string(".") + part.object;
        obj = object(m, part.object, path);
      } else if (part.extension) {
        path += std::string(".extensions.") + part.extension;
        obj = extensions ? object(*extensions, part.extension, path) : nullptr;
      }
      if (!obj) continue;
      if (part.sheen == Sheen::Draft) {
        out.params.draftSheen = true;
        if (obj->contains("intensityFactor") && obj->contains("sheenFactor"))
          fail(path, "has both intensityFactor and sheenFactor (the draft's two names for one value); keep one");
      }
      if (part.extension && std::string(part.extension) == "KHR_materials_anisotropy")
        out.params.anisotropyExtension = true;
      for (const TextureKey& t : part.textures)
        if (obj->contains(t.key) && c_.texture) c_.texture(t.slot, *obj, t.key, path, t.valueKey);
      for (const Factor& f : part.factors)
        if (const auto v = obj->find(f.key); v != obj->end()) factor(*v, path + "." + f.key, f, out);
    }
    alpha(m, out);
    checkMaterialKeys(m, base_, c_.reader, [&](const std::string& finding) {
      if (c_.strict) throw Error(c_.source + ": " + strictError(finding));
      if (c_.warn) c_.warn(c_.source + ": " + finding);
    });
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw Error(c_.source + ": " + path + ": " + message);
  }

  const json* object(const json& parent, const char* key, const std::string& path) const {
    const auto it = parent.find(key);
    if (it == parent.end()) return nullptr;
    if (!it->is_object()) fail(path, "expected an object, got " + describeJson(*it));
    return &*it;
  }

  // The draft and the ratified sheen share a name but not a single key; the keys decide. Only a
  // materials file reads the draft; a glTF asset reports its keys as unknown (checkMaterialKeys).
  Sheen sheenKind(const json* extensions, int reader) const {
    if (reader != kFile || !extensions) return Sheen::Ratified;
    const std::string path = base_ + ".extensions.KHR_materials_sheen";
    const json* s = object(*extensions, "KHR_materials_sheen", path);
    if (!s) return Sheen::Ratified;
    static const char* const draftKeys[] = {"intensityFactor", "sheenFactor", "colorFactor", "colorIntensityTexture"};
    static const char* const ratifiedKeys[] = {"sheenColorFactor", "sheenRoughnessFactor", "sheenColorTexture",
                                               "sheenRoughnessTexture"};
    std::string draftSeen, ratifiedSeen;
    for (const char* k : draftKeys)
      if (s->contains(k)) draftSeen += (draftSeen.empty() ? "" : ", ") + std::string(k);
    for (const char* k : ratifiedKeys)
      if (s->contains(k)) ratifiedSeen += (ratifiedSeen.empty() ? "" : ", ") + std::string(k);
    if (!draftSeen.empty() && !ratifiedSeen.empty())
      fail(path, "mixes draft keys (" + draftSeen + ") with ratified keys (" + ratifiedSeen +
                     "); use either intensityFactor/colorFactor or sheenColorFactor/sheenRoughnessFactor");
    return draftSeen.empty() ? Sheen::Ratified : Sheen::Draft;
  }

  float number(const json& v, const std::string& path, Domain domain) const {
    const char* expected = expectedNumber(domain);
    if (!v.is_number()) fail(path, std::string("expected ") + expected + ", got " + describeJson(v));
    // nlohmann turns overflowing literals such as 1e999 into inf; glTF has no infinities.
    const double d = v.get<double>();
    if (!inDomain(d, domain)) fail(path, std::string("expected ") + expected + ", got " + formatNumber(d));
    if (std::fabs(d) > std::numeric_limits<float>::max())
      fail(path, std::string("expected ") + expected + ", got " + formatNumber(d) + " (too large for float)");
    if (domain == Domain::Intensity && static_cast<float>(d) > kMaxDraftIntensity)
      fail(path, std::string("expected ") + expected + ", got " + formatNumber(d) +
                     " (at most 1e+30: f would overflow float)");
    return static_cast<float>(d);
  }

  void factor(const json& v, const std::string& path, const Factor& f, GltfMaterial& out) const {
    float* at = f.at(out);
    if (f.length == 1) {
      *at = number(v, path, f.domain);
      return;
    }
    // glTF colors are RGB or RGBA arrays; the BRDF reads RGB, the renderer the base color's alpha.
    const std::string expected = "expected an array of " + std::to_string(f.length) + " numbers" +
                                 (f.domain == Domain::Unit          ? " in [0, 1]"
                                  : f.domain == Domain::NonNegative ? " >= 0"
                                                                    : "");
    if (!v.is_array() || v.size() != f.length) fail(path, expected + ", got " + describeJson(v));
    Rgb rgb{};
    for (std::size_t c = 0; c < f.length; ++c) {
      const float x = number(v[c], path + "[" + std::to_string(c) + "]", f.domain);
      if (c < 3) rgb[c] = x;
      else out.baseColorAlpha = x;
    }
    // The schema bounds emissiveFactor to [0, 1]; engines take more (emissive_factor.hpp).
    if (at == &out.params.emissive[0]) rgb = clampEmissiveFactor(rgb, c_.source, path, c_.strict, c_.warn);
    for (std::size_t c = 0; c < 3; ++c) at[c] = rgb[c];
  }

  // What only the renderer reads; a materials file is held to the same schema.
  void alpha(const json& m, GltfMaterial& out) const {
    if (const auto a = m.find("alphaMode"); a != m.end()) {
      const std::string mode = a->is_string() ? a->get<std::string>() : "";
      if (mode == "OPAQUE") out.alphaMode = gltf::AlphaMode::Opaque;
      else if (mode == "MASK") out.alphaMode = gltf::AlphaMode::Mask;
      else if (mode == "BLEND") out.alphaMode = gltf::AlphaMode::Blend;
      else fail(base_ + ".alphaMode", "expected \"OPAQUE\", \"MASK\" or \"BLEND\", got " + describeJson(*a));
    }
    if (const auto c = m.find("alphaCutoff"); c != m.end())
      out.alphaCutoff = number(*c, base_ + ".alphaCutoff", Domain::NonNegative);
    if (const auto d = m.find("doubleSided"); d != m.end()) {
      if (!d->is_boolean()) fail(base_ + ".doubleSided", "expected true or false, got " + describeJson(*d));
      out.doubleSided = d->get<bool>();
    }
  }

  const std::string& base_;
  const GltfMaterialContext& c_;
};

// The shortest text that reads back as the same float ("0.1", not 0.100000001490116).
std::string floatText(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

GltfMaterial readGltfMaterial(const json& m, const std::string& path, const GltfMaterialContext& context) {
  return Reader(path, context).read(m);
}

void checkMaterialFactors(const MaterialParams& m, std::size_t index) {
  GltfMaterial g;
  g.params = m;
  for (const Part& part : parts())
    for (const Factor& f : part.factors) {
      if (!f.field) continue;
      const float* at = f.at(g);
      const std::size_t n = f.length == 1 ? 1 : 3;
      for (std::size_t c = 0; c < n; ++c) {
        const float v = at[c];
        const std::string field = n == 1 ? std::string(f.field) : fmt::format("{}[{}]", f.field, c);
        if (!inDomain(v, f.domain))
          throw Error(fmt::format("material {}: {} must be {}, got {}", index, field, expectedNumber(f.domain), floatText(v)));
        if (f.domain == Domain::Intensity && v > kMaxDraftIntensity)
          throw Error(fmt::format("material {}: {} must be {}, got {} (at most 1e+30: f would overflow float)", index,
                                  field, expectedNumber(f.domain), floatText(v)));
      }
    }
}

}  // namespace brdfcl::detail
