// Independent double-precision reference of the engine parity profiles (see profiles.hpp):
// the material as every engine profile reads it, each engine's cosine clamps and the lobe
// split; the engines are in profile_<engine>.cpp, their tables in profile_tables.cpp.
#include "reference/profiles.hpp"

#include <algorithm>
#include <cmath>

#include "reference/profile_terms.hpp"

namespace ref {

using brdfcl::Lobe;
using brdfcl::MaterialParams;
using brdfcl::Profile;
using namespace engine;

namespace {

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
