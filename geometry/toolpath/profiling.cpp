#include "geometry/toolpath/profiling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace fabmesh {
namespace {

// The outward normal of a counter-clockwise loop's edge from a to b.
Vec2 outward(const Vec2& a, const Vec2& b) {
  const Vec2 u = (b - a).normalized();
  return {u.y(), -u.x()};
}

// The tool centre's points round vertex v between edges with outward
// normals ma (arriving) and mb (leaving).
void corner(const Vec2& v, const Vec2& ma, const Vec2& mb, double radius, double tolerance,
            std::vector<Vec2>& path) {
  const double turn = std::atan2(cross2(ma, mb), ma.dot(mb));  // > 0: a convex corner of the part
  if (turn > 1e-12) {
    const double step = tolerance >= radius ? 0.5 * M_PI : 2.0 * std::acos(1.0 - tolerance / radius);
    const int pieces = std::max(1, static_cast<int>(std::ceil(turn / step)));
    for (int k = 0; k <= pieces; ++k) {
      const double a = turn * k / pieces;
      const double c = std::cos(a), s = std::sin(a);
      path.push_back(v + radius * Vec2(c * ma.x() - s * ma.y(), s * ma.x() + c * ma.y()));
    }
  } else {
    path.push_back(v + radius * (ma + mb) / (1.0 + ma.dot(mb)));
  }
}

}  // namespace

std::vector<ProfileRun> profile_runs(const std::vector<Vec2>& outer, const std::vector<bool>& exposed,
                                     double radius, double tolerance, const std::string& label) {
  const std::size_t n = outer.size();
  if (n < 3 || exposed.size() != n || !(radius > 0.0) || !(tolerance > 0.0))
    throw std::invalid_argument(
        "profile_runs: a loop of 3 or more points, a flag per edge, radius and tolerance > 0");
  const auto edge_normal = [&](std::size_t i) { return outward(outer[i], outer[(i + 1) % n]); };
  std::vector<ProfileRun> runs;
  if (std::all_of(exposed.begin(), exposed.end(), [](bool e) { return e; })) {
    ProfileRun run;
    run.closed = true;
    run.label = fmt::format("{} exposed edges 1", label);
    for (std::size_t i = 0; i < n; ++i)
      corner(outer[i], edge_normal((i + n - 1) % n), edge_normal(i), radius, tolerance, run.path);
    run.path.push_back(run.path.front());
    runs.push_back(std::move(run));
    return runs;
  }
  // Start after an unexposed edge, so that no run wraps round the start.
  std::size_t first = 0;
  while (exposed[first]) ++first;
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t i = (first + k) % n;
    if (!exposed[i] || exposed[(i + n - 1) % n]) continue;  // not the start of a run
    ProfileRun run;
    run.label = fmt::format("{} exposed edges {}", label, runs.size() + 1);
    run.path.push_back(outer[i] + radius * edge_normal(i));
    std::size_t j = i;
    while (exposed[(j + 1) % n]) {
      const std::size_t next = (j + 1) % n;
      corner(outer[next], edge_normal(j), edge_normal(next), radius, tolerance, run.path);
      j = next;
    }
    run.path.push_back(outer[(j + 1) % n] + radius * edge_normal(j));
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace fabmesh
