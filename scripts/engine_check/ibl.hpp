// What the image-based-light glues answer an engine's environment and split-sum samplers with:
// a constant radiance in every direction and at every level (brdfcl's `uniform` environment), and
// brdfcl's own 64x64 GGX DFG table (`brdfcl lut --kind ggx-dfg --size 64`), sampled as the
// profiles' ibl_dfg() samples it (x = N.V, y = roughness, texel i at i / 63).
#pragma once
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace ec {
// The environment's radiance (EC_ENV_RADIANCE, default 1): every prefiltered level and the
// irradiance of a constant environment are that constant.
inline real env_radiance() {
  static const real v = [] {
    const char* s = std::getenv("EC_ENV_RADIANCE");
    return s ? real(std::atof(s)) : real(1);
  }();
  return v;
}

// brdfcl's GGX DFG table from the CSV `brdfcl lut` writes (N.V, roughness, A, B per line), named by
// EC_GGX_DFG.
struct DfgTable {
  int size = 0;
  std::vector<float> ab;  // row j (roughness) major, i (N.V) fastest, (A, B) interleaved
};
inline const DfgTable& ggx_dfg_table() {
  static const DfgTable t = [] {
    DfgTable d;
    const char* path = std::getenv("EC_GGX_DFG");
    if (!path) { std::fprintf(stderr, "EC_GGX_DFG is not set\n"); std::exit(2); }
    FILE* f = std::fopen(path, "r");
    if (!f) { std::perror(path); std::exit(2); }
    char line[256];
    if (!std::fgets(line, sizeof line, f)) { std::fprintf(stderr, "%s is empty\n", path); std::exit(2); }
    float x, y, a, b;
    while (std::fscanf(f, "%f,%f,%f,%f", &x, &y, &a, &b) == 4) {
      d.ab.push_back(a);
      d.ab.push_back(b);
    }
    std::fclose(f);
    size_t n = 0;
    while (n * n * 2 < d.ab.size()) ++n;
    if (n < 2 || n * n * 2 != d.ab.size()) { std::fprintf(stderr, "%s is not a square table\n", path); std::exit(2); }
    d.size = int(n);
    return d;
  }();
  return t;
}

// (A, B) at (N.V, roughness), bilinear between texels at i / (size - 1) (kernels/brdf/profiles/ibl.h).
inline vec2 ggx_dfg(real nv, real r) {
  const DfgTable& t = ggx_dfg_table();
  const int n = t.size;
  real x = glm::clamp(nv, real(0), real(1)) * real(n - 1), y = glm::clamp(r, real(0), real(1)) * real(n - 1);
  int x0 = std::min(int(x), n - 2), y0 = std::min(int(y), n - 2);
  real fx = x - real(x0), fy = y - real(y0);
  auto at = [&](int i, int j, int c) { return real(t.ab[(size_t(j) * size_t(n) + size_t(i)) * 2 + size_t(c)]); };
  vec2 a(mix(at(x0, y0, 0), at(x0 + 1, y0, 0), fx), mix(at(x0, y0, 1), at(x0 + 1, y0, 1), fx));
  vec2 b(mix(at(x0, y0 + 1, 0), at(x0 + 1, y0 + 1, 0), fx), mix(at(x0, y0 + 1, 1), at(x0 + 1, y0 + 1, 1), fx));
  return vec2(mix(a.x, b.x, fy), mix(a.y, b.y, fy));
}
}  // namespace ec
