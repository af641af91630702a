// The main() of every compiled engine glue: reads the materials and direction pairs that
// scripts/engine-check wrote, runs the engine's direct-light code once per lobe and prints f.
// A glue defines ec_variants[] (one per set of extensions present) before including this.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <map>
#include <tuple>
#include <vector>

namespace ec {
struct Material {
  int has_sheen, has_clearcoat, has_anisotropy, has_ior;
  float base[3], metallic, roughness, sheen[3], sheen_roughness, clearcoat, clearcoat_roughness;
  float anisotropy, anisotropy_cos, anisotropy_sin, ior;
};
// L and V as brdfcl normalizes them (in float); E_* are the harness's table look-ups for this
// pair (brdfcl's tables, which the profiles use in place of the engines' textures).
struct Pair {
  int material;
  vec3 L, V;
  float e_cc_v, e_cc_l, e_cn_v, e_cn_l;
};
inline const Pair* g_pair = nullptr;
inline const Material* g_material = nullptr;
using RunFn = vec3 (*)(const Material&, const Pair&);

inline vec3 unit(real x, real y, real z) {
  real n = std::sqrt((x * x + y * y) + z * z);
  return vec3(x / n, y / n, z / n);
}

// Table look-up served from the harness's values for the current pair: u is N.V or N.L
// (whichever is nearer), v must be the sheen roughness.
inline real pair_lookup(real u, real v, bool neubelt) {
  const Pair& p = *g_pair;
  if (v != g_material->sheen_roughness) return NAN;
  real nv = glm::clamp(p.V.z, real(0), real(1)), nl = glm::clamp(p.L.z, real(0), real(1));
  bool view = std::fabs(u - nv) <= std::fabs(u - nl);
  if (neubelt) return view ? p.e_cn_v : p.e_cn_l;
  return view ? p.e_cc_v : p.e_cc_l;
}

// Table reads answered at the coordinates the engine asks: a first run with EC_LOOKUPS_OUT set
// writes every (table, u, v) it reads and gets 0.5 back; the harness then reads brdfcl's value
// at each, and a second run with EC_LOOKUPS set to those answers gets them (NaN where the engine
// asks at a coordinate the first run did not: its control flow then depended on a table value).
enum Table { E_CC = 0, E_CN = 1 };
inline FILE* g_lookups_out = nullptr;
inline std::map<std::tuple<int, double, double>, double> g_lookups;
inline real table_lookup(int table, real u, real v) {
  if (g_lookups_out) {
    std::fprintf(g_lookups_out, "%d %a %a\n", table, double(u), double(v));
    return real(0.5);
  }
  auto it = g_lookups.find(std::make_tuple(table, double(u), double(v)));
  return it == g_lookups.end() ? real(NAN) : real(it->second);
}

inline void open_lookups() {
  if (const char* out = std::getenv("EC_LOOKUPS_OUT")) {
    g_lookups_out = std::fopen(out, "w");
    if (!g_lookups_out) { std::perror(out); std::exit(2); }
  } else if (const char* in = std::getenv("EC_LOOKUPS")) {
    FILE* f = std::fopen(in, "r");
    if (!f) { std::perror(in); std::exit(2); }
    int t;
    double u, v, e;
    while (std::fscanf(f, "%d %la %la %la", &t, &u, &v, &e) == 4) g_lookups[std::make_tuple(t, u, v)] = e;
    std::fclose(f);
  }
}

inline int run(RunFn const* variants, int argc, char** argv) {
  if (argc != 3) { std::fprintf(stderr, "usage: %s MATERIALS PAIRS\n", argv[0]); return 2; }
  open_lookups();
  std::vector<Material> mats;
  FILE* f = std::fopen(argv[1], "r");
  if (!f) { std::perror(argv[1]); return 2; }
  Material m;
  while (std::fscanf(f, "%d %d %d %d %f %f %f %f %f %f %f %f %f %f %f %f %f %f %f",
                     &m.has_sheen, &m.has_clearcoat, &m.has_anisotropy, &m.has_ior, &m.base[0],
                     &m.base[1], &m.base[2], &m.metallic, &m.roughness, &m.sheen[0], &m.sheen[1],
                     &m.sheen[2], &m.sheen_roughness, &m.clearcoat, &m.clearcoat_roughness,
                     &m.anisotropy, &m.anisotropy_cos, &m.anisotropy_sin, &m.ior) == 19)
    mats.push_back(m);
  std::fclose(f);
  f = std::fopen(argv[2], "r");
  if (!f) { std::perror(argv[2]); return 2; }
  int mi;
  float l[3], v[3], e[4];
  while (std::fscanf(f, "%d %f %f %f %f %f %f %f %f %f %f", &mi, &l[0], &l[1], &l[2], &v[0], &v[1],
                     &v[2], &e[0], &e[1], &e[2], &e[3]) == 11) {
    Pair p{mi, unit(l[0], l[1], l[2]), unit(v[0], v[1], v[2]), e[0], e[1], e[2], e[3]};
    const Material& mm = mats.at(size_t(mi));
    g_pair = &p;
    g_material = &mm;
    int variant = mm.has_sheen | mm.has_clearcoat << 1 | mm.has_anisotropy << 2 | mm.has_ior << 3;
    for (int lobe = 0; lobe < 5; ++lobe) {
      g_lobe = lobe;
      g_ctx = 0;
      vec3 r = variants[variant](mm, p);
      std::printf(lobe ? " %.9g %.9g %.9g" : "%.9g %.9g %.9g", r.x, r.y, r.z);
    }
    std::printf("\n");
  }
  std::fclose(f);
  if (g_lookups_out) std::fclose(g_lookups_out);
  return 0;
}
}  // namespace ec
