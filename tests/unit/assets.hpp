// Where the real glTF sample assets (the Khronos glTF sample models) are: $BRDFCL_ASSETS,
// else <source dir>/../shared/assets. Tests that need them skip, naming BRDFCL_ASSETS, when absent.
#pragma once
#include <gtest/gtest.h>

#include "tests/assets_dir.hpp"

#include <filesystem>
#include <string>

namespace brdfcl::test {

// The path of `relative` inside the assets folder, or "" when it is missing.
inline std::string assetPath(const std::string& relative) {
  const std::string dir = assetsDir();
  if (dir.empty()) return {};
  const std::string p = dir + "/" + relative;
  return std::filesystem::exists(p) ? p : std::string();
}

// Why a test skips: `if (p.empty()) GTEST_SKIP() << missingAsset("X/y.glb");`
inline std::string missingAsset(const std::string& relative) {
  return "glTF sample asset '" + relative + "' not found: set BRDFCL_ASSETS to the assets folder (default " +
         "<source dir>/../shared/assets; see its README.md)";
}

}  // namespace brdfcl::test

