// The scene file that goes with a G-buffer: camera, KHR_lights_punctual-style lights and the
// environment. The JSON format is specified in docs/gbuffer.md ("Scene JSON").
#pragma once
#include <array>
#include <string>
#include <vector>

namespace brdfcl {

struct Light {
  enum class Type { Directional, Point, Spot } type = Type::Point;
  std::array<float, 3> color{1.0f, 1.0f, 1.0f};  // linear RGB
  float intensity = 1.0f;  // lux (directional) or candela (point, spot)
  float range = 0.0f;      // 0 = infinite
  float innerCone = 0.0f, outerCone = 0.78539816f;  // radians (default pi/4), 0 <= inner < outer <= pi/2 (spot)
  std::array<float, 3> position{};                    // world; point and spot
  std::array<float, 3> direction{0.0f, 0.0f, -1.0f};  // unit; the way the light travels
};

struct Environment {
  bool builtin = true;
  std::string builtinKind = "sky";  // "sky", "studio" or "uniform"
  std::string path;                 // when !builtin: equirectangular EXR or Radiance HDR, resolved against the scene's directory
  float intensity = 1.0f;
  float rotation = 0.0f;  // radians about +Y
};

struct Scene {
  // The camera is given (a scene file with "camera", spheresScene()) or stands in with the
  // defaults below; Shader::shade takes a G-buffer's own camera over a stand-in.
  bool hasCamera = false;
  std::array<float, 3> cameraPosition{0.0f, 0.0f, 5.0f}, cameraTarget{0.0f, 0.0f, 0.0f};
  float fovDegrees = 40.0f;  // vertical field of view
  std::vector<Light> lights;
  Environment environment;
};

// Reads a scene JSON file; a relative environment path is resolved against the file's directory.
// Every rejection is a one-line brdfcl::Error "<file>: <key path>: <what is wrong>", e.g.
// "scene.json: lights[1].spot.outerConeAngle: expected a number in (innerConeAngle, pi/2], got 2".
// The environment path must name a regular file inside the scene file's folder, reached without
// links (docs/gltf.md, "Files an asset names"); allowOutside also lets it be absolute, climb out
// with ".." or pass links, as --allow-outside-uris asks.
Scene readScene(const std::string& path, bool allowOutside = false);
// The same from text; sourceName prefixes messages, baseDir resolves a relative environment path
// ("" = the current directory). The environment file must exist and be readable; its contents
// are read later (readEnvironmentRgb: OpenEXR or Radiance HDR, whatever the file's name).
Scene parseScene(const std::string& json, const std::string& sourceName, const std::string& baseDir,
                 bool allowOutside = false);

// The command line's environment: spec "builtin" (= "sky"), "sky", "studio", "uniform", or a
// file ending in .hdr or .exr (any case; a relative path is taken from the current directory)
// that exists and is readable. Its pixels are read later, as for the scene's. An unknown spec,
// an unreadable file, a negative or non-finite intensity or a non-finite rotation (radians about
// +Y) is a one-line brdfcl::Error naming --environment.
Environment parseEnvironmentSpec(const std::string& spec, float intensity, float rotation);

}  // namespace brdfcl
