// The host side of --ibl exact (kernels/ibl_exact.cl): the environment's luminance CDFs for
// importance sampling, the chunked launches over samples, and the image's error estimate.
#pragma once
#include <vector>

#include "brdfcl/render.hpp"
#include "runtime/opencl.hpp"
#include "kernels/common/shading_layout.h"

namespace brdfcl::detail {

// Importance sampling of an equirectangular map (3 planes) by luminance x sin(theta): the
// marginal CDF over rows (h + 1 entries), a conditional CDF per row (w + 1 each) and each texel's
// probability. `share` is the probability the kernel gives to sampling it: 0 for a black or a
// uniform environment, up to kMaxEnvironmentShare for a peaked one (a sun).
constexpr double kMaxEnvironmentShare = 0.5;
struct EnvironmentCdf {
  std::vector<float> rows, cols, texelP;
  float share = 0.0f;
};
EnvironmentCdf environmentCdf(const std::vector<float>& planes, int w, int h);

// Everything one exact integration needs on the device.
struct ExactIblInputs {
  cl::Program program;
  const cl::Buffer* gbuffer = nullptr;  // the planes of shading_layout.h
  int width = 0, height = 0;
  brdfcl_camera camera{};
  const cl::Buffer *environment = nullptr, *rows = nullptr, *cols = nullptr, *texelP = nullptr;
  int envW = 0, envH = 0;
  float envShare = 0.0f;
  float rotation = 0.0f;
  const cl::Buffer* sheenE = nullptr;
  int sheenESize = 0;
};

// Integrates the image-based light of every covered pixel and adds it, times the occlusion plane
// of `planes`, to `out` (3 planes of width * height). Fills `stats` when given.
void integrateExactIbl(Runtime& rt, const ExactIblInputs& in, const std::vector<float>& planes,
                       const ShadeOptions& options, std::vector<float>& out, ShadeStats* stats);

}  // namespace brdfcl::detail
