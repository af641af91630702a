// glbJsonChunk (glb.hpp): the GLB header and chunk checks that tinygltf leaves out (it trusts the
// BIN chunk's length), done once for every reader of .glb files.
#include "io/glb.hpp"

#include "brdfcl/error.hpp"
#include "io/input_limits.hpp"

namespace brdfcl::detail {
namespace {
constexpr std::uint32_t kChunkJson = 0x4E4F534A, kChunkBin = 0x004E4942;
}  // namespace

std::uint32_t le32(const std::string& b, std::size_t at) {
  return std::uint32_t(std::uint8_t(b[at])) | std::uint32_t(std::uint8_t(b[at + 1])) << 8 |
         std::uint32_t(std::uint8_t(b[at + 2])) << 16 | std::uint32_t(std::uint8_t(b[at + 3])) << 24;
}

bool hasGlbMagic(const std::string& bytes) { return bytes.size() >= 4 && le32(bytes, 0) == kGlbMagic; }

std::string glbJsonChunk(const std::string& b, const std::string& source, std::size_t& binSize) {
  auto bad = [&](const std::string& what) { throw Error(source + ": " + what); };
  if (b.size() < 12) bad("truncated GLB file (" + std::to_string(b.size()) + " bytes, shorter than the 12-byte header); re-export the file");
  if (le32(b, 4) != 2)
    bad("unsupported GLB version " + std::to_string(le32(b, 4)) + "; brdfcl reads glTF 2.0 binaries (version 2)");
  const std::uint64_t length = le32(b, 8);
  if (length > b.size())
    bad("truncated GLB file: the header says " + std::to_string(length) + " bytes, the file has " +
        std::to_string(b.size()) + "; download or export it again");
  if (length < b.size())
    bad("the GLB header says " + std::to_string(length) + " bytes, but the file has " + std::to_string(b.size()) +
        "; re-export the file");
  if (length < 20) bad("truncated GLB file: no room for the JSON chunk; re-export the file");
  const std::uint64_t jsonLength = le32(b, 12);
  if (le32(b, 16) != kChunkJson) bad("GLB chunk 0 is not JSON; re-export the file");
  if (jsonLength == 0 || 20 + jsonLength > length)
    bad("truncated GLB chunk 0 (JSON): it claims " + std::to_string(jsonLength) + " bytes, " +
        std::to_string(length - 20) + " remain; re-export the file");
  if (jsonLength > maxJsonBytes())
    bad("its JSON chunk has " + std::to_string(jsonLength) + " bytes, more than " +
        byteLimitText(maxJsonBytes()) + " (BRDFCL_MAX_JSON_BYTES); set BRDFCL_MAX_JSON_BYTES to allow more");
  const std::uint64_t next = 20 + jsonLength;
  binSize = 0;
  if (next < length) {
    if (length - next < 8) bad("truncated GLB chunk 1: its 8-byte header is cut off; re-export the file");
    const std::uint64_t binLength = le32(b, std::size_t(next));
    if (le32(b, std::size_t(next + 4)) != kChunkBin) bad("GLB chunk 1 is not BIN; re-export the file");
    if (binLength > length - next - 8)
      bad("truncated GLB chunk 1 (BIN): it claims " + std::to_string(binLength) + " bytes, " +
          std::to_string(length - next - 8) + " remain; re-export the file");
    if (binLength < 4 || binLength % 4 != 0)
      bad("GLB chunk 1 (BIN) has " + std::to_string(binLength) + " bytes, not a non-zero multiple of 4; re-export the file");
    binSize = std::size_t(binLength);
  }
  return b.substr(20, std::size_t(jsonLength));
}

}  // namespace brdfcl::detail
