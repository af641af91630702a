// PNG/JPEG decoding (images.hpp). stb_image is compiled into this file only (static, PNG and JPEG
// only), so the loader does not depend on which stb symbols a tinygltf build exports, and fuzzing
// instruments the decoder too.
#include "gltf/images.hpp"

#include "io/input_limits.hpp"

#include <climits>
#include <exception>
#include <cstdint>
#include <memory>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 65536
#include <stb_image.h>

namespace brdfcl::gltf::detail {

bool decodeImage(const unsigned char* bytes, std::size_t size, std::size_t maxPixels, Image& out, std::string& reason) {
  if (size == 0 || size > std::size_t(INT_MAX)) {
    reason = size == 0 ? "the image data is empty" : "the image data is larger than 2 GiB";
    return false;
  }
  const int n = static_cast<int>(size);
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes, n, &w, &h, &channels)) {
    reason = stbi_failure_reason() ? stbi_failure_reason() : "unknown format";
    return false;
  }
  // Checked before decoding: the header alone can claim any size.
  if (maxPixels == 0) {
    // Called from tinygltf, which is not to be unwound by an exception: a bad variable becomes the reason.
    try {
      reason = brdfcl::detail::imagePixelRefusal(brdfcl::detail::ImageKind::Texture, w, h);
    } catch (const std::exception& e) {
      reason = e.what();
    }
    if (!reason.empty()) return false;
  }
  if (w <= 0 || h <= 0 || (maxPixels != 0 && std::size_t(w) * std::size_t(h) > maxPixels)) {
    reason = std::to_string(w) + "x" + std::to_string(h) + " pixels are more than brdfcl's limit of " +
             std::to_string(maxPixels);
    return false;
  }
  const bool sixteen = stbi_is_16_bit_from_memory(bytes, n) != 0;
  const std::size_t texels = std::size_t(w) * std::size_t(h);
  out.width = w;
  out.height = h;
  out.bits = sixteen ? 16 : 8;
  if (sixteen) {
    std::unique_ptr<stbi_us, void (*)(void*)> px(stbi_load_16_from_memory(bytes, n, &w, &h, &channels, 4),
                                                  stbi_image_free);
    if (!px) {
      reason = stbi_failure_reason() ? stbi_failure_reason() : "corrupt data";
      return false;
    }
    out.rgba.assign(px.get(), px.get() + 4 * texels);
  } else {
    std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_memory(bytes, n, &w, &h, &channels, 4),
                                                  stbi_image_free);
    if (!px) {
      reason = stbi_failure_reason() ? stbi_failure_reason() : "corrupt data";
      return false;
    }
    out.rgba.resize(4 * texels);
    for (std::size_t i = 0; i < 4 * texels; ++i) out.rgba[i] = static_cast<std::uint16_t>(px.get()[i] * 257u);
  }
  return true;
}

}  // namespace brdfcl::gltf::detail
