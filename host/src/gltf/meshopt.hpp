// EXT_meshopt_compression for the glTF loader: fallback buffers without data, and the decoding of
// compressed buffer views (Debian's libmeshoptimizer) into new buffers before accessors read them.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdfcl/gltf.hpp"

namespace tinygltf {
class Model;
}

namespace brdfcl::gltf::detail {

// Per buffers[i]: whether it is an EXT_meshopt_compression fallback (`"fallback": true`) without
// a uri, i.e. a buffer that has no bytes at all (its byteLength only says how large the decoded
// views are). Messages are "<source>: buffers[i]...: ...".
std::vector<bool> meshoptFallbacks(const nlohmann::json& doc, const std::string& source);

// The document as tinygltf must see it: each fallback buffer replaced by a 1-byte data URI, since
// tinygltf refuses a buffer without data (and, in a .glb, would give it the BIN chunk's bytes).
nlohmann::json withoutFallbackBuffers(const nlohmann::json& doc, const std::vector<bool>& fallbacks);

// Before tinygltf reads `doc` (buffers and views already checked): a view that is not compressed,
// or one an image reads, may not lie in a fallback buffer, which has no bytes to read.
void checkFallbackUse(const nlohmann::json& doc, const std::vector<bool>& fallbacks, const std::string& source);

// Decodes every bufferView with EXT_meshopt_compression: its bytes become a new buffer of
// count * byteStride bytes, which the view then points at (byteOffset 0). Sizes are checked
// against the compressed data and options.maxElements before anything is allocated. Messages
// are "<source>: bufferViews[i]...: ...".
void decodeMeshopt(const nlohmann::json& doc, tinygltf::Model& model, const std::vector<bool>& fallbacks,
                   const std::string& source, const LoadOptions& options);

}  // namespace brdfcl::gltf::detail
