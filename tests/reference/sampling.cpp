// Reference densities of the samplers (see sampling.hpp): each from its formula in double, and the
// lobe probabilities of the one-sample mixture restated from docs/sampling.md.
#include "reference/sampling.hpp"

#include <algorithm>
#include <cmath>

namespace ref {

namespace {
double dot3(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 unit(Vec3 v) {
  const double n = std::sqrt(dot3(v, v));
  return {v.x / n, v.y / n, v.z / n};
}
double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
constexpr double kMinAlpha = 1e-3;
}  // namespace

SamplingAlphas samplingAlphas(const brdfcl::MaterialParams& m) {
  const double a = double(m.roughness) * m.roughness, s2 = double(m.anisotropyStrength) * m.anisotropyStrength;
  SamplingAlphas out;
  out.ab = std::max(a, kMinAlpha);
  out.at = std::max(a * (1.0 - s2) + s2, kMinAlpha);
  out.rotation = m.anisotropyRotation;
  out.coat = std::max(double(m.clearcoatRoughness) * m.clearcoatRoughness, kMinAlpha);
  out.sheen = std::max(double(m.sheenRoughness) * m.sheenRoughness, kMinAlpha);
  return out;
}

double pdfCosine(Vec3 L) { return L.z > 0.0 ? L.z / kPi : 0.0; }

double pdfGGXVNDF(Vec3 L, Vec3 V, double at, double ab, double rotation) {
  if (V.z <= 0.0) return 0.0;
  const Vec3 H = unit({L.x + V.x, L.y + V.y, L.z + V.z});
  if (H.z <= 0.0) return 0.0;
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double ht = H.x * c + H.y * s, hb = H.y * c - H.x * s;
  const double vt = V.x * c + V.y * s, vb = V.y * c - V.x * s;
  // Smith G1(V) = 1 / (1 + Lambda(V)), Lambda = (-1 + sqrt(1 + (at^2 vt^2 + ab^2 vb^2) / vz^2)) / 2.
  const double lambda = 0.5 * (-1.0 + std::sqrt(1.0 + (at * at * vt * vt + ab * ab * vb * vb) / (V.z * V.z)));
  const double G1 = 1.0 / (1.0 + lambda);
  return G1 * D_GGX_Anisotropic(H.z, ht, hb, at, ab) / (4.0 * V.z);
}

namespace {
// Eto & Tokuyoshi 2023, eq. 5 and 6: the bounded cap's k for V (in the lobe's frame, V.z > 0).
double boundedK(Vec3 V, double at, double ab) {
  const double a = std::clamp(std::min(at, ab), 0.0, 1.0), s = 1.0 + std::hypot(V.x, V.y);
  return (1.0 - a * a) * s * s / (s * s + a * a * V.z * V.z);
}
Vec3 rotated(Vec3 v, double rotation) {
  const double c = std::cos(rotation), s = std::sin(rotation);
  return {v.x * c + v.y * s, v.y * c - v.x * s, v.z};
}
}  // namespace

double pdfBoundedVNDF(Vec3 L, Vec3 V, double at, double ab, double rotation) {
  if (V.z <= 0.0 || L.z <= 0.0) return 0.0;
  const Vec3 H = unit({L.x + V.x, L.y + V.y, L.z + V.z});
  if (H.z <= 0.0) return 0.0;
  const Vec3 h = rotated(H, rotation), v = rotated(V, rotation);
  const double t = std::sqrt(at * at * v.x * v.x + ab * ab * v.y * v.y + v.z * v.z);
  return D_GGX_Anisotropic(h.z, h.x, h.y, at, ab) / (2.0 * (t + boundedK(v, at, ab) * v.z));
}

double boundedVNDFKeptMass(Vec3 V, double at, double ab, double rotation) {
  const Vec3 v = rotated(V, rotation);
  const Vec3 vh = unit({at * v.x, ab * v.y, v.z});
  const double b = boundedK(v, at, ab) * vh.z;
  // The sampler's construction: a point o uniform on the cap z in [-b, 1], H = unstretch(o + vh),
  // L = reflect(V, H); kept where L.z > 0.
  auto lz = [&](double phi, double z) {
    const double st = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 H = unit({at * (st * std::cos(phi) + vh.x), ab * (st * std::sin(phi) + vh.y), std::max(z + vh.z, 0.0)});
    return 2.0 * dot3(v, H) * H.z - v.z;
  };
  auto keptAlong = [&](double phi) {
    // Kept length of [-b, 1] at this azimuth: a grid, each sign change refined by bisection.
    constexpr int kSteps = 512;
    double kept = 0.0, z0 = -b, f0 = lz(phi, z0);
    for (int i = 1; i <= kSteps; ++i) {
      const double z1 = -b + (1.0 + b) * i / kSteps, f1 = lz(phi, z1);
      if ((f0 > 0.0) == (f1 > 0.0)) {
        if (f0 > 0.0) kept += z1 - z0;
      } else {
        double lo = z0, hi = z1;
        for (int k = 0; k < 60; ++k) {
          const double mid = 0.5 * (lo + hi);
          ((lz(phi, mid) > 0.0) == (f0 > 0.0) ? lo : hi) = mid;
        }
        kept += f0 > 0.0 ? lo - z0 : z1 - lo;
      }
      z0 = z1, f0 = f1;
    }
    return kept;
  };
  return integrate(keptAlong, 0.0, 2.0 * kPi, 1e-8) / (2.0 * kPi * (1.0 + b));
}

double pdfSheen(Vec3 L, Vec3 V, double alpha, brdfcl::SheenDistribution d) {
  const Vec3 H = unit({L.x + V.x, L.y + V.y, L.z + V.z});
  const double VdotH = dot3(V, H);
  if (H.z <= 0.0 || VdotH <= 0.0) return 0.0;
  return sheenD(H.z, alpha, d) * H.z / (4.0 * VdotH);
}

double sheenFacingMass(Vec3 V, double alpha, brdfcl::SheenDistribution d) {
  const double sv = std::sqrt(std::max(0.0, 1.0 - V.z * V.z)), cv = V.z;
  // For N.H = mu, V.H > 0 holds on the azimuths where cos(phi - phi_v) > -mu cv / (sin_h sv).
  auto azimuths = [&](double mu) {
    const double sh = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    if (sh * sv <= 0.0) return mu * cv > 0.0 ? 2.0 * kPi : 0.0;
    return 2.0 * std::acos(std::clamp(-mu * cv / (sh * sv), -1.0, 1.0));
  };
  // D of small alpha lies near mu = 0: the panels follow it.
  double total = 0.0;
  const double edges[] = {0.0, 1e-4, 1e-3, 1e-2, 0.1, 0.5, 1.0};
  for (int k = 0; k + 1 < 7; ++k)
    total += integrate([&](double mu) { return sheenD(mu, alpha, d) * mu * azimuths(mu); }, edges[k], edges[k + 1], 1e-11);
  return total;
}

std::array<double, kLobeCount> lobeProbabilities(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 V) {
  std::array<double, kLobeCount> p{};
  switch (o.lobe) {
    case brdfcl::Lobe::Diffuse: p[kLobeDiffuse] = 1; return p;
    case brdfcl::Lobe::Specular: p[kLobeSpecular] = 1; return p;
    case brdfcl::Lobe::Sheen: p[kLobeSheen] = 1; return p;
    case brdfcl::Lobe::Clearcoat: p[kLobeClearcoat] = 1; return p;
    case brdfcl::Lobe::All: break;
  }
  const SamplingAlphas a = samplingAlphas(m);
  const double nv = std::clamp(V.z, 1e-4, 1.0), fw = std::pow(1.0 - nv, 5.0);
  // A GGX lobe's directional albedo with Schlick's Fresnel, F0 A + B, by Karis's 2014 fit
  // (EnvBRDFApprox) in perceptual roughness r.
  auto ggxAlbedo = [nv](double r, double f0) {
    const double rx = 1.0 - r, ry = 0.0425 - 0.0275 * r, rz = 1.04 - 0.572 * r, rw = 0.022 * r - 0.04;
    const double a004 = std::min(rx * rx, std::exp2(-9.28 * nv)) * rx + ry;
    return f0 * (rz - 1.04 * a004) + (rw + 1.04 * a004);
  };
  const double coatF = m.clearcoat * (0.04 + 0.96 * fw);
  const auto& sc = m.sheenColor;
  const double sheenLum = luminance(sc[0], sc[1], sc[2]);
  const double sheenMax = std::max({sc[0], sc[1], sc[2]});
  // E as the kernels' table gives it (docs/model.md), looked up at sqrt(alpha_s).
  const double e = sheenLum > 0.0 ? tabulatedSheenAlbedo(nv, std::sqrt(a.sheen), o.sheenDistribution, o.sheenVisibility)
                                  : 0.0;
  const double below = (1.0 - coatF) * std::max(1.0 - sheenMax * e, 0.0);
  const auto& b = m.baseColor;
  const double met = m.metallic, baseLum = luminance(b[0], b[1], b[2]);
  const double rs = std::sqrt(std::sqrt(a.at * a.ab));  // anisotropic GGX as the isotropic of alpha_t alpha_b
  const double specF = (1.0 - met) * ggxAlbedo(rs, 0.04) + met * ggxAlbedo(rs, baseLum);
  const double Wd = below * (1.0 - met) * 0.96 * baseLum;
  const double Ws = below * specF, Wsh = sheenLum > 0.0 ? (1.0 - coatF) * sheenLum * e : 0.0;
  const double Wc = coatF * ggxAlbedo(std::sqrt(a.coat), 1.0);
  // Each lobe's breadth (docs/sampling.md).
  const double Ks = 1.0 / (1.0 + a.at * a.ab), Kc = 1.0 / (1.0 + a.coat * a.coat);
  const double m2 = a.sheen * a.sheen, pc = 1.0 / (1.0 + 4.0 * m2);
  const double Ksh = o.sheenDistribution == brdfcl::SheenDistribution::Ashikhmin
                         ? 0.5 * pc + (1.0 - pc) * std::exp(-1.0 / m2)
                         : std::pow(2.0, -(0.5 / a.sheen + 1.0));
  // A GGX lobe's own share: K^4 alone, K^8 where the diffuse lobe outweighs it.
  auto share = [Wd](double K, double W) {
    const double k4 = std::pow(K, 4.0), k8 = k4 * k4;
    return k8 + (k4 - k8) * W / std::max(W + Wd, 1e-30);
  };
  const double Ks4 = share(Ks, Ws), Kc4 = share(Kc, Wc), Ksh4 = std::pow(Ksh, 4.0);
  const double toUniform = m.draftSheen ? 1.0 : 1.0 - nv;
  double w[kLobeCount];
  w[kLobeSpecular] = Ws * Ks4;
  w[kLobeSheen] = Wsh * Ksh4;
  w[kLobeClearcoat] = Wc * Kc4;
  w[kLobeUniform] = Wsh * (1.0 - Ksh4) * toUniform;
  w[kLobeDiffuse] = Wd + Ws * (1.0 - Ks4) + Wsh * (1.0 - Ksh4) * (1.0 - toUniform) + Wc * (1.0 - Kc4) + 0.01;
  const double total = w[0] + w[1] + w[2] + w[3] + w[4];
  for (int t = 0; t < kLobeCount; ++t) p[t] = w[t] / total;
  return p;
}

double lobePdf(int t, const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V) {
  const SamplingAlphas a = samplingAlphas(m);
  switch (t) {
    case kLobeDiffuse: return pdfCosine(L);
    case kLobeSpecular: return pdfBoundedVNDF(L, V, a.at, a.ab, a.rotation);
    case kLobeSheen: return pdfSheen(L, V, a.sheen, o.sheenDistribution);
    case kLobeUniform: return L.z > 0.0 ? 1.0 / (2.0 * kPi) : 0.0;
    default: return pdfBoundedVNDF(L, V, a.coat, a.coat, 0.0);
  }
}

double mixturePdf(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V) {
  if (L.z <= 0.0 || V.z <= 0.0) return 0.0;
  const auto p = lobeProbabilities(m, o, V);
  double pdf = 0.0;
  for (int t = 0; t < kLobeCount; ++t)
    if (p[t] > 0.0) pdf += p[t] * lobePdf(t, m, o, L, V);
  return pdf;
}

}  // namespace ref
