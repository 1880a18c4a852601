#include "geometry/mould/release.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fabmesh {
namespace {

// Indices i where v[i] is greater than an earlier value or less than a later one
// (the sequence should be non-increasing).
std::vector<std::size_t> non_monotone(const std::vector<double>& v) {
  const std::size_t n = v.size();
  std::vector<double> later_max(n + 1, -std::numeric_limits<double>::infinity());
  for (std::size_t i = n; i-- > 0;) later_max[i] = std::max(later_max[i + 1], v[i]);
  std::vector<std::size_t> out;
  double earlier_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    if (v[i] > earlier_min || v[i] < later_max[i + 1]) out.push_back(i);
    earlier_min = std::min(earlier_min, v[i]);
  }
  return out;
}

}  // namespace

std::vector<Undercut> find_undercuts(const std::vector<Vec2>& side_cavity,
                                     const std::vector<Vec2>& base_cavity) {
  std::vector<Undercut> out;
  std::vector<double> z;
  z.reserve(side_cavity.size());
  for (const Vec2& p : side_cavity) z.push_back(p.y());
  for (std::size_t i : non_monotone(z)) out.push_back({side_cavity[i], MouldPartKind::Side});
  std::vector<double> r;
  r.reserve(base_cavity.size());
  for (const Vec2& p : base_cavity) r.push_back(p.x());
  for (std::size_t i : non_monotone(r)) out.push_back({base_cavity[i], MouldPartKind::Base});
  return out;
}

double key_pull_angle(int parts) { return M_PI / 2.0 - M_PI / parts; }

bool keys_release(int parts, double key_radius, double socket_radius) {
  return socket_radius * std::cos(key_pull_angle(parts)) >= key_radius;
}

std::string describe_undercuts(const std::vector<Undercut>& undercuts, std::size_t max_points) {
  std::string text;
  for (MouldPartKind kind : {MouldPartKind::Side, MouldPartKind::Base}) {
    std::vector<std::string> pts;
    std::size_t count = 0;
    for (const Undercut& u : undercuts) {
      if (u.part != kind) continue;
      if (count++ < max_points) pts.push_back(fmt::format("(r {:.6g}, z {:.6g})", u.point.x(), u.point.y()));
    }
    if (count == 0) continue;
    if (!text.empty()) text += "; ";
    text +=
        kind == MouldPartKind::Side
            ? "the side parts cannot be pulled horizontally: the cavity folds back (a horizontal slice is "
              "not a disc) at "
            : "the base part cannot be pulled down: the cavity widens downward inside it at ";
    text += fmt::format("{}", fmt::join(pts, ", "));
    if (count > pts.size()) text += fmt::format(" and {} more points", count - pts.size());
  }
  return text;
}

}  // namespace fabmesh
