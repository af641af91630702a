// What an input may make brdfcl allocate: the pixel limits per kind of image (checked from the
// header, before decoding), the byte cap on JSON inputs and on inputs that are not regular files,
// the CSV line cap, and the name of the input being read for the out-of-memory message.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace brdfcl::detail {

// Textures, environments and diff images have a fixed pixel limit; a G-buffer's is the frame
// budget of `shade` (frame_budget.hpp). BRDFCL_MAX_IMAGE_PIXELS, when set, replaces all of them.
enum class ImageKind { Texture, Environment, GBuffer, DiffImage };
constexpr std::uint64_t kMaxTexturePixels = std::uint64_t(1) << 26;      // 8192 x 8192
constexpr std::uint64_t kMaxEnvironmentPixels = std::uint64_t(1) << 26;  // 8192 x 8192
constexpr std::uint64_t kMaxDiffPixels = std::uint64_t(1) << 25;         // 8192 x 4096: about 70 B each

// BRDFCL_MAX_IMAGE_PIXELS as a number, 0 when unset; a bad value throws a one-line Error.
std::uint64_t imagePixelOverride();

// "" when an image of `kind` may have width x height pixels; otherwise the refusal, without the
// image's name: "declares 16384x16384 pixels (268M), more than the 67M a texture may have; set
// BRDFCL_MAX_IMAGE_PIXELS to allow it". G-buffers are checked by checkImagePixels only.
std::string imagePixelRefusal(ImageKind kind, long long width, long long height);

// Throws Error("<shown> <refusal>") when imagePixelRefusal refuses; a G-buffer without the
// variable gets the frame budget's message.
void checkImagePixels(ImageKind kind, const std::string& shown, long long width, long long height);

// BRDFCL_MAX_JSON_BYTES (default 256 MiB): the largest materials, scene or .gltf file, GLB JSON
// chunk, and the most bytes read from any input that is not a regular file (pipe, device).
constexpr std::size_t kDefaultMaxJsonBytes = std::size_t(256) << 20;
std::size_t maxJsonBytes();
// "256 MiB", or "1000 bytes" for a cap that is not a whole number of MiB.
std::string byteLimitText(std::size_t cap);
// The error for an input past maxJsonBytes; `size` is its size, or 0 for a stream that kept going.
std::string jsonBytesRefusal(const std::string& shown, std::uint64_t size, std::size_t cap);

// CSV lines (the header included) longer than this are refused before they are read whole.
constexpr std::size_t kMaxCsvLineBytes = std::size_t(1) << 20;

// Names the input this thread is reading, for the out-of-memory message (outOfMemoryMessage in
// brdfcl/error.hpp). When an exception leaves the scope the name stays, so that the handler that
// catches a bad_alloc can still read it.
class ReadingInput {
 public:
  explicit ReadingInput(const std::string& shown);
  ~ReadingInput();
  ReadingInput(const ReadingInput&) = delete;
  ReadingInput& operator=(const ReadingInput&) = delete;

 private:
  std::string previous_;
  int exceptions_;
};

}  // namespace brdfcl::detail
