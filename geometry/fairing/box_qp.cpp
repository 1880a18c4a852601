#include "geometry/fairing/box_qp.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace fabmesh {
namespace {

enum class Bound { Free, Lower, Upper, Fixed };

}  // namespace

BoxQpResult solve_box_qp(const Eigen::MatrixXd& h, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                         const Eigen::VectorXd& hi) {
  const Eigen::Index n = g.size();
  BoxQpResult result;
  result.x = Eigen::VectorXd::Zero(n);
  std::vector<Bound> state(static_cast<std::size_t>(n), Bound::Free);
  const double scale = std::max(1.0, h.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < n; ++i) {
    result.x[i] = std::clamp(0.0, lo[i], hi[i]);
    if (h.row(i).cwiseAbs().maxCoeff() <= 1e-14 * scale && std::abs(g[i]) <= 1e-14 * scale) {
      state[i] = Bound::Fixed;
    }
  }
  const int max_iterations = static_cast<int>(10 * n + 100);
  for (int it = 0; it < max_iterations; ++it) {
    result.iterations = it + 1;
    std::vector<Eigen::Index> free;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (state[i] == Bound::Free) free.push_back(i);
    }
    // Minimiser over the free variables with the others held.
    Eigen::VectorXd target = result.x;
    if (!free.empty()) {
      const auto m = static_cast<Eigen::Index>(free.size());
      Eigen::MatrixXd hff(m, m);
      Eigen::VectorXd rhs(m);
      for (Eigen::Index a = 0; a < m; ++a) {
        rhs[a] = -g[free[a]];
        for (Eigen::Index j = 0; j < n; ++j) {
          if (state[j] != Bound::Free) rhs[a] -= h(free[a], j) * result.x[j];
        }
        for (Eigen::Index b = 0; b < m; ++b) hff(a, b) = h(free[a], free[b]);
      }
      Eigen::LLT<Eigen::MatrixXd> llt(hff);
      if (llt.info() != Eigen::Success) throw std::runtime_error("box QP: Hessian is not positive definite");
      const Eigen::VectorXd xf = llt.solve(rhs);
      for (Eigen::Index a = 0; a < m; ++a) target[free[a]] = xf[a];
    }
    // Step toward it as far as the box allows.
    double step = 1.0;
    Eigen::Index blocking = -1;
    for (Eigen::Index i : free) {
      const double d = target[i] - result.x[i];
      if (d < 0 && target[i] < lo[i]) {
        const double s = (lo[i] - result.x[i]) / d;
        if (s < step) step = s, blocking = i;
      } else if (d > 0 && target[i] > hi[i]) {
        const double s = (hi[i] - result.x[i]) / d;
        if (s < step) step = s, blocking = i;
      }
    }
    for (Eigen::Index i : free) result.x[i] += step * (target[i] - result.x[i]);
    if (blocking >= 0) {
      const bool lower = target[blocking] < lo[blocking];
      result.x[blocking] = lower ? lo[blocking] : hi[blocking];
      state[blocking] = lower ? Bound::Lower : Bound::Upper;
      continue;
    }
    // At the subspace minimiser: check the multipliers of the active bounds.
    const Eigen::VectorXd grad = h * result.x + g;
    Eigen::Index worst = -1;
    double worst_violation = 1e-12 * scale;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double v = state[i] == Bound::Lower ? -grad[i] : state[i] == Bound::Upper ? grad[i] : 0.0;
      if (v > worst_violation) worst_violation = v, worst = i;
    }
    if (worst < 0) break;
    state[worst] = Bound::Free;
  }
  result.value = 0.5 * result.x.dot(h * result.x) + g.dot(result.x);
  return result;
}

}  // namespace fabmesh
