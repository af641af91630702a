// glTF 2.0 assets: what the loader (host/src/gltf/loader.cpp, on Debian's tinygltf) keeps of a
// .gltf/.glb file: world-space triangles, materials with every texture slot of the core spec,
// KHR_materials_{sheen,clearcoat,anisotropy,emissive_strength,variants} and KHR_texture_transform,
// decoded images, camera nodes and KHR_lights_punctual lights. Conventions in docs/gltf.md.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "brdfcl/scene.hpp"

namespace brdfcl::gltf {

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores node matrices

// KHR_texture_transform: uv' = Translation(offset) * Rotation(rotation) * Scale(scale) * uv, with
// the extension's rotation matrix [cos sin; -sin cos] (counter-clockwise in UV space).
struct TextureTransform {
  std::array<float, 2> offset{0.0f, 0.0f};
  float rotation = 0.0f;
  std::array<float, 2> scale{1.0f, 1.0f};
};

// A textureInfo: which texture, which TEXCOORD_n (after the transform's texCoord override), and
// the slot's own number (normalTexture.scale, occlusionTexture.strength; 1 elsewhere).
struct TextureRef {
  int texture = -1;  // index into Asset::textures; -1 = no texture in this slot
  int texCoord = 0;  // 0 or 1
  float value = 1.0f;  // normal scale or occlusion strength
  TextureTransform transform;
  bool present() const { return texture >= 0; }
};

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

// glTF sampler; absent filters are "undefined" in glTF, taken here as LINEAR and
// LINEAR_MIPMAP_LINEAR (what engines do).
struct Sampler {
  Wrap wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
  bool magNearest = false;
  bool minNearest = false;      // texel filter within a mip level
  bool mipmaps = true;          // false for minFilter NEAREST or LINEAR
  bool mipNearest = false;      // *_MIPMAP_NEAREST
};

// A decoded image: 8- or 16-bit PNG/JPEG, widened to 16 bits (an 8-bit value v is v * 257), always
// RGBA (missing channels filled as stb_image does: grey -> RGB, alpha 1). Values are the file's,
// not yet linearized: colour slots decode sRGB when sampled.
struct Image {
  std::string name;  // uri, or "images[i]"
  int width = 0, height = 0;
  int bits = 8;                     // as stored in the file
  std::vector<std::uint16_t> rgba;  // 4 per texel, rows from the top (glTF UV (0,0) is the top-left)
};

struct Texture {
  int image = -1;    // index into Asset::images
  int sampler = -1;  // index into Asset::samplers; -1 = default sampler
};

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
  std::string name;
  // Core.
  std::array<float, 4> baseColorFactor{1, 1, 1, 1};
  TextureRef baseColorTexture;  // sRGB
  float metallicFactor = 1.0f, roughnessFactor = 1.0f;
  TextureRef metallicRoughnessTexture;  // B metallic, G roughness, linear
  TextureRef normalTexture;             // value = scale
  TextureRef occlusionTexture;          // value = strength; R
  std::array<float, 3> emissiveFactor{0, 0, 0};
  float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength
  TextureRef emissiveTexture;     // sRGB
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  // KHR_materials_sheen.
  std::array<float, 3> sheenColorFactor{0, 0, 0};
  TextureRef sheenColorTexture;  // sRGB, RGB
  float sheenRoughnessFactor = 0.0f;
  TextureRef sheenRoughnessTexture;  // linear, A
  // KHR_materials_clearcoat.
  float clearcoatFactor = 0.0f;
  TextureRef clearcoatTexture;  // R
  float clearcoatRoughnessFactor = 0.0f;
  TextureRef clearcoatRoughnessTexture;  // G
  TextureRef clearcoatNormalTexture;     // value = scale
  // KHR_materials_anisotropy.
  float anisotropyStrength = 0.0f, anisotropyRotation = 0.0f;
  TextureRef anisotropyTexture;  // RG direction in [-1, 1], B strength; linear

  // Whether shading needs a tangent frame from TANGENT or generated tangents.
  bool needsTangents() const {
    return normalTexture.present() || clearcoatNormalTexture.present() || anisotropyStrength > 0.0f ||
           anisotropyTexture.present();
  }
};

// One drawable triangle list in world space: a glTF primitive under one node's world transform
// (rest pose). Strips and fans are already expanded into triangles (counter-clockwise front
// faces in world space: a node with a negative determinant has had its winding reversed).
struct Primitive {
  int material = -1;  // index into Asset::materials; -1 = the glTF default material
  std::string where;  // "meshes[2].primitives[0] (node 5)", for messages
  std::vector<float> positions;  // 3 per vertex, world
  std::vector<float> normals;    // 3 per vertex, world, unit; empty = flat normals per triangle
  std::vector<float> tangents;   // 4 per vertex: world xyz (unit), w = bitangent sign in world space; may be empty
  std::vector<float> uv0, uv1;   // 2 per vertex; may be empty
  std::vector<float> color0;     // 4 per vertex (RGB gets alpha 1), linear; may be empty
  std::vector<std::uint32_t> indices;  // 3 per triangle
  bool generatedTangents = false;      // tangents come from brdfcl's generator, not the file
  std::size_t vertexCount() const { return positions.size() / 3; }
  std::size_t triangleCount() const { return indices.size() / 3; }
};

// A camera node of the chosen scene. yfov/aspect for perspective, xmag/ymag for orthographic.
struct Camera {
  int index = -1;  // glTF cameras[index]
  int node = -1;
  std::string name;
  bool orthographic = false;
  double yfov = 0.8, aspectRatio = 0.0;  // aspectRatio 0 = not given
  double xmag = 1.0, ymag = 1.0;
  double znear = 0.01, zfar = 0.0;  // zfar 0 = infinite
  Mat4 world{};                     // camera-to-world; the camera looks down its local -Z, +Y up
};

struct Asset {
  std::string path;
  std::vector<Primitive> primitives;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Sampler> samplers;
  std::vector<Image> images;
  std::vector<Camera> cameras;     // camera nodes of the scene, in depth-first node order
  std::vector<Light> lights;       // KHR_lights_punctual lights of the scene, placed in world space
  std::vector<std::string> variants;  // KHR_materials_variants names
  std::array<double, 3> boundsMin{0, 0, 0}, boundsMax{0, 0, 0};  // world bounding box of all triangles
  std::vector<std::string> warnings;  // one line each: skipped points/lines, skins, morphs, ignored extensions
};

struct LoadOptions {
  int scene = -1;       // -1 = the file's default scene, else scene 0
  std::string variant;  // KHR_materials_variants name; "" = the default materials
  // Unknown keys and KHR_/EXT_ names in materials (typos: checkMaterialKeys) are warnings in
  // Asset::warnings; strict makes the first of them the load's Error instead.
  bool strict = false;
  // Buffer and image URIs name files inside the asset's folder (docs/gltf.md, "Files an asset
  // names"); true also lets them name absolute paths, ".." above the folder and links, which a
  // user who keeps textures in a sibling folder asks for. Non-regular files are refused either way.
  bool allowOutsideUris = false;
  // Bounds against hostile files, checked before allocating (the fuzz harness lowers them): the
  // world-space vertices plus triangles of all primitives together, and the pixels of one image
  // (0: brdfcl's texture limit, 2^26 pixels, or BRDFCL_MAX_IMAGE_PIXELS when that is set).
  std::size_t maxElements = std::size_t(1) << 28;
  std::size_t maxImagePixels = 0;
};

// Loads a .gltf (external or data-URI buffers and images) or .glb file and the scene chosen.
// Every failure is a one-line brdfcl::Error naming the file and the JSON path or object index,
// e.g. "chair.gltf: accessors[3]: bufferView 9 does not exist (the file has 4)".
Asset load(const std::string& path, const LoadOptions& options = {});

// The same from the bytes of a .gltf or .glb (told apart by the GLB magic); `name` prefixes
// messages, external buffers and images resolve against baseDir ("" = the current directory).
// load() reads the file and calls this; the fuzz harness calls it directly.
Asset loadFromMemory(const std::string& bytes, const std::string& name, const std::string& baseDir,
                     const LoadOptions& options = {});

}  // namespace brdfcl::gltf
