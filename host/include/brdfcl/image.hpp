// Image files: OpenEXR RGB read/write (environments, linear renders), Radiance HDR environments,
// the checked low-level EXR channel reader shared with the G-buffer, and the PNG display
// pipeline (exposure -> Khronos PBR Neutral tone mapping -> sRGB OETF -> 8-bit PNG).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "brdfcl/material.hpp"

namespace brdfcl {

// One channel of an EXR file as the header describes it.
struct ExrChannelInfo {
  std::string name;
  bool isFloat = false;  // FLOAT (32 bit) rather than HALF or UINT; choosing a UINT channel is an error
};

// Reads the chosen channels of a single-part, flat (not deep) OpenEXR file as float planes,
// row-major from the top-left of the data window. `choose` sees every channel of the header and
// returns the names to read (it may throw brdfcl::Error, e.g. for a missing channel). Before
// any pixel is read the file is checked: EXR magic number, not multi-part, not deep, data window
// equal to the display window, each chosen channel HALF or FLOAT with x/y sampling 1, and the
// file complete. Every failure is a one-line brdfcl::Error that starts with the file name.
std::vector<std::vector<float>> readExrChannels(
    const std::string& path,
    const std::function<std::vector<std::string>(const std::vector<ExrChannelInfo>&)>& choose, int& width,
    int& height);

// Writes FLOAT channels R, G, B (ZIP compression) from interleaved rgb (3 floats per pixel,
// row-major from the top-left), atomically (see writeAtomically). rgb.size() != 3·w·h or
// w, h < 1 is a caller bug: std::invalid_argument.
void writeExrRgb(const std::string& path, int width, int height, const std::vector<float>& rgb);

// Reads R, G, B of a single-part EXR (checked as readExrChannels does) into interleaved rgb.
// A luminance-only file (channel Y, no R/G/B) is read as grey (r = g = b = Y).
std::vector<float> readExrRgb(const std::string& path, int& width, int& height);

// Reads an equirectangular Radiance RGBE file (FORMAT=32-bit_rle_rgbe, "-Y h +X w", flat or
// run-length encoded) into interleaved linear rgb, top row first, as stb_image decodes it
// (m * 2^(e - 136), no gamma). Limits as for EXR (65536 per side, 2^28 pixels). A missing,
// truncated or corrupt file, another format or orientation: one-line brdfcl::Error naming it.
std::vector<float> readRadianceHdr(const std::string& path, int& width, int& height);

// An environment image: Radiance HDR or OpenEXR, chosen by the file's first bytes (not its
// name), then read as readRadianceHdr or readExrRgb; a NaN or infinite texel is an error. The
// values are returned as stored (environmentPlanes clamps negatives to 0).
std::vector<float> readEnvironmentRgb(const std::string& path, int& width, int& height);

// Khronos PBR Neutral tone mapper (KhronosGroup/ToneMapping, "PBR Neutral"). Constants:
// startCompression = 0.8 - 0.04 (where highlight compression begins, after the 0.04 Fresnel
// offset), desaturation = 0.15 (how fast compressed highlights move towards white). It acts on
// RGB jointly: the offset uses min(r,g,b), the compression max(r,g,b). Output is in [0, 1]
// (below 1 for any input under ~1e6).
// Negative and NaN components are taken as 0 first (the reference is undefined there; negative
// f can occur, see docs/model.md), +inf as the largest float.
Rgb toneMapPbrNeutral(const Rgb& linear);
// Grey convenience: toneMapPbrNeutral({g, g, g})[0].
float toneMapPbrNeutral(float grey);
// In place on interleaved rgb (size a multiple of 3, else std::invalid_argument).
void toneMapPbrNeutral(std::vector<float>& rgb);

// sRGB OETF (IEC 61966-2-1): 12.92·v for v <= 0.0031308, else 1.055·v^(1/2.4) - 0.055, on v
// clamped to [0, 1] (NaN -> 0), then round-to-nearest to 0..255. So 0.0031308 -> 10
// (0.04045·255 = 10.31), 0.5 -> 188 (0.73536·255 = 187.52), 1 -> 255.
std::uint8_t encodeSrgb8(float linear);

// The display pipeline on `pixels` interleaved linear RGB pixels: each component times
// 2^exposure, PBR Neutral, sRGB-encoded to 8 bits (the bytes writePng encodes). exposure must
// be finite (the caller checks).
std::vector<std::uint8_t> displayRgb8(const float* linearRgb, std::size_t pixels, float exposure);

// The display pipeline: each component times 2^exposure, PBR Neutral, sRGB-encoded to 8 bits,
// written as an RGB PNG with stb_image_write through writeAtomically (no partial file on
// failure). Errors: brdfcl::Error (unwritable path, non-finite exposure, encoder failure);
// linearRgb.size() != 3·w·h or w, h < 1: std::invalid_argument.
void writePng(const std::string& path, int width, int height, const std::vector<float>& linearRgb,
              float exposure = 0.0f);

}  // namespace brdfcl
