// Environment images in either format brdfcl accepts: OpenEXR (readExrRgb) or Radiance RGBE
// (.hdr, decoded by stb_image after the checks below), told apart by their first bytes.
// Every failure is one line naming the file.
#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

// No STB_IMAGE_IMPLEMENTATION: stb_image comes from Debian's libstb.so (CMakeLists.txt), which
// libtinygltf.so links too; a compiled-in copy would interpose on tinygltf's.
#include <stb/stb_image.h>

#include "io/exr_header.hpp"
#include "io/files.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"

namespace brdfcl {
namespace {

std::string printable(const std::string& s, std::size_t maxLength = 300) { return detail::printable(s, maxLength, ' '); }

bool startsWith(const std::string& s, const char* prefix) { return s.compare(0, std::strlen(prefix), prefix) == 0; }

bool isRadiance(const std::string& bytes) { return startsWith(bytes, "#?RADIANCE") || startsWith(bytes, "#?RGBE"); }

bool isExr(const std::string& bytes) { return startsWith(bytes, "\x76\x2f\x31\x01"); }

// The header as stb_image parses it (lines up to the blank one, then "-Y <h> +X <w>"), read here
// first so that the size limits apply before stb allocates, and so that messages can be precise.
// Returns the offset of the pixel data.
std::size_t parseHeader(const std::string& bytes, const std::string& shown, long long& width, long long& height) {
  auto fail = [&](const std::string& why) -> void {
    throw Error(shown + ": cannot decode Radiance HDR (" + why + "); write it again as RGBE, top row first");
  };
  std::size_t at = 0;
  auto line = [&]() {
    const std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) fail("the header ends before the image size line");
    std::string l = bytes.substr(at, end - at);
    at = end + 1;
    return l;
  };
  const std::string magic = line();
  if (magic != "#?RADIANCE" && magic != "#?RGBE") fail("unexpected first line '" + printable(magic, 40) + "'");
  bool rgbe = false;
  for (std::string l = line(); !l.empty(); l = line()) {
    if (l == "FORMAT=32-bit_rle_rgbe") rgbe = true;
    if (startsWith(l, "FORMAT=") && l != "FORMAT=32-bit_rle_rgbe")
      fail("pixel format '" + printable(l.substr(7), 40) + "'; only 32-bit_rle_rgbe is read");
  }
  if (!rgbe) fail("no FORMAT=32-bit_rle_rgbe line");
  const std::string size = line();
  // Other orientations (+Y, -X, or X before Y) are legal Radiance but rare; stb_image reads only this one.
  char* end = nullptr;
  const char* s = size.c_str();
  if (std::strncmp(s, "-Y ", 3) == 0) {
    height = std::strtoll(s + 3, &end, 10);
    if (end != s + 3 && std::strncmp(end, " +X ", 4) == 0) {
      const char* w = end + 4;
      width = std::strtoll(w, &end, 10);
      if (end != w && *end == '\0') {
        if (!detail::exrImageSizeOk(width, height)) throw Error(detail::exrImageSizeError(shown, width, height));
        return at;
      }
    }
  }
  fail("image size line '" + printable(size, 40) + "'; expected '-Y <height> +X <width>'");
  return at;
}

// Walks the scan lines as stb_image will decode them, without decoding: stb_image 2.27 reads
// zeros past the end of the data (a truncated flat file would come out black at the bottom)
// and loops forever on a zero-length run-length packet at the end of a truncated file.
void checkPixelData(const std::string& bytes, std::size_t at, long long width, long long height, const std::string& shown) {
  auto fail = [&](const std::string& why) {
    throw Error(shown + ": cannot decode Radiance HDR (" + why + "); the file is truncated or corrupt: write it again");
  };
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
  const std::size_t size = bytes.size();
  const auto isRleStart = [&](std::size_t i) {
    return i + 4 <= size && byte(i) == 2 && byte(i + 1) == 2 && (byte(i + 2) & 0x80) == 0 &&
           ((static_cast<long long>(byte(i + 2)) << 8) | byte(i + 3)) == width;
  };
  // stb_image: flat RGBE for widths outside [8, 32768) or when the first scan line does not start
  // with a run-length marker; then every scan line must have one.
  if (width < 8 || width >= 32768 || !isRleStart(at)) {
    if ((size - at) / 4 < static_cast<std::size_t>(width * height))
      fail("flat pixel data of " + std::to_string(size - at) + " bytes, expected " + std::to_string(4 * width * height));
    return;
  }
  for (long long y = 0; y < height; ++y) {
    if (at + 4 > size) fail("scan line " + std::to_string(y) + " is missing");
    if (!isRleStart(at)) fail("scan line " + std::to_string(y) + " lacks its run-length marker");
    at += 4;
    for (int c = 0; c < 4; ++c)
      for (long long x = 0; x < width;) {
        if (at >= size) fail("scan line " + std::to_string(y) + " ends early");
        const unsigned count = byte(at++);
        const long long n = count > 128 ? count - 128 : count;
        if (n == 0 || n > width - x) fail("bad run-length packet in scan line " + std::to_string(y));
        const std::size_t skip = count > 128 ? 1 : static_cast<std::size_t>(n);
        if (size - at < skip) fail("scan line " + std::to_string(y) + " ends early");
        at += skip;
        x += n;
      }
  }
}

}  // namespace

std::vector<float> readRadianceHdr(const std::string& path, int& width, int& height) {
  const std::string shown = printable(path);
  // stb_image takes the size as an int; checked before the file is read into memory.
  if (struct stat st {}; ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
                         st.st_size > std::numeric_limits<int>::max())
    throw Error(shown + ": cannot decode Radiance HDR (the file is larger than 2 GiB, stb_image's limit); use OpenEXR");
  const detail::ReadingInput reading(shown);
  std::string bytes;
  detail::readInputFile(path, shown, "", bytes, std::numeric_limits<int>::max());
  if (!isRadiance(bytes))
    throw Error(shown + ": not a Radiance HDR file (it does not start with #?RADIANCE or #?RGBE)");
  long long w = 0, h = 0;
  const std::size_t data = parseHeader(bytes, shown, w, h);
  // Before the scan lines are walked or decoded: a few kilobytes of run-length data can declare
  // gigabytes of float pixels (12 bytes each, and the prefiltered chain after).
  detail::checkImagePixels(detail::ImageKind::Environment, shown, w, h);
  checkPixelData(bytes, data, w, h, shown);
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error(shown + ": cannot decode Radiance HDR (the file is larger than 2 GiB, stb_image's limit); use OpenEXR");
  int sw = 0, sh = 0, comp = 0;
  // stbi_loadf converts LDR files with stbi_ldr_to_hdr_gamma, but only Radiance data reaches it
  // here, which it returns as decoded (m * 2^(e - 136)), with no gamma or scale.
  std::unique_ptr<float, void (*)(void*)> pixels(
      stbi_loadf_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &sw, &sh,
                             &comp, 3),
      stbi_image_free);
  if (!pixels) {
    const char* why = stbi_failure_reason();
    throw Error(shown + ": cannot decode Radiance HDR (" + printable(why ? why : "unknown reason", 100) +
                "); the file is truncated or corrupt: write it again");
  }
  if (sw != w || sh != h)
    throw Error("internal: " + shown + ": stb_image decoded " + std::to_string(sw) + "x" + std::to_string(sh) +
                    " where brdfcl read the header as " + std::to_string(w) + "x" + std::to_string(h),
                3);
  const std::size_t n = 3 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<float> rgb(pixels.get(), pixels.get() + n);
  width = sw;
  height = sh;
  return rgb;
}

std::vector<float> readEnvironmentRgb(const std::string& path, int& width, int& height) {
  const std::string shown = printable(path);
  std::string head;
  {
    // Only the magic number is needed to dispatch; each reader reports its own errors.
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!f) throw Error("cannot read '" + shown + "': " + std::strerror(errno));
    char buf[16];
    head.assign(buf, std::fread(buf, 1, sizeof buf, f.get()));
    if (std::ferror(f.get())) throw Error("cannot read '" + shown + "': " + std::strerror(errno));
  }
  std::vector<float> rgb;
  if (isRadiance(head))
    rgb = readRadianceHdr(path, width, height);
  else if (isExr(head))
    rgb = detail::readExrRgb(path, width, height, [&](long long w, long long h) {
      detail::checkImagePixels(detail::ImageKind::Environment, shown, w, h);
    });
  else
    throw Error(shown + ": not an environment image: expected OpenEXR or Radiance HDR (.hdr, starting with #?RADIANCE)");
  // One NaN would spread through every prefiltered level. (RGBE cannot encode one; EXR can.)
  for (std::size_t i = 0; i < rgb.size(); ++i)
    if (!std::isfinite(rgb[i]))
      throw Error(shown + ": texel (" + std::to_string((i / 3) % std::size_t(width)) + ", " +
                  std::to_string((i / 3) / std::size_t(width)) + ") has a non-finite value (" +
                  (std::isnan(rgb[i]) ? "nan" : rgb[i] > 0 ? "inf" : "-inf") + ") in channel " + "RGB"[i % 3] +
                  "; an environment needs finite radiance");
  return rgb;
}

}  // namespace brdfcl
