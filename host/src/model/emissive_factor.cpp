// clampEmissiveFactor (emissive_factor.hpp): one rule and one message for emissiveFactor above the
// glTF schema's maximum, for the materials file and the glTF loader alike.
#include "model/emissive_factor.hpp"

#include <charconv>

#include "brdfcl/error.hpp"

namespace brdfcl::detail {

std::array<float, 3> clampEmissiveFactor(std::array<float, 3> rgb, const std::string& source, const std::string& path,
                                         bool strict, const std::function<void(const std::string&)>& warn) {
  for (std::size_t c = 0; c < 3; ++c) {
    if (!(rgb[c] > 1.0f)) continue;
    char shortest[32];  // the float as the file wrote it: 1.1, not 1.100000023841858
    const auto end = std::to_chars(shortest, shortest + sizeof shortest, rgb[c]).ptr;
    const std::string what = source + ": " + path + "[" + std::to_string(c) + "]: " + std::string(shortest, end) +
                             " is above 1, the glTF schema's maximum";
    const char* hint = "KHR_materials_emissive_strength gives brighter emission";
    if (strict) throw Error(what + "; " + hint + " (an error under --strict)");
    if (warn) warn(what + ", clamped to 1; " + hint);
    rgb[c] = 1.0f;
  }
  return rgb;
}

}  // namespace brdfcl::detail
