// Double-precision densities of brdfcl's samplers, written from their derivations in
// docs/sampling.md (Heitz 2018, Dupuy & Benyoub 2023, the sheen inversions) and the reference
// terms of reference.hpp; like the rest of tests/reference it shares no code with kernels/.
#pragma once

#include <array>

#include "reference/reference.hpp"

namespace ref {

// The lobes in the order the mixture lists them.
// kLobeUniform: the uniform hemisphere, which takes a sheen lobe's share beyond its own sampler's.
enum SamplingLobe { kLobeDiffuse, kLobeSpecular, kLobeSheen, kLobeClearcoat, kLobeUniform, kLobeCount };

// The alphas the samplers use: roughness^2 floored at the kernels' documented minimum (1e-3),
// the anisotropic tangent's mix(alpha, 1, strength^2), the coat's and the sheen's.
struct SamplingAlphas {
  double at, ab, rotation, coat, sheen;
};
SamplingAlphas samplingAlphas(const brdfcl::MaterialParams& m);

// Cosine hemisphere, N.L / pi (0 below the horizon).
double pdfCosine(Vec3 L);
// L = reflect(V, H), H a visible normal of anisotropic GGX with alphas at (along T' rotated by
// `rotation` from +X) and ab: G1(V) D(H) / (4 N.V). Defined on the whole sphere of L (no horizon
// test), where it integrates to 1.
double pdfGGXVNDF(Vec3 L, Vec3 V, double at, double ab, double rotation);
// The bounded VNDF sampler of Eto & Tokuyoshi 2023 (the specular and clearcoat lobes): the same
// density as pdfGGXVNDF above the horizon, times the ratio of the full cap's area to the bounded
// one's: D(H) / (2 (t + k N.V)), t = |(at V_t, ab V_b, V_z)|. 0 for L.z <= 0.
double pdfBoundedVNDF(Vec3 L, Vec3 V, double at, double ab, double rotation);
// The bounded sampler's kept mass (the share of its directions above the horizon), integrated
// over its spherical cap from the sampler's construction, not from the pdf.
double boundedVNDFKeptMass(Vec3 V, double at, double ab, double rotation);
// L = reflect(V, H), H with density D(H) N.H of the sheen distribution d: D N.H / (4 V.H), for
// V.H > 0 (a normal facing away from V produces no direction). On the whole sphere of L.
double pdfSheen(Vec3 L, Vec3 V, double alpha, brdfcl::SheenDistribution d);
// The share of sheen normals that face V: the integral of D(H) N.H over the hemisphere of H
// where V.H > 0, integrated in H's own coordinates (the sheen sampler's total mass in L).
double sheenFacingMass(Vec3 V, double alpha, brdfcl::SheenDistribution d);

// The mixture's lobe probabilities at V for the options (one lobe alone unless options.lobe is
// All): each lobe's estimated albedo, split between its sampler and the cosine hemisphere by the
// share its sampler keeps at normal incidence, the cosine's plus 0.01, normalized. Ratified sheen only.
std::array<double, kLobeCount> lobeProbabilities(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 V);
// Lobe t's pdf of L (as above: the cosine, the bounded VNDF, the sheen's) for material m.
double lobePdf(int t, const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V);
// The mixture's pdf of L, sum of p_t pdf_t; 0 for L.z <= 0 or V.z <= 0 (what the sampler keeps).
double mixturePdf(const brdfcl::MaterialParams& m, const brdfcl::EvalOptions& o, Vec3 L, Vec3 V);

}  // namespace ref
