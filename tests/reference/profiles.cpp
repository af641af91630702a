// Independent double-precision reference of the engine parity profiles (see profiles.hpp):
// khronos, threejs, filament, babylon and materialx as docs/profiles.md writes them, line by
// line, with their tables (three.js DFG data, the Sample Renderer's sheen albedo texels,
// MaterialX fits) and the lobe split.
#include "reference/profiles.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace ref {

using brdfcl::Lobe;
using brdfcl::MaterialParams;
using brdfcl::Profile;
using brdfcl::SheenDistribution;
using brdfcl::SheenVisibility;

// ============================================================================================
// Tables and fits
// ============================================================================================

namespace {

// The data only (the .inc is numbers and comments): row j = NdotV (j + 0.5)/16, 16 texels
// i = roughness (i + 0.5)/16 each, each texel (A, B) as half-float bits.
constexpr std::uint16_t kThreejsDfgBits[16 * 16 * 2] = {
#include "../../host/src/model/threejs_dfg_lut.inc"
};

}  // namespace

double halfToDouble(std::uint16_t bits) {
  const int sign = (bits >> 15) & 1;
  const int exponent = (bits >> 10) & 0x1f;
  const int mantissa = bits & 0x3ff;
  double v;
  if (exponent == 0) {
    v = std::ldexp(static_cast<double>(mantissa), -24);  // subnormal: m / 2^10 * 2^-14
  } else if (exponent == 31) {
    v = mantissa == 0 ? HUGE_VAL : std::nan("");
  } else {
    v = std::ldexp(1.0 + mantissa / 1024.0, exponent - 15);
  }
  return sign ? -v : v;
}

std::array<double, 2> threejsDfg(double roughness, double NdotV) {
  // A GPU's bilinear fetch: coordinate x in texel units measured from texel 0's centre, the
  // two neighbours clamped to the edge (so beyond the outer centres the edge texel is returned).
  auto split = [](double u, int& i0, int& i1, double& w) {
    const double x = u * 16.0 - 0.5;
    const double fl = std::floor(x);
    w = x - fl;
    i0 = std::clamp(static_cast<int>(fl), 0, 15);
    i1 = std::clamp(static_cast<int>(fl) + 1, 0, 15);
  };
  int i0, i1, j0, j1;
  double wu, wv;
  split(roughness, i0, i1, wu);
  split(NdotV, j0, j1, wv);
  auto texel = [](int i, int j, int ch) {
    return halfToDouble(kThreejsDfgBits[(j * 16 + i) * 2 + ch]);
  };
  std::array<double, 2> out{};
  for (int ch = 0; ch < 2; ++ch) {
    const double bottom = texel(i0, j0, ch) * (1.0 - wu) + texel(i1, j0, ch) * wu;
    const double top = texel(i0, j1, ch) * (1.0 - wu) + texel(i1, j1, ch) * wu;
    out[ch] = bottom * (1.0 - wv) + top * wv;
  }
  return out;
}

namespace {
// The data only: lut_sheen_E.png's red channel as 8-bit texels, zlib-compressed, rows = sheen
// roughness, columns = N.V (docs/profiles.md "Tables").
constexpr unsigned char kKhronosSheenE[] = {
#include "../../host/src/model/khronos_sheen_e_lut.inc"
};
constexpr int kKhronosN = 1024;

const std::vector<unsigned char>& khronosTexels() {
  static const std::vector<unsigned char> t = [] {
    std::vector<unsigned char> v(std::size_t(kKhronosN) * kKhronosN);
    uLongf n = uLongf(v.size());
    if (uncompress(v.data(), &n, kKhronosSheenE, uLong(sizeof kKhronosSheenE)) != Z_OK || n != v.size())
      throw std::logic_error("khronos_sheen_e_lut.inc does not inflate to 1024x1024 texels");
    return v;
  }();
  return t;
}
}  // namespace

double khronosSheenE(double NdotV, double sheenRoughness) {
  // texture(u_SheenELUT, vec2(N.V, r_s)).r with LINEAR and CLAMP_TO_EDGE: texel centres at
  // (i + 0.5)/1024, neighbours clamped to the edge; each texel unorm8 / 255.
  auto split = [](double u, int& i0, int& i1, double& w) {
    const double x = u * kKhronosN - 0.5;
    const double fl = std::floor(x);
    w = x - fl;
    i0 = std::clamp(static_cast<int>(fl), 0, kKhronosN - 1);
    i1 = std::clamp(static_cast<int>(fl) + 1, 0, kKhronosN - 1);
  };
  int i0, i1, j0, j1;
  double wu, wv;
  split(NdotV, i0, i1, wu);
  split(sheenRoughness, j0, j1, wv);
  const auto& t = khronosTexels();
  auto texel = [&](int i, int j) { return t[std::size_t(j) * kKhronosN + std::size_t(i)] / 255.0; };
  const double bottom = texel(i0, j0) * (1.0 - wu) + texel(i1, j0) * wu;
  const double top = texel(i0, j1) * (1.0 - wu) + texel(i1, j1) * wu;
  return bottom * (1.0 - wv) + top * wv;
}

namespace {
// The data only: Babylon's BRDF texture decoded from RGBD, (r, g, b) half-float bits per texel
// little-endian, zlib-compressed, rows = perceptual roughness, columns = N.V (docs/profiles.md "Tables").
constexpr unsigned char kBabylonBrdf[] = {
#include "../../host/src/model/babylon_brdf_lut.inc"
};
constexpr int kBabylonN = 256;

const std::vector<double>& babylonTexels() {
  static const std::vector<double> t = [] {
    std::vector<unsigned char> b(std::size_t(kBabylonN) * kBabylonN * 3 * 2);
    uLongf n = uLongf(b.size());
    if (uncompress(b.data(), &n, kBabylonBrdf, uLong(sizeof kBabylonBrdf)) != Z_OK || n != b.size())
      throw std::logic_error("babylon_brdf_lut.inc does not inflate to 256x256 texels of 3 half floats");
    std::vector<double> v(b.size() / 2);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = halfToDouble(std::uint16_t(b[2 * i] | (b[2 * i + 1] << 8)));
    return v;
  }();
  return t;
}
}  // namespace

std::array<double, 3> babylonBrdf(double NdotV, double roughness) {
  // texture2D(environmentBrdfSampler, vec2(N.V, r)) with BILINEAR and CLAMP: texel centres at
  // (i + 0.5)/256, neighbours clamped to the edge.
  auto split = [](double u, int& i0, int& i1, double& w) {
    const double x = u * kBabylonN - 0.5;
    const double fl = std::floor(x);
    w = x - fl;
    i0 = std::clamp(static_cast<int>(fl), 0, kBabylonN - 1);
    i1 = std::clamp(static_cast<int>(fl) + 1, 0, kBabylonN - 1);
  };
  int i0, i1, j0, j1;
  double wu, wv;
  split(NdotV, i0, i1, wu);
  split(roughness, j0, j1, wv);
  const auto& t = babylonTexels();
  auto texel = [&](int i, int j, int ch) { return t[(std::size_t(j) * kBabylonN + std::size_t(i)) * 3 + std::size_t(ch)]; };
  std::array<double, 3> out{};
  for (int ch = 0; ch < 3; ++ch) {
    const double bottom = texel(i0, j0, ch) * (1.0 - wu) + texel(i1, j0, ch) * wu;
    const double top = texel(i0, j1, ch) * (1.0 - wu) + texel(i1, j1, ch) * wu;
    out[ch] = bottom * (1.0 - wv) + top * wv;
  }
  return out;
}

double threejsDfgEss(double roughness, double NdotV) {
  const auto ab = threejsDfg(roughness, NdotV);
  return ab[0] + ab[1];
}

std::array<double, 2> mxGgxAlbedoFit(double mu, double alpha) {
  // docs/profiles.md "Fit_MX": r = k0 + k1 x + k2 y + k3 x y + k4 x^2 + k5 y^2 + k6 x^2 y
  // + k7 x y^2 + k8 x^2 y^2 per component, (A, B) = clamp(r.xy / r.zw, 0, 1).
  static constexpr double k[9][4] = {
      {0.1003, 0.9345, 1.0, 1.0},         {-0.6303, -2.323, -1.765, 0.2281},
      {9.748, 2.229, 8.263, 15.94},       {-2.038, -3.748, 11.53, -55.83},
      {29.34, 1.424, 28.96, 13.08},       {-8.245, -0.7684, -7.507, 41.26},
      {-26.44, 1.436, -36.11, 54.9},      {19.99, 0.2913, 15.86, 300.2},
      {-5.448, 0.6286, 33.37, -285.1}};
  const double x = mu, y = alpha;
  const double basis[9] = {1.0, x, y, x * y, x * x, y * y, x * x * y, x * y * y, x * x * y * y};
  double r[4] = {0.0, 0.0, 0.0, 0.0};
  for (int t = 0; t < 9; ++t)
    for (int c = 0; c < 4; ++c) r[c] += k[t][c] * basis[t];
  return {std::clamp(r[0] / r[2], 0.0, 1.0), std::clamp(r[1] / r[3], 0.0, 1.0)};
}

double mxSheenAlbedo(double mu, double alpha) {
  const double x = mu, y = alpha;
  const double num = 13.673 - 68.78018 * x + 799.08825 * y - 905.00061 * x * y + 60.28956 * x * x +
                     1086.96473 * y * y;
  const double den = 1.0 + 61.57746 * x + 442.78211 * y + 2597.49308 * x * y + 121.81241 * x * x +
                     3045.55075 * y * y;
  return std::clamp(num / den, 0.0, 1.0);
}

double threejsSheenAlbedo(double mu, double r) {
  const double rho = std::clamp(r, 0.07, 1.0);
  const double a = -1.9362 + 1.0678 * rho + 0.4573 * rho * rho - 0.8469 / (rho + 0.1);
  const double b = -0.6014 + 0.5538 * rho - 0.4670 * rho * rho - 0.1255 / (rho + 0.1);
  return std::clamp(std::exp(a * mu + b), 0.0, 1.0);
}

// ============================================================================================
// Profiles
// ============================================================================================

namespace {

Vec3 normalized(Vec3 v) {
  const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / len, v.y / len, v.z / len};
}

double dot3(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

double mix(double a, double b, double t) { return a * (1.0 - t) + b * t; }

// S5(x) = (1 - x)^5, the Schlick weight.
double S5(double x) {
  const double y = 1.0 - x;
  return y * y * y * y * y;
}

// docs/profiles.md "Common terms". No guards: each profile applies its own clamps around them.
double D_GGXp(double alpha, double NdotH) {
  const double a2 = alpha * alpha;
  const double d = NdotH * NdotH * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

// The sum in V_GGX's denominator: NdotL sqrt(NdotV^2 (1 - a^2) + a^2) + NdotV sqrt(...L...).
// three.js guards this sum rather than V, so both need it.
double ggxDenominator(double alpha, double NdotL, double NdotV) {
  const double a2 = alpha * alpha;
  return NdotL * std::sqrt(NdotV * NdotV * (1.0 - a2) + a2) +
         NdotV * std::sqrt(NdotL * NdotL * (1.0 - a2) + a2);
}

double V_GGXp(double alpha, double NdotL, double NdotV) {
  return 0.5 / ggxDenominator(alpha, NdotL, NdotV);
}

double D_Burley(double at, double ab, double HdotT, double HdotB, double NdotH) {
  const double x = HdotT / at, y = HdotB / ab;
  const double q = x * x + y * y + NdotH * NdotH;
  return 1.0 / (kPi * at * ab * q * q);
}

double heitzDenominator(double at, double ab, double NdotL, double NdotV, double TdotV,
                        double BdotV, double TdotL, double BdotL) {
  const double lv = std::sqrt((at * TdotV) * (at * TdotV) + (ab * BdotV) * (ab * BdotV) + NdotV * NdotV);
  const double ll = std::sqrt((at * TdotL) * (at * TdotL) + (ab * BdotL) * (ab * BdotL) + NdotL * NdotL);
  return NdotL * lv + NdotV * ll;
}

// D_Charlie with sin^2(theta_h) passed in, since three.js and Filament floor it.
double D_CharlieS(double alpha, double sin2) {
  return (2.0 + 1.0 / alpha) * std::pow(sin2, 1.0 / (2.0 * alpha)) / (2.0 * kPi);
}

double V_Neubelt(double NdotL, double NdotV) {
  return 1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV));
}

double F_SchlickP(double f0, double f90, double x) { return f0 + (f90 - f0) * S5(x); }

// three.js's F: Epic's spherical-Gaussian weight in place of S5.
double F3(double f0, double f90, double x) {
  const double Fs = std::exp2((-5.55473 * x - 6.98316) * x);
  return f0 * (1.0 - Fs) + f90 * Fs;
}

// MaterialX's exact dielectric Fresnel for unpolarised light, c = cos of the incident angle.
double F_diel(double c, double eta) {
  const double g = std::sqrt(eta * eta + c * c - 1.0);
  const double a = (g - c) / (g + c);
  const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

double f0FromIor(double ior) {
  const double t = (ior - 1.0) / (ior + 1.0);
  return t * t;
}

double max3(const brdfcl::Rgb& c) {
  return std::max({static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])});
}

// The E table lookups of docs/profiles.md: mu = max(cos, 1e-4); r as each profile passes it.
double E_CC(double mu, double r) {
  return sheenAlbedo(std::max(mu, 1e-4), r, SheenDistribution::Charlie, SheenVisibility::Charlie);
}
double E_CN(double mu, double r) {
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

Mat readMaterial(const MaterialParams& p) {
  Mat q;
  for (int i = 0; i < 3; ++i) {
    q.b[i] = p.baseColor[i];
    q.c[i] = p.sheenColor[i];
  }
  q.m = p.metallic;
  q.r = p.roughness;
  q.rs = p.sheenRoughness;
  q.cc = p.clearcoat;
  q.rc = p.clearcoatRoughness;
  q.s = p.anisotropyStrength;
  q.ior = p.ior;
  q.maxC = max3(p.sheenColor);
  // The draft sheen exists in no engine; a zero sheenColor is no sheen extension (as in spec).
  q.sheen = !p.draftSheen && q.maxC > 0.0;
  q.coat = p.clearcoat != 0.0f;
  q.aniso = p.anisotropyStrength > 0.0f;
  q.anisoExt = p.anisotropyExtension || q.aniso;
  return q;
}

// ---- khronos: glTF Sample Renderer ----
// D_GGX, infinite where the engine's float denominator NdotH^2 (alpha^2 - 1) + 1 is exactly 0
// (N.H = 1 and alpha^2 - 1 rounding to -1 in float), NaN there at alpha = 0.
double khronosD(double alpha, double NdotH) {
  const float nh = static_cast<float>(NdotH), a2 = static_cast<float>(alpha * alpha);
  const float f = nh * nh * (a2 - 1.0f) + 1.0f;
  if (f == 0.0f) return alpha * alpha / 0.0;
  return D_GGXp(alpha, NdotH);
}

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

// Filament's GGX D: k = min(alpha / (1 - NdotH^2 + (NdotH alpha)^2), 453.5), D = k^2 / pi.
// Its V, Kelemen and anisotropic D carry no cap on desktop.
double D_Filament(double alpha, double NdotH) {
  const double k = std::min(alpha / (1.0 - NdotH * NdotH + (NdotH * alpha) * (NdotH * alpha)), 453.5);
  return k * k / kPi;
}

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

Rgb pick(const Lobes& l, Lobe lobe) {
  switch (lobe) {
    case Lobe::Diffuse:
      return l.diffuse;
    case Lobe::Specular:
      return l.specular;
    case Lobe::Sheen:
      return l.sheen;
    case Lobe::Clearcoat:
      return l.clearcoat;
    case Lobe::All:
      break;
  }
  Rgb sum{};
  for (int i = 0; i < 3; ++i) sum[i] = l.diffuse[i] + l.specular[i] + l.sheen[i] + l.clearcoat[i];
  return sum;
}

}  // namespace

Rgb profileBrdf(const MaterialParams& m, Profile p, Lobe lobe, Vec3 L, Vec3 V) {
  if (p == Profile::Spec) {
    brdfcl::EvalOptions o;
    o.lobe = lobe;
    return brdf(m, o, L, V);
  }
  Geometry g;
  g.L = normalized(L);
  g.V = normalized(V);
  g.NdotL = g.L.z;
  g.NdotV = g.V.z;
  if (g.NdotL <= 0.0 || g.NdotV <= 0.0) return {0.0, 0.0, 0.0};
  g.H = normalized({g.L.x + g.V.x, g.L.y + g.V.y, g.L.z + g.V.z});
  g.NdotH = g.H.z;
  g.VdotH = dot3(g.V, g.H);
  const double theta = m.anisotropyRotation;
  g.T = {std::cos(theta), std::sin(theta), 0.0};
  g.B = {-std::sin(theta), std::cos(theta), 0.0};

  // Each engine's own cosine clamps: Khronos and three.js clamp to [0, 1] (no floor), Filament
  // floors N.V at 1e-4 (clampNoV) and saturates N.L, MaterialX clamps both to [1e-8, 1],
  // Babylon floors N.L at 1e-7 and adds 1e-7 to N.V.
  if (p == Profile::Filament) g.NdotV = std::max(g.NdotV, 1e-4);
  if (p == Profile::Materialx) {
    g.NdotL = std::max(g.NdotL, 1e-8);
    g.NdotV = std::max(g.NdotV, 1e-8);
  }
  // Babylon: saturateEps floors N.L at 1e-7, absEps adds 1e-7 to N.V.
  if (p == Profile::Babylon) {
    g.NdotL = std::max(g.NdotL, 1e-7);
    g.NdotV = g.NdotV + 1e-7;
  }

  const Mat q = readMaterial(m);
  switch (p) {
    case Profile::Khronos:
      return pick(khronos(q, g), lobe);
    case Profile::Threejs:
      return pick(threejs(q, g), lobe);
    case Profile::Filament:
      return pick(filament(q, g), lobe);
    case Profile::Babylon:
      return pick(babylon(q, g), lobe);
    case Profile::Materialx:
      return pick(materialx(q, g), lobe);
    case Profile::Spec:
      break;
  }
  return {0.0, 0.0, 0.0};
}

}  // namespace ref
