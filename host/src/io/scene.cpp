// readScene/parseScene: the scene JSON of docs/gbuffer.md (camera, KHR_lights_punctual lights
// with brdfcl's position/direction keys, environment). Every rejection is one line naming the
// file and the JSON key path, in the style of the materials reader.
#include "io/confined_open.hpp"
#include "io/files.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"
#include "brdfcl/scene.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "brdfcl/error.hpp"
#include "io/option_style.hpp"
#include "io/vec3.hpp"

namespace brdfcl {
namespace {

using json = nlohmann::json;
using detail::printable;
using detail::formatNumber;
std::string describe(const json& v) { return detail::describeJson(v); }
std::string withoutTag(std::string what) { return detail::withoutJsonTag(std::move(what)); }

constexpr double kPi = 3.14159265358979323846;
// Users write pi/2 with a few digits (1.5708); a hair above pi/2 is taken as pi/2.
constexpr double kHalfPiTolerance = 1e-4;

class SceneReader {
 public:
  SceneReader(const std::string& source, const std::string& baseDir, bool allowOutside)
      : source_(printable(source, 300)), baseDir_(baseDir), allowOutside_(allowOutside) {}

  Scene read(const std::string& text) {
    json doc;
    try {
      doc = json::parse(text);
    } catch (const json::exception& e) {
      // Includes literals beyond double range (1e999), which nlohmann rejects as out_of_range.
      throw Error(source_ + ": invalid JSON: " + printable(withoutTag(e.what()), 300));
    }
    if (!doc.is_object()) throw Error(source_ + ": expected a JSON object at the top level, got " + describe(doc));
    onlyKeys(doc, "", {"camera", "lights", "environment"});
    Scene s;
    if (const auto it = doc.find("camera"); it != doc.end()) camera(*it, s);
    if (const auto it = doc.find("lights"); it != doc.end()) {
      if (!it->is_array()) fail("lights", "expected an array of light objects, got " + describe(*it));
      for (std::size_t i = 0; i < it->size(); ++i) s.lights.push_back(light((*it)[i], "lights[" + std::to_string(i) + "]"));
    }
    if (const auto it = doc.find("environment"); it != doc.end()) s.environment = environment(*it);
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw Error(source_ + ": " + path + ": " + message);
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  // Unknown keys are rejected so that a misspelt key ("postion") is not silently replaced by a
  // default; "name" and "extras" are free for the user, as in glTF.
  void onlyKeys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed) const {
    for (const auto& item : obj.items()) {
      const std::string& k = item.key();
      if (k == "name" || k == "extras") continue;
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return k == a; })) {
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(join(path, printable(k)), "unknown key; expected one of " + list);
      }
    }
  }

  void requireObject(const json& v, const std::string& path) const {
    if (!v.is_object()) fail(path, "expected an object, got " + describe(v));
  }

  // `ok` is the range check; `expected` says it in words for the message.
  template <class Ok>
  float number(const json& v, const std::string& path, const std::string& expected, Ok ok) const {
    if (!v.is_number()) fail(path, "expected " + expected + ", got " + describe(v));
    const double d = v.get<double>();
    if (!std::isfinite(d) || !ok(d)) fail(path, "expected " + expected + ", got " + formatNumber(d));
    if (std::fabs(d) > std::numeric_limits<float>::max())
      fail(path, "expected " + expected + ", got " + formatNumber(d) + " (too large for float)");
    return static_cast<float>(d);
  }

  float finite(const json& v, const std::string& path) const {
    return number(v, path, "a finite number", [](double) { return true; });
  }

  std::array<float, 3> vec3(const json& v, const std::string& path, bool nonNegative = false) const {
    const std::string expected =
        std::string("an array of 3 ") + (nonNegative ? "numbers >= 0" : "finite numbers");
    if (!v.is_array() || v.size() != 3) fail(path, "expected " + expected + ", got " + describe(v));
    std::array<float, 3> out{};
    for (std::size_t i = 0; i < 3; ++i)
      out[i] = number(v[i], path + "[" + std::to_string(i) + "]", nonNegative ? "a number >= 0" : "a finite number",
                      [&](double d) { return !nonNegative || d >= 0.0; });
    return out;
  }

  std::array<float, 3> unit(const json& v, const std::string& path) const {
    const Imath::V3d d(detail::toVec3(vec3(v, path)));
    const double len = detail::norm(d);
    if (!(len > 0.0) || !std::isfinite(len)) fail(path, "the direction has zero length; give a non-zero vector");
    return detail::toArray(Imath::V3f(d / len));
  }

  void camera(const json& v, Scene& s) const {
    requireObject(v, "camera");
    onlyKeys(v, "camera", {"position", "target", "fov"});
    const auto pos = v.find("position");
    if (pos == v.end()) fail("camera", "missing \"position\": [x, y, z]");
    s.hasCamera = true;
    s.cameraPosition = vec3(*pos, "camera.position");
    if (const auto it = v.find("target"); it != v.end()) s.cameraTarget = vec3(*it, "camera.target");
    if (s.cameraPosition == s.cameraTarget)
      fail(v.count("target") ? "camera.target" : "camera.position",
           "the camera position equals its target, so there is no view direction; move one of them");
    if (const auto it = v.find("fov"); it != v.end())
      s.fovDegrees = number(*it, "camera.fov", "a number of degrees in (0, 180)", [](double d) { return d > 0.0 && d < 180.0; });
  }

  Light light(const json& v, const std::string& path) const {
    requireObject(v, path);
    Light l;
    const auto type = v.find("type");
    if (type == v.end()) fail(path, "missing \"type\"; expected \"directional\", \"point\" or \"spot\"");
    const std::string t = type->is_string() ? type->get<std::string>() : std::string();
    if (t == "directional")
      l.type = Light::Type::Directional;
    else if (t == "point")
      l.type = Light::Type::Point;
    else if (t == "spot")
      l.type = Light::Type::Spot;
    else
      fail(path + ".type", "expected \"directional\", \"point\" or \"spot\", got " + describe(*type));

    switch (l.type) {
      case Light::Type::Directional:
        onlyKeys(v, path, {"type", "color", "intensity", "direction"});
        break;
      case Light::Type::Point:
        onlyKeys(v, path, {"type", "color", "intensity", "range", "position"});
        break;
      case Light::Type::Spot:
        onlyKeys(v, path, {"type", "color", "intensity", "range", "spot", "position", "direction"});
        break;
    }
    if (const auto it = v.find("color"); it != v.end()) l.color = vec3(*it, path + ".color", true);
    if (const auto it = v.find("intensity"); it != v.end())
      l.intensity = number(*it, path + ".intensity", "a number >= 0", [](double d) { return d >= 0.0; });
    if (const auto it = v.find("range"); it != v.end())
      l.range = number(*it, path + ".range", "a number > 0 (omit the key for infinite range)",
                       [](double d) { return d > 0.0; });
    // Placement has no default: a light silently at the origin or pointing down -Z is rarely
    // what was meant.
    if (l.type != Light::Type::Directional) {
      const auto it = v.find("position");
      if (it == v.end()) fail(path, "missing \"position\": [x, y, z] (required for " + t + " lights)");
      l.position = vec3(*it, path + ".position");
    }
    if (l.type != Light::Type::Point) {
      const auto it = v.find("direction");
      if (it == v.end())
        fail(path, "missing \"direction\": [x, y, z], the way the light travels (required for " + t + " lights)");
      l.direction = unit(*it, path + ".direction");
    }
    if (l.type == Light::Type::Spot) {
      if (const auto it = v.find("spot"); it != v.end()) {
        const std::string sp = path + ".spot";
        requireObject(*it, sp);
        onlyKeys(*it, sp, {"innerConeAngle", "outerConeAngle"});
        if (const auto o = it->find("outerConeAngle"); o != it->end()) {
          const double outer = number(*o, sp + ".outerConeAngle", "a number in (0, pi/2]",
                                      [](double d) { return d > 0.0 && d <= kPi / 2 + kHalfPiTolerance; });
          l.outerCone = static_cast<float>(std::min(outer, kPi / 2));
        }
        if (const auto i = it->find("innerConeAngle"); i != it->end()) {
          const float outer = l.outerCone;
          l.innerCone = number(*i, sp + ".innerConeAngle",
                               "a number in [0, outerConeAngle) = [0, " + formatNumber(outer) + ")",
                               [&](double d) { return d >= 0.0 && d < outer; });
        }
      }
    }
    return l;
  }

  Environment environment(const json& v) const {
    Environment e;
    if (v.is_string()) {
      if (v.get<std::string>() == "builtin") return e;
      fail("environment",
           "expected \"builtin\" or an object {\"path\": \"env.exr\"} or {\"builtin\": \"sky\"|\"studio\"}, got " +
               describe(v));
    }
    if (!v.is_object())
      fail("environment", "expected \"builtin\" or an object with \"path\" or \"builtin\", got " + describe(v));
    onlyKeys(v, "environment", {"path", "builtin", "intensity", "rotation"});
    const auto path = v.find("path");
    const auto builtin = v.find("builtin");
    if (path != v.end() && builtin != v.end())
      fail("environment", "has both \"path\" and \"builtin\"; keep one");
    if (path == v.end() && builtin == v.end())
      fail("environment", "needs \"path\": \"env.exr\" or \"builtin\": \"sky\"|\"studio\"|\"uniform\"");
    if (builtin != v.end()) {
      const std::string k = builtin->is_string() ? builtin->get<std::string>() : std::string();
      if (k != "sky" && k != "studio" && k != "uniform")
        fail("environment.builtin", "expected \"sky\", \"studio\" or \"uniform\", got " + describe(*builtin));
      e.builtinKind = k;
    } else {
      if (!path->is_string() || path->get_ref<const std::string&>().empty())
        fail("environment.path", "expected a non-empty file name string, got " + describe(*path));
      namespace fs = std::filesystem;
      const std::string name = path->get<std::string>();
      const fs::path p(name);
      e.builtin = false;
      e.path = (p.is_absolute() || baseDir_.empty()) ? p.string() : (fs::path(baseDir_) / p).string();
      // Checked here so the message can name the key; the pixels are read later. Confinement is
      // decided before anything outside the folder is looked at, so a refusal tells nothing of it.
      const std::string shown = source_ + ": environment.path '" + printable(name, 300) + "' ";
      detail::OpenRules rules;
      rules.allowOutside = allowOutside_;
      if (name.find('\0') != std::string::npos) throw Error(shown + "holds a NUL character; name a file");
      detail::Opened opened;
      if (const int fd = detail::openInside(baseDir_, name, rules, opened); fd >= 0) ::close(fd);
      using Outcome = detail::Opened::Outcome;
      if (opened.outcome == Outcome::Outside)
        throw Error(shown + "points outside the scene file's folder; move the file into the folder, or pass " +
                    flagName("--allow-outside-uris"));
      if (opened.outcome == Outcome::Link)
        throw Error(shown + "is or passes through a symbolic link, which brdfcl does not follow from a scene file's "
                            "folder; copy the file in, or pass " + flagName("--allow-outside-uris"));
      if (opened.outcome == Outcome::NotRegular)
        throw Error(shown + "is not a regular file (a directory, FIFO or device); name a file");
      if (opened.outcome != Outcome::Ok)
        fail("environment.path", "cannot read '" + printable(e.path, 300) + "': " + std::strerror(opened.error));
    }
    if (const auto it = v.find("intensity"); it != v.end())
      e.intensity = number(*it, "environment.intensity", "a number >= 0", [](double d) { return d >= 0.0; });
    if (const auto it = v.find("rotation"); it != v.end()) e.rotation = finite(*it, "environment.rotation");
    return e;
  }

  std::string source_;
  std::string baseDir_;
  bool allowOutside_ = false;
};

}  // namespace

Scene parseScene(const std::string& jsonText, const std::string& sourceName, const std::string& baseDir,
                 bool allowOutside) {
  return SceneReader(sourceName, baseDir, allowOutside).read(jsonText);
}

Scene readScene(const std::string& path, bool allowOutside) {
  const std::string shown = printable(path, 300);
  const detail::ReadingInput reading(shown);
  std::string text;
  detail::readInputFile(path, shown, "", text);
  return parseScene(text, path, std::filesystem::path(path).parent_path().string(), allowOutside);
}

}  // namespace brdfcl
