#pragma once
// Box-constrained convex quadratic programs, solved exactly (up to rounding).

#include <Eigen/Core>

namespace fabmesh {

struct BoxQpResult {
  Eigen::VectorXd x;   ///< the minimiser
  double value = 0.0;  ///< 1/2 x'Hx + g'x at x
  int iterations = 0;
};

/// Minimises 1/2 x'Hx + g'x subject to lo <= x <= hi, for symmetric positive
/// semidefinite H, with a primal active-set method: each step solves the
/// equality-constrained problem on the free variables exactly and frees a
/// bound only when its multiplier has the wrong sign, so the result satisfies
/// the KKT conditions (not a clamp of the unconstrained optimum). Variables
/// that do not appear in the objective (zero row of H and zero g) are set to
/// the point of [lo, hi] nearest 0.
/// \throw std::runtime_error when H is not positive definite on the rest.
BoxQpResult solve_box_qp(const Eigen::MatrixXd& h, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                         const Eigen::VectorXd& hi);

}  // namespace fabmesh
