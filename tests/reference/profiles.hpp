// Independent double-precision reference of the engine parity profiles (docs/profiles.md): each
// engine's direct-light BRDF and its lobe split, plus the tables and fits the profiles read.
// Written from the contract only; shares no code with kernels/ or host/src (data excepted).
#pragma once

#include <array>
#include <cstdint>

#include "reference/reference.hpp"

namespace ref {

// f of profile p (no cosine), in 1/sr, for the material m; lobe selects one additive part
// (Diffuse + Specular + Sheen + Clearcoat == All). L and V are normalised here; f = 0 when
// L.z <= 0 or V.z <= 0. Profile::Spec is ref::brdf with default EvalOptions and that lobe.
// Engine profiles: a draft-sheen material has no sheen; the sheen layer exists when
// max3(sheenColor) > 0 and the coat when clearcoat != 0 (as in ref::brdf); NaN and infinities of
// the engine's maths are kept (khronos: D_GGX at alpha = 0, N.H = 1 is 0/0).
Rgb profileBrdf(const brdfcl::MaterialParams& m, brdfcl::Profile p, brdfcl::Lobe lobe, Vec3 L,
                Vec3 V);

// ---- Tables and fits the profiles use (exposed for tests) ----

// IEEE binary16 bits to double (normals, subnormals, inf, NaN).
double halfToDouble(std::uint16_t bits);

// three.js's 16x16 DFG table (DFGLUT.js@79a613e6) sampled as a GPU does: bilinear in
// (u = perceptual roughness, v = NdotV), texel centres at (i + 0.5)/16, clamp to edge.
// Returns its two channels (A, B).
std::array<double, 2> threejsDfg(double roughness, double NdotV);
// E_ss = A + B: GGX single-scattering directional albedo with F = 1.
double threejsDfgEss(double roughness, double NdotV);

// MaterialX's mx_ggx_dir_albedo_analytic rational fit: (A, B) at (mu = NdotV, alpha), each
// clamped to [0, 1]. E_ggx(F0, F90) = F0 A + F90 B.
std::array<double, 2> mxGgxAlbedoFit(double mu, double alpha);

// MaterialX's sheen directional-albedo rational fit E_MX(mu, alpha), clamped to [0, 1] as
// gltf_pbr's throughput uses it; alpha = sheenRoughness^2 (unfloored).
double mxSheenAlbedo(double mu, double alpha);

// three.js's analytic sheen albedo fit Ê(mu) = clamp(exp(a mu + b), 0, 1). r is the perceptual
// sheen roughness; it is clamped to [1e-4, 1] here as the profile does (a no-op in range).
double threejsSheenAlbedo(double mu, double r);

}  // namespace ref
