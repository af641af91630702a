// emissiveFactor as both material readers (model/materials.cpp, gltf/document.cpp) finish it. The
// glTF schema bounds each component to [0, 1], but engines take larger values; brdfcl clamps such a
// component to 1 with a warning, and refuses it under --strict.
#pragma once
#include <array>
#include <functional>
#include <string>

namespace brdfcl::detail {

// `rgb` was read at JSON path `path` of `source` as three finite floats >= 0. Each component above
// 1 becomes 1 and is one warning through `warn` (which may be empty), or the Error under `strict`.
std::array<float, 3> clampEmissiveFactor(std::array<float, 3> rgb, const std::string& source, const std::string& path,
                                         bool strict, const std::function<void(const std::string&)>& warn);

}  // namespace brdfcl::detail
