// readGBuffer/writeGBuffer: the G-buffer EXR of docs/gbuffer.md. Channel naming (canonical and
// Blender's multilayer pass names) lives here; the file-level checks (magic, single part, data
// window, sampling, truncation) are readExrChannels' in image.cpp.
#include "io/messages.hpp"
#include "brdfcl/gbuffer.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <half.h>
#include <algorithm>
#include <cmath>
#include <exception>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"

namespace brdfcl {
namespace {

// File names and OpenEXR's messages: longer, with blanks for control characters.
std::string printable(const std::string& s, std::size_t maxLength = 300) { return detail::printable(s, maxLength, ' '); }

struct Field {
  const char* name;       // canonical prefix ("P") or whole name ("metallic")
  const char* suffixes;   // "XYZ", "RGB" or "" for a scalar
  const char* blender;    // Blender pass name ("Normal") or nullptr
  bool required;
  std::vector<float> GBuffer::*member;
};

const Field kFields[] = {
    {"P", "XYZ", "Position", true, &GBuffer::P},
    {"N", "XYZ", "Normal", true, &GBuffer::N},
    {"baseColor", "RGB", nullptr, true, &GBuffer::baseColor},
    {"metallic", "", nullptr, true, &GBuffer::metallic},
    {"roughness", "", nullptr, true, &GBuffer::roughness},
    {"mask", "", nullptr, true, &GBuffer::mask},
    {"T", "XYZ", nullptr, false, &GBuffer::T},
    {"emissive", "RGB", nullptr, false, &GBuffer::emissive},
    {"sheenColor", "RGB", nullptr, false, &GBuffer::sheenColor},
    {"sheenRoughness", "", nullptr, false, &GBuffer::sheenRoughness},
    {"clearcoat", "", nullptr, false, &GBuffer::clearcoat},
    {"clearcoatRoughness", "", nullptr, false, &GBuffer::clearcoatRoughness},
    {"clearcoatN", "XYZ", nullptr, false, &GBuffer::clearcoatN},
    {"anisotropyStrength", "", nullptr, false, &GBuffer::anisotropyStrength},
    {"anisotropyRotation", "", nullptr, false, &GBuffer::anisotropyRotation},
    {"occlusion", "", nullptr, false, &GBuffer::occlusion},
    {"V", "XYZ", nullptr, false, &GBuffer::V},
};

std::vector<std::string> channelNames(const std::string& prefix, const char* suffixes) {
  if (!*suffixes) return {prefix};
  std::vector<std::string> out;
  for (const char* s = suffixes; *s; ++s) out.push_back(prefix + "." + *s);
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : " ") + n;
  return out;
}

}  // namespace

GBuffer readGBuffer(const std::string& path) {
  const std::string shown = printable(path);
  // Which file channels feed which field, decided once the header is known.
  struct Source {
    const Field* field;
    std::size_t firstPlane;
  };
  std::vector<Source> sources;
  std::vector<std::string> chosenNames;  // as the file spells them, one per plane read

  auto choose = [&](const std::vector<ExrChannelInfo>& channels) {
    std::set<std::string> have;
    for (const auto& c : channels) have.insert(c.name);
    std::vector<std::string> chosen;
    for (const Field& f : kFields) {
      std::vector<std::string> names = channelNames(f.name, f.suffixes);
      std::size_t present = std::count_if(names.begin(), names.end(), [&](const auto& n) { return have.count(n) > 0; });
      if (present == 0 && f.blender) {
        // Blender multilayer: "<layer>.<Pass>.X". Any one layer name is accepted; several would
        // leave it ambiguous which render layer is meant.
        const std::string pass = std::string(".") + f.blender + ".";
        std::set<std::string> layers;
        for (const auto& c : have) {
          const auto at = c.rfind(pass);
          if (at != std::string::npos && at > 0 && at + pass.size() + 1 == c.size()) layers.insert(c.substr(0, at));
        }
        if (layers.size() > 1) {
          std::vector<std::string> list(layers.begin(), layers.end());
          throw Error(shown + ": several layers have a " + f.blender + " pass (" + printable(joined(list), 200) +
                      "); keep one layer, or add canonical channels " + joined(names));
        }
        if (layers.size() == 1) {
          names = channelNames(*layers.begin() + "." + f.blender, f.suffixes);
          present = std::count_if(names.begin(), names.end(), [&](const auto& n) { return have.count(n) > 0; });
        }
      }
      if (present == 0) {
        if (f.required)
          throw Error(shown + ": missing required channel" + (names.size() > 1 ? "s " : " ") + joined(names) +
                      (f.blender ? std::string(" (or Blender's <layer>.") + f.blender + ".X/Y/Z)" : "") +
                      "; see docs/gbuffer.md for the channel names");
        continue;
      }
      if (present != names.size()) {
        std::string missing;
        for (const auto& n : names)
          if (!have.count(n)) missing += (missing.empty() ? "" : " ") + n;
        throw Error(shown + ": incomplete " + printable(names[0].substr(0, names[0].size() - 2)) + " vector: missing " +
                    printable(missing) + "; write all of " + printable(joined(names)));
      }
      sources.push_back({&f, chosen.size()});
      chosen.insert(chosen.end(), names.begin(), names.end());
    }
    chosenNames = chosen;
    return chosen;
  };

  GBuffer g;
  std::vector<std::vector<float>> planes = readExrChannels(path, choose, g.width, g.height);
  const std::size_t n = g.pixelCount();
  // Checked here, where the file can be named, rather than only when shading starts (after the
  // environment is prepared, which takes seconds).
  for (std::size_t p = 0; p < planes.size(); ++p)
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(planes[p][i])) {
        const float v = planes[p][i];
        throw Error(shown + ": pixel (" + std::to_string(i % std::size_t(g.width)) + ", " +
                    std::to_string(i / std::size_t(g.width)) + ") has a non-finite value (" +
                    (std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf") + ") in channel '" + printable(chosenNames[p]) +
                    "'; fix the renderer's output");
      }
  for (const Source& s : sources) {
    const std::size_t k = std::max<std::size_t>(1, std::char_traits<char>::length(s.field->suffixes));
    std::vector<float>& out = g.*(s.field->member);
    if (k == 1) {
      out = std::move(planes[s.firstPlane]);
      continue;
    }
    out.resize(k * n);
    for (std::size_t c = 0; c < k; ++c) {
      const std::vector<float>& plane = planes[s.firstPlane + c];
      for (std::size_t i = 0; i < n; ++i) out[k * i + c] = plane[i];
    }
  }
  // V is not renormalized (as N and T are not), but it has to have a direction: a zero vector
  // would silently fall back to no view at all.
  for (std::size_t i = 0; i < g.V.size() / 3; ++i) {
    const double x = g.V[3 * i], y = g.V[3 * i + 1], z = g.V[3 * i + 2];
    if (x * x + y * y + z * z < 1e-12)
      throw Error(shown + ": pixel (" + std::to_string(i % std::size_t(g.width)) + ", " +
                  std::to_string(i / std::size_t(g.width)) +
                  ") has a zero-length view direction V; write the unit direction towards the viewer, or leave "
                  "V.X V.Y V.Z out to use the scene camera");
  }
  return g;
}

void writeGBuffer(const std::string& path, const GBuffer& g, bool half) {
  if (g.width < 1 || g.height < 1) throw std::invalid_argument("writeGBuffer: width and height must be >= 1");
  const std::size_t n = g.pixelCount();
  for (const Field& f : kFields) {
    const std::vector<float>& v = g.*(f.member);
    const std::size_t k = std::max<std::size_t>(1, std::char_traits<char>::length(f.suffixes));
    if (v.empty() && f.required)
      throw std::invalid_argument(std::string("writeGBuffer: required channel ") + f.name + " is empty");
    if (!v.empty() && v.size() != k * n)
      throw std::invalid_argument(std::string("writeGBuffer: ") + f.name + " must hold " + std::to_string(k) +
                                  " * width * height floats");
  }
  const std::string shown = printable(path);
  writeAtomically(path, [&](const std::string& tmp) {
    try {
      Imf::Header header(g.width, g.height);
      header.compression() = Imf::ZIP_COMPRESSION;
      Imf::FrameBuffer fb;
      // OpenEXR does not convert FLOAT frame buffers to HALF file channels, so half output
      // goes through converted copies that must live until writePixels.
      std::vector<std::vector<::half>> halves;
      halves.reserve(std::size(kFields));
      for (const Field& f : kFields) {
        const std::vector<float>& v = g.*(f.member);
        if (v.empty()) continue;
        const std::vector<std::string> names = channelNames(f.name, f.suffixes);
        const std::size_t k = names.size();
        const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
        std::size_t elem = sizeof(float);
        // Slice wants a mutable pointer even for writing; the data is only read.
        char* base = const_cast<char*>(reinterpret_cast<const char*>(v.data()));
        if (half) {
          halves.emplace_back(v.begin(), v.end());
          base = reinterpret_cast<char*>(halves.back().data());
          elem = sizeof(::half);
        }
        for (std::size_t c = 0; c < k; ++c) {
          header.channels().insert(names[c], Imf::Channel(type));
          fb.insert(names[c], Imf::Slice(type, base + c * elem, k * elem, k * elem * static_cast<std::size_t>(g.width)));
        }
      }
      Imf::OutputFile out(tmp.c_str(), header);
      out.setFrameBuffer(fb);
      out.writePixels(g.height);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error("cannot write '" + shown + "': " + printable(detail::withUserPath(e.what(), tmp, path), 200));
    }
  });
}

}  // namespace brdfcl
