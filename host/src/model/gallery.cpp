// Gallery materials. The seed examples keep the spec defaults they were written against
// (baseColor 1, metallic 1, roughness 1 when the example sets only its own extension).
#include "model/gallery.hpp"

#include "brdfcl/io.hpp"

namespace brdfcl {

const std::string& galleryJson() {
  static const std::string json = R"json({
  "materials": [
    {"name": "velvet (000 example)",
     "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.9, 0.9]}}},
    {"name": "red velvet",
     "pbrMetallicRoughness": {"baseColorFactor": [0.35, 0.02, 0.04, 1], "metallicFactor": 0, "roughnessFactor": 0.9},
     "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.3, 0.35], "sheenRoughnessFactor": 0.4}}},
    {"name": "draft sheen cloth (001)",
     "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.25, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0.6},
     "extensions": {"KHR_materials_sheen": {"intensityFactor": 1.0, "colorFactor": [1, 1, 1]}}},
    {"name": "varnish (004 example)",
     "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0}}},
    {"name": "coated varnish",
     "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.2, 0.07, 1], "metallicFactor": 0, "roughnessFactor": 0.6},
     "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}},
    {"name": "anisotropy (002 example)",
     "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 1.57}}},
    {"name": "brushed metal",
     "pbrMetallicRoughness": {"baseColorFactor": [0.91, 0.92, 0.92, 1], "metallicFactor": 1, "roughnessFactor": 0.3},
     "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8, "anisotropyRotation": 0.0}}},
    {"name": "plain dielectric",
     "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 0.5}}
  ]
})json";
  return json;
}

std::vector<MaterialParams> gallery() { return parseMaterials(galleryJson(), "built-in gallery"); }

}  // namespace brdfcl
