// parseEnvironmentSpec: the command line's --environment (a built-in kind or an .hdr/.exr file)
// as a scene Environment. The file is only checked for readability here; readEnvironmentRgb
// decodes it when the shader prepares its light.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "io/messages.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/scene.hpp"
#include "io/option_style.hpp"

namespace brdfcl {

Environment parseEnvironmentSpec(const std::string& spec, float intensity, float rotation) {
  const std::string shown = optionWithValue("--environment", "'" + detail::printable(spec, 300, ' ') + "'");
  if (!std::isfinite(intensity) || intensity < 0.0f)
    throw Error(optionWithValue("--env-intensity", detail::formatNumber(intensity)) +
                " is not a finite number >= 0; give a radiance scale such as 1 or 0.5");
  if (!std::isfinite(rotation))
    throw Error(optionWithValue("--env-rotation", detail::formatNumber(rotation)) +
                " is not a finite number of radians; give an angle such as 0 or 1.5708");
  Environment e;
  e.intensity = intensity;
  e.rotation = rotation;
  if (spec == "builtin" || spec == "sky" || spec == "studio" || spec == "uniform") {
    e.builtinKind = spec == "builtin" ? "sky" : spec;
    return e;
  }
  std::string ext = std::filesystem::path(spec).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".hdr" && ext != ".exr")
    throw Error(shown + ": expected builtin, sky, studio, uniform, or an equirectangular .hdr or .exr file");
  struct stat st {};
  if (::stat(spec.c_str(), &st) != 0) throw Error(shown + ": cannot read: " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(shown + ": cannot read: " + std::strerror(EISDIR));
  if (::access(spec.c_str(), R_OK) != 0) throw Error(shown + ": cannot read: " + std::strerror(errno));
  e.builtin = false;
  e.path = spec;
  return e;
}

}  // namespace brdfcl
