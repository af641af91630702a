// Gauss-Legendre nodes and weights by Newton iteration on P_n, from the three-term recurrence.
#include "eval/quadrature.hpp"

#include <cmath>

namespace brdfcl {

QuadratureRule gaussLegendre(int n, double a, double b) {
  QuadratureRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));  // Tricomi's initial guess
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      double dx = p1 / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-16) break;
    }
    rule.nodes[i] = mid - half * x;  // ascending
    rule.weights[i] = 2.0 * half / ((1.0 - x * x) * dp * dp);
  }
  return rule;
}

QuadratureRule compositeGaussLegendre(const std::vector<double>& breaks, int nPerPanel) {
  QuadratureRule out;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    auto r = gaussLegendre(nPerPanel, breaks[i], breaks[i + 1]);
    out.nodes.insert(out.nodes.end(), r.nodes.begin(), r.nodes.end());
    out.weights.insert(out.weights.end(), r.weights.begin(), r.weights.end());
  }
  return out;
}

}  // namespace brdfcl
