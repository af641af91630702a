// Test support for one-material profile evaluations: direction pairs as Samples, and f of one
// material under one profile and lobe, for the engine-profile tests.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "support.hpp"

namespace brdfcl::test {

// Rows (Lx, Ly, Lz, Vx, Vy, Vz), all against material 0.
inline Samples pairsOf(const std::vector<std::array<float, 6>>& pairs) {
  Samples s;
  for (const auto& p : pairs) {
    s.L.insert(s.L.end(), p.begin(), p.begin() + 3);
    s.V.insert(s.V.end(), p.begin() + 3, p.end());
    s.material.push_back(0);
  }
  return s;
}

inline std::vector<float> evalProfile(const MaterialParams& m, Profile p, Lobe lobe, const Samples& s) {
  EvalOptions o;
  o.profile = p;
  o.lobe = lobe;
  return Evaluator(runtime(), o).evaluate({m}, s);
}

// One sample: L and V (normalized here, in double, then rounded to float).
inline std::array<double, 3> evalPair(const MaterialParams& m, Profile p, Lobe lobe, std::array<double, 3> L,
                                      std::array<double, 3> V) {
  auto unit = [](std::array<double, 3> v) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return std::array<float, 3>{float(v[0] / n), float(v[1] / n), float(v[2] / n)};
  };
  const auto l = unit(L), v = unit(V);
  const auto got = evalProfile(m, p, lobe, pairsOf({{l[0], l[1], l[2], v[0], v[1], v[2]}}));
  return {got[0], got[1], got[2]};
}

}  // namespace brdfcl::test
