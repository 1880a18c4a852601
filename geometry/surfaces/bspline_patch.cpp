#include "geometry/surfaces/bspline_patch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/disjoint_sets.h"
#include "geometry/core/errors.h"
#include "geometry/surfaces/cell_bound.h"

namespace fabmesh {
namespace {

// The slot of a patch's direction a side runs along (2 p + 0: along s, + 1:
// along t; a u side, row i = 0 or 3, runs along t). Directions tied by shared
// borders get one number of intervals; on a uniform grid a reversed border
// has the same breaks, so no orientation is kept.
std::size_t slot_along(std::size_t patch, PatchSide side) {
  return 2 * patch + (side == PatchSide::UMin || side == PatchSide::UMax ? 1 : 0);
}

// The part of the bound the errors of u (first) and of v (second) make.
std::array<double, 2> bound_parts(const ControlNet& net, const HermiteBasis& u, const HermiteBasis& v) {
  Vec3 mean = Vec3::Zero();
  for (const auto& row : net)
    for (const Vec3& p : row) mean += p / 16.0;
  std::array<double, 2> parts{0.0, 0.0};
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      const double d = (net[i][j] - mean).norm();
      parts[0] += u.error[i] * v.sup[j] * d;
      parts[1] += (u.sup[i] + u.error[i]) * v.error[j] * d;
    }
  }
  return parts;
}

// Rounding: each pole a sum of 16 products, its coefficients summing to 1 and
// of magnitude at most a few; a generous multiple of the unit roundoff times
// the largest coordinate covers the poles and the evaluation of the surface.
double rounding_bound(const ControlNet& net) {
  double largest = 0.0;
  for (const auto& row : net)
    for (const Vec3& p : row) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  return 256.0 * std::numeric_limits<double>::epsilon() * largest;
}

}  // namespace

HermiteBasis hermite_basis(const HBezierParams& params, int intervals) {
  if (intervals < 1) {
    throw RangeError("intervals", intervals,
                     fmt::format("a Hermite basis needs at least one interval, not {}", intervals));
  }
  const HBezierConstants constants = hbezier_constants(params.alpha);
  const std::array<double, 4> fourth = unit_fourth_bound(params);
  const int n = intervals;
  const double h = 1.0 / n;
  HermiteBasis b;
  b.intervals = n;
  b.multiplicities.assign(static_cast<std::size_t>(n) + 1, 2);
  b.multiplicities.front() = b.multiplicities.back() = 4;
  for (int k = 0; k <= n; ++k) b.knots.push_back(k == n ? 1.0 : k * h);
  for (auto& c : b.coefficients) c.assign(2 * static_cast<std::size_t>(n) + 2, 0.0);
  UnitJet start = unit_jet(0.0, params, constants);
  for (std::size_t i = 0; i < 4; ++i) b.coefficients[i][0] = start[0][i];
  for (int k = 0; k < n; ++k) {
    const UnitJet end = unit_jet(b.knots[static_cast<std::size_t>(k) + 1], params, constants);
    const std::size_t m = 2 * static_cast<std::size_t>(k);
    const BasisEnclosure e = enclose(start, end, h, fourth);
    for (std::size_t i = 0; i < 4; ++i) {
      b.coefficients[i][m + 1] = start[0][i] + h * start[1][i] / 3.0;
      b.coefficients[i][m + 2] = end[0][i] - h * end[1][i] / 3.0;
      b.sup[i] = std::max(b.sup[i], std::min(1.0, e[0][i].magnitude()));  // a non-negative partition of unity
    }
    start = end;
  }
  for (std::size_t i = 0; i < 4; ++i) {
    b.coefficients[i].back() = start[0][i];
    b.error[i] = fourth[i] * std::pow(h, 4) / 384.0;
  }
  return b;
}

double bspline_patch_bound(const ControlNet& net, const HermiteBasis& u, const HermiteBasis& v) {
  const std::array<double, 2> parts = bound_parts(net, u, v);
  return parts[0] + parts[1] + rounding_bound(net);
}

BSplinePatch bspline_patch(const HBezierPatch& patch, int u_intervals, int v_intervals) {
  BSplinePatch out;
  out.u = hermite_basis(patch.u(), u_intervals);
  out.v = hermite_basis(patch.v(), v_intervals);
  const ControlNet& net = patch.points();
  out.u_poles = out.u.coefficients[0].size();
  out.v_poles = out.v.coefficients[0].size();
  // Rows first: R_il = sum_j d_jl P_ij, then Q_kl = sum_i c_ik R_il.
  std::array<std::vector<Vec3>, 4> rows;
  for (std::size_t i = 0; i < 4; ++i) {
    rows[i].assign(out.v_poles, Vec3::Zero());
    for (std::size_t l = 0; l < out.v_poles; ++l)
      for (std::size_t j = 0; j < 4; ++j) rows[i][l] += out.v.coefficients[j][l] * net[i][j];
  }
  out.poles.assign(out.u_poles * out.v_poles, Vec3::Zero());
  for (std::size_t k = 0; k < out.u_poles; ++k)
    for (std::size_t l = 0; l < out.v_poles; ++l)
      for (std::size_t i = 0; i < 4; ++i)
        out.poles[k * out.v_poles + l] += out.u.coefficients[i][k] * rows[i][l];
  out.bound = bspline_patch_bound(net, out.u, out.v);
  return out;
}

BSplineNetwork bspline_network(const PatchNetwork& network, double tolerance, int max_intervals) {
  if (!(tolerance > 0.0)) {
    throw RangeError("tolerance", tolerance,
                     fmt::format("the B-spline surfaces' tolerance must be > 0, not {}", tolerance));
  }
  const std::size_t np = network.patches.size();
  std::vector<int> count(2 * np, 1);
  for (std::size_t p = 0; p < np; ++p) {
    const HBezierPatch& patch = network.patches[p];
    int nu = 1, nv = 1;
    HermiteBasis u = hermite_basis(patch.u(), nu), v = hermite_basis(patch.v(), nv);
    for (;;) {
      const std::array<double, 2> parts = bound_parts(patch.points(), u, v);
      if (parts[0] + parts[1] + rounding_bound(patch.points()) <= tolerance) break;
      // Halve the grid of the direction that contributes more (the other one when it is at its limit).
      const bool refine_u = (parts[0] >= parts[1] && nu < max_intervals) || nv >= max_intervals;
      if ((refine_u ? nu : nv) >= max_intervals) {
        throw GeometryError(
            "patches", fmt::format("patch '{}': writing it as a B-spline surface within {:.3g} needs more "
                                   "than {} intervals in a direction (the bound is still {:.3g})",
                                   network.names[p], tolerance, max_intervals, parts[0] + parts[1]));
      }
      if (refine_u) {
        nu *= 2;
        u = hermite_basis(patch.u(), nu);
      } else {
        nv *= 2;
        v = hermite_basis(patch.v(), nv);
      }
    }
    count[2 * p] = nu;
    count[2 * p + 1] = nv;
  }
  // More intervals never raise a bound (e_i and sup |h_i| + e_i only shrink): take each tied class's largest.
  DisjointSets<std::size_t> tied(2 * np);
  for (const SharedBorder& b : network.borders)
    tied.unite(slot_along(b.a, b.side_a), slot_along(b.b, b.side_b));
  std::vector<int> largest(2 * np, 1);
  for (std::size_t d = 0; d < 2 * np; ++d) largest[tied.find(d)] = std::max(largest[tied.find(d)], count[d]);
  BSplineNetwork out;
  for (std::size_t p = 0; p < np; ++p) {
    out.patches.push_back(
        bspline_patch(network.patches[p], largest[tied.find(2 * p)], largest[tied.find(2 * p + 1)]));
    out.max_bound = std::max(out.max_bound, out.patches.back().bound);
  }
  return out;
}

}  // namespace fabmesh
