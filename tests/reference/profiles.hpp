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
//
// Readings of docs/profiles.md where it leaves room (kernels should match or say otherwise):
//  - Layers are gated, not just weighted: sheen only when max3(c) > 0, coat only when cc != 0, so
//    khronos with cc = 0, r_c = 0 is not NaN at L = V = N (the coat is never evaluated).
//  - E lookups: mu = max(cos, 1e-4); khronos and babylon pass the raw r_s, filament its clamped
//    rho_s (its own line says E_CN(NdotV, rho_s), over the Tables line's "raw r_s"). E comes from
//    ref::sheenAlbedo, which integrates directly (ms a call) for mu < 0.01 or r_s outside
//    [0.05, 1]; r_s = 0 with a non-zero sheen colour is singular there.
//  - threejs: Ê at the raw N.V / N.L (no 1e-4 floor), its a, b in rho_s; ms per channel (f0_b).
//  - filament: f90 one scalar from f0.r + f0.g + f0.b; every D and V (and Kelemen's V) goes
//    through saturateMediump, min(x, 65504), as Filament's source writes them.
//  - babylon: E_ss = DFG(raw r, N.V) (not alphaG's roughness), clamp-to-edge below 1/32; the
//    coat's E_ss = DFG(raw r_c, N.V).
//  - materialx: the isotropic case is the Burley form with alpha_t = alpha_b = clamp(alpha, 1e-5,
//    1); t_d uses comp(F_d(V.H), alpha_bar), so it depends on L as the contract writes it.
//  - khronos: the "differs from spec only where" list omits the anisotropic V's min(., 1), which
//    spec does not have; the two differ there too.
//  - Anisotropy only when anisotropyStrength > 0 (a negative strength is isotropic).
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

// The glTF Sample Renderer's lut_sheen_E.png (8-bit texels, 1024x1024) sampled as a GPU does:
// bilinear in (u = NdotV, v = sheen roughness), texel centres at (i + 0.5)/1024, clamp to edge.
double khronosSheenE(double NdotV, double sheenRoughness);

// Babylon's environment BRDF texture (host/src/model/babylon_brdf_lut.inc): (.x, .y, .b) of
// texture(environmentBrdfSampler, vec2(N.V, r)), bilinear with clamp, texels decoded from RGBD
// and held as half floats; .x = B, .y = A + B = E_ss, .b = the sheen albedo.
std::array<double, 3> babylonBrdf(double NdotV, double roughness);

// MaterialX's mx_ggx_dir_albedo_analytic rational fit: (A, B) at (mu = NdotV, alpha), each
// clamped to [0, 1]. E_ggx(F0, F90) = F0 A + F90 B.
std::array<double, 2> mxGgxAlbedoFit(double mu, double alpha);

// MaterialX's sheen directional-albedo rational fit E_MX(mu, alpha), clamped to [0, 1] as
// gltf_pbr's throughput uses it; alpha = sheenRoughness^2 (unfloored).
double mxSheenAlbedo(double mu, double alpha);

// three.js's analytic sheen albedo fit Ê(mu) = clamp(exp(a mu + b), 0, 1). r is the perceptual
// sheen roughness; it is clamped to [0.07, 1] here as the profile does (MaterialNode's
// SHEEN_ROUGHNESS clamp).
double threejsSheenAlbedo(double mu, double r);

}  // namespace ref
