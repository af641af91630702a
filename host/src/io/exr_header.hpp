// The checks an OpenEXR file's header must pass before OpenEXR itself reads it (image.cpp's
// readExrChannels), and the limits on what brdfcl accepts.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "brdfcl/image.hpp"

namespace brdfcl::detail {

// A corrupt header can claim billions of pixels: without limits, the reader's allocations would
// end in bad_alloc (an internal error) instead of a message about the file. 2^28 pixels is a
// 16384 x 16384 image.
constexpr long long kExrMaxPixels = 1LL << 28;
constexpr long long kExrMaxSide = 1LL << 16;
// What OpenEXR may allocate to decode one chunk (a block of scan lines, or a tile) of all channels.
constexpr long long kExrMaxChunkBytes = 1LL << 30;

struct ExrLayout {
  long long width = 0, height = 0;
  int chunkLines = 1;  // scan lines OpenEXR decodes together: a chunk's lines or a tile's height
};

// The image size as readExrChannels reports it: "<file>: unsupported image size WxH (...)".
std::string exrImageSizeError(const std::string& shown, long long width, long long height);
bool exrImageSizeOk(long long width, long long height);

// Walks the magic number, the version field and the header attributes, and throws a one-line
// brdfcl::Error starting with `shown` for a file that is not EXR, is multi-part or deep, ends
// inside its header, has an attribute whose value does not match its size, an image larger
// than the limits above, or too few bytes after the header for its chunk offset table.
ExrLayout checkExrHeader(const std::string& path, const std::string& shown);

// readExrChannels and readExrRgb (brdfcl/image.hpp) with `checkSize` called with the header's
// width and height after checkExrHeader and before any pixel is decoded (it throws to refuse).
std::vector<std::vector<float>> readExrChannels(
    const std::string& path,
    const std::function<std::vector<std::string>(const std::vector<ExrChannelInfo>&)>& choose, int& width,
    int& height, const std::function<void(long long, long long)>& checkSize);
std::vector<float> readExrRgb(const std::string& path, int& width, int& height,
                              const std::function<void(long long, long long)>& checkSize);

}  // namespace brdfcl::detail
