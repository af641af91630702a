// Whole-file reading shared by the JSON readers (materials, scene), and whole-file writing for
// the writers that build their output in memory (PNG, LUT text).
#pragma once
#include <cstddef>
#include <string>

namespace brdfcl::detail {

// Reads `path` into `out`; returns 0 or the errno that stopped it (EISDIR for a directory, EFBIG
// for a file that is not regular, such as a pipe or /dev/zero, that gives more than
// maxJsonBytes(): a regular file's size is known and honest, a stream's is not).
int readWholeFile(const std::string& path, std::string& out);

// Reads a whole input file of at most `maxRegular` bytes (0: maxJsonBytes()) into `out`; any
// other file (pipe, device) at most maxJsonBytes(). Throws a one-line Error: the cap's
// (jsonBytesRefusal), or "cannot read <what>'<shown>': <errno text>" (`what`: "" or e.g.
// "materials file ").
// The maxRegular for readInputFile of a glTF or materials file: a regular .glb is read whole
// (its JSON chunk is checked against maxJsonBytes() by glbJsonChunk; its binary data is what it
// claims), anything else up to maxJsonBytes().
std::size_t maxInputFileBytes(const std::string& path);

void readInputFile(const std::string& path, const std::string& shown, const std::string& what, std::string& out,
                   std::size_t maxRegular = 0);

// Replaces the contents of the existing file `path` with `size` bytes; returns 0 or the errno of
// the write or close that failed (ENOSPC, EFBIG, EIO, ...).
int writeWholeFile(const std::string& path, const void* data, std::size_t size);

}  // namespace brdfcl::detail
