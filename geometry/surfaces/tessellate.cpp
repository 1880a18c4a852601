#include "geometry/surfaces/tessellate.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/core/budget.h"
#include "geometry/core/disjoint_sets.h"
#include "geometry/core/error_checks.h"
#include "geometry/surfaces/cell_bound.h"

namespace fabmesh {
namespace {

bool is_u_side(PatchSide side) { return side == PatchSide::UMin || side == PatchSide::UMax; }

// Union-find with parity: directions of patches tied by shared borders,
// `parity` saying whether a direction runs against its class's orientation.
class DirectionClasses {
 public:
  explicit DirectionClasses(std::size_t n) : parent_(n), parity_(n, 0), symmetric_(n, false) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::pair<std::size_t, int> find(std::size_t x) const {
    int parity = 0;
    while (parent_[x] != x) {
      parity ^= parity_[x];
      x = parent_[x];
    }
    return {x, parity};
  }
  void unite(std::size_t a, std::size_t b, int parity) {
    const auto [ra, pa] = find(a);
    const auto [rb, pb] = find(b);
    if (ra == rb) {
      if ((pa ^ pb) != parity) symmetric_[ra] = true;  // the class must be symmetric under x -> 1 - x
      return;
    }
    parent_[rb] = ra;
    parity_[rb] = pa ^ pb ^ parity;
    symmetric_[ra] = symmetric_[ra] || symmetric_[rb];
  }
  bool symmetric(std::size_t root) const { return symmetric_[root]; }

 private:
  std::vector<std::size_t> parent_;
  std::vector<int> parity_;
  std::vector<bool> symmetric_;
};

std::size_t slot(std::size_t patch, bool along_t) { return 2 * patch + (along_t ? 1 : 0); }

std::vector<double> oriented(const std::vector<double>& breaks, int parity) {
  if (parity == 0) return breaks;
  std::vector<double> out(breaks.size());
  for (std::size_t i = 0; i < breaks.size(); ++i) out[i] = 1.0 - breaks[breaks.size() - 1 - i];
  return out;
}

// A cell's proven bound and the directions to split it in.
struct CellError {
  double bound = 0.0;
  bool split_s = false, split_t = false;
  bool degenerate = false;  ///< the normal's lower bound is 0: the offset cannot be bounded here
};

// One direction of one patch at the breaks of the current grid: the basis
// enclosure of every interval and the jet at its midpoint.
struct DirectionSamples {
  std::vector<BasisEnclosure> cells;
  std::vector<UnitJet> mids;
};

DirectionSamples sample_direction(const std::vector<double>& breaks, const HBezierParams& params) {
  const HBezierConstants constants = hbezier_constants(params.alpha);
  const std::array<double, 4> fourth = unit_fourth_bound(params);
  DirectionSamples out;
  out.cells.reserve(breaks.size());
  out.mids.reserve(breaks.size());
  UnitJet previous = unit_jet(breaks[0], params, constants);
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const UnitJet next = unit_jet(breaks[i + 1], params, constants);
    out.cells.push_back(enclose(previous, next, breaks[i + 1] - breaks[i], fourth));
    out.mids.push_back(unit_jet(0.5 * (breaks[i] + breaks[i + 1]), params, constants));
    previous = next;
  }
  return out;
}

// The bound of one cell: the surface, each offset sheet of the shell (plus
// the averaged-normal term), and the side wall's twist along an outer border.
CellError cell_error(const CellDerivatives& d, double ds, double dt, const TessellateOptions& o,
                     double normal_term, const std::function<double()>& cone, double twist_s,
                     double twist_t) {
  CellError e;
  double ss = d.ss, st = d.st, tt = d.tt;
  const double surface = surface_cell_error(d, ds, dt);
  e.bound = surface;
  double cone_angle = -1.0;  // computed when first needed
  for (double offset : {o.shell_from, o.shell_to}) {
    if (offset == 0.0) continue;
    const OffsetSecond sec = offset_second(d, offset);
    double err = (sec.ss * ds * ds + 2.0 * sec.st * ds * dt + sec.tt * dt * dt) / 8.0;
    bool by_cone = false;
    if (!(err + std::abs(offset) * normal_term <= o.tolerance)) {
      // Near a singular point of the normal its derivatives blow up, but the
      // normals stay in a narrow cone: bound the sheet by that instead.
      if (cone_angle < 0.0) cone_angle = cone();
      const double by_angle = surface + std::abs(offset) * 2.0 * std::sin(std::min(cone_angle, M_PI / 2));
      if (std::isfinite(cone_angle) && !(err <= by_angle)) {
        err = by_angle;
        by_cone = true;
      }
    }
    err += std::abs(offset) * normal_term;
    if (!std::isfinite(err)) {
      e.bound = err;
      e.degenerate = e.split_s = e.split_t = true;
      return e;
    }
    if (by_cone) e.split_s = e.split_t = true;
    if (err > e.bound) {
      e.bound = err;
      if (!by_cone) ss = sec.ss, st = sec.st, tt = sec.tt;
    }
  }
  const double sheets = e.bound;
  e.bound += std::max(twist_s, twist_t);
  const double ts = ss * ds * ds, tm = 2.0 * st * ds * dt, tq = tt * dt * dt, total = ts + tm + tq;
  e.split_s = e.split_s || ts + 0.5 * tm >= 0.25 * total || twist_s >= 0.5 * sheets;
  e.split_t = e.split_t || tq + 0.5 * tm >= 0.25 * total || twist_t >= 0.5 * sheets;
  if (!e.split_s && !e.split_t) e.split_s = e.split_t = true;
  return e;
}

// Point "enclosure" of a jet (both ends the same).
BasisEnclosure point_enclosure(const UnitJet& jet, const std::array<double, 4>& fourth) {
  BasisEnclosure e{};
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t i = 0; i < 4; ++i) e[k][i] = {jet[k][i], jet[k][i]};
  }
  for (std::size_t i = 0; i < 4; ++i) e[4][i] = {-fourth[i], fourth[i]};
  return e;
}

// Lower bound of the columns (along_t: rows) a patch needs, see min_triangle_count.
double direction_count(const HBezierPatch& p, const NetDifferences& diff, bool along_t, double tolerance) {
  constexpr int kIntervals = 64, kLines = 8;
  const HBezierParams& mine = along_t ? p.v() : p.u();
  const HBezierParams& other = along_t ? p.u() : p.v();
  std::vector<double> grid;
  for (int k = 0; k <= kIntervals; ++k) grid.push_back(static_cast<double>(k) / kIntervals);
  const DirectionSamples samples = sample_direction(grid, mine);
  const HBezierConstants oc = hbezier_constants(other.alpha);
  const double step = 1.0 / kIntervals;
  double best = 0.0;
  for (int m = 0; m <= kLines; ++m) {
    const UnitJet line = unit_jet(static_cast<double>(m) / kLines, other, oc);
    const BasisEnclosure at_line = point_enclosure(line, unit_fourth_bound(other));
    double integral = 0.0;
    for (int k = 0; k < kIntervals; ++k) {
      const auto& enc = samples.cells[static_cast<std::size_t>(k)];
      const auto& mid = samples.mids[static_cast<std::size_t>(k)];
      const CellDerivatives d = along_t
                                    ? cell_derivatives(p.points(), diff, at_line, enc, line, mid, 0.0, step)
                                    : cell_derivatives(p.points(), diff, enc, at_line, mid, line, step, 0.0);
      Vec3 second = Vec3::Zero();
      for (std::size_t i = 0; i < 4; ++i) {
        for (std::size_t j = 0; j < 4; ++j) {
          second += (along_t ? line[0][i] * mid[2][j] : mid[2][i] * line[0][j]) * p.points()[i][j];
        }
      }
      const double low = second.norm() - 0.5 * step * (along_t ? d.ttt : d.sss);
      if (low > 0.0) integral += step * std::sqrt(low / (8.0 * tolerance));
    }
    best = std::max(best, integral);
  }
  return best;
}

// Grid vertex ids of the patches, and the identification of shared ones
// (the earliest patch's vertex represents its class).
class VertexIds {
 public:
  explicit VertexIds(const std::vector<std::pair<std::size_t, std::size_t>>& grid_sizes)
      : sets_(total(grid_sizes)) {
    std::size_t first = 0;
    for (const auto& [ns, nt] : grid_sizes) {
      first_.push_back(first);
      nt_.push_back(nt);
      first += (ns + 1) * (nt + 1);
    }
  }
  std::size_t id(std::size_t patch, std::size_t a, std::size_t b) const {
    return first_[patch] + a * (nt_[patch] + 1) + b;
  }
  std::size_t root(std::size_t x) { return sets_.find(x); }
  void unite(std::size_t x, std::size_t y) { sets_.unite(x, y); }
  std::size_t size() const { return sets_.size(); }

 private:
  static std::size_t total(const std::vector<std::pair<std::size_t, std::size_t>>& sizes) {
    std::size_t n = 0;
    for (const auto& [ns, nt] : sizes) n += (ns + 1) * (nt + 1);
    return n;
  }
  std::vector<std::size_t> first_, nt_;
  DisjointSets<std::size_t> sets_;
};

// Grid index of the k-th vertex along a side.
std::pair<std::size_t, std::size_t> side_vertex(PatchSide side, std::size_t k, std::size_t ns,
                                                std::size_t nt) {
  switch (side) {
    case PatchSide::UMin:
      return {0, k};
    case PatchSide::UMax:
      return {ns, k};
    case PatchSide::VMin:
      return {k, 0};
    case PatchSide::VMax:
      return {k, nt};
  }
  return {0, 0};
}

// Twist of each side-wall quad along an outer side: thickness |n(k+1) - n(k)| / 4 per grid edge.
std::vector<double> side_twists(const HBezierPatch& patch, PatchSide side, const std::vector<double>& breaks,
                                double thickness) {
  std::vector<double> twist;
  Vec3 previous = Vec3::Zero();
  for (std::size_t k = 0; k < breaks.size(); ++k) {
    const auto [s, t] = border_uv(side, breaks[k]);
    const Vec3 n = patch.normal(s, t);
    if (k > 0) twist.push_back(thickness * (n - previous).norm() / 4.0);
    previous = n;
  }
  return twist;
}

// The cone of normals of cell (a, b), from the corner where |N| is least.
double corner_cone(const HBezierPatch& patch, const std::vector<double>& sb, const std::vector<double>& tb,
                   std::size_t a, std::size_t b, const CellDerivatives& d) {
  double least = std::numeric_limits<double>::infinity(), angle = least;
  const HBezierConstants ku = hbezier_constants(patch.u().alpha), kv = hbezier_constants(patch.v().alpha);
  for (int corner = 0; corner < 4; ++corner) {
    const bool s1 = (corner & 1) != 0, t1 = (corner & 2) != 0;
    const PointPartials at = point_partials(patch.points(), unit_jet(s1 ? sb[a + 1] : sb[a], patch.u(), ku),
                                            unit_jet(t1 ? tb[b + 1] : tb[b], patch.v(), kv));
    const double n = at[1][0].cross(at[0][1]).norm();
    if (n < least) {
      least = n;
      angle = normal_cone_angle(at, s1, t1, d);
    }
  }
  return angle;
}

// What a refinement pass needs besides the grid.
struct Pass {
  const TessellateOptions& options;
  double normal_term;  // the thickness-free part of the averaged-normal term
  bool shell;
  double thickness;
};

// The bounds of the cells of one patch that a pass accepted, kept for the
// next: a cell neither of whose intervals was split is the same cell, with
// the same bound (a cell's bound depends on its intervals alone), so only the
// cells a split made are bounded again.
struct AcceptedCells {
  std::size_t nt = 0;         ///< t intervals of the grid the bounds belong to
  std::vector<double> bound;  ///< per cell a * nt + b; NaN where not accepted
};

// Where each interval of a refined grid was in the grid before: its index
// there, or -1 for the two halves of a split one.
using IntervalOrigin = std::vector<std::ptrdiff_t>;

// One pass over the cells of patch p on its grid (sb, tb): the worst bound,
// and the cells to split marked in split_s / split_t (grid order). Cells
// accepted by the previous pass (`before`, its intervals found by s_from and
// t_from) keep their bound; the cells this pass accepts are put in `now`.
// True when any cell is over the tolerance.
bool mark_patch(const PatchNetwork& network, std::size_t p, const NetDifferences& diff,
                const std::array<bool, 4>& outer, const std::vector<double>& sb,
                const std::vector<double>& tb, const Pass& pass, const IntervalOrigin& s_from,
                const IntervalOrigin& t_from, const AcceptedCells& before, AcceptedCells& now,
                double& achieved, std::vector<bool>& split_s, std::vector<bool>& split_t) {
  const HBezierPatch& patch = network.patches[p];
  const DirectionSamples su = sample_direction(sb, patch.u()), sv = sample_direction(tb, patch.v());
  // Side walls: twists along the outer sides (u sides run along t, v sides along s).
  std::array<std::vector<double>, 4> twist;
  for (PatchSide side : {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax}) {
    const auto i = static_cast<std::size_t>(side);
    if (pass.shell && outer[i])
      twist[i] = side_twists(patch, side, is_u_side(side) ? tb : sb, pass.thickness);
  }
  auto twist_at = [&](PatchSide side, std::size_t k) {
    const auto& v = twist[static_cast<std::size_t>(side)];
    return v.empty() ? 0.0 : v[k];
  };
  bool any = false;
  const std::size_t nt = tb.size() - 1;
  now.nt = nt;
  now.bound.assign((sb.size() - 1) * nt, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t a = 0; a + 1 < sb.size(); ++a) {
    for (std::size_t b = 0; b < nt; ++b) {
      if (s_from[a] >= 0 && t_from[b] >= 0) {
        const double kept =
            before
                .bound[static_cast<std::size_t>(s_from[a]) * before.nt + static_cast<std::size_t>(t_from[b])];
        if (!std::isnan(kept)) {
          achieved = std::max(achieved, kept);
          now.bound[a * nt + b] = kept;
          continue;
        }
      }
      const double ds = sb[a + 1] - sb[a], dt = tb[b + 1] - tb[b];
      const CellDerivatives d =
          cell_derivatives(patch.points(), diff, su.cells[a], sv.cells[b], su.mids[a], sv.mids[b], ds, dt);
      double twist_t = 0.0, twist_s = 0.0;
      if (a == 0) twist_t = std::max(twist_t, twist_at(PatchSide::UMin, b));
      if (a + 2 == sb.size()) twist_t = std::max(twist_t, twist_at(PatchSide::UMax, b));
      if (b == 0) twist_s = std::max(twist_s, twist_at(PatchSide::VMin, a));
      if (b + 2 == tb.size()) twist_s = std::max(twist_s, twist_at(PatchSide::VMax, a));
      const auto cone = [&]() { return corner_cone(patch, sb, tb, a, b, d); };
      const CellError e = cell_error(d, ds, dt, pass.options, pass.normal_term, cone, twist_s, twist_t);
      achieved = std::max(achieved, e.bound);
      if (e.bound <= pass.options.tolerance) {
        now.bound[a * nt + b] = e.bound;
        continue;
      }
      if (e.degenerate && ds < 1e-4 && dt < 1e-4) {
        throw GeometryError(
            network.names[p],
            fmt::format("patch '{}': the surface normal vanishes near (s {:.6g}, t {:.6g}), so "
                        "the offset sheet of the shell cannot be bounded there (a collapsed "
                        "side or a cusp cannot be thickened)",
                        network.names[p], sb[a], tb[b]));
      }
      any = true;
      if (e.split_s) split_s[a] = true;
      if (e.split_t) split_t[b] = true;
    }
  }
  return any;
}

// Halves the marked intervals (and their mirror images in a symmetric class);
// `from` receives the origin of each interval of the result.
std::vector<double> refine(const std::vector<double>& breaks, const std::vector<bool>& split, bool symmetric,
                           double tolerance, IntervalOrigin& from) {
  std::vector<double> refined{breaks[0]};
  from.clear();
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const bool mirror = symmetric && split[breaks.size() - 2 - k];
    if (split[k] || mirror) {
      const double mid = 0.5 * (breaks[k] + breaks[k + 1]);
      if (!(mid > breaks[k] && mid < breaks[k + 1])) {
        throw BudgetError(
            0.0, 0.0, fmt::format("the surface cannot be refined to {:.3g} in double precision", tolerance));
      }
      refined.push_back(mid);
      from.push_back(-1);
      from.push_back(-1);
    } else {
      from.push_back(static_cast<std::ptrdiff_t>(k));
    }
    refined.push_back(breaks[k + 1]);
  }
  return refined;
}

// A class's interval origins seen from a patch direction of the given parity.
IntervalOrigin oriented_origin(const IntervalOrigin& from, int parity, std::size_t before) {
  if (parity == 0) return from;
  IntervalOrigin out(from.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    const std::ptrdiff_t k = from[from.size() - 1 - i];
    out[i] = k < 0 ? -1 : static_cast<std::ptrdiff_t>(before) - 1 - k;
  }
  return out;
}

}  // namespace

double min_triangle_count(const PatchNetwork& network, double tolerance) {
  require_positive("tolerance", tolerance);
  const std::size_t np = network.patches.size();
  DirectionClasses classes(2 * np);
  for (const SharedBorder& b : network.borders) {
    classes.unite(slot(b.a, is_u_side(b.side_a)), slot(b.b, is_u_side(b.side_b)), b.reversed ? 1 : 0);
  }
  std::vector<double> count(2 * np, 1.0);
  for (std::size_t p = 0; p < np; ++p) {
    const NetDifferences diff = net_differences(network.patches[p].points());
    for (bool along_t : {false, true}) {
      const std::size_t root = classes.find(slot(p, along_t)).first;
      count[root] =
          std::max(count[root], std::ceil(direction_count(network.patches[p], diff, along_t, tolerance)));
    }
  }
  const double eps = 1e-12 * network.size;
  double triangles = 0.0;
  for (std::size_t p = 0; p < np; ++p) {
    const double ns = count[classes.find(slot(p, false)).first],
                 nt = count[classes.find(slot(p, true)).first];
    double cells = 2.0 * ns * nt;
    for (PatchSide side : {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax}) {
      if (collapsed_side(network.patches[p], side, eps))
        cells -= is_u_side(side) ? nt : ns;  // one triangle per cell there
    }
    triangles += std::max(cells, 0.0);
  }
  return triangles;
}

void for_each_cell_bound(
    const PatchNetwork& network, const std::vector<std::vector<double>>& s_breaks,
    const std::vector<std::vector<double>>& t_breaks,
    const std::function<void(std::size_t, double, double, double, double, const CellDerivatives&)>& visit) {
  for (std::size_t p = 0; p < network.patches.size(); ++p) {
    const HBezierPatch& patch = network.patches[p];
    const NetDifferences diff = net_differences(patch.points());
    const auto& sb = s_breaks[p];
    const auto& tb = t_breaks[p];
    const DirectionSamples su = sample_direction(sb, patch.u()), sv = sample_direction(tb, patch.v());
    for (std::size_t a = 0; a + 1 < sb.size(); ++a) {
      for (std::size_t b = 0; b + 1 < tb.size(); ++b) {
        const double ds = sb[a + 1] - sb[a], dt = tb[b + 1] - tb[b];
        visit(
            p, sb[a], sb[a + 1], tb[b], tb[b + 1],
            cell_derivatives(patch.points(), diff, su.cells[a], sv.cells[b], su.mids[a], sv.mids[b], ds, dt));
      }
    }
  }
}

namespace {

void require_tessellation_options(const PatchNetwork& network, const TessellateOptions& options) {
  require_positive("tolerance", options.tolerance);
  require_in_range("shell_from", options.shell_from, -1e12, 1e12);
  require_in_range("shell_to", options.shell_to, -1e12, 1e12);
  if (options.initial_segments < 1) {
    throw RangeError("initial_segments", options.initial_segments, "initial_segments must be >= 1");
  }
  const double estimate = min_triangle_count(network, options.tolerance);
  require_within_budget(
      estimate, options.max_triangles,
      [&] {
        return fmt::format(
            "the mesh needs at least {:.4g} triangles (estimated from the surface's second "
            "derivatives before refining)",
            estimate);
      },
      "raise max_triangles or the tolerance");
}

// Each patch's s and t breakpoints, and the deviation the grid is proven within.
struct RefinedGrid {
  std::vector<std::vector<double>> s_breaks, t_breaks;
  double achieved = 0.0;
};

// Splits the cells of every patch until each is within the tolerance. The
// breakpoints live per class of directions that shared borders tie together
// (in the class root's orientation), so patches sharing a border split it alike.
RefinedGrid refine_grid(const PatchNetwork& network, const TessellateOptions& options) {
  const std::size_t np = network.patches.size();
  DirectionClasses classes(2 * np);
  for (const SharedBorder& b : network.borders) {
    classes.unite(slot(b.a, is_u_side(b.side_a)), slot(b.b, is_u_side(b.side_b)), b.reversed ? 1 : 0);
  }
  std::vector<std::vector<double>> breaks(2 * np);
  for (std::size_t c = 0; c < 2 * np; ++c) {
    const auto n = static_cast<std::size_t>(options.initial_segments);
    for (std::size_t k = 0; k <= n; ++k) breaks[c].push_back(static_cast<double>(k) / static_cast<double>(n));
  }
  auto slot_breaks = [&](std::size_t s) {
    const auto [root, parity] = classes.find(s);
    return oriented(breaks[root], parity);
  };
  auto triangles = [&]() {
    std::size_t total = 0;
    for (std::size_t p = 0; p < np; ++p)
      total += 2 * (slot_breaks(slot(p, false)).size() - 1) * (slot_breaks(slot(p, true)).size() - 1);
    return total;
  };
  const bool shell = options.shell_to > options.shell_from;
  const double thickness = shell ? options.shell_to - options.shell_from : 0.0;
  // Vertex normals average the patches meeting there: off by up to the
  // measured normal angle along shared borders.
  double normal_term = 0.0;
  for (const SharedBorder& b : network.borders) normal_term = std::max(normal_term, b.normal_angle);
  const std::vector<std::array<bool, 4>> outer = outer_sides(network);
  std::vector<NetDifferences> diffs;
  for (const HBezierPatch& patch : network.patches) diffs.push_back(net_differences(patch.points()));
  const Pass pass{options, normal_term, shell, thickness};
  double achieved = 0.0;
  // Per class: each interval's origin in the previous pass's grid, and how
  // many intervals that grid had.
  std::vector<IntervalOrigin> origin(2 * np);
  std::vector<std::size_t> before(2 * np);
  for (std::size_t c = 0; c < 2 * np; ++c) origin[c].assign(breaks[c].size() - 1, -1);
  std::vector<AcceptedCells> accepted(np);
  for (;;) {
    std::vector<std::vector<bool>> split(2 * np);
    for (std::size_t c = 0; c < 2 * np; ++c) split[c].assign(breaks[c].size() - 1, false);
    bool any = false;
    achieved = 0.0;
    for (std::size_t p = 0; p < np; ++p) {
      const auto [rs, ps] = classes.find(slot(p, false));
      const auto [rt, pt] = classes.find(slot(p, true));
      const auto sb = slot_breaks(slot(p, false)), tb = slot_breaks(slot(p, true));
      std::vector<bool> split_s(sb.size() - 1, false), split_t(tb.size() - 1, false);
      AcceptedCells now;
      const bool over = mark_patch(
          network, p, diffs[p], outer[p], sb, tb, pass, oriented_origin(origin[rs], ps, before[rs]),
          oriented_origin(origin[rt], pt, before[rt]), accepted[p], now, achieved, split_s, split_t);
      accepted[p] = std::move(now);
      if (!over) continue;
      any = true;
      for (std::size_t a = 0; a < split_s.size(); ++a) {
        if (split_s[a]) split[rs][ps ? split_s.size() - 1 - a : a] = true;
      }
      for (std::size_t b = 0; b < split_t.size(); ++b) {
        if (split_t[b]) split[rt][pt ? split_t.size() - 1 - b : b] = true;
      }
    }
    if (!any) break;
    for (std::size_t c = 0; c < 2 * np; ++c) {
      before[c] = breaks[c].size() - 1;
      breaks[c] = refine(breaks[c], split[c], classes.symmetric(c), options.tolerance, origin[c]);
    }
    const std::size_t count = triangles();
    require_within_budget(
        count, options.max_triangles,
        [&] { return fmt::format("the mesh needs more than {} triangles", count); },
        "raise max_triangles or the tolerance");
  }
  RefinedGrid grid;
  grid.achieved = achieved;
  for (std::size_t p = 0; p < np; ++p) {
    grid.s_breaks.push_back(slot_breaks(slot(p, false)));
    grid.t_breaks.push_back(slot_breaks(slot(p, true)));
  }
  return grid;
}

using GridSizes = std::vector<std::pair<std::size_t, std::size_t>>;

// The grid vertices that are one mesh vertex: along shared borders, and
// along a side collapsed to a point (a pole).
VertexIds shared_vertices(const PatchNetwork& network, const GridSizes& sizes) {
  VertexIds ids(sizes);
  for (const SharedBorder& b : network.borders) {
    const auto [nsa, nta] = sizes[b.a];
    const auto [nsb, ntb] = sizes[b.b];
    const std::size_t n = is_u_side(b.side_a) ? nta : nsa;
    for (std::size_t k = 0; k <= n; ++k) {
      const auto [aa, ab] = side_vertex(b.side_a, k, nsa, nta);
      const auto [ba, bb] = side_vertex(b.side_b, b.reversed ? n - k : k, nsb, ntb);
      ids.unite(ids.id(b.a, aa, ab), ids.id(b.b, ba, bb));
    }
  }
  const double eps = 1e-12 * network.size;
  for (std::size_t p = 0; p < sizes.size(); ++p) {
    const auto [ns, nt] = sizes[p];
    for (PatchSide side : {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax}) {
      if (!collapsed_side(network.patches[p], side, eps)) continue;
      const std::size_t n = is_u_side(side) ? nt : ns;
      const auto [a0, b0] = side_vertex(side, 0, ns, nt);
      for (std::size_t k = 1; k <= n; ++k) {
        const auto [ak, bk] = side_vertex(side, k, ns, nt);
        ids.unite(ids.id(p, a0, b0), ids.id(p, ak, bk));
      }
    }
  }
  return ids;
}

// Adds one mesh vertex per class of grid vertices, placed by the first patch
// that has it, with the average of the patches' normals there; returns each
// class root's vertex.
std::vector<int> place_vertices(const PatchNetwork& network, const GridSizes& sizes, VertexIds& ids,
                                SurfaceTessellation& out) {
  std::vector<int> handle(ids.size(), -1);
  std::vector<Vec3> normal_sum;
  for (std::size_t p = 0; p < sizes.size(); ++p) {
    const auto [ns, nt] = sizes[p];
    const HBezierPatch& patch = network.patches[p];
    std::vector<HBezierPatch::Weights> at_t;  // the weights of each grid line, computed once
    at_t.reserve(nt + 1);
    for (double t : out.t_breaks[p]) at_t.push_back(patch.v_weights(t));
    for (std::size_t a = 0; a <= ns; ++a) {
      const double s = out.s_breaks[p][a];
      const HBezierPatch::Weights at_s = patch.u_weights(s);
      for (std::size_t b = 0; b <= nt; ++b) {
        const std::size_t r = ids.root(ids.id(p, a, b));
        const PatchJet jet = patch.jet(at_s, at_t[b]);
        if (handle[r] < 0) {
          const Vec3& q = jet.point;
          handle[r] = out.mesh.add_vertex(Mesh::Point(q.x(), q.y(), q.z())).idx();
          normal_sum.push_back(Vec3::Zero());
        }
        normal_sum[static_cast<std::size_t>(handle[r])] += patch.normal(jet, s, out.t_breaks[p][b]);
      }
    }
  }
  out.normals.reserve(normal_sum.size());
  for (const Vec3& n : normal_sum) out.normals.push_back(n.norm() > 0.0 ? Vec3(n.normalized()) : n);
  return handle;
}

// Two triangles per grid cell, split along the shorter diagonal (one where a
// side collapsed); returns how many faces the mesh refused as non-manifold.
std::size_t connect_cells(const GridSizes& sizes, VertexIds& ids, const std::vector<int>& handle,
                          SurfaceTessellation& out) {
  std::size_t refused = 0;
  for (std::size_t p = 0; p < sizes.size(); ++p) {
    const auto [ns, nt] = sizes[p];
    auto vh = [&](std::size_t a, std::size_t b) {
      return Mesh::VertexHandle(handle[ids.root(ids.id(p, a, b))]);
    };
    auto pos = [&](Mesh::VertexHandle v) {
      const auto& q = out.mesh.point(v);
      return Vec3(q[0], q[1], q[2]);
    };
    auto add = [&](Mesh::VertexHandle x, Mesh::VertexHandle y, Mesh::VertexHandle z) {
      if (x == y || y == z || z == x) return;  // a collapsed side: the cell is one triangle
      if (!out.mesh.add_face(x, y, z).is_valid()) ++refused;
    };
    for (std::size_t a = 0; a < ns; ++a) {
      for (std::size_t b = 0; b < nt; ++b) {
        const auto v00 = vh(a, b), v10 = vh(a + 1, b), v01 = vh(a, b + 1), v11 = vh(a + 1, b + 1);
        if ((pos(v00) - pos(v11)).norm() <= (pos(v10) - pos(v01)).norm()) {
          add(v00, v10, v11);
          add(v00, v11, v01);
        } else {
          add(v00, v10, v01);
          add(v10, v11, v01);
        }
      }
    }
  }
  return refused;
}

}  // namespace

SurfaceTessellation tessellate(const PatchNetwork& network, const TessellateOptions& options) {
  require_tessellation_options(network, options);
  RefinedGrid grid = refine_grid(network, options);
  SurfaceTessellation out;
  out.max_deviation = grid.achieved;
  out.s_breaks = std::move(grid.s_breaks);
  out.t_breaks = std::move(grid.t_breaks);
  GridSizes sizes;
  for (std::size_t p = 0; p < network.patches.size(); ++p)
    sizes.emplace_back(out.s_breaks[p].size() - 1, out.t_breaks[p].size() - 1);
  VertexIds ids = shared_vertices(network, sizes);
  const std::vector<int> handle = place_vertices(network, sizes, ids, out);
  for (std::size_t p = 0; p < sizes.size(); ++p) {
    const auto [ns, nt] = sizes[p];
    std::vector<int>& ids_of = out.grid_vertices.emplace_back((ns + 1) * (nt + 1));
    for (std::size_t a = 0; a <= ns; ++a) {
      for (std::size_t b = 0; b <= nt; ++b) ids_of[a * (nt + 1) + b] = handle[ids.root(ids.id(p, a, b))];
    }
  }
  const std::size_t refused = connect_cells(sizes, ids, handle, out);
  if (refused > 0) {
    throw GeometryError("surface",
                        fmt::format("{} triangles of the surface could not be connected manifoldly: "
                                    "patches overlap or meet along partial borders",
                                    refused));
  }
  return out;
}

}  // namespace fabmesh
