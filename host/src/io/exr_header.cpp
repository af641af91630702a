// checkExrHeader: the OpenEXR header walked by hand before OpenEXR reads it. OpenEXR trusts the
// header: it allocates what an attribute's size field or a preview's dimensions claim, reads a
// channel list past its declared size, sizes the chunk offset table and the decoding buffers
// from the data window, and only then finds that the file is too short. A few hundred corrupt
// bytes could cost gigabytes or end in bad_alloc. Here every attribute value must have exactly
// the size OpenEXR will read, and the image, its chunks and their offset table must fit the
// limits and the file, so that what OpenEXR allocates is bounded by the file's own size.
#include "io/exr_header.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <map>
#include <string>

#include "brdfcl/error.hpp"
#include "io/messages.hpp"

namespace brdfcl::detail {
namespace {

// OpenEXR version-field flags (OpenEXR file layout, "Version Field").
constexpr std::uint32_t kTiledFlag = 0x200;
constexpr std::uint32_t kNonImageFlag = 0x800;  // deep data
constexpr std::uint32_t kMultiPartFlag = 0x1000;

// Attribute types whose value OpenEXR reads as a fixed number of bytes, whatever the size field says.
struct FixedType {
  const char* name;
  std::int32_t size;
};
constexpr FixedType kFixedTypes[] = {
    {"box2i", 16},         {"box2f", 16},   {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
    {"double", 8},         {"envmap", 1},   {"float", 4},           {"int", 4},         {"keycode", 28},
    {"lineOrder", 1},      {"m33f", 36},    {"m33d", 72},           {"m44f", 64},       {"m44d", 128},
    {"rational", 8},       {"tiledesc", 9}, {"timecode", 8},        {"v2i", 8},         {"v2f", 8},
    {"v2d", 16},           {"v3i", 12},     {"v3f", 12},            {"v3d", 24},
};

// Scan lines per chunk for each compression (NO, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA,
// DWAB); 0 for others, which OpenEXR rejects itself.
int linesPerChunk(unsigned compression) {
  constexpr int kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  return compression < std::size(kLines) ? kLines[compression] : 0;
}

std::uint32_t le32(const unsigned char* b) {
  return b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
}

std::string shownName(const std::string& s) { return printable(s, 60, ' '); }

class HeaderWalk {
 public:
  HeaderWalk(const std::string& path, const std::string& shown) : shown_(shown) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw Error("cannot read '" + shown_ + "': " + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0) {
      const int err = errno;
      ::close(fd_);
      throw Error("cannot read '" + shown_ + "': " + std::strerror(err));
    }
    size_ = st.st_size > 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
  }
  ~HeaderWalk() { ::close(fd_); }
  HeaderWalk(const HeaderWalk&) = delete;
  HeaderWalk& operator=(const HeaderWalk&) = delete;

  ExrLayout run() {
    unsigned char b[8];
    const std::size_t got = read(0, b, 8);
    const bool magic = got >= 4 && b[0] == 0x76 && b[1] == 0x2f && b[2] == 0x31 && b[3] == 0x01;
    if (!magic)
      throw Error(shown_ + ": not an OpenEXR file (" +
                  (got == 0 ? std::string("the file is empty") : "no EXR magic number") +
                  "); save the image as OpenEXR (.exr)");
    if (got < 8) throw truncated();
    const std::uint32_t version = le32(b + 4);
    if (version & kMultiPartFlag)
      throw Error(shown_ +
                  ": multi-part OpenEXR file; brdfcl reads single-part files only: save all channels in one part");
    if (version & kNonImageFlag)
      throw Error(shown_ + ": deep OpenEXR file; brdfcl reads flat images only: flatten the deep data");

    pos_ = 8;
    std::string name, type;
    for (;;) {
      name = readName(size_);
      if (name.empty()) break;
      type = readName(size_);
      if (read(pos_, b, 4) < 4) throw truncated();
      const auto size = static_cast<std::int32_t>(le32(b));
      pos_ += 4;
      if (size < 0) throw corrupt("attribute '" + shownName(name) + "' claims " + std::to_string(size) + " bytes");
      if (static_cast<std::uint64_t>(size) > size_ - pos_) throw truncated();
      attribute(name, type, static_cast<std::uint32_t>(size));
    }
    return layout(version);
  }

 private:
  // Up to n bytes at offset; fewer only at the end of the file.
  std::size_t read(std::uint64_t offset, unsigned char* b, std::size_t n) const {
    std::size_t got = 0;
    while (got < n) {
      const ssize_t r = ::pread(fd_, b + got, n - got, static_cast<off_t>(offset + got));
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw Error("cannot read '" + shown_ + "': " + std::strerror(errno));
      if (r == 0) break;
      got += static_cast<std::size_t>(r);
    }
    return got;
  }

  Error truncated() const { return Error(shown_ + ": truncated OpenEXR file (ends inside the header); write the file again"); }
  Error corrupt(const std::string& what) const {
    return Error(shown_ + ": corrupt OpenEXR header (" + what + "); write the file again");
  }

  // A NUL-terminated name of at most 255 bytes (OpenEXR's limit) ending before `end`.
  std::string readName(std::uint64_t end) {
    unsigned char b[256];
    const std::size_t n = read(pos_, b, static_cast<std::size_t>(std::min<std::uint64_t>(sizeof b, end - pos_)));
    const auto* nul = static_cast<const unsigned char*>(std::memchr(b, 0, n));
    if (!nul) {
      if (n == sizeof b) throw corrupt("a name longer than 255 bytes");
      if (end < size_) throw corrupt("a name runs past the end of its attribute");
      throw truncated();
    }
    std::string s(reinterpret_cast<const char*>(b), static_cast<std::size_t>(nul - b));
    pos_ += s.size() + 1;
    return s;
  }

  // Checks one attribute value of `size` bytes at pos_ and moves past it.
  void attribute(const std::string& name, const std::string& type, std::uint32_t size) {
    const std::uint64_t end = pos_ + size;
    auto mismatch = [&](const std::string& expected) {
      return corrupt("attribute '" + shownName(name) + "' of type '" + shownName(type) + "' has " +
                     std::to_string(size) + " bytes, expected " + expected);
    };
    auto listMismatch = [&] {
      return corrupt("the channel list '" + shownName(name) + "' does not end where its size of " +
                     std::to_string(size) + " bytes says");
    };
    unsigned char b[16];
    const auto fixed = std::find_if(std::begin(kFixedTypes), std::end(kFixedTypes),
                                    [&](const FixedType& t) { return type == t.name; });
    if (fixed != std::end(kFixedTypes)) {
      if (size != static_cast<std::uint32_t>(fixed->size)) throw mismatch(std::to_string(fixed->size));
      if (name == "dataWindow" && type == "box2i") {
        read(pos_, b, 16);
        for (int i = 0; i < 4; ++i) window_[i] = static_cast<std::int32_t>(le32(b + 4 * i));
      } else if (name == "tiles" && type == "tiledesc") {
        read(pos_, b, 8);
        tile_[0] = le32(b);
        tile_[1] = le32(b + 4);
      } else if (name == "compression" && type == "compression") {
        read(pos_, b, 1);
        compression_ = b[0];
      }
    } else if (type == "chlist") {
      // OpenEXR reads entries up to an empty name, wherever the size field says the value ends.
      for (;;) {
        const std::string channel = readName(end);
        if (channel.empty()) break;
        if (end - pos_ < 16) throw listMismatch();
        read(pos_, b, 4);
        // HALF takes 2 bytes; UINT, FLOAT (and invalid types, which OpenEXR rejects) 4.
        if (name == "channels") channelBytes_[channel] = le32(b) == 1 ? 2 : 4;
        pos_ += 16;
      }
      if (pos_ != end) throw listMismatch();
    } else if (type == "preview") {
      if (size < 8) throw mismatch("at least 8");
      read(pos_, b, 8);
      const std::uint64_t pixels = static_cast<std::uint64_t>(le32(b)) * le32(b + 4);
      if (pixels > (size - 8) / 4 || 8 + 4 * pixels != size) throw mismatch("8 + 4 * width * height of the preview");
    } else if (type == "floatvector") {
      if (size % 4 != 0) throw mismatch("a multiple of 4");
    }
    // Strings, string vectors, ID manifests and unknown types are read as `size` bytes.
    pos_ = end;
  }

  ExrLayout layout(std::uint32_t version) const {
    ExrLayout out;
    out.width = static_cast<long long>(window_[2]) - window_[0] + 1;
    out.height = static_cast<long long>(window_[3]) - window_[1] + 1;
    if (!exrImageSizeOk(out.width, out.height)) throw Error(exrImageSizeError(shown_, out.width, out.height));
    long long chunks = 0, chunkWidth = out.width;
    if (version & kTiledFlag) {
      if (tile_[0] == 0 || tile_[1] == 0 || tile_[0] > kExrMaxChunkBytes || tile_[1] > kExrMaxChunkBytes)
        throw corrupt("tile size " + std::to_string(tile_[0]) + "x" + std::to_string(tile_[1]));
      chunks = ((out.width + tile_[0] - 1) / tile_[0]) * ((out.height + tile_[1] - 1) / tile_[1]);
      chunkWidth = std::max<long long>(out.width, tile_[0]);
      out.chunkLines = static_cast<int>(std::min<long long>(tile_[1], out.height));
    } else if (const int lines = linesPerChunk(compression_)) {
      chunks = (out.height + lines - 1) / lines;
      out.chunkLines = lines;
    }
    // Each chunk has an 8-byte entry in the offset table right after the header.
    if (static_cast<std::uint64_t>(chunks) * 8 > size_ - pos_)
      throw Error(shown_ + ": truncated OpenEXR file (too short for the offsets of its " + std::to_string(chunks) +
                  " chunks of pixels); write the file again");
    long long pixelBytes = 0;
    for (const auto& c : channelBytes_) pixelBytes += c.second;
    const long long lines = (version & kTiledFlag) ? tile_[1] : out.chunkLines;
    // chunkWidth <= 2^30 and lines <= 2^30: the check divides rather than multiplies three factors.
    if (pixelBytes > 0 && chunkWidth * lines > kExrMaxChunkBytes / pixelBytes)
      throw Error(shown_ + ": unsupported OpenEXR layout: decoding one chunk of " + std::to_string(chunkWidth) + "x" +
                  std::to_string(lines) + " pixels of " + std::to_string(channelBytes_.size()) +
                  " channels would take more than " + std::to_string(kExrMaxChunkBytes >> 20) +
                  " MiB; write it with fewer channels, smaller tiles or another compression");
    return out;
  }

  std::string shown_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::uint64_t pos_ = 0;
  // OpenEXR's defaults for a header without these attributes: 64 x 64, ZIP.
  std::int32_t window_[4] = {0, 0, 63, 63};
  std::uint32_t tile_[2] = {0, 0};
  unsigned compression_ = 3;
  std::map<std::string, int> channelBytes_;
};

}  // namespace

bool exrImageSizeOk(long long width, long long height) {
  // Each side first, so that the product cannot overflow.
  return width >= 1 && height >= 1 && width <= kExrMaxSide && height <= kExrMaxSide &&
         width * height <= kExrMaxPixels;
}

std::string exrImageSizeError(const std::string& shown, long long width, long long height) {
  return shown + ": unsupported image size " + std::to_string(width) + "x" + std::to_string(height) + " (at most " +
         std::to_string(kExrMaxPixels) + " pixels and " + std::to_string(kExrMaxSide) + " on a side)";
}

ExrLayout checkExrHeader(const std::string& path, const std::string& shown) { return HeaderWalk(path, shown).run(); }

}  // namespace brdfcl::detail
