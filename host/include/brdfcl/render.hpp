// Deferred shading of G-buffers under punctual and image-based light, and the built-in
// "spheres" scene ray-cast on the device. The shader evaluates the same BRDF layers as batch
// evaluation (kernels/brdf/material.h) and prepares its environment maps and tables once.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "brdfcl/gbuffer.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/runtime.hpp"
#include "brdfcl/scene.hpp"

namespace brdfcl {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear radiance, interleaved, rows from the top
};

// The built-in scene: a 6 x 6 grid of spheres sweeping sheen colour x sheen roughness, clearcoat
// roughness over a rough coloured base, anisotropy strength and rotation, metallic x roughness;
// its camera, a key and a fill light, and the built-in studio environment.
Scene spheresScene();
GBuffer renderSpheresGBuffer(Runtime& rt, const Scene& scene, int width, int height);

// Equirectangular RGB (3 planes) of a scene's environment, intensity applied; `builtin` kinds:
// "sky", "studio", "uniform" (radiance 1: the white furnace). A file (readEnvironmentRgb) has its
// negative texels taken as 0.
std::vector<float> environmentPlanes(const Environment& env, int& width, int& height);

// C(mu): the Lambert albedo weighted by Schlick's (1 - V.H)^5, integral of w (N.L) / pi over L.
// The IBL diffuse weight 1 - (0.04 + 0.96 C) then matches Appendix B's directional albedo.
double fresnelWeightedLambert(double mu);

class Shader {
 public:
  Shader(Runtime& rt, const Scene& scene, EvalOptions options = {});
  ~Shader();
  // Not for concurrent calls on one Shader: it keeps its G-buffer planes between frames.
  Image shade(const GBuffer& g);

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace brdfcl
