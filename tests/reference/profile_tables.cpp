// The tables and fits the engine profiles of the reference read (see profiles.hpp): three.js's
// DFG data, the Sample Renderer's sheen albedo texels, Babylon's environment BRDF texture and
// the MaterialX and three.js albedo fits, each sampled as the engine samples it.
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "reference/profiles.hpp"

namespace ref {

// ============================================================================================
// Tables and fits
// ============================================================================================

namespace {

// The data only (the .inc is numbers and comments): row j = NdotV (j + 0.5)/16, 16 texels
// i = roughness (i + 0.5)/16 each, each texel (A, B) as half-float bits.
constexpr std::uint16_t kThreejsDfgBits[16 * 16 * 2] = {
#include "../../host/src/model/threejs_dfg_lut.inc"
};

// One axis of a GPU's bilinear fetch over n texels: coordinate x in texel units measured from
// texel 0's centre, the two neighbours i0, i1 clamped to the edge (so beyond the outer centres the
// edge texel is returned), w the weight of i1.
void clampedTaps(double u, int n, int& i0, int& i1, double& w) {
  const double x = u * n - 0.5;
  const double fl = std::floor(x);
  w = x - fl;
  i0 = std::clamp(static_cast<int>(fl), 0, n - 1);
  i1 = std::clamp(static_cast<int>(fl) + 1, 0, n - 1);
}

// The bilinear blend of the four texels texel(i, j) that clampedTaps picked on each axis.
template <class Texel>
double bilinear(const Texel& texel, int i0, int i1, double wu, int j0, int j1, double wv) {
  const double bottom = texel(i0, j0) * (1.0 - wu) + texel(i1, j0) * wu;
  const double top = texel(i0, j1) * (1.0 - wu) + texel(i1, j1) * wu;
  return bottom * (1.0 - wv) + top * wv;
}

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
  // A GPU's bilinear fetch (clampedTaps on each axis) of the 16 x 16 texels.
  int i0, i1, j0, j1;
  double wu, wv;
  clampedTaps(roughness, 16, i0, i1, wu);
  clampedTaps(NdotV, 16, j0, j1, wv);
  auto texel = [](int i, int j, int ch) {
    return halfToDouble(kThreejsDfgBits[(j * 16 + i) * 2 + ch]);
  };
  std::array<double, 2> out{};
  for (int ch = 0; ch < 2; ++ch)
    out[ch] = bilinear([&](int i, int j) { return texel(i, j, ch); }, i0, i1, wu, j0, j1, wv);
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
  int i0, i1, j0, j1;
  double wu, wv;
  clampedTaps(NdotV, kKhronosN, i0, i1, wu);
  clampedTaps(sheenRoughness, kKhronosN, j0, j1, wv);
  const auto& t = khronosTexels();
  auto texel = [&](int i, int j) { return t[std::size_t(j) * kKhronosN + std::size_t(i)] / 255.0; };
  return bilinear(texel, i0, i1, wu, j0, j1, wv);
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
  int i0, i1, j0, j1;
  double wu, wv;
  clampedTaps(NdotV, kBabylonN, i0, i1, wu);
  clampedTaps(roughness, kBabylonN, j0, j1, wv);
  const auto& t = babylonTexels();
  auto texel = [&](int i, int j, int ch) { return t[(std::size_t(j) * kBabylonN + std::size_t(i)) * 3 + std::size_t(ch)]; };
  std::array<double, 3> out{};
  for (int ch = 0; ch < 3; ++ch)
    out[ch] = bilinear([&](int i, int j) { return texel(i, j, ch); }, i0, i1, wu, j0, j1, wv);
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

}  // namespace ref
