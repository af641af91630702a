// The reference's materialx profile (docs/profiles.md): MaterialX gltf_pbr's direct-light BRDF
// and its lobe split, with its albedo fits and exact dielectric Fresnel.
#include <algorithm>
#include <cmath>

#include "reference/profile_terms.hpp"

namespace ref::engine {

// ---- materialx: MaterialX gltf_pbr ----
Lobes materialx(const Mat& q, const Geometry& g) {
  const double alpha = q.r * q.r;
  const double s2 = q.aniso ? q.s * q.s : 0.0;
  const double alphaT = std::clamp(mix(alpha, 1.0, s2), 1e-5, 1.0);
  const double alphaB = std::clamp(alpha, 1e-5, 1.0);
  const double alphaBar = std::sqrt(alphaT * alphaB);
  const double f0ior = f0FromIor(q.ior);

  // Burley D in the rotated frame (GGX when alphaT = alphaB); isotropic Smith on alphaBar.
  const double DV = D_Burley(alphaT, alphaB, dot3(g.H, g.T), dot3(g.H, g.B), g.NdotH) *
                    V_GGXp(alphaBar, g.NdotL, g.NdotV);

  // comp = 1 + Favg (1 - E) / E, E = A + B of the fit at (NdotV, a'), Favg the hemispherical
  // cosine-weighted average of Schlick's F: the integral of 2 mu (1 - mu)^5 over [0, 1] is 1/21.
  auto comp = [&](double F0, double F90, double a) {
    const auto ab = mxGgxAlbedoFit(g.NdotV, a);
    const double E = ab[0] + ab[1];
    const double Favg = F0 + (F90 - F0) / 21.0;
    return 1.0 + Favg * (1.0 - E) / E;
  };
  const auto fitBase = mxGgxAlbedoFit(g.NdotV, alphaBar);

  const double Fd = F_SchlickP(f0ior, 1.0, g.VdotH);
  const double compD = comp(f0ior, 1.0, alphaBar);
  const double specD = DV * Fd * compD;
  const double td = 1.0 - (f0ior * fitBase[0] + fitBase[1]) * compD;

  // Each BSDF returns at once (no response, throughput 1) when its weight is below M_FLOAT_EPS = 1e-8:
  // the sheen's weight is max3(c), the coat's cc (compared with the float the GLSL literal is).
  const double epsF = static_cast<double>(1e-8f);
  double ts = 1.0, sheenDV = 0.0;
  if (q.sheen && q.maxC >= epsF) {
    const double alphaS = q.rs * q.rs;
    // mx_imageworks_sheen_NDF's sin^2 = 1 - NdotH^2, in the engine's float.
    const float nhF = static_cast<float>(g.NdotH);
    sheenDV = D_CharlieS(std::max(alphaS, 0.005), 1.0f - nhF * nhF) * V_Neubelt(g.NdotL, g.NdotV);
    ts = 1.0 - q.maxC * mxSheenAlbedo(g.NdotV, alphaS);  // view only, unfloored alpha
  }

  double tc = 1.0, coat = 0.0;
  if (q.coat && q.cc >= epsF) {
    const double alphaC = std::clamp(q.rc * q.rc, 1e-8, 1.0);
    const double Fc = F_diel(g.VdotH, 1.5);
    const double compC = comp(F_diel(1.0, 1.5), 1.0, alphaC);  // the coat's normal-incidence F
    const auto fitC = mxGgxAlbedoFit(g.NdotV, alphaC);
    coat = q.cc * D_GGXp(alphaC, g.NdotH) * V_GGXp(alphaC, g.NdotL, g.NdotV) * Fc * compC;
    tc = 1.0 - q.cc * (0.04 * fitC[0] + fitC[1]) * compC;
  }

  Lobes out;
  for (int i = 0; i < 3; ++i) {
    const double Fm = F_SchlickP(q.b[i], 1.0, g.VdotH);
    const double specM = DV * Fm * comp(q.b[i], 1.0, alphaBar);
    out.diffuse[i] = tc * ts * (1.0 - q.m) * td * q.b[i] / kPi;
    out.specular[i] = tc * ts * ((1.0 - q.m) * specD + q.m * specM);
    out.sheen[i] = tc * q.c[i] * sheenDV;
    out.clearcoat[i] = coat;
  }
  return out;
}

}  // namespace ref::engine
