// The common terms and types of the reference's engine profiles (docs/profiles.md "Common
// terms"): one home for what khronos, threejs, filament, babylon and materialx share, each
// engine in its own profile_<engine>.cpp. Private to tests/reference.
#pragma once

#include <algorithm>
#include <cmath>

#include "reference/profiles.hpp"

namespace ref::engine {

using brdfcl::SheenDistribution;
using brdfcl::SheenVisibility;

inline Vec3 normalized(Vec3 v) {
  const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / len, v.y / len, v.z / len};
}

inline double dot3(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

inline double mix(double a, double b, double t) { return a * (1.0 - t) + b * t; }

// S5(x) = (1 - x)^5, the Schlick weight.
inline double S5(double x) {
  const double y = 1.0 - x;
  return y * y * y * y * y;
}

// docs/profiles.md "Common terms". No guards: each profile applies its own clamps around them.
inline double D_GGXp(double alpha, double NdotH) {
  const double a2 = alpha * alpha;
  const double d = NdotH * NdotH * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

// The sum in V_GGX's denominator: NdotL sqrt(NdotV^2 (1 - a^2) + a^2) + NdotV sqrt(...L...).
// three.js guards this sum rather than V, so both need it.
inline double ggxDenominator(double alpha, double NdotL, double NdotV) {
  const double a2 = alpha * alpha;
  return NdotL * std::sqrt(NdotV * NdotV * (1.0 - a2) + a2) +
         NdotV * std::sqrt(NdotL * NdotL * (1.0 - a2) + a2);
}

inline double V_GGXp(double alpha, double NdotL, double NdotV) {
  return 0.5 / ggxDenominator(alpha, NdotL, NdotV);
}

inline double D_Burley(double at, double ab, double HdotT, double HdotB, double NdotH) {
  const double x = HdotT / at, y = HdotB / ab;
  const double q = x * x + y * y + NdotH * NdotH;
  return 1.0 / (kPi * at * ab * q * q);
}

inline double heitzDenominator(double at, double ab, double NdotL, double NdotV, double TdotV,
                               double BdotV, double TdotL, double BdotL) {
  const double lv = std::sqrt((at * TdotV) * (at * TdotV) + (ab * BdotV) * (ab * BdotV) + NdotV * NdotV);
  const double ll = std::sqrt((at * TdotL) * (at * TdotL) + (ab * BdotL) * (ab * BdotL) + NdotL * NdotL);
  return NdotL * lv + NdotV * ll;
}

// D_Charlie with sin^2(theta_h) passed in, since three.js and Filament floor it.
inline double D_CharlieS(double alpha, double sin2) {
  return (2.0 + 1.0 / alpha) * std::pow(sin2, 1.0 / (2.0 * alpha)) / (2.0 * kPi);
}

inline double V_Neubelt(double NdotL, double NdotV) {
  return 1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV));
}

inline double F_SchlickP(double f0, double f90, double x) { return f0 + (f90 - f0) * S5(x); }

// three.js's F: Epic's spherical-Gaussian weight in place of S5.
inline double F3(double f0, double f90, double x) {
  const double Fs = std::exp2((-5.55473 * x - 6.98316) * x);
  return f0 * (1.0 - Fs) + f90 * Fs;
}

// MaterialX's exact dielectric Fresnel for unpolarised light, c = cos of the incident angle.
inline double F_diel(double c, double eta) {
  const double g = std::sqrt(eta * eta + c * c - 1.0);
  const double a = (g - c) / (g + c);
  const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

inline double f0FromIor(double ior) {
  const double t = (ior - 1.0) / (ior + 1.0);
  return t * t;
}

inline double max3(const brdfcl::Rgb& c) {
  return std::max({static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])});
}

// The E table lookups of docs/profiles.md: mu = max(cos, 1e-4); r as each profile passes it.
inline double E_CC(double mu, double r) {
  return sheenAlbedo(std::max(mu, 1e-4), r, SheenDistribution::Charlie, SheenVisibility::Charlie);
}
inline double E_CN(double mu, double r) {
  return sheenAlbedo(std::max(mu, 1e-4), r, SheenDistribution::Charlie, SheenVisibility::Ashikhmin);
}

struct Lobes {
  Rgb diffuse{}, specular{}, sheen{}, clearcoat{};
};

// Everything a profile reads about the geometry, in the N = +Z frame.
struct Geometry {
  Vec3 L, V, H, T, B;
  double NdotL, NdotV, NdotH, VdotH;
};

// The material as doubles, with the layer switches every engine profile shares.
struct Mat {
  Rgb b;
  Rgb c;
  double m, r, rs, cc, rc, s, ior;
  bool sheen;  // ratified sheen present (not draft, max3(c) > 0)
  bool coat;   // clearcoat != 0
  bool aniso;     // anisotropyStrength > 0
  bool anisoExt;  // KHR_materials_anisotropy named (khronos's MATERIAL_ANISOTROPY)
  double maxC;
};

// Each engine's lobes for the material q at the geometry g (cosines already clamped as the
// engine clamps them).
Lobes khronos(const Mat& q, const Geometry& g);
Lobes threejs(const Mat& q, const Geometry& g);
Lobes filament(const Mat& q, const Geometry& g);
Lobes babylon(const Mat& q, const Geometry& g);
Lobes materialx(const Mat& q, const Geometry& g);

}  // namespace ref::engine
