// The limits of input_limits.hpp: environment variables parsed once per call (they are read
// rarely: once per image or file), and the thread's current input for the out-of-memory message.
#include "io/input_limits.hpp"

#include <cerrno>
#include <cstdlib>
#include <exception>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "io/option_style.hpp"

namespace brdfcl {
namespace detail {
namespace {

thread_local std::string tCurrentInput;

// A positive integer from the environment, 0 when unset or empty.
std::uint64_t positiveVariable(const char* name, const char* example) {
  const char* v = std::getenv(name);
  if (!v || !*v) return 0;
  char* end = nullptr;
  errno = 0;
  const unsigned long long n = std::strtoull(v, &end, 10);
  if (*end != '\0' || errno != 0 || n == 0 || v[0] == '-' || v[0] == '+' || v[0] == ' ')
    throw Error(fmt::format("{}={} is not a positive whole number; unset it or give e.g. {}", name, v, example));
  return n;
}

// 268435456 -> "268M", 65536 -> "65536".
std::string millions(std::uint64_t n) {
  return n >= 10000000 ? std::to_string(n / 1000000) + "M" : std::to_string(n);
}

const char* kindName(ImageKind kind) {
  switch (kind) {
    case ImageKind::Texture: return "a texture";
    case ImageKind::Environment: return "an environment";
    case ImageKind::GBuffer: return "a G-buffer";
    case ImageKind::DiffImage: return "an image to diff";
  }
  return "an image";
}

std::uint64_t kindLimit(ImageKind kind) {
  switch (kind) {
    case ImageKind::Texture: return kMaxTexturePixels;
    case ImageKind::Environment: return kMaxEnvironmentPixels;
    case ImageKind::DiffImage: return kMaxDiffPixels;
    case ImageKind::GBuffer: break;
  }
  return UINT64_MAX;
}

}  // namespace

std::uint64_t imagePixelOverride() { return positiveVariable("BRDFCL_MAX_IMAGE_PIXELS", "268435456"); }

std::string imagePixelRefusal(ImageKind kind, long long width, long long height) {
  const std::uint64_t override = imagePixelOverride();
  const std::uint64_t limit = override ? override : kindLimit(kind);
  if (width >= 0 && height >= 0 && std::uint64_t(width) * std::uint64_t(height) <= limit) return "";
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  if (override)
    return fmt::format("declares {}x{} pixels ({}), more than BRDFCL_MAX_IMAGE_PIXELS={} allows; raise it to allow it",
                       width, height, millions(pixels), override);
  return fmt::format("declares {}x{} pixels ({}), more than the {} {} may have; set BRDFCL_MAX_IMAGE_PIXELS to allow it",
                     width, height, millions(pixels), millions(limit), kindName(kind));
}

void checkImagePixels(ImageKind kind, const std::string& shown, long long width, long long height) {
  if (kind == ImageKind::GBuffer && imagePixelOverride() == 0) {
    checkFrameFits(FrameJob::Shade, int(width), int(height), usableHostMemory(), shown);
    return;
  }
  if (const std::string why = imagePixelRefusal(kind, width, height); !why.empty()) throw Error(shown + " " + why);
}

std::size_t maxJsonBytes() {
  const std::uint64_t n = positiveVariable("BRDFCL_MAX_JSON_BYTES", "1073741824");
  return n ? std::size_t(n) : kDefaultMaxJsonBytes;
}

std::string byteLimitText(std::size_t cap) {
  return cap % (1 << 20) == 0 ? std::to_string(cap >> 20) + " MiB" : std::to_string(cap) + " bytes";
}

std::string jsonBytesRefusal(const std::string& shown, std::uint64_t size, std::size_t cap) {
  const std::string limit = byteLimitText(cap);
  if (size == 0)
    return "'" + shown + "' is not a regular file and gives more than " + limit +
           " (BRDFCL_MAX_JSON_BYTES); give a regular file, or set BRDFCL_MAX_JSON_BYTES to allow more";
  return "'" + shown + "' has " + std::to_string(size) + " bytes, more than " + limit +
         " (BRDFCL_MAX_JSON_BYTES); set BRDFCL_MAX_JSON_BYTES to allow more";
}

ReadingInput::ReadingInput(const std::string& shown)
    : previous_(tCurrentInput), exceptions_(std::uncaught_exceptions()) {
  tCurrentInput = shown;
}

ReadingInput::~ReadingInput() {
  if (std::uncaught_exceptions() == exceptions_) tCurrentInput = previous_;
}

}  // namespace detail

std::string outOfMemoryMessage() {
  if (!detail::tCurrentInput.empty())
    return "out of memory while reading '" + detail::tCurrentInput +
           "'; free memory, or check that the file is what it claims to be";
  if (optionStyle() == OptionStyle::Python) return "out of memory; try smaller arrays or a smaller size=, or free memory";
  return "out of memory; try a smaller --size or --chunk, or free memory";
}

}  // namespace brdfcl
