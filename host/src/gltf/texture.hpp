// Texture sampling for the glTF ray caster: one mip chain per (image, colour space) built once,
// holding only the channels some material slot reads, and glTF sampler filtering and wrapping
// with KHR_texture_transform and a level of detail from the ray cone (docs/gltf.md, Rendering).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "brdfcl/gltf.hpp"

namespace brdfcl::gltf {

// A mip chain. Images whose every value is an 8-bit code keep 8 bits per channel: linear
// channels as code / 255, sRGB colour channels sRGB-encoded and decoded per texel before
// filtering (as GPUs do with sRGB formats); level 0 is then the file's codes, exactly. Other
// images store linear values as 16-bit unorm. Only the channels in `channels` (bit c = RGBA
// channel c) are stored, packed in RGBA order.
struct MipChain {
  struct Level {
    int width = 0, height = 0;
    std::vector<std::uint16_t> texels16;  // `count` per texel, rows from the top (16-bit chains)
    std::vector<std::uint8_t> texels8;    // likewise (8-bit chains)
  };
  unsigned channels = 0;
  int count = 0;                            // stored channels per texel
  std::array<int, 4> slot{-1, -1, -1, -1};  // RGBA channel -> index in a texel, -1 = not stored
  bool eightBit = false;
  std::array<const float*, 4> decode8{};  // per stored channel: code -> linear value (8-bit chains)
  std::vector<Level> levels;
  float log2Size = 0.0f;  // 0.5 log2(width height) of level 0: the texture's share of the LOD
  std::size_t bytes() const;
};

// Colour space in which a slot reads its texture: sRGB-encoded RGB (baseColor, emissive,
// sheenColor; alpha stays linear) or linear.
enum class ColorSpace { Linear = 0, Srgb = 1 };

class Textures {
 public:
  // Scans every material's slots to learn which channels of which image each colour space
  // needs, then builds those chains. Throws brdfcl::Error for a texture or image index out of range.
  explicit Textures(const Asset& asset);

  // Samples slot `ref` at the mesh coordinates uv (TEXCOORD_ref.texCoord) with the ray-cone
  // level of detail `coneLod` = Δ_tri + log2(width / |cos θ|) (the texture adds its size and
  // the transform's scale). Channels the chain does not hold read as 0 (alpha 1).
  std::array<float, 4> sample(const TextureRef& ref, ColorSpace space, float u, float v, float coneLod) const;

  std::size_t bytes() const;  // texel memory of all chains

 private:
  std::vector<Texture> textures_;  // copies: the asset's images may be freed after construction
  std::vector<Sampler> samplers_;
  std::vector<MipChain> chains_;  // 2 per image: [2 image + space]
};

// sRGB EOTF (IEC 61966-2-1), for 8/16-bit colour values in [0, 1].
float srgbToLinear(float c);

}  // namespace brdfcl::gltf
