// libFuzzer harness: samples CSV (readSamples picks the format by the .csv extension). Each
// input is read both in grid mode (no material count, material column optional) and as the
// evaluator reads it for 4 materials. Seeds: tests/fuzz/corpus/samples_csv/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/io.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const brdfcl::fuzz::ScratchFile file(".csv");
  const std::string& path = file.write(data, size);
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::readSamples(path, 0, true); });
  brdfcl::fuzz::expectCleanRefusal([&] { brdfcl::readSamples(path, 4, false); });
  return 0;
}
