// How the commands report warnings, and the materials reader they share with its warning sink.
#include <cstdio>

#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "host/src/mpi/session.hpp"

namespace brdfcl::cli {

// Under mpirun every rank reads the same inputs: rank 0 alone speaks for them.
void printWarning(const std::string& text) {
  if (mpi::Session::get().rank() == 0) std::fprintf(stderr, "brdfcl: warning: %s\n", text.c_str());
}

std::vector<MaterialParams> readUserMaterials(const std::string& path, bool strict,
                                              const std::function<void(const std::string&)>& warn) {
  MaterialReadOptions options;
  options.warn = warn ? warn : std::function<void(const std::string&)>(printWarning);
  options.strict = strict;
  return readMaterials(path, options);
}

}  // namespace brdfcl::cli
