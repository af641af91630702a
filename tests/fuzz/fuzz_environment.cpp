// libFuzzer harness: environment images through readEnvironmentRgb, which tells Radiance HDR from
// OpenEXR by content; the seeds are Radiance files (flat and run-length encoded), so this mostly
// drives hdr.cpp's header and scan-line checks and stb_image behind them. Seeds:
// tests/fuzz/corpus/environment/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/image.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const brdfcl::fuzz::ScratchFile file(".hdr");
  const std::string& path = file.write(data, size);
  int width = 0, height = 0;
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::readEnvironmentRgb(path, width, height); });
  return 0;
}
