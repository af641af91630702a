// libFuzzer harness: samples NPY (readSamples picks the format by the .npy extension). Each
// input is read both in grid mode (no material count, material column optional) and as the
// evaluator reads it for 4 materials, whole and streamed in small chunks, which must agree
// (fuzz_samples.hpp). Seeds: tests/fuzz/corpus/samples_npy/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/io.hpp"
#include "fuzz_samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const brdfcl::fuzz::ScratchFile file(".npy");
  const std::string& path = file.write(data, size);
  // Chunks of 1 to 8 rows, so that small inputs still cross chunk boundaries everywhere.
  const std::size_t chunk = 1 + (size > 0 ? data[size - 1] % 8 : 0);
  brdfcl::fuzz::expectStreamMatchesWhole(path, 0, true, chunk);
  brdfcl::fuzz::expectStreamMatchesWhole(path, 4, false, chunk);
  return 0;
}
