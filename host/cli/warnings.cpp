// How the commands report warnings, and the materials reader they share with its warning sink.
#include <cstdio>

#include "brdfcl/io.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

void printWarning(const std::string& text) { std::fprintf(stderr, "brdfcl: warning: %s\n", text.c_str()); }

std::vector<MaterialParams> readUserMaterials(const std::string& path, bool strict) {
  MaterialReadOptions options;
  options.warn = printWarning;
  options.strict = strict;
  return readMaterials(path, options);
}

}  // namespace brdfcl::cli
