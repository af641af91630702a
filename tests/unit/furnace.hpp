// G-buffer pixels and the scene of the image-based-light tests: a flat quad (N = +Z, T = +X) with a
// material and a view per pixel, lit by one of the built-in environments (the white furnace:
// `uniform` at radiance 1), the set-up `scripts/engine-check --ibl` shades as well.
#pragma once

#include <string>

#include "brdfcl/gbuffer.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/scene.hpp"

namespace brdfcl::test {

// Appends one pixel at the origin with material m seen from V (unit); the caller sets width, height.
inline void addFurnacePixel(GBuffer& g, const MaterialParams& m, float vx, float vy, float vz) {
  g.P.insert(g.P.end(), {0, 0, 0});
  g.N.insert(g.N.end(), {0, 0, 1});
  g.T.insert(g.T.end(), {1, 0, 0});
  g.V.insert(g.V.end(), {vx, vy, vz});
  g.baseColor.insert(g.baseColor.end(), m.baseColor.begin(), m.baseColor.end());
  g.metallic.push_back(m.metallic);
  g.roughness.push_back(m.roughness);
  g.mask.push_back(1);
  g.sheenColor.insert(g.sheenColor.end(), m.sheenColor.begin(), m.sheenColor.end());
  g.sheenRoughness.push_back(m.sheenRoughness);
  g.clearcoat.push_back(m.clearcoat);
  g.clearcoatRoughness.push_back(m.clearcoatRoughness);
  g.anisotropyStrength.push_back(m.anisotropyStrength);
  g.anisotropyRotation.push_back(m.anisotropyRotation);
}

// No lights; the built-in environment `kind` at intensity 1.
inline Scene builtinEnvironment(const std::string& kind = "uniform") {
  Scene s;
  s.environment.builtin = true;
  s.environment.builtinKind = kind;
  s.environment.intensity = 1.0f;
  return s;
}

}  // namespace brdfcl::test
