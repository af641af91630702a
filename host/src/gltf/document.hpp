// The JSON side of the glTF loader: what brdfcl reads straight from the document (extension
// lists, materials with their extensions, textures, samplers, cameras, KHR_lights_punctual,
// KHR_materials_variants), with the file's JSON key paths in every message.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "brdfcl/gltf.hpp"

namespace brdfcl::gltf::detail {

class Document {
 public:
  Document(const nlohmann::json& doc, std::string source) : doc_(doc), source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& message) const;
  const nlohmann::json& root() const { return doc_; }
  const std::string& source() const { return source_; }

  // extensionsRequired that brdfcl lacks are an error; extensionsUsed it ignores, one warning.
  void checkExtensions(std::vector<std::string>& warnings) const;
  bool ktx2WithoutFallback() const;
  std::vector<Sampler> samplers() const;
  std::vector<Texture> textures(std::size_t imageCount, std::size_t samplerCount) const;
  // Keys brdfcl does not know (typos) go to `warnings`, or are the Error when `strict`.
  std::vector<Material> materials(std::size_t textureCount, std::vector<std::string>& warnings, bool strict) const;
  std::vector<std::string> variants() const;
  // The material of meshes[mesh].primitives[prim] under variant `variant` (-1 = none), else `fallback`.
  int variantMaterial(std::size_t mesh, std::size_t prim, int variant, int fallback) const;
  // cameras[index], checked; the caller fills node and world.
  Camera camera(int index) const;
  // The KHR_lights_punctual light of nodes[node] in the node's space (at the origin, shining down
  // -Z), if it has one.
  std::optional<Light> nodeLight(std::size_t node) const;

 private:
  // Safe lookups: nullptr where the document has no such member or element (never operator[]
  // on a const json, which asserts).
  const nlohmann::json* member(const nlohmann::json& obj, const char* key) const;
  const nlohmann::json* element(const nlohmann::json& array, std::size_t i) const;
  const nlohmann::json& object(const nlohmann::json& v, const std::string& path) const;
  double checked(const nlohmann::json& v, const std::string& path, const char* expected, bool (*ok)(double)) const;
  double number(const nlohmann::json& obj, const char* key, const std::string& path, double fallback,
                const char* expected, bool (*ok)(double)) const;
  int index(const nlohmann::json& obj, const char* key, const std::string& path, int fallback, std::size_t count,
            const char* what) const;
  template <std::size_t N>
  std::array<float, N> numbers(const nlohmann::json& obj, const char* key, const std::string& path,
                               std::array<float, N> fallback, bool unitRange) const;
  TextureRef textureRef(const nlohmann::json& obj, const char* key, const std::string& path, std::size_t textureCount,
                        const char* valueKey = nullptr) const;
  Material material(const nlohmann::json& m, const std::string& path, std::size_t textureCount, bool strict,
                    std::vector<std::string>& warnings) const;

  const nlohmann::json& doc_;
  std::string source_;
};

}  // namespace brdfcl::gltf::detail
