// The reference's khronos profile (docs/profiles.md): the glTF Sample Renderer's direct-light
// BRDF and its lobe split, with the float rounding the engine's D and sheen show.
#include <algorithm>
#include <cmath>

#include "reference/profile_terms.hpp"

namespace ref::engine {

namespace {

// ---- khronos: glTF Sample Renderer ----
// D_GGX, infinite where the engine's float denominator NdotH^2 (alpha^2 - 1) + 1 is exactly 0
// (N.H = 1 and alpha^2 - 1 rounding to -1 in float), NaN there at alpha = 0.
double khronosD(double alpha, double NdotH) {
  const float nh = static_cast<float>(NdotH), a2 = static_cast<float>(alpha * alpha);
  const float f = nh * nh * (a2 - 1.0f) + 1.0f;
  if (f == 0.0f) return alpha * alpha / 0.0;
  return D_GGXp(alpha, NdotH);
}

}  // namespace

Lobes khronos(const Mat& q, const Geometry& g) {
  const double alpha = q.r * q.r;
  const double f0d = f0FromIor(q.ior);

  double S;
  if (q.anisoExt) {  // the anisotropic path on presence, strength 0 included
    const double at = mix(alpha, 1.0, q.s * q.s);  // unfloored, as the engine has it
    const double ab = std::clamp(alpha, 0.001, 1.0);
    const double NdotH = std::clamp(g.NdotH, 0.001, 1.0);
    // The engine's grouping (a = at ab, w2 = a / |(ab H.T, at H.B, a N.H)|^2, D = a w2^2 / pi):
    // 0 at at = 0 off N.H = 1, where dividing by at first would give NaN.
    const double a = at * ab;
    const double fx = ab * dot3(g.H, g.T), fy = at * dot3(g.H, g.B), fz = a * NdotH;
    const double w2 = a / (fx * fx + fy * fy + fz * fz);
    const double D = a * w2 * w2 / kPi;
    const double Vis = std::min(0.5 / heitzDenominator(at, ab, g.NdotL, g.NdotV, dot3(g.T, g.V),
                                                       dot3(g.B, g.V), dot3(g.T, g.L), dot3(g.B, g.L)),
                                1.0);
    S = D * Vis;
  } else {
    S = khronosD(alpha, g.NdotH) * V_GGXp(alpha, g.NdotL, g.NdotV);  // NaN at alpha = 0, N.H = 1
  }

  const double Fd = F_SchlickP(f0d, 1.0, g.VdotH);

  double sh = 1.0;
  double sheenDV = 0.0;
  if (q.sheen) {
    const double rsF = std::max(q.rs, 1e-6);
    const double alphaS = rsF * rsF;
    // sin^2 = 1 - N.H^2 as the engine computes it, in float: 1 below N.H ~ 1.7e-4.
    const float nhF = static_cast<float>(g.NdotH);
    const float sin2F = 1.0f - nhF * nhF;
    sheenDV = D_CharlieS(alphaS, sin2F) *
              std::min(V_Charlie(g.NdotL, g.NdotV, alphaS), 1.0);
    // albedoSheenScalingLUT: the renderer's own texture at the raw sheen roughness (the D's
    // floor does not reach it) and the clamped cosines.
    sh = std::min(1.0 - q.maxC * khronosSheenE(g.NdotV, q.rs), 1.0 - q.maxC * khronosSheenE(g.NdotL, q.rs));
  }

  double k = 1.0, coat = 0.0;
  if (q.coat) {
    // The engine takes the coat's F0 from the material IOR, not 1.5.
    const double Fc = F_SchlickP(f0FromIor(q.ior), 1.0, g.NdotV);
    const double alphaC = q.rc * q.rc;
    coat = q.cc * Fc * khronosD(alphaC, g.NdotH) * V_GGXp(alphaC, g.NdotL, g.NdotV);
    k = 1.0 - q.cc * Fc;
  }

  Lobes out;
  for (int i = 0; i < 3; ++i) {
    const double Fm = F_SchlickP(q.b[i], 1.0, g.VdotH);
    out.diffuse[i] = k * sh * (1.0 - q.m) * (1.0 - Fd) * q.b[i] / kPi;
    // mix(S Fd, S F_m, m) as the engine mixes them: an infinite S is NaN at any m (0 * inf).
    out.specular[i] = k * sh * ((1.0 - q.m) * Fd * S + q.m * (Fm * S));
    out.sheen[i] = k * q.c[i] * sheenDV;
    out.clearcoat[i] = coat;
  }
  return out;
}

}  // namespace ref::engine
