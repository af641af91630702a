// Where the real glTF sample models and HDR environments are, for the tests and the benchmarks:
// $BRDFCL_ASSETS, else <source dir>/../shared/assets. They are not part of the repository.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <string>

namespace brdfcl::test {

// The assets folder, or "" when there is none.
inline std::string assetsDir() {
  namespace fs = std::filesystem;
  if (const char* e = std::getenv("BRDFCL_ASSETS"); e && *e) return fs::is_directory(e) ? std::string(e) : std::string();
#ifdef BRDFCL_SOURCE_DIR
  const fs::path p = fs::path(BRDFCL_SOURCE_DIR) / ".." / "shared" / "assets";
  if (fs::is_directory(p)) return fs::weakly_canonical(p).string();
#endif
  return {};
}

}  // namespace brdfcl::test
