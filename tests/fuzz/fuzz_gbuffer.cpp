// libFuzzer harness: OpenEXR inputs, read as a G-buffer (readGBuffer, with and without the value
// check) and as an environment map (readExrRgb), which share the checked channel reader.
// Seeds: tests/fuzz/corpus/gbuffer/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const brdfcl::fuzz::ScratchFile file(".exr");
  const std::string& path = file.write(data, size);
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::readGBuffer(path); });
  // Unchecked, so that inputs with arbitrary pixel values still reach the camera attributes.
  brdfcl::GBufferReadOptions unchecked;
  unchecked.check = false;
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::readGBuffer(path, unchecked); });
  int width = 0, height = 0;
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::readExrRgb(path, width, height); });
  return 0;
}
