#include "geometry/mesh/sweep.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

void check_section(const SweepSection& section) {
  const auto& loop = section.loop;
  const std::size_t n = loop.size();
  if (n < 3) throw RangeError("section", static_cast<double>(n), "a swept section needs at least 3 vertices");
  if (!section.on_outline.empty() && section.on_outline.size() != n) {
    throw RangeError("on_outline", static_cast<double>(section.on_outline.size()),
                     "on_outline must be empty or have one flag per loop vertex");
  }
  auto outline = [&](std::size_t i) { return !section.on_outline.empty() && section.on_outline[i]; };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = loop[i];
    if (p.x() < 0.0) throw RangeError("radius", p.x(), fmt::format("section vertex radius {} < 0", p.x()));
    const std::size_t prev = (i + n - 1) % n, next = (i + 1) % n;
    if (p.x() == 0.0) {
      const int neighbours = (loop[prev].x() == 0.0) + (loop[next].x() == 0.0);
      if (neighbours != 1 || outline(i)) {
        throw GeometryError("section", fmt::format("section vertex (r 0, z {}) is on the axis with {} axis "
                                                   "neighbours; a loop may meet the axis only along single "
                                                   "axis edges",
                                                   p.y(), neighbours));
      }
    }
    if (outline(i) && !outline(next) && loop[next].y() != p.y()) {
      throw GeometryError("section", fmt::format("the edge from outline vertex (r {}, z {}) to (r {}, z {}) "
                                                 "is not horizontal",
                                                 p.x(), p.y(), loop[next].x(), loop[next].y()));
    }
    if (!outline(i) && outline(next) && loop[next].y() != p.y()) {
      throw GeometryError("section", fmt::format("the edge from (r {}, z {}) to outline vertex (r {}, z {}) "
                                                 "is not horizontal",
                                                 p.x(), p.y(), loop[next].x(), loop[next].y()));
    }
  }
}

}  // namespace

std::size_t swept_triangle_count(const SweepSection& section, std::size_t samples, bool closed) {
  const auto& loop = section.loop;
  std::size_t per_step = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const bool a = loop[i].x() == 0.0, b = loop[(i + 1) % loop.size()].x() == 0.0;
    per_step += (a && b) ? 0 : (a || b) ? 1 : 2;
  }
  const std::size_t steps = closed ? samples : (samples == 0 ? 0 : samples - 1);
  return per_step * steps;
}

SweptSurface sweep_section(const SweepSection& section, const SweepPath& path) {
  check_section(section);
  const std::size_t m = path.directions.size();
  if (m < (path.closed ? 3u : 2u)) {
    throw RangeError("samples", static_cast<double>(m),
                     fmt::format("a {} sweep needs at least {} angular samples, got {}",
                                 path.closed ? "closed" : "partial", path.closed ? 3 : 2, m));
  }
  const bool any_outline = !section.on_outline.empty();
  if (any_outline && path.outline.size() != m) {
    throw RangeError("outline", static_cast<double>(path.outline.size()),
                     "the path needs one outline point per sample when the section has outline vertices");
  }
  const auto& loop = section.loop;
  const std::size_t n = loop.size();
  auto on_axis = [&](std::size_t i) { return loop[i].x() == 0.0; };

  SweptSurface out;
  std::vector<std::uint32_t> first(n);  // index of vertex i at sample 0 (or its pole)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = loop[i];
    first[i] = static_cast<std::uint32_t>(out.soup.vertices.size());
    if (on_axis(i)) {
      out.soup.vertices.emplace_back(0.0, 0.0, p.y());
      continue;
    }
    const bool outline = any_outline && section.on_outline[i];
    for (std::size_t j = 0; j < m; ++j) {
      const Vec2 xy = outline ? path.outline[j] : Vec2(p.x() * path.directions[j]);
      out.soup.vertices.emplace_back(xy.x(), xy.y(), p.y());
    }
  }
  auto v = [&](std::size_t i, std::size_t j) {
    return on_axis(i) ? first[i] : first[i] + static_cast<std::uint32_t>(j % m);
  };
  const std::size_t steps = path.closed ? m : m - 1;
  out.soup.triangles.reserve(swept_triangle_count(section, m, path.closed));
  // Faces of loop edge (a, b) between samples j and j+1, as revolve: for a
  // counter-clockwise loop (a_j, a_j+1, b_j+1) and (a_j, b_j+1, b_j) point outward.
  for (std::size_t e = 0; e < n; ++e) {
    const std::size_t a = e, b = (e + 1) % n;
    if (on_axis(a) && on_axis(b)) continue;
    for (std::size_t j = 0; j < steps; ++j) {
      if (!on_axis(a)) out.soup.triangles.push_back({v(a, j), v(a, j + 1), v(b, j + 1)});
      if (!on_axis(b)) out.soup.triangles.push_back({v(a, j), v(b, j + 1), v(b, j)});
    }
  }
  out.first.resize(n);
  out.last.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.first[i] = v(i, 0);
    out.last[i] = v(i, path.closed ? 0 : m - 1);
  }
  return out;
}

}  // namespace fabmesh
