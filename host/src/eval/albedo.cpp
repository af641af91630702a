// Directional albedo by a composite Gauss-Legendre rule over (N.L, phi), graded towards grazing
// light where the sheen lobes live; one grid evaluation per view direction.
#include "brdfcl/albedo.hpp"

#include <cmath>

#include "eval/quadrature.hpp"

namespace brdfcl {

std::vector<float> directionalAlbedo(Evaluator& evaluator, const std::vector<MaterialParams>& materials,
                                     const std::vector<float>& viewCosines) {
  // Narrow specular lobes (alpha down to 1e-3) need the dense panels near the mirror direction;
  // this rule resolves roughness >= 0.1 to about 1e-3 and is meant for tables, not for proofs.
  auto cosRule = compositeGaussLegendre({0.0, 0.01, 0.05, 0.2, 0.4, 0.6, 0.8, 0.9, 0.95, 0.99, 1.0}, 12);
  // Full circle: a rotated anisotropic lobe is not mirror-symmetric about the plane of V and N.
  std::vector<double> phiBreaks = {0.0, 0.05, 0.2, 0.5, 1.0, M_PI / 2, 2.2, 2.8, M_PI};
  for (int i = int(phiBreaks.size()) - 2; i >= 0; --i) phiBreaks.push_back(2 * M_PI - phiBreaks[i]);
  auto phiRule = compositeGaussLegendre(phiBreaks, 12);
  const std::size_t nq = cosRule.nodes.size() * phiRule.nodes.size();
  std::vector<float> out(materials.size() * viewCosines.size() * 3, 0.0f);
  for (std::size_t v = 0; v < viewCosines.size(); ++v) {
    const double mu = viewCosines[v];
    const double sinV = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    Samples s;
    std::vector<double> w;
    s.L.reserve(3 * nq);
    s.V.reserve(3 * nq);
    for (std::size_t i = 0; i < cosRule.nodes.size(); ++i) {
      const double u = cosRule.nodes[i], sinL = std::sqrt(1.0 - u * u);
      for (std::size_t j = 0; j < phiRule.nodes.size(); ++j) {
        const double phi = phiRule.nodes[j];
        s.L.insert(s.L.end(), {float(sinL * std::cos(phi)), float(sinL * std::sin(phi)), float(u)});
        s.V.insert(s.V.end(), {float(sinV), 0.0f, float(mu)});
        w.push_back(cosRule.weights[i] * phiRule.weights[j] * u);
      }
    }
    auto f = evaluator.evaluateGrid(materials, s);
    for (std::size_t m = 0; m < materials.size(); ++m) {
      double acc[3] = {0, 0, 0};
      for (std::size_t q = 0; q < nq; ++q)
        for (int c = 0; c < 3; ++c) acc[c] += w[q] * f[3 * (m * nq + q) + c];
      for (int c = 0; c < 3; ++c) out[3 * (m * viewCosines.size() + v) + c] = float(acc[c]);
    }
  }
  return out;
}

}  // namespace brdfcl
