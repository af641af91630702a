// Image decoding for the glTF loader: 8- and 16-bit PNG and JPEG through stb_image, widened to
// RGBA uint16 (gltf::Image), with a pixel limit checked before decoding.
#pragma once
#include <cstddef>
#include <string>

#include "brdfcl/gltf.hpp"

namespace brdfcl::gltf::detail {

// Decodes `size` bytes into out.width/height/bits/rgba. On failure returns false and says why in
// `reason` (stb_image's words, or the size limit). maxPixels 0: the texture limit of
// input_limits.hpp, whose refusal (a `reason` starting "declares ") is a whole sentence.
bool decodeImage(const unsigned char* bytes, std::size_t size, std::size_t maxPixels, Image& out, std::string& reason);

}  // namespace brdfcl::gltf::detail
