#include "geometry/surfaces/bspline_shell.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <iterator>

#include "geometry/core/errors.h"
#include "geometry/surfaces/bspline_patch.h"
#include "geometry/surfaces/tessellate.h"

namespace fabmesh {
namespace {

constexpr std::array<PatchSide, 4> kSides{PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax};

bool along_t(PatchSide side) { return side == PatchSide::UMin || side == PatchSide::UMax; }

// Distinct clamped knots: the ends `degree + 1` times, the others once.
std::vector<int> simple_multiplicities(std::size_t knots, int degree) {
  std::vector<int> m(knots, 1);
  m.front() = m.back() = degree + 1;
  return m;
}

// A border curve as cubic Bézier pieces: piece k over [breaks[k], breaks[k +
// 1]] has the points 3k .. 3k + 3.
struct BezierChain {
  std::vector<double> breaks;
  std::vector<Vec3> points;
};

// A cubic B-spline's Bézier pieces: each span's points are the blossoms
// f(a, a, a), f(a, a, b), f(a, b, b), f(b, b, b) of its four poles.
BezierChain cubic_chain(const std::vector<double>& knots, const std::vector<int>& multiplicities,
                        const std::vector<Vec3>& poles) {
  const std::vector<double> full = full_knots(knots, multiplicities);
  BezierChain out;
  out.breaks = knots;
  for (std::size_t span = 3; span + 1 < full.size() - 3; ++span) {
    const double a = full[span], b = full[span + 1];
    if (!(b > a)) continue;
    const std::size_t first = out.points.empty() ? 0 : 1;
    const std::array<std::array<double, 3>, 4> args{{{a, a, a}, {a, a, b}, {a, b, b}, {b, b, b}}};
    for (std::size_t q = first; q < 4; ++q) {
      std::array<Vec3, 4> d{poles[span - 3], poles[span - 2], poles[span - 1], poles[span]};
      for (std::size_t r = 1; r <= 3; ++r) {
        for (std::size_t j = 3; j >= r; --j) {
          const std::size_t i = span - 3 + j;
          const double alpha = (args[q][r - 1] - full[i]) / (full[i + 4 - r] - full[i]);
          d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
        }
      }
      out.points.push_back(d[3]);
    }
  }
  return out;
}

// A polyline's pieces as cubic Bézier segments (the line's points at 0, 1/3, 2/3, 1).
BezierChain line_chain(const std::vector<double>& breaks, const std::vector<Vec3>& points) {
  BezierChain out;
  out.breaks = breaks;
  out.points.push_back(points[0]);
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    out.points.push_back((2.0 * points[k] + points[k + 1]) / 3.0);
    out.points.push_back((points[k] + 2.0 * points[k + 1]) / 3.0);
    out.points.push_back(points[k + 1]);
  }
  return out;
}

// The same curve with its pieces split at every break of `breaks` (a
// superset of the chain's own): de Casteljau.
BezierChain split_at(const BezierChain& chain, const std::vector<double>& breaks) {
  BezierChain out;
  out.breaks = breaks;
  out.points.push_back(chain.points[0]);
  std::size_t next = 1;  // the first break of `breaks` not yet reached
  for (std::size_t k = 0; k + 1 < chain.breaks.size(); ++k) {
    std::array<Vec3, 4> piece{chain.points[3 * k], chain.points[3 * k + 1], chain.points[3 * k + 2],
                              chain.points[3 * k + 3]};
    double from = chain.breaks[k];
    const double to = chain.breaks[k + 1];
    for (; next < breaks.size() && breaks[next] < to; ++next) {
      const double x = (breaks[next] - from) / (to - from);
      // Left part: the first points of the de Casteljau triangle's levels; right part: the last.
      const Vec3 a = (1 - x) * piece[0] + x * piece[1], b = (1 - x) * piece[1] + x * piece[2],
                 c = (1 - x) * piece[2] + x * piece[3];
      const Vec3 ab = (1 - x) * a + x * b, bc = (1 - x) * b + x * c;
      const Vec3 mid = (1 - x) * ab + x * bc;
      out.points.insert(out.points.end(), {a, ab, mid});
      piece = {mid, bc, c, piece[3]};
      from = breaks[next];
    }
    out.points.insert(out.points.end(), {piece[1], piece[2], piece[3]});
    ++next;  // `to` itself
  }
  return out;
}

std::vector<double> merged(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// One patch's bilinear face through the grid's points at `offset` along the normals.
BSplineFace grid_face(const ShellGrid& grid, std::size_t p, double offset, const std::string& name) {
  BSplineFace f;
  f.name = name;
  f.u_degree = f.v_degree = 1;
  f.u_knots = grid.s_breaks[p];
  f.v_knots = grid.t_breaks[p];
  f.u_multiplicities = simple_multiplicities(f.u_knots.size(), 1);
  f.v_multiplicities = simple_multiplicities(f.v_knots.size(), 1);
  f.u_poles = f.u_knots.size();
  f.v_poles = f.v_knots.size();
  for (const int v : grid.vertices[p]) {
    const auto i = static_cast<std::size_t>(v);
    f.poles.push_back(grid.points[i] + offset * grid.normals[i]);
  }
  return f;
}

// The poles of a face's side, in the direction of the side's parameter
// (PatchSide's rows and columns: u_min is k = 0, v_min is l = 0).
std::vector<Vec3> side_poles(const BSplineFace& f, PatchSide side) {
  std::vector<Vec3> out;
  if (along_t(side)) {
    const std::size_t k = side == PatchSide::UMin ? 0 : f.u_poles - 1;
    for (std::size_t l = 0; l < f.v_poles; ++l) out.push_back(f.poles[k * f.v_poles + l]);
  } else {
    const std::size_t l = side == PatchSide::VMin ? 0 : f.v_poles - 1;
    for (std::size_t k = 0; k < f.u_poles; ++k) out.push_back(f.poles[k * f.v_poles + l]);
  }
  return out;
}

// A sheet face's border along `side` as Bézier pieces.
BezierChain side_chain(const BSplineFace& f, PatchSide side) {
  const std::vector<Vec3> poles = side_poles(f, side);
  const bool t = along_t(side);
  const std::vector<double>& knots = t ? f.v_knots : f.u_knots;
  if ((t ? f.v_degree : f.u_degree) == 1) return line_chain(knots, poles);
  return cubic_chain(knots, t ? f.v_multiplicities : f.u_multiplicities, poles);
}

// The ruled face between two chains over the same parameter range.
BSplineFace ruled_face(const BezierChain& near, const BezierChain& far, const std::string& name) {
  const std::vector<double> breaks = merged(near.breaks, far.breaks);
  const BezierChain a = split_at(near, breaks), b = split_at(far, breaks);
  BSplineFace f;
  f.name = name;
  f.u_degree = 3;
  f.v_degree = 1;
  f.u_knots = breaks;
  f.u_multiplicities.assign(breaks.size(), 3);
  f.u_multiplicities.front() = f.u_multiplicities.back() = 4;
  f.v_knots = {0.0, 1.0};
  f.v_multiplicities = {2, 2};
  f.u_poles = a.points.size();
  f.v_poles = 2;
  for (std::size_t k = 0; k < a.points.size(); ++k) f.poles.insert(f.poles.end(), {a.points[k], b.points[k]});
  return f;
}

void require_grid(const PatchNetwork& network, const ShellGrid& grid) {
  if (!(grid.to > grid.from)) {
    throw RangeError(
        "to", grid.to,
        fmt::format("a shell spans from {} to {} along the normals: it needs to > from", grid.from, grid.to));
  }
  const std::size_t np = network.patches.size();
  bool ok = grid.s_breaks.size() == np && grid.t_breaks.size() == np && grid.vertices.size() == np &&
            grid.points.size() == grid.normals.size();
  for (std::size_t p = 0; ok && p < np; ++p) {
    ok = grid.s_breaks[p].size() >= 2 && grid.t_breaks[p].size() >= 2 &&
         grid.vertices[p].size() == grid.s_breaks[p].size() * grid.t_breaks[p].size();
    for (std::size_t i = 0; ok && i < grid.vertices[p].size(); ++i)
      ok = grid.vertices[p][i] >= 0 && static_cast<std::size_t>(grid.vertices[p][i]) < grid.points.size();
  }
  if (!ok) {
    throw RangeError("grid", static_cast<double>(grid.vertices.size()),
                     fmt::format("the shell's grid does not match the network of {} patches", np));
  }
}

}  // namespace

ShellGrid shell_grid(const SurfaceTessellation& sheet, double from, double to) {
  ShellGrid g;
  g.from = from;
  g.to = to;
  g.bound = sheet.max_deviation;
  g.s_breaks = sheet.s_breaks;
  g.t_breaks = sheet.t_breaks;
  g.vertices = sheet.grid_vertices;
  g.points.reserve(sheet.mesh.n_vertices());
  for (const auto v : sheet.mesh.vertices()) {
    const auto& q = sheet.mesh.point(v);
    g.points.emplace_back(q[0], q[1], q[2]);
  }
  g.normals = sheet.normals;
  return g;
}

BSplineFace bspline_face(const BSplinePatch& b, const std::string& name) {
  BSplineFace f;
  f.name = name;
  f.u_knots = b.u.knots;
  f.v_knots = b.v.knots;
  f.u_multiplicities = b.u.multiplicities;
  f.v_multiplicities = b.v.multiplicities;
  f.u_poles = b.u_poles;
  f.v_poles = b.v_poles;
  f.poles = b.poles;
  return f;
}

BSplineShell bspline_shell(const PatchNetwork& network, const ShellGrid& grid, double tolerance) {
  require_grid(network, grid);
  const std::size_t np = network.patches.size();
  BSplineShell out;
  out.bound = grid.bound;
  BSplineNetwork exact;
  if (grid.from == 0.0 || grid.to == 0.0) {
    exact = bspline_network(network, tolerance);
    out.bound = std::max(out.bound, exact.max_bound);
  }
  // Both sheets, one face per patch: `from` first, then `to`.
  for (const double offset : {grid.from, grid.to}) {
    for (std::size_t p = 0; p < np; ++p) {
      out.faces.push_back(offset == 0.0 ? bspline_face(exact.patches[p], network.names[p])
                                        : grid_face(grid, p, offset, network.names[p] + " offset"));
    }
  }
  const std::vector<std::array<bool, 4>> outer = outer_sides(network);
  for (std::size_t p = 0; p < np; ++p) {
    for (const PatchSide side : kSides) {
      if (!outer[p][static_cast<std::size_t>(side)]) continue;
      out.faces.push_back(ruled_face(side_chain(out.faces[p], side), side_chain(out.faces[np + p], side),
                                     network.names[p] + " " + to_string(side) + " wall"));
    }
  }
  return out;
}

}  // namespace fabmesh
