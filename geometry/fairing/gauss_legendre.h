#pragma once
// Gauss-Legendre quadrature nodes and weights on [0, 1].

#include <vector>

namespace fabmesh {

struct QuadratureRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

/// The n-point Gauss-Legendre rule mapped to [0, 1] (Newton on P_n); exact
/// for polynomials of degree 2n - 1.
QuadratureRule gauss_legendre(int n);

}  // namespace fabmesh
