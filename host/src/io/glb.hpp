// The GLB container (glTF 2.0 binary): its header and chunk table, checked completely, shared by
// the glTF loader and the materials reader (a .glb passed to --materials).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace brdfcl::detail {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"

// Little-endian 32-bit word at b[at]; the caller has checked that 4 bytes are there.
std::uint32_t le32(const std::string& b, std::size_t at);

bool hasGlbMagic(const std::string& bytes);

// The JSON chunk of the GLB `b`, after checking the header (version 2, total length equal to the
// file's), the JSON chunk and the optional BIN chunk against the file's bounds; sets binSize (0
// when there is no BIN chunk). Throws Error "<source>: ..." (one line) on any inconsistency.
std::string glbJsonChunk(const std::string& b, const std::string& source, std::size_t& binSize);

}  // namespace brdfcl::detail
