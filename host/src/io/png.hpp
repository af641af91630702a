// PNG encoding in memory, for writers that embed images in their own containers (the demo .glb).
// The encoder is the stb_image_write compiled (static) into io/image.cpp.
#pragma once
#include <cstdint>
#include <string>

namespace brdfcl::detail {

// `pixels`: width * height * channels bytes (1 to 4 channels), rows from the top. Returns the
// PNG file's bytes, or an empty string if the encoder failed (out of memory).
std::string encodePng(const std::uint8_t* pixels, int width, int height, int channels);

}  // namespace brdfcl::detail
