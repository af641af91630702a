// KHR_draco_mesh_compression for the glTF loader: compressed primitives decoded with Debian's
// libdraco into new buffers that the primitive's accessors then read like any other.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "brdfcl/gltf.hpp"

namespace tinygltf {
class Model;
}

namespace brdfcl::gltf::detail {

// Whether some primitive has KHR_draco_mesh_compression.
bool hasDracoPrimitives(const nlohmann::json& doc);

// Removes "indices" from those primitives in `doc` (the copy tinygltf reads): tinygltf refuses an
// indices accessor without a bufferView, which a Draco primitive's is; decodeDraco reads the
// index from the original document.
void withoutDracoIndices(nlohmann::json& doc);

// Decodes every primitive with KHR_draco_mesh_compression: its indices accessor (added when the
// primitive has none) and the accessors of the attributes the extension maps get a new buffer
// view of 32-bit indices / floats (componentType, normalized and count rewritten to match);
// integer Draco values are normalized as the glTF accessor says. Draco point ids become vertex
// indices. Messages are "<source>: meshes[m].primitives[p]...: ...".
void decodeDraco(const nlohmann::json& doc, tinygltf::Model& model, const std::string& source,
                 const LoadOptions& options);

}  // namespace brdfcl::gltf::detail
