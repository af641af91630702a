// libFuzzer harness: glTF material JSON (readMaterials, through a scratch file so that the
// whole-file reader is covered too). Seeds: tests/fuzz/corpus/materials/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/io.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const brdfcl::fuzz::ScratchFile file(".json");
  const std::string& path = file.write(data, size);
  // The warning text is built only when there is a callback; keep it in the fuzzed paths.
  std::size_t warnings = 0;
  brdfcl::MaterialReadOptions options;
  options.warn = [&](const std::string&) { ++warnings; };
  options.strict = size % 2 == 1;  // a typo's two outcomes: the warning and the error
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::readMaterials(path, options); });
  return 0;
}
