#include "geometry/mesh/sweep.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"
#include "geometry/mesh/revolve.h"

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
  if (section.open_edge != SweepSection::kNoEdge && section.open_edge >= n) {
    throw RangeError("open_edge", static_cast<double>(section.open_edge),
                     fmt::format("open edge {} of a loop of {} vertices", section.open_edge, n));
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
    if (i == section.open_edge && (loop[next].y() != p.y() || p.x() == 0.0 || loop[next].x() == 0.0)) {
      throw GeometryError("section", fmt::format("the open edge from (r {}, z {}) to (r {}, z {}) is not "
                                                 "horizontal or has an end on the axis",
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
  const std::size_t steps = closed ? samples : (samples == 0 ? 0 : samples - 1);
  const std::size_t open =
      section.open_edge == SweepSection::kNoEdge ? 0 : 2;  // an open edge is off the axis
  return (revolved_triangles_per_step(section.loop) - open) * steps;
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
  SweptSurface out;
  // revolve's layout, with outline vertices at the path's outline points.
  const LoopGrid grid = append_loop_grid(loop, m, out.soup.vertices, [&](std::size_t i, std::size_t j) {
    if (any_outline && section.on_outline[i])
      return Vec3(path.outline[j].x(), path.outline[j].y(), loop[i].y());
    return revolved_point(loop[i], {path.directions[j].x(), path.directions[j].y()});
  });
  const std::size_t steps = path.closed ? m : m - 1;
  out.soup.triangles.reserve(swept_triangle_count(section, m, path.closed));
  // revolve's faces, each written from its corner at sample j: (a_j, a_j+1, b_j+1), (a_j, b_j+1, b_j).
  for_each_grid_face(
      grid, steps,
      [&](std::uint32_t c0, std::uint32_t c1, std::uint32_t c2) {
        out.soup.triangles.push_back({c2, c0, c1});
      },
      section.open_edge);
  out.first.resize(loop.size());
  out.last.resize(loop.size());
  for (std::size_t i = 0; i < loop.size(); ++i) {
    out.first[i] = grid.at(i, 0);
    out.last[i] = grid.at(i, path.closed ? 0 : m - 1);
  }
  if (section.open_edge != SweepSection::kNoEdge) {
    const std::size_t a = section.open_edge, b = (a + 1) % loop.size();
    for (std::size_t j = 0; j < m; ++j) {
      out.open_from.push_back(grid.at(a, j));
      out.open_to.push_back(grid.at(b, j));
    }
  }
  return out;
}

}  // namespace fabmesh
