// readMaterials/parseMaterials: a materials file (JSON, or a .glb's JSON chunk) and its "materials"
// array into MaterialParams. Each material object is read by the glTF material reader that the
// glTF loader shares (model/gltf_material.hpp), with its messages and key checks.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/files.hpp"
#include "io/input_limits.hpp"
#include "io/glb.hpp"
#include "io/messages.hpp"
#include "model/gltf_material.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/material.hpp"

namespace brdfcl {
namespace {

using json = nlohmann::json;
using detail::printable;
std::string describe(const json& v) { return detail::describeJson(v); }
std::string withoutTag(std::string what) { return detail::withoutJsonTag(std::move(what)); }

using Warn = std::function<void(const std::string&)>;

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
    for (std::size_t i = 0; i < it->size(); ++i) {
      std::string textureNote;
      // The reader reports unread keys after the material is read; the texture note comes after
      // them, so that --strict fails with nothing printed first.
      out.push_back(material((*it)[i], i, textureNote));
      if (!textureNote.empty()) warn_(textureNote);
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw Error(source_ + ": " + path + ": " + message);
  }

  // textureNote: the warning for ignored texture references, or "".
  MaterialParams material(const json& m, std::size_t index, std::string& textureNote) const {
    const std::string base = "materials[" + std::to_string(index) + "]";
    if (!m.is_object()) fail(base, "expected a material object, got " + describe(m));
    std::vector<std::string> textures;
    detail::GltfMaterialContext context;
    context.source = source_;
    context.reader = detail::MaterialKeyReader::MaterialsFile;
    context.strict = strict_;
    context.warn = warn_;
    context.texture = [&textures](detail::MaterialTexture, const json&, const char* key, const std::string&,
                                  const char*) { textures.emplace_back(key); };
    MaterialParams p = detail::readGltfMaterial(m, base, context).params;
    if (!textures.empty() && warn_) {
      std::string list;
      for (const auto& t : textures) list += (list.empty() ? "" : ", ") + t;
      const std::string who = p.name.empty() ? base : base + " ('" + printable(p.name) + "')";
      textureNote = source_ + ": " + who + ": texture references are ignored (" + list + "); using factors only";
    }
    return p;
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
