// The test-only probe kernels of tests/kernels/, read from the source tree and built by the
// library's runtime with their #include lines resolved from the embedded kernels/, as the
// product's own kernels are; they are not part of the library.
#pragma once
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "host/src/runtime/opencl.hpp"

namespace brdfcl::test {

// The program of tests/kernels/<file> with `defines`, from the runtime's program cache.
inline cl::Program testProgram(Runtime& rt, const std::string& file, const std::string& defines) {
  const std::string path = std::string(BRDFCL_SOURCE_DIR) + "/tests/kernels/" + file;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the test kernel " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return rt.opencl().programFromSource(file, text.str(), defines);
}

}  // namespace brdfcl::test
