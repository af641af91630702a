// Independent double-precision reference of the brdfcl BRDF stack (see reference.hpp): the terms
// of seeds 000-004 and glTF 2.0 Appendix B, the layered BRDF with its lobe split, and the
// directional albedo; the sheen albedo E is in sheen_albedo.cpp.
#include "reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "reference/quadrature.hpp"

namespace ref {

using brdfcl::SheenDistribution;
using brdfcl::SheenVisibility;

// ============================================================================================
// Terms
// ============================================================================================

// glTF 2.0 Appendix B, "Specular BRDF" (microfacet distribution): not a seed file, the core spec.
double D_GGX(double NdotH, double alpha) {
  if (NdotH <= 0.0) return 0.0;  // chi+(N.H): back-facing microfacets do not exist
  const double a2 = alpha * alpha;
  const double d = NdotH * NdotH * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

// glTF 2.0 Appendix B, "Specular BRDF" (height-correlated Smith joint masking-shadowing, V form).
double V_SmithGGXCorrelated(double NdotL, double NdotV, double alpha) {
  const double a2 = alpha * alpha;
  const double ggxv = NdotL * std::sqrt(NdotV * NdotV * (1.0 - a2) + a2);
  const double ggxl = NdotV * std::sqrt(NdotL * NdotL * (1.0 - a2) + a2);
  return 0.5 / (ggxv + ggxl);
}

// the KHR_materials_anisotropy specification, "Anisotropy": D(h) = 1/(pi at ab ((h.t)^2/at^2 + (h.b)^2/ab^2 + (h.n)^2)^2).
// Written as the normative formula rather than the sample code's rescaled form (same value).
double D_GGX_Anisotropic(double NdotH, double TdotH, double BdotH, double at, double ab) {
  const double q = TdotH * TdotH / (at * at) + BdotH * BdotH / (ab * ab) + NdotH * NdotH;
  return 1.0 / (kPi * at * ab * q * q);
}

// the KHR_materials_anisotropy specification, "Implementation / Individual lights", V_GGX_anisotropic.
// The sample code clamps v to [0, 1]; the reference does not (the brief's model is unclamped).
double V_GGX_Anisotropic(double NdotL, double NdotV, double TdotV, double BdotV, double TdotL,
                         double BdotL, double at, double ab) {
  const double ggxv = NdotL * std::sqrt(at * TdotV * at * TdotV + ab * BdotV * ab * BdotV + NdotV * NdotV);
  const double ggxl = NdotV * std::sqrt(at * TdotL * at * TdotL + ab * BdotL * ab * BdotL + NdotL * NdotL);
  return 0.5 / (ggxv + ggxl);
}

// the KHR_materials_sheen specification, "Sheen distribution" (also the experimental draft, and "CharlieD" in Narkowicz, "Cloth Shading").
// pow(sin2h, 1/(2 alpha)) is sin^(1/alpha) theta_h, the Conty-Kulla exponentiated sinusoid.
double D_Charlie(double NdotH, double alpha) {
  const double invR = 1.0 / alpha;
  const double cos2h = NdotH * NdotH;
  const double sin2h = 1.0 - cos2h;
  return (2.0 + invR) * std::pow(sin2h, invR * 0.5) / (2.0 * kPi);
}

// Narkowicz, "Cloth Shading", "AshikhminD": inverted Gaussian, called with roughness := alpha.
double D_Ashikhmin(double NdotH, double alpha) {
  const double m2 = alpha * alpha;
  const double cos2h = NdotH * NdotH;
  const double sin2h = 1.0 - cos2h;
  // At H = N the article's expression is 0/0; its limit is the constant term alone.
  if (sin2h <= 0.0) return 1.0 / (kPi * (1.0 + 4.0 * m2));
  const double sin4h = sin2h * sin2h;
  return (sin4h + 4.0 * std::exp(-cos2h / (sin2h * m2))) / (kPi * (1.0 + 4.0 * m2) * sin4h);
}

namespace {
// the KHR_materials_sheen specification, "Sheen visibility", l(x, alpha_g): the Conty-Kulla fit of the
// sheen Lambda, its five constants mixed by (1 - alpha_g)^2.
double sheenL(double x, double alphaG) {
  const double oneMinusAlphaSq = (1.0 - alphaG) * (1.0 - alphaG);
  auto mix = [&](double a, double b) { return a * (1.0 - oneMinusAlphaSq) + b * oneMinusAlphaSq; };
  const double a = mix(21.5473, 25.3245);
  const double b = mix(3.82987, 3.32435);
  const double c = mix(0.19823, 0.16801);
  const double d = mix(-1.97760, -1.27393);
  const double e = mix(-4.32054, -4.85967);
  return a / (1.0 + b * std::pow(x, c)) + d * x + e;
}

// the KHR_materials_sheen specification, "Sheen visibility", lambda_sheen: the fit is only trusted below
// cos = 0.5 and mirrored (in log space) about 0.5 above it.
double lambdaSheen(double cosTheta, double alphaG) {
  return std::abs(cosTheta) < 0.5
             ? std::exp(sheenL(cosTheta, alphaG))
             : std::exp(2.0 * sheenL(0.5, alphaG) - sheenL(1.0 - cosTheta, alphaG));
}
}  // namespace

// the KHR_materials_sheen specification, "Sheen visibility": 1/((1 + Lambda(V) + Lambda(L)) 4 N.V N.L),
// a height-correlated Smith form of the fitted Lambda.
double V_Charlie(double NdotL, double NdotV, double alpha) {
  return 1.0 / ((1.0 + lambdaSheen(NdotV, alpha) + lambdaSheen(NdotL, alpha)) *
                (4.0 * NdotV * NdotL));
}

// the KHR_materials_sheen specification, "Sheen visibility" (simpler alternative); same as 003 AshikhminV and
// the experimental draft's sheenVisibility.
double V_Ashikhmin(double NdotL, double NdotV) {
  return 1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV));
}

// glTF 2.0 Appendix B, "Fresnel": Schlick with f90 = 1, on |V.H| as the Appendix writes it.
double F_Schlick(double f0, double VdotH) {
  return f0 + (1.0 - f0) * std::pow(1.0 - std::abs(VdotH), 5.0);
}

// the KHR_materials_sheen specification "Sheen distribution" / 003 "AshikhminD": the option's choice of D.
double sheenD(double NdotH, double alpha, SheenDistribution d) {
  return d == SheenDistribution::Charlie ? D_Charlie(NdotH, alpha) : D_Ashikhmin(NdotH, alpha);
}

// the KHR_materials_sheen specification "Sheen visibility": the option's choice of V.
double sheenV(double NdotL, double NdotV, double alpha, SheenVisibility v) {
  return v == SheenVisibility::Charlie ? V_Charlie(NdotL, NdotV, alpha) : V_Ashikhmin(NdotL, NdotV);
}

// ============================================================================================
// The layered BRDF
// ============================================================================================

namespace {

Vec3 normalize(Vec3 v) {
  const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / len, v.y / len, v.z / len};
}

double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

double max3(const brdfcl::Rgb& c) {
  return std::max(std::max(static_cast<double>(c[0]), static_cast<double>(c[1])), static_cast<double>(c[2]));
}

// The four additive parts of the layered result; brdf() returns one of them or their sum.
struct Lobes {
  Rgb diffuse{}, specular{}, sheen{}, clearcoat{};
};

Lobes evalLobes(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V,
                bool tabulated = false) {
  auto sheenAlbedo = [tabulated](double mu, double r, SheenDistribution d, SheenVisibility v) {
    return tabulated ? tabulatedSheenAlbedo(mu, r, d, v) : ref::sheenAlbedo(mu, r, d, v);
  };
  Lobes out;
  L = normalize(L);
  V = normalize(V);
  const Vec3 N{0.0, 0.0, 1.0};
  const double NdotL = dot(N, L), NdotV = dot(N, V);
  if (NdotL <= 0.0 || NdotV <= 0.0) return out;
  const Vec3 H = normalize({L.x + V.x, L.y + V.y, L.z + V.z});
  const double NdotH = dot(N, H), VdotH = dot(V, H);

  const double metallic = m.metallic;
  const double roughness = m.roughness;
  const double alpha = roughness * roughness;
  const Rgb baseColor{m.baseColor[0], m.baseColor[1], m.baseColor[2]};

  // glTF 2.0 Appendix B: the specular microfacet term D * V, shared by dielectric and metal.
  // 002 "Anisotropy" replaces it when the extension has a non-zero strength: alpha grows along
  // T' = (cos r, sin r, 0) to mix(alpha, 1, strength^2), B' = N x T' keeps alpha.
  double spec;
  if (m.anisotropyStrength != 0.0f) {
    const double strength = m.anisotropyStrength;
    const double rot = m.anisotropyRotation;
    const Vec3 T{std::cos(rot), std::sin(rot), 0.0};
    const Vec3 B{-std::sin(rot), std::cos(rot), 0.0};  // N x T
    const double at = alpha * (1.0 - strength * strength) + 1.0 * strength * strength;
    const double ab = alpha;
    spec = D_GGX_Anisotropic(NdotH, dot(T, H), dot(B, H), at, ab) *
           V_GGX_Anisotropic(NdotL, NdotV, dot(T, V), dot(B, V), dot(T, L), dot(B, L), at, ab);
  } else {
    spec = D_GGX(NdotH, alpha) * V_SmithGGXCorrelated(NdotL, NdotV, alpha);
  }

  // glTF 2.0 Appendix B: dielectric_brdf = mix(diffuse, specular, F(0.04)) and
  // metal_brdf = F(baseColor) * specular; material = mix(dielectric, metal, metallic).
  const double F = F_Schlick(0.04, VdotH);
  Rgb diffuse{}, specular{};
  for (int c = 0; c < 3; ++c) {
    diffuse[c] = (1.0 - metallic) * (1.0 - F) * baseColor[c] / kPi;
    specular[c] = (1.0 - metallic) * F * spec + metallic * F_Schlick(baseColor[c], VdotH) * spec;
  }

  // Sheen: the layer between the base and the clearcoat.
  Rgb sheenLobe{};
  double albedoScaling = 1.0;
  if (m.draftSheen) {
    // Experimental draft: roughness is the material's, always Charlie D with Ashikhmin V, blended by
    // (1 - reflectance) with reflectance = max3(mix(0.04, baseColor, metallic)); no albedo scaling.
    double reflectance = 0.0;
    for (int c = 0; c < 3; ++c)
      reflectance = std::max(reflectance, 0.04 * (1.0 - metallic) + baseColor[c] * metallic);
    const double dv = D_Charlie(NdotH, alpha) * V_Ashikhmin(NdotL, NdotV);
    for (int c = 0; c < 3; ++c)
      sheenLobe[c] = (1.0 - reflectance) * m.draftColor[c] * static_cast<double>(m.draftIntensity) * dv;
  } else if (max3(m.sheenColor) > 0.0) {
    // 000 ratified: sheen_material = sheenColor * sheen_brdf + material * sheen_albedo_scaling.
    // A zero sheenColor disables the layer (and its default roughness 0 would be singular).
    const double sheenRoughness = m.sheenRoughness;
    const double alphaS = sheenRoughness * sheenRoughness;
    const double dv = sheenD(NdotH, alphaS, o.sheenDistribution) *
                      sheenV(NdotL, NdotV, alphaS, o.sheenVisibility);
    for (int c = 0; c < 3; ++c) sheenLobe[c] = m.sheenColor[c] * dv;
    const double mc = max3(m.sheenColor);
    switch (o.sheenScaling) {
      case brdfcl::SheenScaling::Min:
        albedoScaling = std::min(
            1.0 - mc * sheenAlbedo(NdotV, sheenRoughness, o.sheenDistribution, o.sheenVisibility),
            1.0 - mc * sheenAlbedo(NdotL, sheenRoughness, o.sheenDistribution, o.sheenVisibility));
        break;
      case brdfcl::SheenScaling::View:
        albedoScaling =
            1.0 - mc * sheenAlbedo(NdotV, sheenRoughness, o.sheenDistribution, o.sheenVisibility);
        break;
      case brdfcl::SheenScaling::None:
        albedoScaling = 1.0;
        break;
    }
  }

  // 004: coated = mix(sheened, clearcoat_brdf, clearcoat * Fc), Fc on N.V (not V.H); the coat is
  // isotropic GGX with alpha = clearcoatRoughness^2 on N = +Z. A zero factor disables the layer.
  double coatWeight = 0.0, coat = 0.0;
  if (m.clearcoat != 0.0f) {
    const double Fc = 0.04 + (1.0 - 0.04) * std::pow(1.0 - std::abs(NdotV), 5.0);
    coatWeight = m.clearcoat * Fc;
    const double alphaC = static_cast<double>(m.clearcoatRoughness) * m.clearcoatRoughness;
    coat = D_GGX(NdotH, alphaC) * V_SmithGGXCorrelated(NdotL, NdotV, alphaC);
  }

  for (int c = 0; c < 3; ++c) {
    out.diffuse[c] = (1.0 - coatWeight) * albedoScaling * diffuse[c];
    out.specular[c] = (1.0 - coatWeight) * albedoScaling * specular[c];
    out.sheen[c] = (1.0 - coatWeight) * sheenLobe[c];
    out.clearcoat[c] = coatWeight * coat;
  }
  return out;
}

}  // namespace

namespace {
Rgb pickLobes(const Lobes& l, const brdfcl::EvalOptions& o) {
  switch (o.lobe) {
    case brdfcl::Lobe::Diffuse:
      return l.diffuse;
    case brdfcl::Lobe::Specular:
      return l.specular;
    case brdfcl::Lobe::Sheen:
      return l.sheen;
    case brdfcl::Lobe::Clearcoat:
      return l.clearcoat;
    case brdfcl::Lobe::All:
      break;
  }
  Rgb sum{};
  for (int c = 0; c < 3; ++c) sum[c] = l.diffuse[c] + l.specular[c] + l.sheen[c] + l.clearcoat[c];
  return sum;
}
}  // namespace

Rgb brdf(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V) {
  return pickLobes(evalLobes(m, o, L, V), o);
}

Rgb brdfTabulated(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V) {
  return pickLobes(evalLobes(m, o, L, V, true), o);
}

// ============================================================================================
// Integration helpers (test helpers)
// ============================================================================================

double integrate(const std::function<double(double)>& f, double a, double b, double absTol,
                 int maxIntervals) {
  return qag1(f, a, b, absTol, maxIntervals);
}

// Nested adaptive Gauss-Kronrod in x = N.L (outer) and the azimuth of L relative to V's (inner).
// Breakpoints where the integrand has peaks or kinks: the mirror direction (x = N.V, azimuth pi)
// for the specular and coat lobes, x = 0.5 for Charlie V's Lambda branch switch, x = 0.01 where
// the ln x part starts.
Rgb directionalAlbedo(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 V,
                      double absTol) {
  V = normalize(V);
  if (V.z <= 0.0) return {0.0, 0.0, 0.0};
  const double mu = V.z;
  const double phiV = std::atan2(V.y, V.x);
  auto inner = [&](double x) {
    const double sx = std::sqrt(std::max(0.0, 1.0 - x * x));
    auto f = [&](double phi) {
      const double a = phiV + phi;
      const Vec3 L{sx * std::cos(a), sx * std::sin(a), x};
      return brdf(m, o, L, V);
    };
    // [0, pi] and [pi, 2 pi] separately: anisotropy breaks the mirror symmetry about V's plane.
    const Rgb lo = qag<3>(f, 0.0, kPi, 0.25 * absTol);
    const Rgb hi = qag<3>(f, kPi, 2.0 * kPi, 0.25 * absTol);
    return Rgb{x * (lo[0] + hi[0]), x * (lo[1] + hi[1]), x * (lo[2] + hi[2])};
  };
  // Below x = 0.01 the integrand varies like x^0.2 (Charlie Lambda) and on the scale of x, so
  // that part is integrated in ln x down to 1e-12 (the rest, < 1e-12 * max |x f|, is dropped).
  auto innerLog = [&](double s) {
    const double x = std::exp(s);
    const Rgb v = inner(x);
    return Rgb{v[0] * x, v[1] * x, v[2] * x};
  };
  std::vector<double> breaks{kAlbedoMuMin, 0.5, 1.0};
  if (mu > kAlbedoMuMin && mu < 1.0 && mu != 0.5) breaks.push_back(mu);
  std::sort(breaks.begin(), breaks.end());
  const double tolPiece = 0.5 * absTol / static_cast<double>(breaks.size());
  Rgb sum = qag<3>(innerLog, std::log(1e-12), std::log(kAlbedoMuMin), tolPiece);
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const Rgb part = qag<3>(inner, breaks[k], breaks[k + 1], tolPiece);
    for (int c = 0; c < 3; ++c) sum[c] += part[c];
  }
  return sum;
}

}  // namespace ref
