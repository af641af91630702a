// Whole-file reading shared by the JSON readers (materials, scene).
#pragma once
#include <string>

namespace brdfcl::detail {

// Reads `path` into `out`; returns 0 or the errno that stopped it (EISDIR for a directory).
int readWholeFile(const std::string& path, std::string& out);

}  // namespace brdfcl::detail
