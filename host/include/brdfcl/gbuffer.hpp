// The G-buffer: per-pixel world-space geometry and glTF material parameters read from (and
// written to) a single-part OpenEXR file. The format is specified in docs/gbuffer.md.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace brdfcl {

// The camera that made a G-buffer, as brdfcl writes it into the EXR header (docs/gbuffer.md,
// "Camera attributes"). Pixel (x, y) maps to s = 2 (x + 0.5) / width - 1, t = 1 - 2 (y + 0.5) /
// height; a perspective ray leaves `position` along forward + s tan(fov/2) aspect right +
// t tan(fov/2) up (aspect = width / height); an orthographic ray leaves position + s xmag right +
// t ymag up along forward.
struct GBufferCamera {
  bool orthographic = false;
  std::array<float, 3> position{0.0f, 0.0f, 0.0f};
  // World-space unit axes, orthogonal: right x up = -forward (glTF's camera looks down its -Z).
  std::array<float, 3> right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f}, forward{0.0f, 0.0f, -1.0f};
  float fovDegrees = 40.0f;   // perspective: vertical field of view, in (0, 180)
  float xmag = 1.0f, ymag = 1.0f;  // orthographic: half width and half height of the view, > 0
  float znear = 0.0f, zfar = 0.0f;  // distances along forward where surfaces start and end; zfar 0 = infinite
};

// 3-channel vectors are interleaved xyz (or rgb) per pixel; every vector is row-major from the
// top-left pixel. Optional channels are empty when absent; the shading then uses the glTF
// defaults (0 for every extension factor, no emission, clearcoatN = N) and, without T, the
// frame built from N that docs/gbuffer.md specifies.
struct GBuffer {
  int width = 0, height = 0;
  // Required.
  std::vector<float> P;          // world position
  std::vector<float> N;          // world shading normal, unit length
  std::vector<float> baseColor;  // linear RGB
  std::vector<float> metallic, roughness;
  std::vector<float> mask;  // 1 where a surface is present, 0 where the environment shows
  // Optional.
  std::vector<float> T;  // world tangent, unit length, perpendicular to N
  std::vector<float> emissive;
  std::vector<float> sheenColor, sheenRoughness;
  std::vector<float> clearcoat, clearcoatRoughness, clearcoatN;
  std::vector<float> anisotropyStrength, anisotropyRotation;  // rotation in radians, CCW from T
  std::vector<float> occlusion;  // glTF ambient occlusion, [0, 1]; dims image-based light only (default 1)
  std::vector<float> V;          // world direction towards the viewer, unit; overrides the scene camera
  // The camera that made it, when the file says (brdfcl's own G-buffers do); written to and
  // read from the EXR header, never a channel.
  std::optional<GBufferCamera> camera;

  std::size_t pixelCount() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  bool hasTangent() const { return !T.empty(); }
  bool hasEmissive() const { return !emissive.empty(); }
  bool hasSheen() const { return !sheenColor.empty() || !sheenRoughness.empty(); }
  bool hasClearcoat() const { return !clearcoat.empty() || !clearcoatRoughness.empty() || !clearcoatN.empty(); }
  bool hasAnisotropy() const { return !anisotropyStrength.empty() || !anisotropyRotation.empty(); }
  bool hasOcclusion() const { return !occlusion.empty(); }
  bool hasView() const { return !V.empty(); }
};

// Reads and checks a G-buffer EXR (HALF or FLOAT channels). Accepts the canonical names of
// docs/gbuffer.md and, for N and P, Blender's multilayer pass names "<layer>.Normal.X" and
// "<layer>.Position.X" (one layer; the canonical names win when both are present). Throws a
// one-line brdfcl::Error starting with the file name for: a file that is missing, not EXR,
// multi-part, deep or truncated; a data window other than the display window; a missing
// required channel; an incomplete vector (T.X without T.Z); a used channel with x/y sampling
// other than 1 or of type UINT; several Blender layers with the same pass; a NaN or an infinity
// in a used channel; camera attributes that are incomplete, of the wrong type or out of range.
// With options.check (the default), also a value outside its documented range on a covered
// pixel (mask >= 0.5): a glTF factor outside [0, 1], a negative emission, a normal or tangent
// (N, clearcoatN, T) whose length is not 1 within kGBufferUnitTolerance.
struct GBufferReadOptions {
  bool check = true;
};
constexpr double kGBufferUnitTolerance = 1e-3;
GBuffer readGBuffer(const std::string& path, const GBufferReadOptions& options);
GBuffer readGBuffer(const std::string& path);

// readGBuffer's value check (options.check) on a G-buffer made in memory, such as the Python
// package's dict of channels: the first covered pixel (raster order) with a value outside its
// documented range throws the same brdfcl::Error, with `shown` in place of the file name and
// `skip` naming how to turn the check off ("--no-check" for the CLI, "check=False" for Python).
void checkGBufferValues(const GBuffer& g, const std::string& shown, const std::string& skip);

// Writes every non-empty channel under its canonical name (HALF when `half`, else FLOAT; ZIP
// compression) and the camera's header attributes when it has one, atomically (see writeAtomically). A required channel that is empty or any
// channel whose size is not width·height·(1 or 3) is a caller bug: std::invalid_argument.
void writeGBuffer(const std::string& path, const GBuffer& g, bool half = false);

}  // namespace brdfcl
