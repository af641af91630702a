// readMaterials/parseMaterials: glTF 2.0 materials (core metallic-roughness, KHR_materials_sheen
// ratified or draft, KHR_materials_clearcoat, KHR_materials_anisotropy, and KHR_materials_ior for
// the engine profiles) into MaterialParams.
// Every rejection is one line naming the file and the JSON path of the offending key; keys it
// does not read are reported by checkMaterialKeys (model/material_keys.hpp), shared with the glTF loader.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/files.hpp"
#include "io/input_limits.hpp"
#include "io/glb.hpp"
#include "io/messages.hpp"
#include "model/emissive_factor.hpp"
#include "model/material_keys.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/material.hpp"

namespace brdfcl {
namespace {

using json = nlohmann::json;
using detail::printable;
using detail::formatNumber;
std::string describe(const json& v) { return detail::describeJson(v); }
std::string withoutTag(std::string what) { return detail::withoutJsonTag(std::move(what)); }

using Warn = std::function<void(const std::string&)>;

// Intensity: the draft's intensityFactor, >= 0 and at most kMaxDraftIntensity.
enum class Range { Unit, NonNegative, Intensity, Finite, Ior };

const char* expectedNumber(Range r) {
  switch (r) {
    case Range::Unit:
      return "a number in [0, 1]";
    case Range::NonNegative:
    case Range::Intensity:
      return "a number >= 0";
    case Range::Ior:
      return "0 or a number >= 1";
    case Range::Finite:
      break;
  }
  return "a finite number";
}

class MaterialReader {
 public:
  MaterialReader(const std::string& source, const MaterialReadOptions& options)
      : source_(printable(source, 300)), warn_(options.warn), strict_(options.strict) {}

  std::vector<MaterialParams> read(const std::string& text) {
    json doc;
    try {
      doc = json::parse(text);
    } catch (const json::out_of_range& e) {
      // nlohmann rejects literals beyond double range (1e999) without a position; point at the
      // first occurrence of the literal so the user can find it.
      const std::string what = withoutTag(e.what());
      std::string where;
      const auto q1 = what.find('\''), q2 = what.rfind('\'');
      if (q1 != std::string::npos && q2 > q1 + 1) {
        const auto at = text.find(what.substr(q1 + 1, q2 - q1 - 1));
        if (at != std::string::npos)
          where = " at line " +
                  std::to_string(1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
      }
      throw Error(source_ + ": invalid JSON: " + printable(what, 300) + where + "; numbers must be finite");
    } catch (const json::exception& e) {
      // parse_error's text already says "parse error at line L, column C: ...".
      throw Error(source_ + ": invalid JSON: " + printable(withoutTag(e.what()), 300));
    }
    if (!doc.is_object())
      throw Error(source_ + ": expected a JSON object with a \"materials\" array at the top level, got " +
                  describe(doc));
    const auto it = doc.find("materials");
    if (it == doc.end())
      throw Error(source_ +
                  ": no \"materials\" array at the top level; expected a glTF 2.0 document or "
                  "{\"materials\": [...]}");
    if (!it->is_array()) fail("materials", "expected an array of material objects, got " + describe(*it));
    if (it->empty()) fail("materials", "the array is empty; at least one material is needed");

    std::vector<MaterialParams> out;
    out.reserve(it->size());
    const auto report = [&](const std::string& finding) {
      if (strict_) throw Error(source_ + ": " + detail::strictError(finding));
      if (warn_) warn_(source_ + ": " + finding);
    };
    for (std::size_t i = 0; i < it->size(); ++i) {
      std::string textureNote;
      out.push_back(material((*it)[i], i, textureNote));
      // After the material is read, so that a value of the wrong type gets the reader's message;
      // before the texture note, so that --strict fails with nothing printed first.
      detail::checkMaterialKeys((*it)[i], "materials[" + std::to_string(i) + "]", detail::MaterialKeyReader::MaterialsFile,
                                report);
      if (!textureNote.empty()) warn_(textureNote);
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw Error(source_ + ": " + path + ": " + message);
  }

  const json* object(const json& parent, const char* key, const std::string& path) const {
    const auto it = parent.find(key);
    if (it == parent.end()) return nullptr;
    if (!it->is_object()) fail(path, "expected an object, got " + describe(*it));
    return &*it;
  }

  float number(const json& v, const std::string& path, Range range) const {
    const char* expected = expectedNumber(range);
    if (!v.is_number()) fail(path, std::string("expected ") + expected + ", got " + describe(v));
    // nlohmann turns overflowing literals such as 1e999 into inf; glTF has no infinities.
    const double d = v.get<double>();
    bool ok = std::isfinite(d);
    if (ok && range == Range::Unit) ok = d >= 0.0 && d <= 1.0;
    if (ok && (range == Range::NonNegative || range == Range::Intensity)) ok = d >= 0.0;
    if (ok && range == Range::Ior) ok = d == 0.0 || d >= 1.0;  // KHR_materials_ior's schema
    if (!ok) fail(path, std::string("expected ") + expected + ", got " + formatNumber(d));
    if (std::fabs(d) > std::numeric_limits<float>::max())
      fail(path, std::string("expected ") + expected + ", got " + formatNumber(d) + " (too large for float)");
    if (range == Range::Intensity && static_cast<float>(d) > kMaxDraftIntensity)
      fail(path, std::string("expected ") + expected + ", got " + formatNumber(d) +
                     " (at most 1e+30: f would overflow float)");
    return static_cast<float>(d);
  }

  // glTF colors are RGB or RGBA arrays; only RGB matters for the BRDF.
  Rgb color(const json& v, const std::string& path, std::size_t length, Range range) const {
    const std::string expected = "expected an array of " + std::to_string(length) + " numbers" +
                                 (range == Range::Unit          ? " in [0, 1]"
                                  : range == Range::NonNegative ? " >= 0"
                                                                : "");
    if (!v.is_array() || v.size() != length) fail(path, expected + ", got " + describe(v));
    Rgb rgb{};
    for (std::size_t c = 0; c < length; ++c) {
      const float x = number(v[c], path + "[" + std::to_string(c) + "]", range);
      if (c < 3) rgb[c] = x;
    }
    return rgb;
  }

  template <typename Apply>
  void optional(const json& obj, const char* key, const std::string& path, Apply apply) const {
    const auto it = obj.find(key);
    if (it != obj.end()) apply(*it, path + "." + key);
  }

  static void noteTextures(const json& obj, std::initializer_list<const char*> keys, std::vector<std::string>& found) {
    for (const char* key : keys)
      if (obj.contains(key)) found.emplace_back(key);
  }

  // textureNote: the warning for ignored texture references, or "".
  MaterialParams material(const json& m, std::size_t index, std::string& textureNote) const {
    const std::string base = "materials[" + std::to_string(index) + "]";
    if (!m.is_object()) fail(base, "expected a material object, got " + describe(m));

    MaterialParams p;
    std::vector<std::string> textures;
    optional(m, "name", base, [&](const json& v, const std::string& path) {
      if (!v.is_string()) fail(path, "expected a string, got " + describe(v));
      p.name = v.get<std::string>();
    });
    noteTextures(m, {"normalTexture", "occlusionTexture", "emissiveTexture"}, textures);

    if (const json* pbr = object(m, "pbrMetallicRoughness", base + ".pbrMetallicRoughness")) {
      const std::string path = base + ".pbrMetallicRoughness";
      optional(*pbr, "baseColorFactor", path,
               [&](const json& v, const std::string& at) { p.baseColor = color(v, at, 4, Range::Unit); });
      optional(*pbr, "metallicFactor", path,
               [&](const json& v, const std::string& at) { p.metallic = number(v, at, Range::Unit); });
      optional(*pbr, "roughnessFactor", path,
               [&](const json& v, const std::string& at) { p.roughness = number(v, at, Range::Unit); });
      noteTextures(*pbr, {"baseColorTexture", "metallicRoughnessTexture"}, textures);
    }
    optional(m, "emissiveFactor", base, [&](const json& v, const std::string& at) {
      p.emissive = detail::clampEmissiveFactor(color(v, at, 3, Range::NonNegative), source_, at, strict_, warn_);
    });

    if (const json* ext = object(m, "extensions", base + ".extensions")) {
      const std::string extPath = base + ".extensions";
      if (const json* sheen = object(*ext, "KHR_materials_sheen", extPath + ".KHR_materials_sheen"))
        readSheen(*sheen, extPath + ".KHR_materials_sheen", p, textures);
      const std::string ccPath = extPath + ".KHR_materials_clearcoat";
      if (const json* cc = object(*ext, "KHR_materials_clearcoat", ccPath)) {
        optional(*cc, "clearcoatFactor", ccPath,
                 [&](const json& v, const std::string& at) { p.clearcoat = number(v, at, Range::Unit); });
        optional(*cc, "clearcoatRoughnessFactor", ccPath,
                 [&](const json& v, const std::string& at) { p.clearcoatRoughness = number(v, at, Range::Unit); });
        noteTextures(*cc, {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"}, textures);
      }
      const std::string anPath = extPath + ".KHR_materials_anisotropy";
      if (const json* an = object(*ext, "KHR_materials_anisotropy", anPath)) {
        p.anisotropyExtension = true;
        optional(*an, "anisotropyStrength", anPath,
                 [&](const json& v, const std::string& at) { p.anisotropyStrength = number(v, at, Range::Unit); });
        optional(*an, "anisotropyRotation", anPath,
                 [&](const json& v, const std::string& at) { p.anisotropyRotation = number(v, at, Range::Finite); });
        noteTextures(*an, {"anisotropyTexture"}, textures);
      }
      // Read for the engine profiles (docs/profiles.md); the spec profile's f has no IOR input.
      const std::string iorPath = extPath + ".KHR_materials_ior";
      if (const json* io = object(*ext, "KHR_materials_ior", iorPath))
        optional(*io, "ior", iorPath, [&](const json& v, const std::string& at) { p.ior = number(v, at, Range::Ior); });
      // Other extensions (transmission, volume, ...) are not part of this BRDF: checkMaterialKeys
      // names what each would have changed.
    }

    if (!textures.empty() && warn_) {
      std::string list;
      for (const auto& t : textures) list += (list.empty() ? "" : ", ") + t;
      const std::string who = p.name.empty() ? base : base + " ('" + printable(p.name) + "')";
      textureNote = source_ + ": " + who + ": texture references are ignored (" + list + "); using factors only";
    }
    return p;
  }

  // The draft and the ratified extension share a name but not a single key; the keys decide.
  void readSheen(const json& s, const std::string& path, MaterialParams& p, std::vector<std::string>& textures) const {
    // "sheenFactor" is the draft's own example and disable rule for what its table calls
    // intensityFactor: read it as that, so the draft's velvet example renders as velvet.
    static const char* const draftKeys[] = {"intensityFactor", "sheenFactor", "colorFactor", "colorIntensityTexture"};
    static const char* const ratifiedKeys[] = {"sheenColorFactor", "sheenRoughnessFactor", "sheenColorTexture",
                                               "sheenRoughnessTexture"};
    std::string draftSeen, ratifiedSeen;
    for (const char* k : draftKeys)
      if (s.contains(k)) draftSeen += (draftSeen.empty() ? "" : ", ") + std::string(k);
    for (const char* k : ratifiedKeys)
      if (s.contains(k)) ratifiedSeen += (ratifiedSeen.empty() ? "" : ", ") + std::string(k);
    if (!draftSeen.empty() && !ratifiedSeen.empty())
      fail(path, "mixes draft keys (" + draftSeen + ") with ratified keys (" + ratifiedSeen +
                     "); use either intensityFactor/colorFactor or sheenColorFactor/sheenRoughnessFactor");

    if (!draftSeen.empty()) {
      p.draftSheen = true;
      if (s.contains("intensityFactor") && s.contains("sheenFactor"))
        fail(path, "has both intensityFactor and sheenFactor (the draft's two names for one value); keep one");
      for (const char* key : {"intensityFactor", "sheenFactor"})
        optional(s, key, path,
                 [&](const json& v, const std::string& at) { p.draftIntensity = number(v, at, Range::Intensity); });
      optional(s, "colorFactor", path,
               [&](const json& v, const std::string& at) { p.draftColor = color(v, at, 3, Range::Unit); });
      noteTextures(s, {"colorIntensityTexture"}, textures);
    } else {
      optional(s, "sheenColorFactor", path,
               [&](const json& v, const std::string& at) { p.sheenColor = color(v, at, 3, Range::Unit); });
      optional(s, "sheenRoughnessFactor", path,
               [&](const json& v, const std::string& at) { p.sheenRoughness = number(v, at, Range::Unit); });
      noteTextures(s, {"sheenColorTexture", "sheenRoughnessTexture"}, textures);
    }
  }

  const std::string source_;
  const Warn& warn_;
  const bool strict_;
};

}  // namespace

std::vector<MaterialParams> parseMaterials(const std::string& jsonText, const std::string& sourceName,
                                           const MaterialReadOptions& options) {
  return MaterialReader(sourceName, options).read(jsonText);
}

std::vector<MaterialParams> parseMaterials(const std::string& jsonText, const std::string& sourceName,
                                           const Warn& warn) {
  return parseMaterials(jsonText, sourceName, MaterialReadOptions{warn, false});
}

std::vector<MaterialParams> readMaterials(const std::string& path, const MaterialReadOptions& options) {
  const detail::ReadingInput reading(printable(path, 300));
  std::string text;
  detail::readInputFile(path, printable(path, 300), "materials file ", text, detail::maxInputFileBytes(path));
  // A .glb holds the same JSON in its first chunk; the magic decides, not the name.
  if (detail::hasGlbMagic(text)) {
    std::size_t binSize = 0;
    text = detail::glbJsonChunk(text, printable(path, 300), binSize);
  } else if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0) {
    throw Error(printable(path, 300) + ": not a GLB file (no glTF magic number); a .glb must start with 'glTF'");
  }
  return parseMaterials(text, path, options);
}

std::vector<MaterialParams> readMaterials(const std::string& path, const Warn& warn) {
  return readMaterials(path, MaterialReadOptions{warn, false});
}

}  // namespace brdfcl
