// libFuzzer harness: glTF loader (gltf::loadFromMemory), .gltf text or .glb bytes (told apart by
// the GLB magic). External buffers and images resolve against an empty directory, and the element
// and image limits are lowered so that a hostile file's claims stay within libFuzzer's memory
// limit. Seeds: tests/fuzz/corpus/gltf/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/gltf.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const brdfcl::fuzz::EmptyDirectory baseDir;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  brdfcl::gltf::LoadOptions options;
  options.maxElements = std::size_t(1) << 20;
  options.maxImagePixels = std::size_t(1) << 20;
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::gltf::loadFromMemory(bytes, "fuzz.gltf", baseDir.path(), options); });
  return 0;
}
