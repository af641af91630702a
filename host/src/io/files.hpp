// Whole-file reading shared by the JSON readers (materials, scene), and whole-file writing for
// the writers that build their output in memory (PNG, LUT text).
#pragma once
#include <cstddef>
#include <string>

namespace brdfcl::detail {

// Reads `path` into `out`; returns 0 or the errno that stopped it (EISDIR for a directory).
int readWholeFile(const std::string& path, std::string& out);

// Replaces the contents of the existing file `path` with `size` bytes; returns 0 or the errno of
// the write or close that failed (ENOSPC, EFBIG, EIO, ...).
int writeWholeFile(const std::string& path, const void* data, std::size_t size);

}  // namespace brdfcl::detail
