// The sheen directional albedo E(mu, r) of the reference (see reference.hpp): nested adaptive
// Gauss-Kronrod integrals and the tensor Chebyshev tables built from them, with the table
// lookup as the layered BRDF defines it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>
#include <tuple>
#include <vector>

#include "reference/quadrature.hpp"
#include "reference/reference.hpp"

namespace ref {

using brdfcl::SheenDistribution;
using brdfcl::SheenVisibility;

// ============================================================================================
// Sheen directional albedo E(mu, r)
// ============================================================================================
//
// E = int_0^1 dx x V(x, mu) int_0^{2pi} dphi D(N.H(x, phi))  with x = N.L, phi the azimuth of L
// from V's. Both sheen visibilities depend on N.L and N.V only, so the azimuthal integral holds
// D alone. Structure of the integrand, which decides the splits:
//  - Charlie V's Lambda switches branch at N.L = 0.5 (continuous with its first derivative only),
//    so the x integral is split there;
//  - Lambda contains x^c (c ~ 0.2) and the D peak sits near x ~ mu for grazing views, so
//    [0, 0.5] is integrated in s = ln x (smooth in s), cut at x = 1e-14 where the neglected
//    part is < 1e-14 * max(x V I) < 1e-11;
//  - the azimuthal integrand is even and 2pi-periodic: 2 * int_0^pi.
//  - x = mu: see below.

namespace {

// E for K visibilities at once (they share the azimuthal integral of D); K = 2 builds the two
// tables of one distribution for the price of one.
template <std::size_t K>
VecK<K> albedoIntegrals(double mu, double r, SheenDistribution dist,
                        const std::array<SheenVisibility, K>& vis, double tol) {
  const double alpha = r * r;
  const double sv = std::sqrt(std::max(0.0, 1.0 - mu * mu));  // V = (sv, 0, mu)
  // The azimuthal integral is weighted by w = x V (times x in ln x), so its absolute tolerance is
  // 0.1 tol / w: the outer integrand is then accurate to 0.1 tol everywhere, and no work is spent
  // where w is negligible (Charlie V at small x).
  auto azimuthal = [&](double x, double weight) {
    const double sx = std::sqrt(std::max(0.0, 1.0 - x * x));
    auto dOfPhi = [&](double phi) {
      const double hx = sx * std::cos(phi) + sv, hy = sx * std::sin(phi), hz = x + mu;
      const double NdotH = hz / std::sqrt(hx * hx + hy * hy + hz * hz);
      return sheenD(NdotH, alpha, dist);
    };
    const double innerTol = 0.1 * tol / std::max(weight, 1e-300);
    return 2.0 * qag1(dOfPhi, 0.0, kPi, 0.5 * innerTol);
  };
  auto weighted = [&](double x, double jacobian) {
    VecK<K> w{};
    double wMax = 0.0;
    for (std::size_t k = 0; k < K; ++k) {
      w[k] = x * sheenV(x, mu, alpha, vis[k]) * jacobian;
      wMax = std::max(wMax, std::abs(w[k]));
    }
    const double I = azimuthal(x, wMax);
    for (std::size_t k = 0; k < K; ++k) w[k] *= I;
    return w;
  };
  auto integrand = [&](double x) { return weighted(x, 1.0); };
  auto inLog = [&](double s) {
    const double x = std::exp(s);
    return weighted(x, x);
  };
  // x = mu is where H = N becomes reachable (at phi = pi); sin^(1/alpha) theta_h is not smooth
  // there for non-even 1/alpha, so the x integral is split at mu as well.
  VecK<K> sum{};
  auto add = [&](const VecK<K>& part) {
    for (std::size_t k = 0; k < K; ++k) sum[k] += part[k];
  };
  if (mu < 0.5) {
    add(qag<K>(inLog, std::log(1e-14), std::log(mu), 0.25 * tol));
    add(qag<K>(inLog, std::log(mu), std::log(0.5), 0.25 * tol));
    add(qag<K>(integrand, 0.5, 1.0, 0.5 * tol));
  } else {
    add(qag<K>(inLog, std::log(1e-14), std::log(0.5), 0.5 * tol));
    if (mu > 0.5) add(qag<K>(integrand, 0.5, mu, 0.25 * tol));
    if (mu < 1.0) add(qag<K>(integrand, mu, 1.0, 0.25 * tol));
  }
  return sum;
}

double albedoIntegralImpl(double mu, double r, SheenDistribution dist, SheenVisibility vis,
                          double tol) {
  return albedoIntegrals<1>(mu, r, dist, {vis}, tol)[0];
}

// ---- Table: tensor Chebyshev interpolation in (mu, r) ----
// E is smooth in (mu, r) except where Charlie V's Lambda(mu) is not:
//  - mu^c (c ~ 0.17-0.2) as mu -> 0: smooth in t = ln mu, so the piece [0.01, 0.5] uses ln mu;
//  - a second-derivative jump at mu = 0.5 (branch switch): pieces meet there;
//  - (1 - mu)^c as mu -> 1 (the mirrored branch uses l(1 - mu)): its effect on E is ~1e-5 within
//    1e-5 of mu = 1, enough to ruin a polynomial fit in mu, so the piece [0.5, 1] uses
//    z = (2 (1 - mu))^c(alpha), in which Lambda is analytic (only mu = 1 - z^(1/c)/2 remains, a
//    z^5 kind of term at z = 0, harmless).
// r is mapped by u = ln r on [0.05, 1] because the sheen features scale with alpha_s = r^2.
// Node counts were chosen from the coefficient decay and checked against the direct integral
// at random points (1e-6 budget; see "Accuracy and cost" at the end of this file).
enum class MuMap { LogMu, OneMinusMuPow };

struct ChebPiece {
  MuMap map = MuMap::LogMu;
  int nx = 0, ny = 0;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  std::vector<double> coef;  // coef[i * ny + j] multiplies T_i(x) T_j(y)
};

constexpr double kMuSplit = 0.5;
constexpr int kNxLow = 28, kNxHigh = 24, kNy = 36;

// Exponent c of the Lambda fit (000, l(x, alpha_g)), reused as the mapping exponent near mu = 1.
double lambdaFitExponent(double alphaG) {
  const double t = (1.0 - alphaG) * (1.0 - alphaG);
  return 0.19823 * (1.0 - t) + 0.16801 * t;
}

double muToX(MuMap map, double mu, double alphaG) {
  if (map == MuMap::LogMu) return std::log(mu);
  return std::pow((1.0 - mu) / (1.0 - kMuSplit), lambdaFitExponent(alphaG));
}

double xToMu(MuMap map, double x, double alphaG) {
  if (map == MuMap::LogMu) return std::exp(x);
  return 1.0 - (1.0 - kMuSplit) * std::pow(x, 1.0 / lambdaFitExponent(alphaG));
}

double chebNode(int j, int n, double lo, double hi) {
  const double xi = std::cos(kPi * j / (n - 1));
  return 0.5 * (lo + hi) + 0.5 * (hi - lo) * xi;
}

// Values at Chebyshev-Lobatto nodes -> Chebyshev coefficients (type-I DCT, O(n^2) is fine here).
std::vector<double> chebCoefficients(const std::vector<double>& f) {
  const int n = static_cast<int>(f.size());
  std::vector<double> c(n);
  for (int k = 0; k < n; ++k) {
    double s = 0.0;
    for (int j = 0; j < n; ++j) {
      const double w = (j == 0 || j == n - 1) ? 0.5 : 1.0;
      s += w * f[j] * std::cos(kPi * j * k / (n - 1));
    }
    c[k] = s * 2.0 / (n - 1);
  }
  c[0] *= 0.5;
  c[n - 1] *= 0.5;
  return c;
}

// sum_ij c_ij T_i(x) T_j(y) with the T values from their recurrence (bounded by 1, so direct
// summation is as stable as Clenshaw) and the i loop outside: one multiply-add per coefficient,
// contiguous and independent across j, so it vectorises even at -O2.
double evalPiece(const ChebPiece& p, double x, double y) {
  const double xs = (2.0 * x - p.x0 - p.x1) / (p.x1 - p.x0);
  const double ys = (2.0 * y - p.y0 - p.y1) / (p.y1 - p.y0);
  double acc[kNy] = {};
  const double* coef = p.coef.data();
  double tPrev = 1.0, t = xs;  // T_0(xs), T_1(xs)
  for (int j = 0; j < kNy; ++j) acc[j] = coef[j];
  for (int i = 1; i < p.nx; ++i) {
    const double* c = coef + static_cast<std::size_t>(i) * kNy;
    for (int j = 0; j < kNy; ++j) acc[j] += c[j] * t;
    const double tNext = 2.0 * xs * t - tPrev;
    tPrev = t;
    t = tNext;
  }
  double sum = acc[0];
  tPrev = 1.0;
  t = ys;
  for (int j = 1; j < kNy; ++j) {
    sum += acc[j] * t;
    const double tNext = 2.0 * ys * t - tPrev;
    tPrev = t;
    t = tNext;
  }
  return sum;
}

ChebPiece fitPiece(MuMap map, int nx, int ny, double x0, double x1, double y0, double y1,
                   const std::vector<double>& values) {
  ChebPiece p;
  p.map = map;
  p.nx = nx;
  p.ny = ny;
  p.x0 = x0;
  p.x1 = x1;
  p.y0 = y0;
  p.y1 = y1;
  // 2-D transform: along y for each row, then along x for each column.
  std::vector<double> tmp(values.size());
  for (int i = 0; i < nx; ++i) {
    std::vector<double> row(values.begin() + static_cast<std::ptrdiff_t>(i) * ny,
                            values.begin() + static_cast<std::ptrdiff_t>(i + 1) * ny);
    const auto c = chebCoefficients(row);
    std::copy(c.begin(), c.end(), tmp.begin() + static_cast<std::ptrdiff_t>(i) * ny);
  }
  p.coef.assign(values.size(), 0.0);
  for (int j = 0; j < ny; ++j) {
    std::vector<double> col(nx);
    for (int i = 0; i < nx; ++i) col[i] = tmp[static_cast<std::size_t>(i) * ny + j];
    const auto c = chebCoefficients(col);
    for (int i = 0; i < nx; ++i) p.coef[static_cast<std::size_t>(i) * ny + j] = c[i];
  }
  return p;
}

// One mu piece of the tables of distribution d for both visibilities (Charlie, Ashikhmin).
std::array<ChebPiece, 2> buildPieces(MuMap map, int nx, SheenDistribution d, double tol) {
  const int ny = kNy;
  double x0, x1;
  if (map == MuMap::LogMu) {
    x0 = std::log(kAlbedoMuMin);
    x1 = std::log(kMuSplit);
  } else {
    x0 = 0.0;  // mu = 1
    x1 = 1.0;  // mu = 0.5
  }
  const double y0 = std::log(kAlbedoRMin), y1 = 0.0;
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  std::vector<double> valuesC(n), valuesA(n);
  const unsigned nThreads = std::max(1u, std::min(16u, std::thread::hardware_concurrency()));
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < nThreads; ++t) {
    workers.emplace_back([&, t] {
      for (std::size_t idx = t; idx < n; idx += nThreads) {
        const int i = static_cast<int>(idx) / ny, j = static_cast<int>(idx) % ny;
        const double r = std::exp(chebNode(j, ny, y0, y1));
        const double mu = xToMu(map, chebNode(i, nx, x0, x1), r * r);
        const auto e = albedoIntegrals<2>(mu, r, d, {SheenVisibility::Charlie, SheenVisibility::Ashikhmin}, tol);
        valuesC[idx] = e[0];
        valuesA[idx] = e[1];
      }
    });
  }
  for (auto& w : workers) w.join();
  return {fitPiece(map, nx, ny, x0, x1, y0, y1, valuesC), fitPiece(map, nx, ny, x0, x1, y0, y1, valuesA)};
}

struct AlbedoTable {
  ChebPiece low, high;  // mu in [0.01, 0.5] and [0.5, 1]
};

int comboIndex(SheenDistribution d, SheenVisibility v) {
  return (d == SheenDistribution::Charlie ? 0 : 2) + (v == SheenVisibility::Charlie ? 0 : 1);
}

// Tables are built per distribution, both visibilities at once (see albedoIntegrals).
AlbedoTable gTables[4];
std::once_flag gOnce[2];

// Node values are integrated to 1e-8 (true errors observed < 3e-10), far below the 1e-6 budget.
constexpr double kTableTol = 1e-8;

const AlbedoTable& table(SheenDistribution d, SheenVisibility v, double* builtSeconds = nullptr) {
  const int k = comboIndex(d, v);
  std::call_once(gOnce[d == SheenDistribution::Charlie ? 0 : 1], [&] {
    const auto t0 = std::chrono::steady_clock::now();
    const auto low = buildPieces(MuMap::LogMu, kNxLow, d, kTableTol);
    const auto high = buildPieces(MuMap::OneMinusMuPow, kNxHigh, d, kTableTol);
    const int kC = comboIndex(d, SheenVisibility::Charlie), kA = comboIndex(d, SheenVisibility::Ashikhmin);
    gTables[kC] = {low[0], high[0]};
    gTables[kA] = {low[1], high[1]};
    if (builtSeconds)
      *builtSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
  return gTables[k];
}

}  // namespace

double sheenAlbedoIntegral(double mu, double sheenRoughness, SheenDistribution d,
                           SheenVisibility v, double tol) {
  return albedoIntegralImpl(mu, sheenRoughness, d, v, tol);
}

double sheenAlbedo(double mu, double sheenRoughness, SheenDistribution d, SheenVisibility v) {
  // A normalised N.V can exceed 1 by an ulp; (1 - mu)^c would then be NaN.
  if (mu > 1.0 && mu < 1.0 + 1e-12) mu = 1.0;
  if (!(mu >= kAlbedoMuMin && mu <= 1.0 && sheenRoughness >= kAlbedoRMin && sheenRoughness <= 1.0)) {
    // Outside the table: integrate. Quadratures over L (directionalAlbedo) ask for the same
    // E(N.L) at every azimuth of one N.L (up to the rounding of normalize), so the last answer
    // is remembered per thread and reused within a relative 1e-12 of mu (|dE/dmu| * 1e-12 mu is
    // far below the integration error).
    struct Last {
      double mu = -1.0, r = -1.0;
      int combo = -1;
      double value = 0.0;
    };
    thread_local Last last;
    const int combo = comboIndex(d, v);
    if (!(std::abs(last.mu - mu) <= 1e-12 * mu) || last.r != sheenRoughness || last.combo != combo)
      last = {mu, sheenRoughness, combo, albedoIntegralImpl(mu, sheenRoughness, d, v, kTableTol)};
    return last.value;
  }
  const AlbedoTable& t = table(d, v);
  const double u = std::log(sheenRoughness);
  const ChebPiece& p = mu < kMuSplit ? t.low : t.high;
  return evalPiece(p, muToX(p.map, mu, sheenRoughness * sheenRoughness), u);
}

double tabulatedSheenAlbedo(double mu, double sheenRoughness, SheenDistribution d, SheenVisibility v) {
  // docs/model.md, "Sheen, ratified": 320 x 320 nodes at mu = s^2, r = t^2, bilinear in (s, t);
  // the nodes' values are this reference's own E, remembered as they are asked for.
  constexpr int kSize = 320;
  static std::mutex mutex;
  static std::map<std::tuple<int, int, int>, double> nodes;
  auto node = [&](int i, int j) {
    const int combo = comboIndex(d, v);
    std::lock_guard<std::mutex> lock(mutex);
    const auto key = std::make_tuple(combo, i, j);
    auto it = nodes.find(key);
    if (it != nodes.end()) return it->second;
    const double s = double(i) / (kSize - 1), t = double(j) / (kSize - 1);
    return nodes[key] = sheenAlbedo(s * s, t * t, d, v);
  };
  const double x = std::sqrt(std::clamp(mu, 0.0, 1.0)) * (kSize - 1);
  const double y = std::sqrt(std::clamp(sheenRoughness, 0.0, 1.0)) * (kSize - 1);
  const int x0 = std::min(int(x), kSize - 2), y0 = std::min(int(y), kSize - 2);
  const double fx = x - x0, fy = y - y0;
  const double top = node(x0, y0) + (node(x0 + 1, y0) - node(x0, y0)) * fx;
  const double bottom = node(x0, y0 + 1) + (node(x0 + 1, y0 + 1) - node(x0, y0 + 1)) * fx;
  return top + (bottom - top) * fy;
}

double precomputeSheenAlbedo(SheenDistribution d, SheenVisibility v) {
  double seconds = 0.0;
  table(d, v, &seconds);
  return seconds;
}

// ============================================================================================
// Accuracy and cost of E (measured on a shared 2-core x86-64 VM, g++ 12 -O2)
// ============================================================================================
// - Integral: tolerance 1e-8 / 1e-10 / 1e-13 runs agree to < 3e-10 / < 1e-11 over mu in
//   {0.01 .. 1} x r in {0.05 .. 1}, all four D x V; an independent half-vector composite
//   Gauss-Legendre quadrature (test_reference.cpp) agrees to < 5e-8 and converges towards it;
//   closed forms at mu = 1 (Charlie D x Ashikhmin V with 1/alpha even, Ashikhmin x Ashikhmin)
//   are met to 1e-10. ~1-10 ms per value.
// - Table (28 + 24 nodes in mu, 36 in r per distribution): max |table - integral| < 1e-7 over
//   2000 random points (log- and linearly distributed, dense near mu = 1) and the test grid.
//   Fewer nodes (22 + 20, 30) reach ~9e-7, hence these counts. Lookup ~0.3-0.6 us.
// - Build: ~1.3-1.7 s of CPU per distribution (both visibilities), split over all cores.

}  // namespace ref
