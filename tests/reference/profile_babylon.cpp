// The reference's babylon profile (docs/profiles.md): Babylon.js PBRMaterial's direct-light
// BRDF and its lobe split, read from its environment BRDF texture.
#include <algorithm>
#include <cmath>

#include "reference/profile_terms.hpp"

namespace ref::engine {

// ---- babylon: Babylon.js PBRMaterial ----
Lobes babylon(const Mat& q, const Geometry& g) {
  // convertRoughnessToAverageSlope: r^2 + 0.0005 for every lobe.
  const double alphaG = q.r * q.r + 0.0005;
  const double f0ior = f0FromIor(q.ior);

  double S;
  if (q.aniso) {
    const double at = std::max(mix(alphaG, 1.0, q.s * q.s), 0.0005);
    const double ab = std::max(alphaG, 0.0005);
    S = D_Burley(at, ab, dot3(g.H, g.T), dot3(g.H, g.B), g.NdotH) * 0.5 /
        heitzDenominator(at, ab, g.NdotL, g.NdotV, dot3(g.T, g.V), dot3(g.B, g.V), dot3(g.T, g.L),
                         dot3(g.B, g.L));
  } else {
    S = D_GGXp(alphaG, g.NdotH) * V_GGXp(alphaG, g.NdotL, g.NdotV);
  }
  const double Ess = babylonBrdf(g.NdotV, q.r)[1];  // .y at the raw roughness, not alphaG's

  double sh = 1.0, sheenDV = 0.0;
  if (q.sheen) {
    const double alphaGS = q.rs * q.rs + 0.0005;
    // normalDistributionFunction_CharlieSheen's sin^2 = 1 - NdotH^2, in the engine's float.
    const float nhF = static_cast<float>(g.NdotH);
    sheenDV = D_CharlieS(alphaGS, 1.0f - nhF * nhF) * V_Neubelt(g.NdotL, g.NdotV);
    sh = 1.0 - q.maxC * babylonBrdf(g.NdotV, q.rs)[2];  // .b, view only, raw r_s
  }

  double Fc = 0.0, coat = 0.0, EssC = 1.0;
  if (q.coat) {
    const double alphaGC = q.rc * q.rc + 0.0005;
    Fc = q.cc * F_SchlickP(0.04, 1.0, g.VdotH);
    coat = Fc * D_GGXp(alphaGC, g.NdotH) * 0.25 / (g.VdotH * g.VdotH);
    EssC = babylonBrdf(g.NdotV, q.rc)[1];  // the coat's own raw roughness
  }

  Lobes out;
  for (int i = 0; i < 3; ++i) {
    const double f0 = mix(f0ior, q.b[i], q.m);
    const double F = F_SchlickP(f0, 1.0, g.VdotH);
    const double ec = 1.0 + f0 * (1.0 / Ess - 1.0);
    // Legacy specular energy conservation: the albedo is b (1 - f0_ior)(1 - m), no angle.
    // finalDiffuse = max(diffuseBase * surfaceAlbedo, 0): the sheen scaling can be negative.
    out.diffuse[i] = std::max((1.0 - Fc) * sh * (1.0 - f0ior) * (1.0 - q.m) * q.b[i] / kPi, 0.0);
    out.specular[i] = (1.0 - Fc) * sh * F * S * ec;
    out.sheen[i] = (1.0 - Fc) * q.c[i] * sheenDV;
    // The coat's multiscatter factor with the base's F0, per channel.
    out.clearcoat[i] = coat * (1.0 + f0 * (1.0 / EssC - 1.0));
  }
  return out;
}

}  // namespace ref::engine
