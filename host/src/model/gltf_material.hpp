// The one reader of a glTF 2.0 `material` object, for the materials file (model/materials.cpp)
// and the glTF loader (gltf/document.cpp): its factors, their ranges and messages, the texture
// references it finds, and the factor table that checkMaterial applies to a caller's MaterialParams.
#pragma once
#include <cstddef>
#include <functional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "brdfcl/gltf.hpp"
#include "brdfcl/material.hpp"
#include "model/material_keys.hpp"

namespace brdfcl::detail {

// The textureInfo slots of a material and its extensions, in the order the reader meets them.
enum class MaterialTexture {
  Normal,
  Occlusion,
  Emissive,
  BaseColor,
  MetallicRoughness,
  SheenColor,
  SheenRoughness,
  DraftColorIntensity,  // the experimental sheen draft's; materials files only
  Clearcoat,
  ClearcoatRoughness,
  ClearcoatNormal,
  Anisotropy,
};

// A material as read: what f takes (params), and what only the renderer reads.
struct GltfMaterial {
  MaterialParams params;
  float baseColorAlpha = 1.0f;   // baseColorFactor[3]
  float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength (glTF assets only)
  gltf::AlphaMode alphaMode = gltf::AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
};

struct GltfMaterialContext {
  std::string source;  // the file as messages name it, first in each
  // Which reader asks: a materials file also reads the sheen draft and KHR_materials_ior, a glTF
  // asset KHR_materials_emissive_strength (the same split as checkMaterialKeys').
  MaterialKeyReader reader = MaterialKeyReader::MaterialsFile;
  bool strict = false;  // --strict: what would be a warning is the Error
  std::function<void(const std::string&)> warn;  // may be empty
  // Called for each texture reference present: `key` of `parent` (at JSON path `parentPath`);
  // `valueKey` is its info's "scale" or "strength", or null. May be empty.
  std::function<void(MaterialTexture slot, const nlohmann::json& parent, const char* key, const std::string& parentPath,
                     const char* valueKey)>
      texture;
};

// Reads the material object `m` found at JSON path `path` ("materials[3]"), then reports the keys
// it did not read (checkMaterialKeys). Throws brdfcl::Error naming the source and the key's path.
GltfMaterial readGltfMaterial(const nlohmann::json& m, const std::string& path, const GltfMaterialContext& context);

// The same ranges as the reader's, for a MaterialParams a caller filled in:
// "material <index>: <field> must be <range>, got <value>".
void checkMaterialFactors(const MaterialParams& m, std::size_t index);

}  // namespace brdfcl::detail
