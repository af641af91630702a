// libFuzzer harness: scene JSON (parseScene). A relative environment path resolves against an
// empty directory, so inputs cannot reach files of the working tree. Seeds: tests/fuzz/corpus/scene/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/scene.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const brdfcl::fuzz::EmptyDirectory baseDir;
  const std::string json(reinterpret_cast<const char*>(data), size);
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::parseScene(json, "scene.json", baseDir.path()); });
  return 0;
}
