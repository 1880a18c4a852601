#include "geometry/surfaces/tessellate.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

#include "geometry/core/disjoint_sets.h"
#include "geometry/core/errors.h"

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

struct CellError {
  double bound = 0.0;
  bool split_s = false, split_t = false;
};

// Taylor bound of the linear interpolation over the cell [s0,s1] x [t0,t1];
// with an offset also the sampled deviation of the offset sheet.
CellError cell_error(const HBezierPatch& p, double s0, double s1, double t0, double t1, double offset) {
  double mss = 0.0, mst = 0.0, mtt = 0.0;
  for (int a = 0; a <= 2; ++a) {
    for (int b = 0; b <= 2; ++b) {
      const PatchJet j = p.jet(s0 + 0.5 * a * (s1 - s0), t0 + 0.5 * b * (t1 - t0));
      mss = std::max(mss, j.dss.norm());
      mst = std::max(mst, j.dst.norm());
      mtt = std::max(mtt, j.dtt.norm());
    }
  }
  constexpr double kMargin = 1.25;
  const double ds = s1 - s0, dt = t1 - t0;
  const double ts = kMargin * mss * ds * ds, tt = kMargin * mtt * dt * dt, tm = kMargin * 2.0 * mst * ds * dt;
  CellError e;
  e.bound = 0.5 * (ts + tm + tt);
  if (offset != 0.0) {
    // Offset corners, then the offset surface against the two triangles' interpolation.
    auto off = [&](double s, double t) -> Vec3 { return p.point(s, t) + offset * p.normal(s, t); };
    const Vec3 c00 = off(s0, t0), c10 = off(s1, t0), c01 = off(s0, t1), c11 = off(s1, t1);
    const bool main_diagonal = (c00 - c11).norm() <= (c10 - c01).norm();
    double sampled = 0.0;
    constexpr int n = 4;
    for (int a = 0; a <= n; ++a) {
      for (int b = 0; b <= n; ++b) {
        const double x = static_cast<double>(a) / n, y = static_cast<double>(b) / n;
        Vec3 lin;
        if (main_diagonal) {
          lin = x >= y ? Vec3(c00 + x * (c10 - c00) + y * (c11 - c10))
                       : Vec3(c00 + y * (c01 - c00) + x * (c11 - c01));
        } else {
          lin = x + y <= 1.0 ? Vec3(c00 + x * (c10 - c00) + y * (c01 - c00))
                             : Vec3(c11 + (1.0 - x) * (c01 - c11) + (1.0 - y) * (c10 - c11));
        }
        sampled = std::max(sampled, (off(s0 + x * ds, t0 + y * dt) - lin).norm());
      }
    }
    e.bound = std::max(e.bound, 1.5 * sampled);
  }
  const double total = ts + tm + tt;
  e.split_s = ts + 0.5 * tm >= 0.25 * total;
  e.split_t = tt + 0.5 * tm >= 0.25 * total;
  if (!e.split_s && !e.split_t) e.split_s = e.split_t = true;  // an offset-driven split of a flat cell
  return e;
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

bool collapsed(const HBezierPatch& p, PatchSide side, double eps) {
  const auto b = border_points(p, side);
  return (b[1] - b[0]).norm() <= eps && (b[2] - b[0]).norm() <= eps && (b[3] - b[0]).norm() <= eps;
}

}  // namespace

SurfaceTessellation tessellate(const PatchNetwork& network, const TessellateOptions& options) {
  require_positive("tolerance", options.tolerance);
  require_in_range("offset", options.offset, -1e12, 1e12);
  if (options.initial_segments < 1) {
    throw RangeError("initial_segments", options.initial_segments, "initial_segments must be >= 1");
  }
  const std::size_t np = network.patches.size();
  DirectionClasses classes(2 * np);
  for (const SharedBorder& b : network.borders) {
    classes.unite(slot(b.a, is_u_side(b.side_a)), slot(b.b, is_u_side(b.side_b)), b.reversed ? 1 : 0);
  }
  // Breakpoints per class root, in the root's orientation.
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
  double achieved = 0.0;
  // A cell that survives a refinement pass unchanged has the same error: each
  // cell is evaluated once, keyed by its patch and exact parameter bounds.
  std::map<std::array<double, 5>, CellError> cell_cache;
  auto error_of = [&](std::size_t p, double s0, double s1, double t0, double t1) -> const CellError& {
    const std::array<double, 5> key{static_cast<double>(p), s0, s1, t0, t1};
    auto it = cell_cache.find(key);
    if (it == cell_cache.end()) {
      it = cell_cache.emplace(key, cell_error(network.patches[p], s0, s1, t0, t1, options.offset)).first;
    }
    return it->second;
  };
  for (;;) {
    std::vector<std::vector<bool>> split(2 * np);
    for (std::size_t c = 0; c < 2 * np; ++c) split[c].assign(breaks[c].size() - 1, false);
    bool any = false;
    achieved = 0.0;
    for (std::size_t p = 0; p < np; ++p) {
      const auto [rs, ps] = classes.find(slot(p, false));
      const auto [rt, pt] = classes.find(slot(p, true));
      const auto sb = slot_breaks(slot(p, false)), tb = slot_breaks(slot(p, true));
      for (std::size_t a = 0; a + 1 < sb.size(); ++a) {
        for (std::size_t b = 0; b + 1 < tb.size(); ++b) {
          const CellError& e = error_of(p, sb[a], sb[a + 1], tb[b], tb[b + 1]);
          achieved = std::max(achieved, e.bound);
          if (e.bound <= options.tolerance) continue;
          any = true;
          if (e.split_s) split[rs][ps ? sb.size() - 2 - a : a] = true;
          if (e.split_t) split[rt][pt ? tb.size() - 2 - b : b] = true;
        }
      }
    }
    if (!any) break;
    for (std::size_t c = 0; c < 2 * np; ++c) {
      std::vector<double> refined{breaks[c][0]};
      for (std::size_t k = 0; k + 1 < breaks[c].size(); ++k) {
        const bool mirror = classes.symmetric(c) && split[c][breaks[c].size() - 2 - k];
        if (split[c][k] || mirror) refined.push_back(0.5 * (breaks[c][k] + breaks[c][k + 1]));
        refined.push_back(breaks[c][k + 1]);
      }
      breaks[c] = std::move(refined);
    }
    const std::size_t count = triangles();
    if (count > options.max_triangles) {
      throw BudgetError(static_cast<double>(count), static_cast<double>(options.max_triangles),
                        fmt::format("tolerance {} needs more than {} triangles, over the budget of {} (raise "
                                    "max_triangles or the tolerance)",
                                    options.tolerance, count, options.max_triangles));
    }
  }

  SurfaceTessellation out;
  out.max_deviation = achieved;
  std::vector<std::pair<std::size_t, std::size_t>> sizes;
  for (std::size_t p = 0; p < np; ++p) {
    out.s_breaks.push_back(slot_breaks(slot(p, false)));
    out.t_breaks.push_back(slot_breaks(slot(p, true)));
    sizes.emplace_back(out.s_breaks[p].size() - 1, out.t_breaks[p].size() - 1);
  }
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
  for (std::size_t p = 0; p < np; ++p) {
    const auto [ns, nt] = sizes[p];
    for (PatchSide side : {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax}) {
      if (!collapsed(network.patches[p], side, eps)) continue;
      const std::size_t n = is_u_side(side) ? nt : ns;
      const auto [a0, b0] = side_vertex(side, 0, ns, nt);
      for (std::size_t k = 1; k <= n; ++k) {
        const auto [ak, bk] = side_vertex(side, k, ns, nt);
        ids.unite(ids.id(p, a0, b0), ids.id(p, ak, bk));
      }
    }
  }
  // Mesh vertices: one per class of grid vertices, placed by the first patch that has it.
  std::vector<int> handle(ids.size(), -1);
  std::vector<Vec3> normal_sum;
  for (std::size_t p = 0; p < np; ++p) {
    const auto [ns, nt] = sizes[p];
    for (std::size_t a = 0; a <= ns; ++a) {
      for (std::size_t b = 0; b <= nt; ++b) {
        const std::size_t r = ids.root(ids.id(p, a, b));
        const double s = out.s_breaks[p][a], t = out.t_breaks[p][b];
        if (handle[r] < 0) {
          const Vec3 q = network.patches[p].point(s, t);
          handle[r] = out.mesh.add_vertex(Mesh::Point(q.x(), q.y(), q.z())).idx();
          normal_sum.push_back(Vec3::Zero());
        }
        normal_sum[static_cast<std::size_t>(handle[r])] += network.patches[p].normal(s, t);
      }
    }
  }
  out.normals.reserve(normal_sum.size());
  for (const Vec3& n : normal_sum) out.normals.push_back(n.norm() > 0.0 ? Vec3(n.normalized()) : n);
  std::size_t refused = 0;
  for (std::size_t p = 0; p < np; ++p) {
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
  if (refused > 0) {
    throw GeometryError("surface",
                        fmt::format("{} triangles of the surface could not be connected manifoldly: "
                                    "patches overlap or meet along partial borders",
                                    refused));
  }
  return out;
}

}  // namespace fabmesh
