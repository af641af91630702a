// Helpers of the tests of the reference (test_reference.cpp, test_reference_albedo.cpp): directions,
// random materials, an own Gauss-Legendre rule and a half-vector quadrature of the sheen albedo.
// Internal to each test file (anonymous namespace), as they were when one file held them.
#pragma once
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "reference/reference.hpp"

namespace {

using brdfcl::EvalOptions;
using brdfcl::Lobe;
using brdfcl::MaterialParams;
using brdfcl::SheenDistribution;
using brdfcl::SheenScaling;
using brdfcl::SheenVisibility;
using ref::kPi;
using ref::Rgb;
using ref::Vec3;

constexpr SheenDistribution kDists[2] = {SheenDistribution::Charlie, SheenDistribution::Ashikhmin};
constexpr SheenVisibility kVises[2] = {SheenVisibility::Charlie, SheenVisibility::Ashikhmin};

Vec3 dir(double cosTheta, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

Vec3 rotateZ(Vec3 v, double a) {
  return {v.x * std::cos(a) - v.y * std::sin(a), v.x * std::sin(a) + v.y * std::cos(a), v.z};
}

double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Vec3 normalized(Vec3 v) {
  const double l = std::sqrt(dot(v, v));
  return {v.x / l, v.y / l, v.z / l};
}

// Random material parameters come as floats from a function that is not inlined: with GCC 12.2
// at -O2, `arr = {uf(rng), ...}` followed by double(arr[k]) in the same function was seen
// to yield the unrounded double (the narrowing vanished), so expected values computed here
// disagreed with the float the reference reads.
[[gnu::noinline]] float uf(std::mt19937_64& rng, double lo = 0.0, double hi = 1.0) {
  std::uniform_real_distribution<double> u(lo, hi);
  return static_cast<float>(u(rng));
}

// Random direction in the upper hemisphere with cos theta in [lo, 1].
Vec3 randomDir(std::mt19937_64& rng, double lo = 0.01) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  return dir(lo + (1.0 - lo) * u(rng), 2.0 * kPi * u(rng));
}

void expectRgbNear(const Rgb& a, const Rgb& b, double rel, double abs, const char* what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c], b[c], abs + rel * std::max(std::abs(a[c]), std::abs(b[c]))) << what << " channel " << c;
}

// A varied set of materials exercising every layer (no clearcoat: used where symmetry matters).
std::vector<MaterialParams> baseAndSheenMaterials() {
  std::vector<MaterialParams> ms;
  MaterialParams m;
  ms.push_back(m);  // defaults: white metal, roughness 1
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  m.baseColor = {0.8f, 0.3f, 0.1f};
  ms.push_back(m);  // dielectric
  m.metallic = 0.4f;
  m.roughness = 0.05f;
  ms.push_back(m);  // very smooth mixture
  m.roughness = 0.35f;
  m.anisotropyStrength = 0.7f;
  m.anisotropyRotation = 0.9f;
  ms.push_back(m);  // anisotropic
  m.anisotropyStrength = 0.0f;
  m.sheenColor = {0.9f, 0.5f, 0.2f};
  m.sheenRoughness = 0.3f;
  ms.push_back(m);  // ratified sheen
  m.sheenRoughness = 0.05f;
  ms.push_back(m);
  m.sheenRoughness = 1.0f;
  m.anisotropyStrength = 0.4f;
  ms.push_back(m);
  MaterialParams d;
  d.draftSheen = true;
  d.metallic = 0.2f;
  d.roughness = 0.6f;
  d.baseColor = {0.2f, 0.5f, 0.7f};
  d.draftColor = {1.0f, 0.6f, 0.3f};
  d.draftIntensity = 0.8f;
  ms.push_back(d);  // draft sheen
  return ms;
}

// ---- Own Gauss-Legendre (independent of ref::integrate) for the half-vector quadrature ----
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), pp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      pp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / pp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2.0 / ((1.0 - z * z) * pp * pp);
  }
}

// E(mu, r) = int D(H) V(L, V) (N.L) 4 (V.H) dw_H over the half vectors whose reflected L is above
// the horizon: theta_h <= pi/4 + theta_v/2, |phi_h| <= acos(mu (1 - 2 cos^2) / (2 sin_v sin cos)).
// Composite Gauss-Legendre with square-root-resolving maps at both range ends. A different
// parameterisation and rule from the reference's L-space adaptive integration.
double halfVectorAlbedo(double mu, double r, SheenDistribution d, SheenVisibility v) {
  const int panels = 32, n = 10;
  std::vector<double> gx, gw, t, w;
  gaussLegendre(n, gx, gw);
  for (int p = 0; p < panels; ++p)
    for (int i = 0; i < n; ++i) {
      t.push_back((p + 0.5 + 0.5 * gx[i]) / panels);
      w.push_back(0.5 * gw[i] / panels);
    }
  const double alpha = r * r, sv = std::sqrt(1.0 - mu * mu);
  const double thetaMax = kPi / 4.0 + std::acos(mu) / 2.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double th = thetaMax * t[i] * (2.0 - t[i]), dth = 2.0 * thetaMax * (1.0 - t[i]) * w[i];
    const double st = std::sin(th), ct = std::cos(th);
    const double q = sv > 0.0 ? (mu - 2.0 * mu * ct * ct) / (2.0 * sv * st * ct) : -2.0;
    const double phiMax = q <= -1.0 ? kPi : (q >= 1.0 ? 0.0 : std::acos(q));
    double inner = 0.0;
    for (std::size_t j = 0; j < t.size(); ++j) {
      const double ph = phiMax * t[j] * (2.0 - t[j]), dph = 2.0 * phiMax * (1.0 - t[j]) * w[j];
      const double VdotH = sv * st * std::cos(ph) + mu * ct;
      const double Lz = 2.0 * VdotH * ct - mu;
      if (Lz <= 0.0) continue;
      inner += ref::sheenD(ct, alpha, d) * ref::sheenV(Lz, mu, alpha, v) * Lz * 4.0 * VdotH * dph;
    }
    sum += 2.0 * inner * st * dth;
  }
  return sum;
}

// int over the hemisphere of D(N.H) (N.H) dw_H, in t = N.H; split at tSplit to help the adaptive
// rule find narrow peaks near t = 0 (sheen) or t = 1 (GGX).
template <class D>
double projectedArea(D d, double tSplit) {
  auto f = [&](double t) { return d(t) * t * 2.0 * kPi; };
  return ref::integrate(f, 0.0, tSplit, 1e-12) + ref::integrate(f, tSplit, 1.0, 1e-12);
}

}  // namespace
