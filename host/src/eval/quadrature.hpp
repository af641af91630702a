// Gauss-Legendre rules, plain and composite over graded panels, for the albedo integrals.
#pragma once
#include <vector>

namespace brdfcl {

struct QuadratureRule {
  std::vector<double> nodes, weights;
};

// n-point Gauss-Legendre on [a, b] (Newton on the Legendre recurrence, double precision).
QuadratureRule gaussLegendre(int n, double a, double b);

// Concatenated n-point rules on the panels [breaks[i], breaks[i+1]].
QuadratureRule compositeGaussLegendre(const std::vector<double>& breaks, int nPerPanel);

}  // namespace brdfcl
