#include "geometry/surfaces/patch_network.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/error_checks.h"
#include "geometry/curves/basis.h"

namespace fabmesh {
namespace {

bool is_u_side(PatchSide side) { return side == PatchSide::UMin || side == PatchSide::UMax; }

PatchSide opposite(PatchSide side) {
  switch (side) {
    case PatchSide::UMin:
      return PatchSide::UMax;
    case PatchSide::UMax:
      return PatchSide::UMin;
    case PatchSide::VMin:
      return PatchSide::VMax;
    case PatchSide::VMax:
      return PatchSide::VMin;
  }
  return side;
}

// Line k (k = 0..3, counted from the far side towards `side`) of a net, as 4
// points along the border direction: rows for u sides, columns for v sides.
std::array<Vec3, 4> line_towards(const ControlNet& net, PatchSide side, std::size_t k) {
  const std::size_t index = (side == PatchSide::UMax || side == PatchSide::VMax) ? k : 3 - k;
  std::array<Vec3, 4> line;
  for (std::size_t j = 0; j < 4; ++j) line[j] = is_u_side(side) ? net[index][j] : net[j][index];
  return line;
}

void set_line_towards(ControlNet& net, PatchSide side, std::size_t k, const std::array<Vec3, 4>& line) {
  const std::size_t index = (side == PatchSide::UMax || side == PatchSide::VMax) ? k : 3 - k;
  for (std::size_t j = 0; j < 4; ++j) (is_u_side(side) ? net[index][j] : net[j][index]) = line[j];
}

// The parameters across a side, oriented towards it.
HBezierParams across_towards(const HBezierPatch& p, PatchSide side) {
  const HBezierParams& q = is_u_side(side) ? p.u() : p.v();
  return (side == PatchSide::UMax || side == PatchSide::VMax) ? q : q.reversed();
}

std::size_t computed_lines(Continuity c) { return static_cast<std::size_t>(static_cast<int>(c)) + 1; }

// An error about patch i (`spec`): at its key, named with the patch's name
// ("patches[1] ('lid')"); for a network built without keys, the message says "patches[i]".
GeometryError patch_error(const PatchSpec& spec, std::size_t i, const std::string& message) {
  if (spec.key.empty()) return GeometryError(ErrorLocation{}, fmt::format("patches[{}]: {}", i, message));
  return GeometryError(ErrorLocation{spec.key, fmt::format("{} ('{}')", spec.key, spec.name)}, message);
}

HBezierPatch joined_patch(const PatchSpec& spec, std::size_t spec_index, const HBezierPatch& target,
                          const std::string& target_name) {
  const PatchJoin& join = *spec.join;
  const PatchSide own = opposite(join.side);  // the new patch's side on the border
  const bool along_u = is_u_side(join.side);
  const HBezierParams& border = border_params(target, join.side);
  const HBezierParams& own_border = along_u ? spec.v : spec.u;
  if (own_border != border) {
    throw patch_error(
        spec, spec_index,
        fmt::format("patch '{}' joins '{}' along {} but its {} parameters "
                    "(alpha {}, lambda {}, mu {}) differ from "
                    "the border's (alpha {}, lambda {}, mu {}): joined patches "
                    "must share the border's parameterisation",
                    spec.name, target_name, to_string(join.side), along_u ? "v" : "u", own_border.alpha,
                    own_border.lambda, own_border.mu, border.alpha, border.lambda, border.mu));
  }
  const std::size_t computed = computed_lines(join.continuity);
  if (spec.points.size() != 4 - computed) {
    throw patch_error(
        spec, spec_index,
        fmt::format("a {} join along {} leaves {} free {} of 4 points; got {}", to_string(join.continuity),
                    to_string(join.side), 4 - computed, along_u ? "rows" : "columns", spec.points.size()));
  }
  // The new patch's net, line k counted from the border outwards.
  ControlNet net{};
  const HBezierParams p_params = across_towards(target, join.side);
  const HBezierParams own_across = along_u ? spec.u : spec.v;
  const HBezierParams q_params =
      (own == PatchSide::UMin || own == PatchSide::VMin) ? own_across : own_across.reversed();
  std::array<std::array<Vec3, 4>, 3> lines{};
  for (std::size_t j = 0; j < 4; ++j) {
    std::array<Vec3, 4> row;
    for (std::size_t k = 0; k < 4; ++k) row[k] = line_towards(target.points(), join.side, k)[j];
    const auto q = join_curve_points(row, p_params, q_params, join);
    for (std::size_t k = 0; k < 3; ++k) lines[k][j] = q[k];
  }
  // Free lines come in increasing index of the new patch; computed lines sit at the border side.
  const bool border_at_min = own == PatchSide::UMin || own == PatchSide::VMin;
  for (std::size_t k = 0; k < computed; ++k) set_line_towards(net, opposite(own), k, lines[k]);
  for (std::size_t f = 0; f < spec.points.size(); ++f) {
    const std::size_t index = border_at_min ? computed + f : f;  // index in the new patch
    for (std::size_t j = 0; j < 4; ++j) (along_u ? net[index][j] : net[j][index]) = spec.points[f][j];
  }
  return HBezierPatch(net, spec.u, spec.v);
}

double network_size(const std::vector<HBezierPatch>& patches) {
  Eigen::AlignedBox3d box;
  for (const auto& p : patches)
    for (const auto& row : p.points())
      for (const auto& q : row) box.extend(q);
  return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

// Curvature of the cross-border curve at a border point (j the jet there):
// along s for u sides, t for v sides.
double cross_curvature(const PatchJet& j, PatchSide side) {
  const Vec3 d1 = is_u_side(side) ? j.ds : j.dt;
  const Vec3 d2 = is_u_side(side) ? j.dss : j.dtt;
  const double n = d1.norm();
  return n > 0.0 ? d1.cross(d2).norm() / (n * n * n) : 0.0;
}

void measure(const PatchNetwork& net, SharedBorder& b, const NetworkOptions& o) {
  const HBezierPatch& pa = net.patches[b.a];
  const HBezierPatch& pb = net.patches[b.b];
  for (int k = 0; k < o.samples; ++k) {
    const double x = static_cast<double>(k) / (o.samples - 1);
    const auto ua = border_uv(b.side_a, x);
    const auto ub = border_uv(b.side_b, b.reversed ? 1.0 - x : x);
    const PatchJet ja = pa.jet(ua[0], ua[1]), jb = pb.jet(ub[0], ub[1]);
    b.gap = std::max(b.gap, (ja.point - jb.point).norm());
    const Vec3 na = pa.normal(ja, ua[0], ua[1]), nb = pb.normal(jb, ub[0], ub[1]);
    b.normal_angle = std::max(b.normal_angle, std::atan2(na.cross(nb).norm(), na.dot(nb)));
    const double ka = cross_curvature(ja, b.side_a);
    const double kb = cross_curvature(jb, b.side_b);
    b.curvature_jump = std::max(b.curvature_jump, std::abs(ka - kb) / std::max({ka, kb, 1.0 / net.size}));
  }
  b.achieved = Continuity::None;
  if (b.gap <= o.relative_gap_tolerance * net.size) b.achieved = Continuity::G0;
  if (b.achieved == Continuity::G0 && b.normal_angle <= o.angle_tolerance) b.achieved = Continuity::G1;
  if (b.achieved == Continuity::G1 && b.curvature_jump <= o.relative_curvature_tolerance)
    b.achieved = Continuity::G2;
}

// Finds the sides of patches p < q that are the same border curve.
void find_shared_borders(PatchNetwork& net, const std::vector<PatchSpec>& specs, const NetworkOptions& o) {
  const double eps = o.relative_gap_tolerance * net.size;
  const PatchSide sides[] = {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax};
  std::vector<std::array<int, 4>> used(net.patches.size(), {-1, -1, -1, -1});
  for (std::size_t q = 0; q < net.patches.size(); ++q) {
    for (std::size_t p = 0; p < q; ++p) {
      for (PatchSide sp : sides) {
        if (collapsed_side(net.patches[p], sp, eps)) continue;  // a point, not a border
        const auto bp = border_points(net.patches[p], sp);
        for (PatchSide sq : sides) {
          const auto bq = border_points(net.patches[q], sq);
          bool same = true, rev = true;
          for (std::size_t k = 0; k < 4; ++k) {
            same = same && (bp[k] - bq[k]).norm() <= eps;
            rev = rev && (bp[k] - bq[3 - k]).norm() <= eps;
          }
          if (!same && !rev) continue;
          const bool declared = specs[q].join && specs[q].join->to == p && specs[q].join->side == sp;
          const HBezierParams& pp = border_params(net.patches[p], sp);
          const HBezierParams& pq = border_params(net.patches[q], sq);
          if ((same && pp != pq) || (!same && pp != pq.reversed())) {
            throw patch_error(
                specs[q], q,
                fmt::format(
                    "side {} of patch '{}' coincides with side {} of patch '{}' but is parameterised "
                    "differently (alpha {}, lambda {}, mu {} vs {}, {}, {}{}): shared borders need the same "
                    "parameterisation, or the tessellation would crack",
                    to_string(sq), net.names[q], to_string(sp), net.names[p], pq.alpha, pq.lambda, pq.mu,
                    pp.alpha, pp.lambda, pp.mu, same ? "" : ", run backwards"));
          }
          const auto ip = static_cast<std::size_t>(sp), iq = static_cast<std::size_t>(sq);
          if (used[p][ip] >= 0 || used[q][iq] >= 0) {
            throw patch_error(
                specs[q], q,
                fmt::format(
                    "side {} of patch '{}' and side {} of patch '{}' meet a border already shared by two "
                    "patches: a border may join only two patches",
                    to_string(sq), net.names[q], to_string(sp), net.names[p]));
          }
          used[p][ip] = used[q][iq] = static_cast<int>(net.borders.size());
          SharedBorder b;
          b.a = p;
          b.b = q;
          b.side_a = sp;
          b.side_b = sq;
          b.reversed = !same;
          b.declared = declared ? specs[q].join->continuity : Continuity::None;
          net.borders.push_back(b);
        }
      }
    }
  }
}

}  // namespace

const char* to_string(PatchSide side) {
  switch (side) {
    case PatchSide::UMin:
      return "u_min";
    case PatchSide::UMax:
      return "u_max";
    case PatchSide::VMin:
      return "v_min";
    case PatchSide::VMax:
      return "v_max";
  }
  return "?";
}

std::array<Vec3, 4> border_points(const HBezierPatch& patch, PatchSide side) {
  return line_towards(patch.points(), side, 3);
}

const HBezierParams& border_params(const HBezierPatch& patch, PatchSide side) {
  return is_u_side(side) ? patch.v() : patch.u();
}

std::array<double, 2> border_uv(PatchSide side, double x) {
  switch (side) {
    case PatchSide::UMin:
      return {0.0, x};
    case PatchSide::UMax:
      return {1.0, x};
    case PatchSide::VMin:
      return {x, 0.0};
    case PatchSide::VMax:
      return {x, 1.0};
  }
  return {x, x};
}

bool collapsed_side(const HBezierPatch& patch, PatchSide side, double eps) {
  const auto b = border_points(patch, side);
  return (b[1] - b[0]).norm() <= eps && (b[2] - b[0]).norm() <= eps && (b[3] - b[0]).norm() <= eps;
}

std::vector<std::array<bool, 4>> outer_sides(const PatchNetwork& network) {
  std::vector<std::array<bool, 4>> outer(network.patches.size(), {true, true, true, true});
  for (const SharedBorder& b : network.borders) {
    outer[b.a][static_cast<std::size_t>(b.side_a)] = false;
    outer[b.b][static_cast<std::size_t>(b.side_b)] = false;
  }
  const double eps = 1e-12 * network.size;
  for (std::size_t p = 0; p < network.patches.size(); ++p) {
    for (PatchSide side : {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax}) {
      if (collapsed_side(network.patches[p], side, eps)) outer[p][static_cast<std::size_t>(side)] = false;
    }
  }
  return outer;
}

std::array<Vec3, 3> join_curve_points(const std::array<Vec3, 4>& p, const HBezierParams& p_params,
                                      const HBezierParams& q_params, const PatchJoin& join) {
  std::array<Vec3, 3> q{p[3], p[3], p[3]};
  if (join.continuity == Continuity::G0 || join.continuity == Continuity::None) return q;
  const auto c1 = hbezier_end_constants(p_params.alpha, p_params.lambda, p_params.mu);
  const auto c2 = hbezier_end_constants(q_params.alpha, q_params.lambda, q_params.mu);
  const double rho = join.continuity == Continuity::G1 ? join.gamma : join.k * c1.a1 / c2.a0;
  q[1] = p[3] + rho * (p[3] - p[2]);
  if (join.continuity == Continuity::G2) {
    const double k2 = join.k * join.k;
    q[2] = p[3] + (rho + (k2 * c1.b1 + join.m * c1.a1 + rho * c2.b0) / c2.e) * (p[3] - p[2]) +
           k2 * (c1.e / c2.e) * (p[1] - p[2]);
  }
  return q;
}

namespace {

// Whether the 16 control points lie on one line (or in one point), to
// 1e-12 of their extent: the patch is then a curve, with no area to mesh.
bool collinear_net(const ControlNet& net) {
  const Vec3 a = net[0][0];
  Vec3 far = a;
  for (const auto& row : net) {
    for (const Vec3& p : row) {
      if ((p - a).squaredNorm() > (far - a).squaredNorm()) far = p;
    }
  }
  const Vec3 axis = far - a;
  const double length2 = axis.squaredNorm();
  if (length2 == 0.0) return true;
  for (const auto& row : net) {
    for (const Vec3& p : row) {
      if ((p - a).cross(axis).squaredNorm() > 1e-24 * length2 * length2) return false;
    }
  }
  return true;
}

}  // namespace

PatchNetwork build_patch_network(const std::vector<PatchSpec>& specs, const NetworkOptions& options) {
  if (specs.empty()) throw GeometryError("patches", "a surface needs at least one patch");
  PatchNetwork net;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const PatchSpec& s = specs[i];
    if (std::find(net.names.begin(), net.names.end(), s.name) != net.names.end()) {
      throw patch_error(s, i, fmt::format("patch name '{}' is used twice", s.name));
    }
    if (!s.join) {
      if (s.points.size() != 4) {
        throw patch_error(
            s, i, fmt::format("an explicit patch needs 4 rows of 4 points; got {} rows", s.points.size()));
      }
      ControlNet p{};
      for (std::size_t r = 0; r < 4; ++r) p[r] = s.points[r];
      net.patches.emplace_back(p, s.u, s.v);
    } else {
      const PatchJoin& j = *s.join;
      if (j.to >= i) {
        throw patch_error(
            s, i, fmt::format("patch '{}' joins patch {}, which is not an earlier patch", s.name, j.to));
      }
      if (j.continuity == Continuity::None) throw patch_error(s, i, "a join needs G0, G1 or G2");
      if (j.continuity == Continuity::G1) require_positive("gamma", j.gamma);
      if (j.continuity == Continuity::G2) require_positive("k", j.k);
      require_in_range("m", j.m, -1e12, 1e12);
      net.patches.push_back(joined_patch(s, i, net.patches[j.to], net.names[j.to]));
    }
    if (collinear_net(net.patches.back().points())) {
      throw patch_error(s, i,
                        "its 16 control points lie on one line: the patch is a curve, with no surface to "
                        "mesh; move the points apart across the line");
    }
    net.names.push_back(s.name);
  }
  net.size = std::max(network_size(net.patches), 1e-300);
  find_shared_borders(net, specs, options);
  for (const PatchSpec& s : specs) {
    if (!s.join) continue;
    const auto self = static_cast<std::size_t>(&s - specs.data());
    const bool found = std::any_of(net.borders.begin(), net.borders.end(), [&](const SharedBorder& b) {
      return b.b == self && b.a == s.join->to && b.declared != Continuity::None;
    });
    if (!found) {
      throw patch_error(s, self,
                        fmt::format("patch '{}' was joined to '{}' but their borders do not meet", s.name,
                                    net.names[s.join->to]));
    }
  }
  for (SharedBorder& b : net.borders) {
    measure(net, b, options);
    if (b.declared == Continuity::None || b.achieved >= b.declared) continue;
    throw patch_error(
        specs[b.b], b.b,
        fmt::format(
            "the {} join of '{}' to '{}' along {} measures {}: gap {:.3g}, normal angle {:.3g} rad{}{}",
            to_string(b.declared), net.names[b.b], net.names[b.a], to_string(b.side_a), to_string(b.achieved),
            b.gap, b.normal_angle,
            b.declared == Continuity::G2 ? fmt::format(", relative curvature jump {:.3g}", b.curvature_jump)
                                         : "",
            b.normal_angle > M_PI / 2
                ? " (the normals flip: the patches are oriented oppositely; the rows next to "
                  "the border may fold back, or a degenerate border)"
                : " (degenerate rows next to the border?)"));
  }
  return net;
}

}  // namespace fabmesh
