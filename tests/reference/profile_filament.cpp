// The reference's filament profile (docs/profiles.md): Filament (desktop)'s direct-light BRDF
// and its lobe split, with the engine's capped GGX D.
#include <algorithm>
#include <cmath>

#include "reference/profile_terms.hpp"

namespace ref::engine {

namespace {

// Filament's GGX D: k = min(alpha / (1 - NdotH^2 + (NdotH alpha)^2), 453.5), D = k^2 / pi.
// Its V, Kelemen and anisotropic D carry no cap on desktop.
double D_Filament(double alpha, double NdotH) {
  const double k = std::min(alpha / (1.0 - NdotH * NdotH + (NdotH * alpha) * (NdotH * alpha)), 453.5);
  return k * k / kPi;
}

}  // namespace

// ---- filament: Filament (desktop) ----
Lobes filament(const Mat& q, const Geometry& g) {
  // The coat raises the base roughness before the floor.
  const double rho = std::clamp(mix(q.r, std::max(q.r, q.rc), q.cc), 0.045, 1.0);
  const double alpha = rho * rho;
  const double f0ior = f0FromIor(std::max(q.ior, 1.0));

  Rgb f0;
  for (int i = 0; i < 3; ++i) f0[i] = q.b[i] * q.m + f0ior * (1.0 - q.m);
  const double f90 = std::clamp(16.5 * (f0[0] + f0[1] + f0[2]), 0.0, 1.0);

  double DV;
  if (q.anisoExt) {
    // Kulla's parametrisation with A = s (brdfcl's mapping of glTF strength), on the extension's
    // presence (gltfio's MATERIAL_HAS_ANISOTROPY), strength 0 included: no cap on D.
    const double at = std::max(alpha * (1.0 + q.s), 0.002025);
    const double ab = std::max(alpha * (1.0 - q.s), 0.002025);
    DV = D_Burley(at, ab, dot3(g.H, g.T), dot3(g.H, g.B), g.NdotH) *
         (0.5 / heitzDenominator(at, ab, g.NdotL, g.NdotV, dot3(g.T, g.V), dot3(g.B, g.V), dot3(g.T, g.L),
                                 dot3(g.B, g.L)));
  } else {
    DV = D_Filament(alpha, g.NdotH) * V_GGXp(alpha, g.NdotL, g.NdotV);
  }
  const double Ess = threejsDfgEss(rho, g.NdotV);

  double sh = 1.0, sheenDV = 0.0;
  if (q.sheen) {
    const double rhoS = std::clamp(q.rs, 0.045, 1.0);
    const double alphaS = rhoS * rhoS;
    sheenDV = D_CharlieS(alphaS, std::max(1.0 - g.NdotH * g.NdotH, 0.0078125)) *
              V_Neubelt(g.NdotL, g.NdotV);
    sh = 1.0 - q.maxC * E_CN(g.NdotV, rhoS);  // view only, at the clamped roughness
  }

  double k = 1.0, coat = 0.0;
  if (q.coat) {
    const double rhoC = std::clamp(q.rc, 0.045, 1.0);
    const double alphaC = rhoC * rhoC;
    const double Fcc = q.cc * F_SchlickP(0.04, 1.0, g.VdotH);  // on L.H, not N.V
    coat = Fcc * D_Filament(alphaC, g.NdotH) * (0.25 / (g.VdotH * g.VdotH));  // Kelemen V
    k = 1.0 - Fcc;
  }

  Lobes out;
  for (int i = 0; i < 3; ++i) {
    const double F = F_SchlickP(f0[i], f90, g.VdotH);
    const double ec = 1.0 + f0[i] * (1.0 / Ess - 1.0);
    out.diffuse[i] = k * sh * (1.0 - q.m) * q.b[i] / kPi;  // Lambert, no Fresnel weight
    out.specular[i] = k * sh * F * DV * ec;
    out.sheen[i] = k * q.c[i] * sheenDV;
    out.clearcoat[i] = coat;
  }
  return out;
}

}  // namespace ref::engine
