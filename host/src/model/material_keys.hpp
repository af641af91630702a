// checkMaterialKeys: the glTF 2.0 material schema as brdfcl knows it, for catching typos (a
// misspelt key or extension name would otherwise silently leave a factor at its default). One
// implementation for the materials-file reader (model/materials.cpp) and the glTF loader (gltf/document.cpp).
#pragma once
#include <functional>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace brdfcl::detail {

// Who reads the material decides what is known: the materials file feeds f, which reads the
// draft sheen keys and leaves out every extension but sheen, clearcoat and anisotropy (each
// left-out one is reported with what it would have changed); the glTF loader reads the ratified
// sheen keys only and KHR_materials_emissive_strength too, and reports extensions it leaves out
// once per file from extensionsUsed instead of once per material.
enum class MaterialKeyReader { MaterialsFile, GltfAsset };

// Reports, once each and in key order, as "<path>.<key>: <what>": unknown keys of the
// material, of pbrMetallicRoughness, of the KHR_materials_* objects the reader evaluates and of
// their textureInfo objects, with "did you mean <key>?" when a known key is near; unknown
// KHR_/EXT_ extension names (any case) in any of those "extensions" objects, likewise; and, for
// the materials file, the ratified material extensions f leaves out. Silent on "extras",
// vendor extensions (other prefixes) and real KHR_/EXT_ extensions that are not material
// extensions (KHR_texture_transform). Values of the wrong type are the readers' business: a
// member that is not an object is not looked into.
void checkMaterialKeys(const nlohmann::json& material, const std::string& path, MaterialKeyReader reader,
                       const std::function<void(const std::string&)>& report);

// A finding as the error --strict makes of it: the warning's ", ignored" (or "ignored: " of a
// left-out extension) no longer holds, so it is dropped (or reads "not evaluated: "), and the
// option that made it an error is named.
std::string strictError(std::string finding);

}  // namespace brdfcl::detail
