// OpenEXR channel reading with the checks every brdfcl EXR input needs, RGB EXR read/write, and
// the PNG display pipeline (exposure, Khronos PBR Neutral, sRGB OETF, stb_image_write).
// Every user-facing failure is one line naming the file; outputs go through the output layer (io.hpp).
#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "io/files.hpp"
#include "io/png.hpp"
#include "io/exr_header.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"

namespace brdfcl {
namespace {

// File names and OpenEXR's messages: longer, with blanks for control characters.
std::string printable(const std::string& s, std::size_t maxLength = 300) { return detail::printable(s, maxLength, ' '); }

}  // namespace

namespace {
std::vector<std::vector<float>> readExrChannelsChecked(
    const std::string& path,
    const std::function<std::vector<std::string>(const std::vector<ExrChannelInfo>&)>& choose, int& width,
    int& height, const std::function<void(long long, long long)>& checkSize) {
  const std::string shown = printable(path);
  const detail::ReadingInput reading(shown);
  const detail::ExrLayout layout = detail::checkExrHeader(path, shown);
  // From the header, before OpenEXR allocates anything: a few hundred kilobytes of compressed
  // scan lines can declare gigabytes of pixels.
  if (checkSize) checkSize(layout.width, layout.height);
  try {
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const Imath::Box2i dw = header.dataWindow();
    const Imath::Box2i disp = header.displayWindow();
    // A data window smaller or larger than the display window would put G-buffer pixels at
    // positions that no longer match the camera's raster, so it is refused rather than padded.
    if (dw.min != disp.min || dw.max != disp.max)
      throw Error(shown + ": the data window (" + std::to_string(dw.min.x) + "," + std::to_string(dw.min.y) + ")-(" +
                  std::to_string(dw.max.x) + "," + std::to_string(dw.max.y) + ") differs from the display window (" +
                  std::to_string(disp.min.x) + "," + std::to_string(disp.min.y) + ")-(" + std::to_string(disp.max.x) +
                  "," + std::to_string(disp.max.y) + "); write the full, uncropped image");
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    if (!detail::exrImageSizeOk(w, h)) throw Error(detail::exrImageSizeError(shown, w, h));

    std::vector<ExrChannelInfo> available;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
      available.push_back({it.name(), it.channel().type == Imf::FLOAT});
    const std::vector<std::string> names = choose(available);

    for (const auto& name : names) {
      const Imf::Channel* c = header.channels().findChannel(name);
      if (!c) throw Error(shown + ": no channel '" + printable(name) + "'");
      if (c->type == Imf::UINT)
        throw Error(shown + ": channel '" + printable(name) + "' is UINT; expected HALF or FLOAT");
      if (c->xSampling != 1 || c->ySampling != 1)
        throw Error(shown + ": channel '" + printable(name) + "' has x/y sampling " + std::to_string(c->xSampling) +
                    "/" + std::to_string(c->ySampling) + ", so its size differs from the image's " +
                    std::to_string(w) + "x" + std::to_string(h) + "; write every channel at full resolution");
    }
    // Checked before reading: readPixels of missing scan lines may throw or leave fill values,
    // depending on where the file ends.
    if (!in.isComplete())
      throw Error(shown + ": truncated OpenEXR file (some scan lines or tiles are missing); write the file again");

    // Read in bands of whole chunks, the planes growing as the pixels decode: a small corrupt
    // file that claims a large image fails in its first chunk, before the memory for the
    // whole image is taken.
    constexpr long long kBandPixels = 1 << 20;
    const long long chunk = std::max(1, layout.chunkLines);
    const long long bandLines = std::max(1LL, (kBandPixels / w) / chunk) * chunk;
    const std::size_t xStride = sizeof(float), yStride = sizeof(float) * static_cast<std::size_t>(w);
    std::vector<std::vector<float>> planes(names.size()), band(names.size());
    for (long long y0 = dw.min.y; y0 <= dw.max.y; y0 += bandLines) {
      const long long lines = std::min<long long>(bandLines, dw.max.y - y0 + 1);
      const std::size_t n = static_cast<std::size_t>(lines * w);
      Imf::FrameBuffer fb;
      for (std::size_t i = 0; i < names.size(); ++i) {
        band[i].resize(n);
        // Slice::Make offsets the base to pixel (0, 0) in integer arithmetic: that address lies
        // outside the buffer, and reaching it with pointer arithmetic would be undefined.
        fb.insert(names[i], Imf::Slice::Make(Imf::FLOAT, band[i].data(), Imath::V2i(dw.min.x, static_cast<int>(y0)),
                                             w, lines, xStride, yStride));
      }
      in.setFrameBuffer(fb);
      in.readPixels(static_cast<int>(y0), static_cast<int>(y0 + lines - 1));
      for (std::size_t i = 0; i < names.size(); ++i) planes[i].insert(planes[i].end(), band[i].begin(), band[i].end());
    }
    width = static_cast<int>(w);
    height = static_cast<int>(h);
    return planes;
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // outOfMemoryMessage names the file (ReadingInput above)
  } catch (const std::exception& e) {
    // OpenEXR reports truncation inside the header or a corrupt chunk as Iex exceptions.
    throw Error(shown + ": cannot read OpenEXR data (" + printable(e.what(), 200) +
                "); the file is truncated or corrupt: write it again");
  }
}
}  // namespace

std::vector<std::vector<float>> readExrChannels(
    const std::string& path,
    const std::function<std::vector<std::string>(const std::vector<ExrChannelInfo>&)>& choose, int& width,
    int& height) {
  return readExrChannelsChecked(path, choose, width, height, {});
}

std::vector<std::vector<float>> detail::readExrChannels(
    const std::string& path,
    const std::function<std::vector<std::string>(const std::vector<ExrChannelInfo>&)>& choose, int& width,
    int& height, const std::function<void(long long, long long)>& checkSize) {
  return readExrChannelsChecked(path, choose, width, height, checkSize);
}

void writeExrRgb(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  if (width < 1 || height < 1 || rgb.size() != 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("writeExrRgb: rgb must hold 3 * width * height floats");
  const std::string shown = printable(path);
  writeAtomically(path, [&](const std::string& tmp) {
    try {
      Imf::Header header(width, height);
      header.compression() = Imf::ZIP_COMPRESSION;
      Imf::FrameBuffer fb;
      const char* names[3] = {"R", "G", "B"};
      // OpenEXR's Slice takes a non-const pointer for both directions; writing only reads it.
      char* base = const_cast<char*>(reinterpret_cast<const char*>(rgb.data()));
      for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 3 * sizeof(float),
                                       3 * sizeof(float) * static_cast<std::size_t>(width)));
      }
      Imf::OutputFile out(tmp.c_str(), header);
      out.setFrameBuffer(fb);
      out.writePixels(height);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error("cannot write '" + shown + "': " + printable(detail::withUserPath(e.what(), tmp, path), 200));
    }
  });
}

std::vector<float> readExrRgb(const std::string& path, int& width, int& height) {
  return detail::readExrRgb(path, width, height, {});
}

std::vector<float> detail::readExrRgb(const std::string& path, int& width, int& height,
                                      const std::function<void(long long, long long)>& checkSize) {
  const std::string shown = brdfcl::printable(path);
  const detail::ReadingInput reading(shown);
  bool grey = false;
  const auto planes = readExrChannelsChecked(
      path,
      [&](const std::vector<ExrChannelInfo>& channels) -> std::vector<std::string> {
        auto has = [&](const char* n) {
          return std::any_of(channels.begin(), channels.end(), [&](const ExrChannelInfo& c) { return c.name == n; });
        };
        if (has("R") && has("G") && has("B")) return {"R", "G", "B"};
        if (has("Y") && !has("R") && !has("G") && !has("B")) {
          grey = true;
          return {"Y"};
        }
        std::string list;
        for (const auto& c : channels) list += (list.empty() ? "" : " ") + c.name;
        throw Error(shown + ": expected channels R, G, B (or Y alone), found: " +
                    brdfcl::printable(list.empty() ? std::string("none") : list, 200));
      },
      width, height, checkSize);
  const std::size_t n = planes[0].size();
  std::vector<float> rgb(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = planes[grey ? 0 : c][i];
  return rgb;
}

Rgb toneMapPbrNeutral(const Rgb& linear) {
  // Constants of the Khronos reference implementation.
  constexpr float startCompression = 0.8f - 0.04f;
  constexpr float desaturation = 0.15f;
  Rgb c;
  for (int i = 0; i < 3; ++i) {
    const float v = linear[i];
    c[i] = !(v > 0.0f) ? 0.0f : std::min(v, std::numeric_limits<float>::max());
  }
  // The offset undoes the 4 % Fresnel floor of dielectrics, with a quadratic toe so that black
  // stays black.
  const float x = std::min({c[0], c[1], c[2]});
  const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
  for (float& v : c) v -= offset;
  const float peak = std::max({c[0], c[1], c[2]});
  if (peak < startCompression) return c;
  const float d = 1.0f - startCompression;
  const float newPeak = 1.0f - d * d / (peak + d - startCompression);
  for (float& v : c) v *= newPeak / peak;
  const float g = 1.0f - 1.0f / (desaturation * (peak - newPeak) + 1.0f);
  for (float& v : c) v = v * (1.0f - g) + newPeak * g;
  return c;
}

float toneMapPbrNeutral(float grey) { return toneMapPbrNeutral(Rgb{grey, grey, grey})[0]; }

void toneMapPbrNeutral(std::vector<float>& rgb) {
  if (rgb.size() % 3 != 0) throw std::invalid_argument("toneMapPbrNeutral: rgb size must be a multiple of 3");
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    const Rgb out = toneMapPbrNeutral(Rgb{rgb[i], rgb[i + 1], rgb[i + 2]});
    rgb[i] = out[0];
    rgb[i + 1] = out[1];
    rgb[i + 2] = out[2];
  }
}

std::uint8_t encodeSrgb8(float linear) {
  const float v = !(linear > 0.0f) ? 0.0f : std::min(linear, 1.0f);
  const float e = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(std::clamp(e, 0.0f, 1.0f) * 255.0f));
}

std::vector<std::uint8_t> displayRgb8(const float* linearRgb, std::size_t pixels, float exposure) {
  const float scale = std::exp2(exposure);
  std::vector<std::uint8_t> out(3 * pixels);
  for (std::size_t i = 0; i < out.size(); i += 3) {
    const Rgb t = toneMapPbrNeutral(Rgb{linearRgb[i] * scale, linearRgb[i + 1] * scale, linearRgb[i + 2] * scale});
    for (int c = 0; c < 3; ++c) out[i + c] = encodeSrgb8(t[c]);
  }
  return out;
}

void writePng(const std::string& path, int width, int height, const std::vector<float>& linearRgb, float exposure) {
  if (width < 1 || height < 1 ||
      linearRgb.size() != 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("writePng: linearRgb must hold 3 * width * height floats");
  if (!std::isfinite(exposure))
    throw Error("cannot write '" + printable(path) + "': exposure must be a finite number of stops");
  const std::vector<std::uint8_t> pixels = displayRgb8(linearRgb.data(), linearRgb.size() / 3, exposure);
  const std::string shown = printable(path);
  // Encoded in memory and written here: stbi_write_png ignores the results of fwrite and fclose,
  // so on a full disk it reported success and a truncated PNG was renamed into place.
  int length = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> png(
      stbi_write_png_to_mem(pixels.data(), 3 * width, width, height, 3, &length), std::free);
  if (!png) throw Error("cannot write '" + shown + "': the PNG encoder failed (out of memory?)");
  writeOutput(path, png.get(), static_cast<std::size_t>(length));
}

}  // namespace brdfcl

namespace brdfcl::detail {

// Here because stb_image_write is compiled static in this file: a second implementation elsewhere
// would be a second copy of the encoder.
std::string encodePng(const std::uint8_t* pixels, int width, int height, int channels) {
  std::string png;
  const int ok = stbi_write_png_to_func(
      [](void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<const char*>(data), size); },
      &png, width, height, channels, pixels, width * channels);
  if (!ok) png.clear();
  return png;
}

}  // namespace brdfcl::detail
