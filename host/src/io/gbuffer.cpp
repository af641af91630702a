// readGBuffer/writeGBuffer: the G-buffer EXR of docs/gbuffer.md. Channel naming (canonical and
// Blender's multilayer pass names), the value range checks and the camera header attributes live
// here; the file-level checks (magic, single part, data window, sampling, truncation) are
// readExrChannels' in image.cpp.
#include "io/exr_header.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"
#include "brdfcl/gbuffer.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfVecAttribute.h>
#include <half.h>
#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"
#include "io/option_style.hpp"
#include "io/rows.hpp"

namespace brdfcl {
namespace {

// File names and OpenEXR's messages: longer, with blanks for control characters.
std::string printable(const std::string& s, std::size_t maxLength = 300) { return detail::printable(s, maxLength, ' '); }

// What readGBuffer's value check asks of a channel on covered pixels (docs/gbuffer.md).
enum class Range { Any, Factor, NonNegative, UnitVector };

struct Field {
  const char* name;       // canonical prefix ("P") or whole name ("metallic")
  const char* suffixes;   // "XYZ", "RGB" or "" for a scalar
  const char* blender;    // Blender pass name ("Normal") or nullptr
  bool required;
  std::vector<float> GBuffer::*member;
  Range range;
};

// V is only refused when zero (readGBuffer): it is a direction, used normalized, whereas a normal
// whose length is off 1 betrays a decoding mistake (a normal map left in [0, 1], say).
const Field kFields[] = {
    {"P", "XYZ", "Position", true, &GBuffer::P, Range::Any},
    {"N", "XYZ", "Normal", true, &GBuffer::N, Range::UnitVector},
    {"baseColor", "RGB", nullptr, true, &GBuffer::baseColor, Range::Factor},
    {"metallic", "", nullptr, true, &GBuffer::metallic, Range::Factor},
    {"roughness", "", nullptr, true, &GBuffer::roughness, Range::Factor},
    {"mask", "", nullptr, true, &GBuffer::mask, Range::Any},
    {"T", "XYZ", nullptr, false, &GBuffer::T, Range::UnitVector},
    {"emissive", "RGB", nullptr, false, &GBuffer::emissive, Range::NonNegative},
    {"sheenColor", "RGB", nullptr, false, &GBuffer::sheenColor, Range::Factor},
    {"sheenRoughness", "", nullptr, false, &GBuffer::sheenRoughness, Range::Factor},
    {"clearcoat", "", nullptr, false, &GBuffer::clearcoat, Range::Factor},
    {"clearcoatRoughness", "", nullptr, false, &GBuffer::clearcoatRoughness, Range::Factor},
    {"clearcoatN", "XYZ", nullptr, false, &GBuffer::clearcoatN, Range::UnitVector},
    {"anisotropyStrength", "", nullptr, false, &GBuffer::anisotropyStrength, Range::Factor},
    {"anisotropyRotation", "", nullptr, false, &GBuffer::anisotropyRotation, Range::Any},
    {"occlusion", "", nullptr, false, &GBuffer::occlusion, Range::Factor},
    {"V", "XYZ", nullptr, false, &GBuffer::V, Range::Any},
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

// A float as short as reads back the same (1.3, not 1.2999999523162842).
std::string shortFloat(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string pixelName(std::size_t i, int width) {
  return "pixel (" + std::to_string(i % std::size_t(width)) + ", " + std::to_string(i / std::size_t(width)) + ")";
}

// ---- Camera header attributes (docs/gbuffer.md, "Camera attributes") ----

constexpr const char* kProjection = "brdfcl:cameraProjection";
constexpr const char* kPosition = "brdfcl:cameraPosition";
constexpr const char* kOrientation = "brdfcl:cameraOrientation";
constexpr const char* kFov = "brdfcl:cameraFov";
constexpr const char* kXMag = "brdfcl:cameraXMag";
constexpr const char* kYMag = "brdfcl:cameraYMag";
constexpr const char* kNear = "brdfcl:cameraNear";
constexpr const char* kFar = "brdfcl:cameraFar";

void putCamera(Imf::Header& header, const GBufferCamera& c) {
  const Imath::V3f right(c.right[0], c.right[1], c.right[2]), up(c.up[0], c.up[1], c.up[2]);
  const Imath::V3f back(-c.forward[0], -c.forward[1], -c.forward[2]), pos(c.position[0], c.position[1], c.position[2]);
  // Rows right, up, back: the rotation of camera-to-world in OpenEXR's row-vector convention
  // (p_world = p_camera * M + position), so that worldToCamera below is its rigid inverse.
  const Imath::M33f orientation(right.x, right.y, right.z, up.x, up.y, up.z, back.x, back.y, back.z);
  header.insert(kProjection, Imf::StringAttribute(c.orthographic ? "orthographic" : "perspective"));
  header.insert(kPosition, Imf::V3fAttribute(pos));
  header.insert(kOrientation, Imf::M33fAttribute(orientation));
  if (c.orthographic) {
    header.insert(kXMag, Imf::FloatAttribute(c.xmag));
    header.insert(kYMag, Imf::FloatAttribute(c.ymag));
  } else {
    header.insert(kFov, Imf::FloatAttribute(c.fovDegrees));
  }
  header.insert(kNear, Imf::FloatAttribute(c.znear));
  header.insert(kFar, Imf::FloatAttribute(c.zfar));
  // OpenEXR's standard attribute, for tools that know no brdfcl names: world to camera space
  // (+X right, +Y up, looking down -Z), p_camera = p_world * M.
  Imath::M44f w2c(right.x, up.x, back.x, 0.0f, right.y, up.y, back.y, 0.0f, right.z, up.z, back.z, 0.0f,  //
                  -pos.dot(right), -pos.dot(up), -pos.dot(back), 1.0f);
  Imf::addWorldToCamera(header, w2c);
}

class CameraReader {
 public:
  CameraReader(const Imf::Header& header, const std::string& shown) : header_(header), shown_(shown) {}

  std::optional<GBufferCamera> read() const {
    bool any = false;
    for (auto it = header_.begin(); it != header_.end(); ++it)
      if (std::string(it.name()).rfind("brdfcl:camera", 0) == 0) any = true;
    if (!any) return std::nullopt;
    GBufferCamera c;
    const std::string projection = get<Imf::StringAttribute>(kProjection, "string", "")->value();
    if (projection != "perspective" && projection != "orthographic")
      fail(std::string("header attribute ") + kProjection + " is '" + printable(projection, 40) +
           "'; expected perspective or orthographic");
    c.orthographic = projection == "orthographic";
    const Imath::V3f pos = get<Imf::V3fAttribute>(kPosition, "v3f", projection)->value();
    const Imath::M33f m = get<Imf::M33fAttribute>(kOrientation, "m33f", projection)->value();
    finite(kPosition, &pos.x, 3);
    finite(kOrientation, &m[0][0], 9);
    const Imath::V3f right(m[0][0], m[0][1], m[0][2]), up(m[1][0], m[1][1], m[1][2]), back(m[2][0], m[2][1], m[2][2]);
    // The rows must be a right-handed orthonormal frame: anything else has no single camera.
    const double tol = kGBufferUnitTolerance;
    const bool unit = std::fabs(right.length() - 1.0) <= tol && std::fabs(up.length() - 1.0) <= tol &&
                      std::fabs(back.length() - 1.0) <= tol;
    const bool orthogonal = std::fabs(right.dot(up)) <= tol && std::fabs(right.dot(back)) <= tol &&
                            std::fabs(up.dot(back)) <= tol && (right.cross(up)).dot(back) > 0.0f;
    if (!unit || !orthogonal)
      fail(std::string("header attribute ") + kOrientation +
           " is not a rotation; its rows must be the camera's unit right, up and back (-forward) axes, "
           "orthogonal and right-handed");
    for (int k = 0; k < 3; ++k) {
      c.position[k] = pos[k];
      c.right[k] = right[k];
      c.up[k] = up[k];
      c.forward[k] = -back[k];
    }
    if (c.orthographic) {
      c.xmag = positive(kXMag, projection);
      c.ymag = positive(kYMag, projection);
    } else {
      c.fovDegrees = get<Imf::FloatAttribute>(kFov, "float", projection)->value();
      if (!(c.fovDegrees > 0.0f && c.fovDegrees < 180.0f))
        fail(std::string("header attribute ") + kFov + " = " + shortFloat(c.fovDegrees) +
             " is outside (0, 180) degrees");
    }
    c.znear = get<Imf::FloatAttribute>(kNear, "float", projection)->value();
    c.zfar = get<Imf::FloatAttribute>(kFar, "float", projection)->value();
    if (!(c.znear >= 0.0f) || !std::isfinite(c.znear))
      fail(std::string("header attribute ") + kNear + " = " + shortFloat(c.znear) + " must be a finite number >= 0");
    if (!(c.zfar >= 0.0f) || !std::isfinite(c.zfar))
      fail(std::string("header attribute ") + kFar + " = " + shortFloat(c.zfar) +
           " must be a finite number >= 0 (0: infinite)");
    return c;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(shown_ + ": " + what + "; fix the camera attributes (docs/gbuffer.md) or remove every brdfcl:camera attribute");
  }

  template <class A>
  const A* get(const char* name, const char* type, const std::string& projection) const {
    const auto it = header_.find(name);
    const Imf::Attribute* a = it == header_.end() ? nullptr : &it.attribute();
    if (!a)
      fail(std::string("missing header attribute ") + name +
           (projection.empty() ? std::string() : " (required for a " + projection + " camera)"));
    const A* typed = dynamic_cast<const A*>(a);
    if (!typed)
      fail(std::string("header attribute ") + name + " has type " + printable(a->typeName(), 40) + "; expected " + type);
    return typed;
  }

  void finite(const char* name, const float* v, int n) const {
    for (int k = 0; k < n; ++k)
      if (!std::isfinite(v[k])) fail(std::string("header attribute ") + name + " has a non-finite value (" + shortFloat(v[k]) + ")");
  }

  float positive(const char* name, const std::string& projection) const {
    const float v = get<Imf::FloatAttribute>(name, "float", projection)->value();
    if (!(v > 0.0f) || !std::isfinite(v))
      fail(std::string("header attribute ") + name + " = " + shortFloat(v) + " must be a finite number > 0");
    return v;
  }

  const Imf::Header& header_;
  const std::string& shown_;
};

// ---- The value check (GBufferReadOptions::check) ----

struct Source {
  const Field* field;
  std::size_t firstPlane;
};

// A pixel whose value breaks its channel's range, and what to say about it; a pixel index of
// SIZE_MAX = none found.
struct Failure {
  std::size_t pixel = SIZE_MAX;
  std::string message;
};

// The checks of checkValues over one G-buffer's planes.
struct ValueCheck {
  const std::vector<std::vector<float>>& planes;
  const std::vector<Source>& sources;
  const std::vector<std::string>& names;
  int width;
  const std::string& shown;
  const std::string& skip;
  const std::vector<float>& mask;

  // Whether pixel i breaks a range; if so, `f` says how.
  bool pixelFails(std::size_t i, Failure& f) const {
    if (!(mask[i] >= 0.5f)) return false;  // the environment shows: nothing here is shaded
    for (const Source& s : sources) {
      const Field& fd = *s.field;
      if (fd.range == Range::Any) continue;
      if (fd.range == Range::UnitVector) {
        const double x = planes[s.firstPlane][i], y = planes[s.firstPlane + 1][i], z = planes[s.firstPlane + 2][i];
        const double len = std::sqrt(x * x + y * y + z * z);
        if (std::fabs(len - 1.0) > kGBufferUnitTolerance) {
          const std::string& first = names[s.firstPlane];
          char length[32];
          std::snprintf(length, sizeof length, "%.6g", len);
          f = {i, shown + ": " + pixelName(i, width) + ": vector " + printable(first.substr(0, first.size() - 2)) +
                      " = (" + shortFloat(float(x)) + ", " + shortFloat(float(y)) + ", " + shortFloat(float(z)) +
                      ") has length " + length + ", not 1 within " + shortFloat(float(kGBufferUnitTolerance)) +
                      "; fix the G-buffer or pass " + skip};
          return true;
        }
        continue;
      }
      const std::size_t k = std::max<std::size_t>(1, std::char_traits<char>::length(fd.suffixes));
      for (std::size_t c = 0; c < k; ++c) {
        const float v = planes[s.firstPlane + c][i];
        const bool ok = fd.range == Range::Factor ? (v >= 0.0f && v <= 1.0f) : v >= 0.0f;
        if (!ok) {
          f = {i, shown + ": " + pixelName(i, width) + ": channel " + printable(names[s.firstPlane + c]) + " = " +
                      shortFloat(v) + " is outside " + (fd.range == Range::Factor ? "[0, 1]" : "[0, inf)") +
                      "; fix the G-buffer or pass " + skip};
          return true;
        }
      }
    }
    return false;
  }

  // Whether a block of pixels may hold a failure: branch-free loops over one plane at a time,
  // which the compiler vectorizes; only a flagged block is searched pixel by pixel. The unit
  // test on the squared length is a little stricter than pixelFails', which has the last word.
  bool blockMayFail(std::size_t b0, std::size_t b1) const {
    const float lo = float((1.0 - kGBufferUnitTolerance) * (1.0 - kGBufferUnitTolerance)) + 1e-6f;
    const float hi = float((1.0 + kGBufferUnitTolerance) * (1.0 + kGBufferUnitTolerance)) - 1e-6f;
    const float* m = mask.data();
    for (const Source& s : sources) {
      const Field& fd = *s.field;
      if (fd.range == Range::Any) continue;
      int bad = 0;
      if (fd.range == Range::UnitVector) {
        const float *x = planes[s.firstPlane].data(), *y = planes[s.firstPlane + 1].data(),
                    *z = planes[s.firstPlane + 2].data();
        for (std::size_t i = b0; i < b1; ++i) {
          const float l2 = x[i] * x[i] + y[i] * y[i] + z[i] * z[i];
          bad |= (m[i] >= 0.5f) & ((l2 < lo) | (l2 > hi));
        }
      } else {
        const std::size_t k = std::max<std::size_t>(1, std::char_traits<char>::length(fd.suffixes));
        const float top = fd.range == Range::Factor ? 1.0f : std::numeric_limits<float>::max();
        for (std::size_t c = 0; c < k; ++c) {
          const float* v = planes[s.firstPlane + c].data();
          for (std::size_t i = b0; i < b1; ++i) bad |= (m[i] >= 0.5f) & ((v[i] < 0.0f) | (v[i] > top));
        }
      }
      if (bad) return true;
    }
    return false;
  }
};

// The first offending value in raster order (then in kFields order within the pixel), found by
// all cores over bands of rows: a 4K G-buffer has 8 million pixels of up to 24 planes.
void checkValues(const std::vector<std::vector<float>>& planes, const std::vector<Source>& sources,
                 const std::vector<std::string>& names, int width, const std::string& shown, const std::string& skip) {
  const std::vector<float>* mask = nullptr;
  for (const Source& s : sources)
    if (s.field->member == &GBuffer::mask) mask = &planes[s.firstPlane];
  if (!mask) return;
  const std::size_t n = mask->size();
  const ValueCheck check{planes, sources, names, width, shown, skip, *mask};
  const unsigned threads = n < (1u << 16) ? 1u : unsigned(std::min<std::size_t>(16, detail::parallelThreads()));
  const std::size_t band = (n + threads - 1) / threads;
  constexpr std::size_t kBlock = 2048;
  std::vector<Failure> found(threads);
  std::atomic<std::size_t> earliest{SIZE_MAX};  // lets bands after a known failure stop early
  auto work = [&](unsigned t) {
    const std::size_t end = std::min(n, (t + 1) * band);
    for (std::size_t b0 = t * band; b0 < end && b0 < earliest.load(std::memory_order_relaxed); b0 += kBlock) {
      const std::size_t b1 = std::min(end, b0 + kBlock);
      if (!check.blockMayFail(b0, b1)) continue;
      for (std::size_t i = b0; i < b1; ++i)
        if (check.pixelFails(i, found[t])) {
          std::size_t e = earliest.load();
          while (i < e && !earliest.compare_exchange_weak(e, i)) {
          }
          return;
        }
    }
  };
  // One band a thread; an exception (out of memory) must not leave the OpenMP region.
  std::vector<std::exception_ptr> errors(threads);
#pragma omp parallel for num_threads(int(threads)) schedule(static, 1) if (threads > 1)
  for (int t = 0; t < int(threads); ++t) {
    try {
      work(unsigned(t));
    } catch (...) {
      errors[std::size_t(t)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  for (const Failure& f : found)
    if (f.pixel != SIZE_MAX) throw Error(f.message);
}

}  // namespace

void checkGBufferValues(const GBuffer& g, const std::string& shown, const std::string& skip) {
  // The planes, sources and canonical channel names readGBuffer would have had from a file.
  const std::size_t n = g.pixelCount();
  std::vector<std::vector<float>> planes;
  std::vector<Source> sources;
  std::vector<std::string> names;
  for (const Field& f : kFields) {
    const std::vector<float>& v = g.*(f.member);
    if (v.empty()) continue;
    const std::size_t k = std::max<std::size_t>(1, std::char_traits<char>::length(f.suffixes));
    if (v.size() != k * n) throw std::invalid_argument(std::string("checkGBufferValues: ") + f.name + " has the wrong size");
    sources.push_back({&f, planes.size()});
    for (const std::string& name : channelNames(f.name, f.suffixes)) names.push_back(name);
    for (std::size_t c = 0; c < k; ++c) {
      std::vector<float> plane(n);
      for (std::size_t i = 0; i < n; ++i) plane[i] = v[k * i + c];
      planes.push_back(std::move(plane));
    }
  }
  checkValues(planes, sources, names, g.width, shown, skip);
}

GBuffer readGBuffer(const std::string& path) { return readGBuffer(path, GBufferReadOptions{}); }

namespace {
// The file channels that feed each field of kFields (appended to `sources`) and their names in
// plane order, from the file's header: canonical names, else one Blender layer's passes.
std::vector<std::string> chooseChannels(const std::vector<ExrChannelInfo>& channels, const std::string& shown,
                                        std::vector<Source>& sources) {
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
  return chosen;

}

// Checked where the file can be named, rather than only when shading starts (after the
// environment is prepared, which takes seconds).
void checkFinite(const std::vector<std::vector<float>>& planes, const std::vector<std::string>& names, int width,
                 const std::string& shown) {
  for (std::size_t p = 0; p < planes.size(); ++p)
    for (std::size_t i = 0; i < planes[p].size(); ++i)
      if (!std::isfinite(planes[p][i])) {
        const float v = planes[p][i];
        throw Error(shown + ": pixel (" + std::to_string(i % std::size_t(width)) + ", " +
                    std::to_string(i / std::size_t(width)) + ") has a non-finite value (" +
                    (std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf") + ") in channel '" + printable(names[p]) +
                    "'; fix the renderer's output");
      }
}

// The planes moved into the fields of `g`, vectors interleaved (x y z a pixel).
void storePlanes(GBuffer& g, std::vector<std::vector<float>>& planes, const std::vector<Source>& sources) {
  const std::size_t n = g.pixelCount();
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
}

// V is not renormalized (as N and T are not), but it has to have a direction: a zero vector
// would silently fall back to no view at all.
void checkViewDirections(const GBuffer& g, const std::string& shown) {
  for (std::size_t i = 0; i < g.V.size() / 3; ++i) {
    const double x = g.V[3 * i], y = g.V[3 * i + 1], z = g.V[3 * i + 2];
    if (x * x + y * y + z * z < 1e-12)
      throw Error(shown + ": pixel (" + std::to_string(i % std::size_t(g.width)) + ", " +
                  std::to_string(i / std::size_t(g.width)) +
                  ") has a zero-length view direction V; write the unit direction towards the viewer, or leave "
                  "V.X V.Y V.Z out to use the scene camera");
  }
}
}  // namespace

GBuffer readGBuffer(const std::string& path, const GBufferReadOptions& options) {
  const std::string shown = printable(path);
  // Which file channels feed which field, decided once the header is known.
  std::vector<Source> sources;
  std::vector<std::string> chosenNames;  // as the file spells them, one per plane read

  auto choose = [&](const std::vector<ExrChannelInfo>& channels) {
    chosenNames = chooseChannels(channels, shown, sources);
    return chosenNames;
  };

  GBuffer g;
  // The frame budget of shade (or BRDFCL_MAX_IMAGE_PIXELS), from the header before decoding.
  std::vector<std::vector<float>> planes =
      detail::readExrChannels(path, choose, g.width, g.height, [&](long long w, long long h) {
        detail::checkImagePixels(detail::ImageKind::GBuffer, shown, w, h);
      });
  checkFinite(planes, chosenNames, g.width, shown);
  if (options.check)
    checkValues(planes, sources, chosenNames, g.width, shown,
                optionStyle() == OptionStyle::Python ? "check=False" : "--no-check");
  storePlanes(g, planes, sources);
  checkViewDirections(g, shown);
  // The header once more, now that readExrChannels has checked the file: its attributes are
  // small and the reader keeps no header of its own.
  try {
    Imf::InputFile in(path.c_str());
    g.camera = CameraReader(in.header(), shown).read();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(shown + ": cannot read OpenEXR data (" + printable(e.what(), 200) +
                "); the file is truncated or corrupt: write it again");
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
      if (g.camera) putCamera(header, *g.camera);
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
