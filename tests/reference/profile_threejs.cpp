// The reference's threejs profile (docs/profiles.md): three.js WebGPU (TSL)'s direct-light
// BRDF and its lobe split.
#include <algorithm>
#include <cmath>

#include "reference/profile_terms.hpp"

namespace ref::engine {

// ---- threejs: three.js WebGPU (TSL) ----
Lobes threejs(const Mat& q, const Geometry& g) {
  const double rho = std::min(std::max(q.r, 0.045), 1.0);
  const double alpha = rho * rho;
  const double f0d = std::min(f0FromIor(q.ior), 1.0);

  double S;
  if (q.aniso) {
    const double at = mix(alpha, 1.0, q.s * q.s), ab = alpha;
    const double den = heitzDenominator(at, ab, g.NdotL, g.NdotV, dot3(g.T, g.V), dot3(g.B, g.V),
                                        dot3(g.T, g.L), dot3(g.B, g.L));
    S = D_Burley(at, ab, dot3(g.H, g.T), dot3(g.H, g.B), g.NdotH) * 0.5 / std::max(den, 1e-6);
  } else {
    S = D_GGXp(alpha, g.NdotH) * 0.5 / std::max(ggxDenominator(alpha, g.NdotL, g.NdotV), 1e-6);
  }
  const double Ess = threejsDfgEss(rho, g.NdotV);

  double sh = 1.0, sheenDV = 0.0;
  if (q.sheen) {
    const double rhoS = std::clamp(q.rs, 0.07, 1.0);  // the WebGPU path's clamp, not WebGL's 1e-4
    const double alphaS = rhoS * rhoS;
    sheenDV = D_CharlieS(alphaS, std::max(1.0 - g.NdotH * g.NdotH, 0.0078125)) *
              std::min(V_Neubelt(g.NdotL, g.NdotV), 1.0);
    sh = 1.0 - q.maxC * std::max(threejsSheenAlbedo(g.NdotV, rhoS), threejsSheenAlbedo(g.NdotL, rhoS));
  }

  double k = 1.0, coat = 0.0;
  if (q.coat) {
    const double rhoC = std::min(std::max(q.rc, 0.045), 1.0);
    const double alphaC = rhoC * rhoC;
    k = 1.0 - q.cc * F3(0.04, 1.0, g.NdotV);
    // F on V.H inside the lobe, weight cc (not cc Fcc).
    coat = q.cc * F3(0.04, 1.0, g.VdotH) * D_GGXp(alphaC, g.NdotH) * 0.5 /
           std::max(ggxDenominator(alphaC, g.NdotL, g.NdotV), 1e-6);
  }

  Lobes out;
  for (int i = 0; i < 3; ++i) {
    const double f0b = mix(f0d, q.b[i], q.m);
    const double ms = 1.0 + f0b * (1.0 / Ess - 1.0);
    // The diffuse weight uses the dielectric f0, not f0_b.
    out.diffuse[i] = k * sh * (1.0 - q.m) * (1.0 - F3(f0d, 1.0, g.VdotH)) * q.b[i] / kPi;
    out.specular[i] = k * sh * F3(f0b, 1.0, g.VdotH) * S * ms;
    out.sheen[i] = q.c[i] * sheenDV;  // TSL finish(): sheen on top of the coat, not attenuated
    out.clearcoat[i] = coat;
  }
  return out;
}

}  // namespace ref::engine
