// Independent double-precision reference of the brdfcl BRDF stack, written from the spec texts in
// seeds/ (000..004) and glTF 2.0 Appendix B only; it shares no code with kernels/ or host/src/.
// Terms, the sheen directional albedo E(mu, r) (integral + fast table), the layered BRDF, helpers.
#pragma once

#include <array>
#include <functional>

// The reference library's CMake target only adds tests/ to the include path, so fall back to
// the header's place in the tree when host/include is not on it.
#if __has_include(<brdfcl/material.hpp>)
#include <brdfcl/material.hpp>
#else
#include "../../host/include/brdfcl/material.hpp"
#endif

namespace ref {

using Rgb = std::array<double, 3>;
struct Vec3 {
  double x, y, z;
};

constexpr double kPi = 3.14159265358979323846;

// Shading frame of the whole reference: N = +Z, T = +X, B = +Y.

// ---- Terms (each is the formula of its text; no clamps, callers keep inputs in range) ----

// GGX / Trowbridge-Reitz NDF with chi+(N.H); alpha = roughness^2.
double D_GGX(double NdotH, double alpha);
// Height-correlated Smith visibility G/(4 N.L N.V).
double V_SmithGGXCorrelated(double NdotL, double NdotV, double alpha);
// Burley's anisotropic GGX NDF; at/ab are the alpha roughnesses along T'/B'.
double D_GGX_Anisotropic(double NdotH, double TdotH, double BdotH, double at, double ab);
// Anisotropic height-correlated visibility, unclamped. NOTE: the argument order differs from the
// sample code in 002 (which takes BdotV before TdotV).
double V_GGX_Anisotropic(double NdotL, double NdotV, double TdotV, double BdotV, double TdotL,
                         double BdotL, double at, double ab);
// Charlie sheen NDF; alpha = sheenRoughness^2 (KHR_materials_sheen) or roughness^2 (the experimental draft).
double D_Charlie(double NdotH, double alpha);
// Ashikhmin velvet NDF as the article's AshikhminD(roughness := alpha, ndoth): m2 = alpha^2.
double D_Ashikhmin(double NdotH, double alpha);
// Conty-Kulla sheen visibility with the lambda_sheen fit; alpha = sheenRoughness^2.
double V_Charlie(double NdotL, double NdotV, double alpha);
// Ashikhmin-Premoze smooth visibility (denominator included).
double V_Ashikhmin(double NdotL, double NdotV);
// Schlick Fresnel with f90 = 1.
double F_Schlick(double f0, double VdotH);

// The sheen D or V that the options select; alpha = sheenRoughness^2.
double sheenD(double NdotH, double alpha, brdfcl::SheenDistribution d);
double sheenV(double NdotL, double NdotV, double alpha, brdfcl::SheenVisibility v);

// ---- Sheen directional albedo ----
// E(mu, r) = integral over the upper hemisphere of D(H) V(L, V) (N.L) dw_L for the white sheen
// lobe, with N.V = mu and alpha_s = r^2.

// Domain of the precomputed table; sheenAlbedo() integrates directly outside it (slow).
constexpr double kAlbedoMuMin = 0.01;
constexpr double kAlbedoRMin = 0.05;

// Fast (~0.5 us): tensor Chebyshev interpolation of tables built lazily by sheenAlbedoIntegral
// (thread-safe, multi-threaded, once per distribution: both visibilities share the azimuthal
// integral of D, ~1.5 s of CPU). Max error < 1e-7 measured, < 1e-6 tested, for mu in [0.01, 1]
// and r in [0.05, 1]. Outside that domain it integrates directly (slow, remembers the last value
// per thread); r < 0.05 is outside the model's tested range (r = 0 is singular).
double sheenAlbedo(double mu, double sheenRoughness, brdfcl::SheenDistribution d,
                   brdfcl::SheenVisibility v);
// Direct nested adaptive Gauss-Kronrod integration (~1-10 ms). tol is the absolute error target
// of the outer integral; the default gives errors far below 1e-9.
double sheenAlbedoIntegral(double mu, double sheenRoughness, brdfcl::SheenDistribution d,
                           brdfcl::SheenVisibility v, double tol = 1e-11);
// E looked up as the layered BRDF's table is defined (docs/model.md, "Sheen, ratified": 320 x 320
// nodes at mu = s^2, r = t^2, bilinear in (s, t) = (sqrt mu, sqrt r)), each node's value from
// sheenAlbedo() (remembered; nodes at mu < 0.01 integrate, r = 0 is singular). What the kernels'
// f and lobe probabilities see, for comparisons tighter than the table's interpolation error.
double tabulatedSheenAlbedo(double mu, double sheenRoughness, brdfcl::SheenDistribution d,
                            brdfcl::SheenVisibility v);
// Builds the tables of distribution d (both visibilities) now instead of on first use; returns
// the seconds it took, 0 when they were already built.
double precomputeSheenAlbedo(brdfcl::SheenDistribution d, brdfcl::SheenVisibility v);

// ---- The layered BRDF ----
// f in 1/sr (no cosine). L points to the light, V to the viewer, both normalised here.
// Returns 0 when N.L <= 0 or N.V <= 0. options.lobe selects one additive part of the sum
// (Diffuse + Specular + Sheen + Clearcoat == All). Layers: Appendix B base (anisotropic GGX when
// anisotropyStrength != 0, T' rotated CCW from +X), then the ratified sheen (if max3(sheenColor)
// > 0; scaled by 1 - max3 * E as options say, unclamped, so it can go negative where E > 1) or
// the draft sheen (draftSheen: always Charlie D, Ashikhmin V, roughness^2, no options), then the
// clearcoat (if clearcoat != 0) with Fc on N.V. Sheen E lookups use sheenAlbedo().
Rgb brdf(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V);

// brdf() with every E from tabulatedSheenAlbedo().
Rgb brdfTabulated(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V);

// ---- Test helpers ----

// Globally adaptive Gauss-Kronrod (10/21) integration of f on [a, b] to absolute error estimate
// absTol (bisection of the worst interval, at most maxIntervals intervals).
double integrate(const std::function<double(double)>& f, double a, double b, double absTol,
                 int maxIntervals = 4000);

// Directional albedo of the material for view V: integral over the upper hemisphere of
// brdf(m, o, L, V) (N.L) dw_L, per channel, by nested adaptive Gauss-Kronrod in (N.L, azimuth),
// N.L < 0.01 in ln N.L. absTol is per channel. Cost: ~1-100 ms; with SheenScaling::Min ~0.5-1 s,
// because E(N.L) below the table's N.L = 0.01 is integrated (once per N.L node).
Rgb directionalAlbedo(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 V,
                      double absTol = 1e-7);

}  // namespace ref
