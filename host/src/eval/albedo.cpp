// Directional albedo by a composite Gauss-Legendre rule over the half vector (theta_h, phi_h):
// dw_L = 4 (V.H) dw_h puts the mirror peak of a near-specular lobe at theta_h = 0, where the
// panels are graded down to 1e-4 rad, and the sheen lobes' grazing mass at theta_h -> pi/2.
#include "brdfcl/albedo.hpp"

#include <cmath>

#include "eval/quadrature.hpp"

namespace brdfcl {

std::vector<float> directionalAlbedo(Evaluator& evaluator, const std::vector<MaterialParams>& materials,
                                     const std::vector<float>& viewCosines) {
  const auto thetaRule = compositeGaussLegendre(
      {0.0, 1e-4, 4e-4, 1.6e-3, 6.4e-3, 0.025, 0.1, 0.3, 0.6, 1.0, 1.3, 1.45, 1.52, 1.555, M_PI / 2}, 12);
  // Full circle: a rotated anisotropic lobe is not mirror-symmetric about the plane of V and N.
  std::vector<double> phiBreaks;
  for (int i = 0; i <= 16; ++i) phiBreaks.push_back(2 * M_PI * i / 16);
  const auto phiRule = compositeGaussLegendre(phiBreaks, 8);
  const std::size_t nq = thetaRule.nodes.size() * phiRule.nodes.size();

  std::vector<float> out(materials.size() * viewCosines.size() * 3, 0.0f);
  for (std::size_t v = 0; v < viewCosines.size(); ++v) {
    const double mu = viewCosines[v];
    const double V[3] = {std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu};
    Samples s;
    std::vector<double> w;
    s.L.reserve(3 * nq);
    s.V.reserve(3 * nq);
    w.reserve(nq);
    for (std::size_t i = 0; i < thetaRule.nodes.size(); ++i) {
      const double th = thetaRule.nodes[i], sh = std::sin(th), ch = std::cos(th);
      for (std::size_t j = 0; j < phiRule.nodes.size(); ++j) {
        const double ph = phiRule.nodes[j];
        const double H[3] = {sh * std::cos(ph), sh * std::sin(ph), ch};
        const double VdotH = V[0] * H[0] + V[1] * H[1] + V[2] * H[2];
        double L[3];
        for (int c = 0; c < 3; ++c) L[c] = 2.0 * VdotH * H[c] - V[c];
        const bool valid = VdotH > 0.0 && L[2] > 0.0;
        s.L.insert(s.L.end(), {float(L[0]), float(L[1]), valid ? float(L[2]) : -1.0f});
        s.V.insert(s.V.end(), {float(V[0]), float(V[1]), float(V[2])});
        w.push_back(valid ? thetaRule.weights[i] * phiRule.weights[j] * sh * 4.0 * VdotH * L[2] : 0.0);
      }
    }
    const auto f = evaluator.evaluateGrid(materials, s);
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
